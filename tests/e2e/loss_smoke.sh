#!/usr/bin/env bash
# make test's short bench-loss: bench/loss.sh's own machinery (network namespaces of its own
# that drop a random share of the packets they receive, nftables) for a few seconds over UDP at
# 0 % and 5 % loss, then loss_check.py on what the server and the bots reported: the redundant
# inputs close every gap the loss opens. Needs root (ip netns, nft), as CI runs: without it the
# test fails and says so, it never skips. Usage: loss_smoke.sh BIN_DIR SOURCE_DIR
set -euo pipefail
bin=$1
root=$2
bots=8
if [ "$(id -u)" != 0 ]; then
  echo "loss smoke test: needs root for ip netns and nft (CI runs as root); run 'make test' as root" >&2
  exit 1
fi
work=$(mktemp -d /tmp/arena-loss-smoke.XXXXXX)
trap 'rm -rf "$work"' EXIT
LOSS_PERCENT="0 5" LOSS_LATENCY_MS=0 LOSS_SECONDS=5 LOSS_BOTS=$bots LOSS_TRANSPORTS=udp LOSS_WORK="$work" \
  "$root/bench/loss.sh" "$bin"
python3 "$root/tests/e2e/loss_check.py" "$work" "$bots"
