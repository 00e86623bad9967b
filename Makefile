# Thin wrapper over CMake. `make run`: install what is missing, build, generate the
# default tables into out/. `make test`: build and run the whole suite through CTest.
BUILD ?= build
OUT ?= out
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo

# Everything a fresh Debian 12 (with git, make, g++, cmake) lacks.
DEB_PACKAGES := cmake g++ make pkg-config \
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo \
  libopenexr-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev \
  libboost-math-dev libgtest-dev libbenchmark-dev \
  glslang-tools spirv-cross libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri \
  clang libclang-rt-14-dev zlib1g-dev python3 python3-mpmath

.PHONY: all run test deps configure build clean

all: build

deps:
	@missing=""; \
	for p in $(DEB_PACKAGES); do \
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

configure: deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

run: build
	./$(BUILD)/scatterlut generate --out $(OUT)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD)
