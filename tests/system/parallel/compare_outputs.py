#!/usr/bin/python3
"""Bitwise comparison of raceway output files (the reference first, then the others).

Every dataset outside /scheduler must have the same shape, dtype and bytes (the values, and each
stored chunk: offset, filter mask, its bytes with the deflate filter undone: the serial writer's
libdeflate and the parallel writer's zlib encode the same bytes differently); every attribute
must be equal, except the ones that legitimately differ between runs: the root's summary_json
is compared without its timing fields (wall_time_s, time_per_rhs_s, time_per_jacobian_s, time_split_s, output_time_s,
output_write_time_s, output_thread_time_s), and
/scheduler (plans, imbalance, rank count) is skipped. Exit 0 when all files match, 1 otherwise.

    compare_outputs.py [--known PATH ...] REFERENCE.h5 OTHER.h5 [OTHER.h5 ...]

--known PATH: a dataset (and its chunks) whose difference is a known, documented defect: it is
still compared and its difference printed as "known", but not counted as a failure.
"""
import json
import os
import sys

import h5py
import numpy as np

# The timing fields, the skipped groups, references as names and chunks as stored: the same as the
# refactor comparison's (scripts/compare_outputs.py), which this one extends to several files.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))
from compare_outputs import SKIPPED_GROUPS, TIMING_KEYS, dereferenced, stored_chunks  # noqa: E402


def has_references(v):
    return isinstance(v, np.ndarray) and (v.dtype.kind == "O" or (v.dtype.names and any(
        v.dtype.fields[n][0].kind == "O" for n in v.dtype.names)))


def collect(path):
    items = {}
    with h5py.File(path, "r") as f:
        def attrs_of(name, obj):
            out = {}
            for k, v in obj.attrs.items():
                if has_references(v):
                    out[k] = repr(dereferenced(f, v))
                    continue
                if name == "/" and k == "summary_json":
                    d = json.loads(v)
                    for key in TIMING_KEYS:
                        d.pop(key, None)
                    v = json.dumps(d, sort_keys=True)
                if isinstance(v, np.ndarray):
                    v = repr(v.tolist()) if v.dtype.kind == "O" else (str(v.dtype), v.shape, v.tobytes())
                out[k] = v
            return out

        items["/"] = ("group", attrs_of("/", f))

        def visit(name, obj):
            full = "/" + name
            if full.startswith(SKIPPED_GROUPS):
                return
            if isinstance(obj, h5py.Dataset):
                data = obj[()]
                raw = data.tobytes() if isinstance(data, np.ndarray) and data.dtype.kind != "O" else repr(data.tolist() if isinstance(data, np.ndarray) else data)
                items[full] = ("dataset", str(obj.dtype), obj.shape, raw, attrs_of(full, obj), stored_chunks(obj))
            else:
                items[full] = ("group", attrs_of(full, obj))

        f.visititems(visit)
    return items


def main(argv):
    known = []
    while len(argv) > 2 and argv[1] == "--known":
        known.append(argv[2])
        argv = argv[:1] + argv[3:]
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    reference = collect(argv[1])
    datasets = sum(1 for v in reference.values() if v[0] == "dataset")
    if datasets == 0:
        print(f"{argv[1]}: no datasets", file=sys.stderr)
        return 1
    failures = 0
    for other_path in argv[2:]:
        other = collect(other_path)
        for name in sorted(set(reference) | set(other)):
            if name not in other or name not in reference:
                print(f"{other_path}: {name} only in {'the reference' if name in reference else 'this file'}")
                failures += 1
            elif reference[name] != other[name]:
                if any(name == k or name.startswith(k + "/") or name.startswith(k + " ") for k in known):
                    print(f"{other_path}: {name} differs from {argv[1]} (known)")
                    continue
                print(f"{other_path}: {name} differs from {argv[1]}")
                failures += 1
    print(f"compared {datasets} datasets of {argv[1]} with {len(argv) - 2} file(s): "
          f"{'identical' if failures == 0 else f'{failures} difference(s)'}")
    return 0 if failures == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
