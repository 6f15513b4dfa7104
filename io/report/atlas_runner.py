"""The atlas's loop (docs/atlas.md): batches of points proposed by the search, each run, classified
and certified, the state file written after every finished point, the table and the map at the end.

The state file DIR/atlas_state.json holds the atlas's identity (its settings but the budgets, and
its base scene's text: a finished atlas resumed with larger budgets goes on searching), the batch size, and every point: planned (proposed, not finished), done or failed, with its
results. A stop signal (SIGINT, SIGTERM, SIGUSR1) starts no new run, asks the running ones to
stop and leaves their points planned (exit 4). A stopped or killed atlas resumed with --resume
runs the planned points again and goes on; since a
batch is proposed only from finished points, in a fixed order, the resumed atlas is the
uninterrupted one.
"""
import hashlib
import json
import math
import os
import threading
from concurrent.futures import ThreadPoolExecutor

import atlas_certify as ac
import atlas_search as search
from atlas_file import parameter_value
import cage_motion as cm
from atlas_models import STOP, PointFailed, PointStopped, unit_value

STATE = "atlas_state.json"


class AtlasStateError(Exception):
    """The folder holds another atlas, or no atlas where --resume expects one (exit 2)."""


# What an atlas's points do not depend on: its budgets (how far the search goes; raised on --resume
# they extend a finished atlas), where its files lie, and its file's text as such (comments).
NOT_IDENTITY = ("budget_points", "budget_core_hours", "stop_band_share", "text", "lines", "path", "scene")
# Nor the certification's later keys: they decide how a point is certified, not its runs (a resumed
# atlas re-certifies its uncertified points with them).
NOT_IDENTITY_CERTIFY = ("threshold_realisations",)


def identity(atlas):
    """The atlas's identity: its parsed settings but the budgets, and its base scene's text."""
    with open(atlas["scene"], "rb") as f:
        scene = f.read()
    settings = {k: v for k, v in atlas.items() if k not in NOT_IDENTITY}
    settings["certify"] = {k: v for k, v in atlas["certify"].items() if k not in NOT_IDENTITY_CERTIFY}
    text = json.dumps(settings, sort_keys=True, default=str, allow_nan=True)
    return hashlib.sha256(text.encode() + b"\0" + scene).hexdigest()


def text_identity(atlas):
    """The identity atlases written before the budgets could be raised kept: the file's own text."""
    with open(atlas["scene"], "rb") as f:
        scene = f.read()
    return hashlib.sha256(atlas["text"].encode() + b"\0" + scene).hexdigest()


def save_state(folder, state):
    path = os.path.join(folder, STATE)
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        json.dump(state, f, indent=1, allow_nan=True)
    os.replace(path + ".tmp", path)


def open_state(atlas, folder, resume, batch_size):
    """The folder's state (resume) or a new one; refuses a folder of another atlas."""
    path = os.path.join(folder, STATE)
    if os.path.exists(path):
        if not resume:
            raise AtlasStateError(f"{folder} already holds an atlas ({STATE}): give --resume to continue it, "
                                  "or another folder")
        with open(path, encoding="utf-8") as f:
            state = json.load(f)
        if state.get("identity") not in (identity(atlas), text_identity(atlas)):
            raise AtlasStateError(f"{folder} holds another atlas (its settings other than the budgets, or its base "
                                  f"scene, differ from {atlas['path']}): refused, the folder's points would be "
                                  "mislabelled")
        state["identity"] = identity(atlas)
        return state
    os.makedirs(folder, exist_ok=True)
    state = {"identity": identity(atlas), "name": atlas["name"], "batch_size": batch_size, "points": [],
             "core_hours": 0.0, "stop": None}
    save_state(folder, state)
    return state


def point_sets(atlas, unit):
    """The --set overrides of the unit-cube point `unit` and the parameters' values."""
    sets, values = {}, {}
    for p, u in zip(atlas["parameters"], unit):
        values[p["name"]] = parameter_value(p, u)
        sets[p["key"]] = unit_value(values[p["name"]], p["unit"])
    return sets, values


def mapped_class(cls, classes):
    """The class the map shows: a class left out of the atlas's list joins its neighbour; None for
    "unknown" (no clearance in the output: such a point trains nothing)."""
    if cls in classes:
        return cls
    if cls not in ("stable", "circling", "unstable"):
        return None
    if cls == "circling":
        return "stable" if "stable" in classes else "unstable"
    return "circling"


def run_settled(atlas, run, window_class=None):
    """The settled record of one run's window (its blocks), for `window_class` (default: its own)."""
    c, blocks = atlas["certify"], run["blocks"]
    return ac.settled([b["metric"] for b in blocks], [b["class"] for b in blocks], window_class or run["motion_class"],
                      c["block_tolerance"], [b.get("orbit_radius_m", math.nan) for b in blocks], c["growth_tolerance"])


# A probe that neither persists nor has decayed below the sustained amplitude in its window is run
# longer, PROBE_LATER windows more before its window (its window as long, that much later), the
# first and, still undecided, the second: the cap of its extension. Each longer run's last two
# windows are read too, as one window twice as long (segments of twice the revolutions: a whirl
# between two spectral bins of the short segments, whose line hops between them, is one line at
# their finer resolution); it persists if either reading says so.
PROBE_LATER = (2, 6)


def later_probe(model, point, sets, rerun, tag, more, later):
    """An undecided probe run longer: its last window's metrics, or where they do not call it unstable
    and its last two windows' do, theirs (the same run's output, read again)."""
    m = rerun(tag, more, later)
    if m["motion_class"] != "unstable":
        wide = model.evaluate(point["id"], {**sets, **more}, tag, reuse=True, later=later - 1, longer=2)
        if wide["motion_class"] == "unstable":
            wide["wall_s"], wide["window_read"] = m["wall_s"], "last two windows"
            m = wide
    m["later_windows"] = later
    return m


def probe(model, atlas, point, sets, base, cert, rerun):
    """The stability probe of a point whose window cannot say where its whirl ends: the realisations'
    start offsets, run once (shared with the realisations), an undecided one longer (PROBE_LATER);
    the class they agree on, or None."""
    c = atlas["certify"]
    t = cm.thresholds(atlas["thresholds"])
    if not (ac.needs_probe(cert["settled"], base, t) and c["realisations"]
            and c["realisation_key"] == "cage.initial_offset"):
        return None
    key = c["realisation_key"]
    runs = [(v, rerun(f"r{i}", {key: v})) for i, v in enumerate(c["realisations"])]
    for step, later in enumerate(PROBE_LATER):
        words, _ = ac.probe_words(runs, [run_settled(atlas, m) for _, m in runs], t)
        for i, (v, m) in enumerate(runs):
            if words[i] == "undecided":
                runs[i] = (v, later_probe(model, point, sets, rerun, f"r{i}_later" + (f"{later}" if step else ""),
                                          {key: v}, later))
    records = [run_settled(atlas, m) for _, m in runs]
    cert["probe"] = ac.probes(base, runs, records, t)
    if not cert["probe"]["ok"]:
        return None
    cert["settled"] = run_settled(atlas, base, cert["probe"]["class"])
    return cert["probe"]["class"]


def threshold(atlas, base, tight, rerun):
    """A point whose tighter-rtol rerun changes its class: the threshold's record over the base, the
    rerun, the realisations and the threshold realisations (start offsets)."""
    c = atlas["certify"]
    values = c["realisations"] + c["threshold_realisations"]
    runs = [base, tight] + [rerun(f"r{i}" if i < len(c["realisations"]) else f"t{i - len(c['realisations'])}",
                                  {c["realisation_key"]: v}) for i, v in enumerate(values)]
    record = ac.threshold_decision(runs, cm.thresholds(atlas["thresholds"]),
                                   lambda m: cm.classify_metrics(m, atlas["thresholds"]))
    record["key"], record["values"] = c["realisation_key"], values
    return record


def certify(model, atlas, point, sets, base, reuse=False):
    """The point's certification (atlas_certify), its class and the wall time of its extra runs; with
    `reuse`, runs whose output is in the folder are read, not made again (re-certification)."""
    c, metric = atlas["certify"], atlas["metric"]
    done = {}

    def rerun(tag, more, later=0):
        if tag not in done:
            done[tag] = model.evaluate(point["id"], {**sets, **more}, tag, reuse=reuse, later=later)
        return done[tag]

    cert = {"rule": ac.RULE, "settled": run_settled(atlas, base), "probe": {"checked": False}}
    cls = probe(model, atlas, point, sets, base, cert, rerun) or base["motion_class"]
    cert["converged"], cert["threshold"] = {"checked": False}, {"checked": False}
    if ac.in_convergence_sample(point["index"], c["convergence_sample"]):
        tight = rerun("rtol", {"solver.rtol": f"{c['convergence_rtol']:g}"})
        # Against the base run (both start centred: a probe speaks for both).
        cert["converged"] = ac.converged(base["motion_class"], base[metric], tight["motion_class"], tight[metric],
                                         c["convergence_rtol"], c["convergence_tolerance"])
        if tight["motion_class"] != base["motion_class"] and c["realisations"]:
            cert["threshold"] = threshold(atlas, base, tight, rerun)
            cls = cert["threshold"]["class"] or cls
    cert["realisations"] = {"checked": False}
    if cls == "unstable" and c["realisations"]:
        values = [base[metric]] + [rerun(f"r{i}", {c["realisation_key"]: v})[metric]
                                   for i, v in enumerate(c["realisations"])]
        cert["realisations"] = ac.confidence(values, c["ci_target"])
        cert["realisations"]["key"] = c["realisation_key"]
    cert["class"] = cls
    return cert, sum(r["wall_s"] for r in done.values())


def certify_reasons(atlas, base, cert):
    """The base's reasons and what the probe or the threshold's runs added."""
    reasons = list(base.get("reasons", []))
    if cert["probe"].get("checked"):
        reasons.append(ac.probe_reason(cert["probe"], atlas["certify"]["realisation_key"],
                                       cm.thresholds(atlas["thresholds"])["whirl_growth_min_amplitude"]))
    if cert["threshold"].get("checked"):
        reasons.append("on a class threshold (the rtol rerun's class differs): " + ac.summary(
            {"settled": {"ok": True}, "threshold": cert["threshold"]}).split("; ", 1)[1])
    return reasons


def evaluate_point(model, atlas, point, reuse=False):
    """Runs and certifies one point; its record's results (status done or failed). With `reuse`, the
    runs whose output is in the folder are read again, not made (re-certification)."""
    sets, _ = point_sets(atlas, point["unit"])
    try:
        base = model.evaluate(point["id"], sets, reuse=reuse)
        cert, extra = certify(model, atlas, point, sets, base, reuse)
    except PointStopped:
        return {"status": "planned"}
    except PointFailed as err:
        return {"status": "failed", "error": str(err), "wall_s": 0.0}
    except Exception as err:  # an unreadable output, a window without samples: the point, not the atlas
        return {"status": "failed", "error": f"{type(err).__name__}: {err}", "wall_s": 0.0}
    metrics = {k: v for k, v in base.items() if k not in ("blocks", "wall_s", "output", "reasons")}
    return {"status": "done", "class": cert["class"], "label": mapped_class(cert["class"], atlas["classes"]),
            "metric": cert.get("realisations", {}).get("mean", base[atlas["metric"]]),
            "reasons": certify_reasons(atlas, base, cert), "metrics": metrics, "certification": cert,
            "certified": ac.certified(cert), "certified_by": ac.summary(cert), "output": base.get("output", ""),
            "wall_s": base["wall_s"] + extra}


def recertify(model, atlas, state, folder, workers, log):
    """A resumed atlas's points certified before the current rule and not certified then, or that
    the rule would probe: their outputs read again and certified with the rule (the probe, the
    threshold's runs), only the runs missing made. Their wall time adds to the core-hours."""
    t = cm.thresholds(atlas["thresholds"])

    def stale(p):
        cert = p.get("certification", {})
        if p["status"] != "done" or cert.get("rule") == ac.RULE:
            return False
        m = p.get("metrics", {})
        unprobed = not cert.get("probe", {}).get("checked")
        # A record without the segments' lines, whose whirl grows but was not one line: read again.
        unread = "subsync_frequencies" not in m and m.get("motion_class") in ("stable", "circling") and \
            not m.get("subsync_coherent") and m.get("subsync_growth_per_rev", math.nan) > t["whirl_growth_rate"]
        probed_stable = cert.get("probe", {}).get("class") in ("stable", "circling")  # its probes read again
        return not p.get("certified") or not ac.certified(cert) or probed_stable or (
            unprobed and (unread or ac.needs_probe(cert["settled"], m, t)))
    todo = [p for p in state["points"] if stale(p)]
    lock = threading.Lock()

    def one(point):
        if STOP.is_set():
            return
        if hasattr(model, "remember_window"):
            model.remember_window(point["id"], point["metrics"])
        result = evaluate_point(model, atlas, point, reuse=True)
        if result["status"] != "done":
            return  # stopped or unreadable: the point keeps its record
        with lock:
            was = point["class"]
            result["wall_s"] += point.get("wall_s", 0.0)
            state["core_hours"] += (result["wall_s"] - point.get("wall_s", 0.0)) / 3600.0
            point.update(result)
            save_state(folder, state)
            log(f"{point['id']} re-certified: {was} -> {point['class']}, {point['certified_by']}")

    with ThreadPoolExecutor(max_workers=max(1, workers)) as pool:
        list(pool.map(one, todo))


def run_pending(model, atlas, state, folder, workers, log):
    """Runs the planned points, `workers` at a time; the state is saved after each."""
    pending = [p for p in state["points"] if p["status"] == "planned"]
    lock = threading.Lock()

    def one(point):
        if STOP.is_set():
            return
        result = evaluate_point(model, atlas, point)
        if result["status"] == "planned":
            return
        with lock:
            point.update(result)
            state["core_hours"] += result["wall_s"] / 3600.0
            save_state(folder, state)
            log(f"{point['id']} {point['status']}: " + (f"{point['class']}, {atlas['metric']} {point['metric']:.3g}, "
                f"{point['certified_by']}" if point["status"] == "done" else point["error"]))

    with ThreadPoolExecutor(max_workers=max(1, workers)) as pool:
        list(pool.map(one, pending))


def next_batch(atlas, state):
    """The next points (unit cube) and the search's record of them, or [] with state['stop'] saying why
    the search ends."""
    points, d = state["points"], len(atlas["parameters"])
    left = atlas["budget_points"] - len(points)
    if left <= 0:
        state["stop"] = f"the budget of {atlas['budget_points']} points is spent"
        return [], None
    if state["core_hours"] >= atlas["budget_core_hours"]:
        state["stop"] = f"the budget of {atlas['budget_core_hours']:g} core-hours is spent"
        return [], None
    if not points:
        return list(search.initial_design(d))[:left], {"rule": "initial design: the corners and the centre"}
    done = [p for p in points if p["status"] == "done" and p.get("label")]
    labels = [p["label"] for p in done]
    units = [p["unit"] for p in done]
    model = record = None
    if len(set(labels)) > 1:
        model, record = search.search_classifier(units, labels)
    # An untrusted classifier's band is no measure of the map: the search goes on.
    if atlas["stop_band_share"] > 0 and record and record["trusted"]:
        band = search.band_share(model, search.candidate_pool(d))
        if band < atlas["stop_band_share"]:
            state["stop"] = (f"the uncertainty band (u > {search.BAND_UNCERTAINTY:g}) covers {band:.4g} of the "
                             f"map, less than stop_band_share {atlas['stop_band_share']:g}")
            return [], None
    taken = [p["unit"] for p in points]  # failed points too: not proposed again
    return search.propose_batch(units, labels, min(left, state["batch_size"]), taken=taken, model=model,
                                record=record)


def add_batch(state, batch, record):
    """The batch's points, planned, and the search's record of it (state['batches'])."""
    number = 1 + max((p["batch"] for p in state["points"]), default=-1)
    for unit in batch:
        index = len(state["points"])
        state["points"].append({"id": f"p{index:04d}", "index": index, "batch": number,
                                "unit": [float(u) for u in unit], "status": "planned"})
    state.setdefault("batches", []).append({"batch": number, "points": len(batch), **record})


def batch_note(record):
    """The log's word on a batch: how many points the search placed by exploring, and why."""
    if not record.get("explored"):
        return ""
    return f" ({record['explored']} by space filling: the classifier is untrusted, {'; '.join(record['reasons'])})"


def run_atlas(model, atlas, folder, resume, batch_size, workers, log):
    """The whole atlas into `folder`; returns the state."""
    state = open_state(atlas, folder, resume, batch_size)
    if state["batch_size"] != batch_size:
        log(f"batch size {state['batch_size']} from the folder's state (asked: {batch_size}): a resumed atlas keeps "
            "its batches")
    state["stop"] = None
    recertify(model, atlas, state, folder, workers, log)
    while True:
        run_pending(model, atlas, state, folder, workers, log)
        if STOP.is_set():
            state["stop"] = "stopped by a signal: continue with --resume"
            break
        batch, record = next_batch(atlas, state)
        if not batch:
            break
        add_batch(state, batch, record)
        for p in state["points"][-len(batch):]:
            p["values"] = point_sets(atlas, p["unit"])[1]
        save_state(folder, state)
        log(f"batch {state['points'][-1]['batch']}: {len(batch)} points{batch_note(record)}")
    save_state(folder, state)
    log(f"search ended: {state['stop']}")
    return state
