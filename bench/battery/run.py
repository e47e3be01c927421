"""Score `jointid diagnose` on a battery made by bench/battery/generate.py.

Runs, for every case folder (model.toml, measured.csv, truth.json) of a battery, 2 at a time:

    jointid diagnose --model model.toml --measured measured.csv \
        --frequency-noise <stated> --shape-noise <stated> --json <reports>/<battery>/<case>.json

reads each report's `verdict` and `selected`, and prints (markdown) per noise situation the
confusion matrix truth class x verdict and the fraction of right verdicts, then a summary.

Verdict words: `none`, `effect` (with `selected` naming the effect; today a string, later
perhaps an object with a `name` or a list), `unexplained`, and whatever future verdicts say
(`ambiguous`, `frequency_dependent`, ...): an unknown word is its own column, never a crash. A
case where the tool fails (exit code != 0, no JSON) is `error`.

The right verdicts per truth are the table RULES below (the generator writes the same into each
truth.json under "expected"). Why these:
- clean: `none`, nothing is missing from the model.
- a library effect, strong (noncentrality 400 at the stated noise, 20 sigma): `effect` with
  that name; anything else is wrong (a joint mass with its larger rotary inertia is still a
  joint mass: naming it is what the user needs).
- a library effect, weak (noncentrality 16: a perfect one-parameter candidate would pass the
  Bonferroni test in ~80% of tests under the stated noise): `effect` with its name, or `none`.
  At the detection limit a miss is the test's limited power, not a false statement; naming
  another effect or `unexplained` is wrong. The report also gives the detection rate.
- an effect outside the library, strong: `unexplained` (for the frequency-dependent joint also
  `frequency_dependent`): no candidate is the truth, so a named effect is wrong, and a
  20-sigma discrepancy passing as `none` is wrong too.
- outside, weak: `unexplained`, or `none` (at the limit, as above); a named effect is wrong.
- `partial:<name>` (a cause named, a misfit beyond the noise remaining) is right wherever
  `unexplained` is: for an effect outside the library it says that something remains.
`ambiguous` is counted as not right everywhere (shown in its own column).

Mimicry (truth.json "effect.mimicry", computed by the generator, detect.py): a library effect
e that reproduces the truth's noise-free data to within the detection limit is not something
any test can tell from the truth, and naming it states what the data show. `effect:e` is also
right when e's mimicry noncentrality lambda_e, at the situation's true noise, is at most
min(16, lambda / 16): below the battery's detection limit (16) and leaving at most 1/16 of the
truth's own noncentrality lambda (so a weak effect, lambda 16, is mimicked only by an effect
within lambda_e <= 1). At the true noise: lambda scales as (stated / true sigma)^2, so x4 for
half_stated and x1/4 for twice_stated; floor_x10 and heavy_tailed keep the stated value (for
floor_x10 that overstates lambda_e: the strict side). The tables give both scores: `right`
with the mimicry rule, `strict` without it.

Several battery folders (the same design drawn with other seeds) are scored together: the
tables pool their cases, and a first table gives each folder's score per situation.

Usage: run.py BATTERY_DIR [BATTERY_DIR ...] [--jointid target/release/jointid] [--jobs 2]
       [--reports DIR] [--markdown FILE] [--csv FILE]
"""

from __future__ import annotations

import argparse
import concurrent.futures
import csv
import json
import subprocess
import sys
import time
from collections import Counter, defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import detect  # noqa: E402

# (truth kind, size class) -> right verdict words; "{name}" is the truth's effect name.
RULES = {
    ("clean", "none"): ["none"],
    ("library", "strong"): ["effect:{name}"],
    ("library", "weak"): ["effect:{name}", "none"],
    ("outside", "strong"): ["unexplained"],
    ("outside", "weak"): ["unexplained", "none"],
}
# effects for which a future verdict word is also right
ALSO_RIGHT = {"frequency_joint": ["frequency_dependent"]}

RULE_TEXT = {
    ("clean", "none"): "clean: nothing is missing, the verdict must be none",
    ("library", "strong"): "library effect clearly above the noise (lambda 400): it must be named",
    ("library", "weak"): "library effect at the detection limit (lambda 16): named, or none (a miss is limited power); another name or unexplained is wrong",
    ("outside", "strong"): "effect outside the library clearly above the noise (lambda 400): unexplained; a named library effect or none is wrong",
    ("outside", "weak"): "effect outside the library at the detection limit (lambda 16): unexplained or none; a named library effect is wrong",
}


# noncentrality at the situation's true noise over that at the stated noise (module docs)
TRUE_NOISE_POWER = {"as_stated": 1.0, "floor_x10": 1.0, "twice_stated": 0.25, "half_stated": 4.0, "heavy_tailed": 1.0}
DETECTION_LIMIT = detect.WEAK


def mimics(noncentrality: float | None, mimicry: dict | None, situation: str | None) -> list:
    """The library effects that reproduce the truth within the detection limit (module docs)."""
    if not mimicry or not noncentrality or situation is None:
        return []
    power = TRUE_NOISE_POWER[situation]
    limit = min(DETECTION_LIMIT, power * noncentrality / DETECTION_LIMIT)
    return sorted(e for e, m in mimicry.items() if power * m["noncentrality"] <= limit)


def expected(effect: str | None, kind: str, size_class: str, noncentrality: float | None = None,
             mimicry: dict | None = None, situation: str | None = None) -> dict:
    """The right verdict words of a truth and the rules that give them (without `mimicry`:
    the strict rules)."""
    key = (kind, size_class)
    words = [w.format(name=effect) for w in RULES[key]] + ALSO_RIGHT.get(effect or "", [])
    also = mimics(noncentrality, mimicry, situation)
    rule = RULE_TEXT[key]
    if also:
        words += [f"effect:{e}" for e in also if f"effect:{e}" not in words]
        rule += f"; mimicked within the detection limit by {', '.join(also)}: naming it is also right"
    return {"right_verdicts": words, "rule": rule}


def verdict_word(report: dict) -> str:
    """`none`, `effect:<name>`, `unexplained`, or any other verdict word as it is."""
    v = report.get("verdict")
    if not isinstance(v, str):
        return "other"
    if v == "partial":
        sel = report.get("selected")
        return f"partial:{sel}" if isinstance(sel, str) else "partial:?"
    if v != "effect":
        return v
    sel = report.get("selected")
    if isinstance(sel, str):
        return f"effect:{sel}"
    if isinstance(sel, dict) and isinstance(sel.get("name"), str):
        return f"effect:{sel['name']}"
    if isinstance(sel, list):
        names = [s if isinstance(s, str) else s.get("name", "?") for s in sel if isinstance(s, (str, dict))]
        return "effect:" + "+".join(names)
    return "effect:?"


def is_right(word: str, right: list) -> bool:
    """Whether `word` is among the right verdicts, a partial explanation counting where
    `unexplained` does (module docs)."""
    return word in right or (word.startswith("partial:") and "unexplained" in right)


def run_case(jointid: str, case: Path, reports: Path) -> dict:
    truth = json.loads((case / "truth.json").read_text())
    reports = reports / case.parent.name
    reports.mkdir(parents=True, exist_ok=True)
    stated = truth["noise"]["stated"]
    out = reports / f"{case.name}.json"
    if out.exists():
        out.unlink()
    cmd = [
        jointid, "diagnose", "--model", str(case / "model.toml"), "--measured", str(case / "measured.csv"),
        "--frequency-noise", repr(stated["frequency"]), "--shape-noise", repr(stated["shape"]), "--json", str(out),
    ]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    if proc.returncode != 0 or not out.exists():
        word = "error"
        lines = [l.strip() for l in proc.stderr.splitlines() if l.strip()]
        panic = [i for i, l in enumerate(lines) if "panicked at" in l]
        if panic:
            i = panic[0]
            detail = "panic: " + " ".join(lines[i : i + 2])
        else:
            detail = next((l for l in lines if l.startswith("error")), lines[-1] if lines else "(no message)")
    else:
        try:
            word = verdict_word(json.loads(out.read_text()))
            detail = ""
        except (json.JSONDecodeError, OSError) as e:
            word, detail = "error", f"unreadable report: {e}"
    eff = truth["effect"]
    strict = expected(eff["name"], eff["kind"], eff["size_class"])["right_verdicts"]
    situation = truth["noise"]["situation"]
    right = expected(eff["name"], eff["kind"], eff["size_class"], eff.get("noncentrality"), eff.get("mimicry"), situation)["right_verdicts"]
    return {
        "battery": case.parent.name,
        "case": case.name,
        "situation": situation,
        "truth": "clean" if eff["name"] is None else f"{eff['name']}/{eff['size_class']}",
        "kind": eff["kind"],
        "size_class": eff["size_class"],
        "effect": eff["name"],
        "geometry": truth["geometry"]["id"],
        "sensors": truth["sensors"]["kind"],
        "verdict": word,
        "right": is_right(word, right),
        "strict": is_right(word, strict),
        "mimics": "+".join(mimics(eff.get("noncentrality"), eff.get("mimicry"), situation)),
        "seconds": seconds,
        "detail": detail,
    }


KIND_ORDER = {"clean": 0, "library": 1, "outside": 2}


def truth_key(row: dict):
    return (KIND_ORDER[row["kind"]], row["effect"] or "", row["size_class"] != "strong")


def markdown(rows: list, wall: float, battery: str) -> str:
    lines = [f"# jointid diagnose on battery `{battery}`", ""]
    situations = list(dict.fromkeys(r["situation"] for r in sorted(rows, key=lambda r: r["case"])))
    words = sorted({r["verdict"] for r in rows}, key=lambda w: (w != "none", not w.startswith("effect:"), w))
    lines += [
        "| noise situation | cases | right | strict | clean -> none | library strong named | library weak named | library weak named or none | outside right | errors |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]

    def frac(sel, pred):
        sel = list(sel)
        return f"{sum(pred(r) for r in sel)}/{len(sel)}" if sel else "-"

    def summary(label, rs):
        right = sum(r["right"] for r in rs)
        return (
            f"| {label} | {len(rs)} | {right}/{len(rs)} ({100 * right / len(rs):.0f}%) "
            f"| {frac(rs, lambda r: r['strict'])} "
            f"| {frac((r for r in rs if r['kind'] == 'clean'), lambda r: r['verdict'] == 'none')} "
            f"| {frac((r for r in rs if r['kind'] == 'library' and r['size_class'] == 'strong'), lambda r: r['right'])} "
            f"| {frac((r for r in rs if r['kind'] == 'library' and r['size_class'] == 'weak'), lambda r: r['verdict'] == 'effect:' + r['effect'])} "
            f"| {frac((r for r in rs if r['kind'] == 'library' and r['size_class'] == 'weak'), lambda r: r['right'])} "
            f"| {frac((r for r in rs if r['kind'] == 'outside'), lambda r: r['right'])} "
            f"| {sum(r['verdict'] == 'error' for r in rs)} |"
        )

    for s in situations + ["all"]:
        lines.append(summary(s, [r for r in rows if s == "all" or r["situation"] == s]))
    batteries = list(dict.fromkeys(r["battery"] for r in rows))
    if len(batteries) > 1:
        lines += ["", "Per battery folder (right verdicts per situation):", "",
                  "| battery | " + " | ".join(situations) + " | all | clean -> none |",
                  "|---" * (len(situations) + 3) + "|"]
        for b in batteries:
            rb = [r for r in rows if r["battery"] == b]
            cells = []
            for s in situations + ["all"]:
                rs = [r for r in rb if s == "all" or r["situation"] == s]
                cells.append(f"{sum(r['right'] for r in rs)}/{len(rs)}")
            clean = [r for r in rb if r["kind"] == "clean"]
            cells.append(f"{sum(r['verdict'] == 'none' for r in clean)}/{len(clean)}")
            lines.append(f"| {b} | " + " | ".join(cells) + " |")
    layouts = sorted({r["sensors"] for r in rows})
    if len(layouts) > 1:
        lines += ["", "By sensor layout (all: w at every node; subset: w at 3-6 nodes):", "", lines[2], lines[3]]
        for lay in layouts:
            for s in situations:
                rs = [r for r in rows if r["situation"] == s and r["sensors"] == lay]
                if rs:
                    lines.append(summary(f"{s}, {lay}", rs))
    secs = sorted(r["seconds"] for r in rows)
    lines += ["", f"{len(rows)} cases in {wall:.1f} s wall time (2 at a time); per case median {secs[len(secs) // 2]:.2f} s, max {secs[-1]:.2f} s.", ""]
    for s in situations:
        rs = [r for r in rows if r["situation"] == s]
        right = sum(r["right"] for r in rs)
        lines += [f"## {s}: {right}/{len(rs)} right ({100 * right / len(rs):.0f}%)", ""]
        cols = [w for w in words if any(r["verdict"] == w for r in rows)]
        lines.append("| truth \\ verdict | " + " | ".join(c.replace("effect:", "") if c.startswith("effect:") else f"*{c}*" for c in cols) + " | right | strict | mimicked by |")
        lines.append("|---" * (len(cols) + 4) + "|")
        by_truth = defaultdict(list)
        for r in rs:
            by_truth[r["truth"]].append(r)
        for t in sorted(by_truth, key=lambda t: truth_key(by_truth[t][0])):
            cnt = Counter(r["verdict"] for r in by_truth[t])
            ok = sum(r["right"] for r in by_truth[t])
            cells = [str(cnt[c]) if cnt[c] else "." for c in cols]
            strict = sum(r["strict"] for r in by_truth[t])
            mim = Counter(m for r in by_truth[t] for m in r["mimics"].split("+") if m)
            mimicked = ", ".join(f"{m} ({n})" for m, n in sorted(mim.items())) or "."
            lines.append(f"| {t} | " + " | ".join(cells) + f" | {ok}/{len(by_truth[t])} | {strict}/{len(by_truth[t])} | {mimicked} |")
        lines.append("")
    lines.append("Columns: effect names are `effect` verdicts naming that candidate; words in italics are other verdicts.")
    errors = [r for r in rows if r["verdict"] == "error"]
    if errors:
        lines += ["", "Errors:", ""] + [f"- {r['case']}: {r['detail']}" for r in errors[:20]]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("battery", type=Path, nargs="+")
    ap.add_argument("--jointid", default="target/release/jointid")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--reports", type=Path, default=None, help="where the JSON reports go, a folder per battery (default target/battery-reports)")
    ap.add_argument("--markdown", type=Path, default=None, help="also write the tables here")
    ap.add_argument("--csv", type=Path, default=None, help="one row per case")
    args = ap.parse_args(argv)
    if len({b.resolve().name for b in args.battery}) < len(args.battery):
        print("battery folders must have distinct names (their reports go under them)", file=sys.stderr)
        return 2
    cases = []
    for battery in args.battery:
        found = sorted(p for p in battery.iterdir() if (p / "truth.json").exists())
        if not found:
            print(f"{battery}: no case folders (with truth.json)", file=sys.stderr)
            return 2
        cases += found
    if not Path(args.jointid).exists():
        print(f"{args.jointid}: no such binary; build it with `cargo build --release`", file=sys.stderr)
        return 2
    reports = args.reports or Path("target/battery-reports")
    t0 = time.perf_counter()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        rows = list(pool.map(lambda c: run_case(args.jointid, c, reports), cases))
    wall = time.perf_counter() - t0
    text = markdown(rows, wall, " + ".join(b.name for b in args.battery))
    print(text)
    if args.markdown:
        args.markdown.write_text(text)
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
