//! `jointid extract` end to end: universal files written by `jointid::uff`'s writer from FRFs
//! of a lumped system solved directly per line (tests/common/frf.rs, independent of the
//! extractor), extracted to a measured-modes CSV that reads back against the UNESP-BERT model;
//! then every bad input of the issue (truncated record, no peak in the band, a response node
//! missing from the geometry, mixed units) with its message, exit code 2 and no output file.

use crate::common::frf;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use faer::c64;
use frf::{frf_set, lines, prescribed, receptance};
use jointid::extract::Quantity;
use jointid::measured::MeasuredModes;
use jointid::uff::{
    Abscissa, Axis, Dof, Encoding, Function, FunctionType, Node, NodeFormat, Nodes, Precision,
    Values, write_function, write_nodes,
};

struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("jointid-extract-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

const TRUE_HZ: [f64; 3] = [30.0, 90.0, 200.0];
const POSITIONS: [f64; 3] = [0.5, 0.357, 0.176];

fn axis(data_type: i32, label: &str, units: &str) -> Axis {
    Axis {
        data_type,
        length_exponent: 0,
        force_exponent: 0,
        temperature_exponent: 0,
        label: label.into(),
        units: units.into(),
    }
}

/// The accelerance FRF of response node `node` (direction 2) to node 100, as dataset 58.
fn function(node: u64, step: f64, values: Vec<c64>, units: &str) -> Function {
    Function {
        id_lines: [
            format!("H node {node}"),
            "synthetic".into(),
            "NONE".into(),
            "NONE".into(),
            "NONE".into(),
        ],
        function_type: FunctionType::Frf,
        function_id: node as i64,
        version: 1,
        load_case: 0,
        response: Dof {
            entity: "NONE".into(),
            node,
            direction: 2,
        },
        reference: Dof {
            entity: "NONE".into(),
            node: 100,
            direction: 2,
        },
        precision: Precision::Double,
        abscissa: Abscissa::Even { start: 0.0, step },
        z_value: 0.0,
        abscissa_axis: axis(18, "Frequency", "Hz"),
        ordinate_axis: axis(12, "Acceleration", units),
        denominator_axis: axis(13, "Force", "N"),
        z_axis: axis(0, "NONE", "NONE"),
        ordinate: Values::Complex(values),
        encoding: Encoding::Ascii,
    }
}

/// FRFs of nodes 1..=3 (one file each when `split`, else one file), geometry of `nodes`.
fn write_case(dir: &Scratch, split: bool, geometry_nodes: &[u64]) -> (Vec<PathBuf>, PathBuf) {
    let sys = prescribed(&TRUE_HZ, &[0.01, 0.005, 0.02], 3);
    let freqs = lines(0.25, 300.0);
    let h = receptance(&sys, 0, &freqs);
    let set = frf_set(&h, &freqs, &[0, 1, 2], Quantity::Acceleration);
    let mut files = Vec::new();
    let mut text = Vec::new();
    for (o, values) in set.responses.into_iter().enumerate() {
        let units = if split && o == 2 { "g/N" } else { "m/s^2/N" };
        let mut bytes = Vec::new();
        write_function(&mut bytes, &function(o as u64 + 1, 0.25, values, units)).unwrap();
        if split {
            let p = dir.path(&format!("frf{}.uff", o + 1));
            std::fs::write(&p, bytes).unwrap();
            files.push(p);
        } else {
            text.extend(bytes);
        }
    }
    if !split {
        let p = dir.path("frf.uff");
        std::fs::write(&p, text).unwrap();
        files.push(p);
    }
    let nodes = Nodes {
        format: NodeFormat::Single15,
        nodes: geometry_nodes
            .iter()
            .map(|&label| Node {
                label,
                definition_cs: 0,
                displacement_cs: 0,
                color: 1,
                coordinates: [
                    POSITIONS.get(label as usize - 1).copied().unwrap_or(0.085),
                    0.0,
                    0.0,
                ],
            })
            .collect(),
    };
    let mut g = Vec::new();
    write_nodes(&mut g, &nodes).unwrap();
    let geometry = dir.path("geometry.uff");
    std::fs::write(&geometry, g).unwrap();
    (files, geometry)
}

fn run(frf: &[PathBuf], geometry: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_jointid"));
    cmd.arg("extract").arg("--frf").args(frf);
    cmd.arg("--geometry").arg(geometry).arg("--out").arg(out);
    cmd.args(["--max-order", "16"]).args(extra);
    cmd.output().unwrap()
}

fn assert_refused(output: &Output, out: &Path, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    for n in needles {
        assert!(stderr.contains(n), "{n:?} not in {stderr}");
    }
    assert!(!out.exists(), "{} was written", out.display());
    let dir = out.parent().unwrap();
    let leftovers: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[test]
fn extracts_three_modes_to_a_csv_the_beam_model_reads() {
    let dir = Scratch::new("good");
    let (files, geometry) = write_case(&dir, false, &[1, 2, 3, 100]);
    let out = dir.path("modes.csv");
    let chart = dir.path("chart.svg");
    let output = run(
        &files,
        &geometry,
        &out,
        &["--chart", chart.to_str().unwrap()],
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(stderr.contains("3 modes"), "{stderr}");
    assert!(std::fs::read_to_string(&chart).unwrap().starts_with("<svg"));
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.starts_with(
            "mode,frequency_hz,x,dof,value,damping_ratio,mpc,frequency_std,damping_std,value_std\n"
        ),
        "{text}"
    );
    let model = jointid::model::from_path(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("models/unesp-bert.toml"),
    )
    .unwrap();
    let measured = MeasuredModes::from_path(&out, &model).unwrap();
    assert_eq!(measured.modes().len(), 3);
    for (m, (f, z)) in measured
        .modes()
        .iter()
        .zip(TRUE_HZ.iter().zip([0.01, 0.005, 0.02]))
    {
        assert!(
            (m.frequency_hz - f).abs() < 1e-3 * f,
            "{} vs {f}",
            m.frequency_hz
        );
        let zeta = m.damping_ratio.unwrap();
        assert!((zeta - z).abs() < 0.1 * z, "{zeta} vs {z}");
        assert!(m.mpc.unwrap() > 0.999);
        // Standard errors from the residuals (no coherence in these files): present, and 0
        // only at the peak, which is 1 by definition.
        assert!(m.frequency_std.unwrap() > 0.0 && m.damping_std.unwrap() > 0.0);
        for (v, s) in m.values.iter().zip(m.value_std.as_ref().unwrap()) {
            assert_eq!(*s == 0.0, *v == 1.0, "value {v}, std {s}");
        }
        // The reader orders the points along the chain.
        let x: Vec<f64> = m.points.iter().map(|p| p.x).collect();
        assert_eq!(x, [POSITIONS[2], POSITIONS[1], POSITIONS[0]]);
    }
}

/// `--space`: rows by the geometry's coordinates and the response direction (`x,y,z,dof`),
/// the form a measured file takes for an external 3D model; the modes are those of the rows
/// by `x,dof`.
#[test]
fn with_space_the_rows_are_the_geometry_coordinates_and_directions() {
    let dir = Scratch::new("space");
    let (files, geometry) = write_case(&dir, false, &[1, 2, 3, 100]);
    let (along, space) = (dir.path("along.csv"), dir.path("space.csv"));
    assert!(run(&files, &geometry, &along, &[]).status.success());
    let output = run(&files, &geometry, &space, &["--space"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let (along, space) = (
        std::fs::read_to_string(&along).unwrap(),
        std::fs::read_to_string(&space).unwrap(),
    );
    let mut rows = space.lines();
    assert_eq!(
        rows.next(),
        Some(
            "mode,frequency_hz,x,y,z,dof,value,damping_ratio,mpc,frequency_std,damping_std,value_std"
        )
    );
    for (a, b) in along.lines().skip(1).zip(rows) {
        // mode,f,x,w,rest  against  mode,f,x,0,0,y,rest: the response direction 2 is y.
        let a: Vec<&str> = a.split(',').collect();
        let b: Vec<&str> = b.split(',').collect();
        assert_eq!(a[..3], b[..3]);
        assert_eq!((a[3], b[3], b[4], b[5]), ("w", "0", "0", "y"));
        assert_eq!(a[4..], b[6..]);
    }
    assert_eq!(along.lines().count(), space.lines().count());
}

#[test]
fn averages_need_the_coherence_and_two_of_them() {
    let dir = Scratch::new("averages");
    let (files, geometry) = write_case(&dir, false, &[1, 2, 3]);
    let out = dir.path("modes.csv");
    let output = run(&files, &geometry, &out, &["--averages", "1"]);
    assert_refused(&output, &out, &["--averages 1 is invalid", ">= 2"]);
    let output = run(&files, &geometry, &out, &["--averages", "20"]);
    assert_refused(
        &output,
        &out,
        &["20 averages were given, but the FRFs carry no coherence"],
    );
}

#[test]
fn truncated_record_names_file_record_and_line() {
    let dir = Scratch::new("truncated");
    let (files, geometry) = write_case(&dir, false, &[1, 2, 3]);
    let text = std::fs::read_to_string(&files[0]).unwrap();
    // Cut inside the values of the second FRF (record 2).
    let second = text.match_indices("H node 2").next().unwrap().0;
    std::fs::write(&files[0], &text[..second + 4000]).unwrap();
    let out = dir.path("modes.csv");
    let output = run(&files, &geometry, &out, &[]);
    assert_refused(&output, &out, &["frf.uff", "record 2", "line"]);
}

#[test]
fn no_peak_in_the_band_is_refused() {
    let dir = Scratch::new("nopeak");
    let (files, geometry) = write_case(&dir, false, &[1, 2, 3]);
    let out = dir.path("modes.csv");
    let output = run(&files, &geometry, &out, &["--band", "120:180"]);
    assert_refused(&output, &out, &["frf.uff", "no mode found in 120..180 Hz"]);
}

#[test]
fn response_node_missing_from_the_geometry_is_refused() {
    let dir = Scratch::new("geometry");
    let (files, geometry) = write_case(&dir, false, &[1, 3, 100]);
    let out = dir.path("modes.csv");
    let output = run(&files, &geometry, &out, &[]);
    assert_refused(
        &output,
        &out,
        &["geometry.uff", "response node 2", "record 2", "1, 3, 100"],
    );
}

#[test]
fn mixed_units_are_refused() {
    let dir = Scratch::new("units");
    let (files, geometry) = write_case(&dir, true, &[1, 2, 3]);
    assert_eq!(files.len(), 3);
    let out = dir.path("modes.csv");
    let output = run(&files, &geometry, &out, &[]);
    assert_refused(
        &output,
        &out,
        &["frf3.uff", "record 1", "g/N", "m/s^2/N", "mixed units"],
    );
}

/// An even axis stored as uneven values of 6 digits (`E13.5`), as exporters write it: 2100
/// lines of 0.0625 Hz from 0 Hz, whose last line is written 131.188 for 131.1875, and line
/// 1601 (100.0625 Hz) 100.062. The step from the written span is 2.4e-7 Hz too long, which
/// with line 1601's own rounding puts that line 8.8e-4 Hz from where the step places it:
/// beyond the rounding of one value, within that of the three. The axis is even, and the
/// modes come out.
#[test]
fn an_even_axis_written_to_six_digits_is_even() {
    let dir = Scratch::new("six-digits");
    let (_, geometry) = write_case(&dir, false, &[1, 2, 3]);
    let sys = prescribed(&TRUE_HZ, &[0.01, 0.005, 0.02], 3);
    let freqs: Vec<f64> = (0..2100).map(|k| f64::from(k) * 0.0625).collect();
    let h = receptance(&sys, 0, &freqs);
    let set = frf_set(&h, &freqs, &[0, 1, 2], Quantity::Acceleration);
    let mut bytes = Vec::new();
    for (o, values) in set.responses.into_iter().enumerate() {
        let mut f = function(o as u64 + 1, 0.0625, values, "m/s^2/N");
        f.abscissa = Abscissa::Uneven(freqs.clone());
        write_function(&mut bytes, &f).unwrap();
    }
    let text = String::from_utf8(bytes).unwrap();
    assert!(text.contains("1.31188E+02") && text.contains("1.00062E+02"));
    let frf = dir.path("uneven.uff");
    std::fs::write(&frf, text).unwrap();
    let out = dir.path("modes.csv");
    let output = run(&[frf], &geometry, &out, &["--band", "20:120"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(stderr.contains("2 modes"), "{stderr}");
}

/// A band edge of 1e308 is echoed in exponent form, not in 309 digits: the message stays short.
#[test]
fn a_huge_band_is_echoed_compactly() {
    let dir = Scratch::new("huge-band");
    let (files, geometry) = write_case(&dir, false, &[1, 2, 3]);
    let out = dir.path("modes.csv");
    for (band, echo) in [
        ("0:1e308", "band 0..1e308 Hz"),
        ("1e307:1e308", "band 1e307..1e308 Hz"),
    ] {
        let output = run(&files, &geometry, &out, &["--band", band, "--quiet"]);
        assert_refused(
            &output,
            &out,
            &[&format!(
                "{echo} is invalid: it needs 0 <= lo < hi <= 300 Hz"
            )],
        );
        let stderr = String::from_utf8_lossy(&output.stderr);
        let message = stderr.trim().replace(&format!("{}/", dir.0.display()), "");
        assert!(
            message.len() < 200,
            "{} characters: {message}",
            message.len()
        );
    }
}

/// The FRFs of `write_case` in one file with their coherences: 0.99 below `cut` Hz, 0.05
/// above (where the input stops); the geometry of nodes 1-3 and the shaker.
fn write_coherent_case(dir: &Scratch, cut: f64) -> (PathBuf, PathBuf) {
    let (files, geometry) = write_case(dir, false, &[1, 2, 3, 100]);
    let mut bytes = std::fs::read(&files[0]).unwrap();
    let freqs = lines(0.25, 300.0);
    for node in 1..=3 {
        let mut f = function(node, 0.25, Vec::new(), "NONE");
        f.function_type = FunctionType::Coherence;
        f.ordinate_axis = axis(0, "NONE", "NONE");
        let values = freqs
            .iter()
            .map(|&x| if x < cut { 0.99 } else { 0.05 })
            .collect();
        f.ordinate = Values::Real(values);
        write_function(&mut bytes, &f).unwrap();
    }
    let path = dir.path("coherent.uff");
    std::fs::write(&path, bytes).unwrap();
    (path, geometry)
}

/// Without --band the band follows the coherence (the input stops at 150 Hz: the 200 Hz
/// mode is outside it) and the report says where the band came from and why each candidate
/// was kept or rejected.
#[test]
fn the_automatic_band_follows_the_coherence_and_the_report_says_why() {
    let dir = Scratch::new("report");
    let (frf, geometry) = write_coherent_case(&dir, 150.0);
    let (out, report, chart) = (
        dir.path("modes.csv"),
        dir.path("report.json"),
        dir.path("chart.svg"),
    );
    let output = run(
        std::slice::from_ref(&frf),
        &geometry,
        &out,
        &[
            "--report",
            report.to_str().unwrap(),
            "--chart",
            chart.to_str().unwrap(),
        ],
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(
        stderr.contains("(where the coherence and the level show excitation), 2 modes:"),
        "{stderr}"
    );
    assert!(
        stderr.contains("  kept mode 1 (stable from order"),
        "{stderr}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["version"], 1);
    assert_eq!(json["band"]["source"], "coherence");
    let (lo, hi) = (
        json["band"]["hz"][0].as_f64().unwrap(),
        json["band"]["hz"][1].as_f64().unwrap(),
    );
    assert!(lo <= 1.0 && (140.0..150.0).contains(&hi), "{lo} {hi}");
    assert_eq!(json["rules"]["automatic"], true);
    assert_eq!(json["rules"]["mpc_min"], 0.95);
    let candidates = json["candidates"].as_array().unwrap();
    for (r, f) in [(1, TRUE_HZ[0]), (2, TRUE_HZ[1])] {
        let c = &candidates[r - 1];
        assert_eq!(c["mode"], r);
        assert!(c["rejected"].is_null() && c["edge"].is_null(), "{c}");
        assert!(
            (c["frequency_hz"].as_f64().unwrap() - f).abs() < 1e-3 * f,
            "{c}"
        );
        assert!(c["mpc"].as_f64().unwrap() > 0.999, "{c}");
        assert!(c["margins"][0].as_f64().unwrap() >= 5.0, "{c}");
    }
    for c in &candidates[2..] {
        assert!(
            c["mode"].is_null() && c["rejected"]["kind"].is_string(),
            "{c}"
        );
    }
    let svg = std::fs::read_to_string(&chart).unwrap();
    assert!(
        svg.contains("rejected candidate ("),
        "no rejected mark in the legend"
    );
    assert!(svg.contains("chosen pole (2 modes kept)"));
}

/// A band given where the coherence shows no excitation is refused, naming the flag and its
/// value; an MPC threshold out of (0, 1] too.
#[test]
fn a_band_the_coherence_shows_unexcited_is_refused() {
    let dir = Scratch::new("unexcited");
    let (frf, geometry) = write_coherent_case(&dir, 150.0);
    let out = dir.path("modes.csv");
    let output = run(
        std::slice::from_ref(&frf),
        &geometry,
        &out,
        &["--band", "180:290"],
    );
    assert_refused(
        &output,
        &out,
        &[
            "coherent.uff: --band 180:290 is refused: band 180..290 Hz shows no excitation: \
             its smoothed mean coherence reaches 0.05 (0.8 needed)",
            "give a band the input covered",
        ],
    );
    let output = run(
        std::slice::from_ref(&frf),
        &geometry,
        &out,
        &["--mpc-min", "1.5"],
    );
    assert_refused(
        &output,
        &out,
        &["--mpc-min 1.5 is invalid: it must be in (0, 1]"],
    );
    // The excited part of the data passes, as given.
    let output = run(&[frf], &geometry, &out, &["--band", "10:140"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(
        stderr.contains("band 10.000..140.000 Hz, 2 modes:"),
        "{stderr}"
    );
}
