//! Outputs never overwrite an input, and a failed run leaves nothing behind: paths through
//! missing folders, the files an external model names, planted staging folders, and the
//! folders a failing run created.

use std::path::{Path, PathBuf};

use crate::common::{ci_study, jointid, names, refused, s, scratch};

/// The CI study, 300 trials, its CSV `csv`.
fn study(dir: &Path, csv: &str) -> PathBuf {
    ci_study(dir, "s.toml", "ci-bias", csv, 300)
}

/// Exit 2 with `needle` in the error.
fn refused_with(args: &[&str], needle: &str) {
    refused(args, &[needle]);
}

#[test]
fn a_path_through_a_missing_folder_never_reaches_an_input() {
    let dir = scratch("guarded", "missing");
    let spelled = dir.join("nothere/../s.toml");
    let study_path = study(&dir, "nothere/../s.toml");
    let before = std::fs::read(&study_path).unwrap();
    let says = "refused as output: it is the input";
    refused_with(
        &["study", s(&study_path), "--quiet", "--out", s(&spelled)],
        says,
    );
    refused_with(
        &[
            "study",
            s(&study_path),
            "--quiet",
            "--shard",
            "1/2",
            "--out",
            s(&spelled),
        ],
        says,
    );
    refused_with(&["study", s(&study_path), "--quiet"], says);
    assert_eq!(std::fs::read(&study_path).unwrap(), before);
    assert_eq!(names(&dir), vec!["s.toml"]);
    // merge: its shard is its input.
    let study_path = study(&dir, "single.csv");
    let shard = dir.join("a.csv");
    let shard_run = format!(
        "study {} --quiet --shard 1/1 --out {}",
        s(&study_path),
        s(&shard)
    );
    let o = jointid(&shard_run.split_whitespace().collect::<Vec<_>>());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let shard_bytes = std::fs::read(&shard).unwrap();
    refused_with(
        &[
            "merge",
            s(&shard),
            "--out",
            s(&dir.join("nothere/../a.csv")),
        ],
        says,
    );
    assert_eq!(std::fs::read(&shard).unwrap(), shard_bytes);
    assert!(!dir.join("nothere").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_files_an_external_model_names_are_inputs() {
    let dir = scratch("guarded", "external");
    let fixture = Path::new("tests/fixtures/matrices/two-dof");
    for name in ["free.toml", "K0.mtx", "M.mtx", "dK.mtx", "dofs.csv"] {
        std::fs::copy(fixture.join(name), dir.join(name)).unwrap();
    }
    let model = dir.join("free.toml");
    let before: Vec<Vec<u8>> = ["K0.mtx", "M.mtx", "dK.mtx", "dofs.csv"]
        .iter()
        .map(|n| std::fs::read(dir.join(n)).unwrap())
        .collect();
    let measured = dir.join("m.csv");
    let simulate =
        |out: &Path| format!("simulate --model {} --modes 1 --out {}", s(&model), s(out));
    let o = jointid(&simulate(&measured).split_whitespace().collect::<Vec<_>>());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let says = "refused as output: it is the input";
    for victim in ["K0.mtx", "M.mtx", "dK.mtx", "dofs.csv"] {
        let v = dir.join(victim);
        refused_with(&simulate(&v).split_whitespace().collect::<Vec<_>>(), says);
        refused_with(
            &[
                "identify",
                "--model",
                s(&model),
                "--measured",
                s(&measured),
                "--n",
                "2",
                "--m",
                "1",
                "--weighting",
                "inverse",
                "--out",
                s(&v),
            ],
            says,
        );
        refused_with(
            &[
                "diagnose",
                "--model",
                s(&model),
                "--measured",
                s(&measured),
                "--json",
                s(&v),
            ],
            says,
        );
    }
    let text = "name = \"x\"\nmodel = \"free.toml\"\n[truth]\ndelta = { k = 100.0 }\n[grid]\nmodes = [1]\nn = [2]\nm = [1]\nnf = [0]\nweighting = [\"inverse\"]\nshape_noise = [0.01]\nfrequency_noise = [0.0]\n[monte_carlo]\ntrials = 10\nseed = 1\nnoise = \"uniform\"\n[output]\ncsv = \"dK.mtx\"\n";
    std::fs::write(dir.join("x.toml"), text).unwrap();
    refused_with(&["study", s(&dir.join("x.toml")), "--quiet"], says);
    let after: Vec<Vec<u8>> = ["K0.mtx", "M.mtx", "dK.mtx", "dofs.csv"]
        .iter()
        .map(|n| std::fs::read(dir.join(n)).unwrap())
        .collect();
    assert_eq!(after, before);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `amplitude --out` into the folder of an external model whose matrices bear the names of
/// its outputs: refused, every matrix as it was.
#[test]
fn amplitude_never_overwrites_a_file_its_external_model_names() {
    let dir = scratch("guarded", "amplitude");
    let fixture = Path::new("tests/fixtures/matrices/two-dof");
    let renamed = [
        ("K0.mtx", "amplitude_levels.csv"),
        ("M.mtx", "amplitude_laws.csv"),
        ("dK.mtx", "amplitude_parameters.csv"),
        ("dofs.csv", "amplitude_bands.csv"),
    ];
    let mut model = std::fs::read_to_string(fixture.join("free.toml")).unwrap();
    for (from, to) in renamed {
        std::fs::copy(fixture.join(from), dir.join(to)).unwrap();
        model = model.replace(&format!("\"{from}\""), &format!("\"{to}\""));
    }
    std::fs::write(dir.join("free.toml"), model).unwrap();
    let mut levels = String::from("model = \"free.toml\"\n");
    for (i, f) in [11.25, 11.2].iter().enumerate() {
        let modes = dir.join(format!("modes{i}.csv"));
        std::fs::write(
            &modes,
            format!(
                "mode,frequency_hz,label,value,damping_ratio\n1,{f},m1,1,0.01\n1,{f},m2,-1,0.01\n"
            ),
        )
        .unwrap();
        levels += &format!(
            "[[level]]\nexcitation = {}\nmodes = \"modes{i}.csv\"\nacceleration = [{}]\n",
            i + 1,
            i + 1
        );
    }
    let levels_file = dir.join("levels.toml");
    std::fs::write(&levels_file, levels).unwrap();
    let before: Vec<Vec<u8>> = renamed
        .iter()
        .map(|(_, n)| std::fs::read(dir.join(n)).unwrap())
        .collect();
    let err = refused(
        &["amplitude", s(&levels_file), "--out", s(&dir)],
        &["amplitude_levels.csv: refused as output: it is the input"],
    );
    assert!(err.len() < 300, "{err}");
    let after: Vec<Vec<u8>> = renamed
        .iter()
        .map(|(_, n)| std::fs::read(dir.join(n)).unwrap())
        .collect();
    assert_eq!(after, before);
    assert!(!dir.join("amplitude_mode1.svg").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn export_never_removes_a_folder_it_did_not_create() {
    let dir = scratch("guarded", "export");
    // Folders at every name the staging folder of the next processes could once have had
    // (`.OUT.export-<pid>.tmp`), each holding a file of someone else's.
    let next: u32 = std::fs::read_to_string("/proc/sys/kernel/ns_last_pid")
        .ok()
        .and_then(|t| t.trim().parse().ok())
        .unwrap_or(0);
    for pid in next..next + 200 {
        let planted = dir.join(format!(".out.export-{pid}.tmp"));
        std::fs::create_dir(&planted).unwrap();
        std::fs::write(planted.join("theirs"), "x").unwrap();
    }
    let o = jointid(&[
        "export",
        "models/paper-case-1.toml",
        "--out",
        s(&dir.join("out")),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.join("out/model.toml").exists());
    for pid in next..next + 200 {
        assert!(dir.join(format!(".out.export-{pid}.tmp/theirs")).exists());
    }
    assert_eq!(names(&dir).len(), 201);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_failed_run_removes_the_folders_it_created() {
    let dir = scratch("guarded", "leftovers");
    let study_path = study(&dir, "single.csv");
    // cluster slurm: the logs folder is made before the merged CSV's folder, which cannot be.
    std::fs::write(dir.join("file"), "x").unwrap();
    let (jobs, merged) = (dir.join("jobs"), dir.join("file/merged.csv"));
    let slurm = [
        "cluster",
        "slurm",
        s(&study_path),
        "--shards",
        "2",
        "--dir",
        s(&jobs),
        "--out",
        s(&merged),
    ];
    // study: the trials CSV `out` cannot replace the folder the results go into.
    let (trials, results) = (dir.join("out"), dir.join("out/r.csv"));
    let study = [
        "study",
        s(&study_path),
        "--quiet",
        "--trials-csv",
        s(&trials),
        "--out",
        s(&results),
    ];
    for args in [&slurm[..], &study[..]] {
        refused(args, &[]);
        assert_eq!(names(&dir), vec!["file", "s.toml"], "{args:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
