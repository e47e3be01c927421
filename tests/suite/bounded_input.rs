//! Readers within limits: a huge line is refused naming its line, a file read whole is refused
//! past its size before it is read, an error quotes at most about 80 characters of a value,
//! and `--shard K/N` cannot ask for more shards than cells.

use std::path::Path;

use crate::common::{jointid, s, scratch};

/// Exit 2, `needle` in a short one-line error, no panic.
fn refused_briefly(args: &[&str], needle: &str) {
    let o = jointid(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{}", &err[..err.len().min(300)]);
    assert!(
        err.len() < 600,
        "{} bytes of error: {}",
        err.len(),
        &err[..300]
    );
    assert!(err.contains(needle), "`{needle}` not in {err}");
    assert!(!err.contains("panicked"));
}

#[test]
fn a_shard_count_beyond_the_cells_is_refused_without_allocating() {
    for spec in ["1/18446744073709551615", "1/1000000000", "3/9"] {
        refused_briefly(
            &[
                "study",
                "studies/ci-bias.toml",
                "--quiet",
                "--shard",
                spec,
                "--out",
                "/nonexistent/x.csv",
            ],
            &format!(
                "--shard {spec} is invalid: studies/ci-bias.toml has 8 cell(s), so N must be from 1 to 8"
            ),
        );
    }
}

#[test]
fn a_huge_line_is_refused_naming_it_and_a_long_value_is_quoted_short() {
    let dir = scratch("bounded", "lines");
    let long = "9".repeat(2 << 20);
    let half = "9".repeat(1 << 19);
    // The results reader (check --results): a 2 MiB line.
    let results = dir.join("r.csv");
    let header = "cell,mode,param,n,m,nf,weighting,shape_noise,frequency_noise,noise,introduced,trials,failures,mean,bias,relative_bias,std,rmse,median,mad,q05,q25,q75,q95,bias_se,predicted_std,median_se,unidentified";
    std::fs::write(&results, format!("{header}\n{long}\n")).unwrap();
    refused_briefly(
        &["check", "studies/ci-bias.toml", "--results", s(&results)],
        "line 2 is longer than 1048576 bytes",
    );
    // A half-MiB cell index: quoted short.
    std::fs::write(
        &results,
        format!("{header}\n{half},1,k1{}\n", ",0".repeat(25)),
    )
    .unwrap();
    refused_briefly(
        &["check", "studies/ci-bias.toml", "--results", s(&results)],
        "... (524288 bytes)`",
    );
    // The measured-modes reader.
    let measured = dir.join("m.csv");
    let identify = format!(
        "identify --model models/paper-case-1.toml --measured {} --n 10 --m 5 --weighting inverse",
        s(&measured)
    );
    let identify: Vec<&str> = identify.split_whitespace().collect();
    for (frequency, says) in [
        (&long, "line 2 is longer than 1048576 bytes"),
        (&half, "... (524288 bytes)`"),
    ] {
        let text = format!("mode,frequency_hz,node,dof,value\n1,{frequency},0,w,1\n");
        std::fs::write(&measured, text).unwrap();
        refused_briefly(&identify, says);
    }
    // The Matrix Market and DOF-table readers of an external model.
    let fixture = Path::new("tests/fixtures/matrices/two-dof");
    for name in ["free.toml", "K0.mtx", "M.mtx", "dK.mtx", "dofs.csv"] {
        std::fs::copy(fixture.join(name), dir.join(name)).unwrap();
    }
    let model = dir.join("free.toml");
    let out = dir.join("o.csv");
    let args = format!("simulate --model {} --modes 1 --out {}", s(&model), s(&out));
    let args: Vec<&str> = args.split_whitespace().collect();
    let k0 = std::fs::read_to_string(dir.join("K0.mtx")).unwrap();
    let mut lines: Vec<&str> = k0.lines().collect();
    let size_at = lines.iter().position(|l| !l.starts_with('%')).unwrap();
    let quarter = "9".repeat(1 << 18);
    let huge_size = format!("{quarter} {quarter} 3");
    lines[size_at] = &huge_size;
    std::fs::write(dir.join("K0.mtx"), lines.join("\n")).unwrap();
    refused_briefly(&args, "... (524291 bytes)`");
    std::fs::write(
        dir.join("K0.mtx"),
        format!("{}\n% {long}\n", k0.lines().next().unwrap()),
    )
    .unwrap();
    refused_briefly(&args, "line 2 is longer than 1048576 bytes");
    std::fs::write(dir.join("K0.mtx"), &k0).unwrap();
    let dofs = std::fs::read_to_string(dir.join("dofs.csv")).unwrap();
    std::fs::write(dir.join("dofs.csv"), format!("{dofs}{long}\n")).unwrap();
    refused_briefly(&args, "is longer than 1048576 bytes");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every file read whole (TOML model, study, levels and specimen files, universal files, a
/// study's CSV for `report`), fed a sparse file past its limit or a device that never ends:
/// exit 2 at once, naming the file and the limit, and nothing written.
#[test]
fn a_whole_file_past_its_limit_is_refused_without_reading_it() {
    let dir = scratch("bounded", "whole");
    let sparse = |name: &str, size: u64| {
        let path = dir.join(name);
        std::fs::File::create(&path).unwrap().set_len(size).unwrap();
        path
    };
    let toml = sparse("big.toml", (16 << 20) + 1);
    let uff = sparse("big.uff", (1 << 30) + 1);
    let csv = sparse("big.csv", (4 << 30) + 1);
    let out = dir.join("out");
    let o_csv = dir.join("out.csv");
    let (toml, uff, csv, out, o_csv) = (s(&toml), s(&uff), s(&csv), s(&out), s(&o_csv));
    let toml_says = format!(
        "{toml}: cannot read the file: the file is larger than 16777216 bytes (16 MiB), the most a TOML input file may have"
    );
    let identify = [
        "identify",
        "--model",
        toml,
        "--measured",
        "m.csv",
        "--n",
        "10",
        "--m",
        "5",
        "--weighting",
        "inverse",
        "--out",
        o_csv,
    ];
    // The output guard reads the model for the files it names, before the model's reader.
    let identify_zero = [
        "identify",
        "--model",
        "/dev/zero",
        "--measured",
        "m.csv",
        "--n",
        "10",
        "--m",
        "5",
        "--weighting",
        "inverse",
        "--out",
        o_csv,
    ];
    let cases: [(&[&str], String); 9] = [
        (&["amplitude", toml, "--out", out], toml_says.clone()),
        (&identify, toml_says.clone()),
        (&["study", toml, "--quiet", "--out", o_csv], toml_says.clone()),
        (&["solid", toml, "--out", out], toml_says.clone()),
        (
            &["extract", "--frf", uff, "--geometry", uff, "--out", o_csv],
            format!(
                "{uff}: cannot read the file: the file is larger than 1073741824 bytes (1024 MiB), the most a universal file may have"
            ),
        ),
        (
            &["report", csv, "--out", out],
            format!(
                "{csv}: cannot read: the file is larger than 4294967296 bytes (4096 MiB), the most a text table may have"
            ),
        ),
        (
            &["amplitude", "/dev/zero", "--out", out],
            "/dev/zero: cannot read the file: line 1 is longer than 1048576 bytes, the most a line of a TOML input file may have".into(),
        ),
        (
            &identify_zero,
            "/dev/zero: cannot read the file: line 1 is longer than 1048576 bytes, the most a line of a TOML input file may have".into(),
        ),
        (
            &["report", "/dev/zero", "--out", out],
            "/dev/zero: cannot read: line 1 is longer than 1048576 bytes, the most a line of a text table may have".into(),
        ),
    ];
    for (args, says) in cases {
        if args.contains(&"/dev/zero") && !Path::new("/dev/zero").exists() {
            continue;
        }
        let start = std::time::Instant::now();
        refused_briefly(args, &says);
        assert!(
            start.elapsed().as_secs_f64() < 5.0,
            "{args:?}: {:?}",
            start.elapsed()
        );
        assert!(
            !Path::new(out).exists() && !Path::new(o_csv).exists(),
            "{args:?}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
