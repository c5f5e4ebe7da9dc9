#!/bin/sh
# Builds the folder carried to the device machine for `gblens bench --only methods` on its GPU
# (docs/perf-gpu.md): the binary, stub libraries for what the device image lacks and the
# method comparison never calls (every symbol gblens imports from them defined as an abort),
# libcrypto, libdraco, and the Vulkan loader .debs. Usage: docs/perf-gpu/make_carry.sh BUILD_DIR DEST
set -eu
BUILD=${1:-build}; DEST=${2:-build-perfgpu}
mkdir -p "$DEST/lib" "$DEST/gl"
cp "$BUILD/gblens" "$DEST/"
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
nm -D --undefined-only "$BUILD/gblens" | awk '{print $2}' | sed 's/@.*//' | sort -u > "$TMP/undef"
for L in libglfw.so.3 libstb.so.0 libembree3.so.3 libOpenImageIO.so.2.4 libOpenImageIO_Util.so.2.4; do
  nm -D --defined-only "/usr/lib/x86_64-linux-gnu/$L" | awk '{print $3}' | sed 's/@.*//' | sort -u > "$TMP/def"
  { echo '#include <stdio.h>'; echo '#include <stdlib.h>'
    comm -12 "$TMP/undef" "$TMP/def" | while read -r s; do
      printf 'void %s(void) { fprintf(stderr, "stub: %s %s called\\n"); abort(); }\n' "$s" "$L" "$s"; done; } > "$TMP/$L.c"
  gcc -shared -fPIC -O1 -Wl,-soname,$L -o "$DEST/lib/$L" "$TMP/$L.c"
done
cp /usr/lib/x86_64-linux-gnu/libcrypto.so.3 "$DEST/lib/"
# Draco (glTF mesh compression) is small and has no further dependencies: carried as it is.
cp -L /usr/lib/x86_64-linux-gnu/libdraco.so.7 "$DEST/lib/"
mkdir -p /tmp/amd64/partial
o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
apt-get $o update -qq
(cd "$DEST/gl" && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
