//! The paper's per-mode identification of the joint parameters.
//!
//! For each measured mode r (eq. (4)-(16)):
//! 1. Y, Lambda: the first `n` eigenpairs of the nominal model, rigid-body modes included in
//!    the count (eq. (2)); mode r pairs with basis index s_r = r + (rigid-body modes)
//!    (1-based; 0-based `r - 1 + rigid` here).
//! 2. g_r: least squares of Y~ g = y~ over the identified DOFs, eq. (14)/(15)
//!    ([`projection`]).
//! 3. S_r, b_r: eq. (10)-(12) on the `m` retained rows nearest to s_r ([`system`],
//!    [`weighting`]).
//! 4. Z_r: weighted least squares (13) by QR ([`wls`]); the correction of parameter i is
//!    Delta p_i = p_i Z_r(i) (eq. (8)).
//!
//! [`run`] identifies a set of measured modes, each its own way (this system, else its
//! parameter from its frequency alone, [`frequency_only`]), as `jointid identify` and the
//! Python package run it.
//!
//! Layer 4 (identification; see the crate docs): may import the layers below: [`crate::stats`],
//! [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`], [`crate::modal`],
//! [`crate::model`], [`crate::measured`], [`crate::extract`].

pub mod frequency_error;
pub mod frequency_only;
pub mod identifiability;
pub mod projection;
pub mod propagation;
pub mod reach;
pub mod root;
pub mod run;
pub mod system;
pub mod weighting;
pub mod wls;

use faer::Mat;

pub use identifiability::{MIN_RESOLUTION, Selection};
pub use projection::{ProjectionError, Projector};
pub use system::{LANES, Lanes, ModeSystem};
pub use weighting::{RetainedRows, Weighting};
pub use wls::RankDeficient;

use crate::input::SettingError;
use crate::measured::MeasuredMode;
use crate::modal::{ModalSolution, lambda_to_hz};
use crate::structure::{Parameter, Structure, observe};

/// The method's settings: basis size n, retained equations m, weighting W.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Settings {
    /// Number of calculated eigenpairs in the sub-basis Y, rigid-body modes included.
    pub n: usize,
    /// Number of retained sensitivity equations, q <= m <= n - rigid-body modes.
    pub m: usize,
    /// Weighting of the retained equations (eq. (16)).
    pub weighting: Weighting,
}

impl Settings {
    /// The settings for `structure`, with n checked against it (from its rigid-body modes + 1
    /// to its DOFs). m depends on the parameters identified too: [`Identifier::new`] checks it.
    pub fn new(
        n: usize,
        m: usize,
        weighting: Weighting,
        structure: &Structure,
    ) -> Result<Settings, SettingError> {
        check_basis_size(n, structure.rigid, structure.dof_count())?;
        Ok(Settings { n, m, weighting })
    }

    /// m against `q` identified parameters and the basis's deformable rows (as
    /// [`Identifier::new`] checks it): a check that needs no eigensolution, to make before one.
    pub fn check_equations(&self, q: usize, rigid: usize) -> Result<(), SettingError> {
        check_equations(self.m, q, self.n, rigid)
    }
}

/// n must leave one deformable mode and not exceed the `dofs` pairs available.
fn check_basis_size(n: usize, rigid: usize, dofs: usize) -> Result<(), SettingError> {
    if n <= rigid || n > dofs {
        return Err(SettingError::new(
            "n",
            n,
            format!(
                "it must be from {} to {dofs} (the model's DOFs), rigid-body modes included",
                rigid + 1
            ),
        ));
    }
    Ok(())
}

/// m must give at least one equation per parameter (`q` of them) and use only the deformable
/// rows of a basis of `n` pairs, `rigid` of them rigid-body modes.
fn check_equations(m: usize, q: usize, n: usize, rigid: usize) -> Result<(), SettingError> {
    if m < q {
        return Err(SettingError::new(
            "m",
            m,
            format!("it must be at least the number of parameters q = {q}"),
        ));
    }
    if m > n - rigid {
        return Err(SettingError::new(
            "m",
            m,
            format!(
                "a basis of n = {n} has only {} deformable rows (rigid-body rows are never retained)",
                n - rigid
            ),
        ));
    }
    Ok(())
}

/// The basis index (0-based) that measured mode `mode` pairs with in a basis of `n` pairs,
/// `rigid` of them rigid-body modes, or why none (no eigensolution needed: a check to make
/// before one).
pub fn basis_index(mode: usize, rigid: usize, n: usize) -> Result<usize, IdentifyError> {
    match (mode - 1).checked_add(rigid) {
        Some(s) if s < n => Ok(s),
        _ => Err(IdentifyError::ModeBeyondBasis {
            mode,
            index: (mode - 1).saturating_add(rigid).saturating_add(1),
            rigid,
            n,
        }),
    }
}

/// Settings or data the method cannot work with.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IdentifyError {
    /// n outside what the model offers, or m outside what the basis and the parameters allow
    /// (the setting is named).
    #[error(transparent)]
    Setting(#[from] SettingError),
    /// Nothing to identify.
    #[error(
        "the model identifies no parameter (no joint, or every parameter held fixed): there is nothing to identify"
    )]
    NoParameters,
    /// The mode's own basis vector is not in the sub-basis.
    #[error(
        "mode {mode} pairs with basis index {index} (1-based, after {rigid} rigid-body modes), beyond n = {n}: increase n"
    )]
    ModeBeyondBasis {
        /// Mode r.
        mode: usize,
        /// s_r, 1-based.
        index: usize,
        /// Rigid-body modes.
        rigid: usize,
        /// Basis size n.
        n: usize,
    },
    /// The measured shape cannot be projected on the sub-basis.
    #[error("mode {mode}: {cause}")]
    Projection {
        /// Mode r.
        mode: usize,
        /// Why.
        cause: ProjectionError,
    },
}

/// The nominal model's side of the method, shared by every mode: sub-basis, eigenvalues,
/// parameters and settings.
#[derive(Debug, Clone)]
pub struct Identifier {
    y: Mat<f64>,
    lambdas: Vec<f64>,
    params: Vec<Parameter>,
    settings: Settings,
    rigid: usize,
}

/// The identification of one mode.
#[derive(Debug, Clone)]
pub struct ModeOutcome {
    /// Mode r.
    pub mode: usize,
    /// Basis index s_r, 0-based.
    pub basis_index: usize,
    /// Measured frequency, Hz.
    pub frequency_measured_hz: f64,
    /// Frequency of the paired nominal mode, Hz.
    pub frequency_model_hz: f64,
    /// Coefficients g_r of the measured shape on the sub-basis.
    pub g: Vec<f64>,
    /// Condition number of W S_r (infinite when rank deficient).
    pub condition: f64,
    /// Z_r = Delta p_i / p_i (0 for a parameter held on this mode), or the rank of a
    /// rank-deficient S_r.
    pub relative: Result<Vec<f64>, RankDeficient>,
    /// The resolution of every parameter on this mode, all parameters together
    /// ([`identifiability::resolution`]).
    pub resolution: Vec<f64>,
    /// Whether each parameter was identified on this mode (false: held at its value).
    pub solved: Vec<bool>,
    /// Standard deviation of each Z_r(i) from the data's own standard errors
    /// ([`propagation::std_of`]), when the data carry them and every parameter was solved.
    pub std: Option<Vec<f64>>,
}

impl Identifier {
    /// The identification of the paper on a structure: its identified parameters (k1, k2 of
    /// every joint of a chain, less those held fixed), sub-basis from its modal solution.
    pub fn for_structure(
        structure: &Structure,
        modal: &ModalSolution,
        settings: Settings,
    ) -> Result<Self, IdentifyError> {
        Self::new(modal, structure.identified(), structure.rigid, settings)
    }

    /// General form: any parameters with their derivatives, `rigid` rigid-body modes first.
    pub fn new(
        modal: &ModalSolution,
        params: Vec<Parameter>,
        rigid: usize,
        settings: Settings,
    ) -> Result<Self, IdentifyError> {
        let Settings { n, m, .. } = settings;
        if params.is_empty() {
            return Err(IdentifyError::NoParameters);
        }
        check_basis_size(n, rigid, modal.len())?;
        check_equations(m, params.len(), n, rigid)?;
        let (y, lambdas) = modal.sub_basis(n);
        Ok(Self {
            y,
            lambdas,
            params,
            settings,
            rigid,
        })
    }

    /// The sub-basis Y (N x n).
    pub fn basis(&self) -> &Mat<f64> {
        &self.y
    }

    /// Its eigenvalues.
    pub fn lambdas(&self) -> &[f64] {
        &self.lambdas
    }

    /// The parameters p_i.
    pub fn parameters(&self) -> &[Parameter] {
        &self.params
    }

    /// The settings.
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// Basis index s_r (0-based) of deformable mode r >= 1, checked to lie in the sub-basis.
    pub fn basis_index(&self, mode: usize) -> Result<usize, IdentifyError> {
        basis_index(mode, self.rigid, self.settings.n)
    }

    /// The retained, weighted system of the mode paired with basis index `s_r`.
    pub fn mode_system(&self, s_r: usize) -> ModeSystem {
        let Settings { n, m, weighting } = self.settings;
        let rows = RetainedRows::select(n, self.rigid, s_r, m, weighting);
        ModeSystem::new(&self.y, &self.lambdas, &self.params, rows)
    }

    /// Identifies the parameter corrections on one measured mode.
    pub fn identify(&self, measured: &MeasuredMode) -> Result<ModeOutcome, IdentifyError> {
        self.identify_paired(measured, self.basis_index(measured.mode)?)
    }

    /// As [`Identifier::identify`], the mode paired with basis index `s_r` (0-based, below n)
    /// instead of r + rigid-body modes: for a mode paired by MAC.
    pub fn identify_paired(
        &self,
        measured: &MeasuredMode,
        s_r: usize,
    ) -> Result<ModeOutcome, IdentifyError> {
        self.identify_selected(measured, s_r, Selection::All)
    }

    /// As [`Identifier::identify_paired`], identifying the parameters `selection` keeps.
    pub fn identify_selected(
        &self,
        measured: &MeasuredMode,
        s_r: usize,
        selection: Selection,
    ) -> Result<ModeOutcome, IdentifyError> {
        let mode = measured.mode;
        if s_r >= self.settings.n {
            return Err(IdentifyError::ModeBeyondBasis {
                mode,
                index: s_r + 1,
                rigid: self.rigid,
                n: self.settings.n,
            });
        }
        let yt = observe(&self.y, &measured.points);
        // The shape in units of its largest magnitude (a power of two: exact), its standard
        // errors with it: g, W S_r and W b_r are linear in the shape, so the corrections are
        // unchanged, and the resolution, cond(W S_r) and the propagated errors no longer
        // depend on the shape's unit (no sum of squares overflows or underflows).
        let unit = shape_unit(measured.peak());
        let values: Vec<f64> = measured.values.iter().map(|v| v / unit).collect();
        let sigma = measured
            .value_sigmas()
            .map(|s| s.into_iter().map(|s| s / unit).collect::<Vec<f64>>());
        let projector = match &sigma {
            Some(sigma) => Projector::weighted(&yt, sigma),
            None => Projector::new(&yt),
        }
        .map_err(|cause| IdentifyError::Projection { mode, cause })?;
        let mut g = vec![0.0; self.settings.n];
        projector.project(&values, &mut g);
        let system = self.mode_system(s_r);
        let (m, q) = (system.m(), system.q());
        let mut ws = vec![0.0; m * q];
        let mut wb = vec![0.0; m];
        system.assemble(&g, measured.lambda(), &mut ws, &mut wb);
        let all: Vec<usize> = (0..q).collect();
        let resolution = identifiability::resolution(&ws, m, &all);
        let kept = identifiability::choose(&ws, m, q, selection);
        let mut solved = vec![false; q];
        kept.iter().for_each(|&i| solved[i] = true);
        let mut sub: Vec<f64> = kept
            .iter()
            .flat_map(|&i| ws[i * m..(i + 1) * m].iter().copied())
            .collect();
        let k = kept.len();
        let condition = if k == 0 {
            f64::INFINITY
        } else {
            condition_number(&sub, m, k)
        };
        let mut zk = vec![0.0; k];
        let relative = if k == 0 {
            Err(RankDeficient { rank: 0 })
        } else {
            wls::solve_in_place(&mut sub, &mut wb, m, k, &mut zk).map(|()| {
                let mut z = vec![0.0; q];
                kept.iter().zip(&zk).for_each(|(&i, &v)| z[i] = v);
                z
            })
        };
        let std = match (&sigma, measured.frequency_std, &relative) {
            (Some(sigma), Some(f_std), Ok(_)) if solved.iter().all(|&s| s) => {
                let ones = vec![1.0; q];
                propagation::jacobian(&projector, &system, &values, measured.lambda()).map(|jac| {
                    let variances: Vec<f64> = sigma.iter().map(|s| s * s).collect();
                    let f = f_std / measured.frequency_hz;
                    propagation::std_of(&jac, &variances, measured.lambda(), &ones, f * f)
                })
            }
            _ => None,
        };
        g.iter_mut().for_each(|v| *v *= unit);
        Ok(ModeOutcome {
            mode,
            basis_index: s_r,
            std,
            frequency_measured_hz: measured.frequency_hz,
            frequency_model_hz: lambda_to_hz(self.lambdas[s_r]),
            g,
            condition: if relative.is_ok() {
                condition
            } else {
                f64::INFINITY
            },
            relative,
            resolution,
            solved,
        })
    }
}

/// The power of two nearest `peak`, a shape's largest magnitude (1 for a zero or non-finite
/// peak): the unit a shape is divided by before the identification works on it, exactly.
pub fn shape_unit(peak: f64) -> f64 {
    if peak.is_finite() && peak > 0.0 {
        2f64.powi((peak.log2().round() as i32).clamp(-1022, 1023))
    } else {
        1.0
    }
}

/// 2-norm condition number of the column-major `m x q` matrix `a` (infinite when singular).
pub fn condition_number(a: &[f64], m: usize, q: usize) -> f64 {
    let mat = Mat::from_fn(m, q, |i, j| a[j * m + i]);
    match mat.singular_values() {
        Ok(s) if s[q - 1] > 0.0 => s[0] / s[q - 1],
        _ => f64::INFINITY,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::fixtures::paper_model;

    #[test]
    fn settings_are_checked_where_they_are_set() {
        let model = paper_model(1e7, 1e4);
        let ok = Settings::new(10, 5, Weighting::Inverse, &model).unwrap();
        assert_eq!((ok.n, ok.m), (10, 5));
        for n in [2, 39] {
            let e = Settings::new(n, 5, Weighting::Inverse, &model).unwrap_err();
            assert_eq!(e.setting, "n");
            assert_eq!(
                e.to_string(),
                format!(
                    "n = {n} is invalid: it must be from 3 to 38 (the model's DOFs), rigid-body modes included"
                )
            );
        }
        let modal = ModalSolution::solve(&model.assemble()).unwrap();
        let too_many = Settings::new(10, 9, Weighting::Inverse, &model).unwrap();
        match Identifier::for_structure(&model, &modal, too_many) {
            Err(IdentifyError::Setting(e)) => assert_eq!(
                e.with_name("--m"),
                "--m 9 is invalid: a basis of n = 10 has only 8 deformable rows (rigid-body rows are never retained)"
            ),
            other => panic!("{:?}", other.err()),
        }
    }
}
