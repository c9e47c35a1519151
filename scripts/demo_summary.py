#!/usr/bin/env python3
"""The summary `make run` prints (scripts/run-demo.sh): what ran, the figures that matter with
their meaning, the top five, the winner and the page's URL, from the files the run left:
arena-bots --json, arena-server --stats-json, arena-replay's summary and --scoreboard."""
import argparse
import json
import math

# The delta snapshots' quantisation (protocol/delta/quantize.hpp) as a distance, as arena-bots
# reckons it (client_sim/report.cpp): a position is rounded to 1/256 m (1/512 m off on each
# axis), a velocity to 1/32 m/s (1/64 m/s), carried over about 0.1 s of prediction.
QUANTUM_M = math.sqrt(2) * (1 / 512 + 0.1 / 64)


def mm(metres):
    return f"{metres * 1000:.1f} mm"


def length(metres):
    return mm(metres) if metres < 0.1 else f"{metres:.2f} m"


def read_key_values(path):
    out = {}
    try:
        with open(path) as f:
            for line in f:
                key, sep, value = line.strip().partition("=")
                if sep:
                    out[key] = value
    except OSError:
        pass
    return out


def read_json(path, default):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return default


def comparable(lines):
    keys = ("player", "name", "score", "kills", "deaths", "shots", "hits")
    return [{k: line.get(k) for k in keys} for line in lines]


def main():
    p = argparse.ArgumentParser()
    for name in ("bots", "stats", "replay", "replay-scoreboard", "replay-code", "page", "dir"):
        p.add_argument("--" + name, default="")
    a = p.parse_args()
    bots = read_json(a.bots, {})
    stats = read_json(a.stats, {})
    replay = read_key_values(a.replay)
    replayed = read_json(a.replay_scoreboard, [])
    figures = bots.get("figures", {})
    fig = lambda name, key: figures.get(name, {}).get(key, 0.0)

    print("== what ran ==")
    rate, snapshots = stats.get("tick_rate", 0), stats.get("snapshot_rate", 0)
    print(f"arena-server: the asteroids preset and its rules (bullets, splitting rocks, lives, score), "
          f"{rate} ticks/s, {snapshots} snapshots/s, {stats.get('duration_s', 0):.1f} s, recorded to match.arpl")
    print(f"arena-bots: {bots.get('bots', 0)} bots (--behavior mixed) over TCP on loopback: "
          f"{bots.get('joined', 0)} joined, {bots.get('failed', 0)} failed")

    print("== the figures that matter ==")
    board = bots.get("scoreboard", {})
    clients, agreeing = board.get("clients", 0), board.get("agreeing", 0)
    if board.get("final"):
        print(f"result: {agreeing} of {clients} bots got the final scoreboard in the server's Bye, all the same"
              if agreeing == clients else
              f"result: {clients} bots got the server's Bye, {agreeing} of them with the same final scoreboard")
    else:
        print(f"result: no bot got the server's Bye with the final scoreboard ({clients} saw the game)")
    if figures.get("network_rtt_ms", {}).get("count", 0) > 0:
        print(f"round trip: {fig('network_rtt_ms', 'p50'):.2f} ms on the network (p50, p99 "
              f"{fig('network_rtt_ms', 'p99'):.2f} ms); the server held each Ping {fig('server_hold_ms', 'p50'):.1f} ms "
              f"more (p50) until its next tick read it: {fig('rtt_ms', 'p50'):.1f} ms from Ping to Pong")
    else:
        print(f"round trip: {fig('rtt_ms', 'p50'):.1f} ms from Ping to Pong (p50), the server's wait for its next "
              f"tick included")
    print(f"prediction: each bot drew its ship where the server then put it to within "
          f"{length(fig('prediction_error_m', 'p50'))} (p50), {length(fig('prediction_error_m', 'p99'))} (p99); "
          f"{100 * bots.get('prediction_exact_share', 0):.1f} % exactly")
    own = bots.get("own_shots", {})
    matched = own.get("exact", 0) + own.get("with_error", 0)
    if matched:
        p99, top = fig("own_shot_error_m", "p99"), fig("own_shot_error_m", "max")
        where = ("within" if p99 <= QUANTUM_M else "beyond")
        print(f"own shots: {matched} fired where the server fired them, off by {mm(p99)} (p99, max {mm(top)}): "
              f"{where} the delta snapshots' quantisation ({mm(QUANTUM_M)}: positions to 1/256 m, velocities to 1/32 m/s)")
    tick = stats.get("tick_ms", {})
    period = 1000.0 / rate if rate else 0
    print(f"server: {stats.get('ticks', 0)} ticks, a tick took {tick.get('p99', 0):.2f} ms (p99) of its "
          f"{period:.1f} ms; {stats.get('bytes_out_per_s', 0) / 1000:.0f} kB/s sent, "
          f"{stats.get('bytes_in_per_s', 0) / 1000:.0f} kB/s received")
    live = stats.get("scoreboard", [])
    same = comparable(replayed) == comparable(live)
    if a.replay_code == "0" and replay.get("hashes_checked"):
        print(f"replay: {replay.get('ticks_replayed', 0)} ticks re-simulated, {replay['hashes_checked']} recorded "
              f"hashes matched; " + ("its scoreboard is the live one, names included" if same else
                                     "its scoreboard differs from the live one"))
    else:
        print(f"replay: the recording did not replay bit for bit (arena-replay exited with {a.replay_code}: see "
              f"{a.dir}/replay.txt)")

    ranked = sorted(live, key=lambda l: (-l.get("score", 0), l.get("player", 0)))
    print(f"== top five of {len(live)} ==")
    for rank, l in enumerate(ranked[:5], 1):
        accuracy = 100.0 * l["hits"] / l["shots"] if l.get("shots") else 0.0
        print(f"  {rank}. {l.get('name') or 'player ' + str(l.get('player')):<12} {l.get('score', 0):>6} points "
              f"{l.get('kills', 0):>3} kills {l.get('deaths', 0):>3} deaths {accuracy:>5.1f} % of "
              f"{l.get('shots', 0)} shots hit")
    winner = next((l for l in live if l.get("player") == stats.get("winner")), None)
    print(f"winner: {winner.get('name') or winner.get('player')} with {winner.get('score', 0)} points"
          if winner else "winner: nobody (no score)")
    if a.page:
        print(f"the page: {a.page} (closed with the match; `make run` at a terminal keeps it open until Ctrl-C)")
    else:
        print("the page: not built (build/web holds it when the browser SDK is built: it needs emscripten)")
    print(f"details: {a.dir} (bots.txt: every figure of the bots; server.log; stats.json; match.arpl)")


if __name__ == "__main__":
    main()
