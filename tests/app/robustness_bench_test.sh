#!/usr/bin/env bash
# aerobox bench --sections robustness on one map and one seed: a table row per controller and
# wind, a totals row per controller, a CSV row per flight, the figure-8 in steady wind per
# controller beside the published errors, and tools/plot_robustness.py draws the CSV; bad input
# exits 2 and writes nothing.
# Usage: robustness_bench_test.sh AEROBOX_BENCH_BINARY SOURCE_DIR
set -euo pipefail
bench=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$bench" --sections robustness --scenes "$top/scenes" --maps empty --seeds 1 \
  --robustness-csv "$work/runs.csv" > "$work/table.md" 2> /dev/null
# every controller kind, alone and with the observer, at 0, 2, 4 and 6 m/s
rows=$(grep -c '^| empty |' "$work/table.md")
[ "$rows" -eq 20 ] || { cat "$work/table.md"; echo "FAIL: $rows table rows, expected 20"; exit 1; }
for controller in cascade se3 indi cascade+observer se3+observer; do
  grep -q "^| $controller | [01]/1 | [01]/1 | [01]/1 | [01]/1 |$" "$work/table.md" ||
    { cat "$work/table.md"; echo "FAIL: no totals row for $controller"; exit 1; }
done
# the figure-8 in steady wind: a mean error per controller and wind, and the published ones
for controller in cascade se3 indi cascade+observer se3+observer; do
  grep -qE "^\| ${controller//+/\\+}( \| ([0-9]+\.[0-9]|-)){4} \|$" "$work/table.md" ||
    { cat "$work/table.md"; echo "FAIL: no figure-8 row for $controller"; exit 1; }
done
grep -q '^| INDI | 6.8 | 5.8 | 8.1 | 9.5 |$' "$work/table.md" ||
  { echo "FAIL: no published figure-8 errors"; exit 1; }
flights=$(($(wc -l < "$work/runs.csv") - 1))
[ "$flights" -eq 20 ] || { echo "FAIL: $flights CSV rows, expected 20"; exit 1; }
grep -q '^empty,indi,6,1,reached goal,' "$work/runs.csv" || { cat "$work/runs.csv"; exit 1; }

/usr/bin/python3 "$top/tools/plot_robustness.py" "$work/runs.csv" "$work/plot.png" > /dev/null
[ "$(head -c 8 "$work/plot.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] ||
  { echo "FAIL: plot.png is not a PNG"; exit 1; }

set +e
"$bench" --sections robustness --maps empty --robustness-csv "$work/no/such/folder.csv" \
  > "$work/out.txt" 2> "$work/err.txt"
code=$?
"$bench" --sections robustness --maps empty --controllers cascade,indi+observer \
  > "$work/out3.txt" 2> "$work/err3.txt"
code3=$?
printf 'a,b\n1,2\n' > "$work/bad.csv"
/usr/bin/python3 "$top/tools/plot_robustness.py" "$work/bad.csv" "$work/bad.png" 2> "$work/err2.txt"
code2=$?
set -e
[ "$code" -eq 2 ] || { echo "FAIL: a CSV in a missing folder exited $code"; exit 1; }
grep -q "robustness-csv" "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
[ ! -s "$work/out.txt" ] || { echo "FAIL: work was done before the option was checked"; exit 1; }
[ "$code2" -eq 2 ] || { echo "FAIL: bad CSV exited $code2"; exit 1; }
[ "$code3" -eq 2 ] || { echo "FAIL: an unknown controller exited $code3"; exit 1; }
grep -q 'controllers: controller "indi+observer"' "$work/err3.txt" || { cat "$work/err3.txt"; exit 1; }
[ ! -s "$work/out3.txt" ] || { echo "FAIL: work was done before --controllers was checked"; exit 1; }
[ ! -e "$work/bad.png" ] || { echo "FAIL: a PNG was written for bad input"; exit 1; }
echo "robustness bench: table, CSV and plot; bad input exits 2"
