#!/usr/bin/env python3
"""JSON lines from arena-bench and from ../shared/peers/box2d/run_all.py -> one markdown table.

  bench/table.py ARENA.jsonl [BOX2D.jsonl] [--note TEXT]...

Box2D-scene rows are paired by N and repetition (run_all.py interleaves the engines), so the
speed ratio is the median of ratios taken from runs seconds apart; times are the best of R.
"""
import json
import statistics
import sys

BOX2D_V3_MS = {1000: 0.314, 10000: 5.61, 100000: 133.4}      # ../shared/peers/box2d/README.md, 2026-11-21
BOX2D_24_OVERLAPS = {1000: 66, 10000: 725, 100000: 4266}


def load(path):
    try:
        with open(path) as f:
            return [json.loads(line) for line in f if line.strip().startswith("{")]
    except FileNotFoundError:
        return []


def ok(flag):
    return "**met**" if flag else "**not met**"


def bandwidth_table(rows):
    """Bandwidth: full against delta snapshots per (players, view radius), from the same run."""
    bw = [r for r in rows if r["bench"] == "bandwidth"]
    if not bw:
        return
    print()
    print("Bandwidth: every player moving (thrust and turn re-chosen every 0.5 s), each client")
    print("acknowledging a snapshot 100 ms after it arrived; bytes are whole frames (length prefix and FlatBuffers")
    print("included), \"codec\" the delta bytes alone; tick = world step + that tick's share of the snapshots.")
    print()
    print("| players (bodies) | view | snapshots | bodies in view | bytes per snapshot | bytes per body (codec) | bytes per client per s | full / delta | tick p50 / p99 ms | decode errors |")
    print("|---|---|---|---:|---:|---|---:|---|---|---:|")
    full = {(r["players"], r["view_radius"]): r for r in bw if r["mode"] == "full"}
    whole = {r["players"]: r for r in bw if r["mode"] == "full" and r["view_radius"] == 0}
    for r in bw:
        view = "whole world" if r["view_radius"] == 0 else "%.0f m" % r["view_radius"]
        codec = " (%.2f; ≤ 4: %s)" % (r["payload_bytes_per_body"], ok(r["payload_bytes_per_body"] <= 4)) if r["mode"] == "delta" else ""
        ratio = ""
        if r["mode"] == "delta":
            parts = []
            f = full.get((r["players"], r["view_radius"]))
            if f:
                parts.append("%.1f× same view" % (f["bytes_per_snapshot"] / r["bytes_per_snapshot"]))
            w = whole.get(r["players"])
            if w and r["view_radius"] != 0:
                x = w["bytes_per_snapshot"] / r["bytes_per_snapshot"]
                parts.append("%.1f× whole-world full; ≥ 8×: %s" % (x, ok(x >= 8)) if r["players"] == 256 else "%.1f× whole-world full" % x)
            elif f and r["players"] == 256:
                x = f["bytes_per_snapshot"] / r["bytes_per_snapshot"]
                parts[-1] += "; ≥ 8×: %s" % ok(x >= 8)
            ratio = ", ".join(parts)
        print("| %d (%d) | %s | %s | %.1f | %.0f | %.2f%s | %.0f | %s | %.3f / %.3f | %d |" % (
            r["players"], r["bodies"], view, r["mode"], r["bodies_per_snapshot"], r["bytes_per_snapshot"], r["bytes_per_body"],
            codec, r["bytes_per_client_per_s"], ratio, r["tick_ms_median"], r["tick_ms_p99"], r["errors"]))


def game_bandwidth_table(rows):
    """Asteroids played as a game: every player firing, the game's lines, names and events on top."""
    gb = [r for r in rows if r["bench"] == "game_bandwidth"]
    if not gb:
        return
    print()
    print("Game bandwidth: Asteroids rules, every player firing as often as the cooldown allows, delta snapshots")
    print("acknowledged 100 ms after arrival; \"game\" is the players' lines, names and events a snapshot carries.")
    print()
    print("| players | view | shots / hits / kills | bodies in view | bytes per snapshot | codec bytes per body | game bytes per snapshot | events per snapshot | bytes per client per s | tick p50 / p99 ms | decode errors |")
    print("|---:|---|---|---:|---:|---|---:|---:|---:|---|---:|")
    for r in gb:
        print("| %d | %.0f m | %d / %d / %d | %.1f | %.0f | %.2f (≤ 4: %s) | %.1f | %.2f | %.0f | %.3f / %.3f | %d |" % (
            r["players"], r["view_radius"], r["shots"], r["hits"], r["kills"], r["bodies_per_snapshot"],
            r["bytes_per_snapshot"], r["payload_bytes_per_body"], ok(r["payload_bytes_per_body"] <= 4),
            r["game_bytes_per_snapshot"], r["events_per_snapshot"], r["bytes_per_client_per_s"],
            r["tick_ms_median"], r["tick_ms_p99"], r["errors"]))


def pyramid_table(rows):
    """Box2D's pyramid scenes, Arena and Box2D 2.4.1 in one process (arena-bench-pyramids)."""
    pyr = [r for r in rows if r["bench"] == "pyramids"]
    if not pyr:
        return
    print()
    print("Pyramids (Box2D v3's benchmark scenes and steps): 1 m boxes, μ 0.6, gravity −10 m/s², steps of 1/60 s")
    print("in %d sub-steps of 8 velocity + 3 position iterations, Box2D sleeping off; CPU ms per step of 1/60 s"
          % pyr[0].get("sub_steps", 1))
    print("(the thread's CPU time, best of the runs), engines alternating in one process. Standing: every box")
    print("of a pyramid ends within 0.5 m of its start; drift: the farthest box, m.")
    print()
    print("| scene | boxes | steps | Arena ms/step | Box2D 2.4.1 ms/step | Arena / Box2D | standing (Arena, Box2D) | drift (Arena, Box2D) | target |")
    print("|---|---:|---:|---:|---:|---:|---|---|---|")
    scenes = []
    for r in pyr:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])

    def standing(r):
        if "pyramids" not in r:
            return "yes" if r["standing"] else "**fell**"
        return "%d/%d" % (r["pyramids_standing"], r["pyramids"]) + ("" if r["standing"] else " **fell**")

    for name in scenes:
        ours = next((r for r in pyr if r["scene"] == name and r["engine"] == "arena"), None)
        theirs = next((r for r in pyr if r["scene"] == name and r["engine"] != "arena"), None)
        if not ours or not theirs:
            continue
        ratio = ours["cpu_ms_per_step"] / theirs["cpu_ms_per_step"]
        target = "≤ 0.5×: " + ok(ratio <= 0.5 and ours["standing"]) if name == "large_pyramid" else ""
        drift = "%.3f, %.3f" % (ours.get("worst_box_drift_m", ours["worst_top_drift_m"]),
                                theirs.get("worst_box_drift_m", theirs["worst_top_drift_m"]))
        print("| %s | %d | %d | %.3f | %.3f | %.2f× | %s, %s | %s | %s |" % (
            name, ours["boxes"], ours["steps"], ours["cpu_ms_per_step"], theirs["cpu_ms_per_step"], ratio,
            standing(ours), standing(theirs), drift, target))


PHASES = ["inputs", "forces_velocities", "broadphase", "narrow_phase", "solver", "positions", "correction"]


def profile_table(rows):
    """The world step by phase (world::step_profile), from the best run of each N."""
    prof = [r for r in rows if r["bench"] == "world_step" and "profile_ms" in r]
    if not prof:
        return
    print()
    print("World step by phase: mean ms per step, timed apart from the runs above (as many steps again)")
    print()
    print("| N | " + " | ".join(p.replace("_", " ") for p in PHASES) + " | sum |")
    print("|---:|" + "---:|" * (len(PHASES) + 1))
    for r in prof:
        p = r["profile_ms"]
        print("| %d | " % r["n"] + " | ".join("%.4f" % p[k] for k in PHASES) + " | %.4f |" % sum(p[k] for k in PHASES))


def best_runs(rows):
    """run.sh repeats the step and integration cases: keep, per case and N, the run with the best
    median (the same policy as the Box2D scene's best of R), in first-seen order, with the count."""
    key_of = {"world_step": "ms_per_step_median", "integrate": "integrate_ms_median"}
    best, order = {}, []
    for r in rows:
        if r["bench"] not in key_of:
            order.append(r)
            continue
        k = (r["bench"], r["n"])
        if k not in best:
            best[k] = dict(r, runs=0)
            order.append(k)
        best[k]["runs"] += 1
        if r[key_of[r["bench"]]] < best[k][key_of[r["bench"]]]:
            best[k] = dict(r, runs=best[k]["runs"])
    return [best[x] if isinstance(x, tuple) else x for x in order]


def main(argv):
    notes, paths = [], []
    i = 0
    while i < len(argv):
        if argv[i] == "--note":
            notes.append(argv[i + 1])
            i += 2
        else:
            paths.append(argv[i])
            i += 1
    rows = best_runs(load(paths[0])) if paths else []
    peer = load(paths[1]) if len(paths) > 1 else []
    out = []
    add = out.append
    add("| # | benchmark | N | median | p90 | per unit | target |")
    add("|---|---|---:|---:|---:|---|---|")
    for r in rows:
        b = r["bench"]
        if b == "world_step":
            n = r["n"]
            target = ""
            if n == 10000:
                target = "≤ 1 ms: " + ok(r["ms_per_step_median"] <= 1.0)
            elif n == 100000:
                target = "≤ 16.6 ms: " + ok(r["ms_per_step_median"] <= 16.6)
            add("| 1 | world step, asteroids, collisions (best of %d runs of %d steps, %.0f m side, %d contacts) | %d | %.3f ms | %.3f ms | %.0f ns/body | %s |" % (
                r["runs"], r["steps"], r["world_side_m"], r["contacts_last_step"], n, r["ms_per_step_median"], r["ms_per_step_p90"],
                r["ns_per_body"], target))
        elif b == "integrate":
            add("| 2 | integration alone: forces + semi-implicit Euler (best of %d runs; %d B/body, %.0f MB) | %d | %.2f ms | %.2f ms | %.1f ns/body, %.2f GB/s | |" % (
                r["runs"], r["body_bytes"], r["bytes"] / 1e6, r["n"], r["integrate_ms_median"], r["integrate_ms_p90"],
                r["ns_per_body"], r["integrate_gb_per_s"]))
            add("| 2 | streaming copy (memcpy) of the same bytes, same run | %d | %.2f ms | %.2f ms | %.2f GB/s | integration/copy = **%.2f×**; ≤ 2×: %s |" % (
                r["n"], r["copy_ms_median"], r["copy_ms_p90"], r["copy_gb_per_s"], r["ratio"], ok(r["ratio"] <= 2.0)))
        elif b == "snapshot":
            add("| 3 | snapshot build (world → BodyState + snapshot_encoder::build) | %d | %.4f ms | %.4f ms | %.3g bodies/s, %.2f B/body on the wire (%d B frame) | |" % (
                r["n"], r["build_ms_median"], r["build_ms_p90"], r["bodies_per_s"], r["bytes_per_body"], r["frame_bytes"]))
            add("| 3 | snapshot copy_with_ack, %d clients | %d | %.4f ms | | %.2f µs/client, %.3g bodies/s | |" % (
                r["clients"], r["n"], r["copy_all_clients_ms_median"], r["copy_per_client_us"], r["body_copies_per_s"]))
        elif b == "replay":
            add("| 4 | replay, %d players (%d bodies), %d ticks, %d hashes checked | %d | %.1f ms | | %.0f ticks/s = **%.0f× real time** (60 Hz) | ≥ 100×: %s |" % (
                r["players"], r["bodies"], r["ticks"], r["hashes_checked"], r["players"], r["ms_median"], r["ticks_per_s"],
                r["x_real_time"], ok(r["x_real_time"] >= 100)))
    # Box2D scene: best of R per engine and N, paired ratio per N.
    by = {}
    for r in peer:
        by.setdefault((r["n"], r["engine"]), []).append(r)
    for n in sorted({k[0] for k in by}):
        ours = by.get((n, "arena"), [])
        theirs = [r for (m, e), rs in by.items() if m == n and e != "arena" for r in rs]
        ratios = []
        pairs = {}
        for r in ours + theirs:
            pairs.setdefault((r.get("batch"), r.get("rep")), {})[r["engine"] == "arena"] = r
        for p in pairs.values():
            if True in p and False in p:
                ratios.append(p[False]["ms_per_step_median"] / p[True]["ms_per_step_median"])
        if ours:
            best = min(ours, key=lambda r: r["ms_per_step_median"])
            v3 = BOX2D_V3_MS.get(n)
            speed = "%.1f× Box2D v3 (%.3g ms)" % (v3 / best["ms_per_step_median"], v3) if v3 else ""
            overl = BOX2D_24_OVERLAPS.get(n)
            target = ""
            if v3 and overl is not None:
                target = "≥ 5× v3: %s; overlaps ≤ %d: %s" % (ok(v3 / best["ms_per_step_median"] >= 5), overl,
                                                            ok(best["overlaps_last_step"] <= overl))
            add("| 7 | Box2D scene, Arena (best of %d, %d steps; %d overlaps, mean speed %.3f m/s) | %d | %.3f ms | %.3f ms | %s | %s |" % (
                len(ours), best["steps"], best["overlaps_last_step"], best["mean_speed"], n, best["ms_per_step_median"],
                best["ms_per_step_p90"], speed, target))
        if theirs:
            best = min(theirs, key=lambda r: r["ms_per_step_median"])
            ratio = " Box2D/Arena paired: **%.1f×** (%.1f..%.1f)" % (statistics.median(ratios), min(ratios), max(ratios)) if ratios else ""
            add("| 7 | Box2D scene, %s %s, same run (best of %d; %d overlaps, mean speed %.3f m/s) | %d | %.3f ms | %.3f ms |%s | |" % (
                best["engine"], best["version"], len(theirs), best["overlaps_last_step"], best["mean_speed"], n,
                best["ms_per_step_median"], best["ms_per_step_p90"], ratio))
    print("\n".join(out))
    profile_table(rows)
    bandwidth_table(rows)
    game_bandwidth_table(rows)
    pyramid_table(rows)
    for note in notes:
        print()
        print(note)


if __name__ == "__main__":
    main(sys.argv[1:])
