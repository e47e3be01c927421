//! The measured-modes model: the identified eigensolutions y_r^m, lambda_r^m of the paper,
//! with partially identified shapes (eq. (15)): for every mode its number, frequency and the
//! values read at some measured points, each point an [`Observation`] of the structure (a DOF,
//! or a position between nodes read through the element shape functions).
//!
//! May import: the structure and the modal conversions, nothing of the formats.

use crate::structure::Observation;

/// Largest mode number a file may give.
pub const MAX_MODE: usize = 100_000;
/// Largest frequency a file may give, Hz (an acoustic or ultrasonic test stays far below).
pub const MAX_FREQUENCY_HZ: f64 = 1e9;

/// One measured mode: frequency and the values at its measured points.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredMode {
    /// Deformable mode number r, 1-based (1 = the first elastic mode).
    pub mode: usize,
    /// Measured natural frequency f_r, Hz.
    pub frequency_hz: f64,
    /// Measured points, in the order of [`point_order`].
    pub points: Vec<Observation>,
    /// Shape components at `points`.
    pub values: Vec<f64>,
    /// Modal damping ratio, when the data give it (extracted modes).
    pub damping_ratio: Option<f64>,
    /// Modal phase collinearity of the complex shape it comes from (1: a real mode).
    pub mpc: Option<f64>,
    /// Standard error of the frequency, Hz, when the data give it.
    pub frequency_std: Option<f64>,
    /// Standard error of the damping ratio, when the data give it.
    pub damping_std: Option<f64>,
    /// Standard error of each shape component (same normalisation as `values`, aligned with
    /// `points`), when the data give them.
    pub value_std: Option<Vec<f64>>,
}

impl MeasuredMode {
    /// A mode measured at `points` with `values`, in any order: sorted by [`point_order`].
    pub fn new(mode: usize, frequency_hz: f64, points: Vec<Observation>, values: Vec<f64>) -> Self {
        let mut pairs: Vec<(Observation, f64)> = points.into_iter().zip(values).collect();
        pairs.sort_by(|a, b| point_order(&a.0, &b.0));
        let (points, values) = pairs.into_iter().unzip();
        Self {
            mode,
            frequency_hz,
            points,
            values,
            damping_ratio: None,
            mpc: None,
            frequency_std: None,
            damping_std: None,
            value_std: None,
        }
    }

    /// A mode whose shape rows (point, value, standard error) come in any order: sorted by
    /// [`point_order`], the standard errors kept with their points.
    pub fn with_value_std(
        mode: usize,
        frequency_hz: f64,
        rows: Vec<(Observation, f64, f64)>,
    ) -> Self {
        let mut rows = rows;
        rows.sort_by(|a, b| point_order(&a.0, &b.0));
        let std = rows.iter().map(|r| r.2).collect();
        let (points, values) = rows.into_iter().map(|(o, v, _)| (o, v)).unzip();
        let mut m = Self::new(mode, frequency_hz, points, values);
        m.value_std = Some(std);
        m
    }

    /// The standard errors of the shape components as standard deviations of a likelihood,
    /// when the mode carries them: a zero one (the peak that normalises an extracted mode,
    /// exact by definition, its error carried by the others) raised to the mode's smallest
    /// positive one, so that no component weighs infinitely; None when every one is 0.
    pub fn value_sigmas(&self) -> Option<Vec<f64>> {
        let std = self.value_std.as_ref()?;
        let least = std
            .iter()
            .copied()
            .filter(|s| *s > 0.0)
            .fold(f64::INFINITY, f64::min);
        least.is_finite().then(|| {
            std.iter()
                .map(|&s| if s > 0.0 { s } else { least })
                .collect()
        })
    }

    /// Whether the data carry their own uncertainty: a frequency and shape standard errors.
    pub fn has_std(&self) -> bool {
        self.frequency_std.is_some() && self.value_std.is_some()
    }

    /// The largest magnitude of its components (the unit of the shape noise's floor).
    pub fn peak(&self) -> f64 {
        self.values.iter().fold(0.0_f64, |a, b| a.max(b.abs()))
    }

    /// The measured eigenvalue lambda_r^m = (2 pi f_r)^2.
    pub fn lambda(&self) -> f64 {
        crate::modal::hz_to_lambda(self.frequency_hz)
    }
}

/// The order of measured points: by the lowest DOF read (for DOFs: ascending DOF), then by
/// abscissa, then by direction.
pub fn point_order(a: &Observation, b: &Observation) -> std::cmp::Ordering {
    a.first_dof()
        .cmp(&b.first_dof())
        .then(a.x.total_cmp(&b.x))
        .then(a.direction.cmp(&b.direction))
}

/// All measured modes of a test, ordered by mode number.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredModes {
    modes: Vec<MeasuredMode>,
}

impl MeasuredModes {
    /// Builds from modes already validated (used by simulators); sorted by mode number.
    pub fn new(mut modes: Vec<MeasuredMode>) -> Self {
        modes.sort_by_key(|m| m.mode);
        Self { modes }
    }

    /// The same modes without their standard errors (frequency, damping, shape values).
    pub fn without_std(self) -> Self {
        let modes = self
            .modes
            .into_iter()
            .map(|m| MeasuredMode {
                frequency_std: None,
                damping_std: None,
                value_std: None,
                ..m
            })
            .collect();
        Self { modes }
    }

    /// The modes, ascending mode number.
    pub fn modes(&self) -> &[MeasuredMode] {
        &self.modes
    }

    /// The modes, ascending mode number, taken (not copied: a large model's modes hold
    /// millions of points).
    pub fn into_modes(self) -> Vec<MeasuredMode> {
        self.modes
    }

    /// Whether every mode carries its standard errors ([`MeasuredMode::has_std`]; the reader
    /// takes them for every mode or for none).
    pub fn has_std(&self) -> bool {
        !self.modes.is_empty() && self.modes.iter().all(MeasuredMode::has_std)
    }

    /// The mode with number `r`, if measured.
    pub fn get(&self, r: usize) -> Option<&MeasuredMode> {
        self.modes.iter().find(|m| m.mode == r)
    }

    /// Every distinct measured point of every mode, in [`point_order`].
    pub fn points(&self) -> Vec<Observation> {
        let mut all: Vec<Observation> = self
            .modes
            .iter()
            .flat_map(|m| m.points.iter().cloned())
            .collect();
        all.sort_by(point_order);
        all.dedup_by(|a, b| a.label == b.label);
        all
    }
}
