#!/usr/bin/env bash
# The product binary links neither Google Benchmark nor OMPL: the benchmarks live in
# aerobox-bench, which `aerobox bench` runs. Usage: product_links_test.sh AEROBOX AEROBOX_BENCH
set -euo pipefail
aerobox=$1
bench=$2
if ldd "$aerobox" | grep -E 'libbenchmark|libompl'; then
  echo "FAIL: aerobox links a benchmark library"
  exit 1
fi
if nm -C "$aerobox" | grep -q 'benchmark::'; then
  echo "FAIL: aerobox contains Google Benchmark symbols"
  exit 1
fi
[ -x "$bench" ] || { echo "FAIL: $bench is missing"; exit 1; }
"$aerobox" bench --help | grep -q -- "--sections" || { echo "FAIL: aerobox bench --help"; exit 1; }
set +e
"$aerobox" bench --seeds 0 > /dev/null 2>&1
code=$?
set -e
[ "$code" -eq 2 ] || { echo "FAIL: a bad bench option exited $code, not 2"; exit 1; }
echo "aerobox links no benchmark library; aerobox bench runs aerobox-bench"
