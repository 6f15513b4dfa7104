#!/usr/bin/python3
"""Replay model of raceway's master/worker execution (scheduler/mpi_executor.hpp, plan.hpp).

Predicts the wall time and speed-up of a run at P = 1..64 ranks from a recorded one-rank run
(its output file: /scheduler task costs, evaluation counts, message sizes; the summary's wall
time) and a latency/bandwidth model of the network:

  T(P)       = T_serial + sum over phases of N_phase * T_eval(phase, P)
  T_serial   = measured one-rank wall time - measured task seconds (CVODE, linear algebra,
               output, the start-up outside its contact tasks, on rank 0: does not shrink with P)
  T_eval     = t_bcast + makespan + t_gather
  t_bcast    = ceil(log2 P) * (L + m_cmd / B)          binomial-tree broadcast of the command
                                                        (header + context; runs recorded before
                                                        per-task record sizes: header + max(context,
                                                        task count))
  makespan   = largest rank load of the two-level plan (scheduler/plan.cpp, ported below:
               LPT over rolling elements and border tasks, then level-2 moves and exchanges) on the
               per-task costs (smoothed costs at the end of the run, scaled to the run's
               total task seconds)
  makespan + t_gather = when rank 0 has every reply: the replies travel a binomial tree to rank 0
               (scheduler/replies.cpp; Open MPI's tuned MPI_Gather uses the same tree for
               small blocks): rank r, done with its own tasks at load_r, receives its children's
               messages one after the other in the order they are ready, each taking L + m / B
               (m: the bytes of the child's subtree), then sends its own with its subtree's. m_w =
               8 bytes x (the doubles each of w's tasks fills, /scheduler/task_record_size_*, + 1
               seconds per task). Runs recorded before per-task sizes used the linear protocol
               (every worker to rank 0 directly, whole records): the same recursion with rank 0
               the parent of every worker. With equal loads the linear gather costs (P - 1)(L +
               m / B) after the makespan, the tree ceil(log2 P) L + about (P - 1) m / B.
               The breakdown splits it as: gather latency = (messages on the longest path) x L,
               gather bytes = the rest of (that time - makespan).
  tail       = with --tail-share S > 0 (the executor's --tail-share; scheduler/tail_claims.hpp): the
               plan's tail (mark_tail, ported below) is taken out of the ranks' loads; the rank free
               first takes the front of its own part of it (largest first), or when that is gone
               the back of the part with the most left; each claim costs --claim-us (a compare-and-
               swap on a cache line the ranks share; plus one failing claim per rank); a rank's
               reply carries its fixed list only (the tail's records go through shared memory; rank
               0's copy of them, about 1 us per evaluation, is not modelled).

L, B: one-way latency and bandwidth. Sets: "here" (measured with perf/bench/pingpong on this machine,
shared memory), "infiniband" (typical cluster: 1.5 us, 10 GB/s). The model assumes one core per
rank and the plan's balance for the time-averaged costs (the adaptive scheduler's job); what it
leaves out (the scatter of task times from one evaluation to the next, which the slowest rank
sets; polling, waking a waiting rank and unpacking the replies, about 5 us per evaluation at np=2
here; other processes, cache effects) shows up in the check against measured np = 2. So the model
gives the tail only what it does against the plan's residual imbalance of time-averaged costs (and
its claims' cost), never its real purpose, the per-evaluation scatter: for the tail its
predictions are a lower bound on the gain (perf/studies/results/parallel_notes.md (j) has the measured one).

    replay_model.py [--latency-us L --bandwidth-gbs B] [--measured-np2 S] RUN_NP1.h5 [...]
"""
import argparse
import json
import math
import sys

import h5py
import numpy as np

BORDER = -1


def rank_moves(cost, group, parent, owner, rank, heavy):
    """What level 2 can move off `rank` (plan.cpp's moves_of_rank): per group and piece its tasks
    there, one by one for a piece heavier than `heavy`; (group, tasks, cost) each."""
    pieces = {}
    for t in range(len(cost)):
        if owner[t] == rank:
            pieces.setdefault((group[t], parent[t]), []).append(t)
    moves = []
    for (g, _), ts in sorted(pieces.items()):
        c = sum(cost[t] for t in ts)
        moves += [(g, [t], cost[t]) for t in ts] if c > heavy and len(ts) > 1 else [(g, ts, c)]
    return moves


def exchange_off(cost, group, parent, owner, load, hi, heavy):
    """plan.cpp's exchange_off: the exchange of a move off `hi` with a cheaper one of another rank
    that lowers the larger of the two loads the most; False when none lowers it."""
    mine = rank_moves(cost, group, parent, owner, hi, heavy)
    best = (load[hi], None)
    for r in range(len(load)):
        if r == hi:
            continue
        theirs = rank_moves(cost, group, parent, owner, r, heavy)
        for a in mine:
            for b in theirs:
                d = a[2] - b[2]
                if d > 0 and max(load[hi] - d, load[r] + d) < best[0]:
                    best = (max(load[hi] - d, load[r] + d), (a, b, r))
    if best[1] is None:
        return False
    a, b, r = best[1]
    for t in a[1]:
        owner[t] = r
    for t in b[1]:
        owner[t] = hi
    load[hi] -= a[2] - b[2]
    load[r] += a[2] - b[2]
    return True


def lpt_level2(cost, group, ranks, parent=None, tolerance=0.02, split_share=0.1):
    """Port of scheduler/plan.cpp's greedy LPT + level-2 moves and exchanges (equal capacities).
    parent: per task, its contact segment (sub-tasks of a cut segment); level 2 moves a segment's
    tasks on a rank together unless they cost more than split_share of a rank's mean share."""
    if parent is None:
        parent = list(range(len(cost)))
    units = {}
    for t, g in enumerate(group):
        key = ("b", parent[t]) if g == BORDER else ("g", g)
        units.setdefault(key, []).append(t)
    unit_list = sorted(units.values(), key=lambda ts: -sum(cost[t] for t in ts))
    load = [0.0] * ranks
    owner = [0] * len(cost)
    for ts in unit_list:
        c = sum(cost[t] for t in ts)
        r = min(range(ranks), key=lambda q: load[q] + c)
        load[r] += c
        for t in ts:
            owner[t] = r
    mean = sum(load) / ranks
    for _ in range(len(cost)):
        hi = max(range(ranks), key=lambda q: load[q])
        lo = min(range(ranks), key=lambda q: load[q])
        if hi == lo or load[hi] <= mean * (1 + tolerance):
            break
        x = (load[hi] - load[lo]) / 2
        gcost = {}
        for t in range(len(cost)):
            if owner[t] == hi:
                gcost[group[t]] = gcost.get(group[t], 0.0) + cost[t]
        moves = rank_moves(cost, group, parent, owner, hi, split_share * mean)
        best = None
        for g in sorted(gcost, key=lambda k: -gcost[k]):
            cands = [m[1:] for m in moves if m[0] == g and m[2] > 0 and max(load[hi] - m[2], load[lo] + m[2]) < load[hi]]
            if cands:
                best = min(cands, key=lambda m: abs(m[1] - x))
                break
        if best is None:
            if exchange_off(cost, group, parent, owner, load, hi, split_share * mean):
                continue
            break
        for t in best[0]:
            owner[t] = lo
        load[hi] -= best[1]
        load[lo] += best[1]
    return owner, load


def mark_tail(owner, cost, share, ranks, floor=0.1):
    """Port of scheduler/plan.cpp's mark_tail: per rank its cheapest tasks of at least floor x the
    largest cost, up to share of its load (share 1: every task); the tail largest first."""
    if share <= 0:
        return []
    least = floor * max(cost) if share < 1 else 0.0
    tail = []
    for r in range(ranks):
        mine = [t for t in range(len(cost)) if owner[t] == r]
        load = sum(cost[t] for t in mine)
        taken = 0.0
        for t in sorted((t for t in mine if cost[t] >= least), key=lambda t: (cost[t], -t)):
            if share < 1 and taken + cost[t] > share * load:
                break
            taken += cost[t]
            tail.append(t)
    return sorted(tail, key=lambda t: (-cost[t], t))


def claim_tail(load, owner, cost, tail, claim):
    """Ranks' finish times: their fixed lists, then the tail as scheduler/tail_claims.hpp claims it: the rank
    free first takes its own part's front, else the back of the fullest part; each claim costs
    `claim` (and one failing claim per rank at the end)."""
    ready = list(load)
    parts = [[t for t in tail if owner[t] == r] for r in range(len(ready))]  # each largest first
    for t in tail:
        ready[owner[t]] -= cost[t]
    for _ in tail:
        r = min(range(len(ready)), key=lambda q: ready[q])
        t = parts[r].pop(0) if parts[r] else parts[max(range(len(parts)), key=lambda q: len(parts[q]))].pop()
        ready[r] += claim + cost[t]
    return [x + claim for x in ready] if tail else ready


def read_run(path):
    with h5py.File(path, "r") as f:
        g = f["scheduler"]
        if g.attrs["ranks"] != 1:
            sys.exit(f"{path}: recorded with {g.attrs['ranks']} ranks; the replay needs a one-rank run")
        summary = json.loads(f.attrs["summary_json"])
        run = {"path": path, "wall": summary["wall_time_s"], "split": summary.get("time_split_s", {}),
               "output_write": summary.get("output_write_time_s", 0.0), "group": [int(x) for x in g["task_group"][()]],
               "parent": [int(x) for x in g["task_segment"][()]] if "task_segment" in g else None,
               "context": int(g.attrs["context_size"]), "phases": {}}
        for ph in ("rhs", "jacobian"):
            n = int(g.attrs[f"evaluations_{ph}"])
            if n == 0 or f"task_cost_{ph}" not in g:
                continue
            total = float(g.attrs[f"mean_rank_task_seconds_{ph}"])  # one rank: all task seconds
            cost = np.asarray(g[f"task_cost_{ph}"][()], dtype=float)
            cost = cost * (total / n / cost.sum()) if cost.sum() > 0 else np.full(len(cost), total / n / len(cost))
            record = int(g.attrs[f"record_size_{ph}"])
            sizes = f"task_record_size_{ph}"
            run["phases"][ph] = {"n": n, "total": total, "cost": list(cost), "record": record,
                                 "sizes": [int(x) for x in g[sizes][()]] if sizes in g else [record] * len(cost),
                                 "per_task_sizes": sizes in g}
    return run


def gather_tree(ranks, binomial):
    """Per rank: its children in the replies' tree (binomial rooted at 0, or all workers under 0)."""
    if not binomial:
        return [list(range(1, ranks))] + [[] for _ in range(1, ranks)]
    children = [[] for _ in range(ranks)]
    for r in range(1, ranks):
        children[r & (r - 1)].append(r)
    return children


def gather_finish(load, reply, children, latency, bandwidth):
    """When rank 0 holds every reply (seconds after the broadcast), and the messages on the way
    to it: rank r receives its children's subtree messages one after the other as they are ready."""
    ranks = len(load)
    done, size, hops = [0.0] * ranks, list(reply), [0] * ranks
    for r in reversed(range(ranks)):  # children have higher ranks than their parent
        t, h = load[r], 0  # h: messages on the path that sets t
        for c in sorted(children[r], key=lambda c: done[c]):
            if done[c] > t:
                t, h = done[c], hops[c]
            t += latency + 8 * size[c] / bandwidth
            h += 1
            size[r] += size[c]
        done[r], hops[r] = t, h
    return done[0], hops[0]


def evaluation_parts(run, ph, ranks, latency, bandwidth, tail_share=0.0, claim=0.0):
    """One evaluation of phase ph at `ranks` ranks: broadcast, makespan, ideal makespan (sum / P),
    gather latency part, gather bandwidth part (seconds)."""
    cost, group = ph["cost"], run["group"]
    owner, load = lpt_level2(cost, group, ranks, run["parent"])
    tail = mark_tail(owner, cost, tail_share, ranks)
    load = claim_tail(load, owner, cost, tail, claim)
    shared = set(tail)
    owner = [-1 if t in shared else o for t, o in enumerate(owner)]
    cmd_doubles = 6 + (run["context"] if ph["per_task_sizes"] else max(run["context"], len(cost)))
    t_bcast = math.ceil(math.log2(ranks)) * (latency + 8 * cmd_doubles / bandwidth)
    reply = [0] * ranks  # doubles per rank's reply: its tasks' used doubles and one seconds each
    for t, o in enumerate(owner):
        if o >= 0:  # a tail task's record goes through shared memory
            reply[o] += ph["sizes"][t] + 1
    finish, hops = gather_finish(load, reply, gather_tree(ranks, ph["per_task_sizes"]), latency, bandwidth)
    gather = finish - max(load)
    return t_bcast, max(load), sum(cost) / ranks, min(gather, hops * latency), max(0.0, gather - hops * latency)


def predict(run, ranks, latency, bandwidth, serial_cut=0.0, tail_share=0.0, claim=0.0):
    serial = run["wall"] - sum(p["total"] for p in run["phases"].values()) - serial_cut
    t = serial
    for ph in run["phases"].values():
        if ranks == 1:
            t += ph["n"] * sum(ph["cost"])
            continue
        t_bcast, makespan, _, gather_latency, gather_bytes = evaluation_parts(run, ph, ranks, latency, bandwidth,
                                                                              tail_share, claim)
        t += ph["n"] * (t_bcast + makespan + gather_latency + gather_bytes)
    return t, serial


def print_breakdown(run, ranks, latency, bandwidth, **tail):
    """Where the time of the task part goes at `ranks` ranks, per evaluation and over the run."""
    for name, ph in run["phases"].items():
        b, m, ideal, gl, gb = evaluation_parts(run, ph, ranks, latency, bandwidth, **tail)
        n = ph["n"]
        print(f"  {name} at P={ranks}, per evaluation (over the run): broadcast {1e6 * b:.2f} us ({n * b:.3f} s), "
              f"makespan {1e6 * m:.2f} us ({n * m:.3f} s; ideal sum/P {1e6 * ideal:.2f} us, imbalance {m / ideal:.3f}, "
              f"{n * (m - ideal):.3f} s), gather latency {1e6 * gl:.2f} us ({n * gl:.3f} s), gather bytes "
              f"{1e6 * gb:.2f} us ({n * gb:.3f} s); record doubles per evaluation {sum(ph['sizes'])} "
              f"(whole records: {ph['record'] * len(ph['sizes'])})")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--latency-us", type=float, default=None, help="measured one-way latency here (pingpong)")
    ap.add_argument("--bandwidth-gbs", type=float, default=None, help="measured bandwidth here (pingpong)")
    ap.add_argument("--measured-np2", type=float, action="append", default=[],
                    help="measured np=2 speed-up of the i-th run (repeat per run; 0 = none)")
    ap.add_argument("--tail-share", type=float, default=0.1,
                    help="the executor's --tail-share (its default 0.1): the tail claimed on demand; 0: off")
    ap.add_argument("--claim-us", type=float, default=0.15,
                    help="cost of one claim of a tail task (an atomic add on a shared cache line)")
    ap.add_argument("--table", help="write the predictions as CSV (scene, network, ranks, wall, speed-up, "
                    "efficiency) for `raceway plan`; the scene is the run file's name without .h5")
    args = ap.parse_args()
    tl = {"tail_share": args.tail_share, "claim": args.claim_us * 1e-6}
    table = []
    networks = []
    if args.latency_us is not None:
        networks.append(("here", args.latency_us * 1e-6, args.bandwidth_gbs * 1e9))
    networks.append(("infiniband", 1.5e-6, 10e9))
    for i, path in enumerate(args.runs):
        run = read_run(path)
        t1, serial = predict(run, 1, 0, 1)
        print(f"## {path}")
        per_eval = {k: v["total"] / v["n"] for k, v in run["phases"].items()}
        print(f"one-rank wall {run['wall']:.3f} s, serial part {serial:.3f} s ({100 * serial / run['wall']:.1f} %), "
              f"{len(run['group'])} tasks, task seconds per evaluation " +
              ", ".join(f"{k} {1e6 * v:.1f} us x {run['phases'][k]['n']}" for k, v in per_eval.items()))
        print("largest possible speed-up of the task part (sum / largest task): " +
              ", ".join(f"{k} {sum(v['cost']) / max(v['cost']):.1f}" for k, v in run["phases"].items()) +
              f"; Amdahl bound from the serial part alone: {run['wall'] / serial:.1f}")
        sp = run["split"]
        if sp:
            # The run's time split is wall time by activity; the start-up's contact evaluations (the
            # seating) run as tasks and are in the task seconds, so "the rest" is what is left of
            # rank 0's own work: model, start-up outside its contacts, file, executor, combining.
            linear = sp.get("linear_setup", 0) + sp.get("linear_solve", 0)
            print("rank 0's serial part, from the run's time split: integrator %.3f s, Newton linear algebra %.3f s, "
                  "output writing %.3f s, the rest (model, start-up outside its contact tasks, file, executor, "
                  "completing cut segments) %.3f s" % (sp.get("integrator", 0), linear, run["output_write"],
                  serial - sp.get("integrator", 0) - linear - run["output_write"]))
        for name, lat, bw in networks:
            print(f"network {name}: latency {lat * 1e6:.2f} us, bandwidth {bw / 1e9:.2f} GB/s")
            print("   P  predicted_wall_s  speedup  efficiency")
            for p in [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64]:
                tp, _ = predict(run, p, lat, bw, **tl)
                print(f"{p:4d}  {tp:16.3f}  {t1 / tp:7.2f}  {t1 / tp / p:10.3f}")
                scene = path.rsplit("/", 1)[-1].removesuffix(".h5")
                table.append(f"{scene},{name},{p},{tp:.4f},{t1 / tp:.3f},{t1 / tp / p:.3f}")
            effs = {p: t1 / predict(run, p, lat, bw, **tl)[0] / p for p in (8, 16, 32)}
            print("efficiency at 8, 16, 32 ranks: " + ", ".join(f"{p}: {e:.2f}" for p, e in effs.items()))
            if args.tail_share > 0:
                off = {p: t1 / predict(run, p, lat, bw)[0] / p for p in (2, 8, 16, 32)}
                print(f"  tail share {args.tail_share:g} against none (efficiency at 2, 8, 16, 32 ranks): " +
                      ", ".join(f"{p}: {t1 / predict(run, p, lat, bw, **tl)[0] / p:.3f} / {e:.3f}" for p, e in off.items()))
            print_breakdown(run, 16, lat, bw, **tl)
            if run["output_write"] > 0:
                cut = run["output_write"]
                effs = {p: t1 / predict(run, p, lat, bw, cut, **tl)[0] / p for p in (8, 16, 32)}
                print(f"  what if output writing ({cut:.3f} s) left rank 0 (T(1) kept): " +
                      ", ".join(f"{p}: {e:.2f}" for p, e in effs.items()))
                cut = serial - run["split"].get("integrator", 0) - run["split"].get("linear_setup", 0) \
                    - run["split"].get("linear_solve", 0)
                effs = {p: t1 / predict(run, p, lat, bw, cut, **tl)[0] / p for p in (8, 16, 32)}
                print(f"  what if all but the integrator and the Newton linear algebra ({cut:.3f} s) left rank 0: " +
                      ", ".join(f"{p}: {e:.2f}" for p, e in effs.items()))
            if name == "here" and i < len(args.measured_np2) and args.measured_np2[i] > 0:
                s2 = t1 / predict(run, 2, lat, bw, **tl)[0]
                m = args.measured_np2[i]
                print(f"check np=2: predicted speed-up {s2:.3f}, measured {m:.3f}, "
                      f"difference {100 * (s2 - m) / m:+.1f} %")
        print()
    if args.table:
        with open(args.table, "w") as f:
            f.write("# written by perf/calibration/replay_model.py (perf/calibration/run_scaling_benchmarks.sh); read by `raceway plan`\n")
            f.write("scene,network,ranks,predicted_wall_s,speedup,efficiency\n")
            f.write("\n".join(table) + "\n")


if __name__ == "__main__":
    main()
