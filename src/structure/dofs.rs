//! The DOF map of a structure: for every global DOF its label, position and direction, and the
//! line elements along which a response can be read at any abscissa.
//!
//! Labels are what files refer to: `7:w`, `7:theta` for node 7 of a beam chain, any text for an
//! external model's DOF table. Directions: `w` and `theta` are the transverse displacement and
//! the rotation of a planar beam; `x`, `y`, `z`, `rx`, `ry`, `rz` those of an external model.

use std::collections::HashMap;
use std::fmt;

/// The direction of a DOF.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Direction {
    /// Transverse displacement of a planar beam, m.
    W,
    /// Rotation of a planar beam, rad.
    Theta,
    /// Translation along x, m.
    X,
    /// Translation along y, m.
    Y,
    /// Translation along z, m.
    Z,
    /// Rotation about x, rad.
    Rx,
    /// Rotation about y, rad.
    Ry,
    /// Rotation about z, rad.
    Rz,
}

impl Direction {
    /// Every direction, in the order of [`Direction::name`]'s list.
    pub const ALL: [Direction; 8] = [
        Direction::W,
        Direction::Theta,
        Direction::X,
        Direction::Y,
        Direction::Z,
        Direction::Rx,
        Direction::Ry,
        Direction::Rz,
    ];

    /// The name in files.
    pub fn name(self) -> &'static str {
        match self {
            Direction::W => "w",
            Direction::Theta => "theta",
            Direction::X => "x",
            Direction::Y => "y",
            Direction::Z => "z",
            Direction::Rx => "rx",
            Direction::Ry => "ry",
            Direction::Rz => "rz",
        }
    }

    /// Parses a name of [`Direction::name`].
    pub fn parse(s: &str) -> Option<Direction> {
        Direction::ALL.into_iter().find(|d| d.name() == s)
    }

    /// Whether the DOF is a rotation (rad) rather than a translation (m).
    pub fn is_rotation(self) -> bool {
        matches!(
            self,
            Direction::Theta | Direction::Rx | Direction::Ry | Direction::Rz
        )
    }

    /// The unit of a displacement in this direction.
    pub fn unit(self) -> &'static str {
        if self.is_rotation() { "rad" } else { "m" }
    }
}

impl fmt::Display for Direction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One global DOF.
#[derive(Debug, Clone, PartialEq)]
pub struct DofInfo {
    /// Label in files, unique.
    pub label: String,
    /// Position (x along a beam chain, y = z = 0 there), m.
    pub position: [f64; 3],
    /// Direction.
    pub direction: Direction,
    /// Node number, where the model has numbered nodes.
    pub node: Option<usize>,
}

/// A beam element along the chain's abscissa: a response at x inside it is the Hermite
/// interpolation of its end DOFs (`None` where a support removed the DOF: its value is 0).
#[derive(Debug, Clone, PartialEq)]
pub struct LineElement {
    /// Abscissae of its two ends, m.
    pub x: [f64; 2],
    /// Global DOFs (w_a, theta_a, w_b, theta_b).
    pub dofs: [Option<usize>; 4],
}

/// The DOFs of a structure.
#[derive(Debug, Clone, Default)]
pub struct DofMap {
    dofs: Vec<DofInfo>,
    by_label: HashMap<String, usize>,
    constrained: HashMap<String, String>,
    lines: Vec<LineElement>,
    /// How far a sensor given by coordinates may lie from its nearest DOF, m (`None`: the
    /// default of [`super::nearest`]).
    sensor_tolerance: Option<f64>,
    /// The DOFs sorted by x, built at the first search by coordinates.
    by_x: std::sync::OnceLock<Index>,
}

impl DofMap {
    /// A map of `dofs` (labels unique: the caller checks) and the line elements along which
    /// positions are read; `constrained` lists the labels a support removed, with the support
    /// (for messages).
    pub fn new(
        dofs: Vec<DofInfo>,
        lines: Vec<LineElement>,
        constrained: Vec<(String, String)>,
    ) -> Self {
        let by_label = dofs
            .iter()
            .enumerate()
            .map(|(i, d)| (d.label.clone(), i))
            .collect();
        Self {
            dofs,
            by_label,
            constrained: constrained.into_iter().collect(),
            lines,
            sensor_tolerance: None,
            by_x: std::sync::OnceLock::new(),
        }
    }

    /// The map with the distance a sensor given by coordinates may lie from its nearest DOF,
    /// m (`None`: the default, see [`super::nearest`]).
    pub fn with_sensor_tolerance(mut self, tolerance: Option<f64>) -> Self {
        self.sensor_tolerance = tolerance;
        self
    }

    /// The tolerance set by [`DofMap::with_sensor_tolerance`], if any.
    pub fn sensor_tolerance_set(&self) -> Option<f64> {
        self.sensor_tolerance
    }

    /// The DOFs sorted by x (built once).
    pub(super) fn index_by_x(&self) -> &Index {
        self.by_x.get_or_init(|| Index::new(&self.dofs))
    }

    /// Number of DOFs N.
    pub fn len(&self) -> usize {
        self.dofs.len()
    }

    /// Whether there is no DOF.
    pub fn is_empty(&self) -> bool {
        self.dofs.is_empty()
    }

    /// Every DOF, in global order.
    pub fn dofs(&self) -> &[DofInfo] {
        &self.dofs
    }

    /// DOF `i`.
    pub fn get(&self, i: usize) -> &DofInfo {
        &self.dofs[i]
    }

    /// The global index of a label.
    pub fn index(&self, label: &str) -> Option<usize> {
        self.by_label.get(label).copied()
    }

    /// The support that removed `label`, if one did.
    pub fn constrained_by(&self, label: &str) -> Option<&str> {
        self.constrained.get(label).map(String::as_str)
    }

    /// The line elements (empty for a model without them).
    pub fn lines(&self) -> &[LineElement] {
        &self.lines
    }

    /// The label of node `node`, direction `direction` (`7:w`).
    pub fn node_label(node: usize, direction: Direction) -> String {
        format!("{node}:{direction}")
    }
}

/// The DOFs sorted by x, and the model's bounding-box diagonal.
#[derive(Debug, Clone)]
pub struct Index {
    /// (x, DOF index), ascending x.
    sorted: Vec<(f64, usize)>,
    /// The diagonal of the box of every DOF's position, m.
    diagonal: f64,
}

impl Index {
    /// The index of `dofs`.
    pub fn new(dofs: &[DofInfo]) -> Index {
        let mut sorted: Vec<(f64, usize)> = dofs
            .iter()
            .enumerate()
            .map(|(i, d)| (d.position[0], i))
            .collect();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for d in dofs {
            for k in 0..3 {
                lo[k] = lo[k].min(d.position[k]);
                hi[k] = hi[k].max(d.position[k]);
            }
        }
        let diagonal = (0..3)
            .map(|k| (hi[k] - lo[k]).max(0.0).powi(2))
            .sum::<f64>()
            .sqrt();
        Index { sorted, diagonal }
    }

    /// (x, DOF index), ascending x.
    pub fn sorted(&self) -> &[(f64, usize)] {
        &self.sorted
    }

    /// The diagonal of the box of every DOF's position, m.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }
}
