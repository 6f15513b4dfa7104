#!/usr/bin/env python3
"""The step-resolved pocket statistics (/cage/pocket_step_*, docs/output_layout.md, "Pocket
contacts at step resolution") on short runs, one case per ctest:

    pocket_steps_test.py CASE RACEWAY MPIEXEC SOURCE_DIR

  sampling: 6309 R3 for 20 ms (6 pocket contacts) with a fixed first step at output intervals of
    20 us and 200 us: the same steps, so the summary's pocket_step_totals are the same bits, and
    the rows' totals (onsets summed, peaks' max) are equal and their impulses agree to 1e-12.
  accuracy: the same run sampled every 2 us, where the samples resolve the contacts (at 5 us they
    missed the top of an impact by 1.0 % with the steps of the scene's trapezoidal rule): per side,
    the step statistics against the ones of the samples (normal forces of /segments/ball_pocket
    split by the sign of circumferential_force, trapezoid rule, events = runs above 0 N): events
    within 1, peak within 1.5 % (the steps' peak may be below a sample interpolated between two
    steps: a ~100 us impact's top between steps ~10 us apart, up to 1.2 %), impulse within 3 %, contact time within 1 % plus one sample interval per event (the
    samples place each start and end to half an interval); and the rows add up to the summary's
    totals. Both are compared up to the last sample with no contact on the side: a contact still on
    at the run's end has its last steps past the end time, unwritten.
  ranks: the 200 us run at np = 2, with and without --parallel-output, against np = 1: every
    pocket_step dataset and the totals bitwise (with rank 0 writing and with --parallel-output).
  planar: seed 002 at 40 Hz (roller bearing: the cage_bar_front / cage_bar_rear segments) for 10 ms at 1 us:
    rows [T x N x 2], side 0 the front bar; events, peak, impulse and contact time against the
    samples, with the wider tolerances stated there.

Exit codes: 0 pass, 1 fail, 77 skipped (h5py or numpy missing).
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

try:
    import h5py
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

QUANTITIES = ("onsets", "peak_force", "impulse", "contact_time")
failures = []


def check(cond, what):
    print(f"{'ok' if cond else 'FAIL'}: {what}", file=sys.stderr)
    if not cond:
        failures.append(what)


def run(raceway, scene, out, interval, np_ranks=1, mpiexec=None, extra=()):
    # The segment diagnostics at every sample (6309 R3 ships them at every 5th): the accuracy case
    # compares the step statistics with the pocket forces of every sample.
    cmd = [raceway, "run", scene, "-o", out, "--set", f'scene.output_interval="{interval}"', "--set",
           'solver.initial_step="1 us"', "--set", "output.segment_every=1", *extra]
    if np_ranks > 1:
        cmd = [mpiexec, "--oversubscribe", "-np", str(np_ranks)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {r.returncode}: {r.stderr[-600:]}")
    with h5py.File(out, "r") as f:
        data = {q: f[f"cage/pocket_step_{q}"][()] for q in QUANTITIES}
        data["time"] = f["time"][()]
        data["summary"] = json.loads(f.attrs["summary_json"])
        data["units"] = {q: f[f"cage/pocket_step_{q}"].attrs["units"] for q in QUANTITIES}
        segments = {k: {n: f[f"segments/{k}/{n}"][()] for n in f[f"segments/{k}"].keys()} for k in f["segments"]}
        data["segments"] = segments
    return data


# Seed 002's solver before it took its converged pocket settings: the bounds below were measured with it.
SEED002_SHIPPED = ('rtol = 2e-5\nelement_velocity_frame = "orbital"\npocket_tolerance_factor = 10\n'
                   'pocket_tolerance_cage = true\n')
SEED002_FORMER = "rtol = 1e-5\n"


def scene_for(source, work, name, end, replace=None):
    text = open(os.path.join(source, "jobs", "scenes", name), encoding="utf-8").read()
    if replace:
        check(replace[0] in text, f"{name}: its lines {replace[0]!r}")
        text = text.replace(*replace)
    path = os.path.join(work, name)
    open(path, "w", encoding="utf-8").write(re.sub(r"(?m)^end_time = .*$", f'end_time = "{end}"', text))
    return path


def sampled_sides(d):
    """[T x pockets x 2] forces from the samples, side 0 the bar ahead in +z (the raw convention)."""
    pockets = d["onsets"].shape[1]
    forces = np.zeros((d["time"].size, pockets, 2))
    if "ball_pocket" in d["segments"]:
        seg = d["segments"]["ball_pocket"]
        fn, fc = seg["normal_force"], seg["circumferential_force"]
        for c, k in enumerate(seg["element"].astype(int)):
            side = np.where(fc[:, c] < 0, 0, 1)
            on = fn[:, c] > 0
            for s in (0, 1):
                forces[:, k, s] += np.where(on & (side == s), fn[:, c], 0.0)
    else:
        forces[:, :, 0] = d["segments"]["cage_bar_front"]["normal_force"]
        forces[:, :, 1] = d["segments"]["cage_bar_rear"]["normal_force"]
    return forces


def compare_with_samples(d, label, tol=None):
    """tol: the allowed differences (events: extra step onsets, peak, impulse, contact time relative)."""
    tol = tol or {"events": 1, "peak": 0.01, "impulse": 0.03, "contact": 0.01}
    t, forces = d["time"], sampled_sides(d)
    dt = np.diff(t)
    for side in (0, 1):
        # Up to the last sample with no contact on this side: a contact still on at the run's end
        # is in the samples up to the end time but its last steps may lie past it, unwritten.
        free = np.nonzero(forces[:, :, side].sum(axis=1) == 0)[0]
        k = int(free[-1]) + 1 if free.size else 1
        f = forces[:k, :, side]
        on = f > 0
        events = int(np.sum(on[1:] & ~on[:-1]))
        impulse = float(np.sum(0.5 * (f[1:] + f[:-1]) * dt[:k - 1, None]))
        contact = float(np.sum(0.5 * (on[1:].astype(float) + on[:-1]) * dt[:k - 1, None]))
        peak = float(f.max())
        s_events = int(d["onsets"][:k, :, side].sum())
        s_peak = float(d["peak_force"][:k, :, side].max())
        s_impulse = float(d["impulse"][:k, :, side].sum())
        s_contact = float(d["contact_time"][:k, :, side].sum())
        print(f"{label} side {side}: events {s_events} steps / {events} samples, peak {s_peak:.4f} / {peak:.4f} N, "
              f"impulse {s_impulse:.6g} / {impulse:.6g} N s, contact {s_contact:.6g} / {contact:.6g} s",
              file=sys.stderr)
        check(events > 0, f"{label} side {side}: the samples hold pocket contacts")
        check(events - 1 <= s_events <= events + tol["events"],
              f"{label} side {side}: events {s_events} (steps) vs {events} (samples)")
        check(abs(s_peak - peak) <= tol["peak"] * peak,
              f"{label} side {side}: peak {s_peak} (steps) vs {peak} (samples)")
        check(abs(s_impulse - impulse) <= tol["impulse"] * impulse,
              f"{label} side {side}: impulse {s_impulse} vs {impulse}")
        check(abs(s_contact - contact) <= tol["contact"] * contact + events * dt.max(),
              f"{label} side {side}: contact time {s_contact} vs {contact}")
        totals = d["summary"]["pocket_step_totals"]
        all_events, all_peak = int(d["onsets"][:, :, side].sum()), float(d["peak_force"][:, :, side].max())
        check(totals["onsets"][side] == all_events and totals["peak_force_n"][side] == all_peak,
              f"{label} side {side}: the rows' onsets and peak are the summary's totals")
        check(math.isclose(totals["impulse_n_s"][side], float(d["impulse"][:, :, side].sum()), rel_tol=1e-12),
              f"{label} side {side}: the rows' impulse is the summary's total")


def main():
    case, raceway, mpiexec, source = sys.argv[1:5]
    with tempfile.TemporaryDirectory() as work:
        if case == "planar":
            scene = scene_for(source, work, "seed002_40hz.toml", "10 ms", (SEED002_SHIPPED, SEED002_FORMER))
            d = run(raceway, scene, os.path.join(work, "p.h5"), "1 us")
            n = d["segments"]["cage_bar_front"]["normal_force"].shape[1]
            check(d["onsets"].shape == (d["time"].size, n, 2), f"rows [T x N x 2]: {d['onsets'].shape}")
            check(d["units"] == {"onsets": "-", "peak_force": "N", "impulse": "N s", "contact_time": "s"},
                  f"units {d['units']}")
            # Wider than the ball bearing's: on these stiff roller-bar impacts (10-20 us, one or two
            # steps of ~12 us) the step's last Newton iterate is off the accepted state's force by
            # 4 % (median; peaks 36.6 against 35.0 N) and finds light touches (< 0.1 N) that the
            # interpolated samples pass over, and the front bar's long light pushes (3-4 ms at about
            # 0.6 N) come out above the samples' trapezoids. Which contacts a 10 ms window holds is
            # the rattling's draw (it follows the round-off): over five draws (the Jacobian's
            # increment 0.5-1.5e-7) the step statistics against the samples gave onsets +0 to +6,
            # peaks -0.1 to +2.6 %, impulses -0.4 to +24 % (the front bar +4 to +24 %, the rear
            # -0.4 to +3 %), contact times -2 to +13 % (+19 us over the rear bar's 6 short contacts, where
            # the bound adds a sample interval per event). The bounds cover that spread. (Measured with
            # the scene's former solver, which the run keeps: at its converged pocket settings one draw
            # gave the front bar's contact time +21 % and impulse +27 %, the light pushes again.)
            compare_with_samples(d, "seed 002 1 us", {"events": 8, "peak": 0.05, "impulse": 0.30, "contact": 0.10})
        else:
            scene = scene_for(source, work, "6309_R3.toml", "20 ms")
            coarse = run(raceway, scene, os.path.join(work, "c.h5"), "200 us")
            if case == "sampling":
                fine = run(raceway, scene, os.path.join(work, "f.h5"), "20 us")
                check(fine["summary"]["steps"] == coarse["summary"]["steps"], "the same steps at 20 and 200 us")
                fine_totals = fine["summary"]["pocket_step_totals"]
                coarse_totals = coarse["summary"]["pocket_step_totals"]
                check(json.dumps(fine_totals) == json.dumps(coarse_totals),
                      f"summary totals bitwise equal: {coarse_totals}")
                check(sum(coarse["summary"]["pocket_step_totals"]["onsets"]) > 0, "the run has pocket contacts")
                for q, total in (("onsets", np.sum), ("peak_force", np.max)):
                    check(np.array_equal(total(fine[q], axis=0), total(coarse[q], axis=0)),
                          f"{q}: per pocket and side equal over the rows at 20 and 200 us")
                for q in ("impulse", "contact_time"):
                    a, b = fine[q].sum(axis=0), coarse[q].sum(axis=0)
                    check(np.allclose(a, b, rtol=1e-12, atol=0), f"{q}: rows' sums agree to 1e-12")
            elif case == "accuracy":
                # The steps' peak is the largest force at an accepted step: below a ~100 us impact's
                # top by up to 1 - cos(pi h / 2T), 1.2 % for the trapezoidal rule's steps of h ~ 10 us.
                compare_with_samples(run(raceway, scene, os.path.join(work, "a.h5"), "2 us"), "6309 R3 2 us",
                                     {"events": 1, "peak": 0.015, "impulse": 0.03, "contact": 0.01})
            elif case == "ranks":
                # np 2 with rank 0 writing and with --parallel-output, against np 1.
                for extra in ((), ("--parallel-output",)):
                    two = run(raceway, scene, os.path.join(work, "n2.h5"), "200 us", 2, mpiexec, extra)
                    for q in QUANTITIES:
                        check(two[q].tobytes() == coarse[q].tobytes(), f"{q}: np 2 {' '.join(extra)} bitwise np 1")
                    check(two["summary"]["pocket_step_totals"] == coarse["summary"]["pocket_step_totals"],
                          f"summary totals: np 2 {' '.join(extra)} bitwise np 1")
            else:
                print(f"unknown case {case}", file=sys.stderr)
                return 2
    print(f"{case}: {'passed' if not failures else f'{len(failures)} failure(s)'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
