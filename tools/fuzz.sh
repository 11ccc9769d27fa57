#!/usr/bin/env bash
# Runs one libFuzzer target for SECONDS (clang, AddressSanitizer and UndefinedBehaviorSanitizer).
#   tools/fuzz.sh TARGET SECONDS [libFuzzer options]
# TARGET: map_txt, map_json, map_csv, startgoal or scenario. The corpus starts from the kept
# inputs in tests/fuzz/corpus/TARGET and, when they sit beside the repository, the published
# maps of the matching format; new interesting inputs go to build-fuzz/corpus/TARGET, and a
# crash is written to build-fuzz/findings/ (copy it to tests/fuzz/corpus/TARGET once fixed).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${AEROBOX_FUZZ_DIR:-$top/build-fuzz}
if [ $# -lt 2 ]; then
  echo "usage: tools/fuzz.sh TARGET SECONDS [libFuzzer options]" >&2
  echo "targets: map_txt map_json map_csv startgoal scenario" >&2
  exit 2
fi
target=$1
seconds=$2
shift 2
case "$target" in
  map_txt) pattern='*.txt' ;;
  map_json) pattern='*.json' ;;
  map_csv) pattern='*.csv' ;;
  startgoal) pattern='*.startgoal.txt' ;;
  scenario) pattern='*.toml' ;;
  *) echo "tools/fuzz.sh: unknown target '$target'" >&2; exit 2 ;;
esac

"$top/tools/setup.sh"
if ! command -v clang++ >/dev/null; then
  if [ "$(id -u)" -eq 0 ]; then apt-get install -y clang; else sudo apt-get install -y clang; fi
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  CXX=clang++ CC=clang cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=Release \
    -DAEROBOX_FUZZ=ON -DAEROBOX_BUILD_TESTS=OFF
fi
cmake --build "$build" --parallel "$(nproc)" --target "fuzz_$target"

corpus=$build/corpus/$target
mkdir -p "$corpus" "$build/findings"
seeds=("$top/tests/fuzz/corpus/$target")
for folder in "$top/../shared/maps" "$top/scenes"; do
  if [ -d "$folder" ]; then
    while IFS= read -r -d '' file; do cp -n "$file" "$corpus/" 2>/dev/null || true
    done < <(find "$folder" -name "$pattern" -size -1M -print0)
  fi
done
exec "$build/tests/fuzz/fuzz_$target" "$corpus" "${seeds[@]}" -max_total_time="$seconds" \
  -artifact_prefix="$build/findings/$target-" -print_final_stats=1 "$@"
