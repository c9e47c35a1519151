#!/usr/bin/env bash
# Two arena-server builds under the same load at the same time: the way to tell whether a change
# saves CPU on a shared machine whose speed drifts by 20 % within minutes (bench/README.md, "The
# machine's slow state"), where runs one after the other cannot tell a 5 % change from the drift.
#
# Both servers run at once on CPU 1, each with its own arena-bots on CPU 0 (the many-matches
# load: CLIENTS clients joining matches of ROOM_SIZE, every body in view, one tick thread), so
# whatever the machine does in the window it does to both. Each server's CPU is read from
# /proc/PID/task/*/schedstat (nanoseconds on a CPU, exact, where /proc/PID/stat counts clock
# ticks) over the same window. A round runs the pair twice, A started first and then B, so that
# whatever favours one start order cancels; the figure is B's CPU over A's, the geometric mean
# of the round's two runs. The same binary as A and B gave 0.92 to 1.02 a round
# (bench/README.md, "Two builds at once"): trust a change only when several rounds agree.
#   bench/pair_compare.sh BOTS_BIN SERVER_BIN_A SERVER_BIN_B   (folders: arena-bots', each arena-server)
# Env: PAIR_SECONDS (30 per run), PAIR_ROUNDS (2), PAIR_CLIENTS (400 per server),
# PAIR_ROOM_SIZE (8), PAIR_SETTLE (4: s after the bots start before the window opens).
set -euo pipefail
tools=$1; a=$2; b=$3
seconds=${PAIR_SECONDS:-30}
rounds=${PAIR_ROUNDS:-2}
clients=${PAIR_CLIENTS:-400}
room_size=${PAIR_ROOM_SIZE:-8}
settle=${PAIR_SETTLE:-4}
work=$(mktemp -d /tmp/arena-pair.XXXXXX)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
. "$(dirname "$0")/server_load.sh"
room_load "$work/modes.json" "$room_size"
load_flags "$clients"
pin_to_cpus

started=""  # the pid of what start_server or start_bots started last (a child of this shell)

start_server() {  # start_server BIN TAG
  "${pin_server[@]}" "$1/arena-server" --port 0 "${server_load[@]}" "${room_server[@]}" > "$work/$2.out" \
    2> "$work/$2.log" &
  started=$!
}

start_bots() {  # start_bots TAG: the clients of the server TAG
  local port
  port=$(port_of "$work/$1.out" "listening on")
  [ -n "$port" ] || { echo "pair_compare.sh: server $1 printed no port: $(tail -1 "$work/$1.log")" >&2; exit 1; }
  "${pin_bots[@]}" "$tools/arena-bots" --port "$port" "${bots_load[@]}" --duration "$seconds" "${room_bots[@]}" \
    > "$work/$1.bots" 2>&1 &
  started=$!
}

# run_pair FIRST_BIN SECOND_BIN: "first second", each one's CPU s per s over the same window.
run_pair() {
  local p1 p2 b1 b2 c10 c20 c11 c21 t0 t1
  start_server "$1" first; p1=$started
  start_server "$2" second; p2=$started
  start_bots first; b1=$started
  start_bots second; b2=$started
  sleep "$settle"
  c10=$(cpu_ns "$p1"); c20=$(cpu_ns "$p2"); t0=$(date +%s%N)
  sleep "$((seconds - settle - 2))"
  c11=$(cpu_ns "$p1"); c21=$(cpu_ns "$p2"); t1=$(date +%s%N)
  wait "$b1" "$b2" || true
  kill -TERM "$p1" "$p2"; wait "$p1" "$p2" || true
  python3 -c "import sys; c10, c11, c20, c21, w = map(int, sys.argv[1:]); print((c11 - c10) / w, (c21 - c20) / w)" \
    "$c10" "$c11" "$c20" "$c21" "$((t1 - t0))"
}

printf '| round | A first: A, B (CPU s per s) | B first: B, A | B / A |\n|---|---|---|---:|\n'
ratios=()
for round in $(seq "$rounds"); do
  run_pair "$a" "$b" > "$work/pair"; read -r a1 b1 < "$work/pair"
  run_pair "$b" "$a" > "$work/pair"; read -r b2 a2 < "$work/pair"
  ratio=$(python3 -c "import sys, math; a1, b1, b2, a2 = map(float, sys.argv[1:]); print(f'{math.sqrt(b1 / a1 * b2 / a2):.3f}')" \
    "$a1" "$b1" "$b2" "$a2")
  ratios+=("$ratio")
  printf '| %s | %.4f, %.4f | %.4f, %.4f | %s |\n' "$round" "$a1" "$b1" "$b2" "$a2" "$ratio"
done
echo "B / A over $rounds rounds: ${ratios[*]} (A: $a, B: $b)"
