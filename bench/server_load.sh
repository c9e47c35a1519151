# Sourced by the bench scripts (e2e.sh, floor_compare.sh, hits.sh, loss.sh, page_hits.sh): what
# they need to start and load a server the same way.

# utime + stime of a process, in clock ticks (getconf CLK_TCK a second).
cpu_ticks() {
  awk '{ print $14 + $15 }' "/proc/$1/stat"
}

# Nanoseconds a process's running threads have spent on a CPU, summed: exact, where the clock
# ticks of cpu_ticks are samples (a thread that has ended no longer counts).
cpu_ns() {
  cat /proc/"$1"/task/*/schedstat | awk '{ sum += $1 } END { printf "%d\n", sum }'
}

# pin_to_cpus: sets pin_server (taskset -c 1) and pin_bots (taskset -c 0), the prefixes that keep
# a server and its clients on CPUs of their own; both empty without taskset or a second CPU.
pin_to_cpus() {
  pin_server=(); pin_bots=()
  if command -v taskset >/dev/null && [ "$(nproc)" -ge 2 ]; then pin_server=(taskset -c 1); pin_bots=(taskset -c 0); fi
}

# write_room_mode FILE N: a --modes file with one mode, "roomN": the asteroids preset without
# rocks, sandbox rules, N seats (the many-matches load).
write_room_mode() {
  echo "{\"modes\": [{\"name\": \"room$2\", \"preset\": \"asteroids\", \"rules\": \"sandbox\", \"max_players\": $2,
  \"world\": {\"rocks\": {\"count\": 0}}}]}" > "$1"
}

# port_of FILE PREFIX: the port of the line "PREFIX HOST:PORT" a server prints to FILE (its
# stdout), waiting up to 10 s for it; empty when it never came. PREFIX "listening on" (TCP),
# "udp listening on", "http listening on".
port_of() {
  local p=""
  for _ in $(seq 100); do
    p=$(sed -n "s/^$2 .*:\([0-9]*\)\$/\1/p" "$1" 2>/dev/null || true); [ -n "$p" ] && break; sleep 0.1
  done
  echo "$p"
}
