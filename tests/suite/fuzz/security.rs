//! Properties of the security surfaces (part of the `fuzz` suite, same case counts):
//! `cluster slurm` with hostile strings (no injected command runs, a refusal writes nothing),
//! `merge` of mutated shard rows (refused, or exactly the single-machine CSV), external models
//! of mutated files (refused, or finite positive frequencies), and the universal-file and
//! geometry readers (a node at two places is refused; many blank lines are bounded).

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use proptest::prelude::*;

use super::{config, exits_cleanly, jointid, names};
use crate::common::scratch;

/// Fragments a hostile value is made of: shell syntax, newlines, and plausible values.
fn hostile() -> impl Strategy<Value = String> {
    let fragment = prop::sample::select(vec![
        "short",
        "01:00:00",
        "4G",
        "--qos=x",
        "a",
        "9",
        "\n",
        "\r",
        " ",
        "'",
        "\"",
        "`",
        "$",
        "$(touch PWNED)",
        "`touch PWNED`",
        ";touch PWNED;",
        "|",
        "&",
        "\\",
        "%j",
        "#SBATCH --array=1",
        "/",
        "..",
        "\u{e9}",
    ]);
    proptest::collection::vec(fragment, 1..5).prop_map(|parts| parts.concat())
}

fn script(path: &Path, body: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, format!("#!/bin/sh\n{body}")).unwrap();
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).unwrap();
}

fn pwned(dir: &Path) -> bool {
    std::fs::read_dir(dir).unwrap().any(|e| {
        let p = e.unwrap().path();
        p.file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with("PWNED")
            || (p.is_dir() && pwned(&p))
    })
}

/// The CI study (its model by absolute path, 200 trials) in `dir`.
fn ci_study(dir: &Path) -> PathBuf {
    crate::common::ci_study(dir, "s.toml", "ci-bias", "single.csv", 200)
}

/// Two shards of the CI study and its single-machine CSV, made once.
fn shards() -> &'static (String, String, Vec<u8>) {
    static MADE: OnceLock<(String, String, Vec<u8>)> = OnceLock::new();
    MADE.get_or_init(|| {
        let dir = scratch("fuzz", "shards");
        let study = ci_study(&dir);
        let s = |p: &Path| p.to_str().unwrap().to_string();
        for k in 1..=2 {
            let out = dir.join(format!("{k}.csv"));
            let spec = format!("{k}/2");
            let o = jointid(
                &dir,
                &[
                    "study",
                    &s(&study),
                    "--quiet",
                    "--shard",
                    &spec,
                    "--out",
                    &s(&out),
                ],
            );
            assert!(o.status.success());
        }
        let o = jointid(&dir, &["study", &s(&study), "--quiet"]);
        assert!(o.status.success());
        let read = |n: &str| std::fs::read_to_string(dir.join(n)).unwrap();
        let made = (
            read("1.csv"),
            read("2.csv"),
            std::fs::read(dir.join("single.csv")).unwrap(),
        );
        let _ = std::fs::remove_dir_all(&dir);
        made
    })
}

/// A field of a data row replaced, a line dropped, doubled or swapped with the next, or the
/// text cut at a byte.
fn mutate_shard(text: &str, op: u8, line: usize, field: usize, value: &str, cut: usize) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let i = line % lines.len();
    match op {
        0 => {
            let mut fields: Vec<String> = lines[i].split(',').map(str::to_string).collect();
            let f = field % fields.len();
            fields[f] = value.to_string();
            lines[i] = fields.join(",");
        }
        1 => {
            lines.remove(i);
        }
        2 => lines.insert(i, lines[i].clone()),
        3 if i + 1 < lines.len() => lines.swap(i, i + 1),
        _ => return text[..cut % text.len()].to_string(),
    }
    lines.join("\n") + "\n"
}

/// Dataset 15 with `nodes` (label, x).
fn geometry(nodes: &[(u64, f64)]) -> Vec<u8> {
    let mut text = String::from("    -1\n    15\n");
    for (label, x) in nodes {
        let x = format!("{x:.5e}");
        text.push_str(&format!(
            "{label:>10}{:>10}{:>10}{:>10}{x:>13}{:>13}{:>13}\n",
            0, 0, 1, "0.00000e0", "0.00000e0"
        ));
    }
    text.push_str("    -1\n");
    text.into_bytes()
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn cluster_slurm_runs_no_injected_command(
        flag in prop::sample::select(vec!["--partition", "--time", "--account", "--mem", "--sbatch", "--dir", "--out"]),
        value in hostile(),
    ) {
        let dir = scratch("fuzz", "slurm");
        let study = ci_study(&dir);
        let calls = dir.join("calls");
        let stub = dir.join("bin/jointid");
        script(&stub, &format!("echo \"$@\" >> '{}'\n", calls.display()));
        script(&dir.join("stubs/sbatch"), "echo 7\n");
        let jobs = dir.join("jobs");
        let path_value = dir.join(&value);
        let value = if flag == "--out" || flag == "--dir" { path_value.to_string_lossy().into_owned() } else { value };
        let flagged = format!("{flag}={value}");
        let mut args = vec!["cluster", "slurm", study.to_str().unwrap(), "--shards", "2", "--jointid", stub.to_str().unwrap(), &flagged];
        if flag != "--dir" {
            args.extend(["--dir", jobs.to_str().unwrap()]);
        }
        let before = names(&dir);
        let out = jointid(&dir, &args);
        if exits_cleanly(&out)? {
            let jobs = if flag == "--dir" { PathBuf::from(&value) } else { jobs };
            let path = format!("{}:{}", dir.join("stubs").display(), std::env::var("PATH").unwrap());
            for (shell, name) in [("sh", "ci-bias.submit.sh"), ("bash", "ci-bias.shards.sbatch"), ("bash", "ci-bias.merge.sbatch")] {
                let run = Command::new(shell)
                    .arg(jobs.join(name))
                    .env("PATH", &path)
                    .env("SLURM_ARRAY_TASK_ID", "1")
                    .current_dir(&dir)
                    .output()
                    .unwrap();
                prop_assert!(run.status.success(), "{name}: {}", String::from_utf8_lossy(&run.stderr));
            }
            prop_assert!(!pwned(&dir), "{flag} {value:?} ran a command");
        } else {
            prop_assert_eq!(names(&dir), before);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn merge_of_mutated_shards_is_refused_or_exact(
        which in 0usize..2,
        op in 0u8..5,
        line in 0usize..200,
        field in 0usize..28,
        value in prop_oneof![super::wild_number(), Just("k9".to_string()), Just("NaN".to_string())],
        cut in 0usize..100_000,
    ) {
        let (one, two, single) = shards();
        let dir = scratch("fuzz", "merge");
        let texts = [one.as_str(), two.as_str()];
        let mutated = mutate_shard(texts[which], op, line, field, &value, cut);
        std::fs::write(dir.join("1.csv"), if which == 0 { &mutated } else { one }).unwrap();
        std::fs::write(dir.join("2.csv"), if which == 1 { &mutated } else { two }).unwrap();
        let out = jointid(&dir, &["merge", "1.csv", "2.csv", "--out", "m.csv"]);
        if exits_cleanly(&out)? {
            prop_assert!(&std::fs::read(dir.join("m.csv")).unwrap() == single, "merged a damaged shard into another CSV");
        } else {
            prop_assert!(!dir.join("m.csv").exists());
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn external_models_load_or_are_refused(
        file in prop::sample::select(vec!["K0.mtx", "M.mtx", "dK.mtx", "dofs.csv", "free.toml"]),
        op in 0u8..5,
        line in 0usize..20,
        field in 0usize..4,
        value in super::wild_number(),
        cut in 0usize..400,
    ) {
        let dir = scratch("fuzz", "external");
        let fixture = Path::new("tests/fixtures/matrices/two-dof");
        for name in ["free.toml", "K0.mtx", "M.mtx", "dK.mtx", "dofs.csv"] {
            std::fs::copy(fixture.join(name), dir.join(name)).unwrap();
        }
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let separator = if file.ends_with(".csv") { ',' } else { ' ' };
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        let i = line % lines.len();
        let mutated = match op {
            0 => {
                let mut fields: Vec<String> = lines[i].split(separator).map(str::to_string).collect();
                let f = field % fields.len();
                fields[f] = value;
                lines[i] = fields.join(&separator.to_string());
                lines.join("\n")
            }
            1 => { lines.remove(i); lines.join("\n") }
            2 => { lines.insert(i, lines[i].clone()); lines.join("\n") }
            3 => format!("{}\n{}", lines.join("\n"), "\n".repeat(1000)),
            _ => text[..cut % text.len()].to_string(),
        };
        std::fs::write(dir.join(file), mutated).unwrap();
        let out = jointid(&dir, &["simulate", "--model", "free.toml", "--modes", "1", "--out", "o.csv"]);
        if exits_cleanly(&out)? {
            // mode, frequency, DOF label (any text, `nan` included), value.
            let text = std::fs::read_to_string(dir.join("o.csv")).unwrap();
            for row in text.lines().skip(1) {
                let fields: Vec<&str> = row.split(',').collect();
                let f: f64 = fields[1].parse().unwrap();
                let v: f64 = fields[fields.len() - 1].parse().unwrap();
                prop_assert!(f > 0.0 && f.is_finite() && v.is_finite(), "{row}");
            }
        } else {
            prop_assert!(!dir.join("o.csv").exists());
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_geometry_node_has_one_place(
        nodes in proptest::collection::vec((1u64..5, -1.0f64..1.0), 1..8),
        blank in 0usize..3,
        flip in proptest::option::of((0usize..2000, any::<u8>())),
    ) {
        let mut bytes = geometry(&nodes);
        if blank > 0 {
            // Blank lines inside the dataset: read, and bounded.
            let at = bytes.len() - 7;
            bytes.splice(at..at, std::iter::repeat_n(b'\n', blank * 10_000));
        }
        if let Some((at, b)) = flip {
            let at = at % bytes.len();
            bytes[at] = b;
        }
        let Ok(records) = jointid::uff::read(&bytes, Path::new("g.uff")) else {
            return Ok(());
        };
        let sets: Vec<jointid::uff::Nodes> = records
            .into_iter()
            .filter_map(|r| match r { jointid::uff::Record::Nodes(n) => Some(n), _ => None })
            .collect();
        let channels: Vec<jointid::extract::universal::Channel> = (1..5)
            .map(|node| jointid::extract::universal::Channel { file: "f.uff".into(), record: 1, node, direction: 3 })
            .collect();
        if let Ok(x) = jointid::extract::universal::positions(&channels, &sets, Path::new("g.uff")) {
            for (c, x) in channels.iter().zip(x) {
                for n in sets.iter().flat_map(|s| &s.nodes).filter(|n| n.label == c.node) {
                    prop_assert_eq!(n.coordinates[0], x, "node {} read at two places", c.node);
                }
            }
        }
    }
}
