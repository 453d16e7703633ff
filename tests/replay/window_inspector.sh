#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The inspector in a real window (Xvfb, xdotool, GLFW input through Dear ImGui's GLFW backend):
# opened with --inspector, a click on its "hollow" box changes the marble cylinder's Splitable, and
# presses over it stay with it: in split mode a drag over the window (where the torus is behind it)
# cuts nothing, while a drag across the wooden cube, outside it, cuts the cube.
# usage: window_inspector.sh path/to/cleave-demo output-dir [no-inspector]
# With "no-inspector" (built without Dear ImGui) it only says so and exits 77: ctest's skip.
set -euo pipefail
demo="$1"
out="$2"
if [ "${3:-}" = "no-inspector" ]; then
  echo "window inspector test: skipped, the inspector is not built (libimgui-dev missing, or CLEAVE_INSPECTOR=OFF)"
  exit 77
fi
mkdir -p "$out"
rm -f "$out/state.jsonl" "$out/demo.log"
for tool in xvfb-run xdotool python3; do
  command -v "$tool" >/dev/null || { echo "window inspector test: $tool is not installed"; exit 1; }
done

export CLEAVE_DEMO="$demo" CLEAVE_OUT="$out"
xvfb-run -a -s "-screen 0 1280x720x24" bash -c '
  set -u
  "$CLEAVE_DEMO" --inspector --ticks 900 --width 1280 --height 720 --dump-state "$CLEAVE_OUT/state.jsonl" \
      >"$CLEAVE_OUT/demo.log" 2>&1 &
  pid=$!
  if ! window=$(timeout 30 xdotool search --sync --name "Cleave tech demo" | head -n 1); then
    echo "window inspector test: the demo window did not appear"; kill "$pid"; wait "$pid"; exit 1
  fi
  sleep 2
  xdotool mousemove --window "$window" 640 360
  sleep 0.5
  # The "hollow (no caps)" box of the inspector, laid out at the right of a 1280 x 720 window.
  xdotool mousemove --window "$window" 848 222
  sleep 0.3
  xdotool click --window "$window" 1
  sleep 0.5
  xdotool keydown --window "$window" space
  sleep 0.3
  drag() {  # x y0 y1
    xdotool mousemove --window "$window" "$1" "$2"; sleep 0.3
    xdotool mousedown --window "$window" 1; sleep 0.3
    xdotool mousemove --window "$window" "$1" $(( ($2 + $3) / 2 )); sleep 0.2
    xdotool mousemove --window "$window" "$1" "$3"; sleep 0.3
    xdotool mouseup --window "$window" 1; sleep 0.4
  }
  drag 900 300 480   # over the inspector: the torus behind it must not be cut
  drag 380 300 480   # across the wooden cube
  xdotool keyup --window "$window" space
  wait "$pid"
'
cat "$out/demo.log"
[ -s "$out/state.jsonl" ] || { echo "window inspector test: no state dump"; exit 1; }
tail -n 1 "$out/state.jsonl" | python3 -c '
import json, sys
line = json.loads(sys.stdin.read())
inspector = line["inspector"]
cut = sorted({s["original"] for s in line["splits"] if s["pieces"] > 0})
print("window inspector test: open %s, target %r, settings %s, cut %s" % (
    inspector["open"], inspector["target"], inspector["settings"], cut))
problems = []
if not inspector["open"]: problems.append("the inspector is not open")
if inspector["target"] != "marble cylinder": problems.append("the crosshair object is not the marble cylinder")
elif not inspector["settings"]["hollow"]: problems.append("the click on \"hollow\" did not change the Splitable")
if "wooden cube" not in cut: problems.append("the drag across the wooden cube did not cut it")
if "torus" in cut: problems.append("the drag over the inspector reached the game (the torus was cut)")
for p in problems: print("window inspector test: " + p)
sys.exit(1 if problems else 0)
'
