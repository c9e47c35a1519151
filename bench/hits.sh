#!/usr/bin/env bash
# make bench-hits: hit registration (client_sim/hit_registration.hpp) over UDP with added latency,
# lag compensation on and off. Asteroids, hunter bots; each run gets two network namespaces
# joined by arena-link-delay (as make bench-loss: bench/loss.sh), holding every packet half the
# round trip each way, ± HITS_JITTER_MS / 2 (uniform, order kept; none at round trip 0). One
# table: claimed hits the server confirmed (%), server hits the shooter never claimed (% of
# server hits).
# Env: HITS_RTT_MS ("0 50 100 200"), HITS_JITTER_MS (10, on the round trip), HITS_COMPENSATION_MS
#      ("250 0": --lag-compensation-ms), HITS_SECONDS (20), HITS_BOTS (16), HITS_WORK (a folder
#      that keeps each run's bots' --json LABEL.json; default: a temporary one, removed),
#      HITS_NICE (-10).
set -euo pipefail
bin=${1:-build/bin}
here=$(cd "$(dirname "$0")" && pwd)
rtts=${HITS_RTT_MS:-0 50 100 200}
jitter=${HITS_JITTER_MS:-10}
compensations=${HITS_COMPENSATION_MS:-250 0}
seconds=${HITS_SECONDS:-20}
bots=${HITS_BOTS:-16}
[ "$(id -u)" = 0 ] || { echo "bench-hits: needs root (ip netns)" >&2; exit 1; }
link_name=hits
env_prefix=HITS
link_net=10.78.0
. "$here/netns_link.sh"
. "$here/server_load.sh"

# run RTT_MS COMPENSATION_MS LABEL: one Asteroids server and its hunters, each in its namespace.
run() {
  local rtt=$1 compensation=$2 label=$3
  local spread
  spread=$(awk -v r="$rtt" -v j="$jitter" 'BEGIN { print (r > 0 ? j / 2 : 0) }')
  link_connect "$label" "" --delay-ms "$(awk -v r="$rtt" 'BEGIN { print r / 2 }')" --jitter-ms "$spread"
  : > "$work/$label.out"  # before the server starts: the background job opens it later
  ip netns exec "$server_ns" nice -n "$priority" "$bin/arena-server" --bind "$server_address" --port 0 --udp-port 0 \
    --max-players "$bots" --duration $((seconds + 30)) --preset asteroids --lag-compensation-ms "$compensation" \
    > "$work/$label.out" 2> "$work/$label.log" &
  local server=$! port
  port=$(port_of "$work/$label.out" "udp listening on")
  [ -n "$port" ] || { echo "arena-server did not start" >&2; cat "$work/$label.log" >&2; return 1; }
  ip netns exec "$bots_ns" nice -n "$priority" "$bin/arena-bots" --transport udp --host "$server_address" --port "$port" \
    --bots "$bots" --behavior hunter --duration "$seconds" --connect-rate 100 --seed 1 --quiet --json "$work/$label.json" \
    > "$work/$label.bots.out" 2>&1 || true
  kill -TERM "$server" 2>/dev/null || true
  wait "$server" || true
  drop_namespaces
}

labels=()
for rtt in $rtts; do
  for compensation in $compensations; do
    label="$rtt-$compensation"
    run "$rtt" "$compensation" "$label"
    labels+=("$label")
  done
done
python3 "$here/hits_table.py" "$work" "$jitter" "${labels[@]}"
