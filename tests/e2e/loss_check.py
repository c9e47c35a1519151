#!/usr/bin/env python3
"""loss_smoke.sh's verdict on bench/loss.sh's runs udp-0-0 and udp-5-0 (LOSS_WORK folder).

Each input the bots sent over UDP must reach the world: the server counts `inputs_lost`
(sequences that neither came nor were repeated in a later Input's `earlier` list), and it must
be 0 with and without loss. At 5 % loss some Inputs were lost on the wire, so the world took
some inputs from later Inputs' lists (`inputs_recovered` > 0): the redundant inputs did it.
Every bot joined and kept receiving snapshots. Prints one line per run and exits 1 on a failure.
"""
import sys

from run_reports import load


def main():
    work, bots = sys.argv[1], int(sys.argv[2])
    failures = []
    for loss in ("0", "5"):
        label = f"udp-{loss}-0"
        server, fleet = load(f"{work}/{label}.stats.json"), load(f"{work}/{label}.json")
        if "error" in server or "error" in fleet:
            failures.append(f"{label}: no report ({server.get('error') or fleet.get('error')})")
            continue
        lag = fleet["figures"]["input_lag_ticks"]
        gap = fleet["figures"]["snapshot_gap_ms"]
        print(f"{label}: joined {fleet['joined']}/{fleet['bots']}, inputs received {server['inputs_received']}, "
              f"recovered {server['inputs_recovered']}, lost {server['inputs_lost']}, "
              f"input lag ticks p99 {lag['p99']:.0f}, snapshot gap ms p99 {gap['p99']:.0f}")
        if fleet["joined"] != bots:
            failures.append(f"{label}: {fleet['joined']} of {bots} bots joined")
        if server["inputs_received"] < bots * 60:
            failures.append(f"{label}: only {server['inputs_received']} inputs reached the server")
        if server["inputs_lost"] != 0:
            failures.append(f"{label}: {server['inputs_lost']} inputs never reached the world (an input gap)")
        if loss != "0" and server["inputs_recovered"] == 0:
            failures.append(f"{label}: no input was recovered from an earlier list: was any packet dropped?")
        if fleet["totals"]["snapshots"] < bots * 20:
            failures.append(f"{label}: only {fleet['totals']['snapshots']} snapshots reached the bots")
    for f in failures:
        print(f"FAILED: {f}")
    print("loss smoke test: " + ("failed" if failures else "passed"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
