//! `jointid cluster slurm` with hostile values: every value that cannot be quoted (partition,
//! time, account, memory, extra options, the script folder, the study name) is refused with
//! exit 2 and nothing written; every path that can be quoted (the binary, the study, the
//! merged CSV) may hold `$(...)`, backquotes and quotes, and the scripts, run with stub
//! `sbatch` and `jointid` programs, run no injected command and hand each path through
//! unchanged.

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{ci_study, jointid, names, refused, s, scratch};

/// `cluster slurm` of `study` in 2 shards, scripts in `jobs`, with `extra` flags.
fn slurm(study: &Path, jobs: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "cluster",
        "slurm",
        s(study),
        "--shards",
        "2",
        "--dir",
        s(jobs),
    ];
    args.extend(extra);
    jointid(&args)
}

/// An executable shell script.
fn script(path: &Path, body: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, format!("#!/bin/sh\n{body}")).unwrap();
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).unwrap();
}

/// Every file under `dir` whose name starts with `PWNED`.
fn pwned(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            found.extend(pwned(&path));
        } else if path
            .file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with("PWNED"))
        {
            found.push(path);
        }
    }
    found
}

#[test]
fn hostile_paths_are_quoted_and_the_scripts_run_no_injected_command() {
    let dir = scratch("inject", "paths");
    let jobs = dir.join("jobs");
    // A binary, a study and an output whose paths try every way out of a quoted word.
    let stub = dir.join("bin $(touch PWNED1) `touch PWNED2`/jointid'; touch PWNED3; '");
    let calls = dir.join("calls.txt");
    script(
        &stub,
        &format!(
            "for a in \"$@\"; do printf '%s\\n' \"$a\" >> '{}'; done\n",
            s(&calls)
        ),
    );
    let study_path = ci_study(
        &dir,
        "s \"$(touch PWNED4)\".toml",
        "ci-bias",
        "single.csv",
        300,
    );
    let out = dir.join("out $(touch PWNED5) \"`touch PWNED6`\".csv");
    let o = slurm(
        &study_path,
        &jobs,
        &["--out", s(&out), "--jointid", s(&stub)],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // A stub sbatch that answers job ids; the submit script runs on the "login node".
    let bin = dir.join("stubs");
    script(&bin.join("sbatch"), "echo 42\n");
    let path = format!("{}:{}", s(&bin), std::env::var("PATH").unwrap());
    let submit = Command::new("sh")
        .arg(jobs.join("ci-bias.submit.sh"))
        .env("PATH", &path)
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(submit.status.success());
    let said = String::from_utf8_lossy(&submit.stdout);
    assert_eq!(
        said.trim_end(),
        format!("submitted: shards 42 (array 1-2), merge 42 -> {}", s(&out))
    );
    // The array task and the merge job, run by bash as on a compute node.
    for (name, task) in [("ci-bias.shards.sbatch", "2"), ("ci-bias.merge.sbatch", "")] {
        let run = Command::new("bash")
            .arg(jobs.join(name))
            .env("SLURM_ARRAY_TASK_ID", task)
            .env("SLURM_CPUS_PER_TASK", "1")
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
    }
    assert_eq!(pwned(&dir), Vec::<PathBuf>::new());
    let args = std::fs::read_to_string(&calls).unwrap();
    let args: Vec<&str> = args.lines().collect();
    let shard = |k: usize| jobs.join(format!("ci-bias.shard-{k}-of-2.csv"));
    let (shard1, shard2) = (shard(1), shard(2));
    let absolute_study = std::path::absolute(&study_path).unwrap();
    let expected = [
        "study",
        s(&absolute_study),
        "--shard",
        "2/2",
        "--threads",
        "1",
        "--quiet",
        "--out",
        s(&shard2),
        "merge",
        s(&shard1),
        s(&shard2),
        "--out",
        s(&out),
    ];
    assert_eq!(args, expected);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn values_that_cannot_be_quoted_are_refused_and_nothing_is_written() {
    let dir = scratch("inject", "values");
    let study_path = ci_study(&dir, "s.toml", "ci-bias", "single.csv", 300);
    let jobs = dir.join("jobs");
    let spaced = dir.join("a b");
    let newline_dir = format!("{}\ntouch PWNED", s(&jobs));
    for (flag, value, says) in [
        (
            "--partition",
            "short\ntouch PWNED",
            "--partition `short\\ntouch PWNED` is invalid",
        ),
        (
            "--time",
            "01:00:00\ntouch PWNED",
            "--time `01:00:00\\ntouch PWNED` is invalid",
        ),
        ("--account", "a b", "--account `a b` is invalid"),
        (
            "--mem",
            "2G\n#SBATCH --array=1",
            "--mem `2G\\n#SBATCH --array=1` is invalid",
        ),
        (
            "--sbatch=",
            "--qos=x\ntouch PWNED",
            "--sbatch `--qos=x\\ntouch PWNED` is invalid",
        ),
        ("--dir", newline_dir.as_str(), "--dir `"),
        ("--dir", s(&spaced), "cannot be quoted"),
    ] {
        let joined = format!("{flag}{value}");
        let mut args = vec!["cluster", "slurm", s(&study_path), "--shards", "2"];
        if flag.ends_with('=') {
            args.push(&joined);
        } else {
            args.extend([flag, value]);
        }
        if flag != "--dir" {
            args.extend(["--dir", s(&jobs)]);
        }
        let err = refused(&args, &[says]);
        assert_eq!(err.lines().count(), 1, "one line: {err}");
        assert_eq!(names(&dir), vec!["s.toml".to_string()], "{flag}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_study_name_must_be_a_plain_file_name() {
    let dir = scratch("inject", "name");
    for name in ["x\ntouch PWNED", "../../escape", "a b", "$(id)"] {
        let study_path = ci_study(&dir, "s.toml", name, "single.csv", 300);
        let args = ["cluster", "slurm", s(&study_path), "--shards", "2"];
        refused(
            &[&args[..], &["--dir", s(&dir.join("jobs"))]].concat(),
            &[
                "s.toml: name = `",
                "is invalid: it must be 1 to 100 letters",
            ],
        );
        assert!(!dir.join("jobs").exists());
        assert!(!dir.parent().unwrap().join("escape.submit.sh").exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_merged_csv_may_not_be_the_study_or_its_model() {
    let dir = scratch("inject", "clobber");
    let study_path = ci_study(&dir, "s.toml", "ci-bias", "single.csv", 300);
    let before = std::fs::read(&study_path).unwrap();
    let model = std::path::absolute("models/paper-case-1.toml").unwrap();
    for out in [study_path.clone(), dir.join("nothere/../s.toml"), model] {
        let o = slurm(&study_path, &dir.join("jobs"), &["--out", s(&out)]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("refused as output: it is the input"), "{err}");
        assert!(!dir.join("jobs").exists());
        assert!(!dir.join("nothere").exists());
    }
    assert_eq!(std::fs::read(&study_path).unwrap(), before);
    std::fs::remove_dir_all(&dir).unwrap();
}
