//! `jointid export` and external models end to end: the paper's model exported and read back
//! gives the same `identify` CSV, byte for byte; the other commands run on it; every bad input
//! exits 2 with a message naming the file and the line or field, and writes nothing.
//!
//! Independence of the test data: the measured modes are simulated from the beam-chain builder's
//! model (exact eigenvectors of the truth model, no noise), not from the exported matrices; the
//! bad external models are the hand-written 2-DOF fixtures of tests/fixtures/matrices/ with one
//! edit each.

use std::path::{Path, PathBuf};

use crate::common::{jointid, paper_model, scratch, translations};
use jointid::modal::ModalSolution;
use jointid::simulate::exact_modes;

const PAPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/models/paper-case-1.toml");
const FIXTURES: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/matrices/two-dof"
);

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Measured modes 1-4 (translations) of the paper's chain with k1, k2 raised 20%, by DOF label.
fn measured_by_label(dir: &Path) -> PathBuf {
    let truth = paper_model(1.2e7, 1.2e4);
    let points = translations(&truth);
    let modes = exact_modes(
        &ModalSolution::solve(&truth.assemble()).unwrap(),
        2,
        &[1, 2, 3, 4],
        &points,
    );
    // Written against a structure without nodes or lines: the file names points by label.
    let external = jointid::model::from_path(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/models/paper-matrices/model.toml"
    )))
    .unwrap();
    let mut bytes = Vec::new();
    modes.write_csv(&mut bytes, &external).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    assert!(
        text.starts_with("mode,frequency_hz,label,value\n1,"),
        "{text}"
    );
    let path = dir.join("measured.csv");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn exported_paper_model_gives_the_same_identify_csv() {
    let dir = scratch("cli-matrices", "identify");
    let out = dir.join("exported");
    let o = jointid(&["export", PAPER, "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let measured = measured_by_label(&dir);
    let run = |model: &Path, csv: &Path| {
        let o = jointid(&[
            "identify",
            "--model",
            s(model),
            "--measured",
            s(&measured),
            "--n",
            "19",
            "--m",
            "5",
            "--weighting",
            "inverse",
            "--out",
            s(csv),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(csv).unwrap()
    };
    let chain = run(Path::new(PAPER), &dir.join("chain.csv"));
    let external = run(&out.join("model.toml"), &dir.join("external.csv"));
    assert_eq!(chain.len(), external.len());
    assert!(chain == external, "the two identify CSVs differ");
    // Noise-free data: mode 1 recovers about +2e6 N/m (the sub-basis truncation aside).
    let text = String::from_utf8(chain).unwrap();
    assert_eq!(text.lines().count(), 1 + 4 * 2);
    // And the shipped example is this export, file for file.
    for name in [
        "model.toml",
        "K.mtx",
        "M.mtx",
        "dK_k1.mtx",
        "dK_k2.mtx",
        "dofs.csv",
    ] {
        let shipped = std::fs::read(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("models/paper-matrices")
                .join(name),
        )
        .unwrap();
        let fresh = std::fs::read(out.join(name)).unwrap();
        let fresh = String::from_utf8(fresh)
            .unwrap()
            .replace(PAPER, "models/paper-case-1.toml");
        assert_eq!(String::from_utf8(shipped).unwrap(), fresh, "{name}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn simulate_and_diagnose_run_on_an_external_model() {
    let dir = scratch("cli-matrices", "simulate");
    let model = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/models/paper-matrices/model.toml"
    );
    let measured = dir.join("test.csv");
    let o = jointid(&[
        "simulate",
        "--model",
        model,
        "--modes",
        "4",
        "--measure",
        "w",
        "--seed",
        "1",
        "--shape-noise",
        "0",
        "--frequency-noise",
        "0",
        "--out",
        s(&measured),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&measured).unwrap();
    assert!(
        text.starts_with("mode,frequency_hz,label,value\n"),
        "{text}"
    );
    let o = jointid(&["diagnose", "--model", model, "--measured", s(&measured)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report = String::from_utf8_lossy(&o.stdout);
    assert!(report.starts_with("verdict: none"), "{report}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn export_never_overwrites_and_leaves_nothing_on_error() {
    let dir = scratch("cli-matrices", "export");
    // A folder with a file in it: refused, untouched.
    let busy = dir.join("busy");
    std::fs::create_dir(&busy).unwrap();
    std::fs::write(busy.join("K.mtx"), "mine").unwrap();
    let o = jointid(&["export", PAPER, "--out", s(&busy)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("exists and is not an empty folder"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(busy.join("K.mtx")).unwrap(), "mine");
    // Exporting a model into its own folder is the same case.
    let own = dir.join("own");
    let o = jointid(&["export", PAPER, "--out", s(&own)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = jointid(&["export", s(&own.join("model.toml")), "--out", s(&own)]);
    assert_eq!(o.status.code(), Some(2));
    // A bad model: exit 2, no folder, no temporary left.
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[[beam]]\nlength = -1.0\n").unwrap();
    let target = dir.join("new");
    let o = jointid(&["export", s(&bad), "--out", s(&target)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("bad.toml"), "{}", stderr(&o));
    let left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let mut left = left;
    left.sort();
    assert_eq!(left, ["bad.toml", "busy", "own"]);
    // An empty folder is filled.
    let empty = dir.join("empty");
    std::fs::create_dir(&empty).unwrap();
    let o = jointid(&["export", PAPER, "--out", s(&empty)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(empty.join("model.toml").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The bad inputs of issue 12 through `identify`: exit 2, the message, no output file.
/// `identify` on `case`'s model.toml and d.csv exits 2 with `message` and writes no out.csv.
fn identify_is_refused(case: &Path, name: &str, message: &str) {
    let out = case.join("out.csv");
    let o = jointid(&[
        "identify",
        "--model",
        s(&case.join("model.toml")),
        "--measured",
        s(&case.join("d.csv")),
        "--n",
        "2",
        "--m",
        "1",
        "--weighting",
        "equal",
        "--out",
        s(&out),
    ]);
    assert_eq!(o.status.code(), Some(2), "{name}");
    assert!(stderr(&o).contains(message), "{name}: {}", stderr(&o));
    assert!(!out.exists(), "{name}");
}

#[test]
fn bad_external_inputs_exit_2_and_write_nothing() {
    let dir = scratch("cli-matrices", "bad");
    let model_text = std::fs::read_to_string(Path::new(FIXTURES).join("grounded.toml")).unwrap();
    let cases: [(&str, &str, &str, &str); 5] = [
        (
            "size",
            "dK.mtx",
            "%%MatrixMarket matrix coordinate real symmetric\n3 3 1\n3 3 1\n",
            "model.toml: parameter[0].dk: the matrix is 3 x 3, but K (stiffness) is 2 x 2",
        ),
        (
            "symmetry",
            "K.mtx",
            "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 5000\n2 1 7\n",
            "K.mtx:4: the matrix is not symmetric: a(2,1) = 7e0 but a(1,2) = 0e0",
        ),
        (
            "indefinite",
            "M.mtx",
            "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 1\n2 1 3\n2 2 1\n",
            "model.toml: mass: M (with the parameters' p dM/dp) is not positive definite",
        ),
        (
            "no-dk",
            "model.toml",
            "kind = \"matrices\"\nstiffness = \"K.mtx\"\nmass = \"M.mtx\"\ndofs = \"dofs.csv\"\n[[parameter]]\nname = \"k\"\nvalue = 5000.0\n",
            "model.toml: parameter[0].dk = (missing) is invalid: every parameter needs dk",
        ),
        (
            "header",
            "M.mtx",
            "%%MatrixMarket matrix coordinate complex symmetric\n2 2 1\n1 1 1 0\n",
            "M.mtx:1: header `%%MatrixMarket matrix coordinate complex symmetric` is invalid",
        ),
    ];
    let good_measured = "mode,frequency_hz,label,value\n1,12.0,m1,1.0\n1,12.0,m2,0.6\n";
    for (name, file, text, message) in cases {
        let case = dir.join(name);
        std::fs::create_dir(&case).unwrap();
        for entry in std::fs::read_dir(FIXTURES).unwrap() {
            let p = entry.unwrap().path();
            std::fs::copy(&p, case.join(p.file_name().unwrap())).unwrap();
        }
        std::fs::write(case.join("model.toml"), &model_text).unwrap();
        std::fs::write(case.join(file), text).unwrap();
        std::fs::write(case.join("d.csv"), good_measured).unwrap();
        identify_is_refused(&case, name, message);
    }
    // A DOF label the table does not have, in the measured file.
    let case = dir.join("symmetry");
    std::fs::copy(Path::new(FIXTURES).join("K.mtx"), case.join("K.mtx")).unwrap();
    std::fs::write(
        case.join("d.csv"),
        "mode,frequency_hz,label,value\n1,12.0,m1,1.0\n1,12.0,m3,0.6\n",
    )
    .unwrap();
    identify_is_refused(
        &case,
        "label",
        "d.csv:3: label = `m3` is invalid: it is neither a DOF of the model nor a declared sensor",
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The CI study (NF 0 and 5 by the count rule, two weightings) on the chain and on its export:
/// the same result CSV, byte for byte.
#[test]
fn study_of_the_exported_model_gives_the_same_csv() {
    let dir = scratch("cli-matrices", "study");
    let study =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/studies/ci-bias.toml"))
            .unwrap()
            .replace("trials = 50000", "trials = 300");
    let run = |model: &str, name: &str| {
        let file = dir.join(format!("{name}.toml"));
        std::fs::write(
            &file,
            study.replace(
                "model = \"../models/paper-case-1.toml\"",
                &format!("model = \"{}/models/{model}\"", env!("CARGO_MANIFEST_DIR")),
            ),
        )
        .unwrap();
        let csv = dir.join(format!("{name}.csv"));
        let o = jointid(&["study", s(&file), "--quiet", "--out", s(&csv)]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(csv).unwrap()
    };
    let chain = run("paper-case-1.toml", "chain");
    let external = run("paper-matrices/model.toml", "external");
    assert!(chain.len() > 1000);
    assert!(chain == external, "the two study CSVs differ");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `export` with its stdout on /dev/full: the folder is written, then the summary cannot be.
/// The device makes every write fail whatever the code under test does; the run must end as
/// on any error (exit 2, the cause said), not with a panic.
#[test]
fn export_with_a_stdout_that_cannot_take_the_summary_is_an_error_not_a_panic() {
    let dir = scratch("cli-matrices", "stdout");
    crate::common::stdout_refused(&["export", PAPER, "--out", s(&dir.join("model"))]);
    std::fs::remove_dir_all(&dir).unwrap();
}
