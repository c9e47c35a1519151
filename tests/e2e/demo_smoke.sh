#!/usr/bin/env bash
# `make run` as a script or CI runs it (no terminal): scripts/run-demo.sh with a few bots for a
# few seconds tells its short story, and the story is true: every bot stayed to the match's end
# and got the result in the server's Bye, the round trip is split into the network's and the
# server's hold, the replay's scoreboard is the live one with names, and a winner is named.
#   demo_smoke.sh BIN_DIR SOURCE_DIR
set -euo pipefail
bin=$1
source_dir=$2
bots=8
out=$(DEMO_BOTS=$bots DEMO_SECONDS=6 CI=1 bash "$source_dir/scripts/run-demo.sh" "$bin" < /dev/null 2>&1) || {
  echo "run-demo.sh failed:"; echo "$out"; exit 1; }
echo "$out"
fail=0
expect() {  # a line of the output that matches the extended regular expression $1
  if ! grep -Eq -- "$1" <<< "$out"; then echo "FAIL: no line matches: $1"; fail=1; fi
}
expect "^== arena-server \(asteroids\) with $bots bots for 6 s ==$"
expect "^== what ran ==$"
expect "^arena-server: the asteroids preset and its rules \(bullets, splitting rocks, lives, score\), 60 ticks/s, 20 snapshots/s"
expect "^arena-bots: $bots bots \(--behavior mixed\) over TCP on loopback: $bots joined, 0 failed$"
expect "^== the figures that matter ==$"
# Every bot stayed for the Bye (they used to leave first: "no Bye with the result").
expect "^result: $bots of $bots bots got the final scoreboard in the server's Bye, all the same$"
# The round trip apart from the server's wait for its next read (Pong.server_hold_us).
expect "^round trip: [0-9.]+ ms on the network \(p50, p99 [0-9.]+ ms\); the server held each Ping [0-9.]+ ms more"
expect "^prediction: each bot drew its ship where the server then put it to within [0-9.]+ (mm|m) \(p50\)"
# Own shots are off by the snapshots' quantisation, and say so (they read "0.00 % exactly").
if grep -q "^own shots:" <<< "$out"; then
  expect "^own shots: [0-9]+ fired where the server fired them, off by [0-9.]+ mm \(p99, max [0-9.]+ mm\): (within|beyond) the delta snapshots' quantisation"
fi
expect "^server: [0-9]+ ticks, a tick took [0-9.]+ ms \(p99\) of its 16.7 ms"
expect "^replay: [0-9]+ ticks re-simulated, [0-9]+ recorded hashes matched; its scoreboard is the live one, names included$"
expect "^== top five of $bots ==$"
expect "^  1\. bot-[0-9]+ +[0-9]+ points"
# The rules' winner (a hunter scores within seconds; on a slow machine nobody may have yet).
expect "^winner: (bot-[0-9]+ with [0-9]+ points|nobody \(no score\))$"
expect "^the page: "
expect "^details: /tmp/arena-demo\.[A-Za-z0-9]+ "
# A short run with no terminal: no wait for Ctrl-C.
if grep -q "until Ctrl-C ==" <<< "$out"; then echo "FAIL: a run without a terminal waited for Ctrl-C"; fail=1; fi
# The detailed reports are in the folder the summary names; the first screen stays short.
dir=$(sed -n 's/^details: \(\/tmp\/arena-demo\.[A-Za-z0-9]*\) .*/\1/p' <<< "$out")
[ -s "$dir/bots.txt" ] && [ -s "$dir/stats.json" ] && [ -s "$dir/match.arpl" ] || { echo "FAIL: no details in '$dir'"; fail=1; }
lines=$(wc -l <<< "$out")
[ "$lines" -le 40 ] || { echo "FAIL: $lines lines of output, more than a screen"; fail=1; }
rm -rf "$dir"
exit $fail
