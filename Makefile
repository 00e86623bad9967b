# Thin wrapper over CMake. `make run`: install what is missing, build, generate the
# default tables into out/. `make test`: build and run the whole suite through CTest.
BUILD ?= build
OUT ?= out
JOBS ?= $(shell nproc)
# SCATTERLUT_REQUIRE_ALL_TESTS: `make run` installs every tool the suite uses, so a missing
# one is a configure error here, never a silently skipped test.
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSCATTERLUT_REQUIRE_ALL_TESTS=ON

# Everything a minimal Debian 12 (debootstrap --variant=minbase, plus git, make, g++, cmake
# and python3) lacks for the build and the whole test suite, installed with
# --no-install-recommends: the OpenCL runtime (PoCL) and headers, the libraries, the
# shader tools and Mesa's llvmpipe behind EGL (libopengl-dev: CMake's OpenGL::EGL needs
# libOpenGL), clang's libFuzzer, mpmath for the reference-value script, and node with npm
# for the engine-loader tests and the web demo (three.js and puppeteer-core from npm, pinned
# in tests/js/ and examples/web/package-lock.json; an npm that came with another nodejs
# build, such as NodeSource's, counts as installed), Chromium for the browser tests (WebGL2 and
# WebGPU), and pycparser for the WGSL translator (tables/shaders/wgsl/slut_wgsl.py).
DEB_PACKAGES := cmake g++ make pkg-config python3 python3-mpmath \
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo \
  libopenexr-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev \
  libboost-math-dev libgtest-dev libbenchmark-dev \
  glslang-tools spirv-cross libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri \
  clang libclang-rt-14-dev zlib1g-dev \
  nodejs npm chromium python3-pycparser

.PHONY: all run test deps js-deps configure build clean

all: build

deps:
	@missing=""; \
	for p in $(DEB_PACKAGES); do \
	  if [ $$p = npm ] && command -v npm >/dev/null; then continue; fi; \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "installing:$$missing"; \
	    apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $$missing; \
	  else \
	    echo "missing Debian packages:$$missing"; \
	    echo "install them with:  sudo apt-get install -y$$missing"; \
	    exit 1; \
	  fi; \
	fi

# The npm modules of tests/js and examples/web, exactly as their package-lock.json pin them.
# Offline once done: skipped while node_modules is newer than the lock file (npm ci
# rewrites it).
JS_DIRS := tests/js examples/web
js-deps: deps
	@for d in $(JS_DIRS); do \
	  if [ $$d/node_modules/.package-lock.json -nt $$d/package-lock.json ]; then \
	    echo "$$d: npm modules current"; \
	  else \
	    (cd $$d && npm ci --no-audit --no-fund) || exit 1; \
	  fi; \
	done

configure: deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

run: build js-deps
	./$(BUILD)/scatterlut generate --out $(OUT)

test: build js-deps
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD)
