"""The table of bench/eigen_vs_scipy.sh from its run log. One line a run: case, threads,
solver, kind (whole: the process reads the model, solves and writes the modes; eigen:
jointid's solve alone), the process's wall time s, the solve time s inside it (or -), peak
RSS kB, largest relative residual, largest rounding floor of the residual (or 0), the
frequencies Hz (comma-separated).

Per case and thread count: jointid's whole process and its eigen-only solve beside the
scipy variant fastest as a whole process (and its own solve time inside that process),
medians; their ratios; median peak memory of the whole processes (jointid's eigen-only
process where it has no whole-process run: a chain); the largest residuals;
the largest relative difference of jointid's frequencies from that variant's (the last run
of each); every variant below.

python bench/eigen_table.py RUNS.txt"""
import collections
import statistics
import sys

runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    case, threads, solver, kind, wall, solve, rss, residual, floor, hz = line.split()
    runs[(case, int(threads), solver, kind)].append({
        "wall": float(wall), "solve": None if solve == "-" else float(solve),
        "mb": float(rss) / 1024, "residual": float(residual), "floor": float(floor),
        "hz": [] if hz == "-" else [float(f) for f in hz.split(",")]})


def median(key, field):
    values = [r[field] for r in runs.get(key, []) if r[field] is not None]
    return statistics.median(values) if values else float("nan")


def worst(key, field):
    return max((r[field] for r in runs.get(key, [])), default=float("nan"))


def fmt(x):
    return "-" if x != x else f"{x:.2f}"


def difference(a, b):
    """The largest |a_j - b_j| / b_j over the modes both have."""
    return max((abs(x - y) / y for x, y in zip(a, b) if y > 0), default=float("nan"))


print("| case | threads | jointid whole s | jointid eigen s | jointid MB | best scipy | scipy whole s "
      "| scipy eigen s | scipy MB | whole jointid / scipy | eigen jointid / scipy "
      "| jointid residual (floor) | scipy residual | max rel. diff. of f | first f jointid / scipy (Hz) |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for case, threads in sorted({k[:2] for k in runs}):
    whole, eigen = (case, threads, "jointid", "whole"), (case, threads, "jointid", "eigen")
    peers = [k for k in runs if k[:2] == (case, threads) and k[2] != "jointid"]
    if not peers:
        continue
    best = min(peers, key=lambda k: median(k, "wall"))
    ours = whole if whole in runs else eigen  # a chain has no whole-process run
    ours_hz, theirs_hz = runs[ours][-1]["hz"], runs[best][-1]["hz"]
    print(f"| {case} | {threads} | {fmt(median(whole, 'wall'))} | {median(eigen, 'solve'):.3f} "
          f"| {median(ours, 'mb'):.0f} | {best[2]} | {median(best, 'wall'):.2f} "
          f"| {median(best, 'solve'):.3f} | {median(best, 'mb'):.0f} "
          f"| {fmt(median(whole, 'wall') / median(best, 'wall'))} "
          f"| {median(eigen, 'solve') / median(best, 'solve'):.2f} "
          f"| {worst(eigen, 'residual'):.1e} ({worst(eigen, 'floor'):.1e}) "
          f"| {worst(best, 'residual'):.1e} | {difference(ours_hz, theirs_hz):.1e} "
          f"| {ours_hz[0]:.4f} / {theirs_hz[0]:.4f} |")
print()
print("every run kind, medians (runs):")
for key in sorted(runs):
    rows = runs[key]
    solve = median(key, "solve")
    ours = runs.get((key[0], key[1], "jointid", "whole")) or runs[(key[0], key[1], "jointid", "eigen")]
    print(f"  {key[0]:9s} {key[1]} {key[2]:14s} {key[3]:5s} whole {median(key, 'wall'):.2f} s"
          f"  solve {solve:.3f} s  {median(key, 'mb'):.0f} MB  residual {worst(key, 'residual'):.1e}"
          f"  f from jointid's {difference(rows[-1]['hz'], ours[-1]['hz']):.1e}  ({len(rows)})")
