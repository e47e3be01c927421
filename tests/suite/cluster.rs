//! Sharded studies: the assignment covers every cell once, shard files merge into exactly the
//! bytes of the single-machine CSV, and broken sets of shards (another study, a missing or a
//! duplicated shard) are refused with exit 2 and nothing written.
//!
//! The reference is the single-machine result itself: `jointid study` run whole (or, in the
//! library test, every cell run and written by `study::results::write_results`); the shards
//! are run by separate processes of the binary. Trial counts are cut (the grid is the
//! shipped one) to keep the debug test short: the bits of a cell do not depend on its trial
//! count's size, only on (seed, cell, trial).

use std::path::{Path, PathBuf};

use crate::common::{jointid, scratch};
use jointid::cluster::{
    MergeError, ShardFile, ShardHeader, ShardSpec, merge, read_results, study_assignment,
    write_shard,
};
use jointid::study::fingerprint::{fingerprint, model_data_files};
use jointid::study::results::write_results;
use jointid::study::{Study, StudyRun};

const SHIPPED: [&str; 3] = [
    "studies/paper-case-1.toml",
    "studies/paper-case-2.toml",
    "studies/ci-bias.toml",
];

fn shipped(path: &str, trials: usize) -> Study {
    let mut study = Study::from_path(Path::new(path)).unwrap();
    study.trials = trials;
    study
}

#[test]
fn every_cell_of_the_shipped_studies_is_in_exactly_one_shard_for_n_1_to_17() {
    for path in SHIPPED {
        let study = shipped(path, 1000);
        let cells = study.cells();
        for n in 1..=17 {
            let a = study_assignment(&study, &cells, n);
            assert_eq!(a.len(), cells.len(), "{path}, N = {n}");
            for (c, &k) in a.iter().enumerate() {
                assert!(
                    (1..=n).contains(&k),
                    "{path}, N = {n}: cell {c} in shard {k}"
                );
            }
            // Every shard gets a cell while there are as many cells as shards.
            if n <= cells.len() {
                for k in 1..=n {
                    assert!(a.contains(&k), "{path}, N = {n}: shard {k} is empty");
                }
            }
        }
    }
}

#[test]
fn shard_files_of_the_shipped_studies_merge_into_the_single_run_byte_for_byte() {
    for path in SHIPPED {
        let run = StudyRun::new(shipped(path, 40)).unwrap();
        let names: Vec<String> = run.context.params.iter().map(|p| p.name.clone()).collect();
        let results: Vec<_> = run
            .cells
            .iter()
            .map(|c| run.run_cell(c, &|_| {}).0)
            .collect();
        let mut single = Vec::new();
        write_results(&mut single, &results, &names, run.study.noise_name()).unwrap();
        let print = fingerprint("jointid test", &[b"study", b"model"]);
        for n in [1, 2, 5, 17] {
            let assignment = study_assignment(&run.study, &run.cells, n);
            // Shards given in reverse order: the merge orders the cells.
            let shards: Vec<ShardFile> = (1..=n)
                .rev()
                .map(|k| {
                    let mine: Vec<_> = results
                        .iter()
                        .filter(|r| assignment[r.cell.index] == k)
                        .cloned()
                        .collect();
                    let header = ShardHeader {
                        spec: ShardSpec { index: k, count: n },
                        study: run.study.name.clone(),
                        fingerprint: print.clone(),
                        tool: "jointid test".into(),
                        rows_per_cell: run.study.modes.len() * names.len(),
                        assignment: assignment.clone(),
                        modes: run.study.modes.clone(),
                        params: names.clone(),
                    };
                    let mut bytes = Vec::new();
                    write_shard(&mut bytes, &header, &mine, &names, run.study.noise_name())
                        .unwrap();
                    ShardFile::from_reader(&bytes[..], Path::new("shard.csv")).unwrap()
                })
                .collect();
            let merged = merge(&shards).unwrap();
            assert!(merged == single, "{path}, N = {n}: merged CSV differs");
        }
        // The single CSV reads back as the results it was written from.
        let back = read_results(&single[..], Path::new("single.csv"), &run.study).unwrap();
        assert_eq!(back, results, "{path}");
    }
}

#[test]
fn the_fingerprint_covers_an_external_model_s_matrices_and_a_chain_has_none() {
    let chain = "models/paper-case-1.toml";
    let text = std::fs::read_to_string(chain).unwrap();
    assert!(model_data_files(&text, Path::new(chain)).is_empty());
    let external = Path::new("tests/fixtures/matrices/two-dof/free.toml");
    let text = std::fs::read_to_string(external).unwrap();
    let files = model_data_files(&text, external);
    assert!(files.len() >= 4, "{files:?}");
    for f in &files {
        assert!(f.is_file(), "{} is not a file", f.display());
    }
    let names: Vec<String> = files
        .iter()
        .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert!(names.contains(&"dofs.csv".to_string()), "{names:?}");
    assert!(names.contains(&"dK.mtx".to_string()), "{names:?}");
}

#[test]
fn merge_refuses_no_shard() {
    assert!(matches!(merge(&[]), Err(MergeError::Empty)));
}

/// A copy of ci-bias with few trials in `dir`, its model by absolute path; `extra` is
/// appended (in its last table, `[check]`).
fn small_study(dir: &Path, name: &str, extra: &str) -> PathBuf {
    let model = std::path::absolute("models/paper-case-1.toml").unwrap();
    let text = std::fs::read_to_string("studies/ci-bias.toml")
        .unwrap()
        .replace("trials = 50000", "trials = 300")
        .replace("\"../models/paper-case-1.toml\"", &format!("{model:?}"))
        .replace("\"../results/ci-bias.csv\"", "\"single.csv\"");
    let path = dir.join(name);
    std::fs::write(&path, format!("{text}{extra}")).unwrap();
    path
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn run_ok(args: &[&str]) -> String {
    let out = jointid(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Runs `args`, expects exit 2, no `out` file and every `needles` in stderr.
fn run_err(args: &[&str], out: &Path, needles: &[&str]) {
    let o = jointid(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "`{n}` not in: {err}");
    }
    assert!(!out.exists(), "{} was written", out.display());
}

#[test]
fn shards_run_by_separate_processes_merge_and_check_like_the_single_run() {
    let dir = scratch("cluster", "cli");
    let study = small_study(&dir, "s.toml", "");
    run_ok(&["study", s(&study), "--quiet"]);
    let single = std::fs::read(dir.join("single.csv")).unwrap();
    for k in 1..=3 {
        let text = run_ok(&["study", s(&study), "--shard", &format!("{k}/3"), "--quiet"]);
        assert!(text.contains(&format!("shard {k}/3")), "{text}");
    }
    let shard = |k: usize| dir.join(format!("single.shard-{k}-of-3.csv"));
    let merged = dir.join("merged.csv");
    run_ok(&[
        "merge",
        s(&shard(2)),
        s(&shard(3)),
        s(&shard(1)),
        "--out",
        s(&merged),
    ]);
    assert!(
        std::fs::read(&merged).unwrap() == single,
        "merged CSV differs"
    );
    // check on the merged result says exactly what check on a run says, with the same code.
    let ran = jointid(&[
        "check",
        s(&study),
        "--quiet",
        "--out",
        s(&dir.join("again.csv")),
    ]);
    let read = jointid(&["check", s(&study), "--results", s(&merged)]);
    assert_eq!(read.status.code(), ran.status.code());
    assert_eq!(
        String::from_utf8_lossy(&read.stdout),
        String::from_utf8_lossy(&ran.stdout)
    );
    assert!(String::from_utf8_lossy(&read.stdout).contains("check "));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn broken_shard_sets_exit_2_naming_the_problem_and_write_nothing() {
    let dir = scratch("cluster", "errors");
    let study = small_study(&dir, "s.toml", "");
    // Another study: another seed.
    let other = small_study(&dir, "t.toml", "");
    let text = std::fs::read_to_string(&other).unwrap();
    std::fs::write(&other, text.replace("seed = 1", "seed = 2")).unwrap();
    let shard = |name: &str, k: usize| dir.join(format!("{name}.{k}.csv"));
    for k in 1..=3 {
        let spec = format!("{k}/3");
        let out = shard("s", k);
        run_ok(&[
            "study",
            s(&study),
            "--shard",
            &spec,
            "--quiet",
            "--out",
            s(&out),
        ]);
    }
    let out2 = shard("t", 2);
    run_ok(&[
        "study",
        s(&other),
        "--shard",
        "2/3",
        "--quiet",
        "--out",
        s(&out2),
    ]);
    let merged = dir.join("merged.csv");
    let m = s(&merged);
    // Fingerprint of another study file.
    run_err(
        &[
            "merge",
            s(&shard("s", 1)),
            s(&shard("t", 2)),
            s(&shard("s", 3)),
            "--out",
            m,
        ],
        &merged,
        &["fingerprint", "t.2.csv", "s.1.csv", "different study files"],
    );
    // A missing shard: its cells and the command that makes it.
    let a = study_assignment(
        &Study::from_path(&study).unwrap(),
        &Study::from_path(&study).unwrap().cells(),
        3,
    );
    let first_of_2 = a.iter().position(|&k| k == 2).unwrap();
    run_err(
        &["merge", s(&shard("s", 1)), s(&shard("s", 3)), "--out", m],
        &merged,
        &[
            "missing",
            &format!("shard 2/3: cell(s) {first_of_2}"),
            "--shard 2/3",
        ],
    );
    // A duplicated shard.
    run_err(
        &[
            "merge",
            s(&shard("s", 1)),
            s(&shard("s", 2)),
            s(&shard("s", 2)),
            s(&shard("s", 3)),
            "--out",
            m,
        ],
        &merged,
        &["is in both", "s.2.csv", "shard 2/3 given twice"],
    );
    // Shards of another split.
    let four = dir.join("four.csv");
    run_ok(&[
        "study",
        s(&study),
        "--shard",
        "1/4",
        "--quiet",
        "--out",
        s(&four),
    ]);
    run_err(
        &["merge", s(&shard("s", 1)), s(&four), "--out", m],
        &merged,
        &["four.csv", "same `--shard K/N` split"],
    );
    // Not a shard.
    let single = dir.join("single.csv");
    run_ok(&["study", s(&study), "--quiet"]);
    run_err(
        &["merge", s(&single), "--out", m],
        &merged,
        &["single.csv is not a jointid shard file"],
    );
    // A merged result of one study does not pass for another's.
    let partial = dir.join("partial.csv");
    std::fs::write(
        &partial,
        std::fs::read_to_string(&single)
            .unwrap()
            .lines()
            .take(5)
            .map(|l| format!("{l}\n"))
            .collect::<String>(),
    )
    .unwrap();
    let o = jointid(&["check", s(&study), "--results", s(&partial)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("is not a complete result"));
    // A bad shard spec.
    run_err(
        &["study", s(&study), "--shard", "4/3", "--out", m],
        &merged,
        &["--shard 4/3 is invalid"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn slurm_scripts_are_written_for_every_shard() {
    let dir = scratch("cluster", "slurm");
    let study = small_study(&dir, "s.toml", "");
    let text = run_ok(&[
        "cluster",
        "slurm",
        s(&study),
        "--shards",
        "3",
        "--partition",
        "p",
        "--time",
        "00:05:00",
        "--dir",
        s(&dir.join("jobs")),
    ]);
    assert!(text.contains("ci-bias.submit.sh"), "{text}");
    let array = std::fs::read_to_string(dir.join("jobs/ci-bias.shards.sbatch")).unwrap();
    assert!(array.contains("#SBATCH --array=1-3"));
    assert!(array.contains("#SBATCH --partition=p"));
    let merge = std::fs::read_to_string(dir.join("jobs/ci-bias.merge.sbatch")).unwrap();
    assert!(merge.contains("ci-bias.shard-3-of-3.csv"));
    assert!(dir.join("jobs/ci-bias.submit.sh").exists());
    assert!(dir.join("jobs/logs").is_dir());
    let too_many = jointid(&["cluster", "slurm", s(&study), "--shards", "9"]);
    assert_eq!(too_many.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&too_many.stderr).contains("N must be from 1 to 8"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `merge` and `cluster slurm` with their stdout on /dev/full: the merged CSV (of one shard of
/// a 20-trial study) and the scripts are written, then the summary cannot be. The device makes
/// every write fail whatever the code under test does; each run must end as on any error
/// (exit 2, the cause said), not with a panic.
#[test]
fn merge_and_slurm_with_a_stdout_that_cannot_take_the_summary_exit_2() {
    let dir = scratch("cluster", "stdout");
    let study = small_study(&dir, "s.toml", "");
    let text = std::fs::read_to_string(&study).unwrap();
    std::fs::write(&study, text.replace("trials = 300", "trials = 20")).unwrap();
    let shard = dir.join("shard.csv");
    run_ok(&[
        "study",
        s(&study),
        "--shard",
        "1/1",
        "--quiet",
        "--out",
        s(&shard),
    ]);
    let merged = dir.join("merged.csv");
    crate::common::stdout_refused(&["merge", s(&shard), "--out", s(&merged)]);
    crate::common::stdout_refused(&[
        "cluster",
        "slurm",
        s(&study),
        "--shards",
        "2",
        "--dir",
        s(&dir.join("jobs")),
    ]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Shards run before and after the study file was edited where no row changes (a comment, the
/// output path, the check) carry the same fingerprint and merge into the single run's bytes.
#[test]
fn an_edit_that_changes_no_row_between_shards_keeps_them_mergeable() {
    let dir = scratch("cluster", "edited");
    let study = small_study(&dir, "s.toml", "");
    let first = dir.join("s.1.csv");
    run_ok(&[
        "study",
        s(&study),
        "--shard",
        "1/2",
        "--quiet",
        "--out",
        s(&first),
    ]);
    let text = std::fs::read_to_string(&study).unwrap();
    let edited = format!("# edited between the shards\n{text}")
        .replace("\"single.csv\"", "\"elsewhere.csv\"")
        .replace(
            "max_abs_relative_bias = 0.05",
            "max_abs_relative_bias = 0.04",
        );
    std::fs::write(&study, edited).unwrap();
    let second = dir.join("s.2.csv");
    run_ok(&[
        "study",
        s(&study),
        "--shard",
        "2/2",
        "--quiet",
        "--out",
        s(&second),
    ]);
    let merged = dir.join("merged.csv");
    run_ok(&["merge", s(&first), s(&second), "--out", s(&merged)]);
    run_ok(&["study", s(&study), "--quiet"]);
    assert_eq!(
        std::fs::read(&merged).unwrap(),
        std::fs::read(dir.join("elsewhere.csv")).unwrap()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
