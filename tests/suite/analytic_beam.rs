//! Golden tests of the beam model against the Euler-Bernoulli free-free beam.
//!
//! Reference: free-free uniform beam, omega_i = (beta_i L)^2 sqrt(EI / (rho A L^4)) with
//! beta L = 4.7300407, 7.8532046, 10.9956078, 14.1371655 (roots of cos(bL) cosh(bL) = 1;
//! Blevins, *Formulas for Natural Frequency and Mode Shape*, table 8-1).
//!
//! ```text
//!   free ============================================ free      (one beam, L = 0.5 m)
//!   free =================[k1,k2]==================== free      (two beams, joint at mid)
//! ```

use crate::common::{paper_model, steel_bar};
use jointid::modal::ModalSolution;
use jointid::model::{Chain, Joint};
use jointid::structure::Structure;

const BETA_L: [f64; 4] = [4.7300407, 7.8532046, 10.9956078, 14.1371655];

fn analytic_hz(length: f64, i: usize) -> f64 {
    let b = steel_bar(length, 1);
    let bl = BETA_L[i];
    bl * bl * (b.bending_stiffness() / (b.mass_per_length() * length.powi(4))).sqrt()
        / (2.0 * std::f64::consts::PI)
}

fn elastic_hz(model: &Structure, count: usize) -> Vec<f64> {
    let sol = ModalSolution::solve(&model.assemble()).unwrap();
    (2..2 + count).map(|i| sol.frequency_hz(i)).collect()
}

fn max_relative_error(elements: usize) -> f64 {
    let model = Chain::free(vec![steel_bar(0.5, elements)], vec![]).build();
    let fe = elastic_hz(&model, 4);
    (0..4)
        .map(|i| (fe[i] - analytic_hz(0.5, i)).abs() / analytic_hz(0.5, i))
        .fold(0.0, f64::max)
}

#[test]
fn single_free_free_beam_matches_analytic_frequencies_and_converges() {
    let meshes = [4, 8, 20, 40, 80];
    let errors: Vec<f64> = meshes.iter().map(|&e| max_relative_error(e)).collect();
    for (e, err) in meshes.iter().zip(&errors) {
        if *e >= 20 {
            assert!(*err < 1e-3, "{e} elements: error {err}");
        }
    }
    for w in errors.windows(2) {
        assert!(
            w[1] < w[0],
            "error must shrink as elements are added: {errors:?}"
        );
    }
    // Hermite cubics: frequency error of order h^4 (a factor ~16 per halving).
    assert!(errors[3] / errors[4] > 10.0, "{errors:?}");
}

#[test]
fn fine_meshes_keep_their_accuracy() {
    // Regression for the unscaled symmetric solver, which lost accuracy on the large entries
    // of L^-1 K L^-T of fine meshes.
    for elements in [200, 500] {
        let err = max_relative_error(elements);
        assert!(err < 1e-6, "{elements} elements: error {err}");
    }
}

#[test]
fn very_stiff_joint_gives_the_monoblock_beam() {
    let monoblock = Chain::free(vec![steel_bar(0.5, 20)], vec![]).build();
    let reference = elastic_hz(&monoblock, 4);
    let mut errors = Vec::new();
    for scale in [1e2, 1e3, 1e4] {
        // Multiples of the element stiffnesses 12 EI / l^3 and 4 EI / l of the 0.025 m elements.
        let b = steel_bar(0.25, 10);
        let l = b.element_length();
        let joint = Joint::identified(
            scale * 12.0 * b.bending_stiffness() / l.powi(3),
            scale * 4.0 * b.bending_stiffness() / l,
        );
        let chain =
            Chain::free(vec![steel_bar(0.25, 10), steel_bar(0.25, 10)], vec![joint]).build();
        let f = elastic_hz(&chain, 4);
        errors.push(
            (0..4)
                .map(|i| (f[i] - reference[i]).abs() / reference[i])
                .fold(0.0, f64::max),
        );
    }
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
    assert!(errors[2] < 1e-4, "{errors:?}");
}

#[test]
fn vanishing_joint_gives_the_two_separate_free_beams() {
    let chain = paper_model(1e-6, 1e-9);
    let sol = ModalSolution::solve(&chain.assemble()).unwrap();
    // Four rigid-body modes (two per beam), then the union of both beams' elastic modes.
    let lmax = sol.values()[sol.len() - 1];
    assert_eq!(
        sol.values()
            .iter()
            .filter(|l| l.abs() < 1e-12 * lmax)
            .count(),
        4
    );
    let mut separate: Vec<f64> = [steel_bar(0.2, 7), steel_bar(0.3, 10)]
        .into_iter()
        .flat_map(|b| elastic_hz(&Chain::free(vec![b], vec![]).build(), 4))
        .collect();
    separate.sort_by(f64::total_cmp);
    for (i, f) in separate.iter().take(6).enumerate() {
        let chain_f = sol.frequency_hz(4 + i);
        assert!((chain_f - f).abs() < 1e-6 * f, "mode {i}: {chain_f} vs {f}");
    }
}
