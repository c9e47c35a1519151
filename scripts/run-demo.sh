#!/usr/bin/env bash
# The main job of `make run`: arena-server with simulated players against it, showing their
# live figures, then the server's own summary. Afterwards the lecture's example through
# arena-sim. DEMO_BOTS and DEMO_SECONDS change the size and length; the page to play in a
# browser is on DEMO_HTTP_PORT (default 0: a free port), printed as a URL.
set -euo pipefail
bin=${1:-build/bin}
bots=${DEMO_BOTS:-50}
seconds=${DEMO_SECONDS:-10}
log=$(mktemp /tmp/arena-demo.XXXXXX)
stats="$log.stats.json"
recording="$log.arpl"
trap 'kill "$server" 2>/dev/null || true; rm -f "$log" "$stats" "$recording"' EXIT

echo "== arena-server (asteroids) with $bots bots for $seconds s =="
# Room for a few players from the browser beside the bots.
# The asteroids preset played as a game: bullets, splitting rocks, lives and score.
"$bin/arena-server" --port 0 --preset asteroids --rules asteroids --max-players $((bots + 4)) --duration $((seconds + 3)) \
  --http-port "${DEMO_HTTP_PORT:-0}" --stats-json "$stats" --record "$recording" > "$log" 2> "$log.err" &
server=$!
port=""
http_port=""
for _ in $(seq 100); do
  port=$(sed -n 's/^listening on .*:\([0-9]*\)$/\1/p' "$log")
  http_port=$(sed -n 's/^http listening on .*:\([0-9]*\)$/\1/p' "$log")
  [ -n "$port" ] && [ -n "$http_port" ] && break
  sleep 0.1
done
[ -n "$port" ] && [ -n "$http_port" ] || { echo "arena-server did not start:"; cat "$log.err"; exit 1; }
echo "listening on 127.0.0.1:$port"
# The page is there when the build made it (build/web, beside bin/: the browser SDK is on).
if [ -f "$bin/../web/index.html" ]; then
  echo "play in a browser while the bots play: http://127.0.0.1:$http_port/?name=you"
  echo "  (arrows turn and thrust, space fires, shift boosts; DEMO_SECONDS=300 make run for a longer match)"
fi
"$bin/arena-bots" --port "$port" --bots "$bots" --duration "$seconds" --behavior mixed --seed 1
wait "$server"
echo "== the server's log =="
grep -E "stats|shutting down|recorded" "$log.err" || true
rm -f "$log.err"
echo "== the scoreboard (--stats-json) =="
python3 -c 'import json, sys
for p in json.load(open(sys.argv[1]))["scoreboard"]:
    print("{name:>8} score {score:>5}  kills {kills:>2}  deaths {deaths:>2}  shots {shots:>4}  hits {hits:>4}".format(**p))' "$stats"
echo "== replaying the recorded session =="
"$bin/arena-replay" "$recording"
echo "== the replay's scoreboard (arena-replay --scoreboard) =="
"$bin/arena-replay" "$recording" --scoreboard 2>/dev/null

echo "== the lecture's example: 10 N on 1 kg, dt = 1 s, explicit Euler (exact: 500 m) =="
"$bin/arena-sim" --integrator explicit --dt 1 --steps 10 --mass 1 --force 10,0
