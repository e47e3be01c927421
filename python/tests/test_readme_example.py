"""README's Python example runs on the real UNESP-BERT files (skipped, saying so, where they
are absent) and gives what the CLI's pipeline gives on them: two modes near 18.8 and 98.4 Hz
(the data's README), k2 identified on each, a diagnosis with a verdict.

Independence: the expected frequencies are the data set's own description, not jointid's."""

import re

import numpy as np


def test_readme_example_runs(root, unesp, monkeypatch, capsys):
    text = (root / "README.md").read_text()
    block = re.search(r"## Python\n.*?```python\n(.*?)```", text, re.S).group(1)
    block = block.replace('"../shared/data/unesp-bert"', repr(str(unesp)))
    monkeypatch.chdir(root)
    scope = {}
    exec(compile(block, "README.md", "exec"), scope)
    np.testing.assert_allclose(scope["modes"]["frequency_hz"], [18.8, 98.4], rtol=0.01)
    assert list(scope["k2"]["param"]) == ["k2", "k2"]
    assert np.all(np.isfinite(scope["k2"]["corrected"]))
    assert scope["report"]["verdict"] in {"none", "found", "inconclusive", "unexplained"}
    assert capsys.readouterr().out.strip()
