#!/usr/bin/env bash
# make bench-loss: Arena under packet loss, TCP and UDP side by side. Each run gets a network
# namespace of its own (ip netns, as root) whose loopback drops a random share of the packets
# leaving it (nftables: `numgen random mod 1000 < N drop`; netem does not exist on these
# kernels). Latency is added on the bots' side (arena-bots --simulate-latency, UDP only: a TCP
# socket cannot be delayed from user space without reordering its bytes). One table.
# Env: LOSS_PERCENT ("0 1 2 5 10"), LOSS_LATENCY_MS ("0 50 100"), LOSS_SECONDS (8),
#      LOSS_BOTS (16), LOSS_TRANSPORTS ("tcp udp udp2"; udp2 is UDP with each snapshot sent
#      twice, a tick apart: --udp-snapshot-copies 2), LOSS_WORK (a folder that keeps each run's
#      bots' --json LABEL.json and server's --stats-json LABEL.stats.json, LABEL being
#      TRANSPORT-LOSS-LATENCY; default: a temporary one, removed).
set -euo pipefail
bin=${1:-build/bin}
here=$(cd "$(dirname "$0")" && pwd)
losses=${LOSS_PERCENT:-0 1 2 5 10}
latencies=${LOSS_LATENCY_MS:-0 50 100}
seconds=${LOSS_SECONDS:-8}
bots=${LOSS_BOTS:-16}
transports=${LOSS_TRANSPORTS:-tcp udp udp2}
[ "$(id -u)" = 0 ] || { echo "bench-loss: needs root (ip netns, nft)" >&2; exit 1; }
command -v nft >/dev/null || { echo "bench-loss: needs nft (apt-get install nftables)" >&2; exit 1; }
keep=${LOSS_WORK:-}
if [ -n "$keep" ]; then mkdir -p "$keep"; work=$keep; else work=$(mktemp -d /tmp/arena-bench-loss.XXXXXX); fi
ns=arena-loss-$$
cleanup() { ip netns del "$ns" 2>/dev/null || true; [ -n "$keep" ] || rm -rf "$work"; }
trap cleanup EXIT

# run TRANSPORT LOSS_PERMILLE LATENCY_MS LABEL: one server and its bots in a fresh namespace.
run() {
  local transport=$1 permille=$2 latency=$3 label=$4
  local -a copies=()
  if [ "$transport" = udp2 ]; then transport=udp; copies=(--udp-snapshot-copies 2); fi
  ip netns del "$ns" 2>/dev/null || true
  ip netns add "$ns"
  ip netns exec "$ns" ip link set lo up
  ip netns exec "$ns" nft add table inet arena_loss
  ip netns exec "$ns" nft "add chain inet arena_loss out { type filter hook output priority 0; }"
  if [ "$permille" -gt 0 ]; then
    ip netns exec "$ns" nft "add rule inet arena_loss out numgen random mod 1000 < $permille drop"
  fi
  : > "$work/$label.out"  # before the server starts: the background job opens it later
  ip netns exec "$ns" "$bin/arena-server" --port 0 --udp-port 0 --max-players "$bots" --duration $((seconds + 30)) \
    "${copies[@]}" --stats-json "$work/$label.stats.json" > "$work/$label.out" 2> "$work/$label.log" &
  local server=$! port=""
  local prefix="listening on"; [ "$transport" = udp ] && prefix="udp listening on"
  for _ in $(seq 100); do
    port=$(sed -n "s/^$prefix .*:\([0-9]*\)\$/\1/p" "$work/$label.out" || true); [ -n "$port" ] && break; sleep 0.1
  done
  [ -n "$port" ] || { echo "arena-server did not start" >&2; cat "$work/$label.log" >&2; return 1; }
  local -a delay=()
  [ "$latency" -gt 0 ] && delay=(--simulate-latency "$latency")
  ip netns exec "$ns" "$bin/arena-bots" --transport "$transport" --port "$port" --bots "$bots" \
    --duration "$seconds" --connect-rate 100 --seed 1 --quiet "${delay[@]}" --json "$work/$label.json" \
    > "$work/$label.bots.out" 2>&1 || true
  kill -TERM "$server" 2>/dev/null || true
  wait "$server" || true
  ip netns del "$ns"
}

labels=()
for latency in $latencies; do
  for loss in $losses; do
    permille=$(awk -v p="$loss" 'BEGIN { printf "%d", p * 10 }')
    for transport in $transports; do
      # TCP cannot get the bots' simulated latency: only its 0 ms rows are measured.
      [ "$transport" = tcp ] && [ "$latency" -gt 0 ] && continue
      label="$transport-$loss-$latency"
      run "$transport" "$permille" "$latency" "$label"
      labels+=("$label")
    done
  done
done
python3 "$here/loss_table.py" "$work" "$seconds" "$bots" "${labels[@]}"
