//! Golden tests of test set-ups: supports, point masses, stepped beams, sensors between nodes,
//! and the parameters a set-up may identify.
//!
//! Every support kind has its test here: clamped, pinned and guided against the textbook roots,
//! a spring support against the exact solution of a beam on end springs and in its limits
//! (k -> 0: free; k large: the rigid kind that holds the same motions).
//!
//! References, all independent of the finite-element code:
//! - clamped-free, pinned-pinned, clamped-pinned, guided-pinned and clamped-guided uniform
//!   Euler-Bernoulli beams: omega_i = (beta_i L)^2 sqrt(EI / (rho A L^4)), beta L the textbook
//!   roots (Blevins, *Formulas for Natural Frequency and Mode Shape*, table 8-1; a guided end is
//!   Blevins' "sliding" end, w' = w''' = 0: guided-pinned has beta_i L = (2i - 1) pi / 2 and
//!   clamped-guided the roots of tan(bL) + tanh(bL) = 0);
//! - a cantilever with a tip mass M: roots of
//!   1 + cos(bL) cosh(bL) + mu bL (cos(bL) sinh(bL) - sin(bL) cosh(bL)) = 0, mu = M / (rho A L)
//!   (the same reference, section 8.2), found here by bisection;
//! - a stepped free-free beam: the exact continuous solution, a transfer matrix of the state
//!   (w, theta, M = EI w'', Q = EI w''') through each uniform piece written with the Krylov
//!   functions S, T, U, V of beta x, frequencies where the end moment and shear vanish;
//! - a beam on grounded springs k_t (N/m), k_r (N m/rad) at x = 0, free at x = L: the same
//!   transfer matrix from the spring end's natural boundary conditions EI w'''(0) = -k_t w(0),
//!   EI w''(0) = k_r w'(0) (the variation of the strain energy plus the springs'); k -> 0 gives
//!   the free-free roots and k -> infinity the clamped-free ones of table 8-1, checked below;
//! - mode shapes of the cantilever: w(x) = cosh bx - cos bx - s (sinh bx - sin bx),
//!   s = (cosh bL + cos bL) / (sinh bL + sin bL).
//!
//! ```text
//!   |=========================== free        clamped-free (cantilever)
//!   ^===========================^            pinned-pinned
//!   |===========================^            clamped-pinned
//!   ]===========================^            guided-pinned (] a sliding clamp)
//!   |===========================[            clamped-guided
//!   |===========================[M]          cantilever with a tip mass
//!   ========[##########]=========            free-free, stepped in the middle
//!   $===========================             on springs k_t, k_r at x = 0, free at L
//! ```

use crate::common::steel_bar;
use jointid::identify::{Identifier, Settings, Weighting};
use jointid::modal::ModalSolution;
use jointid::model::chain::{PointMass, Support, SupportKind};
use jointid::model::{Beam, Chain, Joint};
use jointid::simulate::exact_modes;
use jointid::structure::{Direction, Observation, Section, Structure};

const LENGTH: f64 = 0.5;

fn section() -> Section {
    steel_bar(1.0, 1).section()
}

fn omega_of_beta_l(bl: f64) -> f64 {
    let s = section();
    bl * bl * (s.bending_stiffness() / (s.mass_per_length() * LENGTH.powi(4))).sqrt()
}

fn support(x: f64, kind: SupportKind) -> Support {
    Support {
        x,
        kind,
        identify: [false; 2],
    }
}

fn beam_with(supports: Vec<Support>, elements: usize) -> Chain {
    let mut chain = Chain::free(vec![steel_bar(LENGTH, elements)], vec![]);
    chain.supports = supports;
    chain
}

/// The first `count` elastic angular frequencies of a structure.
fn elastic(structure: &Structure, count: usize) -> Vec<f64> {
    let modal = ModalSolution::solve(&structure.assemble()).unwrap();
    (structure.rigid..structure.rigid + count)
        .map(|i| modal.values()[i].sqrt())
        .collect()
}

fn worst_error(found: &[f64], reference: &[f64]) -> f64 {
    found
        .iter()
        .zip(reference)
        .map(|(f, r)| (f - r).abs() / r)
        .fold(0.0, f64::max)
}

#[test]
fn supported_beams_match_the_textbook_roots_with_h4_convergence() {
    let pi = std::f64::consts::PI;
    let cases: [(&str, Vec<Support>, [f64; 5]); 5] = [
        (
            "clamped-free",
            vec![support(0.0, SupportKind::Clamped)],
            [
                1.8751040687,
                4.6940911330,
                7.8547574382,
                10.9955407349,
                14.1371683910,
            ],
        ),
        (
            "pinned-pinned",
            vec![
                support(0.0, SupportKind::Pinned),
                support(LENGTH, SupportKind::Pinned),
            ],
            [pi, 2.0 * pi, 3.0 * pi, 4.0 * pi, 5.0 * pi],
        ),
        (
            "clamped-pinned",
            vec![
                support(0.0, SupportKind::Clamped),
                support(LENGTH, SupportKind::Pinned),
            ],
            [
                3.9266023120,
                7.0685827547,
                10.2101761242,
                13.3517687778,
                16.4933614313,
            ],
        ),
        (
            "guided-pinned",
            vec![
                support(0.0, SupportKind::Guided),
                support(LENGTH, SupportKind::Pinned),
            ],
            [0.5 * pi, 1.5 * pi, 2.5 * pi, 3.5 * pi, 4.5 * pi],
        ),
        (
            "clamped-guided",
            vec![
                support(0.0, SupportKind::Clamped),
                support(LENGTH, SupportKind::Guided),
            ],
            [
                2.3650203724,
                5.4978039190,
                8.6393798287,
                11.7809724510,
                14.9225651046,
            ],
        ),
    ];
    for (name, supports, roots) in cases {
        let reference: Vec<f64> = roots.iter().map(|&b| omega_of_beta_l(b)).collect();
        let errors: Vec<f64> = [20, 40, 80]
            .iter()
            .map(|&elements| {
                let s = beam_with(supports.clone(), elements).build();
                assert_eq!(s.rigid, 0, "{name}");
                worst_error(&elastic(&s, 5), &reference)
            })
            .collect();
        assert!(errors[2] < 2e-6, "{name}: {errors:?}");
        // Hermite cubics: about 16 per halving of h.
        assert!(errors[0] / errors[1] > 12.0, "{name}: {errors:?}");
        assert!(errors[1] / errors[2] > 12.0, "{name}: {errors:?}");
    }
}

#[test]
fn rigid_body_modes_are_counted_from_the_supports() {
    for (supports, rigid) in [
        (vec![], 2),
        (vec![support(0.25, SupportKind::Pinned)], 1),
        (vec![support(0.25, SupportKind::Guided)], 1),
        (vec![support(0.0, SupportKind::Clamped)], 0),
    ] {
        let s = beam_with(supports, 10).build();
        assert_eq!(s.rigid, rigid);
        let modal = ModalSolution::solve(&s.assemble()).unwrap();
        let top = modal.values()[modal.len() - 1];
        let zero = modal
            .values()
            .iter()
            .filter(|l| l.abs() < 1e-10 * top)
            .count();
        assert_eq!(zero, rigid, "the eigensolution agrees");
    }
}

/// The lowest root above `from` of `f` by scanning and bisection.
fn root(f: impl Fn(f64) -> f64, from: f64, step: f64) -> f64 {
    let (mut a, mut fa) = (from, f(from));
    loop {
        let b = a + step;
        let fb = f(b);
        if fa.signum() != fb.signum() {
            let (mut lo, mut hi, mut flo) = (a, b, fa);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                let fm = f(mid);
                if fm.signum() == flo.signum() {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            return 0.5 * (lo + hi);
        }
        a = b;
        fa = fb;
    }
}

#[test]
fn cantilever_with_a_tip_mass_matches_the_frequency_equation() {
    let beam_mass = section().mass_per_length() * LENGTH;
    for mu in [0.1, 0.5, 2.0] {
        let equation = |bl: f64| {
            1.0 + bl.cos() * bl.cosh() + mu * bl * (bl.cos() * bl.sinh() - bl.sin() * bl.cosh())
        };
        let mut roots = vec![root(equation, 0.05, 0.01)];
        for _ in 0..2 {
            let last = *roots.last().unwrap();
            roots.push(root(equation, last + 0.05, 0.01));
        }
        let reference: Vec<f64> = roots.iter().map(|&b| omega_of_beta_l(b)).collect();
        let mut chain = beam_with(vec![support(0.0, SupportKind::Clamped)], 40);
        chain.masses = vec![PointMass {
            x: LENGTH,
            mass: mu * beam_mass,
            rotary_inertia: 0.0,
            spring: None,
            identify: false,
        }];
        let err = worst_error(&elastic(&chain.build(), 3), &reference);
        assert!(err < 1e-6, "mu {mu}: error {err}");
    }
}

/// Angular frequencies where a beam of uniform `pieces` (length, section), held at x = 0 by
/// grounded springs `[k_t, k_r]` (N/m, N m/rad; zero: a free end), has zero moment and shear at
/// its far end: the exact continuous solution, above 10 rad/s.
fn free_far_end(pieces: &[(f64, Section)], springs: [f64; 2], count: usize) -> Vec<f64> {
    let [k_t, k_r] = springs;
    let determinant = |omega: f64| {
        // State (w, theta, M, Q) at x = 0 with Q = -k_t w, M = k_r theta: two free columns
        // (w0, theta0).
        let mut columns = [[1.0, 0.0, 0.0, -k_t], [0.0, 1.0, k_r, 0.0]];
        for (l, s) in pieces {
            let ei = s.bending_stiffness();
            let b = (s.mass_per_length() * omega * omega / ei).powf(0.25);
            let x = b * l;
            let (ch, sh, c, sn) = (x.cosh(), x.sinh(), x.cos(), x.sin());
            let (ss, t, u, v) = (
                0.5 * (ch + c),
                0.5 * (sh + sn),
                0.5 * (ch - c),
                0.5 * (sh - sn),
            );
            for z in &mut columns {
                let [w, th, m, q] = *z;
                *z = [
                    w * ss + th * t / b + m * u / (ei * b * b) + q * v / (ei * b * b * b),
                    w * b * v + th * ss + m * t / (ei * b) + q * u / (ei * b * b),
                    ei * (w * b * b * u + th * b * v) + m * ss + q * t / b,
                    ei * (w * b * b * b * t + th * b * b * u) + m * b * v + q * ss,
                ];
            }
        }
        columns[0][2] * columns[1][3] - columns[0][3] * columns[1][2]
    };
    let mut out = Vec::new();
    let mut from = 10.0;
    while out.len() < count {
        let w = root(determinant, from, 5.0);
        out.push(w);
        from = w + 1.0;
    }
    out
}

#[test]
fn a_stepped_beam_matches_the_exact_stepped_solution() {
    let thin = section();
    // A lap: twice the thickness over 0.20-0.30 m, so twice the area and eight times I.
    let thick = Section {
        area: 2.0 * thin.area,
        second_moment: 8.0 * thin.second_moment,
        ..thin
    };
    let reference = free_far_end(&[(0.2, thin), (0.1, thick), (0.2, thin)], [0.0; 2], 4);
    let errors: Vec<f64> = [20, 40, 80]
        .iter()
        .map(|&elements| {
            let mut beam = Beam::uniform(LENGTH, elements, thin);
            beam.segments = vec![jointid::model::chain::Segment {
                from: 0.2,
                to: 0.3,
                section: thick,
            }];
            let s = Chain::free(vec![beam], vec![]).build();
            worst_error(&elastic(&s, 4), &reference)
        })
        .collect();
    assert!(errors[2] < 1e-6, "{errors:?}");
    assert!(errors[0] / errors[1] > 12.0, "{errors:?}");
}

/// Spring stiffnesses `[k_t, k_r]` (N/m, N m/rad) of relative stiffnesses
/// `[k_t L^3 / EI, k_r L / EI]`.
fn springs_of(relative: [f64; 2]) -> [f64; 2] {
    let ei = section().bending_stiffness();
    [relative[0] * ei / LENGTH.powi(3), relative[1] * ei / LENGTH]
}

fn spring(springs: [f64; 2]) -> SupportKind {
    SupportKind::Spring {
        translational: springs[0],
        rotational: springs[1],
    }
}

/// Asserts that each gap is `factor` times smaller than the one before, within 20%.
fn assert_falls_by(gaps: &[f64], factor: f64, what: &str) {
    for pair in gaps.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!(
            (0.8 * factor..1.2 * factor).contains(&ratio),
            "{what}: {gaps:?}"
        );
    }
}

#[test]
fn a_beam_on_a_spring_support_matches_the_exact_solution() {
    let bar = [(LENGTH, section())];
    // The reference in its limits: free-free and clamped-free (Blevins table 8-1).
    let free: Vec<f64> = [4.7300407449, 7.8532046241, 10.9956078380]
        .iter()
        .map(|&b| omega_of_beta_l(b))
        .collect();
    let clamped: Vec<f64> = [1.8751040687, 4.6940911330, 7.8547574382]
        .iter()
        .map(|&b| omega_of_beta_l(b))
        .collect();
    let loose = free_far_end(&bar, [0.0; 2], 3);
    assert!(worst_error(&loose, &free) < 1e-10, "{loose:?}");
    let stiff = free_far_end(&bar, springs_of([1e14; 2]), 3);
    assert!(worst_error(&stiff, &clamped) < 1e-10, "{stiff:?}");
    // Springs that move the modes far from both limits: on w, on theta, on both.
    for relative in [[10.0, 0.0], [0.0, 3.0], [100.0, 5.0], [1e4, 1e3]] {
        let springs = springs_of(relative);
        let reference = free_far_end(&bar, springs, 5);
        let s = beam_with(vec![support(0.0, spring(springs))], 80).build();
        // A lone spring on one motion leaves one rigid mode, at zero (below the reference's
        // range, which starts at 10 rad/s).
        assert_eq!(s.rigid, 2 - relative.iter().filter(|&&k| k > 0.0).count());
        let err = worst_error(&elastic(&s, 5), &reference);
        assert!(err < 2e-6, "{relative:?}: {err}");
    }
}

#[test]
fn a_spring_support_tends_to_free_when_soft_and_to_the_rigid_kind_when_stiff() {
    // Soft: the elastic modes of the free-free beam; the two spring modes go to zero; the
    // gap falls as k (a hundredfold per step).
    let free = elastic(&Chain::free(vec![steel_bar(LENGTH, 40)], vec![]).build(), 4);
    let soft: Vec<Vec<f64>> = [1e-2, 1e-4, 1e-6]
        .iter()
        .map(|&k| {
            elastic(
                &beam_with(vec![support(0.0, spring(springs_of([k; 2])))], 40).build(),
                6,
            )
        })
        .collect();
    let gaps: Vec<f64> = soft.iter().map(|m| worst_error(&m[2..], &free)).collect();
    assert!(gaps[2] < 1e-6, "soft: {gaps:?}");
    assert_falls_by(&gaps, 100.0, "soft");
    assert!(soft[2][1] < 1e-2 * soft[2][2], "{:?}", soft[2]);
    // Stiff: the kind that holds the same motions, the far end pinned; the gap falls as 1/k
    // (k_t L^3 / EI from 1e5, k_r L / EI from 1e2: stiffer, the round-off of the eigenvalues
    // grows as k).
    let pinned_end = support(LENGTH, SupportKind::Pinned);
    for (holds, rigid) in [
        ([1.0, 0.0], SupportKind::Pinned),
        ([0.0, 1.0], SupportKind::Guided),
        ([1.0, 1.0], SupportKind::Clamped),
    ] {
        let reference = elastic(
            &beam_with(vec![support(0.0, rigid), pinned_end.clone()], 40).build(),
            4,
        );
        let gaps: Vec<f64> = [1.0, 10.0, 100.0]
            .iter()
            .map(|&k| {
                let springs = springs_of([holds[0] * 1e5 * k, holds[1] * 1e2 * k]);
                let s = beam_with(vec![support(0.0, spring(springs)), pinned_end.clone()], 40);
                worst_error(&elastic(&s.build(), 4), &reference)
            })
            .collect();
        let name = rigid.name();
        assert!(gaps[2] < 3e-4, "{name}: {gaps:?}");
        assert_falls_by(&gaps, 10.0, name);
    }
}

#[test]
fn a_sensor_between_nodes_converges_to_the_analytic_cantilever_shape() {
    let bl = 1.8751040687;
    let b = bl / LENGTH;
    let ratio = (bl.cosh() + bl.cos()) / (bl.sinh() + bl.sin());
    let shape = |x: f64| (b * x).cosh() - (b * x).cos() - ratio * ((b * x).sinh() - (b * x).sin());
    // Sensors off the node grid of every mesh below; the tip reads the scale.
    let xs = [0.0371, 0.1234, 0.3333, LENGTH];
    let errors: Vec<f64> = [5, 10, 20]
        .iter()
        .map(|&elements| {
            let s = beam_with(vec![support(0.0, SupportKind::Clamped)], elements).build();
            let points: Vec<Observation> = xs
                .iter()
                .map(|&x| s.dofs.at_x(x, Direction::W).unwrap())
                .collect();
            let modal = ModalSolution::solve(&s.assemble()).unwrap();
            let values: Vec<f64> = points
                .iter()
                .map(|p| p.read_column(modal.vectors(), 0))
                .collect();
            let tip = values[3];
            xs.iter()
                .zip(&values)
                .map(|(&x, v)| (v / tip - shape(x) / shape(LENGTH)).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    assert!(errors[2] < 1e-6, "{errors:?}");
    assert!(
        errors[0] / errors[1] > 8.0 && errors[1] / errors[2] > 8.0,
        "{errors:?}"
    );
}

/// A clamped test with a joint whose k1 is held fixed, a flexible end spring and a point mass,
/// both identified.
fn clamped_test() -> Chain {
    let mut joint = Joint::identified(5e5, 2e3);
    joint.roles[0] = jointid::structure::Role::Fixed;
    let mut chain = Chain::free(vec![steel_bar(0.25, 8), steel_bar(0.25, 8)], vec![joint]);
    let mut end = support(
        LENGTH,
        SupportKind::Spring {
            translational: 2e5,
            rotational: 0.0,
        },
    );
    end.identify = [true, false];
    chain.supports = vec![support(0.0, SupportKind::Clamped), end];
    chain.masses = vec![PointMass {
        x: 0.35,
        mass: 0.3,
        rotary_inertia: 2e-4,
        spring: None,
        identify: true,
    }];
    chain
}

#[test]
fn identified_set_up_parameters_have_exact_eigenvalue_sensitivities() {
    let s = clamped_test().build();
    let names: Vec<String> = s.identified().iter().map(|p| p.name.clone()).collect();
    assert_eq!(names, ["k2", "support1.translational", "mass0.m"]);
    let modal = ModalSolution::solve(&s.assemble()).unwrap();
    let y = modal.vectors();
    let top = modal.values()[modal.len() - 1];
    // Eigenvalues carry an absolute error of about eps * lambda_max (1e-3 here): the step is
    // large enough for the difference quotient to stand above it, small enough for its
    // truncation error (h^2 relative) to stay below the tolerance.
    for (i, p) in s.identified().iter().enumerate() {
        let h = 3e-3 * p.value;
        let at = |sign: f64| {
            let mut delta = vec![0.0; 3];
            delta[i] = sign * h;
            ModalSolution::solve(&s.with_delta(&delta).assemble()).unwrap()
        };
        let (plus, minus) = (at(1.0), at(-1.0));
        for mode in 0..4 {
            let column: Vec<f64> = (0..y.nrows()).map(|d| y[(d, mode)]).collect();
            let lambda = modal.values()[mode];
            let analytic =
                p.stiffness.form(&column, &column) - lambda * p.mass.form(&column, &column);
            let fd = (plus.values()[mode] - minus.values()[mode]) / (2.0 * h);
            assert!(
                (analytic - fd).abs() < 3e-5 * analytic.abs() + 100.0 * f64::EPSILON * top / h,
                "{}: mode {mode}: {analytic} vs {fd}",
                p.name
            );
        }
    }
}

#[test]
fn a_clamped_set_up_is_identified_exactly_from_noise_free_modes() {
    let s = clamped_test().build();
    let delta = [4e2, -3e4, 0.05];
    let truth = s.with_delta(&delta);
    let points: Vec<Observation> = (0..s.dof_count())
        .map(|d| Observation::dof(&s.dofs, d))
        .collect();
    let measured = exact_modes(
        &ModalSolution::solve(&truth.assemble()).unwrap(),
        0,
        &[1, 2, 3, 4],
        &points,
    );
    let modal = ModalSolution::solve(&s.assemble()).unwrap();
    let n = s.dof_count();
    let id = Identifier::for_structure(
        &s,
        &modal,
        Settings {
            n,
            m: 6,
            weighting: Weighting::Inverse,
        },
    )
    .unwrap();
    // The floor is the eigenvector accuracy of the dense solution (1e-9 to 1e-8) times
    // cond(W S_r), up to 1e2 on these modes.
    for mode in measured.modes() {
        let z = id.identify(mode).unwrap().relative.unwrap();
        for ((p, zi), d) in id.parameters().iter().zip(z).zip(delta) {
            let found = p.value * zi;
            assert!(
                (found - d).abs() < 1e-6 * d.abs(),
                "mode {}: {} found {found}, introduced {d}",
                mode.mode,
                p.name
            );
        }
    }
}

#[test]
fn the_unesp_bert_set_up_is_a_model_file_without_tricks() {
    let s = jointid::model::from_path(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/models/unesp-bert.toml"
    )))
    .unwrap();
    assert_eq!(s.rigid, 0);
    let labels: Vec<&str> = s.sensors.iter().map(|o| o.label.as_str()).collect();
    assert_eq!(labels, ["acc1", "acc2", "acc3", "acc4"]);
    // Every sensor and the stinger sit on nodes; the lap is a segment on either side of the
    // joint at its centre.
    assert!(s.sensors.iter().all(|o| o.terms.len() == 1));
    assert!(
        s.dofs
            .dofs()
            .iter()
            .any(|d| (d.position[0] - 0.085).abs() < 1e-12)
    );
    assert_eq!(s.sites.joints.len(), 1);
    assert!((s.sites.joints[0].x - 0.25).abs() < 1e-12);
    assert_eq!(s.sites.joints[0].sections[0].area, 3.2258e-4);
    let names: Vec<String> = s.identified().iter().map(|p| p.name.clone()).collect();
    assert_eq!(names, ["k1", "k2"]);
}

#[test]
fn a_parameter_a_mode_cannot_see_is_held_instead_of_failing_the_mode() {
    // A joint on a pinned support: its transversal spring k1 connects two held DOFs and no
    // mode can see it; k2 is seen by every mode.
    let mut chain = Chain::free(
        vec![steel_bar(0.25, 8), steel_bar(0.25, 8)],
        vec![Joint::identified(1e7, 5e3)],
    );
    chain.supports = vec![
        support(0.0, SupportKind::Clamped),
        support(0.25, SupportKind::Pinned),
    ];
    let s = chain.build();
    let truth = s.with_delta(&[0.0, 1e3]);
    let points: Vec<Observation> = (0..s.dof_count())
        .map(|d| Observation::dof(&s.dofs, d))
        .collect();
    let measured = exact_modes(
        &ModalSolution::solve(&truth.assemble()).unwrap(),
        0,
        &[1, 2, 3],
        &points,
    );
    let modal = ModalSolution::solve(&s.assemble()).unwrap();
    let settings = Settings {
        n: s.dof_count(),
        m: 5,
        weighting: Weighting::Inverse,
    };
    let id = Identifier::for_structure(&s, &modal, settings).unwrap();
    for mode in measured.modes() {
        let s_r = id.basis_index(mode.mode).unwrap();
        let all = id.identify_paired(mode, s_r).unwrap();
        assert!(
            all.relative.is_err(),
            "k1 is invisible: S_r is rank deficient"
        );
        assert_eq!(all.resolution[0], 0.0);
        let auto = id
            .identify_selected(mode, s_r, jointid::identify::Selection::Auto)
            .unwrap();
        assert_eq!(auto.solved, vec![false, true]);
        let z = auto.relative.unwrap();
        assert_eq!(z[0], 0.0);
        assert!(
            (5e3 * z[1] - 1e3).abs() < 1e-6 * 1e3,
            "mode {}: {}",
            mode.mode,
            5e3 * z[1]
        );
    }
}

/// The frequencies (Hz) of the modes `jointid simulate` writes for a two-beam chain (0.35 m
/// each, 70 elements, a stiff point joint) with a 20 g sensor at `x` (none: no mass), in `dir`.
fn chain_with_a_sensor_at(dir: &std::path::Path, x: f64, mass: Option<f64>) -> Vec<f64> {
    let mass = mass.map_or(String::new(), |m| format!("mass = {m}\n"));
    chain_with(
        dir,
        &format!("s{x}-{}", mass.len()),
        &format!("[[sensor]]\nx = {x}\nlabel = \"a2\"\n{mass}"),
    )
}

/// The arguments of `jointid simulate` of the lowest four modes of `model` into `out`.
fn simulate_four<'a>(model: &'a std::path::Path, out: &'a std::path::Path) -> [&'a str; 7] {
    let path = |p: &'a std::path::Path| p.to_str().expect("a UTF-8 path");
    [
        "simulate",
        "--model",
        path(model),
        "--modes",
        "4",
        "--out",
        path(out),
    ]
}

/// The model file of the chain of [`chain_with`] with `extra`.
fn chain_text(extra: &str) -> String {
    let beam = "[[beam]]\nlength = 0.35\nelements = 70\nyoungs_modulus = 2.0e11\n\
        density = 7850\narea = 3.2258e-4\nsecond_moment = 4.3358e-9\n\n";
    format!(
        "{beam}{beam}[[joint]]\nk1 = 1.0e9\nk2 = 1.0e5\n\n[[sensor]]\nx = 0\nlabel = \"a1\"\n\n\
         {extra}\n[[sensor]]\nx = 0.7\nlabel = \"a3\"\n"
    )
}

/// The frequencies (Hz) of the modes `jointid simulate` writes for the chain of
/// [`chain_with_a_sensor_at`] with sensors at its ends and `extra` (model-file text), the
/// files named by `name` in `dir`.
fn chain_with(dir: &std::path::Path, name: &str, extra: &str) -> Vec<f64> {
    let text = chain_text(extra);
    let (model, out) = (
        dir.join(format!("m{name}.toml")),
        dir.join(format!("m{name}.csv")),
    );
    std::fs::write(&model, text).unwrap();
    crate::common::jointid_ok(&simulate_four(&model, &out));
    let mut frequencies: Vec<f64> = Vec::new();
    for line in std::fs::read_to_string(&out).unwrap().lines().skip(1) {
        let f: f64 = line.split(',').nth(1).unwrap().parse().unwrap();
        if frequencies.last() != Some(&f) {
            frequencies.push(f);
        }
    }
    frequencies
}

/// A sensor 5 um from a joint on a 5 mm mesh: as a node of its own it made a 5 um element, a
/// billion times stiffer than its neighbours, and no eigensolution (the model refused). It is
/// read between nodes instead (module `mesh`), and its 20 g mass is spread by the same
/// interpolation: the frequencies are those of the sensor on the joint's node within 2e-7
/// (the mass moved 5 um), and the mass counts (mode 3 is 1.2% lower than without it).
#[test]
fn a_sensor_a_hair_from_a_joint_is_read_between_nodes_with_its_mass() {
    let dir = crate::common::scratch("setups", "sensor-near-joint");
    let near = chain_with_a_sensor_at(&dir, 0.35 - 5e-6, Some(0.02));
    let on = chain_with_a_sensor_at(&dir, 0.35, Some(0.02));
    let bare = chain_with_a_sensor_at(&dir, 0.35 - 5e-6, None);
    assert_eq!(near.len(), 4);
    for ((a, b), c) in near.iter().zip(&on).zip(&bare) {
        assert!((a / b - 1.0).abs() < 2e-7, "{near:?} {on:?}");
        assert!(c >= a, "{bare:?} {near:?}");
    }
    assert!(bare[2] / near[2] - 1.0 > 0.01, "{bare:?} {near:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The frequencies of the chain of [`chain_with`] with `extra(x)` at x = `node` - d for d =
/// 0, 5, 10 and 20 um (d = 0: on the node there; else between nodes, module `mesh`), checked to
/// move smoothly with d: the parabola through d = 0, 5 and 10 um gives the frequency at 20 um
/// within 0.1% of its change, and 5 um moves no mode by more than 1e-4.
fn smooth_beside(
    dir: &std::path::Path,
    name: &str,
    node: f64,
    extra: impl Fn(f64) -> String,
) -> Vec<Vec<f64>> {
    let at: Vec<Vec<f64>> = [0.0, 5e-6, 10e-6, 20e-6]
        .into_iter()
        .map(|d| chain_with(dir, &format!("{name}{d}"), &extra(node - d)))
        .collect();
    for r in 0..4 {
        let f: Vec<f64> = at.iter().map(|one| one[r]).collect();
        assert!((f[1] / f[0] - 1.0).abs() < 1e-4, "{name}: {at:?}");
        // The parabola through d = 0, 5, 10 um at 20 um: 3 f0 - 8 f5 + 6 f10.
        let predicted = 3.0 * f[0] - 8.0 * f[1] + 6.0 * f[2];
        // Measured: at most 1.8e-4 of the change (the springs' mode 2); a node treated apart
        // from its neighbourhood would miss by a fraction of order 1.
        assert!(
            (predicted - f[3]).abs() <= 1e-3 * (f[3] - f[0]).abs() + 2e-12 * f[0],
            "{name}, mode {}: {f:?}",
            r + 1
        );
    }
    at
}

/// A point mass (50 g, rotary inertia 2e-5 kg m^2) 5 um from a joint on a 5 mm mesh: as a
/// node of its own it made a 5 um element and no eigensolution. It is carried between nodes by
/// the elements' interpolation (module `mesh`), and the frequencies move smoothly with its
/// distance from the joint's node ([`smooth_beside`]; 5 um moves mode 3 by 2.6e-7: the
/// slope of the mode there, not an error). The mass and its rotary inertia count: without them
/// mode 3 is more than 1% higher, without the rotary inertia alone higher too.
#[test]
fn a_point_mass_a_hair_from_a_joint_is_carried_between_nodes() {
    let dir = crate::common::scratch("setups", "mass-near-joint");
    let mass = |j: &'static str| move |x: f64| format!("[[mass]]\nx = {x}\nmass = 0.05\n{j}");
    let at = smooth_beside(&dir, "p", 0.35, mass("rotary_inertia = 2e-5\n"));
    let translation = chain_with(&dir, "t", &mass("")(0.35 - 5e-6));
    let bare = chain_with(&dir, "bare", "");
    for r in 0..4 {
        assert!((at[1][r] / at[0][r] - 1.0).abs() < 1e-6, "{at:?}");
        assert!(translation[r] >= at[1][r] && bare[r] >= translation[r]);
    }
    assert!(bare[2] / at[1][2] - 1.0 > 0.01, "{bare:?} {at:?}");
    assert!(
        translation
            .iter()
            .zip(&at[1])
            .any(|(c, a)| c / a - 1.0 > 1e-4),
        "{translation:?} {at:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A support of springs (1e5 N/m, 50 N m/rad) 5 um from the chain's end: spread between nodes
/// as k c c^T (module `mesh`), its frequencies smooth in its distance from the end's node
/// ([`smooth_beside`]; at a joint's abscissa it springs both beams' nodes, so the joint is not
/// the place to compare), and it counts. A pinned support 5 um from a joint holds a node,
/// cannot be spread, and is refused with the field, the distance and what to do (it was "no
/// eigensolution").
#[test]
fn a_support_a_hair_from_a_joint_is_spread_when_sprung_and_refused_when_rigid() {
    let dir = crate::common::scratch("setups", "support-near-joint");
    let spring = |x: f64| {
        format!("[[support]]\nx = {x}\nkind = \"spring\"\ntranslational = 1e5\nrotational = 50\n")
    };
    let at = smooth_beside(&dir, "s", 0.7, spring);
    let bare = chain_with(&dir, "bare", "");
    assert!((at[1][0] / bare[0] - 1.0).abs() > 1e-3, "{at:?} {bare:?}");
    let model = dir.join("pinned.toml");
    let pinned = "[[support]]\nx = 0.349995\nkind = \"pinned\"\n";
    std::fs::write(&model, chain_text(pinned)).unwrap();
    let out = dir.join("pinned.csv");
    let run = crate::common::jointid(&simulate_four(&model, &out));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("support[0].x = 0.349995") && stderr.contains("put it at x = 0.35"),
        "{stderr}"
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
