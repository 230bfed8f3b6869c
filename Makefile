# Relief: the two commands a user needs on a fresh Debian 12 machine (as root).
#
#   make render   install what the renderer needs, build the relief binary alone (build-render/,
#                 no tests, benchmarks or OpenGL), render the default scene to relief.png
#   make test     install what is missing, build everything, run the whole test suite (ctest),
#                 then build again with ASan + UBSan and run the suite once more
#   make fuzz     build the libFuzzer targets with clang (build-fuzz/) and run each for
#                 FUZZ_SECONDS on a copy of its seed corpus; fails if any of them finds a crash
#
# Dependencies come only from Debian's packages (see DEVELOPERS.md); apt-get is run only
# for the packages that are not installed yet.

BUILD        ?= build
ASAN_BUILD   ?= build-asan
RENDER_BUILD ?= build-render
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
JOBS         ?= $(shell nproc)
SCENE        ?= default
PREFIX       ?= /usr/local
# Unity builds (CMake batches of 8 sources compiled as one translation unit, the Highway kernels
# excepted): every header is parsed once a batch instead of once a file, which was most of the
# compile time. UNITY=OFF builds each file on its own (faster to rebuild after editing one file,
# and it shows an #include a file forgot that its batch happened to provide).
UNITY        ?= ON

# What the relief binary and the library need; the tests, benchmarks and the OpenGL side add
# the rest. OpenImageIO is the binary's alone (relief compare, EXR outputs); Debian 12's
# OpenImageIOConfig.cmake refuses to load without its programs, so openimageio-tools comes
# with it (the tests also run its idiff).
RENDER_PACKAGES := cmake make g++ pkg-config \
                   libtbb-dev libglm-dev libstb-dev libdeflate-dev nlohmann-json3-dev libcli11-dev libhwy-dev \
                   libopenimageio-dev openimageio-tools
# gnuplot-nox draws relief sweep's plot (an external program, run only by that command; the
# tests require it).
# python3 runs the independent transcriptions that the golden numbers of the tests come from
# (tests/oracles/, standard library only). slurm-wlm and munge: the test that starts a
# one-node Slurm and renders shards on it (tests/slurm/slurm_test.sh). pybind11-dev,
# python3-dev, python3-numpy and python3-pytest: `import relief` and its pytest suite (python/).
# python-matplotlib-data (data files alone, no Python code) ships a real elevation model that
# tests/heightfield/real_dem_test.py renders (mpl-data/sample_data/jacksboro_fault_dem.npz).
PACKAGES := $(RENDER_PACKAGES) catch2 libbenchmark-dev \
            libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri gnuplot-nox python3 \
            slurm-wlm munge pybind11-dev python3-dev python3-numpy python3-pytest \
            python-matplotlib-data

# make fuzz alone: libFuzzer comes with clang (Debian's clang is clang 14; its runtime
# libraries, libFuzzer among them, are libclang-rt-14-dev). Not needed by make test.
FUZZ_PACKAGES := $(RENDER_PACKAGES) clang libclang-rt-14-dev
FUZZ_TARGETS  := scene override soup texture

# Every part on (the options' defaults, spelled out so that a cache configured otherwise is
# corrected), and every part off for make render.
ALL_PARTS  := -DRELIEF_BUILD_TESTS=ON -DRELIEF_BUILD_BENCHMARKS=ON -DRELIEF_WITH_GL=ON \
              -DRELIEF_WITH_PYTHON=ON
NO_PARTS   := -DRELIEF_BUILD_TESTS=OFF -DRELIEF_BUILD_BENCHMARKS=OFF -DRELIEF_WITH_GL=OFF \
              -DRELIEF_WITH_PYTHON=OFF

.PHONY: all deps deps-render deps-fuzz build render install test test-release test-sanitize \
        fuzz format clean

all: build

deps: DEPS := $(PACKAGES)
deps-render: DEPS := $(RENDER_PACKAGES)
deps-fuzz: DEPS := $(FUZZ_PACKAGES)
deps deps-render deps-fuzz:
	@missing=""; \
	for p in $(DEPS); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' \
	    || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "relief: installing missing Debian packages:$$missing"; \
	  if [ "$$(id -u)" != 0 ]; then echo "relief: run as root (apt-get needs it)" >&2; exit 1; fi; \
	  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $$missing; \
	fi

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DRELIEF_WERROR=ON \
	  -DCMAKE_UNITY_BUILD=$(UNITY) $(ALL_PARTS)
	cmake --build $(BUILD) -j $(JOBS)

render: deps-render
	cmake -S . -B $(RENDER_BUILD) -DCMAKE_BUILD_TYPE=Release -DRELIEF_WERROR=ON \
	  -DCMAKE_UNITY_BUILD=$(UNITY) $(NO_PARTS)
	cmake --build $(RENDER_BUILD) -j $(JOBS) --target relief
	./$(RENDER_BUILD)/tools/relief render $(SCENE) -o relief.png

# The relief binary, the library, its header and relief-config.cmake under PREFIX.
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

test-release: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-sanitize: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRELIEF_WERROR=ON -DRELIEF_SANITIZE=ON \
	  -DCMAKE_UNITY_BUILD=$(UNITY) $(ALL_PARTS)
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

test: test-release test-sanitize

# Each fuzzer runs in $(FUZZ_BUILD)/fuzz/run/TARGET on a fresh copy of fuzz/corpus/TARGET (the
# repository's seeds stay as they are), one process on one core, with its dictionary; a crash,
# sanitizer report, uncaught exception, timeout (10 s an input) or more than 2 GiB leaves its
# input there as crash-*, timeout-*, oom-* or leak-* and fails the target.
fuzz: deps-fuzz
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DRELIEF_WERROR=ON -DRELIEF_BUILD_FUZZERS=ON $(NO_PARTS)
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target relief_fuzzers
	@failed=""; \
	for t in $(FUZZ_TARGETS); do \
	  run=$(FUZZ_BUILD)/fuzz/run/$$t; rm -rf $$run; mkdir -p $$run/corpus; \
	  cp fuzz/corpus/$$t/* $$run/corpus/; \
	  echo "relief: fuzzing $$t for $(FUZZ_SECONDS) s (output in $$run/fuzz.log)"; \
	  (cd $$run && ../../relief_fuzz_$$t corpus -dict=$(CURDIR)/fuzz/$$t.dict \
	     -max_total_time=$(FUZZ_SECONDS) -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
	     >fuzz.log 2>&1) && ok=1 || ok=0; \
	  grep -E '^#[0-9]+[[:space:]]+DONE' $$run/fuzz.log || true; \
	  if ls $$run | grep -Eq '^(crash|timeout|oom|leak)-'; then ok=0; fi; \
	  [ $$ok = 1 ] || failed="$$failed $$t"; \
	done; \
	if [ -n "$$failed" ]; then \
	  echo "relief: the fuzzers found problems in:$$failed (see $(FUZZ_BUILD)/fuzz/run/*/fuzz.log)" >&2; \
	  exit 1; \
	fi

format:
	git ls-files '*.h' '*.cc' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(RENDER_BUILD) $(FUZZ_BUILD)
