#!/usr/bin/env python3
"""Tables for bench/e2e.sh from the server's --stats-json and the bots' --json files."""
import json
import sys


def load(path):
    with open(path) as f:
        return json.load(f)


def arena_row(work, label, n):
    s = load(f"{work}/{label}.server.json")
    b = load(f"{work}/{label}.bots.json")
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
    }


def arena_table(work, counts):
    print("| bots | joined | tick p50 / p99 / max ms | overruns | server CPU s per s | peak RSS MB | bytes out per client per s | bots' snapshots/s (p50) | RTT p99 ms |")
    print("|---:|---:|---|---:|---:|---:|---:|---:|---:|")
    for n in counts:
        r = arena_row(work, f"arena-{n}", int(n))
        t = r["tick"]
        print(f"| {r['n']} | {r['joined']} | {t['p50']:.3f} / {t['p99']:.3f} / {t['max']:.3f} | {r['overruns']} | "
              f"{r['cpu_per_s']:.3f} | {r['rss_mb']:.1f} | {r['out_per_client']:.0f} | {r['snap_rate']:.1f} | {r['rtt_p99']:.2f} |")


def colyseus_table(work):
    try:
        with open(f"{work}/colyseus.json") as f:
            c = json.loads(f.read().strip().splitlines()[-1])
    except (OSError, ValueError, IndexError):
        print("Colyseus run failed: no JSON line (see its log).")
        return
    a = arena_row(work, "arena-200", 200)
    c_cpu = c["server_cpu_pct_of_core"] / 100
    c_bytes = c["recv_bytes_per_s_per_client"]
    print("| 200 clients | server CPU s per s | peak RSS MB | bytes per client per s |")
    print("|---|---:|---:|---:|")
    print(f"| Colyseus 0.18 (Node {c.get('node', '20')}) | {c_cpu:.3f} | {c['server_peak_rss_mb']:.1f} | {c_bytes:.0f} |")
    print(f"| Arena | {a['cpu_per_s']:.3f} | {a['rss_mb']:.1f} | {a['out_per_client']:.0f} |")
    print(f"| Colyseus / Arena | {c_cpu / a['cpu_per_s']:.1f}x | {c['server_peak_rss_mb'] / a['rss_mb']:.1f}x | {c_bytes / a['out_per_client']:.2f}x |")


if __name__ == "__main__":
    if sys.argv[1] == "arena":
        arena_table(sys.argv[2], sys.argv[3:])
    else:
        colyseus_table(sys.argv[2])
