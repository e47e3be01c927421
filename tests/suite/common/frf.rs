//! FRFs of lumped systems solved directly, H(w) = (K - w^2 M + i w C)^-1 e_ref, one complex
//! LU per line, for the tests of `jointid::extract`. Nothing here calls the extractor's code:
//! the true modes come from the construction of the system (prescribed modes) or from an
//! eigensolution (the chain, the state-space form), never from a modal sum of the extractor.
#![allow(dead_code)]

use std::f64::consts::PI;

use faer::linalg::solvers::Solve;
use faer::{Mat, Side, c64};
use jointid::extract::{FrfSet, Quantity};

/// A lumped system and its true modes.
pub struct System {
    pub k: Mat<f64>,
    pub m: Mat<f64>,
    pub c: Mat<f64>,
    /// Undamped natural frequencies (Hz), ascending.
    pub frequencies_hz: Vec<f64>,
    /// Modal damping ratios (proportional damping; for a non-proportional system, of the poles).
    pub damping: Vec<f64>,
    /// Mass-normalised real modes, one column per mode.
    pub shapes: Mat<f64>,
}

/// A deterministic stream: SplitMix64, Box-Muller normals.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    pub fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * PI * v).cos()
    }
}

/// A system with prescribed undamped frequencies and modal damping ratios: masses in [1, 2] kg,
/// a random mass-orthonormal basis Phi = M^-1/2 Q (Q from the QR of a random matrix, R with a
/// positive diagonal),
/// K = M Phi W^2 Phi^T M, C = M Phi diag(2 zeta w) Phi^T M.
pub fn prescribed(frequencies_hz: &[f64], damping: &[f64], seed: u64) -> System {
    let n = frequencies_hz.len();
    let mut rng = Rng::new(seed);
    let masses: Vec<f64> = (0..n).map(|_| 1.0 + rng.uniform()).collect();
    // Row by row, so that another implementation can draw the same matrix.
    let mut g = Mat::<f64>::zeros(n, n);
    for i in 0..n {
        for j in 0..n {
            g[(i, j)] = rng.normal();
        }
    }
    // The QR with a positive diagonal of R is unique: Q does not depend on the QR routine.
    let qr = g.qr();
    let q = qr.compute_Q();
    let sign: Vec<f64> = (0..n).map(|j| qr.R()[(j, j)].signum()).collect();
    let shapes = Mat::from_fn(n, n, |i, r| sign[r] * q[(i, r)] / masses[i].sqrt());
    let build = |diag: &dyn Fn(usize) -> f64| {
        Mat::from_fn(n, n, |i, j| {
            masses[i]
                * masses[j]
                * (0..n)
                    .map(|r| shapes[(i, r)] * diag(r) * shapes[(j, r)])
                    .sum::<f64>()
        })
    };
    let w: Vec<f64> = frequencies_hz.iter().map(|f| 2.0 * PI * f).collect();
    let k = build(&|r| w[r] * w[r]);
    let c = build(&|r| 2.0 * damping[r] * w[r]);
    let m = Mat::from_fn(n, n, |i, j| if i == j { masses[i] } else { 0.0 });
    System {
        k,
        m,
        c,
        frequencies_hz: frequencies_hz.to_vec(),
        damping: damping.to_vec(),
        shapes,
    }
}

/// A fixed-free spring-mass chain with Rayleigh damping C = a M + b K; the true modes from the
/// symmetric eigenproblem of M^-1/2 K M^-1/2, zeta_r = a / (2 w_r) + b w_r / 2.
pub fn chain(masses: &[f64], springs: &[f64], a: f64, b: f64) -> System {
    let n = masses.len();
    let mut k = Mat::<f64>::zeros(n, n);
    for (e, &s) in springs.iter().enumerate() {
        // Spring e joins DOF e - 1 (ground for e = 0) and DOF e.
        k[(e, e)] += s;
        if e > 0 {
            k[(e - 1, e - 1)] += s;
            k[(e - 1, e)] -= s;
            k[(e, e - 1)] -= s;
        }
    }
    let m = Mat::from_fn(n, n, |i, j| if i == j { masses[i] } else { 0.0 });
    let scaled = Mat::from_fn(n, n, |i, j| k[(i, j)] / (masses[i] * masses[j]).sqrt());
    let evd = scaled.self_adjoint_eigen(Side::Lower).unwrap();
    let w: Vec<f64> = (0..n).map(|r| evd.S()[r].sqrt()).collect();
    let shapes = Mat::from_fn(n, n, |i, r| evd.U()[(i, r)] / masses[i].sqrt());
    let c = Mat::from_fn(n, n, |i, j| a * m[(i, j)] + b * k[(i, j)]);
    System {
        frequencies_hz: w.iter().map(|w| w / (2.0 * PI)).collect(),
        damping: w.iter().map(|w| a / (2.0 * w) + b * w / 2.0).collect(),
        k,
        m,
        c,
        shapes,
    }
}

/// The poles (positive imaginary part, ascending) and displacement parts of the eigenvectors
/// of the state-space matrix [[0, I], [-M^-1 K, -M^-1 C]] (for non-proportional damping).
pub fn state_space_modes(sys: &System) -> (Vec<c64>, Vec<Vec<c64>>) {
    let n = sys.k.nrows();
    let minv: Vec<f64> = (0..n).map(|i| 1.0 / sys.m[(i, i)]).collect();
    let a = Mat::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
        (true, true) => 0.0,
        (true, false) => f64::from(u8::from(j - n == i)),
        (false, true) => -minv[i - n] * sys.k[(i - n, j)],
        (false, false) => -minv[i - n] * sys.c[(i - n, j - n)],
    });
    let evd = a.eigen().unwrap();
    let mut modes: Vec<(c64, Vec<c64>)> = (0..2 * n)
        .filter(|&r| evd.S()[r].im > 0.0)
        .map(|r| (evd.S()[r], (0..n).map(|i| evd.U()[(i, r)]).collect()))
        .collect();
    modes.sort_by(|a, b| a.0.im.total_cmp(&b.0.im));
    modes.into_iter().unzip()
}

/// Receptance of every DOF to a unit force at `reference`, on `frequencies_hz`, by a complex
/// LU solve per line. `[dof][line]`.
pub fn receptance(sys: &System, reference: usize, frequencies_hz: &[f64]) -> Vec<Vec<c64>> {
    let n = sys.k.nrows();
    let mut out = vec![Vec::with_capacity(frequencies_hz.len()); n];
    let rhs = Mat::from_fn(n, 1, |i, _| {
        c64::new(f64::from(u8::from(i == reference)), 0.0)
    });
    for &f in frequencies_hz {
        let w = 2.0 * PI * f;
        let z = Mat::from_fn(n, n, |i, j| {
            c64::new(sys.k[(i, j)] - w * w * sys.m[(i, j)], w * sys.c[(i, j)])
        });
        let x = z.partial_piv_lu().solve(&rhs);
        for (i, series) in out.iter_mut().enumerate() {
            series.push(x[(i, 0)]);
        }
    }
    out
}

/// Evenly spaced lines 0, df, ..., up to f_max.
pub fn lines(df: f64, f_max: f64) -> Vec<f64> {
    let n = (f_max / df).round() as usize;
    (0..=n).map(|k| k as f64 * df).collect()
}

/// The FRF set of quantity `q` at the `responses` DOFs: (i w)^p times the receptance.
pub fn frf_set(
    receptance: &[Vec<c64>],
    frequencies_hz: &[f64],
    responses: &[usize],
    q: Quantity,
) -> FrfSet {
    let p = match q {
        Quantity::Displacement => 0,
        Quantity::Velocity => 1,
        Quantity::Acceleration => 2,
    };
    FrfSet {
        frequencies_hz: frequencies_hz.to_vec(),
        responses: responses
            .iter()
            .map(|&d| {
                receptance[d]
                    .iter()
                    .zip(frequencies_hz)
                    .map(|(h, f)| h * c64::new(0.0, 2.0 * PI * f).powi(p))
                    .collect()
            })
            .collect(),
        coherence: None,
        quantity: q,
    }
}

/// Adds complex Gaussian noise of standard deviation `relative` |H| + `floor` max|H| (per
/// response) to every value, from a fixed seed.
pub fn add_noise(set: &mut FrfSet, relative: f64, floor: f64, seed: u64) {
    let mut rng = Rng::new(seed);
    for h in &mut set.responses {
        let peak = h.iter().map(|v| v.norm()).fold(0.0, f64::max);
        for v in h.iter_mut() {
            let sigma = relative * v.norm() + floor * peak;
            let e = c64::new(rng.normal(), rng.normal()) * (sigma / 2f64.sqrt());
            *v += e;
        }
    }
}

/// MAC of two real vectors.
pub fn mac(a: &[f64], b: &[f64]) -> f64 {
    let ab: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let aa: f64 = a.iter().map(|x| x * x).sum();
    let bb: f64 = b.iter().map(|x| x * x).sum();
    ab * ab / (aa * bb)
}

/// MAC of two complex vectors.
pub fn mac_complex(a: &[c64], b: &[c64]) -> f64 {
    let ab: c64 = a.iter().zip(b).map(|(x, y)| x.conj() * y).sum();
    let aa: f64 = a.iter().map(|x| x.norm_sqr()).sum();
    let bb: f64 = b.iter().map(|x| x.norm_sqr()).sum();
    ab.norm_sqr() / (aa * bb)
}

/// True real mode r at the response DOFs.
pub fn shape_at(sys: &System, r: usize, responses: &[usize]) -> Vec<f64> {
    responses.iter().map(|&d| sys.shapes[(d, r)]).collect()
}
