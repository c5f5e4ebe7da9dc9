# Sourced by the measuring scripts (measure_viewer.sh, measure_attach.sh): a private folder $OUT and an
# Xvfb of their own (the display number it picks itself), both gone when the script exits.
OUT=$(mktemp -d)
exec 3>"$OUT/display"
Xvfb -displayfd 3 -screen 0 1600x900x24 -nolisten tcp >/dev/null 2>&1 &
XVFB=$!
trap 'kill $XVFB 2>/dev/null; rm -rf "$OUT"' EXIT
while [ ! -s "$OUT/display" ]; do sleep 0.1; done
export DISPLAY=:$(head -1 "$OUT/display")
