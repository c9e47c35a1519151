#!/usr/bin/env bash
# make bench-loss: Arena under packet loss and added latency, TCP and UDP side by side. Each run
# gets two network namespaces of its own (ip netns, as root), the server's and the bots',
# joined by a point-to-point link (bench/link_delay.cpp, arena-link-delay) that holds every
# packet LATENCY ms each way in the kernel's packet path, so TCP's and ENet's retransmission
# timers see the longer round trip as they would on a real path (netem does not exist on these
# kernels, and a delay inside the bots would hide it from TCP). Each namespace drops a random
# share of the packets leaving it (nftables: `numgen random mod 1000 < N drop`); every packet
# leaves one of them once. One table.
# Env: LOSS_PERCENT ("0 1 2 5 10"), LOSS_LATENCY_MS ("0 50 100"), LOSS_SECONDS (8),
#      LOSS_BOTS (16), LOSS_TRANSPORTS ("tcp udp1 udp udp2"; udp is UDP as the server runs it
#      by default, --udp-snapshot-copies auto: a second copy of each snapshot, a tick later, per
#      client while its loss is above 1 %; udp1 is one copy, --udp-snapshot-copies 1; udp2 two;
#      udpauto names auto explicitly), LOSS_WORK (a folder that keeps each run's
#      bots' --json LABEL.json and server's --stats-json LABEL.stats.json, LABEL being
#      TRANSPORT-LOSS-LATENCY; default: a temporary one, removed), LOSS_NICE (-10: the nice
#      value of the link, the server and the bots).
set -euo pipefail
bin=${1:-build/bin}
here=$(cd "$(dirname "$0")" && pwd)
losses=${LOSS_PERCENT:-0 1 2 5 10}
latencies=${LOSS_LATENCY_MS:-0 50 100}
seconds=${LOSS_SECONDS:-8}
bots=${LOSS_BOTS:-16}
transports=${LOSS_TRANSPORTS:-tcp udp1 udp udp2}
[ "$(id -u)" = 0 ] || { echo "bench-loss: needs root (ip netns, nft)" >&2; exit 1; }
command -v nft >/dev/null || { echo "bench-loss: needs nft (apt-get install nftables)" >&2; exit 1; }
link_name=loss
env_prefix=LOSS
link_net=10.77.0
. "$here/netns_link.sh"
. "$here/server_load.sh"

# drop_share NAMESPACE: drops `permille` of the packets arriving in NAMESPACE (nftables).
drop_share() {
  ip netns exec "$1" nft add table inet arena_loss
  ip netns exec "$1" nft "add chain inet arena_loss in { type filter hook input priority 0; }"
  if [ "$permille" -gt 0 ]; then
    ip netns exec "$1" nft "add rule inet arena_loss in numgen random mod 1000 < $permille counter drop"
  fi
}

# run TRANSPORT LOSS_PERMILLE LATENCY_MS LABEL: one server and its bots, each in its namespace.
run() {
  local transport=$1 permille=$2 latency=$3 label=$4 ns
  local -a copies=()
  if [ "$transport" = udp1 ]; then transport=udp; copies=(--udp-snapshot-copies 1); fi
  if [ "$transport" = udp2 ]; then transport=udp; copies=(--udp-snapshot-copies 2); fi
  if [ "$transport" = udpauto ]; then transport=udp; copies=(--udp-snapshot-copies auto); fi
  link_connect "$label" drop_share --delay-ms "$latency"
  : > "$work/$label.out"  # before the server starts: the background job opens it later
  ip netns exec "$server_ns" nice -n "$priority" "$bin/arena-server" --bind "$server_address" --port 0 --udp-port 0 \
    --max-players "$bots" --duration $((seconds + 30)) --rules sandbox "${copies[@]}" --stats-json "$work/$label.stats.json" \
    > "$work/$label.out" 2> "$work/$label.log" &
  local server=$! port
  local prefix="listening on"; [ "$transport" = udp ] && prefix="udp listening on"
  port=$(port_of "$work/$label.out" "$prefix")
  [ -n "$port" ] || { echo "arena-server did not start" >&2; cat "$work/$label.log" >&2; return 1; }
  ip netns exec "$bots_ns" nice -n "$priority" "$bin/arena-bots" --transport "$transport" --host "$server_address" --port "$port" \
    --bots "$bots" --duration "$seconds" --connect-rate 100 --seed 1 --quiet --json "$work/$label.json" \
    > "$work/$label.bots.out" 2>&1 || true
  kill -TERM "$server" 2>/dev/null || true
  wait "$server" || true
  for ns in "$server_ns" "$bots_ns"; do ip netns exec "$ns" nft list chain inet arena_loss in; done > "$work/$label.nft"
  drop_namespaces
}

labels=()
for latency in $latencies; do
  for loss in $losses; do
    permille=$(awk -v p="$loss" 'BEGIN { printf "%d", p * 10 }')
    for transport in $transports; do
      label="$transport-$loss-$latency"
      run "$transport" "$permille" "$latency" "$label"
      labels+=("$label")
    done
  done
done
python3 "$here/loss_table.py" "$work" "$seconds" "$bots" "${labels[@]}"
