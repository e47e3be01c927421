//! Measured rows by coordinates in space (`mode,frequency_hz,x,y,z,dof,value`) on an external
//! model, the 3D lap of `jointid solid`: a sensor near a node reads that node's DOF, so the
//! file by coordinates gives the same `identify` CSV as the file by label, byte for byte; a
//! sensor off the model, at coincident nodes, in a direction the model lacks, or on a beam
//! chain is refused (exit 2) with the file, the line, the point and the nearest DOF.

use std::fmt::Write as _;
use std::path::Path;

use crate::common::{jointid_ok, refused, s, scratch};
use jointid::measured::MeasuredModes;
use jointid::structure::Structure;

/// A lap of 540 DOFs (that of `solid.rs`, without the bolt).
const LAP: &str = "width = 0.02\noverlap = 0.04\n\
    [material]\nyoungs_modulus = 2.1e11\npoisson_ratio = 0.3\ndensity = 7850.0\n\
    [[bar]]\nlength = 0.16\nthickness = 0.01\n[[bar]]\nlength = 0.12\nthickness = 0.008\n\
    [interface]\nnormal = 1e13\nshear_x = 2e12\nshear_y = 3e12\n\
    [mesh]\nsize = 0.01\nlayers = 1\n";

/// The model folder made by `jointid solid` in `dir`, and its structure.
fn lap(dir: &Path) -> (std::path::PathBuf, Structure) {
    let config = dir.join("lap.toml");
    std::fs::write(&config, LAP).unwrap();
    let out = dir.join("model");
    jointid_ok(&["solid", s(&config), "--out", s(&out)]);
    let model = out.join("model.toml");
    let structure = jointid::model::from_path(&model).unwrap();
    (model, structure)
}

/// The simulated modes 1-3 at the translations of the bottom face (z = 0), by label and by
/// coordinates moved `offset` m along x.
fn measured(dir: &Path, model: &Path, structure: &Structure, offset: f64) -> (String, String) {
    let sim = dir.join("sim.csv");
    jointid_ok(&[
        "simulate",
        "--model",
        s(model),
        "--modes",
        "3",
        "--measure",
        "w",
        "--out",
        s(&sim),
    ]);
    let text = std::fs::read_to_string(&sim).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("mode,frequency_hz,label,value"));
    let mut by_label = String::from("mode,frequency_hz,label,value\n");
    let mut by_xyz = String::from("mode,frequency_hz,x,y,z,dof,value\n");
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let dof = structure.dofs.get(structure.dofs.index(f[2]).unwrap());
        let [x, y, z] = dof.position;
        if z != 0.0 {
            continue;
        }
        writeln!(by_label, "{line}").unwrap();
        writeln!(
            by_xyz,
            "{},{},{},{y},{z},{},{}",
            f[0],
            f[1],
            x + offset,
            dof.direction,
            f[3]
        )
        .unwrap();
    }
    (by_label, by_xyz)
}

/// The arguments of `jointid identify` on `model` and `measured` (n = 20, m = 10, equal
/// weights), writing `out` when given.
fn identify<'a>(model: &'a Path, measured: &'a Path, out: Option<&'a Path>) -> Vec<&'a str> {
    let mut args = vec![
        "identify",
        "--model",
        s(model),
        "--measured",
        s(measured),
        "--n",
        "20",
        "--m",
        "10",
        "--weighting",
        "equal",
    ];
    if let Some(out) = out {
        args.extend(["--out", s(out)]);
    }
    args
}

#[test]
fn sensors_by_coordinates_read_their_nearest_dofs_and_identify_the_same() {
    let dir = scratch("space", "same");
    let (model, structure) = lap(&dir);
    let (by_label, by_xyz) = measured(&dir, &model, &structure, 1e-4);
    let (a, b) = (dir.join("label.csv"), dir.join("xyz.csv"));
    std::fs::write(&a, &by_label).unwrap();
    std::fs::write(&b, &by_xyz).unwrap();
    assert_eq!(
        MeasuredModes::from_path(&a, &structure).unwrap(),
        MeasuredModes::from_path(&b, &structure).unwrap()
    );
    let run = |measured: &Path, out: &Path| {
        jointid_ok(&identify(&model, measured, Some(out)));
        std::fs::read(out).unwrap()
    };
    assert_eq!(run(&a, &dir.join("a.csv")), run(&b, &dir.join("b.csv")));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_sensor_off_the_model_or_ambiguous_is_refused_naming_the_point_and_the_nearest_dof() {
    let dir = scratch("space", "refused");
    let (model, structure) = lap(&dir);
    // The default tolerance: 1% of the bounding box's diagonal (0.24 x 0.02 x 0.018 m).
    let (tolerance, _) = structure.dofs.sensor_tolerance();
    assert!(
        (tolerance - 0.01 * (0.24f64.powi(2) + 0.02f64.powi(2) + 0.018f64.powi(2)).sqrt()).abs()
            < 1e-15
    );
    let run = |name: &str, rows: &str, needles: &[&str]| {
        let file = dir.join(name);
        std::fs::write(&file, format!("mode,frequency_hz,x,y,z,dof,value\n{rows}")).unwrap();
        let out = dir.join(format!("{name}.out.csv"));
        refused(&identify(&model, &file, Some(&out)), needles);
        assert!(!out.exists(), "{name}: nothing is written");
    };
    // 0.1 m above the top: off by more than the tolerance (mm for m would be far more).
    run(
        "far.csv",
        "1,900,0.2,0.01,0.118,z,1\n",
        &[
            "far.csv:2: the point (0.2, 0.01, 0.118) m is 1.000e-1 m from the nearest z DOF `",
            "`, over the sensor tolerance 2.415e-3 m (1% of its size): check the point's unit, origin and axes",
        ],
    );
    // Coordinates of 1e308 are echoed in exponent form, not in 309 digits each.
    let huge = dir.join("huge.csv");
    std::fs::write(
        &huge,
        "mode,frequency_hz,x,y,z,dof,value\n1,900,1e308,-1e308,1e308,z,1\n",
    )
    .unwrap();
    let err = refused(
        &identify(&model, &huge, None),
        &["huge.csv:2: the point (1e308, -1e308, 1e308) m is 1.732e308 m from the nearest z DOF"],
    );
    let message = err.trim().replace(&format!("{}/", dir.display()), "");
    assert!(
        message.len() < 200,
        "{} characters: {message}",
        message.len()
    );
    // On the lap's faces: two coincident nodes.
    run(
        "lap.csv",
        "1,900,0.14,0.01,0.01,z,1\n",
        &[
            "lap.csv:2: the point (0.14, 0.01, 0.01) m is nearest to `",
            "two z DOFs at the same position (coincident nodes): name the one measured by label",
        ],
    );
    run(
        "w.csv",
        "1,900,0.1,0,0,w,1\n",
        &["w.csv:2: direction w is not one of the model's DOFs (it has x, y, z)"],
    );
    run(
        "nan.csv",
        "1,900,0.1,NaN,0,z,1\n",
        &["nan.csv:2: y = `NaN` is invalid: it must be a number (m)"],
    );
    // A tighter tolerance of the model's own: 1e-4 m off is then refused.
    let text = std::fs::read_to_string(&model).unwrap();
    let tight = model.with_file_name("tight.toml");
    std::fs::write(
        &tight,
        text.replace(
            "rigid_body_modes = 6\n",
            "rigid_body_modes = 6\nsensor_tolerance = 5e-5\n",
        ),
    )
    .unwrap();
    let (_, by_xyz) = measured(&dir, &model, &structure, 1e-4);
    let file = dir.join("offset.csv");
    std::fs::write(&file, by_xyz).unwrap();
    refused(
        &identify(&tight, &file, None),
        &[
            "offset.csv:2: the point (0.0001, 0, 0) m is 1.000e-4 m from the nearest",
            "over the sensor tolerance 5.000e-5 m (its sensor_tolerance)",
        ],
    );
    // On a beam chain, rows by x,y,z are refused: its positions are read along the elements.
    let paper = concat!(env!("CARGO_MANIFEST_DIR"), "/models/paper-case-1.toml");
    let chain = dir.join("chain.csv");
    std::fs::write(
        &chain,
        "mode,frequency_hz,x,y,z,dof,value\n1,150,0.1,0,0,w,1\n",
    )
    .unwrap();
    refused(
        &identify(Path::new(paper), &chain, None),
        &[
            "chain.csv:2: rows by x,y,z apply to models without beam elements (external models): on a beam chain give `x,dof`",
        ],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
