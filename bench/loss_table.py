#!/usr/bin/env python3
"""make bench-loss's table: one row per run (transport, loss %, added latency), from the bots' --json."""
import json
import sys


def main():
    work, seconds, bots = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
    print("| transport | loss % | latency ms | joined | input lag ticks p50 / p99 / max | snapshot gap ms p99 / max "
          "| prediction error m p99 | bytes/s per client in / out | round trip ms p50 |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label in sys.argv[4:]:
        transport, loss, latency = label.split("-")
        try:
            with open(f"{work}/{label}.json") as f:
                r = json.load(f)
        except (OSError, ValueError):
            print(f"| {transport} | {loss} | {latency} | (no report) | | | | | |")
            continue
        fig = r["figures"]
        lag, gap, err, rtt = fig["input_lag_ticks"], fig["snapshot_gap_ms"], fig["prediction_error_m"], fig["rtt_ms"]
        per_client = max(1, r["joined"]) * max(r["seconds"], 1e-9)
        print(f"| {transport} | {loss} | {latency} | {r['joined']}/{r['bots']} "
              f"| {lag['p50']:.0f} / {lag['p99']:.0f} / {lag['max']:.0f} "
              f"| {gap['p99']:.0f} / {gap['max']:.0f} | {err['p99']:.3f} "
              f"| {r['totals']['bytes_in'] / per_client:.0f} / {r['totals']['bytes_out'] / per_client:.0f} "
              f"| {rtt['p50']:.0f} |")


if __name__ == "__main__":
    main()
