# Arena's front door. `make run` and `make test` work on a fresh Debian bookworm machine.
SHELL := /bin/bash
JOBS ?= $(shell nproc)
BUILD ?= build
ASAN_BUILD ?= build-asan
CMAKE_FLAGS ?=
ifdef CI
CMAKE_FLAGS += -DARENA_WERROR=ON
endif
# Rebuilds of unchanged files come from the compiler cache when one is installed.
ifneq ($(shell command -v ccache 2>/dev/null),)
CMAKE_FLAGS += -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
endif

# Debian packages the build and every test need (see ../shared/DEPS.md): nothing in `make test`
# may skip for want of a tool. libboost1.81-dev: Boost.Asio and Beast (only 1.81: it conflicts
# with 1.74); libenet-dev: the UDP transport; g++-aarch64-linux-gnu and qemu-user-static: the
# aarch64 replay check; ccache: rebuilds in CI and in the determinism check; nftables, iproute2
# and python3: the short bench-loss test (tests/e2e/loss_smoke.sh); emscripten (its JavaScript
# needs node-acorn) and nodejs: the browser SDK's WebAssembly core and its tests (web/sdk/);
# chromium: the browser tests of the page.
PACKAGES := build-essential cmake ninja-build pkg-config libboost1.81-dev libflatbuffers-dev \
  flatbuffers-compiler libeigen3-dev catch2 libcli11-dev nlohmann-json3-dev clang-14 \
  libclang-rt-14-dev clang-format-14 libsodium-dev procps prometheus ccache \
  g++-aarch64-linux-gnu qemu-user-static libenet-dev nftables iproute2 python3 \
  emscripten node-acorn nodejs chromium
# npm runs the Dockerfile linters and installs the SDK's TypeScript tools (web/sdk/package-lock.json).
# Debian's nodejs comes without npm, so npm is a package of its own; but where node already
# came from elsewhere with npm inside, installing Debian's npm over it fails (held packages),
# so these are installed only when there is no `npm` command.
NPM_PACKAGES := nodejs npm

.PHONY: all deps build timed-build run test test-fast bench bench-deps bench-e2e bench-loss bench-hits bench-page-hits clean fuzz lint-docker format format-check

all: build

deps:
	@missing=$$(for p in $(PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; done); \
	command -v npm >/dev/null 2>&1 || missing="$$missing $(NPM_PACKAGES)"; \
	missing=$$(echo $$missing); \
	if [ -n "$$missing" ]; then \
	  echo "installing:" $$missing; \
	  sudo=""; [ "$$(id -u)" = 0 ] || sudo=sudo; \
	  $$sudo apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$sudo apt-get install -y -qq --no-install-recommends $$missing; \
	else echo "deps: all present"; fi

$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

run: build
	./scripts/run-demo.sh $(BUILD)/bin

# The two tests that use up every file descriptor of a process on purpose run in the Release
# stage only: UBSan's vptr check probes memory through a pipe, so with no descriptor left it
# reports a false "invalid vptr" and ends the process.
# The sanitizer build is the longest stage of `make test`: -O1 with line tables only (-g1: file
# and line in every report, no variable info) compiles the heaviest unit (Beast's WebSocket
# session) in half the time of -O2 -g (61 s against 125), and ASan's own guidance is -O1.
SANITIZER_OPT := -O1 -g1 -DNDEBUG

SANITIZER_EXCLUDED_TESTS := ^(out of descriptors the accept loop|ops http: out of file descriptors)

# Release tests, then the same tests under AddressSanitizer + UBSan, then the cross-compiler
# determinism check. The Dockerfile is linted first: no Docker engine runs here to build it.
# Each stage prints how long it took (scripts/timed.sh), so a CI log shows where the time goes.
test: timed-build format-check lint-docker
	./scripts/timed.sh "release tests" bash -c 'cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 300'
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$(SANITIZER_OPT)" -DARENA_SANITIZE=ON -DARENA_BUILD_BENCH=OFF -DARENA_BUILD_SDK=OFF $(CMAKE_FLAGS)
	./scripts/timed.sh "sanitizer build" cmake --build $(ASAN_BUILD) -j $(JOBS)
	./scripts/timed.sh "sanitizer tests" bash -c "cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS) --timeout 600 -E '$(SANITIZER_EXCLUDED_TESTS)'"
	./scripts/timed.sh "determinism check" ./scripts/determinism-check.sh $(BUILD)
	./scripts/timed.sh "fuzzing" $(MAKE) fuzz

timed-build: deps $(BUILD)/build.ninja
	./scripts/timed.sh "release build" cmake --build $(BUILD) -j $(JOBS)

# libFuzzer (clang++-14, with ASan and UBSan) on the frame reader and message handling, the
# replay-file reader (its checks, and its cost in world steps), the config loader, the delta
# decoder and the UDP connect gate (what reads a datagram before ENet), each for FUZZ_SECONDS from
# tests/fuzz/corpus/.
# A crash stops the run; its input is saved under build-fuzz/crashes/.
FUZZ_BUILD ?= build-fuzz
FUZZ_TARGETS := fuzz_frames fuzz_config fuzz_replay fuzz_delta fuzz_replay_cost fuzz_udp_gate
FUZZ_SECONDS ?= 15
fuzz: deps
	cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DARENA_FUZZ=ON -DARENA_SANITIZE=ON -DARENA_WITH_NET=OFF -DARENA_BUILD_BENCH=OFF -DARENA_BUILD_SDK=OFF $(CMAKE_FLAGS) >/dev/null
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(FUZZ_TARGETS)
	@set -e; for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ_BUILD)/corpus/$$t $(FUZZ_BUILD)/crashes; \
	  echo "fuzz: $$t for $(FUZZ_SECONDS) s"; \
	  $(FUZZ_BUILD)/bin/$$t -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 -timeout=10 -rss_limit_mb=2048 \
	    -artifact_prefix=$(FUZZ_BUILD)/crashes/$$t- $(FUZZ_BUILD)/corpus/$$t tests/fuzz/corpus/$$t \
	    2> $(FUZZ_BUILD)/$$t.log || { tail -40 $(FUZZ_BUILD)/$$t.log; exit 1; }; \
	  grep -E "stat::number_of_executed_units|stat::new_units_added" $(FUZZ_BUILD)/$$t.log | tr '\n' ' '; echo; \
	done

# Every C++ file in one style (.clang-format); `make test` fails on a file that is not.
FORMAT_FILES = $(shell git ls-files '*.cpp' '*.hpp' '*.h')
format: deps
	clang-format-14 -i $(FORMAT_FILES)
format-check: deps
	@clang-format-14 --dry-run -Werror $(FORMAT_FILES) && echo "format-check: $(words $(FORMAT_FILES)) files formatted"

# Release tests only: the quick loop while developing.
test-fast: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 300

# The two Dockerfile linters from npm (see ../shared/DEPS.md), installed on first use into
# .tools/, which ignores itself. Without npm it fails: `make deps` installs it.
TOOLS ?= .tools
DOCKER_LINTERS := dockerfile-utils@0.16.3 dockerfilelint@1.8.0
lint-docker:
	@if ! command -v npm >/dev/null 2>&1; then echo "lint-docker: npm not found (run 'make deps')" >&2; exit 1; fi; \
	mkdir -p $(TOOLS) && echo '*' > $(TOOLS)/.gitignore; \
	if [ ! -x $(TOOLS)/node_modules/.bin/dockerfile-utils ] || [ ! -x $(TOOLS)/node_modules/.bin/dockerfilelint ]; then \
	  npm install --prefix $(TOOLS) --no-audit --no-fund --silent $(DOCKER_LINTERS) || exit 1; \
	fi; \
	set -e; cd $(TOOLS) && npx --yes dockerfile-utils lint ../Dockerfile && npx --yes dockerfilelint ../Dockerfile

# Box2D 2.4.1, the peer the world step is compared with, is only for the benchmarks (the Colyseus peer needs node and
# npm, which the machine image has; bench/e2e.sh skips it with a note without them).
BENCH_PACKAGES := libbox2d-dev nftables iproute2
bench-deps:
	@$(MAKE) --no-print-directory deps PACKAGES="$(BENCH_PACKAGES)"

bench: build bench-deps
	./bench/run.sh $(BUILD)/bin

# End to end: the server and the bots pinned to one core each, and the Colyseus peer.
bench-e2e: build bench-deps
	./bench/e2e.sh $(BUILD)/bin

# TCP and UDP under packet loss (nftables in a network namespace: root) and added latency.
bench-loss: build bench-deps
	./bench/loss.sh $(BUILD)/bin

# Hit registration over UDP with 0 to 200 ms of round trip, lag compensation on and off (root).
bench-hits: build bench-deps
	./bench/hits.sh $(BUILD)/bin

# A person's view of it: the page in Chromium plays over 100 ms of round trip (root).
bench-page-hits: build bench-deps
	./bench/page_hits.sh $(BUILD)/bin $(BUILD)/web-page/node_modules

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD) build-clang-* build-gcc-* build-aarch64-*
