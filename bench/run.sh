#!/usr/bin/env bash
# `make bench`: runs the benchmarks and prints one markdown table (see README.md).
#
# usage: bench/run.sh [BIN_DIR]   (default: build/bin, a Release build)
# env:   BENCH_QUICK=1       fewer timed steps (a smoke run, not for quoting)
#        BENCH_RUNS=N        runs of the world step and integration cases; the table keeps
#                            each one's best (default 5)
#        BOX2D_REPS=N        interleaved repetitions of the Box2D scene at every size (default:
#                            5 up to 10k bodies, where a run takes seconds, 2 at 100k)
#        BOX2D_NS="1000 ..." sizes of the Box2D scene (default "1000 10000 100000")
#        BOX2D_BUILD=DIR     where Box2D's driver is built (default /tmp/arena-box2d-build)
#        BENCH_JSON=DIR      keep the JSON lines there (default: a temporary folder)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin=${1:-$root/build/bin}
case $bin in /*) ;; *) bin=$PWD/$bin ;; esac
peer=$root/../shared/peers/box2d
box2d_build=${BOX2D_BUILD:-/tmp/arena-box2d-build}
ns=${BOX2D_NS:-"1000 10000 100000"}
if [[ -n ${BENCH_JSON:-} ]]; then
  out=$BENCH_JSON
  mkdir -p "$out"
  rm -f "$out"/arena.jsonl "$out"/box2d.jsonl
else
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi

pin=()
if command -v taskset >/dev/null && [[ $(nproc) -ge 2 ]]; then pin=(taskset -c 1); fi
quick=()
[[ -n ${BENCH_QUICK:-} ]] && quick=(--quick)

notes=()
echo "bench: world, integration, snapshot, replay (pinned to CPU 1)..." >&2
"${pin[@]}" "$bin/arena-bench" "${quick[@]}" --tmp "$out" >"$out/arena.jsonl"
# The step and integration cases again, spread over the run: the table keeps each one's best run
# (see the Box2D scene below for why).
runs=${BENCH_RUNS:-5}
for ((k = 1; k < runs; ++k)); do
  "${pin[@]}" "$bin/arena-bench" "${quick[@]}" --only step,integrate >>"$out/arena.jsonl"
done

# Box2D's pyramid scenes against Box2D 2.4.1, in one process.
if [[ -x $bin/arena-bench-pyramids ]]; then
  echo "bench: pyramids, Arena and Box2D 2.4.1 alternating..." >&2
  "${pin[@]}" "$bin/arena-bench-pyramids" "${quick[@]}" >>"$out/arena.jsonl"
else
  notes+=("Pyramids skipped: $bin/arena-bench-pyramids was not built (apt-get install libbox2d-dev, then reconfigure).")
fi

# Our world on Box2D's scene, interleaved with Box2D 2.4.1 by their run_all.py.
if [[ ! -f $peer/run_all.py || ! -f $peer/bench_scene.hpp ]]; then
  notes+=("Box2D comparison skipped: $peer not found.")
elif [[ ! -x $bin/arena-bench-box2d-scene ]]; then
  notes+=("Box2D comparison skipped: $bin/arena-bench-box2d-scene was not built (bench_scene.hpp missing at configure time?).")
else
  binaries=("$bin/arena-bench-box2d-scene")
  if [[ ! -x $box2d_build/bench_box2d ]]; then
    cmake -S "$peer" -B "$box2d_build" >"$out/box2d-build.log" 2>&1 && cmake --build "$box2d_build" >>"$out/box2d-build.log" 2>&1 || true
  fi
  if [[ -x $box2d_build/bench_box2d ]]; then
    binaries+=("$box2d_build/bench_box2d")
  else
    notes+=("Box2D 2.4.1 not built (apt-get install libbox2d-dev): Arena's rows on its scene only.")
  fi
  extra=()
  [[ -n ${BENCH_QUICK:-} ]] && extra=(--steps 60)
  # This machine switches between a fast and a slow state for seconds at a time (the same
  # binary gave 0.054 and 0.095 ms a step at 1k in back-to-back runs): more repetitions where
  # they are cheap, so that the best of them is a run in the fast state for both engines.
  for n in $ns; do
    reps=${BOX2D_REPS:-$([[ $n -le 10000 ]] && echo 5 || echo 2)}
    echo "bench: Box2D scene, N = $n, $reps reps, interleaved: ${binaries[*]##*/}..." >&2
    python3 "$peer/run_all.py" "${binaries[@]}" --label arena-bench --ns "$n" --reps "$reps" "${extra[@]}" \
      --quiet-timeout "${BOX2D_QUIET_TIMEOUT:-10}" --out "$out/box2d.jsonl" >/dev/null
  done
fi

cpu=$(grep -m1 '^model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
echo
echo "$(date -u '+%Y-%m-%d %H:%M UTC'), nproc = $(nproc), $cpu, load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
note_args=()
for n in "${notes[@]}"; do note_args+=(--note "$n"); done
python3 "$root/bench/table.py" "$out/arena.jsonl" "$out/box2d.jsonl" "${note_args[@]}"
