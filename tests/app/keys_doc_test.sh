#!/usr/bin/env bash
# docs/scenario-keys.md is what `aerobox keys` prints: the key reference comes from the
# parameter structs' own descriptions, and the page may not go stale.
# Usage: keys_doc_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
if ! diff -u "$top/docs/scenario-keys.md" <("$aerobox" keys); then
  echo "FAIL: docs/scenario-keys.md is stale: regenerate it with"
  echo "  build/aerobox keys > docs/scenario-keys.md"
  exit 1
fi
echo "docs/scenario-keys.md is current ($(grep -c '^| `' "$top/docs/scenario-keys.md") keys)"
