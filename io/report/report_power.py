"""The power balance over the report's window (docs/output_layout.md, "Power balance"): the work of
each input and loss between the window's first and last samples, integrated by the run over its
solver steps (/power_balance/*), the stored energy's change and what is left (the integrator's)."""
import numpy as np


def read_power(out):
    """{inputs: (names, [T x 4]), losses: (names, [T x L]), stored: [T]} or None (an older file)."""
    if "power_balance/input_work" not in out:
        return None
    return {"inputs": (out.components("power_balance/input_work"),
                       np.asarray(out["power_balance/input_work"], dtype=float)),
            "losses": (out.components("power_balance/loss_work"),
                       np.asarray(out["power_balance/loss_work"], dtype=float)),
            "stored": np.asarray(out["power_balance/stored_energy"], dtype=float)}


def summarize_power(balance, w):
    """The balance between the window's first and last samples (J); None without the series."""
    if balance is None or w.samples < 2:
        return None
    first, last = w.slice.start, w.slice.stop - 1
    out = {}
    totals = {}
    for group, key in (("inputs", "input_work_j"), ("losses", "loss_work_j")):
        names, work = balance[group]
        values = {str(n): float(work[last, i] - work[first, i]) for i, n in enumerate(names)}
        out[key] = values
        totals[group] = sum(values.values())
    stored = float(balance["stored"][last] - balance["stored"][first])
    residual = totals["inputs"] - totals["losses"] - stored
    out.update({"input_work_total_j": totals["inputs"], "loss_work_total_j": totals["losses"],
                "stored_energy_change_j": stored, "residual_j": residual,
                "relative_residual": residual / abs(totals["inputs"]) if totals["inputs"] else 0.0,
                "mean_input_power_w": totals["inputs"] / (w.t_end - w.t_begin) if w.t_end > w.t_begin else 0.0})
    return out


def power_rows(p):
    """(quantity, value) rows of the report page's power balance table."""
    rows = [(f"input: {k}", f"{v:.6g} J") for k, v in p["input_work_j"].items() if v != 0.0]
    rows += [(f"loss: {k}", f"{v:.6g} J") for k, v in p["loss_work_j"].items() if v != 0.0]
    rows += [("inputs, total", f"{p['input_work_total_j']:.6g} J"),
             ("losses, total", f"{p['loss_work_total_j']:.6g} J"),
             ("stored energy change", f"{p['stored_energy_change_j']:.6g} J"),
             ("residual (inputs - losses - stored change)",
              f"{p['residual_j']:.4g} J = {100 * p['relative_residual']:.3g} % of the inputs"),
             ("mean input power", f"{p['mean_input_power_w']:.6g} W")]
    return rows


def read_thermal(out):
    """{parts, temperature [T x 6], heat_input [T x 6], links, link_flow [T x L]} or None (no network)."""
    if "thermal/temperature" not in out:
        return None
    return {"parts": [str(n) for n in out.components("thermal/temperature")],
            "temperature": np.asarray(out["thermal/temperature"], dtype=float),
            "heat_input": np.asarray(out["thermal/heat_input"], dtype=float),
            "links": [str(n) for n in out.components("thermal/link_flow")],
            "link_flow": np.asarray(out["thermal/link_flow"], dtype=float)}


def summarize_thermal(thermal, w):
    """The temperatures at the window's ends and the heat flows' means over it; None without a network."""
    if thermal is None:
        return None
    first, last = w.slice.start, w.slice.stop - 1
    return {"temperature_start_k": dict(zip(thermal["parts"], map(float, thermal["temperature"][first]))),
            "temperature_end_k": dict(zip(thermal["parts"], map(float, thermal["temperature"][last]))),
            "heat_input_mean_w": dict(zip(thermal["parts"], map(float, np.mean(thermal["heat_input"][w.slice], axis=0)))),
            "link_flow_mean_w": dict(zip(thermal["links"], map(float, np.mean(thermal["link_flow"][w.slice], axis=0))))}


def thermal_rows(t):
    """(quantity, value) rows of the report page's thermal table."""
    rows = [(f"{p}: temperature (window start -> end)",
             f"{t['temperature_start_k'][p] - 273.15:.5g} -> {t['temperature_end_k'][p] - 273.15:.5g} degC")
            for p in t["temperature_end_k"]]
    rows += [(f"{p}: heat input (mean)", f"{v:.4g} W") for p, v in t["heat_input_mean_w"].items()]
    rows += [(f"link {k}: heat flow (mean)", f"{v:.4g} W") for k, v in t["link_flow_mean_w"].items()]
    return rows
