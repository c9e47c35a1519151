# Sourced by bench/loss.sh, bench/hits.sh and bench/page_hits.sh: two network namespaces of a
# run's own, the server's and the bots', joined by a point-to-point link (arena-link-delay) that
# holds every packet in the kernel's packet path. Before sourcing, set: bin (the programs),
# link_name (in the namespaces' and the work folder's names), link_net (the /30's first three
# octets, one per script, so that two benches never share addresses) and env_prefix (the
# script's environment: PREFIX_WORK, a folder that keeps each run's files, else a temporary one
# removed at exit; PREFIX_NICE, the nice value of the link, the server and the bots, -10: a
# compiler at nice 0 would otherwise hold a packet or a tick back by tens of ms and show as
# lag). Defines work, keep, priority, server_ns, bots_ns, server_address, bots_address,
# drop_namespaces and link_connect; at exit removes the namespaces, and work unless kept.
keep_variable=${env_prefix}_WORK
nice_variable=${env_prefix}_NICE
keep=${!keep_variable:-}
if [ -n "$keep" ]; then mkdir -p "$keep"; work=$keep; else work=$(mktemp -d "/tmp/arena-bench-$link_name.XXXXXX"); fi
priority=${!nice_variable:--10}
server_ns=arena-$link_name-server-$$
bots_ns=arena-$link_name-bots-$$
server_address=$link_net.1
bots_address=$link_net.2
link=""
drop_namespaces() {
  if [ -n "$link" ]; then kill -TERM "$link" 2>/dev/null || true; wait "$link" 2>/dev/null || true; link=""; fi
  ip netns del "$server_ns" 2>/dev/null || true
  ip netns del "$bots_ns" 2>/dev/null || true
}
cleanup() { drop_namespaces; [ -n "$keep" ] || rm -rf "$work"; }
trap cleanup EXIT

# link_connect LABEL [SETUP_FUNCTION [ARENA_LINK_DELAY_ARGS...]]: both namespaces anew, each
# given to SETUP_FUNCTION NAMESPACE once made (its filters, say), and the link between them
# with the given arguments (--delay-ms ...); its log is WORK/LABEL.link.
link_connect() {
  local label=$1 setup=${2:-} ns
  shift 2 || shift $#
  drop_namespaces
  for ns in "$server_ns" "$bots_ns"; do
    ip netns add "$ns"
    ip -n "$ns" link set lo up
    ip -n "$ns" tuntap add dev arena0 mode tun
    if [ -n "$setup" ]; then "$setup" "$ns"; fi
  done
  ip -n "$server_ns" addr add "$server_address/30" dev arena0
  ip -n "$bots_ns" addr add "$bots_address/30" dev arena0
  : > "$work/$label.link"
  ip netns exec "$server_ns" nice -n "$priority" "$bin/arena-link-delay" --peer-netns "$bots_ns" "$@" \
    > "$work/$label.link" 2>&1 &
  link=$!
  for _ in $(seq 100); do grep -q "^link-delay ready" "$work/$label.link" && break; sleep 0.05; done
  grep -q "^link-delay ready" "$work/$label.link" || { echo "arena-link-delay did not start" >&2; cat "$work/$label.link" >&2; return 1; }
  ip -n "$server_ns" link set arena0 up
  ip -n "$bots_ns" link set arena0 up
}
