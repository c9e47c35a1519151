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
# Env: FLOOR_SECONDS (20), FLOOR_CLIENTS (200), FLOOR_SETTLE (3).
set -euo pipefail
tools=$1; shift
seconds=${FLOOR_SECONDS:-20}
clients=${FLOOR_CLIENTS:-200}
settle=${FLOOR_SETTLE:-3}
work=$(mktemp -d /tmp/arena-floor.XXXXXX)
trap 'rm -rf "$work"' EXIT
pin_server=(); pin_bots=()
if command -v taskset >/dev/null && [ "$(nproc)" -ge 2 ]; then pin_server=(taskset -c 1); pin_bots=(taskset -c 0); fi
ticks_per_s=$(getconf CLK_TCK)

cpu_ticks() {  # utime + stime of a process, in clock ticks
  awk '{ print $14 + $15 }' "/proc/$1/stat"
}
tick_seconds() {  # the server's world-step seconds so far, from its /metrics histogram
  python3 - "$1" <<'PY'
import sys, urllib.request
text = urllib.request.urlopen(f"http://127.0.0.1:{sys.argv[1]}/metrics", timeout=5).read().decode()
print(next(l.split()[1] for l in text.splitlines() if l.startswith("arena_tick_duration_seconds_sum")))
PY
}
port_of() {  # PORT of the line "PREFIX HOST:PORT" in FILE, waiting up to 10 s
  local p=""
  for _ in $(seq 100); do
    p=$(sed -n "s/^$2 .*:\([0-9]*\)\$/\1/p" "$1"); [ -n "$p" ] && break; sleep 0.1
  done
  echo "$p"
}

rows=()
snapshot_bytes=""
i=0
for bin in "$@"; do
  i=$((i + 1))
  "${pin_server[@]}" "$bin/arena-server" --port 0 --http-port 0 --max-players "$clients" \
    --max-connections $((2 * clients + 16)) --max-pending-handshakes "$clients" --view-radius 0 --rules sandbox \
    --stats-json "$work/s$i.json" > "$work/s$i.out" 2> "$work/s$i.log" &
  server=$!
  port=$(port_of "$work/s$i.out" "listening on")
  http=$(port_of "$work/s$i.out" "http listening on")
  "${pin_bots[@]}" "$tools/arena-bots" --port "$port" --bots "$clients" --duration "$seconds" --connect-rate 500 \
    --behavior mixed --seed 1 --quiet --json "$work/b$i.json" > /dev/null 2>&1 &
  bots=$!
  sleep "$settle"
  cpu0=$(cpu_ticks "$server"); step0=$(tick_seconds "$http"); t0=$(date +%s.%N)
  sleep "$((seconds - settle - 1))"
  cpu1=$(cpu_ticks "$server"); step1=$(tick_seconds "$http"); t1=$(date +%s.%N)
  wait "$bots" || true
  kill -TERM "$server"; wait "$server" || true
  read -r steady ticks whole bytes < <(python3 - "$work/s$i.json" "$cpu0" "$cpu1" "$step0" "$step1" "$t0" "$t1" "$ticks_per_s" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
cpu0, cpu1, step0, step1, t0, t1, hz = map(float, sys.argv[2:])
window = t1 - t0
p = j["process"]
s = j["snapshots"]
print((cpu1 - cpu0) / hz / window, (step1 - step0) / window,
      (p["cpu_user_s"] + p["cpu_system_s"]) / j["duration_s"],
      round(s["delta_bytes"] / max(1, s["delta_frames"])))
PY
)
  [ -n "$snapshot_bytes" ] || snapshot_bytes=$bytes
  rows+=("$bin/arena-server $steady $ticks $whole $bytes")
done

taskset -c 0,1 "$tools/arena-bench-tcp-floor" --clients "$clients" --seconds "$((seconds - settle - 1))" \
  --snapshot-bytes "$snapshot_bytes" > "$work/floor.json"
floor=$(python3 -c 'import json,sys
for line in open(sys.argv[1]):
    line=line.strip()
    if line.startswith("{"): j=json.loads(line)
print(j["server_cpu_s_per_s"])' "$work/floor.json")

printf '| server | CPU s per s (steady) | / floor | of which ticks (world step, snapshots) | the rest (transport, admission, timers) | rest / floor | whole run | snapshot B |\n'
printf '|---|---:|---:|---:|---:|---:|---:|---:|\n| arena-bench-tcp-floor | %.3f | 1.00 | | | | | %s |\n' "$floor" "$snapshot_bytes"
for row in "${rows[@]}"; do
  read -r name steady ticks whole bytes <<< "$row"
  python3 -c "import sys
n, s, t, w, b, f = sys.argv[1], *map(float, sys.argv[2:])
print(f'| {n} | {s:.3f} | {s/f:.2f} | {t:.3f} | {s-t:.3f} | {(s-t)/f:.2f} | {w:.3f} | {b:.0f} |')" \
    "$name" "$steady" "$ticks" "$whole" "$bytes" "$floor"
done
