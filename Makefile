# Thin wrapper for the README's commands. Everything real lives in CMake.
#   make run    install dependencies, configure, build, run the showcase, write its output and plot
#   make test   install dependencies, configure, build, run the whole ctest suite
#   make bench  build and run the benchmarks (figures on stdout)
#   make compare  SPH against fv1d on the pipe and channel problems of cases/compare (tables, figures)
#   make sanitize  unit tests under AddressSanitizer + UndefinedBehaviorSanitizer (build/asan/)
#   make format / make format-check   clang-format the sources / check they are formatted
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
DEPS := build-essential cmake pkg-config libgsl-dev libsundials-dev libyaml-dev libcmocka-dev \
        python3-matplotlib python3-yaml
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
SHOWCASE := $(BUILD)/showcase

.PHONY: all deps configure build test run bench compare sanitize format format-check clean

all: build

deps:
	@missing=""; for p in $(DEPS); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing$$missing"; \
	  $(SUDO) apt-get update && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y --no-install-recommends $$missing; \
	fi

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

run: build
	cases/showcase $(BUILD) $(SHOWCASE)

bench: build
	cmake --build $(BUILD) --target bench

compare: build
	@for p in water_hammer acoustic_outlet pipe_startup water_hammer_2d; do \
	  /usr/bin/python3 cases/compare/compare.py cases/compare/$$p/problem.yaml --build $(BUILD) \
	    --output $(BUILD)/cases/compare/$$p || exit 1; done

sanitize: deps
	cmake -S . -B $(BUILD)/asan -DCMAKE_BUILD_TYPE=Debug -DSABRE_SANITIZE=ON
	cmake --build $(BUILD)/asan -j $(JOBS)
	ctest --test-dir $(BUILD)/asan --output-on-failure -j $(JOBS) -L unit

# clang-format (Google base, .clang-format) over every tracked C source and header.
SOURCES = $$(git ls-files '*.c' '*.h')
format:
	clang-format -i $(SOURCES)

format-check:
	clang-format --dry-run --Werror $(SOURCES)

clean:
	rm -rf $(BUILD)
