#!/usr/bin/env bash
# make bench-page-hits: a person's view of lag compensation. The page (headless Chromium,
# bench/page_hits.mjs aiming at the nearest target and firing) plays Asteroids with a few hunter
# bots over a link with added latency (two network namespaces joined by arena-link-delay, as
# make bench-hits), compensation on and off. Prints, per run, the hits the page saw (flashed
# white at once) and the hits the server confirmed (hit markers).
# Env: PAGE_RTT_MS (100), PAGE_JITTER_MS (10, on the round trip), PAGE_COMPENSATION_MS ("250 0"),
#      PAGE_SECONDS (30), PAGE_BOTS (4, hunters over UDP), PAGE_WORK (keeps the logs), PAGE_NICE (-10).
set -euo pipefail
bin=${1:-build/bin}
node_path=${2:-build/web-page/node_modules}
here=$(cd "$(dirname "$0")" && pwd)
rtt=${PAGE_RTT_MS:-100}
jitter=${PAGE_JITTER_MS:-10}
compensations=${PAGE_COMPENSATION_MS:-250 0}
seconds=${PAGE_SECONDS:-30}
bots=${PAGE_BOTS:-4}
chromium=$(command -v chromium || true)
[ "$(id -u)" = 0 ] || { echo "bench-page-hits: needs root (ip netns)" >&2; exit 1; }
[ -n "$chromium" ] || { echo "bench-page-hits: needs chromium (make deps)" >&2; exit 1; }
[ -d "$node_path/puppeteer-core" ] || { echo "bench-page-hits: no puppeteer-core in $node_path (make build)" >&2; exit 1; }
node_path=$(cd "$node_path" && pwd)
link_name=page
env_prefix=PAGE
link_net=10.79.0
. "$here/netns_link.sh"
. "$here/server_load.sh"

# run COMPENSATION_MS LABEL: one Asteroids server (its page from build/web, beside bin/), its
# hunters and the page, the server in its namespace and the players in theirs.
run() {
  local compensation=$1 label=$2
  local spread
  spread=$(awk -v r="$rtt" -v j="$jitter" 'BEGIN { print (r > 0 ? j / 2 : 0) }')
  link_connect "$label" "" --delay-ms "$(awk -v r="$rtt" 'BEGIN { print r / 2 }')" --jitter-ms "$spread"
  : > "$work/$label.out"
  ip netns exec "$server_ns" nice -n "$priority" "$bin/arena-server" --bind "$server_address" --port 0 --udp-port 0 \
    --http-port 0 --max-players $((bots + 1)) --duration $((seconds + 60)) --preset asteroids \
    --lag-compensation-ms "$compensation" > "$work/$label.out" 2> "$work/$label.log" &
  local server=$! udp http
  udp=$(port_of "$work/$label.out" "udp listening on")
  http=$(port_of "$work/$label.out" "http listening on")
  [ -n "$udp" ] && [ -n "$http" ] || { echo "arena-server did not start" >&2; cat "$work/$label.log" >&2; return 1; }
  ip netns exec "$bots_ns" nice -n "$priority" "$bin/arena-bots" --transport udp --host "$server_address" --port "$udp" \
    --bots "$bots" --behavior hunter --duration $((seconds + 10)) --connect-rate 100 --seed 1 --quiet \
    > "$work/$label.bots.out" 2>&1 &
  local hunters=$!
  local line
  line=$(ip netns exec "$bots_ns" env CHROMIUM="$chromium" NODE_PATH="$node_path" \
    node "$here/page_hits.mjs" "http://$server_address:$http/" "$seconds" 2> "$work/$label.page.log" | tail -n 1) || {
    echo "the page failed:" >&2; cat "$work/$label.page.log" >&2; }
  wait "$hunters" || true
  kill -TERM "$server" 2>/dev/null || true
  wait "$server" || true
  drop_namespaces
  echo "round trip ${rtt} ms ± $((jitter / 2)), compensation ${compensation} ms: ${line:-no result}"
}

for compensation in $compensations; do
  run "$compensation" "$rtt-$compensation"
done
