#!/usr/bin/env python3
"""Tables for bench/e2e.sh from the server's --stats-json and the bots' --json files."""
import json
import statistics
import sys


def load(path):
    with open(path) as f:
        return json.load(f)


def arena_row(work, label):
    s = load(f"{work}/{label}.server.json")
    b = load(f"{work}/{label}.bots.json")
    n = b["bots"]
    duration = s["duration_s"]
    cpu = s["process"]["cpu_user_s"] + s["process"]["cpu_system_s"]
    fig = b["figures"]
    try:
        steady = load(f"{work}/{label}.steady.json")["cpu_per_s"]
    except (OSError, KeyError, ValueError):
        steady = None  # a run from before the steady window was measured
    return {
        "n": n,
        "tick": s["tick_ms"],
        "overruns": s["overruns"],
        "cpu_per_s": cpu / duration,  # the whole run: start, joins and shutdown included
        "steady_cpu_per_s": steady,  # every client joined, as Colyseus' and the floor's figures are
        "rss_mb": s["process"]["peak_rss_kib"] / 1024,
        "out_per_client": s["bytes_out"] / duration / n,
        "joined": b["joined"],
        "snap_rate": fig["snapshots_per_s_per_bot"]["p50"],
        "rtt_p99": fig["rtt_ms"]["p99"],
        "view_radius": s.get("snapshots", {}).get("view_radius", 0),
        "deltas": b["totals"].get("delta_snapshots", 0) > 0,
        "in_view": fig.get("bodies_in_view", {}).get("mean", 0),
        "snapshot_bytes": fig.get("snapshot_bytes", {}).get("mean", 0),
        "bytes_per_body": b.get("bytes_per_body", 0),
        "payload_per_body": b.get("delta_payload_bytes_per_body", 0),
    }


def snapshots_kind(r):
    view = "whole world" if r["view_radius"] == 0 else f"{r['view_radius']:.0f} m view"
    return ("delta, " if r["deltas"] else "full, ") + view


def arena_table(work, labels):
    print("| bots | snapshots | joined | tick p50 / p99 / max ms | overruns | server CPU s per s | peak RSS MB | bytes out per client per s | bots' snapshots/s (p50) | RTT p99 ms | bodies in view | bytes per snapshot | bytes per body (codec) |")
    print("|---:|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for label in labels:
        r = arena_row(work, label)
        t = r["tick"]
        codec = f" ({r['payload_per_body']:.2f})" if r["deltas"] else ""
        print(f"| {r['n']} | {snapshots_kind(r)} | {r['joined']} | {t['p50']:.3f} / {t['p99']:.3f} / {t['max']:.3f} | {r['overruns']} | "
              f"{r['cpu_per_s']:.3f} | {r['rss_mb']:.1f} | {r['out_per_client']:.0f} | {r['snap_rate']:.1f} | {r['rtt_p99']:.2f} | "
              f"{r['in_view']:.1f} | {r['snapshot_bytes']:.0f} | {r['bytes_per_body']:.2f}{codec} |")


def last_json_line(path):
    """The last line of a run's output as JSON, or None when the run left none."""
    try:
        with open(path) as f:
            return json.loads(f.read().strip().splitlines()[-1])
    except (OSError, ValueError, IndexError):
        return None


def colyseus_table(work):
    c = last_json_line(f"{work}/colyseus.json")
    if c is None:
        print("Colyseus run failed: no JSON line (see its log).")
        return
    c_cpu = c["server_cpu_pct_of_core"] / 100
    c_bytes = c["recv_bytes_per_s_per_client"]
    print("| 200 clients | server CPU s per s | peak RSS MB | bytes per client per s |")
    print("|---|---:|---:|---:|")
    print(f"| Colyseus 0.18 (Node {c.get('node', '20')}) | {c_cpu:.3f} | {c['server_peak_rss_mb']:.1f} | {c_bytes:.0f} |")
    for label in ("arena-200-world", "arena-200"):
        a = arena_row(work, label)
        print(f"| Arena ({snapshots_kind(a)}) | {a['cpu_per_s']:.3f} | {a['rss_mb']:.1f} | {a['out_per_client']:.0f} |")
        print(f"| Colyseus / Arena ({snapshots_kind(a)}) | {c_cpu / a['cpu_per_s']:.1f}x | {c['server_peak_rss_mb'] / a['rss_mb']:.1f}x | {c_bytes / a['out_per_client']:.2f}x |")
    t = last_json_line(f"{work}/tcp-floor.json")
    if t is None:
        print("\nTCP floor run failed: no JSON line.")
        return
    print(f"| TCP floor: the same messages, no game, no framework | {t['server_cpu_s_per_s']:.3f} | | |")
    print()
    print(f"TCP floor (`arena-bench-tcp-floor`): {t['inputs_per_s']:.0f} inputs/s of {t['input_bytes']} B read with "
          f"{t['recv_calls_per_s']:.0f} recv/s after {t['epoll_waits_per_s']:.0f} epoll_wait/s, "
          f"{t['snapshot_sends_per_s']:.0f} snapshots/s of {t['snapshot_bytes']} B sent. "
          f"10x less CPU than Colyseus would be {c_cpu / 10:.3f} core; "
          f"the floor alone is {t['server_cpu_s_per_s']:.3f} ({t['server_cpu_s_per_s'] / (c_cpu / 10):.1f}x that).")


def rooms_table(work):
    a = arena_row(work, "arena-rooms")
    s = load(f"{work}/arena-rooms.server.json")
    b = load(f"{work}/arena-rooms.bots.json")
    matches = [m for m in s.get("matches", []) if m["mode"] == "room8"]
    gap = b["figures"].get("snapshot_gap_ms", {})
    per_match_ms = a["tick"]["mean"] / max(1, len(matches))
    print("| {} clients in matches of 8 | matches | server CPU s per s | whole run | peak RSS MB | bytes per client per s | snapshot gap p99 ms |".format(a["n"]))
    print("|---|---:|---:|---:|---:|---:|---:|")
    print(f"| Arena (delta, whole match in view) | {len(matches)} | {steady_cpu(a):.3f} | {a['cpu_per_s']:.3f} | {a['rss_mb']:.1f} | {a['out_per_client']:.0f} | {gap.get('p99', 0):.1f} |")
    c = last_json_line(f"{work}/colyseus-rooms.json")
    if c is not None:
        c_cpu = c["server_cpu_pct_of_core"] / 100
        print(f"| Colyseus 0.18, ROOM_SIZE=8 | {c.get('rooms', '')} | {c_cpu:.3f} | | {c['server_peak_rss_mb']:.1f} | {c['recv_bytes_per_s_per_client']:.0f} | |")
    t = last_json_line(f"{work}/tcp-floor-rooms.json")
    if t is not None:
        print(f"| TCP floor: the same messages, no game | | {t['server_cpu_s_per_s']:.3f} | | | | |")
    print()
    print("Server CPU is each server's steady state, every client joined (Colyseus after its 3 s warm-up, the floor "
          "after its last accept, Arena from 3 s after its bots start to 1 s before they stop); Arena's whole run "
          "counts its start, the joins and the shutdown as well.")
    of_colyseus, of_floor, _ = rooms_ratios(work)
    if of_colyseus is not None:
        print(f"Arena's CPU is {of_colyseus:.2f} of Colyseus's (goal: at most 0.33)", end="")
        if of_floor is not None:
            print(f", {of_floor:.2f}x the floor's (goal: at most 1.3)", end="")
        print(".")
    print(f"Whole tick p50 / p99 / max {a['tick']['p50']:.3f} / {a['tick']['p99']:.3f} / {a['tick']['max']:.3f} ms for "
          f"{len(matches)} matches: {per_match_ms:.3f} ms per 8-player match on average, so one core's 16.7 ms tick "
          f"holds about {16.667 / per_match_ms:.0f} such matches before ticks run late (tick work only; the transports "
          f"share the core).")


def steady_cpu(row):
    """A run's steady-state CPU, or its whole run's where the steady window was not measured."""
    return row["cpu_per_s"] if row["steady_cpu_per_s"] is None else row["steady_cpu_per_s"]


def rooms_ratios(work):
    """(Arena / Colyseus, Arena / floor) of one run's folder; None where a figure is missing."""
    row = arena_row(work, "arena-rooms")
    a = steady_cpu(row)
    c = last_json_line(f"{work}/colyseus-rooms.json")
    t = last_json_line(f"{work}/tcp-floor-rooms.json")
    return (a / (c["server_cpu_pct_of_core"] / 100) if c else None,
            a / t["server_cpu_s_per_s"] if t else None,
            row["cpu_per_s"] / t["server_cpu_s_per_s"] if t else None)


def rooms_median(works):
    runs = [rooms_ratios(w) for w in works]
    for k, (name, goal, unit) in enumerate([("Colyseus's", 0.33, ""), ("the floor's", 1.3, "x"),
                                             ("the floor's, Arena's whole run", None, "x")]):
        values = sorted(r[k] for r in runs if r[k] is not None)
        if not values:
            continue
        middle = statistics.median(values)
        listed = ", ".join(f"{v:.2f}{unit}" for v in values)
        aim = f"; goal: at most {goal}{unit}" if goal else ""
        print(f"Over {len(values)} runs, Arena's CPU against {name}: median {middle:.2f}{unit} ({listed}{aim}).")


def matches_table(work):
    m = last_json_line(f"{work}/matches.json")
    if m is None:
        print("arena-bench-matches failed: no JSON line.")
        return
    t = m["tick_ms"]
    print(f"The matches alone (`arena-bench-matches`: {m['matches']} matches of 8 players on one thread, the "
          f"transports' work left out): memory {m['empty_match_mib'] * 1024:.0f} KiB per empty match and "
          f"{m['full_match_mib'] * 1024:.0f} KiB per full one; the whole tick {t['p50']:.3f} / {t['p99']:.3f} / "
          f"{t['max']:.3f} ms (p50 / p99 / max), {m['per_match_ms_p99'] * 1000:.1f} us per match at the p99: "
          f"one core ticks about {m['matches_per_core_at_p99']:.0f} such matches at 60 Hz before its ticks run late.")


if __name__ == "__main__":
    if sys.argv[1] == "arena":
        arena_table(sys.argv[2], sys.argv[3:])
    elif sys.argv[1] == "rooms":
        rooms_table(sys.argv[2])
    elif sys.argv[1] == "rooms-median":
        rooms_median(sys.argv[2:])
    elif sys.argv[1] == "matches":
        matches_table(sys.argv[2])
    else:
        colyseus_table(sys.argv[2])
