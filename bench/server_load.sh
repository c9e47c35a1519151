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

# load_flags N: sets server_load and bots_load, the flags that make arena-server and arena-bots
# the CPU comparisons' load for N clients, the same in every script: seats, connections and
# pending handshakes for N and the sandbox rules; N mixed bots joining 500 a second, seed 1.
# Callers add ports, duration, output and what their run differs in.
load_flags() {
  server_load=(--max-players "$1" --max-connections $((2 * $1 + 16)) --max-pending-handshakes "$1" --rules sandbox)
  bots_load=(--bots "$1" --connect-rate 500 --behavior mixed --seed 1 --quiet)
}

# room_load FILE N: the many-matches load in matches of N. Writes FILE, a --modes file with one
# mode, "roomN": the asteroids preset without rocks, sandbox rules, N seats. Sets room_server
# (that mode, every body of a match in view, one tick thread, room for 1000 matches) and
# room_bots (join-or-create "roomN").
room_load() {
  echo "{\"modes\": [{\"name\": \"room$2\", \"preset\": \"asteroids\", \"rules\": \"sandbox\", \"max_players\": $2,
  \"world\": {\"rocks\": {\"count\": 0}}}]}" > "$1"
  room_server=(--modes "$1" --view-radius 0 --threads 1 --max-matches 1000)
  room_bots=(--mode "room$2")
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
