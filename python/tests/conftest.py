"""Shared fixtures of the Python package's tests: the repository, the release CLI to compare
with (``JOINTID_BIN``, default ``target/release/jointid``; ``CARGO_TARGET_DIR`` is honoured)
and the real UNESP-BERT files (``../shared/data/unesp-bert``, never copied here; the tests
that need them skip, saying so, when they are absent)."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
UNESP = Path(os.environ.get("UNESP_BERT_DIR", ROOT.parent / "shared" / "data" / "unesp-bert"))


def _cli():
    if "JOINTID_BIN" in os.environ:
        return Path(os.environ["JOINTID_BIN"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return target / "release" / "jointid"


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def cli():
    """Runs the release CLI with arguments; returns its completed process (checked)."""
    exe = _cli()
    if not exe.exists():
        pytest.fail(f"{exe} is absent: build it with `cargo build --release` or set JOINTID_BIN")

    def run(*args):
        done = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        return done

    return run


@pytest.fixture(scope="session")
def unesp():
    if not UNESP.is_dir():
        pytest.skip(f"{UNESP} is absent: the UNESP-BERT files are not shared here")
    return UNESP
