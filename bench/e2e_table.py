#!/usr/bin/env python3
"""Tables for bench/e2e.sh from the server's --stats-json and the bots' --json files."""
import json
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
    return {
        "n": n,
        "tick": s["tick_ms"],
        "overruns": s["overruns"],
        "cpu_per_s": cpu / duration,
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


if __name__ == "__main__":
    if sys.argv[1] == "arena":
        arena_table(sys.argv[2], sys.argv[3:])
    else:
        colyseus_table(sys.argv[2])
