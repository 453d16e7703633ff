#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Real-window smoke test: the tech demo in a window on a virtual X server (Xvfb), driven by xdotool
# like a player: hold Space, drag across the wooden cube, release. The state dump of the last tick
# must show at least one split that produced pieces.
# usage: window_smoke.sh path/to/cleave-demo output-dir
set -euo pipefail
demo="$1"
out="$2"
mkdir -p "$out"
rm -f "$out/state.jsonl" "$out/demo.log"
for tool in xvfb-run xdotool; do
  command -v "$tool" >/dev/null || { echo "window smoke test: $tool is not installed"; exit 1; }
done

export CLEAVE_DEMO="$demo" CLEAVE_OUT="$out"
xvfb-run -a -s "-screen 0 1280x720x24" bash -c '
  set -u
  "$CLEAVE_DEMO" --ticks 360 --width 1280 --height 720 --dump-state "$CLEAVE_OUT/state.jsonl" \
      >"$CLEAVE_OUT/demo.log" 2>&1 &
  pid=$!
  if ! window=$(timeout 30 xdotool search --sync --name "Cleave tech demo" | head -n 1); then
    echo "window smoke test: the demo window did not appear"; kill "$pid"; wait "$pid"; exit 1
  fi
  sleep 2
  # The pointer over the window gives it the keyboard (no window manager on Xvfb).
  xdotool mousemove --window "$window" 640 360
  sleep 0.5
  xdotool keydown --window "$window" space
  sleep 0.5
  xdotool mousemove --window "$window" 380 300
  sleep 0.3
  xdotool mousedown --window "$window" 1
  sleep 0.3
  xdotool mousemove --window "$window" 380 400
  sleep 0.2
  xdotool mousemove --window "$window" 380 480
  sleep 0.3
  xdotool mouseup --window "$window" 1
  sleep 0.5
  xdotool keyup --window "$window" space
  wait "$pid"
'
cat "$out/demo.log"
[ -s "$out/state.jsonl" ] || { echo "window smoke test: no state dump"; exit 1; }
last=$(tail -n 1 "$out/state.jsonl")
# Splits that made pieces: a failed split logs "pieces":0 and does not count.
splits=$(grep -o '"pieces":[1-9][0-9]*' <<<"$last" | wc -l)
echo "window smoke test: $splits split(s) in the window run"
[ "$splits" -ge 1 ] || { echo "window smoke test: the drag did not cut anything"; exit 1; }
