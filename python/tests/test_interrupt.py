"""Ctrl-C interrupts a long study: a child Python process runs a study of tens of millions of
trials (minutes); a SIGINT sent to it once it is running raises KeyboardInterrupt there
within a second, and the child exits. A progress callback sees the trials advance, and an
exception raised in it stops the study.

Independence: only the exit, the time and the exception's name are checked."""

import signal
import subprocess
import sys
import time

import pytest

import jointid

CHILD = r"""
import sys, jointid
study = {
    "name": "long", "model": sys.argv[1],
    "truth": {"delta": {"k1": 2.0e6, "k2": 2.0e3}},
    "grid": [{"modes": [1, 2, 3], "n": [10], "m": [5, 7], "nf": [0, 5, 23],
              "weighting": ["equal", "inverse", "inverse-sqrt"],
              "shape_noise": [0.01 * k for k in range(1, 11)], "frequency_noise": [0.0, 0.001]}],
    "monte_carlo": {"trials": 200000, "seed": 1, "noise": "uniform"},
    "output": {"csv": "unused.csv"},
}
print("running", flush=True)
jointid.study(study)
print("finished", flush=True)
"""


def test_sigint_interrupts_a_long_study(root):
    model = str(root / "models" / "paper-case-1.toml")
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, model],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    assert child.stdout.readline().strip() == "running"
    time.sleep(1.5)  # well inside the study (the import and the model take a fraction of it)
    assert child.poll() is None, "the study ended before it could be interrupted"
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=30)
    elapsed = time.monotonic() - sent
    assert "finished" not in out
    assert "KeyboardInterrupt" in err, err
    assert child.returncode != 0
    assert elapsed < 1.0, f"the child took {elapsed:.2f} s to stop"


def test_progress_reaches_the_total_and_can_stop(root):
    """The progress callback sees the trials advance to the total; raising in it stops."""
    model = str(root / "models" / "paper-case-1.toml")
    study = {
        "name": "progress", "model": model,
        "truth": {"delta": {"k1": 2.0e6, "k2": 2.0e3}},
        "grid": [{"modes": [1, 2], "n": [10], "m": [5], "nf": [0, 5],
                  "weighting": ["inverse"], "shape_noise": [0.04], "frequency_noise": [0.0]}],
        "monte_carlo": {"trials": 2000000, "seed": 1, "noise": "uniform"},
        "output": {"csv": "unused.csv"},
    }
    seen = []
    jointid.study(study, progress=lambda done, total: seen.append((done, total)))
    assert seen and all(total == 4000000 for _, total in seen)
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)

    class Enough(Exception):
        pass

    def stop(done, total):
        raise Enough()

    with pytest.raises(Enough):
        jointid.study(study, progress=stop)
