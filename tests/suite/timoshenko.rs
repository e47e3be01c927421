//! Timoshenko beams (`shear_factor` in the model file) against the exact frequencies of the
//! continuous Timoshenko beam: free-free, clamped-free and pinned-pinned, slender to stubby
//! (L/h from 100 to 5), the first six elastic modes within 1e-4 (400 elements at L/h = 5). Where
//! shear matters the error falls as h^2 (see the last test), so a stubby beam needs a fine mesh.
//!
//! References, independent of the finite-element code (another method, no element): the
//! Timoshenko equations, harmonic at omega, as a first-order system in the state
//! y = (w, psi, M, V), psi the section's rotation, M = EI psi', V = kappa G A (w' - psi):
//!
//! ```text
//!   w' = psi + V / (kappa G A),  psi' = M / EI,  M' = -V - rho I omega^2 psi,  V' = -rho A omega^2 w
//! ```
//!
//! y(L) = expm(A L) y(0); an end's conditions (free: M = V = 0; clamped: w = psi = 0; pinned:
//! w = M = 0) leave a 2x2 determinant whose roots in omega, bracketed on a fine grid and
//! bisected, are the frequencies. Pinned-pinned also has a closed form (psi = Psi cos(k x),
//! w = W sin(k x), k = n pi / L: a quadratic in omega^2), which checks the transfer matrix.
//!
//! ```text
//!   free ===================== free
//!   |========================= free     clamped-free
//!   ^=========================^          pinned-pinned
//! ```

use jointid::modal::ModalSolution;
use jointid::model::chain::{Support, SupportKind};
use jointid::model::{Beam, Chain, chain_from_toml};
use jointid::structure::{Section, Shear, Structure};

const LENGTH: f64 = 1.0;
const E: f64 = 2.1e11;
const RHO: f64 = 7850.0;
const KAPPA: f64 = 5.0 / 6.0;
const G: f64 = E / (2.0 * 1.3);
const WIDTH: f64 = 0.03;

/// A steel bar of depth `h`, Timoshenko when `shear`.
fn section(h: f64, shear: bool) -> Section {
    Section {
        youngs_modulus: E,
        density: RHO,
        area: WIDTH * h,
        second_moment: WIDTH * h * h * h / 12.0,
        shear: shear.then_some(Shear {
            factor: KAPPA,
            modulus: G,
        }),
    }
}

#[derive(Clone, Copy, PartialEq)]
enum End {
    Free,
    Clamped,
    Pinned,
}

fn chain(s: Section, elements: usize, ends: [End; 2]) -> Structure {
    let mut chain = Chain::free(vec![Beam::uniform(LENGTH, elements, s)], vec![]);
    for (x, end) in [0.0, LENGTH].into_iter().zip(ends) {
        let kind = match end {
            End::Free => continue,
            End::Clamped => SupportKind::Clamped,
            End::Pinned => SupportKind::Pinned,
        };
        chain.supports.push(Support {
            x,
            kind,
            identify: [false; 2],
        });
    }
    chain.build()
}

/// The first `count` elastic angular frequencies of the finite-element model.
fn fe(s: Section, elements: usize, ends: [End; 2], count: usize) -> Vec<f64> {
    let structure = chain(s, elements, ends);
    let modal = ModalSolution::solve(&structure.assemble()).unwrap();
    (structure.rigid..structure.rigid + count)
        .map(|i| modal.values()[i].sqrt())
        .collect()
}

type M4 = [[f64; 4]; 4];

fn mul(a: &M4, b: &M4) -> M4 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// expm(a) by scaling and squaring of a Taylor series.
fn expm(a: &M4) -> M4 {
    let norm = a
        .iter()
        .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let squarings = norm.log2().ceil().max(0.0) as i32 + 4;
    let scale = 0.5f64.powi(squarings);
    let x: M4 = a.map(|r| r.map(|v| v * scale));
    let mut sum: M4 = std::array::from_fn(|i| std::array::from_fn(|j| f64::from(i == j)));
    let mut term = sum;
    for n in 1..=24 {
        term = mul(&term, &x).map(|r| r.map(|v| v / f64::from(n)));
        for i in 0..4 {
            for j in 0..4 {
                sum[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..squarings {
        sum = mul(&sum, &sum);
    }
    sum
}

/// The transfer matrix of the bar over `length` at angular frequency `omega`.
fn transfer(s: &Section, length: f64, omega: f64) -> M4 {
    let ei = s.bending_stiffness();
    // No shear rigidity: no shear flexibility (a Rayleigh beam).
    let flexibility = s.shear_rigidity().map_or(0.0, |ga| 1.0 / ga);
    let w2 = omega * omega;
    let a: M4 = [
        [0.0, 1.0, 0.0, flexibility],
        [0.0, 0.0, 1.0 / ei, 0.0],
        [0.0, -s.density * s.second_moment * w2, 0.0, -1.0],
        [-s.density * s.area * w2, 0.0, 0.0, 0.0],
    ];
    expm(&a.map(|r| r.map(|v| v * length)))
}

/// The state components an end leaves free, and those it holds to zero.
fn unknown_and_zero(end: End) -> ([usize; 2], [usize; 2]) {
    match end {
        End::Free => ([0, 1], [2, 3]),
        End::Clamped => ([2, 3], [0, 1]),
        End::Pinned => ([1, 3], [0, 2]),
    }
}

/// The boundary determinant at `omega`: the start's free components carried to the end's held.
fn determinant(s: &Section, length: f64, ends: [End; 2], omega: f64) -> f64 {
    let t = transfer(s, length, omega);
    let (free, _) = unknown_and_zero(ends[0]);
    let (_, held) = unknown_and_zero(ends[1]);
    let m = |i: usize, j: usize| t[held[i]][free[j]];
    m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0)
}

/// The first `count` roots of the boundary determinant of a bar of `LENGTH` above a small
/// fraction of the fundamental, bracketed on a grid of `step` and bisected.
fn exact(s: &Section, ends: [End; 2], count: usize, step: f64) -> Vec<f64> {
    exact_over(s, LENGTH, ends, count, step)
}

/// As [`exact`], for a bar of `length`.
fn exact_over(s: &Section, length: f64, ends: [End; 2], count: usize, step: f64) -> Vec<f64> {
    let mut roots = Vec::new();
    let (mut lo, mut f_lo) = (step, determinant(s, length, ends, step));
    while roots.len() < count {
        let hi = lo + step;
        let f_hi = determinant(s, length, ends, hi);
        if f_lo.signum() != f_hi.signum() {
            let (mut a, mut b, mut fa) = (lo, hi, f_lo);
            for _ in 0..200 {
                let mid = 0.5 * (a + b);
                let fm = determinant(s, length, ends, mid);
                if fm.signum() == fa.signum() {
                    (a, fa) = (mid, fm);
                } else {
                    b = mid;
                }
                if b - a <= 1e-14 * b {
                    break;
                }
            }
            roots.push(0.5 * (a + b));
        }
        (lo, f_lo) = (hi, f_hi);
    }
    roots
}

/// The pinned-pinned closed form: the lower root in omega^2 of
/// (rho A w2 - GA k^2)(rho I w2 - EI k^2 - GA) - (GA k)^2 = 0, k = n pi / L.
fn pinned_pinned(s: &Section, n: usize) -> f64 {
    let (ei, ga) = (s.bending_stiffness(), s.shear_rigidity().unwrap());
    let (ra, ri) = (s.density * s.area, s.density * s.second_moment);
    let k = n as f64 * std::f64::consts::PI / LENGTH;
    let a = ra * ri;
    let b = -(ra * (ei * k * k + ga) + ri * ga * k * k);
    let c = ga * k * k * ei * k * k;
    let w2 = (-b - (b * b - 4.0 * a * c).sqrt()) / (2.0 * a);
    w2.sqrt()
}

fn worst(found: &[f64], reference: &[f64]) -> f64 {
    found
        .iter()
        .zip(reference)
        .map(|(f, r)| (f - r).abs() / r)
        .fold(0.0, f64::max)
}

#[test]
fn the_transfer_matrix_reproduces_the_pinned_pinned_closed_form() {
    for slenderness in [5.0, 20.0, 100.0] {
        let s = section(LENGTH / slenderness, true);
        let closed: Vec<f64> = (1..=6).map(|n| pinned_pinned(&s, n)).collect();
        let roots = exact(&s, [End::Pinned, End::Pinned], 6, closed[0] / 50.0);
        assert!(worst(&roots, &closed) < 1e-9, "{roots:?} vs {closed:?}");
    }
}

#[test]
fn timoshenko_beams_match_the_exact_frequencies_from_slender_to_stubby() {
    let ends = [
        [End::Free, End::Free],
        [End::Clamped, End::Free],
        [End::Pinned, End::Pinned],
    ];
    // Elements enough for each: the error falls as h^2, with a constant that grows with the
    // share of shear in the modes.
    for (slenderness, elements) in [(5.0, 400), (10.0, 300), (20.0, 200), (100.0, 60)] {
        let s = section(LENGTH / slenderness, true);
        let step = pinned_pinned(&s, 1) / 50.0;
        for pair in ends {
            let reference = exact(&s, pair, 6, step);
            let found = fe(s, elements, pair, 6);
            let err = worst(&found, &reference);
            assert!(
                err < 1e-4,
                "L/h {slenderness}: error {err:e}: {found:?} vs {reference:?}"
            );
        }
    }
}

#[test]
fn shear_lowers_the_frequencies_more_the_stubbier_the_beam_and_vanishes_when_slender() {
    // The Euler-Bernoulli limit: the relative drop of the sixth free-free frequency shrinks
    // as (h / L)^2, a factor 100 from L/h = 100 to 1000, and is below 1e-3 at L/h = 1000.
    let drop = |slenderness: f64| {
        let h = LENGTH / slenderness;
        let ends = [End::Free, End::Free];
        let eb = fe(section(h, false), 60, ends, 6);
        let ti = fe(section(h, true), 60, ends, 6);
        (eb[5] - ti[5]) / eb[5]
    };
    let (stubby, slender, thin) = (drop(10.0), drop(100.0), drop(1000.0));
    assert!(stubby > 0.05, "{stubby}");
    assert!(slender > 0.0 && slender < stubby, "{slender}");
    assert!((slender / thin - 100.0).abs() < 5.0, "{slender} / {thin}");
    assert!(thin < 1e-3, "{thin}");
}

#[test]
fn the_error_falls_fourfold_per_halving_of_the_elements() {
    // The element's shear strain is constant along it: under inertia loads (not statically,
    // where the element is exact) that is a first-order error in the shear strain, so the
    // frequencies converge as h^2 where shear matters (L/h = 5, the sixth mode).
    let s = section(LENGTH / 5.0, true);
    let ends = [End::Free, End::Free];
    let reference = exact(&s, ends, 6, pinned_pinned(&s, 1) / 50.0);
    let error = |elements| worst(&fe(s, elements, ends, 6), &reference);
    let (coarse, fine) = (error(60), error(120));
    assert!((coarse / fine - 4.0).abs() < 0.2, "{coarse} / {fine}");
}

#[test]
fn the_layers_of_a_lap_are_timoshenko_beams_too() {
    // A half-lap over the whole of a stubby bar (0.6 m, 50 mm deep) whose interface holds the
    // layers together across (k_n large) and lets them slip (k_s ~ 0): each layer bends about
    // its own centroid, so the pair is one Timoshenko beam with the layers' summed EI (a
    // quarter of the bar's), shear rigidity (the bar's kappa G A) and rotary inertia (a
    // quarter of the bar's rho I). Its free-free frequencies from the transfer matrix; the
    // layers' axial modes and their slip are left out.
    let (b, h, length) = (0.02, 0.05, 0.6);
    let beam = |l: f64| {
        format!(
            "[[beam]]\nlength = {l}\nyoungs_modulus = {E}\ndensity = {RHO}\narea = {}\nsecond_moment = {}\nshear_factor = {KAPPA}\nshear_modulus = {G}\n",
            b * h,
            b * h * h * h / 12.0
        )
    };
    let text = format!(
        "[mesh]\nelement_length = 0.005\n{}{}[[joint]]\nkind = \"lap\"\n[joint.lap]\nlength = {length}\nlayers = \"half\"\nk_n = 1e15\nk_s = 1e-3\n",
        beam(length / 2.0),
        beam(length / 2.0)
    );
    let model = chain_from_toml(&text, std::path::Path::new("m.toml"))
        .unwrap()
        .build();
    let modal = ModalSolution::solve(&model.assemble()).unwrap();
    let y = modal.vectors();
    let share = |s: usize, d: jointid::structure::Direction| -> f64 {
        (0..model.dof_count())
            .filter(|&i| model.dofs.get(i).direction == d)
            .map(|i| y[(i, s)].powi(2))
            .sum()
    };
    use jointid::structure::Direction;
    // Above 1 rad/s: the layers' slip on k_s ~ 0 is a near-rigid motion.
    let fe: Vec<f64> = (model.rigid..modal.len())
        .filter(|&s| modal.values()[s].sqrt() > 1.0)
        .filter(|&s| share(s, Direction::W) > share(s, Direction::X))
        .take(4)
        .map(|s| modal.values()[s].sqrt())
        .collect();
    let pair = Section {
        youngs_modulus: E,
        density: RHO,
        area: b * h,
        second_moment: b * h * h * h / 48.0,
        shear: Some(Shear {
            factor: KAPPA,
            modulus: G,
        }),
    };
    let reference = exact_over(&pair, length, [End::Free, End::Free], 4, 20.0);
    let err = worst(&fe, &reference);
    assert!(err < 1e-4, "error {err:e}: {fe:?} vs {reference:?}");
    // The same layers declared Euler-Bernoulli miss by more than shear's share.
    let eb = exact_over(
        &pair.euler_bernoulli(),
        length,
        [End::Free, End::Free],
        1,
        20.0,
    );
    assert!(eb.is_empty() || (eb[0] - reference[0]).abs() / reference[0] > 1e-3);
}
