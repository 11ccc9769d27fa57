#!/usr/bin/env bash
# Every section of `aerobox bench` runs end to end in its smoke mode (one repetition, the
# smallest sizes), the city section on a small generated city, so that no section can ship
# broken. The numbers are not checked: speed is measured by the full benchmark, not by tests.
# Usage: bench_smoke_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# an FCND-style city 790 m across: 30 seeded buildings and two corner posts
/usr/bin/python3 - "$work/city.csv" << 'PY'
import random, sys
random.seed(3)
rows = ["lat0 37.792480, lon0 -122.397450", "posX,posY,posZ,halfSizeX,halfSizeY,halfSizeZ"]
for _ in range(30):
    h = random.uniform(10, 40)
    rows.append(f"{random.uniform(-380, 380):.1f},{random.uniform(-380, 380):.1f},{h:.1f},"
                f"{random.uniform(5, 20):.1f},{random.uniform(5, 20):.1f},{h:.1f}")
rows += ["-395,-395,2,5,5,2", "395,395,2,5,5,2"]
open(sys.argv[1], "w").write("\n".join(rows) + "\n")
PY

cd "$top"
# (a sanitizer build: the python3 the Python section starts needs the sanitizers' runtime first)
LD_PRELOAD="${AEROBOX_PYTHON_PRELOAD:-}" \
  "$aerobox" bench --smoke --city "$work/city.csv" > "$work/tables.md" 2> "$work/progress.txt" ||
  { cat "$work/tables.md" "$work/progress.txt"; echo "FAIL: aerobox bench --smoke failed"; exit 1; }
for heading in "Minimum snap" "The video path" "Closed loop" "Flight time" "A Python controller" \
  "RotorPy's Environment" "Learning environments" "Robustness" "Replanning" "Sweep throughput" "City scale" "RRT\*" \
  "Navigation" "Several vehicles in one world"; do
  grep -q "^## $heading" "$work/tables.md" ||
    { cat "$work/tables.md"; echo "FAIL: no '$heading' section"; exit 1; }
done
if grep -q "skipped" "$work/tables.md"; then
  cat "$work/tables.md"
  echo "FAIL: a section was skipped"
  exit 1
fi
grep -q "^| trained on | environment steps | wall time \[s\] | held on MuJoCo | held on the rigid backend |" "$work/tables.md" &&
  [ "$(grep -cE '^\| (mujoco|rigid) \| [0-9]+ \|' "$work/tables.md")" = 2 ] ||
  { cat "$work/tables.md"; echo "FAIL: the training rows (one per backend) are missing"; exit 1; }
grep -q "^| worlds | physics step | MuJoCo: env steps/s | rigid: env steps/s |" "$work/tables.md" ||
  { cat "$work/tables.md"; echo "FAIL: the rigid backend's table is missing"; exit 1; }
grep -q "aerobox / PyFlyt (simulated s) | aerobox rigid: simulated s per wall s | rigid / PyFlyt |$" "$work/tables.md" ||
  { cat "$work/tables.md"; echo "FAIL: the PyFlyt table is missing"; exit 1; }
grep -q "aerobox / RotorPy | aerobox rigid: env steps/s | rigid / RotorPy |$" "$work/tables.md" ||
  { cat "$work/tables.md"; echo "FAIL: the learning environments' peers table is missing"; exit 1; }
grep -q "^| OctoMap | [0-9.]* ms | 1.00x |" "$work/tables.md" ||
  { cat "$work/tables.md"; echo "FAIL: the occupancy map's comparison with OctoMap is missing"; exit 1; }
grep -q "^| vehicles | arrived | contacts | min separation \[m\] |" "$work/tables.md" &&
  grep -q "^| 4 | 4/4 | 0 |" "$work/tables.md" ||
  { cat "$work/tables.md"; echo "FAIL: the swarm's swap table is missing, or a vehicle did not arrive"; exit 1; }
grep -q "^| navigate |" "$work/tables.md" ||
  { cat "$work/tables.md"; echo "FAIL: the learning environments' table lacks navigate"; exit 1; }
# a misspelt section is refused before any work, naming the one it looks like
if "$aerobox" bench --sections rl,robustnes > "$work/out.txt" 2> "$work/err.txt"; then
  echo "FAIL: an unknown section was accepted"; exit 1
fi
grep -q "unknown section 'robustnes' (did you mean 'robustness'?)" "$work/err.txt" ||
  { cat "$work/err.txt"; echo "FAIL: the unknown section's message"; exit 1; }
[ ! -s "$work/out.txt" ] || { cat "$work/out.txt"; echo "FAIL: work before the refusal"; exit 1; }
echo "bench smoke: all 14 sections ran"
