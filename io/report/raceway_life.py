#!/usr/bin/env python3
"""The rating lives of a run for `raceway run --summary-json` (docs/life.md):

    raceway_life.py OUT.h5 LIFE.json

writes to LIFE.json the `life` object (a `note` where the file lacks what it needs, as the race
contacts' loads of a run with [output] segments = false) that `raceway report` puts into its summary.json
(report_life.summarize_life over the report's default window, the run's second half): ISO 281 C,
P, L10, L_nm and ISO/TS 16281 L10r, L10mr from the window's race contact loads. The run command
finds this script beside the report's (io/report/life.cpp) and adds the object to its summary.

Exit codes: 0 done; 2 bad input (a missing file or dataset); 3 numpy or h5py missing; 1 another failure.
"""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

try:
    import numpy as np  # noqa: F401
    import h5py  # noqa: F401
except ImportError as err:
    print(f"[raceway] life: {err}", file=sys.stderr)
    sys.exit(3)

import report_metrics as rm  # noqa: E402
from report_data import ReportInputError, read_run  # noqa: E402
from report_life import summarize_life  # noqa: E402


def _finite(value):
    """NaN and infinities as None (JSON null), numpy scalars as numbers: as the report's summary.json
    (raceway_report.finite_json)."""
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    if hasattr(value, "item"):  # a numpy scalar
        return _finite(value.item())
    if isinstance(value, float) and (value != value or value in (float("inf"), float("-inf"))):
        return None
    return value


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    path, target = sys.argv[1:]
    try:
        run = read_run(path)
        life = summarize_life(run, rm.select_window(run.time))
    except ReportInputError as err:  # what the file lacks (the race contacts: [output] segments = false)
        life = {"note": f"no life: {err}"}
    except (OSError, KeyError, ValueError) as err:
        print(f"[raceway] life: {path}: {err}", file=sys.stderr)
        return 2
    with open(target + ".tmp", "w", encoding="utf-8") as f:
        json.dump(_finite(life), f, indent=2, allow_nan=False)
    os.replace(target + ".tmp", target)
    return 0


if __name__ == "__main__":
    sys.exit(main())
