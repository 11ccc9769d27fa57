#!/usr/bin/env bash
# The module table is enforced: tools/check_layout.py passes on the tree, and fails, naming the
# file and line, on a copy with a wrong-way include (mission including scenario) and a
# wrong-way link (map linking outputs).
# Usage: layout_test.sh SOURCE_DIR
set -euo pipefail
top=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$top/tools/check_layout.py" "$top"

cp -r "$top/src" "$top/docs" "$work/"
printf '#include "scenario/scenario.h"\n' >> "$work/src/mission/plan.h"
printf 'target_link_libraries(aerobox_map PRIVATE aerobox_outputs)\n' >> "$work/src/map/CMakeLists.txt"
if /usr/bin/python3 "$top/tools/check_layout.py" "$work" > "$work/out.txt"; then
  echo "FAIL: the check passed a wrong-way include and link"
  exit 1
fi
grep -q "src/mission/plan.h:[0-9]*: src/mission may not include src/scenario" "$work/out.txt" ||
  { cat "$work/out.txt"; echo "FAIL: the include is not named"; exit 1; }
grep -q "src/map/CMakeLists.txt: aerobox_map may not link aerobox_outputs" "$work/out.txt" ||
  { cat "$work/out.txt"; echo "FAIL: the link is not named"; exit 1; }
echo "layout: the tree keeps the module table; a wrong-way include and link are caught"
