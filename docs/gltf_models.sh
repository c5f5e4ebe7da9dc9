#!/bin/sh
# Regenerates docs/gltf_models.png: every model under ASSETS (default /work/shared/assets,
# folders <Model>/glTF*/) rendered by `gblens render` with its default camera, in a labelled
# montage (ImageMagick). Usage: docs/gltf_models.sh [BUILD_DIR] [ASSETS]
set -e
build=${1:-build}
assets=${2:-/work/shared/assets}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for f in "$assets"/*/glTF*/*.gltf "$assets"/*/glTF*/*.glb; do
  [ -e "$f" ] || continue
  model=$(basename "$(dirname "$(dirname "$f")")")
  variant=$(basename "$(dirname "$f")")
  "$build/gblens" render "$f" --size 480x360 -o "$out/$model $variant.png" 2>/dev/null
done
montage -font DejaVu-Sans -pointsize 15 -label '%t' "$out"/*.png -tile 4x -geometry 480x360+4+4 \
  -background '#202020' -fill white docs/gltf_models.png
echo "wrote docs/gltf_models.png"
