# Relief: the two commands a user needs on a fresh Debian 12 machine (as root).
#
#   make render   install what is missing, build, render the default scene to relief.png
#   make test     install what is missing, build, run the whole test suite (ctest),
#                 then build again with ASan + UBSan and run the suite once more
#
# Dependencies come only from Debian's packages (see DEVELOPERS.md); apt-get is run only
# for the packages that are not installed yet.

BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc)
SCENE      ?= default

PACKAGES := cmake make g++ pkg-config \
            libtbb-dev libglm-dev libstb-dev catch2 libbenchmark-dev \
            nlohmann-json3-dev libcli11-dev \
            libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri

.PHONY: all deps build render test test-release test-sanitize format clean

all: build

deps:
	@missing=""; \
	for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' \
	    || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "relief: installing missing Debian packages:$$missing"; \
	  if [ "$$(id -u)" != 0 ]; then echo "relief: run as root (apt-get needs it)" >&2; exit 1; fi; \
	  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $$missing; \
	fi

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DRELIEF_WERROR=ON
	cmake --build $(BUILD) -j $(JOBS)

render: build
	./$(BUILD)/tools/relief render $(SCENE) -o relief.png

test-release: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-sanitize: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRELIEF_WERROR=ON -DRELIEF_SANITIZE=ON
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

test: test-release test-sanitize

format:
	git ls-files '*.h' '*.cc' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
