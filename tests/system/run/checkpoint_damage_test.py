#!/usr/bin/env python3
"""Damaged checkpoints never resume silently and never hang `raceway run --resume`
(docs/output_layout.md, "Checkpoints and resume"), one case per ctest:

    checkpoint_damage_test.py CASE RACEWAY SOURCE_DIR

A real checkpoint is made first: 6309 R3 with a checkpoint every 2 ms, stopped by SIGUSR1 after its
first checkpoint (exit 4: a signal checkpoint and a closed .partial). The resume from the pristine
pair (.partial, .checkpoint) is the reference.

  flips: 32 single bytes of the checkpoint flipped at random offsets (seeded; the seed is printed),
    each resumed from a fresh copy of the pair: every resume is refused (exit 2, "cannot resume")
    or completes with every dataset and the summary bitwise those of the reference (the flip hit
    bytes HDF5 does not read: padding, free space). Then one flip inside each of the state, the
    unwritten rows and the scene text: each must be refused as damaged (the checksum); and one
    inside the first stored chunk of three series of the .partial file: refused as damaged (the
    rows' checksums the checkpoint keeps).
  edits: checkpoints edited and signed again with a correct payload checksum and seal (so that
    only the checks behind them can refuse them), each refused with its reason, within 60 s (no
    hang): a short state, a long state, a sample beyond the run, a time that is not the sample's,
    unwritten rows that do not add up, a state value not finite; the file cut to half its length;
    a checkpoint of version 1 (no payload checksum), one without its seal, and one whose state was
    flipped and then sealed again (the payload checksum refuses it).

Exit codes: 0 pass, 1 fail, 77 skipped (h5py or numpy missing).
"""
import concurrent.futures
import os
import random
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import zlib

try:
    import h5py
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

failures = []


def check(cond, what):
    print(f"{'ok' if cond else 'FAIL'}: {what}", file=sys.stderr)
    if not cond:
        failures.append(what)


def make_checkpoint(raceway, source_dir, work):
    """A signal checkpoint of a short 6309 R3 run: (scene, .partial copy, .checkpoint copy)."""
    with open(os.path.join(source_dir, "jobs/scenes/6309_R3.toml")) as f:
        text = f.read()
    lines = []
    for line in text.splitlines():
        if line.startswith("end_time ="):
            line = 'end_time = "12 ms"'
        lines.append(line)
        if line.strip() == "[output]":
            lines.append('checkpoint_interval = "2 ms"')
    if not any(line.startswith("checkpoint_interval") for line in lines):
        lines += ["[output]", 'checkpoint_interval = "2 ms"']
    scene = os.path.join(work, "scene.toml")
    with open(scene, "w") as f:
        f.write("\n".join(lines) + "\n")
    out = os.path.join(work, "made.h5")
    with open(os.path.join(work, "made.log"), "w") as log:
        p = subprocess.Popen([raceway, "run", scene, "-o", out], stdout=log, stderr=log)
        deadline = time.time() + 60
        while not os.path.exists(out + ".checkpoint") and p.poll() is None and time.time() < deadline:
            time.sleep(0.01)
        p.send_signal(signal.SIGUSR1)
        rc = p.wait(timeout=60)
    if rc != 4 or not os.path.exists(out + ".checkpoint"):
        raise RuntimeError(f"making a checkpoint: exit {rc}, expected 4 (the run may have ended first)")
    shutil.copy(out + ".partial", os.path.join(work, "pristine.partial"))
    shutil.copy(out + ".checkpoint", os.path.join(work, "pristine.checkpoint"))
    return scene


def resume(raceway, scene, work, name, checkpoint_bytes, partial_bytes=None):
    """--resume from the pristine .partial (or `partial_bytes`) and `checkpoint_bytes`: (exit code,
    output, log text)."""
    out = os.path.join(work, name + ".h5")
    for suffix in ("", ".partial", ".checkpoint"):
        if os.path.exists(out + suffix):
            os.remove(out + suffix)
    if partial_bytes is None:
        shutil.copy(os.path.join(work, "pristine.partial"), out + ".partial")
    else:
        with open(out + ".partial", "wb") as f:
            f.write(partial_bytes)
    with open(out + ".checkpoint", "wb") as f:
        f.write(checkpoint_bytes)
    try:
        r = subprocess.run([raceway, "run", scene, "-o", out, "--resume"], capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        return None, out, "timed out after 60 s (a hang)"
    return r.returncode, out, r.stdout + r.stderr


def identical(reference, other):
    r = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "tests/system/parallel/compare_outputs.py"), reference, other],
                       capture_output=True, text=True)
    return r.returncode == 0


def flips(raceway, scene, work):
    pristine = open(os.path.join(work, "pristine.checkpoint"), "rb").read()
    rc, ref, log = resume(raceway, scene, work, "reference", pristine)
    if rc != 0:
        check(False, f"the resume from the pristine checkpoint: exit {rc}: {log[-400:]}")
        return
    seed = int(os.environ.get("RACEWAY_FLIP_SEED", random.randrange(1 << 30)))
    print(f"seed {seed} (RACEWAY_FLIP_SEED={seed} repeats it); checkpoint of {len(pristine)} bytes", file=sys.stderr)
    rng = random.Random(seed)
    flipped = []  # (offset, damaged checkpoint), drawn in order so that the seed repeats them
    for _ in range(32):
        offset = rng.randrange(len(pristine))
        damaged = bytearray(pristine)
        damaged[offset] ^= rng.randrange(1, 256)
        flipped.append((offset, bytes(damaged)))
    # Three at a time: a refusal costs little CPU, most of its wall time is MPI's start-up.
    with concurrent.futures.ThreadPoolExecutor(3) as pool:
        answers = list(pool.map(lambda t: resume(raceway, scene, work, f"flip{t}", flipped[t][1]), range(32)))
    refused = same = 0
    for trial, ((offset, _), (rc, out, log)) in enumerate(zip(flipped, answers)):
        if rc == 2 and "cannot resume" in log:
            refused += 1
        elif rc == 0 and identical(ref, out):
            same += 1
        else:
            check(False, f"flip {trial} at byte {offset}: exit {rc}, neither refused nor the reference: {log[-600:]}")
    check(refused + same == 32, f"32 flips: {refused} refused, {same} resumed bitwise identical (unread bytes)")
    check(refused >= 8, f"at least a quarter of random flips land in bytes that matter and are refused ({refused})")
    # One flip inside each payload the checksum covers, found through HDF5's own offsets.
    with h5py.File(os.path.join(work, "pristine.checkpoint"), "r") as f:
        targets = {"the state": f["state"].id.get_offset() + 8 * (f["state"].size // 2),
                   "the unwritten rows": f["unwritten_rows"].id.get_offset() + 8 * (f["unwritten_rows"].size // 3)}
    marker = pristine.find(b"[bearing]")  # the scene text lives in HDF5's global heap: found by its bytes
    if marker >= 0:
        targets["the scene text"] = marker + 3
    for what, offset in targets.items():
        damaged = bytearray(pristine)
        damaged[offset] ^= 0x10
        rc, out, log = resume(raceway, scene, work, "target", bytes(damaged))
        check(rc == 2 and "the file is damaged" in log, f"a flip in {what} (byte {offset}) is refused as damaged: "
                                                          f"exit {rc}: {log.strip().splitlines()[-1:]}")
    check(len(targets) == 3, f"the scene text found in the checkpoint ({sorted(targets)})")
    # The .partial file's stored rows: a flipped byte in a chunk of each of three series (one of
    # them in a chunk's deflated bytes, found through HDF5's chunk index) is refused as damaged.
    partial = open(os.path.join(work, "pristine.partial"), "rb").read()
    with h5py.File(os.path.join(work, "pristine.partial"), "r") as f:
        stored = []  # series with whole chunks in the file (the rest is in the checkpoint)
        f.visititems(lambda n, o: stored.append(n) if isinstance(o, h5py.Dataset) and o.chunks and
                     o.maxshape[0] is None and o.id.get_num_chunks() > 0 else None)
        chunks = {}
        for name in sorted(stored, key=lambda n: -f[n].id.get_chunk_info(0).size)[:3]:
            info = f[name].id.get_chunk_info(0)
            chunks[name] = info.byte_offset + info.size // 2
    check(len(chunks) == 3, f"three series with stored chunks in the .partial ({sorted(chunks)})")
    for name, offset in chunks.items():
        damaged = bytearray(partial)
        damaged[offset] ^= 0x01
        rc, out, log = resume(raceway, scene, work, "partial", pristine, bytes(damaged))
        check(rc == 2 and ("is damaged" in log or "cannot be read back" in log),
              f"a flip in the .partial's first chunk of /{name} (byte {offset}) is refused: exit {rc}: "
              f"{log.strip().splitlines()[-1:]}")
        check(not os.path.exists(out), f"/{name}: no output written")


def payload_crc(f):
    """The checkpoint's payload checksum, as solver/run/checkpoint.cpp computes it."""
    crc = 0

    def put(b):
        nonlocal crc
        crc = zlib.crc32(b, crc)

    def text(s):
        b = s.encode() if isinstance(s, str) else bytes(s)
        put(struct.pack("<Q", len(b)))
        put(b)

    def values(v):
        v = np.asarray(v, dtype="<f8")
        put(struct.pack("<Q", v.size))
        put(v.tobytes())

    text(f.attrs["kind"])
    put(struct.pack("<q", int(f.attrs["sample"])))
    put(struct.pack("<d", float(f.attrs["time"])))
    for name in ("scene_text", "build", "options"):
        text(f.attrs[name])
    values(f["state"][()])
    values(f["restart_times"][()])
    names = sorted(f["values"].attrs.keys(), key=lambda s: s.encode())
    put(struct.pack("<Q", len(names)))
    for name in names:
        text(name)
        put(struct.pack("<d", float(f["values"].attrs[name])))
    series = [s for s in f.attrs["unwritten_series"].split("\n") if s]
    lengths = f["unwritten_lengths"][()].astype(int)
    rows = f["unwritten_rows"][()]
    by_series, at = {}, 0
    for s, n in zip(series, lengths):
        by_series[s] = rows[at:at + n]
        at += n
    put(struct.pack("<Q", len(by_series)))
    for s in sorted(by_series, key=lambda s: s.encode()):
        text(s)
        values(by_series[s])
    rows_crc = f["partial_crc32"].attrs if "partial_crc32" in f else {}
    put(struct.pack("<Q", len(rows_crc)))
    for s in sorted(rows_crc.keys(), key=lambda s: s.encode()):
        text(s)
        put(struct.pack("<d", float(rows_crc[s])))
    return crc


SEAL_BYTES = 512
SEAL_MAGIC = b"raceway sealed HDF5 file\n"


def reseal(path):
    """The file's seal (its 512-byte user block: magic, CRC-32 and size of the rest) made again, as
    io/h5/h5_checksums.cpp makes it."""
    data = bytearray(open(path, "rb").read())
    check(data.startswith(SEAL_MAGIC), "the checkpoint starts with its seal")
    rest = bytes(data[SEAL_BYTES:])
    block = SEAL_MAGIC + f"crc32 {zlib.crc32(rest):08x} bytes {len(rest)}\n".encode()
    data[:SEAL_BYTES] = block + bytes(SEAL_BYTES - len(block))
    with open(path, "wb") as f:
        f.write(data)


def edited(work, name, edit):
    """The pristine checkpoint with `edit(f)` applied and signed again (a correct payload checksum
    and seal), so that only the checks behind them can refuse it."""
    path = os.path.join(work, name + ".edited")
    shutil.copy(os.path.join(work, "pristine.checkpoint"), path)
    with h5py.File(path, "r+") as f:
        edit(f)
        f.attrs["payload_crc32"] = np.int64(payload_crc(f))
    reseal(path)
    return open(path, "rb").read()


def replace(f, name, data):
    del f[name]
    f.create_dataset(name, data=np.asarray(data, dtype="f8"))


def edits(raceway, scene, work):
    with h5py.File(os.path.join(work, "pristine.checkpoint"), "r") as f:
        check(payload_crc(f) == int(f.attrs["payload_crc32"]), "the checksum is recomputed here as raceway computes it")
        state = f["state"][()]
        lengths = f["unwritten_lengths"][()]
    cases = {
        "short state": (lambda f: replace(f, "state", state[:-1]), f"its state has {state.size - 1} values"),
        "long state": (lambda f: replace(f, "state", np.append(state, 0.0)), f"its state has {state.size + 1} values"),
        "sample beyond the run": (lambda f: f.attrs.modify("sample", np.int64(10 ** 6)), "outside the run"),
        "time not the sample's": (lambda f: f.attrs.modify("time", float(f.attrs["time"]) * 1.5),
                                  "is not that of its output sample"),
        "unwritten rows that do not add up": (lambda f: replace(f, "unwritten_lengths", lengths + 1),
                                              "inconsistent unwritten rows"),
        "a state value not finite": (lambda f: replace(f, "state", np.where(np.arange(state.size) == 3, np.nan, state)),
                                     "not finite"),
    }
    for what, (edit, reason) in cases.items():
        data = edited(work, what.replace(" ", "_").replace("'", ""), edit)
        t0 = time.time()
        rc, out, log = resume(raceway, scene, work, "edited", data)
        check(rc == 2 and reason in log, f"{what}: refused naming '{reason}' in {time.time() - t0:.1f} s: exit {rc}: "
                                         f"{log.strip().splitlines()[-1:]}")
        check(not os.path.exists(out), f"{what}: no output written")
    pristine = open(os.path.join(work, "pristine.checkpoint"), "rb").read()
    rc, out, log = resume(raceway, scene, work, "cut", pristine[:len(pristine) // 2])
    check(rc == 2 and "cannot resume" in log, f"a checkpoint cut to half its length is refused: exit {rc}: "
                                              f"{log.strip().splitlines()[-1:]}")

    def older(f):
        del f.attrs["payload_crc32"]
        f.attrs.modify("checkpoint_version", np.int64(1))
    data = edited(work, "older", older)
    rc, out, log = resume(raceway, scene, work, "older", data)
    check(rc == 2 and "checkpoint version 1" in log, f"a checkpoint of version 1 is refused naming it: exit {rc}: "
                                                     f"{log.strip().splitlines()[-1:]}")
    # One written before checkpoints were sealed: HDF5 from its first byte.
    unsealed = bytes(SEAL_BYTES) + pristine[SEAL_BYTES:]
    rc, out, log = resume(raceway, scene, work, "unsealed", unsealed)
    check(rc == 2 and "carries no seal" in log, f"a checkpoint without its seal is refused: exit {rc}: "
                                                f"{log.strip().splitlines()[-1:]}")
    # A flip in the payload under a valid seal (resealed after the flip): the payload's checksum.
    with h5py.File(os.path.join(work, "pristine.checkpoint"), "r") as f:
        at = f["state"].id.get_offset() + 8
    path = os.path.join(work, "flipped_resealed.edited")
    damaged = bytearray(pristine)
    damaged[at] ^= 0x40
    open(path, "wb").write(damaged)
    reseal(path)
    rc, out, log = resume(raceway, scene, work, "resealed", open(path, "rb").read())
    check(rc == 2 and "payload_crc32" in log, f"a state flipped under a valid seal is refused by the payload's "
                                              f"checksum: exit {rc}: {log.strip().splitlines()[-1:]}")


def main():
    global SOURCE_DIR
    case, raceway, SOURCE_DIR = sys.argv[1:4]
    work = tempfile.mkdtemp(prefix=f"raceway_checkpoint_{case}.")
    try:
        scene = make_checkpoint(raceway, SOURCE_DIR, work)
        {"flips": flips, "edits": edits}[case](raceway, scene, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        print(f"{case}: {len(failures)} failure(s)", file=sys.stderr)
        sys.exit(1)
    print(f"{case}: passed")


SOURCE_DIR = ""
if __name__ == "__main__":
    main()
