#!/usr/bin/env bash
# Scripted mouse input to `tandem view` under Xvfb: presses the left button at pixel (X0, Y0),
# moves to (X1, Y1) in small steps over 1.2 s, holds for 1 s, releases, lets the scene settle for
# 3 s, then tells the viewer to quit (SIGTERM: it finishes its frame and prints where the dynamic
# bodies are). Every span is simulated time, not wall-clock time: the script asks the viewer for
# its simulated time with SIGUSR1 and waits for it to pass, because the viewer keeps real time
# only on an idle machine: paced by the wall clock, a loaded machine simulated a shorter, faster
# drag and less settling than an idle one. The script decides when the viewer stops, so no
# xdotool call can meet a window that is already gone.
# It prints the viewer's output (the dynamic bodies' final positions) for the caller to check.
# Usage: viewer_drag.sh TANDEM SCENE X0 Y0 X1 Y1 [CAMERA]   (CAMERA: ex,ey,ez,tx,ty,tz)
set -euo pipefail
tandem=$1 scene=$2 x0=$3 y0=$4 x1=$5 y1=$6 camera=${7:-0,1.2,3,0,0.2,0}
script=$(mktemp) output=$(mktemp)
trap 'rm -f "$script" "$output"' EXIT
cat > "$script" <<INNER
set -euo pipefail
# --max-seconds only guards against a hang; the script ends the viewer with SIGTERM.
"$tandem" view "$scene" --width 960 --height 540 --camera $camera --max-seconds 300 > "$output" &
viewer=\$!
trap 'kill -TERM \$viewer 2>/dev/null || true; cat "$output"' EXIT
# The viewer's simulated time: asked for with SIGUSR1, answered after its next frame.
simulated() {
  local before=\$(grep -c '^simulated ' "$output" || true)
  kill -USR1 \$viewer
  for _ in \$(seq 1 500); do
    [ "\$(grep -c '^simulated ' "$output" || true)" -gt "\$before" ] && break
    sleep 0.02
  done
  grep '^simulated ' "$output" | tail -1 | cut -d' ' -f2
}
# Waits until the viewer has simulated SPAN more seconds (each answer comes after a whole frame,
# so a frame that has not yet seen the last mouse event is never counted as one that has).
# A viewer that has quit, or has not got there within 60 s, ends the script with an error,
# at once, instead of every later wait running into its own limit.
wait_simulated() {
  local start=\$(simulated) deadline=\$((SECONDS + 60))
  while [ \$SECONDS -lt \$deadline ] && kill -0 \$viewer 2>/dev/null; do
    awk -v now="\$(simulated)" -v start="\$start" -v span="\$1" 'BEGIN { exit !(now >= start + span) }' && return
  done
  echo "viewer_drag.sh: the viewer did not simulate \$1 s more (quit, or over 60 s)" >&2
  exit 1
}
window=\$(timeout 60 xdotool search --sync --name Tandem | head -1 || true)
if [ -z "\$window" ]; then echo "viewer_drag.sh: no Tandem window within 60 s" >&2; exit 1; fi
wait_simulated 0.2
xdotool mousemove --window "\$window" $x0 $y0
wait_simulated 0.05
xdotool mousedown 1
wait_simulated 0.05  # the press is seen, and the pick made, at (X0, Y0)
for i in \$(seq 1 20); do
  xdotool mousemove --window "\$window" \$(( $x0 + ($x1 - $x0) * i / 20 )) \$(( $y0 + ($y1 - $y0) * i / 20 ))
  wait_simulated 0.06
done
wait_simulated 1
xdotool mouseup 1
wait_simulated 3
kill -TERM \$viewer
trap - EXIT
wait \$viewer
cat "$output"
INNER
xvfb-run -a -s "-screen 0 1280x720x24" bash "$script"
