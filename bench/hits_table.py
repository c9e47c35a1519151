#!/usr/bin/env python3
"""make bench-hits' table: one row per run (round trip, lag compensation), from the bots' --json."""
import json
import sys


def main():
    work, jitter = sys.argv[1], sys.argv[2]
    print("| round trip ms | compensation ms | claimed hits | confirmed % | unconfirmed: taken first by another "
          "| server hits | unclaimed % | victims' hit after seen ms p50 / p99 (ships) | measured round trip ms p50 |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label in sys.argv[3:]:
        rtt, compensation = label.split("-")
        shown = f"{rtt} ± {jitter}" if rtt != "0" else "0"
        try:
            with open(f"{work}/{label}.json") as f:
                r = json.load(f)
        except (OSError, ValueError):
            print(f"| {shown} | {compensation} | (no report) | | | | | | |")
            continue
        h = r["hit_registration"]
        server_hits = h["confirmed"] + h["unclaimed_hits"]
        confirmed = 100.0 * h["confirmed"] / h["claimed"] if h["claimed"] else 0.0
        unclaimed = 100.0 * h["unclaimed_hits"] / server_hits if server_hits else 0.0
        seen = r["figures"].get("hit_after_seen_ms", {"count": 0})
        victims = f"{seen['p50']:.0f} / {seen['p99']:.0f} ({seen['count']})" if seen["count"] else "(no ship lost)"
        unconfirmed = h["claimed"] - h["confirmed"]
        contested = f"{h.get('contested', 0)} of {unconfirmed}"
        print(f"| {shown} | {compensation} | {h['claimed']} | {confirmed:.1f} | {contested} | {server_hits} | {unclaimed:.1f} "
              f"| {victims} | {r['figures']['rtt_ms']['p50']:.0f} |")


if __name__ == "__main__":
    main()
