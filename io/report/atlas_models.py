"""What evaluates an atlas point: the simulator (`raceway run` with --set overrides, then the cage
motion's classification of its output) or the tests' cheap stand-in with a known boundary.

Both answer evaluate(point_id, sets, tag) with the window's metrics and class (cage_motion), the
blocks' metrics and classes (atlas_certify.settled) and the run's wall time in seconds.
"""
import math
import os
import subprocess
import threading
import time
import zlib

import numpy as np

import atlas_certify as ac
import cage_friction as cf
import cage_motion as cm
from atlas_file import parameter_unit
from atlas_search import standin_boundary


class PointFailed(Exception):
    """A point's run failed: str() says how (exit code, last lines of its log)."""


class PointStopped(Exception):
    """A point's run was stopped by a signal: the point stays planned (rerun on --resume)."""


#: Set by a stop signal (raceway_atlas.py): no new run starts; the running ones got the signal.
STOP = threading.Event()
_RUNNING = set()
_RUNNING_LOCK = threading.Lock()


def stop_runs(signum):
    """Asks every running `raceway run` to stop (it writes a checkpoint and exits 4)."""
    STOP.set()
    with _RUNNING_LOCK:
        for process in _RUNNING:
            try:
                process.send_signal(signum)
            except OSError:
                pass


def set_text(value):
    """A `set` value of the atlas file as --set takes it: TOML booleans in TOML, the rest as written."""
    return ("true" if value else "false") if isinstance(value, bool) else str(value)


def unit_value(value, unit):
    """A range value with its unit as the scene reads it: 3000 rpm -> "3000 rpm"."""
    return f"{value:.10g} {unit}"


def revolution_times(cage_speed, settling_revolutions, window_revolutions):
    """(settling_time, end_time) [s] of a window of `window_revolutions` cage revolutions after
    `settling_revolutions`, at the kinematic cage speed `cage_speed` [rad/s, either sign]."""
    speed = abs(float(cage_speed))
    if not (math.isfinite(speed) and speed > 0):
        raise PointFailed(f"kinematic cage speed {cage_speed!r} rad/s: no window in cage revolutions")
    period = 2.0 * math.pi / speed
    return settling_revolutions * period, (settling_revolutions + window_revolutions) * period


def add_friction_evidence(m, path, settling, mass):
    """The critical pocket friction's columns and, beyond it, a reason (evidence: the class stands)."""
    try:
        ev = cf.atlas_evidence(path, settling, cage_mass=mass)
    except (KeyError, ValueError, OSError) as err:  # an output without what the criterion reads
        ev = {"critical_pocket_friction": math.nan, "pocket_friction_margin": math.nan,
              "critical_pocket_friction_note": f"not evaluated: {type(err).__name__}: {err}"}
    m.update(ev)
    reason = cf.criterion_reason(ev)
    if reason:
        m["reasons"] = list(m.get("reasons", [])) + [reason]


class SimulatorModel:
    """Runs `raceway run BASE --set ...` per point into DIR/points and classifies its output."""

    def __init__(self, raceway, atlas, folder):
        self.raceway, self.atlas = raceway, atlas
        self.folder = os.path.join(folder, "points")
        os.makedirs(self.folder, exist_ok=True)
        self._windows = {}  # point id -> (settling_time, end_time): a point's reruns share its window

    def base_sets(self, end_time):
        sets = {k: set_text(v) for k, v in self.atlas["set"].items()}
        sets["scene.end_time"] = f"{end_time:.10g} s"
        return sets

    def kinematic_cage_speed(self, name, sets):
        """The kinematic cage speed [rad/s] of the scene with `sets` at its start (/cage/epicyclic_speed of
        a run two microseconds long)."""
        from raceway import RacewayOutput

        out = os.path.join(self.folder, name + "_kinematic.h5")
        args = [self.raceway, "run", self.atlas["scene"], "-o", out]
        for key, value in {**self.base_sets(2e-6), **sets, "scene.output_interval": "1 us"}.items():
            args += ["--set", f"{key}={value}"]
        done = subprocess.run(args, capture_output=True, text=True, check=False)
        if done.returncode != 0:
            tail = " | ".join((done.stdout + done.stderr).strip().splitlines()[-2:])
            raise PointFailed(f"the kinematic cage speed's run exited with {done.returncode}: {tail}")
        with RacewayOutput(out) as f:
            speed = float(np.asarray(f["cage/epicyclic_speed"], dtype=float)[0])
        os.remove(out)
        return speed

    def times(self, point_id, sets):
        """(settling_time, end_time) [s] of a point's runs: the atlas's, or its window in cage
        revolutions, found once per point (the kinematic cage speed is the point's parameters', the
        same for its tighter-rtol rerun and its realisations)."""
        a = self.atlas
        if a["window_cage_revolutions"] is None:
            return a["settling_time_s"], a["end_time_s"]
        if point_id not in self._windows:
            self._windows[point_id] = revolution_times(self.kinematic_cage_speed(point_id, sets),
                                                       a["settling_cage_revolutions"], a["window_cage_revolutions"])
        return self._windows[point_id]

    def _run(self, name, sets, end_time):
        out = os.path.join(self.folder, name)
        for stale in (out + ".h5", out + ".h5.partial", out + ".h5.checkpoint"):
            if os.path.exists(stale):
                os.remove(stale)
        # No --summary-json: the summary is in the output (root attribute summary_json), and the
        # rating lives it would add cost a Python start per run.
        args = [self.raceway, "run", self.atlas["scene"], "-o", out + ".h5"]
        for key, value in {**self.base_sets(end_time), **sets}.items():
            args += ["--set", f"{key}={value}"]
        start = time.monotonic()
        with open(out + ".log", "w", encoding="utf-8") as log, _RUNNING_LOCK:
            if STOP.is_set():
                raise PointStopped(name)
            process = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT)
            _RUNNING.add(process)
        status = process.wait()
        with _RUNNING_LOCK:
            _RUNNING.discard(process)
        wall = time.monotonic() - start
        if status == 4 or (status != 0 and STOP.is_set()):
            raise PointStopped(name)
        if status != 0:
            with open(out + ".log", encoding="utf-8", errors="replace") as log:
                tail = " | ".join(log.read().strip().splitlines()[-2:])
            raise PointFailed(f"raceway run exited with {status}: {tail} (log: {out}.log)")
        return out, wall

    def remember_window(self, point_id, metrics):
        """A finished point's times (its record's metrics): its re-certification needs no short run."""
        if self.atlas["window_cage_revolutions"] is not None and "settling_time_s" in metrics:
            self._windows[point_id] = (metrics["settling_time_s"], metrics["end_time_s"])

    def evaluate(self, point_id, sets, tag="", reuse=False, later=0, longer=1):
        """The run's metrics; with `reuse`, an output of the same name already in the folder (a finished
        run: the writer renames it from .partial at the end) is read instead of run again; `later`
        windows more before the window and the window `longer` times as long (a probe's extension)."""
        from report_data import read_run

        name = point_id + (f"_{tag}" if tag else "")
        settling, end = self.times(point_id, sets)
        settling, end = settling + later * (end - settling), settling + (later + longer) * (end - settling)
        out = os.path.join(self.folder, name)
        if reuse and os.path.isfile(out + ".h5") and not os.path.exists(out + ".h5.partial"):
            wall = 0.0
        else:
            out, wall = self._run(name, sets, end)
        run = read_run(out + ".h5")
        mass = cm.output_cage_mass(out + ".h5")
        a = self.atlas
        m = cm.classify_run(run, settling, cage_mass=mass, overrides=a["thresholds"])
        m["settling_time_s"], m["end_time_s"] = settling, end
        add_friction_evidence(m, out + ".h5", settling, mass)
        window = np.nonzero(run.time >= settling)[0]
        blocks = []
        for s in ac.block_slices(len(window), a["certify"]["blocks"]):
            t0, t1 = run.time[window[s.start]], run.time[window[s.stop - 1]]
            blocks.append(cm.classify_run(run, t0, t1, cage_mass=mass, overrides=a["thresholds"]))
        m["blocks"] = [{"metric": b[a["metric"]], "class": b["motion_class"], "orbit_radius_m": b["orbit_radius_m"]}
                       for b in blocks]
        m["wall_s"] = wall
        m["output"] = os.path.relpath(out + ".h5", os.path.dirname(self.folder))
        return m


class StandinModel:
    """The tests' stand-in: the parameters mapped to the unit square, the class of
    atlas_search.standin_classes (unstable below the load 0.15 + 0.7 speed^2; with a third parameter
    w, below 0.15 + 0.7 speed^2 + 0.3 (w - 0.5); any further ones do nothing), the metric a logistic
    of the distance to that boundary; blocks, a tighter rtol and realisations perturb it by small
    amounts drawn from the point (deterministic). RACEWAY_ATLAS_STANDIN_DELAY (s) slows each evaluation
    (the resume test kills a slow atlas), RACEWAY_ATLAS_STANDIN_LOG names a file that gets each
    evaluated point's id, RACEWAY_ATLAS_STANDIN_FAIL the ids of points that fail."""

    def __init__(self, atlas, noise=0.0):
        self.atlas, self.noise = atlas, noise
        self.delay = float(os.environ.get("RACEWAY_ATLAS_STANDIN_DELAY", "0") or 0)

    def unit(self, sets):
        out = []
        for p in self.atlas["parameters"][:3]:
            out.append(parameter_unit(p, sets[p["key"]].split()[0]))
        return np.array(out)

    def evaluate(self, point_id, sets, tag="", reuse=False, later=0, longer=1):
        if self.delay:
            time.sleep(self.delay)
        if point_id in os.environ.get("RACEWAY_ATLAS_STANDIN_FAIL", "").split(","):
            raise PointFailed(f"stand-in: {point_id} fails (RACEWAY_ATLAS_STANDIN_FAIL)")
        if os.environ.get("RACEWAY_ATLAS_STANDIN_LOG"):  # the resume test: which points were evaluated
            with open(os.environ["RACEWAY_ATLAS_STANDIN_LOG"], "a", encoding="utf-8") as f:
                f.write(f"{point_id}\n")
        u = self.unit(sets)
        margin = u[1] - float(standin_boundary(u[0], *u[2:]))
        if self.noise > 0:
            margin += self.noise * math.sin(37.0 * u[0] + 53.0 * u[1])
        cls = "unstable" if margin < 0 else "stable"
        third = "".join(f",{v:.9f}" for v in u[2:])  # none with two parameters: their draws as before
        seed = zlib.crc32(f"{u[0]:.9f},{u[1]:.9f}{third},{tag}".encode())
        jitter = np.random.default_rng(seed).normal(0.0, 0.005, size=self.atlas["certify"]["blocks"] + 1)
        metric = 1.0 / (1.0 + math.exp(margin / 0.05))
        m = {self.atlas["metric"]: metric + float(jitter[0]), "motion_class": cls,
             "reasons": [f"stand-in margin {margin:.3g}"], "wall_s": self.delay, "output": ""}
        m["blocks"] = [{"metric": metric + float(j), "class": cls} for j in jitter[1:]]
        return m
