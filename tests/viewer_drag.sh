#!/usr/bin/env bash
# Scripted mouse input to `tandem view` under Xvfb: presses the left button at pixel (X0, Y0),
# moves to (X1, Y1) in small steps, releases, and lets the viewer run out its wall-clock time.
# It prints the viewer's output (the dynamic bodies' final positions) for the caller to check.
# Usage: viewer_drag.sh TANDEM SCENE X0 Y0 X1 Y1 [CAMERA]   (CAMERA: ex,ey,ez,tx,ty,tz)
set -euo pipefail
tandem=$1 scene=$2 x0=$3 y0=$4 x1=$5 y1=$6 camera=${7:-0,1.2,3,0,0.2,0}
script=$(mktemp)
trap 'rm -f "$script"' EXIT
cat > "$script" <<INNER
set -euo pipefail
"$tandem" view "$scene" --width 960 --height 540 --camera $camera --max-seconds 9 &
viewer=\$!
window=\$(xdotool search --sync --name Tandem | head -1)
sleep 1
xdotool mousemove --window "\$window" $x0 $y0
sleep 0.3
xdotool mousedown 1
for i in \$(seq 1 40); do
  xdotool mousemove --window "\$window" \$(( $x0 + ($x1 - $x0) * i / 40 )) \$(( $y0 + ($y1 - $y0) * i / 40 ))
  sleep 0.03
done
sleep 0.5
xdotool mouseup 1
wait \$viewer
INNER
xvfb-run -a -s "-screen 0 1280x720x24" bash "$script"
