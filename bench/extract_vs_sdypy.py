"""jointid's modal extraction against sdypy-EMA (LSCF poles, LSFD constants) on the same FRFs.

The case is the test `five_modes_with_modes_outside_the_band_noisy_velocity` of
tests/extract.rs, drawn here with the same generator (SplitMix64 + Box-Muller, the unique QR
with a positive diagonal of R) so that the file holds the same FRFs up to rounding: a 7-DOF
lumped system with prescribed modes (40 Hz below the band, 120-650 Hz in it, 1500 Hz above),
damping 0.2% to 3%, mobility of every DOF to a force at DOF 0 solved directly per line
(H = (K - w^2 M + i w C)^-1), 2% complex Gaussian noise plus a 1e-4 floor, lines every 0.25 Hz
to 1000 Hz, band 80-800 Hz.

Both sides read the text file this script writes; jointid through the example
examples/extract_synthetic.rs (release build), with the band and with none (jointid's
automatic band; the modes are jointid's automatic choice in both). sdypy-EMA is given the true frequencies as its
approximate ones for `select_closest_poles` (it has no automatic choice), its polynomial
order up to 2 x 30 = 60 like jointid's default, its band 80-800 Hz.

usage: PY=$(bash scripts/python-env.sh); $PY bench/extract_vs_sdypy.py [--repeat 3]
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MASK = (1 << 64) - 1


class Rng:
    """SplitMix64 with Box-Muller normals (the cosine branch), as tests/common/frf.rs."""

    def __init__(self, seed):
        self.state = seed & MASK

    def uniform(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        z ^= z >> 31
        return ((z >> 11) + 0.5) / float(1 << 53)

    def normal(self):
        u, v = self.uniform(), self.uniform()
        return np.sqrt(-2.0 * np.log(u)) * np.cos(2.0 * np.pi * v)


def prescribed(freqs, zetas, seed):
    n = len(freqs)
    rng = Rng(seed)
    masses = np.array([1.0 + rng.uniform() for _ in range(n)])
    g = np.array([[rng.normal() for _ in range(n)] for _ in range(n)])
    q, r = np.linalg.qr(g)
    q = q * np.sign(np.diag(r))[None, :]
    phi = q / np.sqrt(masses)[:, None]
    w = 2 * np.pi * np.asarray(freqs)
    mphi = masses[:, None] * phi
    k = mphi @ np.diag(w**2) @ mphi.T
    c = mphi @ np.diag(2 * np.asarray(zetas) * w) @ mphi.T
    return k, np.diag(masses), c, phi


def case():
    freqs = [40.0, 120.0, 210.0, 330.0, 480.0, 650.0, 1500.0]
    zetas = [0.01, 0.02, 0.005, 0.01, 0.03, 0.002, 0.01]
    k, m, c, phi = prescribed(freqs, zetas, 5)
    f = np.arange(0, 4001) * 0.25
    n = len(freqs)
    h = np.zeros((n, len(f)), dtype=complex)
    e = np.zeros(n)
    e[0] = 1.0
    for i, fi in enumerate(f):
        w = 2 * np.pi * fi
        h[:, i] = np.linalg.solve(k - w * w * m + 1j * w * c, e) * (1j * w)
    rng = Rng(11)
    for o in range(n):
        peak = np.abs(h[o]).max()
        for i in range(len(f)):
            sigma = 0.02 * abs(h[o, i]) + 1e-4 * peak
            re, im = rng.normal(), rng.normal()
            h[o, i] += (re + 1j * im) * sigma / np.sqrt(2.0)
    modes = [1, 2, 3, 4, 5]
    truth = {
        "frequency_hz": [freqs[r] for r in modes],
        "damping_ratio": [zetas[r] for r in modes],
        "shapes": [phi[:, r] for r in modes],
    }
    return f, h, truth


def write(path, f, h):
    with open(path, "w") as out:
        out.write("# jointid FRF text, version 1 (bench/extract_vs_sdypy.py)\n")
        out.write("quantity velocity\n")
        out.write(f"responses {h.shape[0]}\n")
        for i, fi in enumerate(f):
            values = " ".join(f"{v.real:.17e} {v.imag:.17e}" for v in h[:, i])
            out.write(f"{fi:.17e} {values}\n")


def mac(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return abs(np.vdot(a, b)) ** 2 / (np.vdot(a, a).real * np.vdot(b, b).real)


def run_sdypy(f, h, truth):
    from sdypy import EMA

    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = EMA.Model(frf=h, freq=f, lower=80, upper=800, pol_order_high=30,
                          frf_form="mobility")
        model.get_poles("lscf", show_progress=False)
        model.select_closest_poles(truth["frequency_hz"])
        model.get_constants(method="lsfd", f_lower=80, f_upper=800)
        shapes = model.normal_mode()
    seconds = time.perf_counter() - start
    return {
        "seconds": seconds,
        "frequency_hz": list(model.nat_freq),
        "damping_ratio": list(model.nat_xi),
        "shapes": [shapes[:, j] for j in range(shapes.shape[1])],
    }


def run_jointid(path, extra, band=("80", "800")):
    cmd = ["cargo", "run", "--quiet", "--release", "--example", "extract_synthetic", "--",
           path] + (["--band", *band] if band else []) + extra
    out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    result = json.loads(out)
    return {
        "seconds": result["seconds"],
        "band_hz": result["band_hz"],
        "rejected": result["rejected"],
        "frequency_hz": [m["frequency_hz"] for m in result["modes"]],
        "damping_ratio": [m["damping_ratio"] for m in result["modes"]],
        "shapes": [m["real_shape"] for m in result["modes"]],
    }


def best(runs):
    fastest = min(runs, key=lambda r: r["seconds"])
    return fastest


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    f, h, truth = case()
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "frfs.txt")
        write(path, f, h)
        subprocess.run(["cargo", "build", "--quiet", "--release", "--example",
                        "extract_synthetic"], cwd=ROOT, check=True)
        results = {
            "sdypy-EMA 0.31 (LSCF+LSFD)": best([run_sdypy(f, h, truth) for _ in range(args.repeat)]),
            "jointid (LSCF+LSFD)": best([run_jointid(path, ["--no-refine"]) for _ in range(args.repeat)]),
            "jointid (refined)": best([run_jointid(path, []) for _ in range(args.repeat)]),
            "jointid (no band, refined)": best([run_jointid(path, [], None)
                                                for _ in range(args.repeat)]),
        }
    print(f"{h.shape[0]} mobility FRFs, {len(f)} lines (0.25 Hz), band 80-800 Hz, "
          f"2% + 1e-4 noise; wall time: best of {args.repeat}")
    header = f"{'method':28s} {'mode':>4s} {'f true':>8s} {'f err %':>9s} {'zeta true':>9s} " \
             f"{'zeta err %':>10s} {'MAC':>8s}"
    print(header)
    for name, r in results.items():
        if len(r["frequency_hz"]) != len(truth["frequency_hz"]):
            print(f"{name:28s} found {len(r['frequency_hz'])} modes, expected "
                  f"{len(truth['frequency_hz'])}")
        for j, (ft, zt, st) in enumerate(zip(truth["frequency_hz"], truth["damping_ratio"],
                                             truth["shapes"])):
            # Pair each true mode with the nearest identified frequency.
            if not r["frequency_hz"]:
                continue
            i = int(np.argmin([abs(x - ft) for x in r["frequency_hz"]]))
            fe = 100 * (r["frequency_hz"][i] - ft) / ft
            ze = 100 * (r["damping_ratio"][i] - zt) / zt
            print(f"{name:28s} {j + 1:4d} {ft:8.2f} {fe:+9.4f} {zt:9.4f} {ze:+10.3f} "
                  f"{mac(r['shapes'][i], st):8.6f}")
        print(f"{name:28s} wall time {r['seconds'] * 1000:.1f} ms")
        if "band_hz" in r:
            found = ", ".join(f"{x:.2f}" for x in r["frequency_hz"])
            print(f"{name:28s} band {r['band_hz'][0]:.2f}-{r['band_hz'][1]:.2f} Hz, modes {found} Hz; "
                  f"rejected: {r['rejected'] or 'none'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
