"""The same study from Python (``jointid.study``, in this process) and from the CLI (``jointid
study``, a whole process), runs interleaved so that both see the same machine load, medians of
REPEAT runs; beside them the numpy peer (../shared/bench/numpy_baseline.py, when present) on
the same trials. Then the time of one call on the paper's 40-DOF model (identify, modes),
median of 200 calls: the overhead of a call beyond its work is below it.

usage: $(bash scripts/python-package.sh) bench/python_vs_cli.py [REPEAT [TRIALS [THREADS]]]
  defaults: 5 runs, 1e6 trials, 2 threads; the CLI is JOINTID_BIN or target/release/jointid.
The study is bench/paper-cell.toml (case I, n 10, m 5, NF 5, inverse, uniform 4%, modes 1-4)."""

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import jointid

ROOT = Path(__file__).resolve().parents[1]
repeat = int(sys.argv[1]) if len(sys.argv) > 1 else 5
trials = int(sys.argv[2]) if len(sys.argv) > 2 else 1_000_000
threads = int(sys.argv[3]) if len(sys.argv) > 3 else 2
target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
cli = Path(os.environ.get("JOINTID_BIN", target / "release" / "jointid"))
numpy_peer = ROOT.parent / "shared" / "bench" / "numpy_baseline.py"

with tempfile.TemporaryDirectory() as work:
    work = Path(work)
    study = work / "paper-cell.toml"
    text = (ROOT / "bench" / "paper-cell.toml").read_text()
    text = text.replace('model = "../models/', f'model = "{ROOT}/models/')
    text = text.replace("trials = 1000000", f"trials = {trials}")
    study.write_text(text.replace('csv = "/tmp/paper-cell.csv"', f'csv = "{work}/cli.csv"'))
    times = {"cli": [], "python": [], "numpy": []}
    for r in range(repeat):
        t0 = time.perf_counter()
        subprocess.run([str(cli), "study", str(study), "--quiet", "--threads", str(threads)],
                       check=True, stdout=subprocess.DEVNULL)
        times["cli"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        csv = jointid.study(study, threads=threads, as_csv=True)
        times["python"].append(time.perf_counter() - t0)
        if r == 0:
            same = csv == (work / "cli.csv").read_text()
            print(f"result CSV from Python {'identical to' if same else 'DIFFERS from'} the CLI's")
        if numpy_peer.exists():
            t0 = time.perf_counter()
            subprocess.run([sys.executable, str(numpy_peer), str(trials)], check=True,
                           stdout=subprocess.DEVNULL,
                           env={**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"})
            times["numpy"].append(time.perf_counter() - t0)

print(f"paper cell, {trials} trials x 4 modes, {threads} thread(s), median of {repeat} interleaved runs")
print(f"load average at the end: {open('/proc/loadavg').read().split()[0]}")
cli_s = statistics.median(times["cli"])
print("| program | wall s | x CLI |")
print("|---|---|---|")
print(f"| jointid study (CLI, whole process) | {cli_s:.3f} | 1 |")
py_s = statistics.median(times["python"])
print(f"| jointid.study (Python call) | {py_s:.3f} | {py_s / cli_s:.3f} |")
if times["numpy"]:
    np_s = statistics.median(times["numpy"])
    print(f"| numpy_baseline.py (1 thread, whole process) | {np_s:.3f} | {np_s / cli_s:.3f} |")

model = jointid.Model.from_toml(ROOT / "models" / "paper-case-1.toml")
measured = jointid.simulate(model, 4, shape_noise=0.01, seed=3, measure="w")
for name, call in {
    "identify (n 10, m 5, 4 modes)": lambda: jointid.identify(
        model, measured, n=10, m=5, weighting="inverse", as_csv=True),
    "modes(10)": lambda: model.modes(10),
}.items():
    spans = []
    for _ in range(200):
        t0 = time.perf_counter()
        call()
        spans.append(time.perf_counter() - t0)
    print(f"one call of {name} on the 40-DOF model: median {1e3 * statistics.median(spans):.3f} ms (work included)")
