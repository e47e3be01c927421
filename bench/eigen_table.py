"""The table of bench/eigen_vs_scipy.sh from its run log (one line a run: case, threads,
solver, solve time s, peak RSS kB, largest relative residual, first frequency Hz, largest
rounding floor of the residual or 0): per case and thread count, jointid and the fastest
scipy variant by median time, their ratio, the median peak memory and the largest residual
over the runs.

python bench/eigen_table.py RUNS.txt"""
import collections
import statistics
import sys

runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    case, threads, solver, seconds, rss, residual, f1, floor = line.split()
    runs[(case, int(threads), solver)].append(
        (float(seconds), float(rss) / 1024, float(residual), float(f1), float(floor)))


def summary(key):
    rows = runs[key]
    return (statistics.median(r[0] for r in rows), statistics.median(r[1] for r in rows),
            max(r[2] for r in rows), rows[0][3], len(rows), max(r[4] for r in rows))


print("| case | threads | jointid s | jointid MB | jointid residual (floor) | best scipy | scipy s "
      "| scipy MB | scipy residual | jointid / scipy time | first f jointid / scipy (Hz) |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for case, threads in sorted({(c, t) for c, t, _ in runs}, key=lambda k: (k[0], k[1])):
    if (case, threads, "jointid") not in runs:
        continue
    ours = summary((case, threads, "jointid"))
    peers = [(summary(k), k[2]) for k in runs if k[:2] == (case, threads) and k[2] != "jointid"]
    if not peers:
        continue
    best, name = min(peers)
    print(f"| {case} | {threads} | {ours[0]:.3f} | {ours[1]:.0f} | {ours[2]:.1e} ({ours[5]:.1e}) | {name} "
          f"| {best[0]:.3f} | {best[1]:.0f} | {best[2]:.1e} | {ours[0] / best[0]:.2f} "
          f"| {ours[3]:.4f} / {best[3]:.4f} |")
print()
print("all variants, median s (runs):")
for key in sorted(runs):
    s = summary(key)
    print(f"  {key[0]:9s} {key[1]} {key[2]:14s} {s[0]:.3f} s  {s[1]:.0f} MB  residual {s[2]:.1e}  ({s[4]})")
