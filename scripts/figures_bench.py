"""The documented figures that ``python -m benchmarks ...`` (and the package's catalog)
produce: for each, the command, how its JSON renders as a doc block, and which part of it
is deterministic. ``scripts/docs_figures.py`` runs, writes and checks them; each data file
``docs/figures/NAME.json`` holds the command's JSON with the build, machine and load it
was measured on (``figures_run.measured``)."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

from figures_run import ROOT, command_text, header, measured, run_cli_json

FIGURE_DATA = ROOT / "docs" / "figures"
Doc = dict[str, Any]


def _cmd(*commands: tuple[str, list[str]]) -> Callable[[str], Doc]:
    """A figure's ``run(profile)``: each ``(key, args)`` is one CLI call; one call's JSON is
    the result, several are keyed."""

    def run(profile: str) -> Doc:
        text = " && ".join(command_text(a) for _, a in commands)

        def body() -> Any:
            out = {k: run_cli_json(a) for k, a in commands}
            return out[commands[0][0]] if len(commands) == 1 else out

        return measured(text, profile, body)

    return run


def _td(t: float | None, d: float | None) -> str:
    return "never" if t is None or d is None else f"{t:.2f} s, {d:.2f} m"


def _frac(a: int, b: int, bold: bool = False) -> str:
    if b == 0:
        return "–"
    return f"**{a}/{b}**" if bold else f"{a}/{b}"


def _n(x: float, digits: int = 0) -> str:
    return f"{x:,.{digits}f}"


# ---------------------------------------------------------------- bench fidelity (deterministic)
def fidelity_block(doc: Doc) -> str:
    r = doc["result"]
    s, gs, b, gb = r["straight"], r["gym_straight"], r["braking"], r["gym_braking"]
    sel = {(1, 0.288), (2, 0.192), (3, 0.128), (4, 0.064), (4, 0.192), (5, 0.128), (6, 0.128), (6, 0.288)}
    turns = [t for t in r["turns"] if (round(t["v"]), round(t["steer"], 3)) in sel]
    mug = r["mu_g"]
    rows = "\n".join(
        f"| {t['v']:g} | {t['steer']:.3f} | {t['yaw_rate']:.3f} | {t['linear_yaw_rate']:.3f} | "
        f"{t['yaw_rate'] / t['linear_yaw_rate']:.3f} | {t['lat_acc']:.2f} | {t['lat_acc'] / mug:.2f} | "
        + ("–" if t["qs_lat_acc"] is None else f"{t['qs_lat_acc']:.2f}")
        + f" | {t['gym_yaw_rate']:.3f} | {t['gym_lat_acc']:.2f} |"
        for t in turns
    )
    lim = "\n".join(
        f"| {x['v']:g} | {x['ours_peak']:.2f} | {x['qs_limit']:.2f} ({x['qs_steer']:.3f} rad) | "
        f"{x['qs_limit'] / mug:.3f} | {x['qs_drive_force']:.1f} N | {x['qs_inner_front_load']:.1f} N | "
        f"{x['qs_load_split_limit']:.2f} ({x['qs_load_split_limit'] / mug:.3f} mu g) |"
        for x in r["limit"]
    )
    dts = "\n".join(
        f"| {d['dt']:g} | {d['yaw_rate_3ms_0.2']:.4f} | {d['brake_t']:.3f} s | {d['brake_d']:.3f} m |"
        for d in r["dt_sensitivity"]
    )
    env = r["envelope"]
    peaks = ", ".join(f"{float(v):g} m/s {y:.2f}" for v, y in r["step_steer_peak_yaw"].items())
    return (
        header(doc, "fidelity", timed=False)
        + "\n| straight line and braking | ours | F1TENTH Gym ST | reference |\n|---|---:|---:|---|\n"
        f"| top speed (max_speed raised to 25) | {s['top_speed']:.2f} m/s | {gs['top_speed']:.2f} m/s (its `v_max`) | "
        "duty-limited no-load 16.0 m/s (Velineon 3500 kV, 3S 11.1 V, F1TENTH gearing) |\n"
        + f"| 0 → 6.66 m/s | {_td(s['t_0_to_6_66'], s['d_0_to_6_66'])} | {_td(gs['t_0_to_6_66'], gs['d_0_to_6_66'])} | at mu g: 0.82 s, 2.72 m |\n"
        f"| brake 6 → 0 m/s (0 m/s command) | {_td(b['t'], b['d'])} | {_td(gb['t'], gb['d'])} | "
        f"ideal mu g stop {_td(b['t_ideal'], b['d_ideal'])} |\n"
        f"\nSteady cornering, selected rows (mu g = {mug:.2f} m/s²):\n\n"
        "| v (m/s) | steer (rad) | r ours | r linear | ours / linear | a ours (m/s²) | a / mu g | a QS | r gym | a gym |\n"
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n" + rows + "\n\n"
        "| v (m/s) | ours, peak of the grid | QS limit (best steer) | QS limit / mu g | drive to hold speed | "
        "inner front load | QS, drive shared by load |\n|---:|---:|---:|---:|---:|---:|---:|\n" + lim + "\n\n"
        "| dt (s) | r at 3 m/s, 0.192 rad | brake 6 → 0 time | distance |\n|---:|---:|---:|---:|\n" + dts + "\n\n"
        f"Envelope: the steady non-sliding yaw-rate bound peaks at {env['r_max']:.2f} rad/s at {env['v_at_r_max']:.2f} m/s; "
        f"the recorded 5.46 rad/s would need mu ≥ {env['mu_needed_for_recorded']:.2f}. Full-lock step steer, peak yaw "
        f"rate (rad/s): {peaks}.\n"
    )


def fidelity_deterministic(doc: Doc) -> Any:
    return doc["result"]


# ---------------------------------------------------------------- bench parser (scores deterministic)
def parser_block(doc: Doc) -> str:
    r = doc["result"]
    row = r["rows"]["rules"]
    lat = row["latency_median_s"]
    lines = [
        header(doc, "parser"),
        "| parser | request set | Parse | Audit pass | Refusals | Latency (median) | Memory |",
        "|---|---|---|---|---|---|---|",
        f"| `rules` (ours, no model) | shipped `benchmarks/data/requests.jsonl` | {_frac(row['parse_exact'], row['parse_total'], True)} "
        f"| {_frac(row['audit_pass'], row['audit_calls'], True)} | {_frac(row['refuse_correct'], row['refuse_total'])} | "
        f"{lat * 1e3:.2f} ms | {row['peak_rss_delta_mb']:.1f} MB RSS delta |",
    ]
    for name, srow in (r.get("sets") or {}).items():
        lines.append(
            f"| `rules` | {name} | {_frac(srow['parse_exact'], srow['parse_total'])} | {_frac(srow['audit_pass'], srow['audit_calls'])} "
            f"| {_frac(srow['refuse_correct'], srow['refuse_total'])} | "
            + ("–" if srow["latency_median_s"] is None else f"{srow['latency_median_s'] * 1e3:.2f} ms")
            + " | |"
        )
    return "\n".join(lines) + "\n"


def parser_deterministic(doc: Doc) -> Any:
    keep = ("parse_exact", "parse_total", "audit_pass", "audit_calls", "refuse_correct", "refuse_total", "misses")
    r = doc["result"]
    rows = {"rules": r["rows"]["rules"], **(r.get("sets") or {})}
    return {k: {f: v[f] for f in keep} for k, v in rows.items()}


# ---------------------------------------------------------------- the shipped catalog (deterministic)
CATALOG = ROOT / "python" / "roboracer_arena" / "tracks" / "catalog.json"


def catalog_run(profile: str) -> Doc:
    def body() -> Any:
        cat = json.loads(CATALOG.read_text())
        left = [x["reason"] for x in cat["left_out"]]
        return {
            "counts": cat["counts"],
            "tracks": len(cat["tracks"]),
            "open_maps": len(cat["open_maps"]),
            "left_out": len(left),
            "duplicates": sum(x.startswith("duplicate") for x in left),
            "broken": sum(x.startswith("broken") for x in left),
        }

    return measured("python/roboracer_arena/tracks/catalog.json (roboracer-arena tracks catalog)", profile, body)


def catalog_readme_block(doc: Doc) -> str:
    r = doc["result"]
    rec = r["counts"]["recorded"]
    return (
        f"| recorded maps ({rec + r['left_out']} source maps) | count |\n|---|---|\n"
        f"| tracks (lap verified) | {rec} |\n| open maps (walls only) | {r['open_maps']} |\n"
        f"| **usable (tracks + open maps)** | **{rec + r['open_maps']}** (paper: 74) |\n"
        f"| duplicates (identical grid) | {r['duplicates']} |\n| broken (image missing) | {r['broken']} |\n"
    )


def catalog_bench_block(doc: Doc) -> str:
    r = doc["result"]
    c = r["counts"]
    return (
        f"Catalog (`tracks/catalog.json`): **{r['tracks']} tracks** — {c['circuit']} circuits at 1:10, "
        f"{c['recorded']} recorded maps (referenced in `../shared/track-sources`, not copied), {c['generated']} "
        f"requirement-generated; {r['left_out']} recorded maps left out with a reason, {r['open_maps']} of them "
        f"usable as open maps (the paper: 130 tracks, no drivability check).\n"
    )


def catalog_deterministic(doc: Doc) -> Any:
    return doc["result"]


# ---------------------------------------------------------------- bench library (lengths deterministic)
# Why two bacinger circuits are kept beside a TUM one of the same venue (checked by hand).
LAYOUT_NOTES = {
    "indianapolis-road-course": "layout differs from TUM ims",
    "yas-marina-2009": "layout differs from TUM yas-marina",
}


def library_block(doc: Doc) -> str:
    r = doc["result"]
    p = r["paper"]
    head = (
        header(doc, "library") + "\n| | ours | paper |\n|---|---:|---:|\n"
        f"| circuits built | {r['built']} | {p['circuits']} |\n"
        f"| wall time, whole set ({r['jobs']} threads) | {r['seconds']:.2f} s | {p['seconds']} s |\n"
        f"| centreline-length error, mean over {r['measured_circuits']} | {r['mean_error_pct']:.3f} % | {p['mean_error_pct']} % |\n"
        f"| centreline-length error, max | {r['max_error_pct']:.3f} % | {p['max_error_pct']} % |\n\n"
        "| circuit | source | lap (m) | error (%) | width mean / min (m) | narrowed | raster (px) | notes |\n"
        "|---|---|---:|---:|---:|---:|---:|---|\n"
    )
    rows = []
    for c in r["per_circuit"]:
        ras = c["raster"] or {}
        err = "n/a" if c["grade_separated"] else f"{c['length_error'] * 100:.3f}"
        note = "grade-separated crossing" if c["grade_separated"] else LAYOUT_NOTES.get(c["id"], "")
        rows.append(
            f"| {c['id']} | {c['source']} | {c['lap_length_m']:.1f} | {err} | {c['width_mean_m']:.2f} / "
            f"{c['width_min_m']:.2f} | {c['narrowed_fraction'] * 100:.1f} % | {ras.get('width_px', '?')}×{ras.get('height_px', '?')} | {note} |"
        )
    return head + "\n".join(rows) + "\n"


def library_deterministic(doc: Doc) -> Any:
    r = doc["result"]
    keep = (
        "id",
        "source",
        "lap_length_m",
        "length_error",
        "width_mean_m",
        "width_min_m",
        "narrowed_fraction",
        "raster",
    )
    return {
        "built": r["built"],
        "mean_error_pct": r["mean_error_pct"],
        "max_error_pct": r["max_error_pct"],
        "per_circuit": [{k: c[k] for k in keep} for c in r["per_circuit"]],
    }


# ---------------------------------------------------------------- bench physics (measured)
def physics_block(doc: Doc) -> str:
    from benchmarks.physics import PAPER
    from roboracer_arena.bench.physics import TARGETS

    res = doc["result"]
    lines = [
        header(doc, "physics"),
        "| `bench physics` | vehicles (envs × cars) | rapier steps | vehicle-steps/s | paper (Isaac Sim) | target |",
        "|---|---|---:|---:|---:|---:|",
    ]
    for key, label in (
        ("shortcut", "contact-free shortcut (default)"),
        ("no_shortcut", "rapier pipeline every step (`--no-shortcut`)"),
    ):
        for i, row in enumerate(res[key]["rows"]):
            n, target = row["vehicles"], TARGETS.get(row["vehicles"])
            ok = "–" if target is None else f"≥ {target:,.0f} " + ("✓" if row["vehicle_steps_per_s"] >= target else "✗")
            lines.append(
                f"| {label if i == 0 else ''} | {n} ({row['envs']} × {row['per_env']}) | {row['rapier_pipeline_fraction']:.0%} | "
                f"{_n(row['vehicle_steps_per_s'])} | {PAPER[n]:,g} | {ok} |"
            )
    s = res["shortcut"]["scan"]
    lines.append(
        f"\nOne {s['beams']}-beam scan (exact 2D, stadium track): {s['scan_us_median']:.1f} µs median of {s['repeats']}. "
        f"Physics: lidar off, dt = {res['shortcut']['rows'][0]['dt'] * 1e3:g} ms, {res['shortcut']['rows'][0]['substeps']} "
        "physics steps per `Simulator.step`; a vehicle-step is one physics step of one car."
    )
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- bench env (measured)
def env_block(doc: Doc) -> str:
    from roboracer_arena.bench.env import TARGET_SCAN_US, TARGET_SINGLE_US, TARGET_VECTOR

    r = doc["result"]
    lo, hi = r["f1tenth_gym_env_steps_per_s"]
    lines = [
        header(doc, "env"),
        f"Map {r['map']}, {r['beams']}-beam lidar every step, {r['physics_dt']} s physics step, autoreset on collision; "
        f"F1TENTH Gym: {lo:,.0f}–{hi:,.0f} env-steps/s (constant action, single env; the figure issue 14 quotes, "
        "from another machine; the ratio measured in one run on this machine is in the `peer` table below).\n",
        "| workload | envs | env-steps/s (wall) | per CPU-second | × F1TENTH Gym (wall) | µs/call: physics / scan / Python | target |",
        "|---|---:|---:|---:|---:|---|---|",
    ]
    for row in r["rows"]:
        b = row["breakdown_us_per_call"]
        if row["num_envs"] == 1:
            t = (
                f"≤ {TARGET_SINGLE_US:.0f} µs/step " + ("✓" if row["us_per_step"] <= TARGET_SINGLE_US else "✗")
                if row["workload"] == "constant"
                else "–"
            )
            rate = f"{_n(row['env_steps_per_s'])} ({row['us_per_step']:.1f} µs/step)"
        else:
            tv = TARGET_VECTOR.get(row["workload"])
            t = "–" if tv is None else f"≥ {tv:,.0f} " + ("✓" if row["env_steps_per_s"] >= tv else "✗")
            rate = _n(row["env_steps_per_s"])
        lines.append(
            f"| {row['workload']} | {row['num_envs']} | {rate} | {_n(row['env_steps_per_s'] * row['seconds'] / max(row['cpu_seconds'], 1e-9))} | "
            f"{row['env_steps_per_s'] / ((lo + hi) / 2):.1f}× | "
            f"{b['physics']:.1f} / {b['scan']:.1f} / {b['python']:.1f} | {t} |"
        )
    s = r["scan_over_lap"]
    ok = "✓" if s["median_us"] <= TARGET_SCAN_US else "✗"
    lines.append(
        f"\nOne {s['beams']}-beam scan, median over {s['poses']} centreline poses around the lap: **{s['median_us']:.1f} µs** "
        f"(p90 {s['p90_us']:.1f}, max {s['max_us']:.1f}), target ≤ {TARGET_SCAN_US:.0f} µs {ok}."
    )
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- bench peer (measured; needs F1TENTH Gym)
def peer_block(doc: Doc) -> str:
    r = doc["result"]
    x, y, yaw = r["start_pose"]
    lines = [
        header(doc, "peer"),
        f"Map {r['map']}, both from the grid start ({x:.2f}, {y:.2f}, {yaw:.2f} rad), action [0 rad, 1 m/s], 1080 beams "
        "every 0.01 s step, reset on collision; F1TENTH Gym (`f110_gym` from its repository, under its own venv) "
        "then ours (`gymnasium.make`, standard wrappers), alternating.\n",
        "| pair | F1TENTH Gym env-steps/s | ours env-steps/s | ours ÷ F1TENTH Gym (wall) | per CPU-second |",
        "|---:|---:|---:|---:|---:|",
    ]
    for i, pr in enumerate(r["pairs"], 1):
        f = pr["f1tenth_gym"]
        lines.append(
            f"| {i} | {_n(f['steps'] / f['seconds'])} | {_n(pr['ours']['steps'] / pr['ours']['seconds'])} | "
            f"{pr['ratio_wall']:.2f}× | {pr['ratio_cpu']:.2f}× |"
        )
    ok = "✓" if r["median_ratio_wall"] >= r["target_ratio"] else "✗"
    lines.append(
        f"\nMedian of the pairs: **{r['median_ratio_wall']:.2f}×** wall, {r['median_ratio_cpu']:.2f}× per CPU-second; "
        f"target ≥ {r['target_ratio']:g}× {ok}."
    )
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- bench build (timing measured; sizes, IoU deterministic)
def build_block(doc: Doc) -> str:
    r = doc["result"]
    lines = [
        header(doc, "build"),
        f"{r['repeat']} builds per size, {r['threads']} thread(s) each, in its own subprocess. s = median wall of the in-process builds.\n",
        "| map | raster MP | s (wall, median) | s (wall, min) | CPU s | 1st build s | USD MB | paper s | paper MB | USD / paper | peak RSS GB | IoU |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for row in r["rows"]:
        if "error" in row:
            lines.append(f"| {row['label']} | – | error: {row['error']} | | | | | | | | | |")
            continue
        lines.append(
            f"| {row['label']} | {row['raster_mp']:.3f} | {row['seconds']:.3f} | {row['seconds_min']:.3f} | {row['cpu_seconds']:.3f} | "
            f"{row['seconds_first']:.3f} | {row['usd_mb']:.2f} | {row['paper_seconds']:.2f} | {row['paper_usd_mb']:.1f} | "
            f"{row['usd_fraction_of_paper']:.3f} | {row['peak_rss_gb']:.3f} | {row['iou']:.4f} |"
        )
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- bench ros2 (measured)
def ros2_block(doc: Doc) -> str:
    r = doc["result"]
    lines = [
        header(doc, "ros2"),
        f"Map {Path(r['map']).name}; target ≥ {r['target_real_time_factor']:g}× real time at `--rate max`.\n",
        "| mode | sim s / wall s (received) | msgs/s received | scans/s received | bridge: msgs published | bridge CPU s / wall s | /drive latency median / p99 |",
        "|---|---:|---:|---:|---:|---:|---|",
    ]
    for m in r["rows"]:
        br = m["bridge"]
        lat = br.get("drive_latency_ms") or {}
        lat_txt = f"{lat['median']:.1f} / {lat['p99']:.1f} ms" if lat else "–"
        lines.append(
            f"| `{m['mode']}` | {m['real_time_factor_received']:.2f} | {_n(m['received_per_s'])} | "
            f"{_n(m['scans_received_per_s'])} | {_n(br['messages'])} in {br['wall_time_s']:.1f} s | "
            f"{br['cpu_time_s']:.2f} / {br['wall_time_s']:.1f} | {lat_txt} |"
        )
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- bench constructors: Table 3 (counts deterministic)
def constructors_block(doc: Doc) -> str:
    from benchmarks.constructors import PAPER

    r = doc["result"]
    names = {
        "lattice": "Lattice + ring + polygon (Algorithm 1, `generate_track`)",
        "lattice-raw": "same, constructor checks only (`lattice-raw`)",
        "de": "DE optimiser (scipy, maxiter 30, popsize 5)",
        "random": "Random sampling",
    }
    lines = [
        header(doc, "constructors"),
        f"{r['specs']} specs, {r['specs'] - r['admissible_specs']} rejected by the screen, "
        f"{r['admissible_specs']} × seeds {' '.join(map(str, r['seeds']))} = {r['admissible_specs'] * len(r['seeds'])} trials per constructor.\n",
        "| Constructor | Valid trials | Valid/built | s/trial (mean / median) | candidates (median / max) | Paper |",
        "|---|---|---|---|---|---|",
    ]
    for s in r["summary"]:
        p = PAPER.get(s["constructor"])
        ptxt = f"{p[0]}/{p[2]}, {p[0]}/{p[1]}, {p[3]} s" if p else "—"
        lines.append(
            f"| {names.get(s['constructor'], s['constructor'])} | **{s['valid']}/{s['trials']}** | {s['valid']}/{s['built']} | "
            f"{s['seconds_per_trial_mean']:.3f} / {s['seconds_per_trial_median']:.3f} | {s['candidates_median']:g} / {s['candidates_max']} | {ptxt} |"
        )
    return "\n".join(lines) + "\n"


def constructors_deterministic(doc: Doc) -> Any:
    keep = (
        "constructor",
        "trials",
        "built",
        "valid",
        "candidates_median",
        "candidates_max",
        "failed_checks",
        "not_built",
    )
    return [{k: s[k] for k in keep} for s in doc["result"]["summary"]]


# ---------------------------------------------------------------- bench constructors --sweep (generator-bands)
def sweep_block(doc: Doc) -> str:
    r = doc["result"]
    bands = r["by_fill"]
    return (
        header(doc, "generator-bands")
        + f"\nAll {r['specs']} admissible specs: **{r['accepted']}/{r['specs']} ({r['acceptance']:.1%})**; obvious construction "
        f"{r['obvious_accepted']}/{r['obvious_specs']}; below 0.6 L_max {r['practical_accepted']}/{r['practical_specs']}. "
        f"Seconds per spec median {r['seconds_median']:.3f}, max {r['seconds_max']:.2f}.\n\n"
        "| fill | " + " | ".join(bands) + " |\n|---|" + "---|" * len(bands) + "\n"
        "| accepted | " + " | ".join(bands.values()) + " |\n"
    )


def sweep_readme_block(doc: Doc) -> str:
    r = doc["result"]
    return (
        f"Generator acceptance on this build (`python -m benchmarks constructors --sweep`, {doc['measured']['utc']}; "
        f'BENCHMARKS.md, "Acceptance sweep"): **{r["accepted"]} of {r["specs"]} admissible specs ({r["acceptance"]:.1%})**, '
        f"{r['obvious_accepted']} of the {r['obvious_specs']} that have an obvious construction, and "
        f"{r['practical_accepted']} of the {r['practical_specs']} below 0.6 L_max.\n"
    )


def sweep_deterministic(doc: Doc) -> Any:
    r = doc["result"]
    keep = (
        "specs",
        "accepted",
        "obvious_specs",
        "obvious_accepted",
        "by_lap",
        "by_width",
        "by_hall",
        "by_features",
        "by_fill",
    )
    return {k: r[k] for k in keep} | {"outcomes": [[x["spec"], x["seed"], x["outcome"]] for x in r["rows"]]}


# ---------------------------------------------------------------- bench ray (measured): BENCHMARKS tables and the README's figures
def _ray_rows(r: Doc) -> dict[str, Doc]:
    return {row["config"]: row for row in r["rollouts"]["rows"]}


def ray_block(doc: Doc) -> str:
    r = doc["result"]
    g, ro, pr = r["generation"], r["rollouts"], r["projection"]
    lines = [
        header(doc, "ray"),
        f"Ray {r['ray_version']}, {r['cluster']} ({r['cores']} cores).\n",
        f"**Track generation** ({g['requests']} requests of `examples/sweep.json`, {g['accepted']} accepted):\n",
        "| executor | wall s (median) | runs, s | requests/s | same tracks |",
        "|---|---:|---|---:|---|",
    ]
    for e in g["rows"]:
        lines.append(
            f"| {e['executor']} | {e['wall_s']:.2f} | {min(e['walls_s']):.2f}–{max(e['walls_s']):.2f} | "
            f"{e['requests_per_s']:.2f} | {'yes' if e['same_tracks'] else 'NO'} |"
        )
    lines += [
        f"\nRay overhead per request {g['ray_overhead_per_request_s'] * 1e3:.1f} ms (against the local pool "
        f"{g['ray_vs_local_pool_overhead_per_request_s'] * 1e3:.1f} ms); {g['ray_noop_tasks_per_s']:.0f} no-op tasks/s.\n",
        f"**Rollouts** ({ro['envs_per_actor']} envs per actor or local batch, {ro['beams']} beams, {ro['steps']} steps; "
        f"same rollouts as local: {'yes' if ro['same_rollouts_as_local'] else 'NO'}):\n",
        "| configuration | workers | envs | ms/step (median) | env-steps/s |",
        "|---|---:|---:|---:|---:|",
    ]
    for row in ro["rows"]:
        lines.append(
            f"| {row['config']} | {row['workers']} | {row['num_envs']} | {row['step_ms_median']:.2f} | {_n(row['env_steps_per_s'])} |"
        )
    lines += [
        "\n**Projection to more workers** (`bench ray`'s own, from the figures above; not a measurement):\n",
        "| workers (cores) | generation requests/s | env-steps/s | step overhead ms |",
        "|---:|---:|---:|---:|",
    ]
    for p in pr["rows"]:
        lines.append(
            f"| {p['workers']} | {p['requests_per_s']:.1f} | {_n(p['env_steps_per_s'])} | {p['step_overhead_ms']:.1f} |"
        )
    return "\n".join(lines) + "\n"


def ray_readme_block(doc: Doc) -> str:
    r = doc["result"]
    pr = {p["workers"]: p for p in r["projection"]["rows"]}
    local = [x for x in r["rollouts"]["rows"] if x["config"].startswith("local") and x["workers"] == 1][0]
    one = r["generation"]["rows"][0]
    ws = sorted(pr)
    m = doc["measured"]
    return (
        f"Measured by `bench ray` on this build ({m['utc']}, {m['machine']['cores']} cores, load average "
        f"{m['load_average']['mean']:.1f}; `docs/figures/ray.json`, BENCHMARKS.md):\n\n"
        f"- **Track generation and verification pay off.** Requests are independent, so the projection grows "
        f"with workers until the driver's task rate binds: "
        + ", ".join(f"{pr[w]['requests_per_s']:.3g} requests/s on {w} workers" for w in ws)
        + f", against {one['requests_per_s']:.2g} on one core.\n"
        f"- **Rollouts through `RayVectorEnv` do not**, on one machine or many: every `step` is a round trip to "
        f"every actor, and that cost grows with the actors and with the size of each actor's result. The "
        f"projection levels off near {pr[ws[-1]]['env_steps_per_s'] / 1e3:.0f}k env-steps/s at "
        f"{r['rollouts']['beams']} beams, against {local['env_steps_per_s'] / 1e3:.0f}k for one native vector env "
        f"on one core of this machine.\n"
        + (
            f"\nThat run shared {m['machine']['cores']} cores with other jobs at a load above the core count, so its "
            "absolute figures are far below a quiet machine's (BENCHMARKS.md keeps a quieter run in its history); "
            "the two conclusions held in both.\n"
            if m["load_average"]["mean"] > m["machine"]["cores"]
            else ""
        )
    )


# ---------------------------------------------------------------- PhysX lap table (scripts/physx_lap_bench.py)
def physx_run(profile: str) -> Doc:
    import subprocess
    import sys
    import tempfile

    def body() -> Any:
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "rows.json"
            subprocess.run(
                [sys.executable, str(ROOT / "scripts" / "physx_lap_bench.py"), "--out", str(out)],
                check=True,
                capture_output=True,
            )
            return json.loads(out.read_text())

    return measured("python scripts/physx_lap_bench.py --out FILE", profile, body)


def physx_block(doc: Doc) -> str:
    lines = [
        header(doc, "physx-laps"),
        "| track | lap (m) | engine | lap time (s) | mean / max deviation (m) | physics steps/s |",
        "|---|---:|---|---:|---:|---:|",
    ]
    for r in doc["result"]:
        for key in ("ours", "physx"):
            run = r[key]
            lap = f"{run['lap_time_s']:.2f}" if run["completed"] else "no lap"
            lines.append(
                f"| {r['track']} | {r['length_m']:.1f} | {run['engine']} | {lap} | "
                f"{run['mean_deviation_m']:.3f} / {run['max_deviation_m']:.3f} | {_n(run['steps_per_second'])} |"
            )
    return "\n".join(lines) + "\n"


def physx_deterministic(doc: Doc) -> Any:
    keep = ("engine", "completed", "lap_time_s", "mean_deviation_m", "max_deviation_m")
    return [{"track": r["track"]} | {k: {f: r[k][f] for f in keep} for k in ("ours", "physx")} for r in doc["result"]]


# ---------------------------------------------------------------- engines (issue 36)
_LAT = [
    ("step rise time (s)", "rise (s)"),
    ("step overshoot", "overshoot"),
    ("step gain (1/s)", "gain (1/s)"),
    ("understeer gradient (rad s^2/m)", "K (rad s²/m)"),
    ("a_y at steer 0.10 (m/s^2)", "a_y @0.10"),
    ("a_y at steer 0.20 (m/s^2)", "a_y @0.20"),
    ("peak a_y (m/s^2)", "peak a_y"),
]
_LON = [
    ("0-5 m/s (s)", "0-5 m/s (s)"),
    ("top speed (m/s)", "top speed (m/s)"),
    ("braking distance (m)", "stop from 5 m/s (m)"),
    ("braking time (s)", "stop time (s)"),
    ("a_y at steer 0.05 (m/s^2)", "a_y @0.05"),
    ("a_y at steer 0.15 (m/s^2)", "a_y @0.15"),
]


def _pair(v: dict[str, Any], target: float, digits: int = 3) -> str:
    def f(x: float | None) -> str:
        return "–" if x is None else f"{x:.{digits}f}"

    d = v["diff"]
    pct = "–" if d is None else f"{100 * d:.1f} %"
    if d is not None and d > target:
        pct = f"**{pct}**"
    return f"{f(v['ours'])} / {f(v['physx'])} ({pct})"


def _lap(x: float | None) -> str:
    return "no lap" if x is None else f"{x:.2f}"


def engines_block(doc: Doc, name: str = "engines") -> str:
    r = doc["result"]
    t = r["target"]
    tyre = r.get("lateral_tyre", "linear")
    lines = [
        header(doc, name, timed=False),
        "",
        f"Our engine's lateral tyre: **{tyre}** (`VehicleConfig.lateral_tyre`).",
        "",
    ]
    for cols, what in ((_LAT, "yaw and cornering"), (_LON, "straight line, and the cornering samples left")):
        lines += [
            f"Open loop, {what}: ours / PhysX (difference; **bold** above {100 * t:.0f} %):",
            "",
            "| mu | mass x | " + " | ".join(h for _, h in cols) + " |",
            "|---:|---:|" + "---:|" * len(cols),
        ]
        for c in r["cells"]:
            cells = " | ".join(_pair(c["metrics"][k], t) for k, _ in cols)
            lines.append(f"| {c['mu']:g} | {c['mass_scale']:g} | {cells} |")
        lines.append("")
    lines.append(
        f"Within {100 * t:.0f} %: **{r['within_target']} of {r['compared']}** comparisons "
        "(overshoot compared absolutely, as a fraction of the steady value)."
    )
    if r.get("anchor"):
        lines += [
            "",
            "Real-car anchor: steady yaw rate (rad/s) at 5 m/s and 0.05 rad of steer:",
            "",
            "| car | real car's identified model | ours | PhysX | kinematic |",
            "|---|---:|---:|---:|---:|",
        ]
        for a in r["anchor"]:
            real = "–" if a["real_model"] is None else f"{a['real_model']:.3f}"
            lines.append(f"| {a['car']} | {real} | {a['ours']:.3f} | {a['physx']:.3f} | {a['kinematic']:.3f} |")
    if r.get("laps"):
        lines += [
            "",
            "Closed loop: the same driver (the reference pure pursuit, or the racing driver on its raceline) at the "
            "env's control rate (20 Hz) on the same stage; RMS of the difference between the engines at the same arc "
            "length:",
            "",
            "| track | car | lap ours (s) | lap PhysX (s) | difference | lateral error mean / max, ours (m) | PhysX (m) "
            "| RMS speed (m/s) | RMS yaw rate (rad/s) | RMS steer (rad) | RMS offset (m) | start gap (m) |",
            "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for p in r["laps"]:
            lap = _lap
            d = p["lap_diff"]
            diff = "–" if d is None else (f"{100 * d:.1f} %" if d <= 0.05 else f"**{100 * d:.1f} %**")
            lines.append(
                f"| {p['track']} | {p['condition']} | {lap(p['ours_lap_s'])} | {lap(p['physx_lap_s'])} | {diff} | "
                f"{p['ours_lateral_mean_m']:.3f} / {p['ours_lateral_max_m']:.3f} | "
                f"{p['physx_lateral_mean_m']:.3f} / {p['physx_lateral_max_m']:.3f} | {p['rms_speed_m_s']:.3f} | "
                f"{p['rms_yaw_rate']:.3f} | {p['rms_steer_rad']:.4f} | {p['rms_lateral_offset_m']:.3f} | "
                f"{p.get('start_gap_m', 0.0):.2f} |"
            )
        lines += ["", _laps_summary(r["laps"])]
    return "\n".join(lines) + "\n"


#: The paired-trace RMS columns of a closed-loop run, with their units.
_TRACE_RMS = (
    ("rms_speed_m_s", "speed", "m/s", ".3f"),
    ("rms_yaw_rate", "yaw rate", "rad/s", ".3f"),
    ("rms_steer_rad", "steer", "rad", ".4f"),
    ("rms_lateral_offset_m", "offset", "m", ".3f"),
)


def _laps_summary(laps: list[dict[str, Any]]) -> str:
    """How many runs lap in both engines within 5 %, and the largest paired-trace RMS over
    every run and over the runs off the friction limit (all but the mu 0.4 condition)."""

    def largest(rows: list[dict[str, Any]]) -> str:
        return ", ".join(f"{what} {max(p[k] for p in rows):{fmt}} {unit}" for k, what, unit, fmt in _TRACE_RMS)

    both = [p for p in laps if p["lap_diff"] is not None]
    within = sum(p["lap_diff"] <= 0.05 for p in both)
    off_limit = [p for p in laps if p["condition"] != "mu 0.4"]
    return (
        f"Lap times within 5 %: **{within} of {len(laps)}** runs ({len(both)} lap in both engines). "
        f"Largest RMS difference over every run: {largest(laps)}; over the {len(off_limit)} runs off the friction "
        f"limit (all but mu 0.4): {largest(off_limit)}."
    )


def engines_deterministic(doc: Doc) -> Any:
    r = doc["result"]
    return {
        "cells": [{"mu": c["mu"], "mass_scale": c["mass_scale"], "metrics": c["metrics"]} for c in r["cells"]],
        "anchor": r.get("anchor", []),
        "laps": [{k: p[k] for k in ("track", "condition", "ours_lap_s", "physx_lap_s")} for p in r.get("laps", [])],
    }


def engines_picture(doc: Doc) -> None:
    from benchmarks.engines import EnginesResult, plot, plot_tyres

    res = EnginesResult.model_validate(doc["result"])
    plot(res, FIGURE_DATA / "engines.png")
    plot_tyres(FIGURE_DATA / "engines-tyres.png", _vehicle_data())


def engines_linear_block(doc: Doc) -> str:
    return engines_block(doc, "engines-linear")


def engines_linear_picture(doc: Doc) -> None:
    from benchmarks.engines import EnginesResult, plot

    plot(EnginesResult.model_validate(doc["result"]), FIGURE_DATA / "engines-linear.png")


def _vehicle_data() -> Path:
    from benchmarks.engines import _default_vehicle_data

    return _default_vehicle_data()


# ---------------------------------------------------------------- the registry of bench figures
# ci: "rerun" = CI reruns the command (seconds) and compares the deterministic part;
#     "long"  = only `make docs-figures` reruns it (minutes); CI checks block == data;
#     "measured" = timings only; CI checks block == data.
BENCH_FIGURES: dict[str, dict[str, Any]] = {
    "catalog": {
        "about": "catalog counts (README recorded-maps table, BENCHMARKS catalog line)",
        "run": catalog_run,
        "blocks": [
            ("README.md", "catalog-counts", catalog_readme_block),
            ("BENCHMARKS.md", "catalog-counts", catalog_bench_block),
        ],
        "deterministic": catalog_deterministic,
        "ci": "rerun",
    },
    "fidelity": {
        "about": "bench fidelity: straight line, braking, cornering, limits, dt",
        "run": _cmd(("fidelity", ["bench", "fidelity"])),
        "blocks": [("BENCHMARKS.md", "fidelity", fidelity_block)],
        "deterministic": fidelity_deterministic,
        "ci": "rerun",
    },
    "parser": {
        "about": "bench parser (rules): parse, audit and refusal scores, latency",
        "run": _cmd(("parser", ["bench", "parser"])),
        "blocks": [("BENCHMARKS.md", "parser", parser_block)],
        "deterministic": parser_deterministic,
        "ci": "rerun",
    },
    "library": {
        "about": "bench library: the 46 circuits at 1:10, length errors, build time",
        "run": _cmd(("library", ["bench", "library"])),
        "blocks": [("BENCHMARKS.md", "library", library_block)],
        "deterministic": library_deterministic,
        "ci": "rerun",
    },
    "physics": {
        "about": "bench physics (shortcut and --no-shortcut): vehicle-steps/s, scan time",
        "run": _cmd(
            ("shortcut", ["bench", "physics", "--seconds", "2"]),
            ("no_shortcut", ["bench", "physics", "--seconds", "2", "--no-shortcut"]),
        ),
        "blocks": [("BENCHMARKS.md", "physics", physics_block)],
        "deterministic": None,
        "ci": "measured",
    },
    "env": {
        "about": "bench env on Spielberg: env-steps/s, per-call breakdown, scan over a lap",
        "run": _cmd(("env", ["bench", "env"])),
        "blocks": [("BENCHMARKS.md", "env", env_block)],
        "deterministic": None,
        "ci": "measured",
    },
    "peer": {
        "about": "bench peer (F1TENTH_GYM_PYTHON set): single env against F1TENTH Gym in one run, 5 pairs",
        "run": _cmd(("peer", ["bench", "peer", "--pairs", "5"])),
        "blocks": [("BENCHMARKS.md", "peer", peer_block)],
        "deterministic": None,
        "ci": "measured",
    },
    "build": {
        "about": "bench build --repeat 5: map to USD stage times, sizes, IoU",
        "run": _cmd(("build", ["bench", "build", "--repeat", "5"])),
        "blocks": [("BENCHMARKS.md", "build", build_block)],
        "deterministic": None,
        "ci": "measured",
    },
    "ros2": {
        "about": "bench ros2: bridge real-time factor and /drive latency",
        "run": _cmd(("ros2", ["bench", "ros2", "--seconds", "10"])),
        "blocks": [("BENCHMARKS.md", "ros2", ros2_block)],
        "deterministic": None,
        "ci": "measured",
    },
    "constructors": {
        "about": "bench constructors: Table 3 (lattice, lattice-raw, DE, random; several minutes for DE)",
        "run": _cmd(("constructors", ["bench", "constructors"])),
        "blocks": [("BENCHMARKS.md", "constructors", constructors_block)],
        "deterministic": constructors_deterministic,
        "ci": "long",
    },
    "generator-bands": {
        "about": "bench constructors --sweep: acceptance of the 360-spec sweep by fill band",
        "run": _cmd(("sweep", ["bench", "constructors", "--sweep", "--jobs", "2"])),
        "blocks": [
            ("BENCHMARKS.md", "generator-bands", sweep_block),
            ("README.md", "generator-acceptance", sweep_readme_block),
        ],
        "deterministic": sweep_deterministic,
        "ci": "long",
    },
    "ray": {
        "about": "bench ray: generation and rollouts through Ray, projection (README and BENCHMARKS)",
        "run": _cmd(("ray", ["bench", "ray"])),
        "blocks": [("BENCHMARKS.md", "ray", ray_block), ("README.md", "ray-payoff", ray_readme_block)],
        "deterministic": None,
        "ci": "measured",
    },
    "physx-laps": {
        "about": "scripts/physx_lap_bench.py: PhysX car vs ours, one lap on three tracks (physx extra)",
        "run": physx_run,
        "blocks": [("BENCHMARKS.md", "physx-laps", physx_block)],
        "deterministic": physx_deterministic,
        "ci": "long",
    },
    "engines": {
        "about": "bench engines --anchor --laps: the brush-tyre car open loop and closed loop in ours and PhysX "
        "(physx extra, ~15 min)",
        "run": _cmd(("engines", ["bench", "engines", "--tyre", "brush", "--anchor", "--laps"])),
        "blocks": [("BENCHMARKS.md", "engines", engines_block)],
        "picture": engines_picture,
        "deterministic": engines_deterministic,
        "ci": "long",
    },
    "engines-linear": {
        "about": "bench engines --tyre linear --laps: the default (linear-tyre) car in ours against PhysX's brush "
        "tyre (physx extra, ~15 min)",
        "run": _cmd(("engines", ["bench", "engines", "--tyre", "linear", "--laps"])),
        "blocks": [("BENCHMARKS.md", "engines-linear", engines_linear_block)],
        "picture": engines_linear_picture,
        "deterministic": engines_deterministic,
        "ci": "long",
    },
}
for _name, _fig in BENCH_FIGURES.items():
    _fig["data"] = FIGURE_DATA / f"{_name}.json"
