#!/usr/bin/env bash
# Scripted mouse input to `tandem view` under Xvfb: presses the left button at pixel (X0, Y0),
# moves to (X1, Y1) in small steps, holds, releases, lets the scene settle (3 s: the viewer keeps
# real time only on an idle machine, and a box the drag tipped must have the simulated time to fall
# back flat; after 1 s a loaded CI machine once left it tipped, 13 mm high), then tells the viewer
# to quit (SIGTERM: it finishes its frame and prints where the dynamic bodies are). The script
# decides when the viewer stops, so no xdotool call can meet a window that is already gone (the
# old wall-clock limit raced the drag on a loaded machine: "X Error ... BadWindow").
# It prints the viewer's output (the dynamic bodies' final positions) for the caller to check.
# Usage: viewer_drag.sh TANDEM SCENE X0 Y0 X1 Y1 [CAMERA]   (CAMERA: ex,ey,ez,tx,ty,tz)
set -euo pipefail
tandem=$1 scene=$2 x0=$3 y0=$4 x1=$5 y1=$6 camera=${7:-0,1.2,3,0,0.2,0}
script=$(mktemp)
trap 'rm -f "$script"' EXIT
cat > "$script" <<INNER
set -euo pipefail
# --max-seconds only guards against a hang; the script ends the viewer with SIGTERM.
"$tandem" view "$scene" --width 960 --height 540 --camera $camera --max-seconds 300 &
viewer=\$!
trap 'kill -TERM \$viewer 2>/dev/null || true' EXIT
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
sleep 3
kill -TERM \$viewer
trap - EXIT
wait \$viewer
INNER
xvfb-run -a -s "-screen 0 1280x720x24" bash "$script"
