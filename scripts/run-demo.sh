#!/usr/bin/env bash
# The main job of `make run`: arena-server playing Asteroids with simulated players (arena-bots)
# against it, recorded and replayed, then a short summary: what ran, the figures that matter and
# what they mean, the top five, the winner and the page's URL. Every detail (the bots' figures,
# the server's log, --stats-json, the recording) stays in a folder the summary names.
#
# At a terminal (stdin and stdout are ttys, CI unset) the match goes on until Ctrl-C, so that
# a person can open the page and play against the bots; the summary follows. Anywhere else
# (scripts, CI) it is a short run of DEMO_SECONDS. DEMO_BOTS and DEMO_SECONDS change the size
# and length; the page is on DEMO_HTTP_PORT (default 0: a free port).
set -euo pipefail
bin=${1:-build/bin}
bots=${DEMO_BOTS:-50}
seconds=${DEMO_SECONDS:-10}
here=$(cd "$(dirname "$0")" && pwd)
interactive=0
if [ -t 0 ] && [ -t 1 ] && [ -z "${CI:-}" ]; then interactive=1; fi

dir=$(mktemp -d /tmp/arena-demo.XXXXXX)
log="$dir/server.out"
server_log="$dir/server.log"
stats="$dir/stats.json"
recording="$dir/match.arpl"
bots_json="$dir/bots.json"
bots_text="$dir/bots.txt"
server=""
fleet=""
trap 'for p in $server $fleet; do kill "$p" 2>/dev/null || true; done' EXIT

# At a terminal the server and the bots get a session of their own: Ctrl-C then reaches this
# script alone, which ends the match in order (SIGTERM: every bot gets the result in its Bye).
detach=()
if [ "$interactive" = 1 ]; then detach=(setsid); fi
if [ "$interactive" = 1 ]; then
  duration=()
  bots_seconds=86400
  echo "== arena-server (asteroids) with $bots bots until Ctrl-C =="
else
  duration=(--duration "$seconds")
  # The server ends the match; the bots stay until then, so that each one gets the result.
  bots_seconds=$((seconds + 30))
  echo "== arena-server (asteroids) with $bots bots for $seconds s =="
fi
# Room for a few players from the browser beside the bots. The asteroids preset plays the
# asteroids rules: bullets, splitting rocks, lives and score.
"${detach[@]}" "$bin/arena-server" --port 0 --preset asteroids --max-players $((bots + 4)) "${duration[@]}" \
  --http-port "${DEMO_HTTP_PORT:-0}" --stats-json "$stats" --record "$recording" > "$log" 2> "$server_log" &
server=$!
port=""
http_port=""
for _ in $(seq 100); do
  port=$(sed -n 's/^listening on .*:\([0-9]*\)$/\1/p' "$log")
  http_port=$(sed -n 's/^http listening on .*:\([0-9]*\)$/\1/p' "$log")
  [ -n "$port" ] && [ -n "$http_port" ] && break
  sleep 0.1
done
[ -n "$port" ] && [ -n "$http_port" ] || { echo "arena-server did not start:"; cat "$server_log"; exit 1; }
echo "listening on 127.0.0.1:$port"
page=""
# The page is there when the build made it (build/web, beside bin/: the browser SDK is on).
if [ -f "$bin/../web/index.html" ]; then
  page="http://127.0.0.1:$http_port/?name=you"
  echo "play in a browser while the bots play: $page"
  echo "  (arrows turn and thrust, space fires, shift boosts)"
fi
"${detach[@]}" "$bin/arena-bots" --port "$port" --bots "$bots" --duration "$bots_seconds" --behavior mixed --seed 1 \
  --quiet --json "$bots_json" > "$bots_text" 2>&1 &
fleet=$!
if [ "$interactive" = 1 ]; then
  echo "the match goes on until Ctrl-C; then the summary"
  trap 'kill -TERM "$server" 2>/dev/null || true' INT
  # `wait` returns when Ctrl-C's trap ran; the bots end once the server's Bye reached them.
  while kill -0 "$fleet" 2>/dev/null; do wait "$fleet" 2>/dev/null || true; done
  trap - INT
else
  echo "playing for $seconds s ..."
fi
bots_code=0
wait "$fleet" || bots_code=$?
fleet=""
wait "$server" || true
server=""
replay_code=0
"$bin/arena-replay" "$recording" > "$dir/replay.txt" 2>&1 || replay_code=$?
"$bin/arena-replay" "$recording" --scoreboard > "$dir/replay_scoreboard.json" 2> /dev/null || true

python3 "$here/demo_summary.py" --bots "$bots_json" --stats "$stats" --replay "$dir/replay.txt" \
  --replay-scoreboard "$dir/replay_scoreboard.json" --replay-code "$replay_code" --page "$page" --dir "$dir"
[ "$bots_code" = 0 ] || echo "arena-bots exited with $bots_code: see $bots_text"

echo "== the lecture's example: 10 N on 1 kg, dt = 1 s, explicit Euler (exact: 500 m) =="
"$bin/arena-sim" --integrator explicit --dt 1 --steps 10 --mass 1 --force 10,0 |
  awk -F, 'END { printf "arena-sim: x = %s m after 10 s: explicit Euler moves each step at the speed the step starts with, %d m short\n", $2, 500 - $2 }'

