#!/usr/bin/env bash
# make bench-e2e: arena-server pinned to CPU 1 and arena-bots to CPU 0, 64, 256 and 512 bots
# for 20 s each at 60 Hz ticks and 20 Hz snapshots (the server's defaults: delta snapshots,
# 100 m view radius); 256 bots on the old path (full BodyState snapshots of the whole world)
# for the bandwidth comparison; 1000 bots with a view radius; then the Colyseus peer
# and Arena under the same 200-client load in the same minute; then 50 matches of 8 in one process
# against Colyseus's own matchmaker filling rooms of 8. One markdown table per part.
# Env: E2E_BOTS ("64 256 512"), E2E_SECONDS (20), E2E_LARGE (1000), E2E_LARGE_RADIUS (50),
#      E2E_ROOMS_BOTS (400), E2E_ROOMS_RUNS (1), COLYSEUS (../shared/peers/colyseus),
#      E2E_PARTS ("one colyseus rooms": which parts run), E2E_SETTLE (3: seconds of each run before
#      its steady-state CPU is measured, Colyseus' warm-up).
set -euo pipefail
bin=${1:-build/bin}
here=$(cd "$(dirname "$0")" && pwd)
counts=${E2E_BOTS:-64 256 512}
large=${E2E_LARGE:-1000}
large_radius=${E2E_LARGE_RADIUS:-50}
seconds=${E2E_SECONDS:-20}
colyseus=${COLYSEUS:-$here/../../shared/peers/colyseus}
work=$(mktemp -d /tmp/arena-bench-e2e.XXXXXX)
trap 'rm -rf "$work"' EXIT
parts=" ${E2E_PARTS:-one colyseus rooms} "
part() { [[ "$parts" == *" $1 "* ]]; }
settle=${E2E_SETTLE:-3}
ticks_per_s=$(getconf CLK_TCK)
. "$here/server_load.sh"
pin_to_cpus

# run_arena N LABEL [SERVER_FLAGS] [BOTS_FLAGS]: one run; leaves $work/LABEL.server.json and
# $work/LABEL.bots.json. The flag lists are single words split on spaces.
run_arena() {
  local n=$1 label=$2
  local -a server_flags=(${3:-}) bots_flags=(${4:-}) server_load bots_load
  load_flags "$n"
  "${pin_server[@]}" "$bin/arena-server" --port 0 "${server_load[@]}" --tick-rate 60 --snapshot-rate 20 \
    "${server_flags[@]}" --stats-json "$work/$label.server.json" > "$work/$label.out" 2> "$work/$label.log" &
  local server=$! port
  port=$(port_of "$work/$label.out" "listening on")
  [ -n "$port" ] || { echo "arena-server did not start" >&2; cat "$work/$label.log" >&2; return 1; }
  "${pin_bots[@]}" "$bin/arena-bots" --port "$port" "${bots_load[@]}" --duration "$seconds" "${bots_flags[@]}" \
    --json "$work/$label.bots.json" > "$work/$label.bots.out" 2>&1 &
  local bots=$!
  # The steady state, measured as Colyseus' run.sh and the floor measure theirs: the server's
  # CPU from SETTLE s after the bots start (every join done) to 1 s before they stop.
  sleep "$settle"
  local cpu0 t0 cpu1 t1
  cpu0=$(cpu_ticks "$server"); t0=$(date +%s.%N)
  sleep "$((seconds - settle - 1))"
  cpu1=$(cpu_ticks "$server"); t1=$(date +%s.%N)
  echo "{\"cpu_per_s\": $(python3 -c "print(($cpu1 - $cpu0) / $ticks_per_s / ($t1 - $t0))")}" > "$work/$label.steady.json"
  wait "$bots" || true
  # Stopped as soon as the bots are done, so that its CPU per second covers the load only.
  kill -TERM "$server"
  wait "$server" || true
}

if part one; then
echo "## End to end: arena-server on CPU 1, arena-bots on CPU 0, ${seconds} s, 60 Hz ticks, 20 Hz snapshots"
echo
for n in $counts; do
  echo "running $n bots..." >&2
  run_arena "$n" "arena-$n"
done
echo "running 256 bots on full snapshots of the whole world..." >&2
run_arena 256 arena-256-full "--view-radius 0" "--full-snapshots"
echo "running $large bots, view radius $large_radius m..." >&2
run_arena "$large" "arena-$large-r$large_radius" "--view-radius $large_radius"
labels=()
for n in $counts; do labels+=("arena-$n"); done
labels+=(arena-256-full "arena-$large-r$large_radius")
python3 "$here/e2e_table.py" arena "$work" "${labels[@]}"
echo
echo "The window counts from the server's start to SIGTERM right after the bots' last second, joins included."
echo "Default runs: delta snapshots and a 100 m view radius; 'full': BodyState snapshots of every body (the path"
echo "for clients without delta support); bytes per body are the bots' received frames over the bodies they held."
fi

if ! part colyseus; then
  :
elif [ -x "$colyseus/run.sh" ] && command -v npm >/dev/null; then
  echo
  echo "## Against Colyseus: 200 clients sending 60 inputs/s, 60 Hz simulation, 20 Hz broadcast, server on CPU 1"
  echo
  echo "running Colyseus with 200 clients..." >&2
  "$colyseus/run.sh" 200 "$seconds" > "$work/colyseus.json" 2> "$work/colyseus.log" || { tail -20 "$work/colyseus.log" >&2; }
  echo "running Arena with 200 bots (whole world, then the default 100 m view)..." >&2
  run_arena 200 arena-200-world "--view-radius 0"
  run_arena 200 arena-200
  echo "running the TCP floor with 200 clients (no game, no framework)..." >&2
  taskset -c 0,1 "$bin/arena-bench-tcp-floor" --clients 200 --seconds "$seconds" > "$work/tcp-floor.json" \
    || echo "tcp floor run failed" >&2
  python3 "$here/e2e_table.py" colyseus "$work"
else
  echo
  echo "Colyseus comparison skipped: $colyseus/run.sh or npm not found."
fi

# Many matches in one process: E2E_ROOMS_BOTS bots join-or-create matches of 8 (50 matches at
# 400), every body of a match in view, against Colyseus' matchmaker filling rooms of 8
# (ROOM_SIZE=8) and the TCP floor with the same clients and Arena's snapshot size.
# E2E_ROOMS_RUNS (1) repeats the three, one table per run, then the ratios' medians: a run's
# figures swing by 10 % or more on a shared machine.
rooms_bots=${E2E_ROOMS_BOTS:-400}
rooms_runs=${E2E_ROOMS_RUNS:-1}
part rooms || exit 0
echo
echo "## Many matches in one process: $rooms_bots clients in matches of 8, 60 inputs/s each, every body of a match in view, server on CPU 1"
room_load "$work/modes.json" 8
for run in $(seq "$rooms_runs"); do
  echo >&2
  echo "running Arena with $rooms_bots bots in matches of 8 (run $run of $rooms_runs)..." >&2
  run_arena "$rooms_bots" arena-rooms "${room_server[*]}" "${room_bots[*]}"
  echo
  if [ -x "$colyseus/run.sh" ] && command -v npm >/dev/null; then
    echo "running Colyseus with $rooms_bots clients in rooms of 8..." >&2
    ROOM_SIZE=8 "$colyseus/run.sh" "$rooms_bots" "$seconds" > "$work/colyseus-rooms.json" 2> "$work/colyseus-rooms.log" \
      || { tail -20 "$work/colyseus-rooms.log" >&2; }
    snapshot_bytes=$(python3 -c "import json; print(max(1, round(json.load(open('$work/arena-rooms.bots.json'))['figures']['snapshot_bytes']['mean'])))")
    echo "running the TCP floor with $rooms_bots clients and $snapshot_bytes-byte snapshots..." >&2
    taskset -c 0,1 "$bin/arena-bench-tcp-floor" --clients "$rooms_bots" --seconds "$seconds" \
      --snapshot-bytes "$snapshot_bytes" > "$work/tcp-floor-rooms.json" || echo "tcp floor run failed" >&2
  fi
  python3 "$here/e2e_table.py" rooms "$work"
  mkdir -p "$work/rooms-run-$run"
  cp "$work"/arena-rooms.*.json "$work"/*-rooms.json "$work/rooms-run-$run/" 2>/dev/null || true
done
if [ "$rooms_runs" -gt 1 ]; then
  echo
  python3 "$here/e2e_table.py" rooms-median "$work"/rooms-run-*
fi
echo
echo "running arena-bench-matches (the matches alone, no sockets) on CPU 1..." >&2
"${pin_server[@]}" "$bin/arena-bench-matches" --matches 200 --ticks 1200 > "$work/matches.json"
python3 "$here/e2e_table.py" matches "$work"
