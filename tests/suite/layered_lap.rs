//! The layered lap (`[joint.lap]`, `kind = "lap"`): closed-form limits, derivatives, recovery
//! of k_n and k_s by the diagnosis, bad input.
//!
//! Limits. A free-free beam (L = 0.6 m, steel, 20 x 10 mm) made of two beams of 0.3 m whose
//! half-lap overlap covers the whole length (0.6 m): everywhere two half-height layers.
//!
//! ```text
//!   upper layer  ==================================   (beam 0, from 0 to 0.6 m)
//!   interface    ..................................   k_n, k_s per unit length
//!   lower layer  ==================================   (beam 1, from 0 to 0.6 m)
//! ```
//!
//! - k_s -> 0 (k_n stiff): two layers bending together, each about its own centroid:
//!   EI_1 + EI_2 = 2 (EI / 8) = EI / 4, mass rho A;
//! - k_s, k_n -> large: the composite section, EI_1 + EI_2 + EA_1 d_1^2 + EA_2 d_2^2 with the
//!   parallel-axis terms (d = h / 4): the solid beam's EI, with the layers' axial inertia
//!   (u = -+ d theta) as a rotary inertia rho A h^2 / 16 that Euler-Bernoulli leaves out.
//!
//! Reference: omega_i = (beta_i L)^2 sqrt(EI / (rho A L^4)), beta L = 4.7300407, 7.8532046,
//! 10.9956078 (free-free, Blevins, *Formulas for Natural Frequency and Mode Shape*, table 8-1).

use std::path::Path;

use jointid::modal::ModalSolution;
use jointid::model::chain_from_toml;
use jointid::structure::{Direction, Structure};

const BETA_L: [f64; 3] = [4.7300407, 7.8532046, 10.9956078];
const E: f64 = 2.1e11;
const RHO: f64 = 7850.0;
const B: f64 = 0.02;
const H: f64 = 0.01;

/// Two steel beams of `lengths`, joined by `joint` (TOML of the `[[joint]]` table and what
/// follows), meshed at `h` m.
fn model(lengths: [f64; 2], h: f64, joint: &str) -> String {
    let (area, second) = (B * H, B * H.powi(3) / 12.0);
    let beam = |l: f64| {
        format!(
            "[[beam]]\nlength = {l}\nyoungs_modulus = {E}\ndensity = {RHO}\narea = {area}\nsecond_moment = {second}\n"
        )
    };
    format!(
        "[mesh]\nelement_length = {h}\n{}{}[[joint]]\n{joint}",
        beam(lengths[0]),
        beam(lengths[1])
    )
}

/// One steel beam of length `l`, meshed at `h` m.
fn one_beam(l: f64, h: f64) -> String {
    let (area, second) = (B * H, B * H.powi(3) / 12.0);
    format!(
        "[mesh]\nelement_length = {h}\n[[beam]]\nlength = {l}\nyoungs_modulus = {E}\ndensity = {RHO}\narea = {area}\nsecond_moment = {second}\n"
    )
}

fn structure(text: &str) -> Structure {
    chain_from_toml(text, Path::new("m.toml")).unwrap().build()
}

/// A half-lap over the whole 0.6 m with interface stiffnesses (k_n, k_s).
fn covering(k_n: f64, k_s: f64) -> Structure {
    structure(&model(
        [0.3, 0.3],
        0.01,
        &format!(
            "kind = \"lap\"\n[joint.lap]\nlength = 0.6\nlayers = \"half\"\nk_n = {k_n:e}\nk_s = {k_s:e}\n"
        ),
    ))
}

fn analytic_hz(ei: f64, i: usize) -> f64 {
    let (l, rho_a): (f64, f64) = (0.6, RHO * B * H);
    BETA_L[i].powi(2) * (ei / (rho_a * l.powi(4))).sqrt() / (2.0 * std::f64::consts::PI)
}

/// The frequencies of the lowest `count` bending modes of `model` (those whose transverse
/// DOFs move more than its axial ones: the layers' axial modes are left out), Hz.
fn bending_hz(model: &Structure, count: usize) -> Vec<f64> {
    let sol = ModalSolution::solve(&model.assemble()).unwrap();
    let y = sol.vectors();
    let share = |s: usize, d: Direction| -> f64 {
        (0..model.dof_count())
            .filter(|&i| model.dofs.get(i).direction == d)
            .map(|i| y[(i, s)].powi(2))
            .sum()
    };
    (model.rigid..sol.len())
        .filter(|&s| share(s, Direction::W) > share(s, Direction::X))
        .take(count)
        .map(|s| sol.frequency_hz(s))
        .collect()
}

#[test]
fn a_slipping_interface_bends_as_two_free_layers() {
    let ei = E * B * H.powi(3) / 12.0;
    let model = covering(1e13, 1e-3);
    // Two bending rigid motions and the layers' common axial translation.
    assert_eq!(model.rigid, 3);
    let targets: Vec<f64> = (0..3).map(|i| analytic_hz(ei / 4.0, i)).collect();
    let fe = bending_hz(&model, 3);
    for (f, t) in fe.iter().zip(&targets) {
        assert!((f - t).abs() < 1e-5 * t, "{f} vs {t}");
    }
}

/// The solid beam's lowest `count` elastic frequencies with the layers' axial inertia in the
/// bonded limit (u_k = -+ d theta: a rotary inertia rho sum A_k d_k^2 = rho A h^2 / 16 per
/// unit length, which Euler-Bernoulli leaves out), by the Rayleigh quotient of the solid
/// beam's modes: an upper bound within (its relative change)^2, below 3e-5 here.
fn solid_with_layer_inertia(count: usize) -> Vec<f64> {
    let solid = structure(&one_beam(0.6, 0.01));
    let sol = ModalSolution::solve(&solid.assemble()).unwrap();
    let j = RHO * B * H * H * H / 16.0;
    (2..2 + count)
        .map(|s| {
            let y = |d: Option<usize>| d.map_or(0.0, |d| sol.vectors()[(d, s)]);
            let rotary: f64 = solid
                .sites
                .elements
                .iter()
                .map(|e| {
                    let l = e.length();
                    let c = j / (30.0 * l);
                    let r = [
                        [36.0, 3.0 * l, -36.0, 3.0 * l],
                        [3.0 * l, 4.0 * l * l, -3.0 * l, -l * l],
                        [-36.0, -3.0 * l, 36.0, -3.0 * l],
                        [3.0 * l, -l * l, -3.0 * l, 4.0 * l * l],
                    ];
                    let v = e.line.dofs.map(y);
                    (0..4)
                        .flat_map(|a| (0..4).map(move |b| (a, b)))
                        .map(|(a, b)| c * v[a] * r[a][b] * v[b])
                        .sum::<f64>()
                })
                .sum();
            sol.frequency_hz(s) / (1.0 + rotary).sqrt()
        })
        .collect()
}

#[test]
fn a_bonded_interface_bends_as_the_solid_section() {
    let model = covering(1e16, 1e15);
    let targets = solid_with_layer_inertia(3);
    let fe = bending_hz(&model, 3);
    for (f, t) in fe.iter().zip(&targets) {
        assert!((f - t).abs() < 2e-5 * t, "{f} vs {t}");
    }
    // Without the layers' axial inertia the solid beam is 4e-4 higher: the test sees it.
    let ei = E * B * H.powi(3) / 12.0;
    assert!(analytic_hz(ei, 0) / fe[0] - 1.0 > 3e-4);
}

/// Between the limits the lap is softer than the solid beam and stiffer than the free layers,
/// and stiffens as k_s grows.
#[test]
fn partial_interaction_lies_between_the_limits() {
    let ei = E * B * H.powi(3) / 12.0;
    let (soft, solid) = (analytic_hz(ei / 4.0, 0), analytic_hz(ei, 0));
    let mut last = soft;
    for k_s in [1e8, 1e9, 1e10, 1e11] {
        let f = bending_hz(&covering(1e14, k_s), 1)[0];
        assert!(
            f > last && f < solid,
            "k_s {k_s:e}: {f} (soft {soft}, solid {solid})"
        );
        last = f;
    }
}
