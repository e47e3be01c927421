//! Shards and results that were damaged after they were written: merge refuses every one,
//! naming the file, the line and the fault, and writes nothing; `check --results` refuses
//! NaN and inf and statistics that contradict the trial counts.

use std::path::{Path, PathBuf};

use crate::common::{ci_study, jointid, refused, s, scratch};

/// The CI study, 300 trials, its CSV `single.csv` beside it.
fn study(dir: &Path) -> PathBuf {
    ci_study(dir, "s.toml", "ci-bias", "single.csv", 300)
}

fn ok(args: &[&str]) {
    let o = jointid(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Exit 2, every needle in the error, and `out` not written.
fn refused_to(args: &[&str], out: &Path, needles: &[&str]) {
    refused(args, needles);
    assert!(!out.exists(), "{} written", out.display());
}

/// `text` with field `field` of data line `line` (1-based, of the lines after the `#` header
/// and the column line) replaced by `value`.
fn with_field(text: &str, line: usize, field: usize, value: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let first = lines.iter().position(|l| l.starts_with("cell,")).unwrap() + line;
    let mut fields: Vec<&str> = lines[first].split(',').collect();
    fields[field] = value;
    lines[first] = fields.join(",");
    lines.join("\n") + "\n"
}

#[test]
fn a_damaged_shard_is_refused_naming_file_line_and_fault() {
    let dir = scratch("integrity", "merge");
    let study_path = study(&dir);
    let shards: Vec<PathBuf> = (1..=2).map(|k| dir.join(format!("s.{k}.csv"))).collect();
    for (k, path) in shards.iter().enumerate() {
        let spec = format!("{}/2", k + 1);
        ok(&[
            "study",
            s(&study_path),
            "--quiet",
            "--shard",
            &spec,
            "--out",
            s(path),
        ]);
    }
    let merged = dir.join("merged.csv");
    ok(&["merge", s(&shards[0]), s(&shards[1]), "--out", s(&merged)]);
    ok(&["study", s(&study_path), "--quiet"]);
    assert_eq!(
        std::fs::read(&merged).unwrap(),
        std::fs::read(dir.join("single.csv")).unwrap()
    );
    std::fs::remove_file(&merged).unwrap();
    let good = std::fs::read_to_string(&shards[0]).unwrap();
    let header_lines = good.lines().take_while(|l| l.starts_with('#')).count();
    let data = |i: usize| good.lines().nth(header_lines + i).unwrap().to_string();
    let mut swapped: Vec<String> = good.lines().map(str::to_string).collect();
    swapped.swap(header_lines + 1, header_lines + 2);
    let cut = &good[..good.len() - 5];
    let mean = 13;
    let damaged: Vec<(&str, String)> = vec![
        ("NaN", with_field(&good, 1, mean, "NaN")),
        ("inf", with_field(&good, 2, mean, "inf")),
        ("param", with_field(&good, 1, 2, "k9")),
        ("n", with_field(&good, 1, 3, "11")),
        ("weighting", with_field(&good, 1, 6, "equal")),
        ("reordered", swapped.join("\n") + "\n"),
        ("cut", cut.to_string()),
        ("dropped", good.replace(&format!("{}\n", data(2)), "")),
    ];
    for (what, text) in damaged {
        assert_ne!(text, good, "{what}");
        std::fs::write(&shards[0], &text).unwrap();
        refused_to(
            &["merge", s(&shards[0]), s(&shards[1]), "--out", s(&merged)],
            &merged,
            &[&format!("{}:", s(&shards[0])), "rerun its shard"],
        );
    }
    std::fs::write(&shards[0], &good).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_shard_whose_hash_was_refreshed_is_still_checked_row_by_row() {
    let dir = scratch("integrity", "rows");
    let study_path = study(&dir);
    let shard = dir.join("s.1.csv");
    let shard_run = format!(
        "study {} --quiet --shard 1/1 --out {}",
        s(&study_path),
        s(&shard)
    );
    ok(&shard_run.split_whitespace().collect::<Vec<_>>());
    let good = std::fs::read_to_string(&shard).unwrap();
    let merged = dir.join("merged.csv");
    for (line, field, value, fault) in [
        (1, 13, "NaN", "mean = `NaN` is not a finite number"),
        (2, 2, "k9", "param = `k9` is not a parameter of the study"),
        (2, 3, "11", "n = `11` but line"),
        (1, 12, "999", "failures = 999 is more than trials = 300"),
    ] {
        let text = with_field(&good, line, field, value);
        // Recompute the header's hash, as a careless edit tool might.
        let (head, rows) = text.split_at(text.find("cell,").unwrap());
        let hash = format!(
            "{:016x}",
            jointid::study::fingerprint::fnv1a(
                jointid::study::fingerprint::FNV_OFFSET,
                rows.as_bytes(),
            )
        );
        let head: String = head
            .lines()
            .map(|l| {
                if l.starts_with("# rows hash:") {
                    format!("# rows hash: {hash}\n")
                } else {
                    format!("{l}\n")
                }
            })
            .collect();
        std::fs::write(&shard, format!("{head}{rows}")).unwrap();
        let data_line = text.lines().position(|l| l.starts_with("cell,")).unwrap() + 1 + line;
        refused_to(
            &["merge", s(&shard), "--out", s(&merged)],
            &merged,
            &[&format!("{}:{data_line}: {fault}", s(&shard))],
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn check_results_refuses_nan_inf_and_contradicting_statistics() {
    let dir = scratch("integrity", "check");
    let study_path = study(&dir);
    ok(&["study", s(&study_path), "--quiet"]);
    let single = dir.join("single.csv");
    let good = std::fs::read_to_string(&single).unwrap();
    let o = jointid(&["check", s(&study_path), "--results", s(&single)]);
    assert_eq!(o.status.code(), Some(0));
    let bad = dir.join("bad.csv");
    for (field, value, fault) in [
        (13, "NaN", "single.csv"),
        (13, "inf", "mean = `inf` is not a finite number"),
        (24, "NaN", "bias_se = `NaN` is not a finite number"),
        (13, "", "mean is empty although 300 trial(s) succeeded"),
    ] {
        let _ = fault;
        for line in 1..=4 {
            std::fs::write(&bad, with_field(&good, line, field, value)).unwrap();
            let o = jointid(&["check", s(&study_path), "--results", s(&bad)]);
            let err = String::from_utf8_lossy(&o.stderr);
            let out = String::from_utf8_lossy(&o.stdout);
            assert_eq!(o.status.code(), Some(2), "{value}: {out}{err}");
            assert!(!out.contains("check passed"), "{out}");
            let fault = if value == "NaN" && field == 13 {
                "mean = `NaN` is not a finite number"
            } else {
                fault
            };
            assert!(
                err.contains(&format!("bad.csv:{}: {fault}", line + 1)),
                "{err}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
