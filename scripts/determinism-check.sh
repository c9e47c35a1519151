#!/usr/bin/env bash
# Cross-compiler determinism check (issue 5, ../shared/DETERMINISM.md rule 8): the golden
# recording must replay to the same hash at every tick from a clang++ and a g++ build, at -O0,
# -O2 and -O3. Builds only arena-replay (world, config, protocol; no Asio, which clang++ 14
# cannot build) in three extra build directories, then compares the --dump-hashes outputs
# byte for byte with the Release g++ build's.
#
# usage: scripts/determinism-check.sh [RELEASE_BUILD_DIR]   (default: build)
# Exit 0 when every build agrees; 1 when one differs or fails to build.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
release=${1:-build}
case $release in /*) ;; *) release=$root/$release ;; esac
golden=$root/tests/data/golden_asteroids.arpl
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# name  compiler  CMake build type  extra flags. Debug is -O0 -g (no sanitizers); CMake's Release
# is -O3, so the clang Release build is pinned to -O2 and the main g++ build covers -O3.
builds=(
  "clang-O0 clang++-14 Debug"
  "clang-O2 clang++-14 Release -DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG"
  "gcc-O0 g++ Debug"
)

failed=0

# Builds arena-replay in DIR; the log is printed only when something fails.
build_replay() {
  local dir=$1 compiler=$2 type=$3
  shift 3
  local log=$out/$(basename "$dir").log
  if [[ ! -f $dir/build.ninja ]]; then
    if ! cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_BUILD_TYPE="$type" \
        -DARENA_WITH_NET=OFF -DARENA_BUILD_BENCH=OFF -DARENA_BUILD_TESTS=OFF "$@" >"$log" 2>&1; then
      cat "$log" >&2
      return 1
    fi
  fi
  if ! cmake --build "$dir" --target arena-replay >>"$log" 2>&1; then
    tail -n 40 "$log" >&2
    return 1
  fi
}

# Replays the golden file with BINARY into NAME.csv.
dump() {
  local name=$1 binary=$2
  if ! "$binary" --dump-hashes "$golden" >"$out/$name.csv" 2>"$out/$name.err"; then
    echo "determinism-check: $name: arena-replay failed: $(tail -n 1 "$out/$name.err")" >&2
    return 1
  fi
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
  echo "determinism-check: FAIL gcc-O3 ($release): could not build or replay" >&2
  exit 1
fi
ticks=$(($(wc -l <"$out/gcc-O3.csv") - 2))
echo "determinism-check: gcc-O3   reference ($release): $ticks ticks, final $(tail -n 1 "$out/gcc-O3.csv")"

for spec in "${builds[@]}"; do
  read -r name compiler type extra <<<"$spec"
  dir=$root/build-$name
  flags=()
  [[ -n ${extra:-} ]] && flags=("$extra")
  if ! build_replay "$dir" "$compiler" "$type" "${flags[@]}" || ! dump "$name" "$dir/bin/arena-replay"; then
    echo "determinism-check: FAIL $name ($compiler $type): could not build or replay"
    failed=1
    continue
  fi
  if cmp -s "$out/gcc-O3.csv" "$out/$name.csv"; then
    echo "determinism-check: ok   $name ($compiler $type): all $((ticks + 1)) hashes identical"
  else
    first=$(diff "$out/gcc-O3.csv" "$out/$name.csv" | grep -m1 '^>' | cut -c3- || true)
    echo "determinism-check: FAIL $name ($compiler $type): first differing tick,hash: $first"
    failed=1
  fi
done

if ((failed)); then
  echo "determinism-check: FAILED: the builds disagree (see ../shared/DETERMINISM.md)"
  exit 1
fi
echo "determinism-check: passed: g++ and clang++ at -O0, -O2 and -O3 replay the golden file identically"
