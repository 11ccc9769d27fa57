#!/usr/bin/env bash
# End to end through the real binary: every map in ../shared/maps -> `aerobox scene` ->
# MuJoCo's own compiler (mujoco-compile); and a bad map exits 2 naming its file and line.
# Usage: scene_loads_in_mujoco.sh AEROBOX_BINARY SOURCE_DIR   (exit 77: skipped)
set -euo pipefail
aerobox=$1
maps="$2/../shared/maps"
if [ ! -d "$maps" ]; then
  echo "SKIPPED: ../shared/maps is absent beside the checkout"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

mapfile -d '' files < <(find "$maps" -type f \( -name '*.txt' -o -name '*.json' -o -name '*.csv' \) \
                          ! -name '*.startgoal.txt' -print0 | sort -z)
count=0
for map in "${files[@]}"; do
  name=$(basename "$map")
  "$aerobox" scene "$map" -o "$work/$name.xml"
  mujoco-compile "$work/$name.xml" "$work/$name.mjb" < /dev/null > "$work/compile.log" 2>&1 || {
    cat "$work/compile.log"
    echo "FAIL: mujoco-compile rejected the scene of $map"
    exit 1
  }
  count=$((count + 1))
done
echo "$count scenes compiled by mujoco-compile"
[ "$count" -ge 22 ] || { echo "FAIL: expected 22 maps, found $count"; exit 1; }

printf 'boundary 0 0 0 1 1 1\nblock 0 0 0 1 1\n' > "$work/bad.txt"
set +e
"$aerobox" scene "$work/bad.txt" -o "$work/bad.xml" 2> "$work/err.txt"
code=$?
set -e
[ "$code" -eq 2 ] || { echo "FAIL: bad map exited $code, not 2"; exit 1; }
grep -q "bad.txt:2: block:" "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
[ ! -e "$work/bad.xml" ] || { echo "FAIL: a bad map left an output file"; exit 1; }
echo "bad map: exit 2, message names bad.txt:2"
