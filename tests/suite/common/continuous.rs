//! Exact modes of a free-free chain of uniform Euler-Bernoulli beams joined end to end by a
//! translational spring k1 and a rotational spring k2 (the joint of eq. (17)), from the
//! continuous beam equation EI w'''' = rho A omega^2 w: a model class other than jointid's
//! finite elements, written here without any of its code.
//!
//! Field transfer over a beam of length l with beta^4 = rho A omega^2 / EI, state (w, theta,
//! M, V), M = EI w'', V = EI w''', through the Krylov functions S = (cosh z + cos z) / 2,
//! T = (sinh z + sin z) / 2, U = (cosh z - cos z) / 2, V = (sinh z - sin z) / 2, z = beta l:
//!
//! ```text
//!   w     = w0 S + theta0 T / b + M0 U / (EI b^2) + V0 V / (EI b^3)
//!   theta = w0 b V + theta0 S + M0 T / (EI b) + V0 U / (EI b^2)
//!   M     = w0 EI b^2 U + theta0 EI b V + M0 S + V0 T / b
//!   V     = w0 EI b^3 T + theta0 EI b^2 U + M0 b V + V0 S
//! ```
//!
//! At a joint M and V pass and the springs open w_right - w_left = -V / k1 and theta_right -
//! theta_left = M / k2 (from the virtual work of the springs); free ends have M = V = 0.
//! Natural frequencies are the roots of the 2 x 2 determinant of the far end's (M, V) in the
//! near end's (w0, theta0), found by a scan and bisection.

/// A uniform beam: length, EI, rho A.
#[derive(Debug, Clone, Copy)]
pub struct Span {
    pub length: f64,
    pub ei: f64,
    pub rho_a: f64,
}

/// A chain: spans and the joints (k1, k2) between them (none: one piece).
pub struct ExactChain {
    pub spans: Vec<Span>,
    pub joints: Vec<(f64, f64)>,
}

type State = [f64; 4];

fn field(s: &Span, x: f64, omega: f64, y: State) -> State {
    let b = (s.rho_a * omega * omega / s.ei).powf(0.25);
    let z = b * x;
    let (ch, c, sh, sn) = (z.cosh(), z.cos(), z.sinh(), z.sin());
    let (ks, kt, ku, kv) = (
        (ch + c) / 2.0,
        (sh + sn) / 2.0,
        (ch - c) / 2.0,
        (sh - sn) / 2.0,
    );
    let ei = s.ei;
    let [w, t, m, v] = y;
    [
        w * ks + t * kt / b + m * ku / (ei * b * b) + v * kv / (ei * b * b * b),
        w * b * kv + t * ks + m * kt / (ei * b) + v * ku / (ei * b * b),
        w * ei * b * b * ku + t * ei * b * kv + m * ks + v * kt / b,
        w * ei * b * b * b * kt + t * ei * b * b * ku + m * b * kv + v * ks,
    ]
}

impl ExactChain {
    /// The state at abscissa `x` from the near end's (w0, theta0), at `omega`.
    fn state_at(&self, x: f64, omega: f64, start: [f64; 2]) -> State {
        let mut y = [start[0], start[1], 0.0, 0.0];
        let mut at = 0.0;
        for (i, s) in self.spans.iter().enumerate() {
            if x <= at + s.length || i + 1 == self.spans.len() {
                return field(s, (x - at).max(0.0), omega, y);
            }
            y = field(s, s.length, omega, y);
            let (k1, k2) = self.joints[i];
            y[0] -= y[3] / k1;
            y[1] += y[2] / k2;
            at += s.length;
        }
        y
    }

    fn length(&self) -> f64 {
        self.spans.iter().map(|s| s.length).sum()
    }

    /// The far end's (M, V) for unit (w0, theta0) columns: the 2 x 2 matrix of the BCs.
    fn ends(&self, omega: f64) -> [[f64; 2]; 2] {
        let l = self.length();
        let a = self.state_at(l, omega, [1.0, 0.0]);
        let b = self.state_at(l, omega, [0.0, 1.0]);
        [[a[2], b[2]], [a[3], b[3]]]
    }

    fn determinant(&self, omega: f64) -> f64 {
        let e = self.ends(omega);
        e[0][0] * e[1][1] - e[0][1] * e[1][0]
    }

    /// The first `count` elastic natural frequencies, Hz, searched in steps of `step` Hz.
    pub fn frequencies(&self, count: usize, step: f64) -> Vec<f64> {
        let two_pi = 2.0 * std::f64::consts::PI;
        let d = |f: f64| self.determinant(two_pi * f);
        let mut out = Vec::new();
        let mut f = step;
        let mut last = d(f);
        while out.len() < count {
            let next = d(f + step);
            if last.signum() != next.signum() {
                let (mut a, mut b) = (f, f + step);
                for _ in 0..200 {
                    let m = 0.5 * (a + b);
                    if d(m).signum() == d(a).signum() {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                out.push(0.5 * (a + b));
            }
            f += step;
            last = next;
        }
        out
    }

    /// The mode shape w at the abscissae `xs` of the mode at `hz`, largest |w| 1.
    pub fn shape(&self, hz: f64, xs: &[f64]) -> Vec<f64> {
        let omega = 2.0 * std::f64::consts::PI * hz;
        let e = self.ends(omega);
        // The null vector of the 2 x 2: from its better-conditioned row.
        let row = if e[0][0].abs() + e[0][1].abs() > e[1][0].abs() + e[1][1].abs() {
            e[0]
        } else {
            e[1]
        };
        let start = [row[1], -row[0]];
        let w: Vec<f64> = xs
            .iter()
            .map(|&x| self.state_at(x, omega, start)[0])
            .collect();
        let peak = w
            .iter()
            .fold(0.0f64, |a, v| if v.abs() > a.abs() { *v } else { a });
        w.iter().map(|v| v / peak).collect()
    }
}

/// A normal deviate stream of its own (xorshift64* and Box-Muller): another noise generator
/// than jointid's.
pub struct Normal(u64);

impl Normal {
    pub fn new(seed: u64) -> Self {
        Normal(seed.max(1))
    }

    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let r = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        ((r >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    pub fn sample(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}

/// The measured-modes CSV (`mode,frequency_hz,x,dof,value`) of the first `count` modes of
/// `chain` at `xs`, each frequency times (1 + sf n) and each value plus ss n (n normal).
pub fn measured_csv(
    chain: &ExactChain,
    count: usize,
    xs: &[f64],
    noise: [f64; 2],
    seed: u64,
) -> String {
    let mut normal = Normal::new(seed);
    let mut csv = String::from("mode,frequency_hz,x,dof,value\n");
    for (r, f) in chain.frequencies(count, 1.0).into_iter().enumerate() {
        let f_meas = f * (1.0 + noise[0] * normal.sample());
        for (x, v) in xs.iter().zip(chain.shape(f, xs)) {
            let value = v + noise[1] * normal.sample();
            csv.push_str(&format!("{},{f_meas:.10},{x},w,{value:.10}\n", r + 1));
        }
    }
    csv
}
