# Thin wrapper over CMake: the README's two commands (`make run`, `make test`) start here.
BUILD   ?= build
JOBS    ?= $(shell nproc)
GBLENS  := $(BUILD)/gblens
PACKAGES := $(shell grep -v '^\#' debian-packages.txt)

.PHONY: deps build build-gblens run test bench stress fuzz test-asan clean golden fixtures

# Install missing Debian packages when root; otherwise print the exact command and stop.
deps:
	@missing=""; for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'ok installed' || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "make deps: installing$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	  else \
	    echo "make deps: missing packages; run:"; \
	    echo "  sudo apt-get install -y --no-install-recommends$$missing"; exit 1; \
	  fi; \
	fi

# Ninja (debian-packages.txt installs it): it starts the next compile as soon as one ends and
# rebuilds only what changed; ccache (the same list) serves what any clone compiled before.
GENERATOR := $(if $(shell command -v ninja),-G Ninja,)

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# What `run` needs only: the gblens executable and the layer it loads (not the tests, the test
# subjects or the Python module), so that a fresh clone shows a frame soonest.
build-gblens: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target gblens

# With a display: the viewer. Without: a headless render of the built-in scene.
run: build-gblens
	@if [ -n "$$DISPLAY" ]; then $(GBLENS) view; else \
	  mkdir -p out && $(GBLENS) render builtin:temple -o out/temple.png && \
	  echo "No DISPLAY: rendered a headless frame to $$(pwd)/out/temple.png"; fi

test: build
	cd $(BUILD) && ctest --output-on-failure -j 2 --timeout 900

# Rewrite tests/golden/temple after an intended change to the rendered frame (then review and commit).
golden: build
	tests/golden/golden.sh regenerate $(GBLENS)

# Rewrite tests/data/blender (the Cycles G-buffer that tests/unit/test_blender_import.cpp imports, and
# sequence/: five frames of an animation, checked by check_vectors.py) with Blender (Debian's blender
# 3.4: installed when root, else named); then look at it and commit it.
BLENDER ?= blender
fixtures:
	@command -v $(BLENDER) >/dev/null || { \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "make fixtures: installing blender"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends blender; \
	  else echo "make fixtures: needs Blender; run:"; echo "  sudo apt-get install -y --no-install-recommends blender"; exit 1; fi; }
	$(BLENDER) -b --factory-startup -noaudio -P assets/blender/render_gbuffer.py -- tests/data/blender
	$(BLENDER) -b --factory-startup -noaudio -P assets/blender/render_gbuffer.py -- tests/data/blender/ortho 96 54 --ortho --full-float
	$(BLENDER) -b --factory-startup -noaudio -P assets/blender/render_sequence.py -- tests/data/blender/sequence
	/usr/bin/python3 assets/blender/check_vectors.py tests/data/blender/sequence
	@ls -l tests/data/blender tests/data/blender/ortho tests/data/blender/sequence

# The default sweep on the built-in temple and, when present, the shared VC model (a glTF that
# does not load is skipped with a message). Budgeted to finish within 15 minutes on 2 cores.
VC_SCENE := $(firstword $(wildcard ../shared/assets/VC/glTF/VC.gltf /work/shared/assets/VC/glTF/VC.gltf))
# The attach section also measures a Vulkan 1.0 application that is not gblens: the test subject
# tests/subjects/tiler_deferred at 1280x720, the four targets of its two-subpass G-buffer streamed.
TILER := $(BUILD)/tests/subjects/tiler_deferred/tiler_deferred
bench: build-gblens
	cmake --build $(BUILD) -j $(JOBS) --target tiler_deferred
	$(GBLENS) bench builtin:temple $(VC_SCENE) --out out/bench \
	  --attach-app "$(abspath $(TILER)) --mode subpass --size 1280x720 --frames {frames}" \
	  --attach-app-layout $(abspath tests/subjects/tiler_deferred/layout_subpass_gbuffer.json)

# The numerical stability suite in full (docs/stability.md holds the table of the last run).
stress: build-gblens
	mkdir -p out && $(GBLENS) stress --json out/stress.json

# The glTF loader, the import path, the capture readers and attach's command line under libFuzzer +
# ASan + UBSan (clang-14, libclang-rt-14-dev), FUZZ_SECONDS each; FUZZ_TARGETS chooses (gltf, import,
# capture, attach). Seeds: the glTF test corpus and tests/fuzz/{import,capture,attach}_corpus (the
# crash cases, also run by `make test`); new inputs go to build-fuzz/corpus-TARGET, crashes to
# build-fuzz/crashes. Not run in CI.
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?= gltf import capture attach
FUZZ_SEEDS_gltf := tests/data/gltf/valid tests/data/gltf/invalid -dict=tests/fuzz/gltf.dict -max_len=65536
FUZZ_SEEDS_import := tests/fuzz/import_corpus -max_len=16384
FUZZ_SEEDS_capture := tests/fuzz/capture_corpus -dict=tests/fuzz/capture.dict -max_len=65536
FUZZ_SEEDS_attach := tests/fuzz/attach_corpus -dict=tests/fuzz/attach.dict -max_len=4096
fuzz:
	@command -v clang++-14 >/dev/null && test -e /usr/lib/llvm-14/lib/clang/14.0.6/lib/linux/libclang_rt.fuzzer-x86_64.a || \
	  { echo "make fuzz: needs clang-14 and libclang-rt-14-dev (sudo apt-get install clang-14 libclang-rt-14-dev)"; exit 1; }
	cmake -S tests/fuzz -B build-fuzz -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo
	cmake --build build-fuzz -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
	mkdir -p build-fuzz/crashes
	set -e; for t in $(FUZZ_TARGETS); do mkdir -p build-fuzz/corpus-$$t; \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp build-fuzz/fuzz_$$t build-fuzz/corpus-$$t \
	    $$(case $$t in gltf) echo "$(FUZZ_SEEDS_gltf)";; import) echo "$(FUZZ_SEEDS_import)";; \
                     capture) echo "$(FUZZ_SEEDS_capture)";; attach) echo "$(FUZZ_SEEDS_attach)";; esac) \
	    -max_total_time=$(FUZZ_SECONDS) -timeout=10 -rss_limit_mb=4096 \
	    -artifact_prefix=build-fuzz/crashes/$$t- -print_final_stats=1; done

# The test suite built with -DGBLENS_SANITIZE=ON (AddressSanitizer + UndefinedBehaviorSanitizer)
# in build-asan. ASAN_TESTS narrows it (a ctest -R regex), e.g. ASAN_TESTS=Gltf.
# -O1 -g1 as ASan's documentation advises: at -O2 -g the build alone took about 2 hours on 2 cores;
# -O1 keeps reports exact and -g1 line tables are all a symbolised report needs. Asserts stay on.
ASAN_TESTS ?= .
ASAN_FLAGS := -O1 -g1
# Preloaded: the ASan runtime (first, so /usr/bin/python3 can load the sanitized module and RenderDoc
# can inject its library after it) and the Vulkan driver, which the loader would otherwise unload
# before the leak check (its leaks then show as "<unknown module>" or under whatever library was
# mapped there later). Leak checking is off unless ASAN_LEAKS=1: the loader also opens and unloads
# every installed driver and layer, whose exit-time leaks cannot then be told from ours (preloading
# the validation layer too would name them, but changes how its entry points are called).
ASAN_PRELOAD = $(shell gcc -print-file-name=libasan.so) $(wildcard /usr/lib/$(shell gcc -dumpmachine)/libvulkan_lvp.so)
ASAN_LEAKS ?= 0
test-asan: deps
	cmake -S . -B build-asan $(GENERATOR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGBLENS_SANITIZE=ON \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO='$(ASAN_FLAGS)' -DCMAKE_C_FLAGS_RELWITHDEBINFO='$(ASAN_FLAGS)'
	cmake --build build-asan -j $(JOBS)
	cd build-asan && LD_PRELOAD="$(ASAN_PRELOAD)" \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 ASAN_OPTIONS=abort_on_error=1:verify_asan_link_order=0:detect_leaks=$(ASAN_LEAKS) \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --output-on-failure -j 2 --timeout 1800 -R '$(ASAN_TESTS)'

clean:
	rm -rf $(BUILD)
