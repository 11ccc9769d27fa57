#!/usr/bin/env bash
# A whole `aerobox fly` with video, through the binary: exit 0, an MP4 and a PNG. Under
# `tools/test.sh --sanitize` this is the run that must leak nothing (GL context and encoder
# released). Usage: video_run_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$aerobox" fly "$top/scenes/empty/scenario.toml" --size 320x240 --speed 2 --quiet \
  --out "$work/out" > /dev/null
[ "$(head -c 8 "$work/out/overview.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] ||
  { echo "FAIL: overview.png is not a PNG"; exit 1; }
[ "$(head -c 8 "$work/out/video.mp4" | tail -c 4)" = "ftyp" ] ||
  { echo "FAIL: video.mp4 is not an MP4"; exit 1; }
echo "video run: exit 0, $(stat -c %s "$work/out/video.mp4") bytes of MP4"
