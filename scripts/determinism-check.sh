#!/usr/bin/env bash
# Cross-compiler and cross-architecture determinism check (docs/DETERMINISM.md): the golden
# recordings (a scripted sandbox session, a live Asteroids match under the game's rules, and
# the scripted session in the sub-stepped pyramid preset)
# must replay to the same hash at every tick from clang++ and g++ builds at -O0,
# -O2 and -O3, and from aarch64 builds (Debian's g++-aarch64-linux-gnu, static, run under
# qemu-aarch64-static) at -O0, -O2 and -O3. Builds only arena-replay and its libraries (world,
# config, protocol; no Asio, which clang++ 14 cannot build) in extra build directories, then
# compares each --dump-hashes output byte for byte with the Release g++ build's.
#
# usage: scripts/determinism-check.sh [RELEASE_BUILD_DIR]   (default: build)
# Exit 0 when every build agrees; 1 when one differs, fails to build, or a tool is missing.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
release=${1:-build}
case $release in /*) ;; *) release=$root/$release ;; esac
goldens=("$root/tests/data/golden_asteroids.arpl" "$root/tests/data/golden_asteroids_rules.arpl"
  "$root/tests/data/golden_pyramid.arpl")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# name  compiler  CMake build type  extra flags. Debug is -O0 -g (no sanitizers); CMake's Release
# is -O3, so the Release builds that test -O2 pin it, and the main g++ build covers native -O3.
# The compiler "aarch64" means the cross toolchain file, and running the result under qemu.
builds=(
  "clang-O0 clang++-14 Debug"
  "clang-O2 clang++-14 Release -DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG"
  "gcc-O0 g++ Debug"
  "aarch64-O0 aarch64 Debug"
  "aarch64-O2 aarch64 Release -DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG"
  "aarch64-O3 aarch64 Release"
)
toolchain=$root/cmake/aarch64-linux-gnu.cmake
qemu=qemu-aarch64-static

# Every tool must be there: a check that cannot run fails rather than passing quietly.
for tool in clang++-14 g++ aarch64-linux-gnu-g++ $qemu; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "determinism-check: FAIL: $tool not found (run 'make deps')" >&2
    exit 1
  fi
done

# Rebuilds of unchanged sources come from the compiler cache when one is installed.
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

failed=0

# Configures and builds arena-replay in DIR; the log is printed only when something fails.
build_replay() {
  local dir=$1 compiler=$2 type=$3
  shift 3
  local log=$out/$(basename "$dir").log
  local target=(-DCMAKE_CXX_COMPILER="$compiler")
  [[ $compiler == aarch64 ]] && target=(-DCMAKE_TOOLCHAIN_FILE="$toolchain")
  if ! cmake -S "$root" -B "$dir" -G Ninja "${target[@]}" -DCMAKE_BUILD_TYPE="$type" "${launcher[@]}" \
      -DARENA_WITH_NET=OFF -DARENA_BUILD_BENCH=OFF -DARENA_BUILD_TESTS=OFF -DARENA_BUILD_SDK=OFF "$@" >"$log" 2>&1; then
    cat "$log" >&2
    return 1
  fi
  if ! cmake --build "$dir" --target arena-replay >>"$log" 2>&1; then
    tail -n 40 "$log" >&2
    return 1
  fi
}

# Replays the golden files with BINARY (under RUNNER, if any) into NAME.csv. arena-replay stops
# at the first hash that differs from the recorded one; its last line says which.
# Every golden file's hashes go into the one NAME.csv, each after a line naming its file.
dump() {
  local name=$1 binary=$2 runner=${3:-}
  : >"$out/$name.csv"
  for golden in "${goldens[@]}"; do
    echo "# $(basename "$golden")" >>"$out/$name.csv"
    if ! $runner "$binary" --dump-hashes "$golden" >>"$out/$name.csv" 2>"$out/$name.err"; then
      echo "determinism-check: FAIL $name: arena-replay $(basename "$golden"): $(tail -n 1 "$out/$name.err")"
      return 1
    fi
  done
}

# The reference: the Release g++ build (-O3) that `make build` made; never configured here, so
# that this script cannot leave a stripped-down (ARENA_WITH_NET=OFF) main build behind.
if [[ ! -f $release/build.ninja ]]; then
  echo "determinism-check: $release is not configured: run 'make build' first" >&2
  exit 1
fi
if ! cmake --build "$release" --target arena-replay >"$out/reference.log" 2>&1; then
  tail -n 40 "$out/reference.log" >&2
  echo "determinism-check: FAIL gcc-O3 ($release): arena-replay does not build" >&2
  exit 1
fi
if ! dump gcc-O3 "$release/bin/arena-replay"; then
  exit 1
fi
hashes=$(grep -vc '^[#t]' "$out/gcc-O3.csv")
echo "determinism-check: gcc-O3   reference ($release): ${#goldens[@]} recordings, $hashes tick hashes, final $(tail -n 1 "$out/gcc-O3.csv")"

for spec in "${builds[@]}"; do
  read -r name compiler type extra <<<"$spec"
  dir=$root/build-$name
  flags=()
  [[ -n ${extra:-} ]] && flags=("$extra")
  runner=
  [[ $compiler == aarch64 ]] && runner=$qemu
  if ! build_replay "$dir" "$compiler" "$type" "${flags[@]}"; then
    echo "determinism-check: FAIL $name ($compiler $type): arena-replay does not build"
    failed=1
    continue
  fi
  if ! dump "$name" "$dir/bin/arena-replay" $runner; then
    failed=1
    continue
  fi
  if cmp -s "$out/gcc-O3.csv" "$out/$name.csv"; then
    echo "determinism-check: ok   $name ($compiler $type): all $hashes hashes identical"
  else
    first=$(diff "$out/gcc-O3.csv" "$out/$name.csv" | grep -m1 '^>' | cut -c3- || true)
    echo "determinism-check: FAIL $name ($compiler $type): first differing tick,hash: $first"
    failed=1
  fi
done

if ((failed)); then
  echo "determinism-check: FAILED: the builds disagree (see docs/DETERMINISM.md)"
  exit 1
fi
echo "determinism-check: passed: g++ and clang++ at -O0, -O2 and -O3, and aarch64 at -O0, -O2 and -O3," \
  "replay the golden files identically"
