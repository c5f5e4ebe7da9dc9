# Thin wrapper over CMake: the README's two commands (`make run`, `make test`) start here.
BUILD   ?= build
JOBS    ?= $(shell nproc)
GBLENS  := $(BUILD)/gblens
PACKAGES := $(shell grep -v '^\#' debian-packages.txt)

.PHONY: deps build run test bench stress fuzz test-asan clean golden

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

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# With a display: the viewer. Without: a headless render of the built-in scene.
run: build
	@if [ -n "$$DISPLAY" ]; then $(GBLENS) view; else \
	  mkdir -p out && $(GBLENS) render builtin:temple -o out/temple.png && \
	  echo "No DISPLAY: rendered a headless frame to $$(pwd)/out/temple.png"; fi

test: build
	cd $(BUILD) && ctest --output-on-failure -j 2 --timeout 900

# Rewrite tests/golden/temple after an intended change to the rendered frame (then review and commit).
golden: build
	tests/golden/golden.sh regenerate $(GBLENS)

# The default sweep on the built-in temple and, when present, the shared VC model (a glTF that
# does not load is skipped with a message). Budgeted to finish within 15 minutes on 2 cores.
VC_SCENE := $(firstword $(wildcard ../shared/assets/VC/glTF/VC.gltf /work/shared/assets/VC/glTF/VC.gltf))
bench: build
	$(GBLENS) bench builtin:temple $(VC_SCENE) --out out/bench

stress: build
	$(GBLENS) stress

clean:
	rm -rf $(BUILD)
