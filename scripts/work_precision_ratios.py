#!/usr/bin/env python3
"""CPU-time ratio of pradis's best method to a peer (default IDA) at given final
errors, from the CSV written by bench/work_precision.

For each series (solver + method) the cost of an error e is the CPU time at which
the series first reaches an error <= e: the series' work-precision front (points
sorted by CPU time, keeping each point more accurate than all cheaper ones),
interpolated linearly in log(error)-log(time) between front points. An error
looser than the cheapest front point costs that point's time (no extrapolation);
an error tighter than the series' best is not reached. pradis's best is the
minimum cost over all pradis series (error-controlled and fixed-step).

Usage: scripts/work_precision_ratios.py [CSV ...] [--peer IDA] [--from 1e-3] [--to 1e-6] [--method NAME]
CSV ...: one file, or several runs of the same sweep: each point (problem, solver,
method, setting) then costs the minimum of its CPU times over the runs, the usual
estimate of its undisturbed cost on a shared machine whose speed drifts between and
within runs (its error must be the same in every run, or the script stops);
--peer SOLVER or SOLVER/METHOD: the peer series (SOLVER alone: its first series in
the CSV, e.g. IDA; Simbody/RKM and Simbody/CPodes select one of Simbody's two
integrators, which only the top, topx and chain problems have);
--method NAME: pradis's series of that method only (e.g. BDF: the error-controlled BDF driver);
--skip-method NAME: all of pradis's series but those of that method and its variants
(NAME-...: --skip-method BDF also leaves out BDF-index3, the BDF driver's plain index-3 form).
Prints, per problem, the ratio at each decade, the median ratio over 13 errors
log-spaced from --from to --to, and which pradis series is best at each decade.
"""
import csv
import math
import statistics
import sys


def front(points):
    pts = sorted(points, key=lambda p: (p[1], p[0]))  # (error, cpu) by cpu
    out, best = [], math.inf
    for e, c in pts:
        if e < best:
            out.append((e, c))
            best = e
    return out


def cost(fr, e):
    if not fr or e < fr[-1][0]:
        return None
    if e >= fr[0][0]:
        return fr[0][1]
    for (e1, c1), (e2, c2) in zip(fr, fr[1:]):
        if e1 > e >= e2:
            w = (math.log(e1) - math.log(e)) / (math.log(e1) - math.log(e2))
            return math.exp(math.log(c1) + w * (math.log(c2) - math.log(c1)))
    return None


def main(argv):
    paths, peer, lo, hi, method, skip = [], "IDA", 1e-3, 1e-6, None, None
    i = 0
    while i < len(argv):
        a = argv[i]
        if a == "--peer":
            peer = argv[i + 1]; i += 1
        elif a == "--from":
            lo = float(argv[i + 1]); i += 1
        elif a == "--skip-method":
            skip = argv[i + 1]; i += 1
        elif a == "--method":
            method = argv[i + 1]; i += 1
        elif a == "--to":
            hi = float(argv[i + 1]); i += 1
        else:
            paths.append(a)
        i += 1
    points = {}  # (problem, solver, method, setting) -> [error, least CPU time]
    for path in paths or ["docs/data/work_precision.csv"]:
        with open(path) as f:
            for r in csv.DictReader(f):
                key = (r["problem"], r["solver"], r["method"], r["setting"])
                e, c = float(r["error"]), float(r["cpu_s"])
                if key in points:
                    if points[key][0] != e:
                        sys.exit(f"{path}: {' '.join(key)} has error {e:g}, another run {points[key][0]:g}: "
                                 "not runs of the same sweep")
                    points[key][1] = min(points[key][1], c)
                else:
                    points[key] = [e, c]
    series = {}
    for (prob, solver, meth, _), (e, c) in points.items():
        if 0 < e < 1e300 and c > 0:
            series.setdefault(prob, {}).setdefault((solver, meth), []).append((e, c))
    decades = []
    e = lo
    while e >= hi * 0.999:
        decades.append(e)
        e /= 10
    grid = [lo * (hi / lo) ** (k / 12) for k in range(13)]
    for prob, ss in series.items():
        fronts = {k: front(v) for k, v in ss.items()}
        psolver, _, pmethod = peer.partition("/")
        peers = [k for k in fronts if k[0] == psolver and (not pmethod or k[1] == pmethod)]
        if not peers:
            continue
        pf = fronts[peers[0]]

        def best_pradis(e):
            cands = [(cost(fr, e), k[1]) for k, fr in fronts.items()
                     if k[0] == "pradis" and (method is None or k[1] == method)
                     and not (skip is not None and (k[1] == skip or k[1].startswith(skip + "-")))]
            cands = [c for c in cands if c[0] is not None]
            return min(cands) if cands else (None, None)

        print(f"{prob}: pradis best / {peer} CPU time")
        for e in decades:
            bp, name = best_pradis(e)
            pc = cost(pf, e)
            if bp is None or pc is None:
                print(f"  error {e:.0e}: not reached by {'pradis' if bp is None else peer}")
            else:
                print(f"  error {e:.0e}: {bp / pc:7.2f}  (pradis {name} {bp:.3g} s, {peer} {pc:.3g} s)")
        rs = []
        for e in grid:
            bp, _ = best_pradis(e)
            pc = cost(pf, e)
            if bp is not None and pc is not None:
                rs.append(bp / pc)
        if rs:
            print(f"  median over {len(rs)} errors in [{hi:.0e}, {lo:.0e}]: {statistics.median(rs):.2f}"
                  f" (min {min(rs):.2f}, max {max(rs):.2f})")


if __name__ == "__main__":
    main(sys.argv[1:])
