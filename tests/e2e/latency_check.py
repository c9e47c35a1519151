#!/usr/bin/env python3
"""latency_smoke.sh's verdict on bench/loss.sh's runs TRANSPORT-0-0 and TRANSPORT-0-MS (LOSS_WORK).

The link holds every packet MS each way, in the kernel's path, so for TCP and UDP alike the
bots' Ping round trip (p50) grows by 2 x MS (less a tick: a TCP Pong waits for the server's
tick) and by not much more (a link that held packets far longer, or twice, would be wrong
too), and an input takes at least MS more to reach the world (its lag grows by MS in ticks of
1/60 s, rounded down). Prints one line per transport and exits 1 on a failure.
"""
import sys

from run_reports import load

TICK_MS = 1000 / 60
SLACK_MS = 40  # scheduling on a busy 2-core machine, and TCP's wait for the next tick


def main():
    work, delay = sys.argv[1], float(sys.argv[2])
    failures = []
    for transport in ("tcp", "udp"):
        runs = [load(f"{work}/{transport}-0-{ms}.json") for ms in ("0", f"{delay:g}")]
        if any("error" in r for r in runs):
            failures.append(f"{transport}: no report ({' '.join(r.get('error', '') for r in runs)})")
            continue
        rtt = [r["figures"]["rtt_ms"]["p50"] for r in runs]
        lag = [r["figures"]["input_lag_ticks"]["p50"] for r in runs]
        print(f"{transport}: round trip p50 {rtt[0]:.1f} ms -> {rtt[1]:.1f} ms, input lag p50 {lag[0]:.0f} -> "
              f"{lag[1]:.0f} ticks, joined {runs[0]['joined']} and {runs[1]['joined']} of {runs[1]['bots']}")
        if min(r["joined"] for r in runs) < 1:
            failures.append(f"{transport}: no bot joined")
        # A TCP Pong waits for the server's next tick: its round trip varies by up to a tick.
        if not rtt[0] + 2 * delay - TICK_MS <= rtt[1] <= rtt[0] + 2 * delay + SLACK_MS:
            failures.append(f"{transport}: the round trip grew by {rtt[1] - rtt[0]:.1f} ms, not 2 x {delay:g} ms")
        if lag[1] - lag[0] < int(delay / TICK_MS):
            failures.append(f"{transport}: input lag grew by {lag[1] - lag[0]:.0f} ticks, under {delay:g} ms")
    for f in failures:
        print(f"FAILED: {f}")
    print("latency smoke test: " + ("failed" if failures else "passed"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
