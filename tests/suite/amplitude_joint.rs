//! `jointid amplitude --joint k2`: the joint's own stiffness and damping against amplitude,
//! recovered from levels whose frequencies come from the continuous solution of a jointed
//! beam, and the frequencies before (constant joint) and after (the chosen law).
//!
//! Independence: the levels' frequencies are the symmetric modes of two free-free steel beams
//! joined by a rotational spring (the 4 x 4 determinant of `frequency_only`, not jointid's
//! elements), with k2 following a power law of the amplitude, k2 = K0 (1 - c A^b); the modal
//! damping is the joint's, zeta_j = z0 + d A^g, times the joint's share of the strain energy
//! d ln lambda / d ln k2 taken by central differences of the same continuous solution. jointid
//! sees frequencies, damping ratios and amplitudes, and a 60-element model of the beams.

use std::f64::consts::PI;

use crate::common::{jointid, jointid_ok, s, scratch};
use crate::frequency_only::{HALF, symmetric_hz};

const K0: f64 = 2.0e4;
const POWER: [f64; 2] = [1.0, 0.5];
const DAMPING: [f64; 3] = [0.01, 0.5, 0.7];
const AMPLITUDES: [f64; 7] = [1e-4, 2e-4, 4e-4, 8e-4, 1.6e-3, 3.2e-3, 6.4e-3];

fn k2_at(a: f64) -> f64 {
    K0 * (1.0 - POWER[0] * a.powf(POWER[1]))
}

fn zeta_joint(a: f64) -> f64 {
    DAMPING[0] + DAMPING[1] * a.powf(DAMPING[2])
}

/// d ln lambda / d ln k2 of the two symmetric modes, by central differences.
fn shares(k2: f64) -> [f64; 2] {
    let h = 1e-4;
    let (up, down) = (
        symmetric_hz(k2 * (1.0 + h), 2),
        symmetric_hz(k2 * (1.0 - h), 2),
    );
    std::array::from_fn(|i| 2.0 * (up[i] / down[i]).ln() / ((1.0 + h) / (1.0 - h)).ln())
}

/// The model (60 elements per beam, k2 nominal 1e5), a modes file per level (the symmetric
/// modes, elastic modes 1 and 3), the levels file.
fn inputs(dir: &std::path::Path) -> std::path::PathBuf {
    inputs_with(dir, "")
}

/// As [`inputs`], with `extra` lines at the top of the levels file.
fn inputs_with(dir: &std::path::Path, extra: &str) -> std::path::PathBuf {
    let beam = "[[beam]]\nlength = 0.25\nelements = 60\nyoungs_modulus = 2.1e11\ndensity = 7850\narea = 2.4e-3\nsecond_moment = 3.2e-7\n";
    assert_eq!(HALF, 0.25);
    let model = format!(
        "{beam}{beam}[[joint]]\nk1 = 1e13\nk2 = 1e5\nfixed = [\"k1\"]\n[[sensor]]\nx = 0.0\n"
    );
    std::fs::write(dir.join("model.toml"), model).unwrap();
    let mut levels = format!("model = \"model.toml\"\n{extra}");
    for (i, &a) in AMPLITUDES.iter().enumerate() {
        let k2 = k2_at(a);
        let f = symmetric_hz(k2, 2);
        let share = shares(k2);
        let mut csv = "mode,frequency_hz,x,dof,value,damping_ratio\n".to_string();
        let mut accel = Vec::new();
        for (r, mode) in [1, 3].iter().enumerate() {
            csv += &format!("{mode},{},0.0,w,1.0,{}\n", f[r], share[r] * zeta_joint(a));
            accel.push(a * (2.0 * PI * f[r]).powi(2));
        }
        let name = format!("modes{i}.csv");
        std::fs::write(dir.join(&name), csv).unwrap();
        levels += &format!(
            "[[level]]\nexcitation = {}\nmodes = \"{name}\"\nacceleration = [{}, {}]\n",
            i + 1,
            accel[0],
            accel[1]
        );
    }
    let path = dir.join("levels.toml");
    std::fs::write(&path, levels).unwrap();
    path
}

fn rows(path: &std::path::Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[test]
fn the_joint_law_is_recovered_from_the_levels_and_closes_the_frequencies() {
    let dir = scratch("amplitude-joint", "power");
    let levels = inputs(&dir);
    let out = dir.join("out");
    jointid_ok(&["amplitude", s(&levels), "--out", s(&out), "--joint", "k2"]);
    // Per level: k2 and the joint's damping against the generating law (the FE model's 60
    // elements against the continuous beams: 1e-5 on k2, 1e-4 on the energy share).
    let data = rows(&out.join("joint_levels.csv"));
    assert_eq!(data.len(), 2 * AMPLITUDES.len());
    for row in &data {
        let a: f64 = row[2].parse().unwrap();
        let (k2, zeta): (f64, f64) = (row[7].parse().unwrap(), row[10].parse().unwrap());
        assert_eq!(row[5], "k2");
        assert_eq!(
            row[3], row[2],
            "without a reference point the amplitude is the sensor's"
        );
        assert!(
            (k2 / k2_at(a) - 1.0).abs() < 1e-5,
            "{row:?}: k2 {}",
            k2_at(a)
        );
        assert!(
            (zeta / zeta_joint(a) - 1.0).abs() < 1e-4,
            "{row:?}: zeta_j {}",
            zeta_joint(a)
        );
    }
    // The power law is chosen on both modes and gives back K0, c, b, z0, d, g.
    let params = rows(&out.join("joint_parameters.csv"));
    let want = [K0, POWER[0], POWER[1], DAMPING[0], DAMPING[1], DAMPING[2]];
    for mode in ["1", "3"] {
        let chosen: Vec<&Vec<String>> = params
            .iter()
            .filter(|r| r[0] == mode && r[2] == "yes")
            .collect();
        assert!(
            chosen.iter().all(|r| r[1] == "power_law"),
            "mode {mode}: {chosen:?}"
        );
        for (r, w) in chosen.iter().zip(want) {
            let v: f64 = r[4].parse().unwrap();
            assert!(
                (v / w - 1.0).abs() < 1e-2,
                "mode {mode} {}: {v} vs {w}",
                r[3]
            );
        }
    }
    // Before: one k2 for every level leaves the softening (0.1-0.5%); after: the law's k2.
    for row in rows(&out.join("joint_errors.csv")) {
        let (before, after): (f64, f64) = (row[5].parse().unwrap(), row[8].parse().unwrap());
        assert!(after.abs() < 1e-3, "{row:?}");
        assert!(before.abs() > 10.0 * after.abs(), "{row:?}");
    }
    for f in [
        "joint_laws.csv",
        "joint_bands.csv",
        "joint_mode1.svg",
        "joint_mode3.svg",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The rotation across the joint per unit displacement of the free end, in a symmetric mode
/// of frequency `f_hz` with spring `k2`, from the continuous half beam (x from the joint to
/// the free end at a, w = A cos bx + B sin bx + C cosh bx + D sinh bx): with A = 1 the free
/// end's two conditions and w'''(0) = 0 (D = B) give B and C; the rotations on either side are
/// opposite, so the jump is 2 |w'(0)| = 2 |2 b B|.
fn rotation_per_end(f_hz: f64) -> f64 {
    let bar = jointid::model::fixtures::steel_bar(HALF, 1);
    let c_wave = (bar.bending_stiffness() / bar.mass_per_length()).sqrt();
    let b = (2.0 * PI * f_hz / c_wave).sqrt();
    let a = HALF;
    let (c, s, ch, sh) = ((b * a).cos(), (b * a).sin(), (b * a).cosh(), (b * a).sinh());
    // [ch, sh - s; sh, ch - c] [C; B] = [c; -s]
    let det = ch * (ch - c) - sh * (sh - s);
    let big_c = (c * (ch - c) + s * (sh - s)) / det;
    let big_b = (-s * ch - sh * c) / det;
    let end = c + big_b * s + big_c * ch + big_b * sh;
    2.0 * (2.0 * b * big_b).abs() / end.abs()
}

/// With the reference sensor named (the free end, x = 0), the laws are fitted against the
/// joint's own rotation amplitude A_j = A |theta_left - theta_right| / |w(0)| of the model's
/// mode: against the continuous solution's ratio (`rotation_per_end`) at every level, and the
/// power law's exponent b stays while its coefficient becomes c / r^b.
#[test]
fn with_the_reference_named_the_joint_law_is_against_its_rotation() {
    let dir = scratch("amplitude-joint", "rotation");
    let levels = inputs_with(&dir, "reference_x = 0.0\n");
    let out = dir.join("out");
    jointid_ok(&["amplitude", s(&levels), "--out", s(&out), "--joint", "k2"]);
    let data = rows(&out.join("joint_levels.csv"));
    let params = rows(&out.join("joint_parameters.csv"));
    for mode in ["1", "3"] {
        let ratios: Vec<f64> = data
            .iter()
            .filter(|r| r[0] == mode)
            .map(|r| {
                let ratio = r[3].parse::<f64>().unwrap() / r[2].parse::<f64>().unwrap();
                let exact = rotation_per_end(r[4].parse().unwrap());
                assert!(
                    (ratio / exact - 1.0).abs() < 1e-3,
                    "{r:?}: {ratio} vs {exact}"
                );
                ratio
            })
            .collect();
        let r = ratios[0];
        // The shape changes little with an 8% softer joint.
        assert!(
            ratios.iter().all(|q| (q / r - 1.0).abs() < 0.05),
            "{ratios:?}"
        );
        let value = |name: &str| -> f64 {
            params
                .iter()
                .find(|p| p[0] == mode && p[1] == "power_law" && p[3] == name)
                .unwrap()[4]
                .parse()
                .unwrap()
        };
        let (c, b) = (value("c"), value("b"));
        assert!((b / POWER[1] - 1.0).abs() < 0.05, "mode {mode}: b {b}");
        let c_at_reference = c * r.powf(b);
        assert!(
            (c_at_reference / POWER[0] - 1.0).abs() < 0.05,
            "mode {mode}: c {c} r {r} -> {c_at_reference}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The levels' second mode renumbered 243 in every modes file: the model has two beams of 60
/// elements, 122 nodes x 2 = 244 DOFs (the sensor at x = 0 is an end node), 2 rigid-body
/// modes, so 242 elastic modes (counted here from the model text, not by the code under
/// test). `--joint` needs the model mode each mode pairs with by order: refused naming the
/// mode and the count, exit 2, nothing written.
#[test]
fn a_mode_beyond_the_models_elastic_modes_is_refused_with_the_joint() {
    let dir = scratch("amplitude-joint", "beyond-model");
    let levels = inputs(&dir);
    for i in 0..AMPLITUDES.len() {
        let modes = dir.join(format!("modes{i}.csv"));
        let text = std::fs::read_to_string(&modes).unwrap();
        let renumbered = text.replace("\n3,", "\n243,");
        assert_ne!(renumbered, text);
        std::fs::write(&modes, renumbered).unwrap();
    }
    let out = dir.join("out");
    let o = jointid(&["amplitude", s(&levels), "--out", s(&out), "--joint", "k2"]);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("modes0.csv: mode 243 is beyond the model: it has 242 elastic modes (244 DOFs, 2 rigid-body modes)"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.exists(), "nothing is written");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_joint_the_model_does_not_identify_or_a_mode_that_does_not_see_it_is_refused() {
    let dir = scratch("amplitude-joint", "bad");
    let levels = inputs(&dir);
    let out = dir.join("out");
    let refused = |joint: &str, needle: &str| {
        let o = jointid(&["amplitude", s(&levels), "--out", s(&out), "--joint", joint]);
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(needle), "{err}");
        assert!(!out.exists(), "nothing is written");
    };
    refused(
        "k3",
        "--joint = \"k3\" is invalid: the name of one of the model's identified parameters: k2",
    );
    // k1 held fixed is not identified either.
    refused("k1", "--joint = \"k1\" is invalid");
    // A measured antisymmetric mode (elastic mode 2) does not see k2.
    for i in 0..AMPLITUDES.len() {
        let modes = dir.join(format!("modes{i}.csv"));
        let text = std::fs::read_to_string(&modes)
            .unwrap()
            .replace("\n3,", "\n2,");
        std::fs::write(&modes, text).unwrap();
    }
    refused("k2", "does not depend on k2");
    // A reference point the modes files do not have.
    let dir = scratch("amplitude-joint", "bad-reference");
    let levels = inputs_with(&dir, "reference_x = 0.1\n");
    let out = dir.join("out");
    let o = jointid(&["amplitude", s(&levels), "--out", s(&out), "--joint", "k2"]);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("mode 1 has no point at x = 0.1, w"), "{err}");
    assert!(!out.exists());
    let levels = inputs_with(&dir, "reference_dof = \"theta\"\n");
    let o = jointid(&["amplitude", s(&levels), "--out", s(&out), "--joint", "k2"]);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains("reference_dof = \"theta\" is invalid: it needs `reference_x`"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
