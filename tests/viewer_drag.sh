#!/usr/bin/env bash
# Scripted mouse input to `tandem view` under Xvfb: presses the left button at pixel (X0, Y0),
# moves to (X1, Y1) in small steps, holds, releases, lets the scene settle for 3 s of simulated
# time (a box the drag tipped must fall back flat; the viewer keeps real time only on an idle
# machine, so the script asks it for its simulated time with SIGUSR1 instead of sleeping a
# wall-clock span: a loaded CI machine once left the box tipped, 13 mm high, after 3 wall-clock
# seconds), then tells the viewer to quit (SIGTERM: it finishes its frame and prints where the
# dynamic bodies are). The script decides when the viewer stops, so no xdotool call can meet a
# window that is already gone.
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
  for _ in \$(seq 1 200); do
    [ "\$(grep -c '^simulated ' "$output" || true)" -gt "\$before" ] && break
    sleep 0.05
  done
  grep '^simulated ' "$output" | tail -1 | cut -d' ' -f2
}
window=\$(timeout 60 xdotool search --sync --name Tandem | head -1 || true)
if [ -z "\$window" ]; then echo "viewer_drag.sh: no Tandem window within 60 s" >&2; exit 1; fi
sleep 1
xdotool mousemove --window "\$window" $x0 $y0
sleep 0.3
xdotool mousedown 1
for i in \$(seq 1 40); do
  xdotool mousemove --window "\$window" \$(( $x0 + ($x1 - $x0) * i / 40 )) \$(( $y0 + ($y1 - $y0) * i / 40 ))
  sleep 0.03
done
sleep 1
xdotool mouseup 1
released=\$(simulated)
deadline=\$((SECONDS + 60))  # a viewer that stops answering fails the caller's checks, not hangs
while [ \$SECONDS -lt \$deadline ]; do
  awk -v now="\$(simulated)" -v released="\$released" 'BEGIN { exit !(now >= released + 3) }' && break
  sleep 0.1
done
kill -TERM \$viewer
trap - EXIT
wait \$viewer
cat "$output"
INNER
xvfb-run -a -s "-screen 0 1280x720x24" bash "$script"
