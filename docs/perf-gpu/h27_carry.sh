#!/bin/sh
# The folder carried to the GPU machine for `gblens bench --only attach` (issue 27, docs/attach.md):
# make_carry.sh's (the binary, stubbed libraries, libcrypto, the loader .debs) plus the gblens layer
# (layer/: the library and its implicit-layer manifest, found beside the binary), and an OpenImageIO
# stub whose ImageOutput::create returns none, so that `gblens render` (the application the bench
# attaches to) reports "cannot write PNG" after its frames instead of aborting. Usage:
# docs/perf-gpu/h27_carry.sh BUILD_DIR DEST
set -eu
BUILD=${1:-build}; DEST=${2:-build-h27}
sh "$(dirname "$0")/make_carry.sh" "$BUILD" "$DEST"
mkdir -p "$DEST/layer/vulkan/implicit_layer.d"
cp "$BUILD/layer/libVkLayer_gblens_live.so" "$DEST/layer/"
cp "$BUILD/layer/vulkan/implicit_layer.d/VkLayer_gblens_live.json" "$DEST/layer/vulkan/implicit_layer.d/"
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
L=libOpenImageIO.so.2.4
nm -D --undefined-only "$BUILD/gblens" | awk '{print $2}' | sed 's/@.*//' | sort -u > "$TMP/undef"
nm -D --defined-only "/usr/lib/x86_64-linux-gnu/$L" | awk '{print $3}' | sed 's/@.*//' | sort -u > "$TMP/def"
CREATE=_ZN16OpenImageIO_v2_411ImageOutput6createENS_17basic_string_viewIcSt11char_traitsIcEEEPNS_10Filesystem7IOProxyES4_
ERROR=_ZN16OpenImageIO_v2_48geterrorB5cxx11Eb
{ echo '#include <stdio.h>'; echo '#include <stdlib.h>'
  # std::unique_ptr<ImageOutput> and std::string are returned through a pointer the caller passes
  # first (x86-64 SysV): an empty unique_ptr, an empty std::string (libstdc++: data -> its own buffer).
  echo "void* create_none(void** ret) __asm__(\"$CREATE\"); void* create_none(void** ret) { *ret = 0; return ret; }"
  echo "char* no_error(char* ret) __asm__(\"$ERROR\"); char* no_error(char* ret) { *(char**)ret = ret + 16; *(unsigned long*)(ret + 8) = 0; ret[16] = 0; return ret; }"
  comm -12 "$TMP/undef" "$TMP/def" | grep -v -e "^$CREATE\$" -e "^$ERROR\$" | while read -r s; do
    printf 'void %s(void) { fprintf(stderr, "stub: %s %s called\\n"); abort(); }\n' "$s" "$L" "$s"; done; } > "$TMP/$L.c"
gcc -shared -fPIC -O1 -Wl,-soname,$L -o "$DEST/lib/$L" "$TMP/$L.c"
du -sh "$DEST"
