#!/bin/sh
# Measures gblens attach's viewer under its own Xvfb (docs/attach.md "Cost"): the application's frame
# interval, and for each streamed frame shown the latency from the application's frame end to the
# viewer taking it (attach_frame) and to the present that put it on screen (attach_shown), in ms and
# in application frames; with the grid of every view of the layout (key 1) or the first view alone.
# Usage: [SHOT=FILE.png] [CLICK="X Y"] [KEYS="space x"] [GBLENS_VIEW_DECODE=cpu] [ATTACH_ARGS="--pace off"] tests/gui/measure_attach.sh [BUILD_DIR] [one|grid] [SECONDS] [WINDOW] -- APP ARGS...
#   (defaults: build grid 15 1200x760; APP: the foreign test subject with its layout, 320x180)
set -eu
BUILD=${1:-build}; VIEWS=${2:-grid}; SECONDS_=${3:-15}; WINDOW=${4:-1200x760}
[ $# -ge 4 ] && shift 4 || shift $#
[ "${1:-}" = "--" ] && shift
GBLENS=$BUILD/gblens
. "$(dirname "$0")/own_xvfb.sh"

if [ $# -eq 0 ]; then  # the foreign test subject, its targets live by pass and attachment index
  set -- "$BUILD/tests/subjects/foreign_deferred/foreign_deferred" --frames 16384
  "$1" --frames 1 --dump "$OUT/dump0" >/dev/null  # its camera (the uniform buffer has no name): a sidecar
  /usr/bin/python3 - "$OUT/live.json" "$OUT/dump0/camera.json" <<'EOF'
import json, sys
live = {"position": (0, 0), "normal": (0, 1), "albedo": (0, 2), "depth": (0, -1), "occlusion": (1, 0), "hdr": (2, 0), "final": (3, 0)}
layout = json.load(open("tests/subjects/foreign_deferred/layout.json"))
for t in layout["targets"]:
    p, c = live[t["name"]]
    t["source"] = {"live": {"pass": p, "depth": True} if c < 0 else {"pass": p, "color": c}}
    for q in t["quantities"]:
        q.pop("scale", None) if q.get("quantity") == "depth" else None
camera = json.load(open(sys.argv[2]))
sidecar = sys.argv[1] + ".camera.json"
json.dump({k: camera[k] for k in ("view_from_world", "clip_from_view")}, open(sidecar, "w"))
layout["camera"].pop("renderdoc", None)
layout["camera"].pop("up", None)
layout["camera"]["sidecar"] = sidecar
json.dump(layout, open(sys.argv[1], "w"))
EOF
  LAYOUT=$OUT/live.json
else
  LAYOUT=${LAYOUT:?give LAYOUT=L.json for your application}
fi
"$GBLENS" attach ${ATTACH_ARGS:-} --layout "$LAYOUT" --window "$WINDOW" --event-log "$OUT/events" -- "$@" 2>"$OUT/viewer.log" &
VIEWER=$!
until grep -q '"ready"' "$OUT/events" 2>/dev/null; do
  kill -0 $VIEWER 2>/dev/null || { cat "$OUT/viewer.log"; exit 1; }
  sleep 0.2
done
WID=$(xdotool search --onlyvisible --name '^gblens' | head -1)
[ "$VIEWS" = grid ] && xdotool key --window "$WID" 1
sleep "$SECONDS_"
if [ -n "${CLICK:-}" ]; then  # CLICK="X Y": a click there (window coordinates: the probe), then KEYS
  xdotool mousemove --window "$WID" $CLICK click 1
  sleep 1
fi
for k in ${KEYS:-}; do xdotool key --window "$WID" "$k"; sleep 0.5; done
if [ -n "${SHOT:-}" ]; then  # SHOT=FILE.png: the window as it was at the end, for people to look at
  xwd -root -silent -display "$DISPLAY" > "$OUT/shot.xwd" && convert "xwd:$OUT/shot.xwd" "$SHOT"
fi
xdotool key --window "$WID" ctrl+q
wait $VIEWER || true
# The application ran on after the viewer detached: its pid is the attach_open event's.
APP_PID=$(/usr/bin/python3 -c 'import json, sys
print(next((json.loads(l)["pid"] for l in open(sys.argv[1]) if "attach_open" in l), ""))' "$OUT/events")
[ -n "$APP_PID" ] && kill "$APP_PID" 2>/dev/null || true
/usr/bin/python3 - "$OUT/events" "$VIEWS" "$WINDOW" "$OUT/viewer.log" <<'EOF'
import json, statistics, sys
events = [json.loads(l) for l in open(sys.argv[1]) if l.strip().endswith("}")]
frames = [e for e in events if e["event"] == "attach_frame"][3:]   # after the window's start-up
shown = [e for e in events if e["event"] == "attach_shown"][3:]
hello = [e for e in events if e["event"] == "attach_open"][0]
span = (frames[-1]["time_s"] - frames[0]["time_s"]) or 1.0
app_ms = 1000.0 * span / max(1, frames[-1]["app_frame"] - frames[0]["app_frame"])
presented = [l for l in open(sys.argv[4]) if "presented" in l]
taken = statistics.median(e["latency_ms"] for e in frames)
screen = statistics.median(e["latency_ms"] for e in shown)
print(json.dumps({"application": hello["hello"].get("application"), "views": sys.argv[2], "window": sys.argv[3],
                  "frames_shown": len(shown), "shown_per_s": len(shown) / span, "app_frame_ms": app_ms,
                  "paced": frames[-1].get("paced"),
                  "copied_per_shown": (frames[-1].get("copied", 0) - frames[0].get("copied", 0)) / max(1, len(frames) - 1),
                  "taken_latency_ms": taken, "screen_latency_ms": screen,
                  "screen_latency_frames": screen / app_ms, "show_ms": statistics.median(e["show_ms"] for e in frames),
                  "viewer": presented[-1].strip() if presented else ""}, indent=2))
EOF
