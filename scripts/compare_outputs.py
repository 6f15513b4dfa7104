#!/usr/bin/python3
"""Bitwise comparison of two raceway outputs, for refactors that must not change results.

    compare_outputs.py A.h5 B.h5 [--map OLD=NEW ...] [--ignore PATH ...] [--ignore-attr NAME ...]
                       [--scheduler] [--stored-chunks] [--quiet]
    compare_outputs.py A.json B.json        two run summaries (--summary-json files)

Every dataset and every attribute of A must be in B with the same type, shape and bytes: the
values are compared as raw bytes (numpy array_equal on their uint8 views), so a NaN equals a NaN
of the same bits and 0.0 differs from -0.0. A difference is reported with how many values differ,
the largest one and where. --map OLD=NEW reads A's OLD as B's NEW (a dataset, an attribute path
`/group@name`, or a group prefix: `--map /cage/angle=/cage/angles`); repeat it for several.

Left out because they legitimately differ between two runs of the same results:
  - root attributes IGNORED_ROOT_ATTRIBUTES: the build (raceway_version, raceway_commit) and the
    scene's path (scene_source; its text, scene_text, is compared);
  - in the summary (the root attribute summary_json and the JSON files) the wall-clock fields
    TIMING_KEYS;
  - the group /scheduler (the executor's plans, measured task times, rank count: they depend on
    the rank count and on the machine's load; results do not), unless --scheduler;
  - object addresses: dimension-scale references (DIMENSION_LIST, REFERENCE_LIST) are compared
    as the names they point to.
HDF5 stores no creation or modification times (the writer turns them off), so there are none to
leave out. --stored-chunks also compares each chunk as stored (offset, filter mask, and its bytes,
a deflated chunk's inflated: the deflate encoder's bit stream is not part of the result). Exit code: 0 identical, 1 differences, 2 bad use or an unreadable file.
"""
import argparse
import json
import sys
import zlib

import h5py
import numpy as np

IGNORED_ROOT_ATTRIBUTES = ("raceway_version", "raceway_commit", "scene_source")
TIMING_KEYS = ("wall_time_s", "time_per_rhs_s", "time_per_jacobian_s", "time_split_s", "output_time_s",
               "output_write_time_s", "output_thread_time_s")
SKIPPED_GROUPS = ("/scheduler",)
REFERENCE_ATTRIBUTES = ("DIMENSION_LIST", "REFERENCE_LIST")


def without_timings(summary):
    return {k: v for k, v in summary.items() if k not in TIMING_KEYS}


def dereferenced(f, value):
    """Object references (dimension-scale lists) as the names they point to."""
    if isinstance(value, h5py.Reference):
        return f[value].name if value else None
    if isinstance(value, (np.ndarray, list, tuple, np.void)):
        return tuple(dereferenced(f, v) for v in value)
    return value.item() if isinstance(value, np.generic) else value


def as_array(value):
    """An attribute or dataset value as (kind, payload): numeric and fixed-size values as a numpy
    array (compared by bytes), strings and objects as Python values."""
    if isinstance(value, (bytes, str)):
        return "text", value.decode("utf-8", "replace") if isinstance(value, bytes) else value
    array = np.asarray(value)
    if array.dtype.kind == "O":
        return "text", repr([v.decode("utf-8", "replace") if isinstance(v, bytes) else v
                             for v in array.reshape(-1).tolist()]) + f" shape {array.shape}"
    return "array", array


def stored_chunks(dataset):
    """Each chunk as stored: offset, filter mask and bytes, a deflated chunk's bytes inflated. The
    deflate filter's stream is left out: raceway's background compressor and HDF5's own pipeline
    (the parallel writer) encode the same bytes differently (libdeflate's and zlib's deflate), and
    zlib reads both; what the chunk holds, down to the shuffled bytes, is compared."""
    if dataset.chunks is None:
        return None
    plist = dataset.id.get_create_plist()
    filters = [plist.get_filter(i)[0] for i in range(plist.get_nfilters())]
    deflate_bit = 1 << filters.index(h5py.h5z.FILTER_DEFLATE) if h5py.h5z.FILTER_DEFLATE in filters else 0
    chunks = []
    for i in range(dataset.id.get_num_chunks()):
        offset = dataset.id.get_chunk_info(i).chunk_offset
        mask, data = dataset.id.read_direct_chunk(offset)
        if deflate_bit and not mask & deflate_bit:
            data = zlib.decompress(data)
        chunks.append((offset, mask, data))
    return sorted(chunks)


def renamed(path, mapping):
    """path under the name map (longest matching prefix on whole components)."""
    for old, new in mapping:
        if path == old or path.startswith(old + "/") or path.startswith(old + "@"):
            return new + path[len(old):]
    return path


def collect(path, args, mapping):
    """{name: value} for every dataset ('/a/b'), attribute ('/a/b@attr') and group ('/a/') of a
    file, names under the map."""
    items = {}
    with h5py.File(path, "r") as f:
        def add_attributes(name, obj):
            for key, value in obj.attrs.items():
                if key in args.ignore_attr or (name == "/" and key in IGNORED_ROOT_ATTRIBUTES):
                    continue
                if key in REFERENCE_ATTRIBUTES:
                    items[renamed(f"{name}@{key}", mapping)] = (
                        "text", repr(tuple(renamed(n, mapping) if isinstance(n, str) else n
                                           for n in flatten(dereferenced(f, value)))))
                    continue
                if name == "/" and key == "summary_json":  # one item per summary value
                    for field, v in without_timings(json.loads(value)).items():
                        items[f"/@summary_json.{field}"] = ("text", json.dumps(v, sort_keys=True))
                    continue
                items[renamed(f"{name}@{key}", mapping)] = as_array(value)

        add_attributes("/", f)

        def visit(name, obj):
            full = "/" + name
            if any(full == g or full.startswith(g + "/") for g in skipped(args)):
                return
            if isinstance(obj, h5py.Dataset):
                items[renamed(full, mapping)] = as_array(obj[()])
                if args.stored_chunks:
                    items[renamed(full, mapping) + "#chunks"] = ("text", repr(stored_chunks(obj)))
            else:
                items[renamed(full, mapping) + "/"] = ("text", "group")
            add_attributes(full, obj)

        f.visititems(visit)
    return items


def flatten(value):
    if isinstance(value, tuple):
        for v in value:
            yield from flatten(v)
    else:
        yield value


def skipped(args):
    return tuple(args.ignore) + (() if args.scheduler else SKIPPED_GROUPS)


def describe(a, b):
    """Why two values differ, in one line."""
    (kind_a, x), (kind_b, y) = a, b
    if kind_a != kind_b:
        return f"{kind_a} in A, {kind_b} in B"
    if kind_a == "text":
        return f"{shorten(x)} against {shorten(y)}"
    if x.dtype != y.dtype or x.shape != y.shape:
        return f"{x.dtype} {x.shape} against {y.dtype} {y.shape}"
    if x.dtype.names or x.dtype.kind not in "biuf":
        return "bytes differ"
    xb = x.view(np.uint8).reshape(x.shape + (-1,)) if x.ndim else np.frombuffer(x.tobytes(), np.uint8)[None]
    yb = y.view(np.uint8).reshape(y.shape + (-1,)) if y.ndim else np.frombuffer(y.tobytes(), np.uint8)[None]
    differing = np.any(xb != yb, axis=-1).reshape(x.shape)
    xf, yf = x.astype(float), y.astype(float)
    text = f"{int(differing.sum())} of {x.size} values differ"
    nan_in_one = np.isnan(xf) != np.isnan(yf)
    numeric = differing & ~np.isnan(xf) & ~np.isnan(yf)
    if numeric.any():
        diff = np.where(numeric, np.abs(xf - yf), -1.0)
        where = np.unravel_index(int(np.argmax(diff)), x.shape) if x.ndim else ()
        scale = float(np.nanmax(np.abs(xf))) if x.size else 0.0
        text += (f"; largest |A - B| {float(diff[where]):.3g}"
                 f"{f' ({float(diff[where]) / scale:.2g} of max |A|)' if scale else ''}"
                 f" at {list(where)}: {xf[where]!r} against {yf[where]!r}")
    if nan_in_one.any():
        first = np.argwhere(nan_in_one)[0].tolist() if x.ndim else []
        text += f"; NaN in one file only at {int(nan_in_one.sum())} place(s), first {first}"
    nan_bits = differing & np.isnan(xf) & np.isnan(yf)
    if nan_bits.any():
        text += f"; NaN of other bits at {int(nan_bits.sum())} place(s)"
    return text


def shorten(text, limit=120):
    """One line of at most limit characters (text with line breaks as its repr)."""
    text = repr(text) if isinstance(text, str) and "\n" in text else str(text)
    return text if len(text) <= limit else text[:limit] + f"... ({len(text)} characters)"


def same(a, b):
    if a[0] != b[0]:
        return False
    if a[0] == "text":
        return a[1] == b[1]
    x, y = a[1], b[1]
    return x.dtype == y.dtype and x.shape == y.shape and np.array_equal(
        np.frombuffer(x.tobytes(), np.uint8), np.frombuffer(y.tobytes(), np.uint8))


def compare_h5(args):
    mapping = sorted((tuple(m.split("=", 1)) for m in args.map), key=lambda m: -len(m[0]))
    a, b = collect(args.a, args, mapping), collect(args.b, args, [])
    differences = []
    for name in sorted(set(a) | set(b)):
        if name not in b:
            differences.append(f"{name}: only in A")
        elif name not in a:
            differences.append(f"{name}: only in B")
        elif not same(a[name], b[name]):
            differences.append(f"{name}: {describe(a[name], b[name])}")
    datasets = sum(1 for n in a if not n.endswith("/") and "@" not in n and "#" not in n)
    attributes = sum(1 for n in a if "@" in n)
    return differences, f"{datasets} datasets and {attributes} attributes"


def compare_json(args):
    try:
        with open(args.a) as fa, open(args.b) as fb:
            a, b = without_timings(json.load(fa)), without_timings(json.load(fb))
    except (OSError, ValueError) as error:
        raise OSError(f"cannot read the summaries: {error}")
    differences = []
    for key in list(a) + [k for k in b if k not in a]:
        if key not in b or key not in a:
            differences.append(f"{key}: only in {'A' if key in a else 'B'}")
        # repr of a float is its shortest round trip: equal text, equal bits (0.0 and -0.0 differ)
        elif json.dumps(a[key], sort_keys=True) != json.dumps(b[key], sort_keys=True):
            differences.append(f"{key}: {shorten(json.dumps(a[key]))} against {shorten(json.dumps(b[key]))}")
    return differences, f"{len(a)} summary values"


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("a", metavar="A")
    parser.add_argument("b", metavar="B")
    parser.add_argument("--map", action="append", default=[], metavar="OLD=NEW")
    parser.add_argument("--ignore", action="append", default=[], metavar="PATH",
                        help="leave out a dataset or group (and everything under it) besides /scheduler")
    parser.add_argument("--ignore-attr", action="append", default=[], metavar="NAME",
                        help="leave out attributes of this name, wherever they are")
    parser.add_argument("--scheduler", action="store_true", help="compare /scheduler too")
    parser.add_argument("--stored-chunks", action="store_true")
    parser.add_argument("--quiet", action="store_true", help="only the verdict line")
    args = parser.parse_args(argv)
    for m in args.map:
        if "=" not in m or not m.startswith("/") or not m.split("=", 1)[1].startswith("/"):
            parser.error(f"--map {m}: give /OLD=/NEW (absolute paths)")
    json_pair = args.a.endswith(".json") and args.b.endswith(".json")
    try:
        differences, what = (compare_json if json_pair else compare_h5)(args)
    except OSError as error:
        print(f"compare_outputs: {args.a} / {args.b}: {error}", file=sys.stderr)
        return 2
    if not args.quiet:
        for line in differences:
            print(f"  DIFF {line}")
    verdict = "identical" if not differences else f"{len(differences)} difference(s)"
    print(f"{args.a} vs {args.b}: {what} compared: {verdict}")
    return 0 if not differences else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
