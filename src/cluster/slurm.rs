//! Slurm batch scripts for a sharded study: a job array with one task per shard, a merge job
//! that runs after every task has succeeded (`--dependency=afterok:<array>`), and a small
//! submit script that chains them.
//!
//! Task K of the array runs `jointid study S.toml --shard K/N --out DIR/NAME.shard-K-of-N.csv`
//! with `--threads $SLURM_CPUS_PER_TASK`; the merge job runs `jointid merge` over the N
//! shard files and writes the study's CSV. Every path in the scripts is absolute: the nodes
//! must see the binary, the study, its model and DIR under the same paths (a shared file
//! system, as on every Slurm cluster).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::shell::{SlurmValue, check_option, check_quoted_path, sh_quote};
use crate::input::SettingError;
use crate::study::Study;

/// What the scripts run and where.
#[derive(Debug, Clone, PartialEq)]
pub struct SlurmPlan {
    /// Study name (job names and file names).
    pub name: String,
    /// The jointid binary, absolute.
    pub jointid: PathBuf,
    /// The study file, absolute.
    pub study: PathBuf,
    /// Directory of the scripts, the shard files and the logs, absolute.
    pub dir: PathBuf,
    /// The merged result CSV, absolute.
    pub out: PathBuf,
    /// N.
    pub shards: usize,
    /// `--partition`.
    pub partition: Option<String>,
    /// `--time` of every task and of the merge.
    pub time: Option<String>,
    /// `--account`.
    pub account: Option<String>,
    /// `--mem` of every task.
    pub mem: Option<String>,
    /// `--cpus-per-task` of every shard task (the worker threads).
    pub cpus_per_task: usize,
    /// Further `#SBATCH` options, one token each, e.g. `--qos=short`.
    pub extra: Vec<String>,
}

/// Checks the settings of a plan for `study`: `shards` (N) from 1 to its number of cells,
/// `cpus_per_task` at least 1.
pub fn check_settings(
    study: &Study,
    shards: usize,
    cpus_per_task: usize,
) -> Result<(), SettingError> {
    let cells = study.cells().len();
    if shards == 0 || shards > cells {
        return Err(SettingError::new(
            "shards",
            shards,
            format!(
                "{} has {cells} cell(s), so N must be from 1 to {cells}",
                study.file.display()
            ),
        ));
    }
    if cpus_per_task == 0 {
        return Err(SettingError::new(
            "cpus_per_task",
            0,
            "it must be at least 1",
        ));
    }
    Ok(())
}

/// The three scripts.
#[derive(Debug, Clone, PartialEq)]
pub struct SlurmScripts {
    /// The job array (`NAME.shards.sbatch`).
    pub array: String,
    /// The merge job (`NAME.merge.sbatch`).
    pub merge: String,
    /// `NAME.submit.sh`: submits the array, then the merge depending on it.
    pub submit: String,
}

fn q(path: &Path) -> String {
    sh_quote(&path.display().to_string())
}

impl SlurmPlan {
    /// The shard file of shard K (1-based).
    pub fn shard_file(&self, k: usize) -> PathBuf {
        self.dir
            .join(format!("{}.shard-{k}-of-{}.csv", self.name, self.shards))
    }

    /// The array script's path.
    pub fn array_path(&self) -> PathBuf {
        self.dir.join(format!("{}.shards.sbatch", self.name))
    }

    /// The merge script's path.
    pub fn merge_path(&self) -> PathBuf {
        self.dir.join(format!("{}.merge.sbatch", self.name))
    }

    /// The submit script's path.
    pub fn submit_path(&self) -> PathBuf {
        self.dir.join(format!("{}.submit.sh", self.name))
    }

    /// The directory of the logs.
    pub fn log_dir(&self) -> PathBuf {
        self.dir.join("logs")
    }

    fn common(&self, s: &mut String, job: &str, log: &str) {
        let _ = writeln!(s, "#!/bin/bash");
        let _ = writeln!(s, "#SBATCH --job-name={}-{job}", self.name);
        let log = self.log_dir().join(log);
        let _ = writeln!(s, "#SBATCH --output={}", log.display());
        for (key, value) in [
            ("partition", &self.partition),
            ("time", &self.time),
            ("account", &self.account),
        ] {
            if let Some(v) = value {
                let _ = writeln!(s, "#SBATCH --{key}={v}");
            }
        }
        for e in &self.extra {
            let _ = writeln!(s, "#SBATCH {e}");
        }
    }

    /// Checks every value the scripts hold (see [`super::shell`]): the study name a file
    /// name, partition, account, time and memory in their Slurm sets, each extra option one
    /// token, the folder fit for `#SBATCH --output=`, the quoted paths free of control
    /// characters.
    pub fn check(&self) -> Result<(), SettingError> {
        crate::input::safe::check(&crate::input::safe::FILE_NAME, "name", &self.name)?;
        for (setting, value, kind) in [
            ("partition", &self.partition, SlurmValue::Name),
            ("account", &self.account, SlurmValue::Name),
            ("time", &self.time, SlurmValue::Time),
            ("mem", &self.mem, SlurmValue::Memory),
        ] {
            if let Some(v) = value {
                kind.check(setting, v)?;
            }
        }
        for option in &self.extra {
            check_option("sbatch", option)?;
        }
        for (setting, path) in [
            ("jointid", &self.jointid),
            ("study", &self.study),
            ("out", &self.out),
            ("dir", &self.dir),
        ] {
            check_quoted_path(setting, path)?;
        }
        SlurmValue::Folder.check("dir", &self.dir.to_string_lossy())
    }

    /// The scripts, once every value has passed [`SlurmPlan::check`].
    pub fn scripts(&self) -> Result<SlurmScripts, SettingError> {
        self.check()?;
        let n = self.shards;
        let mut array = String::new();
        self.common(&mut array, "shards", &format!("{}-shard-%a.out", self.name));
        let _ = writeln!(array, "#SBATCH --array=1-{n}");
        let _ = writeln!(array, "#SBATCH --ntasks=1");
        let _ = writeln!(array, "#SBATCH --cpus-per-task={}", self.cpus_per_task);
        if let Some(mem) = &self.mem {
            let _ = writeln!(array, "#SBATCH --mem={mem}");
        }
        let _ = write!(
            array,
            "# Shard K of {n} of study {name}: its cells, chosen by `jointid study --shard`.\n\
             set -euo pipefail\n\
             K=\"$SLURM_ARRAY_TASK_ID\"\n\
             OUT={head}\"$K\"{tail}\n\
             exec {jointid} study {study} --shard \"$K/{n}\" --threads \"${{SLURM_CPUS_PER_TASK:-1}}\" --quiet --out \"$OUT\"\n",
            name = self.name,
            head = q(&self.dir.join(format!("{}.shard-", self.name))),
            tail = sh_quote(&format!("-of-{n}.csv")),
            jointid = q(&self.jointid),
            study = q(&self.study),
        );
        let mut merge = String::new();
        self.common(&mut merge, "merge", &format!("{}-merge.out", self.name));
        let _ = writeln!(merge, "#SBATCH --ntasks=1");
        let _ = writeln!(merge, "#SBATCH --cpus-per-task=1");
        let _ = writeln!(
            merge,
            "# Merges the {n} shards of study {} into its result CSV (after the array has succeeded).",
            self.name
        );
        let _ = writeln!(merge, "set -euo pipefail");
        let _ = write!(merge, "exec {} merge", q(&self.jointid));
        for k in 1..=n {
            let _ = write!(merge, " \\\n  {}", q(&self.shard_file(k)));
        }
        let _ = writeln!(merge, " \\\n  --out {}", q(&self.out));
        let submit = format!(
            "#!/bin/sh\n\
             # Submits the {n} shards of study {name}, then their merge once all have succeeded.\n\
             set -eu\n\
             array=$(sbatch --parsable {array_script})\n\
             array=${{array%%;*}}\n\
             merge=$(sbatch --parsable --dependency=afterok:\"$array\" {merge_script})\n\
             merge=${{merge%%;*}}\n\
             echo \"submitted: shards $array (array 1-{n}), merge $merge -> \"{out}\n",
            name = self.name,
            array_script = q(&self.array_path()),
            merge_script = q(&self.merge_path()),
            out = q(&self.out),
        );
        Ok(SlurmScripts {
            array,
            merge,
            submit,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_and_cpus_are_checked_against_the_study() {
        let study = Study::from_path(Path::new("studies/ci-bias.toml")).unwrap();
        assert!(check_settings(&study, 8, 1).is_ok());
        assert_eq!(
            check_settings(&study, 9, 1).unwrap_err().to_string(),
            "shards = 9 is invalid: studies/ci-bias.toml has 8 cell(s), so N must be from 1 to 8"
        );
        assert_eq!(check_settings(&study, 0, 1).unwrap_err().setting, "shards");
        assert_eq!(
            check_settings(&study, 2, 0).unwrap_err().to_string(),
            "cpus_per_task = 0 is invalid: it must be at least 1"
        );
    }

    fn plan() -> SlurmPlan {
        SlurmPlan {
            name: "case".into(),
            jointid: "/opt/jointid".into(),
            study: "/home/u/s it.toml".into(),
            dir: "/scratch/run".into(),
            out: "/scratch/case.csv".into(),
            shards: 3,
            partition: Some("short".into()),
            time: Some("01:00:00".into()),
            account: None,
            mem: Some("2G".into()),
            cpus_per_task: 4,
            extra: vec!["--qos=low".into()],
        }
    }

    #[test]
    fn the_array_runs_each_shard_and_the_merge_reads_every_shard_file() {
        let s = plan().scripts().unwrap();
        for line in [
            "#SBATCH --array=1-3",
            "#SBATCH --partition=short",
            "#SBATCH --time=01:00:00",
            "#SBATCH --cpus-per-task=4",
            "#SBATCH --mem=2G",
            "#SBATCH --qos=low",
            "#SBATCH --output=/scratch/run/logs/case-shard-%a.out",
        ] {
            assert!(s.array.lines().any(|l| l == line), "{line} in\n{}", s.array);
        }
        assert!(!s.array.contains("--account"));
        assert!(s.array.contains(
            "OUT='/scratch/run/case.shard-'\"$K\"'-of-3.csv'\nexec '/opt/jointid' study '/home/u/s it.toml' --shard \"$K/3\" --threads \"${SLURM_CPUS_PER_TASK:-1}\" --quiet --out \"$OUT\""
        ));
        for k in 1..=3 {
            assert!(
                s.merge
                    .contains(&format!("'/scratch/run/case.shard-{k}-of-3.csv'"))
            );
        }
        assert!(s.merge.contains("--out '/scratch/case.csv'"));
        assert!(
            s.submit
                .contains("--dependency=afterok:\"$array\" '/scratch/run/case.merge.sbatch'")
        );
    }

    #[test]
    fn a_hostile_value_renders_no_script() {
        type Spoil = fn(&mut SlurmPlan);
        let cases: [(&str, Spoil); 7] = [
            ("partition", |p| {
                p.partition = Some("short\necho pwned".into())
            }),
            ("time", |p| p.time = Some("1:00\nrm -rf ~".into())),
            ("account", |p| p.account = Some("a$(id)".into())),
            ("mem", |p| p.mem = Some("2G\n#SBATCH --array=1".into())),
            ("sbatch", |p| p.extra = vec!["--qos=low\ntouch x".into()]),
            ("dir", |p| p.dir = "/scratch/run\ntouch x".into()),
            ("name", |p| p.name = "../../x".into()),
        ];
        for (setting, spoil) in cases {
            let mut p = plan();
            spoil(&mut p);
            let e = p.scripts().unwrap_err();
            assert_eq!(e.setting, setting, "{e}");
        }
    }

    #[test]
    fn the_submit_script_quotes_the_output() {
        let mut p = plan();
        p.out = "/scratch/$(touch x)`id`\"a.csv".into();
        let s = p.scripts().unwrap();
        assert!(
            s.submit
                .ends_with("-> \"'/scratch/$(touch x)`id`\"a.csv'\n"),
            "{}",
            s.submit
        );
    }
}
