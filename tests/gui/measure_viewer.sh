#!/bin/sh
# Measures the viewer under its own Xvfb: idle CPU over 10 s (no input, animation paused),
# click-to-dossier latency (5 clicks), and frame time while the animation plays, with
# presentation (the viewer's render + views + present) and without (gblens render --frames).
# Then input -> updated view: five right-drag steps (orbit), each from idle, timed from just
# before xdotool sends the motion to the first frame on screen after it (the viewer's "frame"
# events carry their wall-clock time), and the refinement to the full size after it.
# Usage: tests/gui/measure_viewer.sh [BUILD_DIR] [RENDER_SIZE] [REDUCE]
#   (defaults: build 320x180 auto; REDUCE is --reduce-while-moving: auto, off or N)
set -eu
BUILD=${1:-build}
SIZE=${2:-320x180}
REDUCE=${3:-auto}
GBLENS=$BUILD/gblens
. "$(dirname "$0")/own_xvfb.sh"

"$GBLENS" view --size "$SIZE" --window 1600x900 --paused --time 1 --reduce-while-moving "$REDUCE" \
  --event-log "$OUT/events" 2>"$OUT/viewer.log" &
VIEWER=$!
until grep -q '"ready"' "$OUT/events" 2>/dev/null; do sleep 0.2; done
WID=$(xdotool search --onlyvisible --name '^gblens' | head -1)
xdotool mousemove --window "$WID" 800 890   # status bar: off the views
# Start-up work outlives "ready" (the first full frame's automatic ranges, region read-backs: about
# 1.5 s of CPU at 1280x720 on a loaded lavapipe): idle is measured after it.
sleep 12

ticks() { awk '{print $14 + $15}' /proc/"$1"/stat; }  # utime + stime of every thread
T0=$(ticks $VIEWER); sleep 10; T1=$(ticks $VIEWER)
HZ=$(getconf CLK_TCK)
echo "idle CPU over 10 s: $((T1 - T0)) ticks of 1/$HZ s = $(awk "BEGIN { printf \"%.2f\", 100 * ($T1 - $T0) / ($HZ * 10) }") %"

# Clicks on five pixels of the final view (window coordinates from the layout event).
LAYOUT=$(grep '"layout"' "$OUT/events" | tail -1)
OX=$(echo "$LAYOUT" | sed 's/.*"origin":\[\([0-9.]*\),\([0-9.]*\)\].*/\1/')
OY=$(echo "$LAYOUT" | sed 's/.*"origin":\[\([0-9.]*\),\([0-9.]*\)\].*/\2/')
SC=$(echo "$LAYOUT" | sed 's/.*"scale":\([0-9.]*\).*/\1/')
for p in "40 30" "100 60" "160 90" "220 120" "280 150"; do
  set -- $p
  X=$(awk "BEGIN { print int($OX + ($1 + 0.5) * $SC) }"); Y=$(awk "BEGIN { print int($OY + ($2 + 0.5) * $SC) }")
  xdotool mousemove --window "$WID" "$X" "$Y" click 1
  sleep 1.5
done
echo "click -> dossier ready (ms):    $(grep '"probe"' "$OUT/events" | sed 's/.*"latency_ms":\([0-9.]*\).*/\1/' | tr '\n' ' ')"
echo "click -> dossier on screen (ms): $(grep '"probe_shown"' "$OUT/events" | sed 's/.*"latency_ms":\([0-9.]*\).*/\1/' | tr '\n' ' ')"

# Drag latency: right button held over the final view, five motions from idle.
xdotool key --window "$WID" 0; sleep 2
VIEW=$(grep '"layout"' "$OUT/events" | tail -1)
VX=$(echo "$VIEW" | sed 's/.*"rect":\[\([0-9.]*\),\([0-9.]*\),\([0-9.]*\),\([0-9.]*\)\].*/\1 \3/' | awk '{print int($1 + $2 / 2)}')
VY=$(echo "$VIEW" | sed 's/.*"rect":\[\([0-9.]*\),\([0-9.]*\),\([0-9.]*\),\([0-9.]*\)\].*/\2 \4/' | awk '{print int($1 + $2 / 2)}')
xdotool mousemove --window "$WID" "$VX" "$VY" mousedown 3; sleep 1.5
: > "$OUT/sent"
for i in 1 2 3 4 5; do
  date +%s%3N >> "$OUT/sent"; xdotool mousemove_relative -- 15 0; sleep 2.5
done
xdotool mouseup 3; sleep 1
python3 - "$OUT/sent" "$OUT/events" "$SIZE" "$REDUCE" <<'PY'
import json, sys
sent = [float(l) for l in open(sys.argv[1])]
frames = [j for j in map(json.loads, open(sys.argv[2])) if j.get("event") == "frame"]
lat, ref, sizes = [], [], []
for t in sent:
    after = [f for f in frames if f["shown_epoch_ms"] > t]
    if not after:
        continue
    lat.append(after[0]["shown_epoch_ms"] - t)
    sizes.append("%dx%d" % tuple(after[0]["size"]))
    full = [f for f in after if f["reduced_by"] == 1]
    if full and after[0]["reduced_by"] > 1:
        ref.append(full[0]["shown_epoch_ms"] - t)
print("drag (%s, --reduce-while-moving %s): input -> updated view (ms): %s" % (sys.argv[3], sys.argv[4], " ".join("%.0f" % x for x in lat)))
print("  first frame after each input: %s" % " ".join(sizes))
print("  input -> full-size frame again (ms): %s" % (" ".join("%.0f" % x for x in ref) or "- (no reduced frames)"))
PY

# Animation: 10 s of continuous rendering with presentation, then quit.
xdotool mousemove --window "$WID" 800 890 key --window "$WID" space
sleep 10
xdotool key --window "$WID" ctrl+q
wait $VIEWER || true
echo "viewer (animation playing, $SIZE): $(grep '"exit"' "$OUT/events")"
# Without presentation: the same frames headless.
"$GBLENS" render --size "$SIZE" --time 1 --frames 20 --stats -o "$OUT/f.png" 2>/dev/null |
  python3 -c 'import json,sys; j=json.load(sys.stdin); print("headless render (%s, %s): frame_ms %.1f (frames in flight: %s), gpu_ms median %.1f" % (j["options"]["size"], j["method"]["ran"], j["frame_ms"], j.get("frames_in_flight", 1), j["gpu_ms"]))'
