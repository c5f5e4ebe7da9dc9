#!/bin/sh
# The zoo_captures fixture for one mode: gbuffer_zoo under `renderdoccmd capture` (frames 0..2, frame 2
# captured and dumped), leaving OUT/MODE.rdc and OUT/MODE_dump/. Earlier results are removed first so a
# failed run leaves nothing stale. usage: capture.sh APP OUT MODE
set -u
app=$1 out=$2 mode=$3
tmp="$out/$mode.tmp"
rm -rf "$tmp" "$out/$mode.rdc" "$out/${mode}_dump" "$out/${mode}_dump.partial"
mkdir -p "$tmp" || exit 1
# renderdoccmd's exit status is not the app's: the app's last line and the .rdc decide.
timeout -k 5 120 renderdoccmd capture -w -c "$tmp/$mode" "$app" --mode "$mode" --frames 3 --capture-frame 2 \
  --dump "$out/${mode}_dump" >"$tmp/log" 2>&1
status=$?
cat "$tmp/log"
if grep -q "gbuffer_zoo: validation" "$tmp/log"; then
  echo "capture.sh: $mode: the app printed validation messages"
  exit 1
fi
if ! grep -q "^gbuffer_zoo $mode: rendered 3 frames, captured frame 2, dumped frame 2\$" "$tmp/log"; then
  echo "capture.sh: $mode: the app did not finish under RenderDoc (renderdoccmd exit $status, 124: time-out)"
  exit 1
fi
set -- "$tmp"/*.rdc
if [ $# -ne 1 ] || [ ! -f "$1" ]; then
  echo "capture.sh: $mode: expected one .rdc in $tmp, found: $*"
  exit 1
fi
mv "$1" "$out/$mode.rdc" && rm -rf "$tmp" && echo "capture.sh: wrote $out/$mode.rdc and $out/${mode}_dump"
