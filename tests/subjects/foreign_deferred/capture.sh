#!/bin/sh
# The foreign_captures fixture: foreign_deferred under `renderdoccmd capture` (frames 0..2, frame 2
# captured and dumped), the .rdc moved to OUT/STEM.rdc and the app's dump to OUT/DUMP. Anything
# left from an earlier run is removed first, so a failed run leaves no stale capture behind.
# usage: capture.sh APP OUT STEM DUMP [APP ARGS...]
set -u
app=$1 out=$2 stem=$3 dump=$4
shift 4
tmp="$out/$stem.tmp"
rm -rf "$tmp" "$out/$stem.rdc" "$out/$dump"
mkdir -p "$tmp" || exit 1
# renderdoccmd's own exit status is not the app's (it is non-zero after short programs even when the
# capture was written): the app's last line and the .rdc say whether it worked.
timeout -k 5 120 renderdoccmd capture -w -c "$tmp/$stem" "$app" --frames 3 --capture-frame 2 --dump "$out/$dump" "$@" \
  >"$tmp/log" 2>&1
status=$?
cat "$tmp/log"
if grep -q "validation" "$tmp/log"; then
  echo "capture.sh: $stem: the app printed validation messages"
  exit 1
fi
if ! grep -q "RenderDoc captured frame 2, dumped frame 2" "$tmp/log"; then
  echo "capture.sh: $stem: the app did not finish its frames under RenderDoc (renderdoccmd exit $status, 124: time-out)"
  exit 1
fi
set -- "$tmp"/*.rdc
if [ $# -ne 1 ] || [ ! -f "$1" ]; then
  echo "capture.sh: $stem: expected one .rdc in $tmp, found: $*"
  exit 1
fi
mv "$1" "$out/$stem.rdc" && rm -rf "$tmp" && echo "capture.sh: wrote $out/$stem.rdc and $out/$dump"
