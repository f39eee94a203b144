#!/bin/sh
# Tandem against Bullet's soft bodies on the paper's three scenes, in one run, back to back
# (docs/performance.md). Bullet's peer is built from ../shared/peers/bullet (its README), at the
# cheapest settings at which it passes each scene; Tandem runs the shipped scenes.
#   bench/against_bullet.sh PEER_BINARY [TANDEM_BINARY ...]     (default: build/tandem)
# Prints the mean ms per step of each, per scene; the rope at K = 2 (the paper's) and K = 4 (the
# shipped scene's), the cloth at its shipped K = 4 and at K = 2.
set -e
peer=$1
shift
[ $# -gt 0 ] || set -- build/tandem
scenes=$(dirname "$0")/../scenes
mean() { "$@" 2>/dev/null | sed -n -E 's/.*mean=([0-9.]+).*/\1/p; s/^ms per step: mean ([0-9.]+).*/\1/p'; }
tandems() {
  line=""
  for t in "$@"; do line="$line $(mean "$t" run "$scenes/$scene" --quiet $options)"; done
  echo "$line"
}
echo "# $(date -u +%FT%TZ)  load $(cut -d' ' -f1-3 /proc/loadavg)  columns: Bullet, then each Tandem given"
echo "rope K=2: $(mean "$peer" rope piter=50 voxel=0.02 substeps=10) |$(scene=rope_wheel.json options='--iterations 2' tandems "$@")"
echo "rope K=4: (same) |$(scene=rope_wheel.json options='--iterations 4' tandems "$@")"
echo "cloth:    $(mean "$peer" cloth piter=10 kkhr=1 voxel=0.05) |$(scene=cloth_sphere.json options='--seconds 4' tandems "$@")"
echo "cloth K=2: (same) |$(scene=cloth_sphere.json options='--seconds 4 --iterations 2' tandems "$@")"
echo "jelly:    $(mean "$peer" jelly piter=2 kkhr=1 substeps=5) |$(scene=jelly_dish.json options='--seconds 4' tandems "$@")"
