#!/usr/bin/env python3
"""Where the output's CPU goes per sample, from `perf script -F tid,ip,sym` of a call-graph profile
(perf/studies/output_full_load.sh): each stack sample counts for every part whose function is on it.

    output_cost_profile.py STACKS FREQUENCY_HZ SUMMARY_JSON
"""
import json
import sys

# (part, functions that must all be on the stack, functions that must not)
PARTS = [
    ("chunk compressor (its thread, and the commit's last chunks)", ["filter_chunk"], []),
    ("right-hand side at output times", ["RunLoop::write_sample", "Equations::rhs"], []),
    ("appends, with the flushes they call (OutputWriter::append)", ["OutputWriter::append"], []),
    ("energy and summary sums", ["RunLoop::write_sample"], ["Equations::rhs", "OutputWriter::append"]),
    ("flushes but those of the appends (H5SeriesWriter::flush)", ["H5SeriesWriter::flush"],
     ["filter_chunk", "OutputWriter::append"]),
    ("commit, less filtering (H5SeriesWriter::commit)", ["H5SeriesWriter::commit"], ["filter_chunk"]),
]


def stacks(path):
    frames = None
    for line in open(path):
        if not line.strip():
            if frames is not None:
                yield frames
            frames = None
        elif not line.startswith("\t"):  # a sample's header (the thread id, maybe padded)
            frames = []
        elif frames is not None:  # a frame: tab, address, symbol
            parts = line.split(None, 1)
            frames.append(parts[1] if len(parts) > 1 else parts[0])
    if frames is not None:
        yield frames


def main():
    path, hz, summary = sys.argv[1], float(sys.argv[2]), json.load(open(sys.argv[3]))
    samples = summary["output_samples"]
    counts = [0] * len(PARTS)
    total = 0
    for frames in stacks(path):
        total += 1
        text = "\n".join(frames)
        for i, (_, need, avoid) in enumerate(PARTS):
            if all(n in text for n in need) and not any(a in text for a in avoid):
                counts[i] += 1
    print(f"CPU of all threads {total / hz:.3f} s, {samples} samples")
    output = 0.0
    for (name, _, _), count in zip(PARTS, counts):
        seconds = count / hz
        output += seconds
        print(f"  {name:62s} {seconds:6.3f} s {1e6 * seconds / samples:6.1f} us/sample {100 * count / total:5.1f} %")
    print(f"  {'the output, all parts':62s} {output:6.3f} s {1e6 * output / samples:6.1f} us/sample "
          f"{100 * output * hz / total:5.1f} %")


if __name__ == "__main__":
    main()
