#!/usr/bin/env bash
# The TCP transport against its floor, in one run: arena-server builds (each given as a bin
# folder) and arena-bench-tcp-floor under the Colyseus comparison's load, 200 clients sending
# 60 inputs/s with every body in view (--view-radius 0), server on CPU 1, clients on CPU 0.
#
# Both are measured the same way: over their steady state only, once every client has joined
# (the floor measures from its last accept to its end; a server from SETTLE s after its bots
# start to 1 s before they stop, its CPU read from /proc and its ticks' time from /metrics),
# and with the same snapshot size (the floor sends frames of the first server's mean delta
# snapshot). Prints each server's CPU share of one core, its ratio to the floor's, and how much
# of it the ticks took (world step and snapshot encoding): the rest is what the transport,
# admission and timers cost, the part a transport can compare with the floor. The whole run's
# CPU (joins and shutdown included) is printed beside it.
#   bench/floor_compare.sh BOTS_AND_FLOOR_BIN SERVER_BIN [SERVER_BIN...]
# Env: FLOOR_SECONDS (20), FLOOR_CLIENTS (200), FLOOR_SETTLE (3), FLOOR_ROOM_SIZE (0: one match
# of every client; N: the clients join-or-create matches of N, as make bench-e2e's rooms part
# runs them: the asteroids preset without rocks, sandbox rules, one tick thread), FLOOR_ROUNDS
# (1: the servers and the floor that many times over, alternating, one table a round: one
# round's figures swing by several per cent on a shared machine).
set -euo pipefail
tools=$1; shift
seconds=${FLOOR_SECONDS:-20}
clients=${FLOOR_CLIENTS:-200}
settle=${FLOOR_SETTLE:-3}
room_size=${FLOOR_ROOM_SIZE:-0}
rounds=${FLOOR_ROUNDS:-1}
work=$(mktemp -d /tmp/arena-floor.XXXXXX)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/server_load.sh"
server_mode=(--view-radius 0); bots_mode=()  # one match of every client, every body in view
if [ "$room_size" -gt 0 ]; then
  room_load "$work/modes.json" "$room_size"
  server_mode=("${room_server[@]}"); bots_mode=("${room_bots[@]}")
fi
load_flags "$clients"
pin_to_cpus
ticks_per_s=$(getconf CLK_TCK)

tick_seconds() {  # the server's world-step seconds so far, from its /metrics histogram
  python3 - "$1" <<'PY'
import sys, urllib.request
text = urllib.request.urlopen(f"http://127.0.0.1:{sys.argv[1]}/metrics", timeout=5).read().decode()
print(next(l.split()[1] for l in text.splitlines() if l.startswith("arena_tick_duration_seconds_sum")))
PY
}

# measure_server BIN N: BIN's arena-server under the load (its files $work/sN.*, the bots'
# $work/bN.json); prints "steady ticks whole bytes": CPU s per s over the steady state, the
# ticks' seconds per s within it, the whole run's CPU s per s, and the mean snapshot's bytes.
measure_server() {
  local bin=$1 n=$2 server port http bots cpu0 cpu1 step0 step1 t0 t1
  "${pin_server[@]}" "$bin/arena-server" --port 0 --http-port 0 "${server_load[@]}" "${server_mode[@]}" \
    --stats-json "$work/s$n.json" > "$work/s$n.out" 2> "$work/s$n.log" &
  server=$!
  port=$(port_of "$work/s$n.out" "listening on")
  http=$(port_of "$work/s$n.out" "http listening on")
  "${pin_bots[@]}" "$tools/arena-bots" --port "$port" "${bots_load[@]}" --duration "$seconds" "${bots_mode[@]}" \
    --json "$work/b$n.json" > /dev/null 2>&1 &
  bots=$!
  sleep "$settle"
  cpu0=$(cpu_ticks "$server"); step0=$(tick_seconds "$http"); t0=$(date +%s.%N)
  sleep "$((seconds - settle - 1))"
  cpu1=$(cpu_ticks "$server"); step1=$(tick_seconds "$http"); t1=$(date +%s.%N)
  wait "$bots" || true
  kill -TERM "$server"; wait "$server" || true
  python3 - "$work/s$n.json" "$work/b$n.json" "$cpu0" "$cpu1" "$step0" "$step1" "$t0" "$t1" "$ticks_per_s" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
cpu0, cpu1, step0, step1, t0, t1, hz = map(float, sys.argv[3:])
window = t1 - t0
p = j["process"]
s = j["snapshots"]
# The snapshots' mean size: the default match's own figure, or with many matches (the default
# one then empty) the bots' mean of what they received.
size = s["delta_bytes"] / s["delta_frames"] if s["delta_frames"] else \
    json.load(open(sys.argv[2]))["figures"]["snapshot_bytes"]["mean"]
print((cpu1 - cpu0) / hz / window, (step1 - step0) / window,
      (p["cpu_user_s"] + p["cpu_system_s"]) / j["duration_s"], round(size))
PY
}

floor_cpu() {  # floor_cpu BYTES: the floor's CPU s per s with BYTES-byte snapshots
  taskset -c 0,1 "$tools/arena-bench-tcp-floor" --clients "$clients" --seconds "$((seconds - settle - 1))" \
    --snapshot-bytes "$1" > "$work/floor.json"
  python3 -c 'import json,sys
for line in open(sys.argv[1]):
    line=line.strip()
    if line.startswith("{"): j=json.loads(line)
print(j["server_cpu_s_per_s"])' "$work/floor.json"
}

print_table() {  # print_table FLOOR BYTES ROW...: one round's table (a row: "NAME steady ticks whole bytes")
  local floor=$1 bytes=$2 row name steady ticks whole size
  shift 2
  printf '| server | CPU s per s (steady) | / floor | of which ticks (world step, snapshots) | the rest (transport, admission, timers) | rest / floor | whole run | snapshot B |\n'
  printf '|---|---:|---:|---:|---:|---:|---:|---:|\n| arena-bench-tcp-floor | %.3f | 1.00 | | | | | %s |\n' "$floor" "$bytes"
  for row in "$@"; do
    read -r name steady ticks whole size <<< "$row"
    python3 -c "import sys
n, s, t, w, b, f = sys.argv[1], *map(float, sys.argv[2:])
print(f'| {n} | {s:.3f} | {s/f:.2f} | {t:.3f} | {s-t:.3f} | {(s-t)/f:.2f} | {w:.3f} | {b:.0f} |')" \
      "$name" "$steady" "$ticks" "$whole" "$size" "$floor"
  done
}

snapshot_bytes=""
i=0
for round in $(seq "$rounds"); do
  rows=()
  for bin in "$@"; do
    i=$((i + 1))
    read -r steady ticks whole bytes < <(measure_server "$bin" "$i")
    [ -n "$snapshot_bytes" ] || snapshot_bytes=$bytes
    rows+=("$bin/arena-server $steady $ticks $whole $bytes")
  done
  [ "$rounds" -eq 1 ] || printf '\nRound %s of %s\n\n' "$round" "$rounds"
  print_table "$(floor_cpu "$snapshot_bytes")" "$snapshot_bytes" "${rows[@]}"
done
