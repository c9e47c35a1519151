#!/usr/bin/env bash
# make test's check of bench-loss's added latency (bench/link_delay.cpp): TCP and UDP bots at
# 0 and 50 ms, no loss, for a few seconds through bench/loss.sh's two namespaces and their
# delaying link; latency_check.py then reads what the bots measured: the 50 ms each way shows
# in both transports' round trips and input lag. Needs root (ip netns, TUN), as CI runs:
# without it the test fails and says so, it never skips. Usage: latency_smoke.sh BIN_DIR SOURCE_DIR
set -euo pipefail
bin=$1
root=$2
if [ "$(id -u)" != 0 ]; then
  echo "latency smoke test: needs root for ip netns and TUN devices (CI runs as root); run 'make test' as root" >&2
  exit 1
fi
work=$(mktemp -d /tmp/arena-latency-smoke.XXXXXX)
trap 'rm -rf "$work"' EXIT
LOSS_PERCENT=0 LOSS_LATENCY_MS="0 50" LOSS_SECONDS=4 LOSS_BOTS=4 LOSS_TRANSPORTS="tcp udp" LOSS_WORK="$work" \
  "$root/bench/loss.sh" "$bin"
python3 "$root/tests/e2e/latency_check.py" "$work" 50
