#!/usr/bin/env bash
# The TCP transport against its floor, in one run: arena-server builds (each given as a bin
# folder) and arena-bench-tcp-floor under the Colyseus comparison's load, 200 clients sending
# 60 inputs/s with every body in view (--view-radius 0), server on CPU 1, clients on CPU 0.
# Prints each server's CPU share of one core, its ratio to the floor's, and how much of it the
# ticks took (world step and snapshot encoding, from --stats-json's tick_ms mean): the rest is
# what the transport, admission and timers cost, the part a transport can compare with the floor.
#   bench/floor_compare.sh BOTS_AND_FLOOR_BIN SERVER_BIN [SERVER_BIN...]
# Env: FLOOR_SECONDS (20), FLOOR_CLIENTS (200).
set -euo pipefail
tools=$1; shift
seconds=${FLOOR_SECONDS:-20}
clients=${FLOOR_CLIENTS:-200}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/arena-floor.XXXXXX)
trap 'rm -rf "$work"' EXIT
pin_server=(); pin_bots=()
if command -v taskset >/dev/null && [ "$(nproc)" -ge 2 ]; then pin_server=(taskset -c 1); pin_bots=(taskset -c 0); fi

cpu_of() {  # the server's CPU seconds per second, and the ticks' share of it, from its --stats-json
  python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); p=j["process"]; d=j["duration_s"]
print((p["cpu_user_s"]+p["cpu_system_s"])/d, j["tick_ms"]["mean"]*j["ticks"]/1000/d)' "$1"
}

taskset -c 0,1 "$tools/arena-bench-tcp-floor" --clients "$clients" --seconds "$seconds" > "$work/floor.json"
floor=$(python3 -c 'import json,sys
for line in open(sys.argv[1]):
    line=line.strip()
    if line.startswith("{"): j=json.loads(line)
print(j["server_cpu_s_per_s"])' "$work/floor.json")
printf '| server | CPU s per s | / floor | of which ticks (world step, snapshots) | the rest (transport, admission, timers) | rest / floor |\n'
printf '|---|---:|---:|---:|---:|---:|\n| arena-bench-tcp-floor | %.3f | 1.00 | | | |\n' "$floor"
i=0
for bin in "$@"; do
  i=$((i + 1))
  "${pin_server[@]}" "$bin/arena-server" --port 0 --max-players "$clients" --max-connections $((2 * clients + 16)) \
    --max-pending-handshakes "$clients" --view-radius 0 --stats-json "$work/s$i.json" > "$work/s$i.out" 2> "$work/s$i.log" &
  server=$!
  port=""
  for _ in $(seq 100); do
    port=$(sed -n 's/^listening on .*:\([0-9]*\)$/\1/p' "$work/s$i.out"); [ -n "$port" ] && break; sleep 0.1
  done
  "${pin_bots[@]}" "$tools/arena-bots" --port "$port" --bots "$clients" --duration "$seconds" --connect-rate 500 \
    --behavior mixed --seed 1 --quiet --json "$work/b$i.json" > /dev/null 2>&1 || true
  kill -TERM "$server"; wait "$server" || true
  read -r cpu ticks < <(cpu_of "$work/s$i.json")
  printf '| %s | %.3f | %.2f | %.3f | %.3f | %.2f |\n' "$bin/arena-server" "$cpu" "$(python3 -c "print($cpu/$floor)")" \
    "$ticks" "$(python3 -c "print($cpu-$ticks)")" "$(python3 -c "print(($cpu-$ticks)/$floor)")"
done
