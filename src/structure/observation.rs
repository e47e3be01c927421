//! Observations: what a sensor reads, as a linear function of the DOFs, c^T u.
//!
//! A sensor on a DOF reads that DOF (c = e_i). A sensor at abscissa x between the nodes of a
//! beam element of length l reads the element's Hermite interpolation, exact for the finite
//! element model: with xi = (x - x_a) / l,
//!
//! ```text
//!   w(x)     = N1 w_a + l N2 theta_a + N3 w_b + l N4 theta_b
//!   theta(x) = dw/dx = (N1' w_a + l N2' theta_a + N3' w_b + l N4' theta_b) / l
//!   N1 = 1 - 3 xi^2 + 2 xi^3   N2 = xi - 2 xi^2 + xi^3   N3 = 3 xi^2 - 2 xi^3   N4 = -xi^2 + xi^3
//! ```
//! At an abscissa shared by two elements (a node, or a joint whose two nodes share it) the
//! first element in chain order is read: at a joint, the end of the beam before it.

use faer::Mat;

use super::DofMap;
use super::dofs::{Direction, LineElement};

/// A measured quantity: a label, its direction and position, and the row c of the observation
/// matrix as its nonzero terms `(dof, coefficient)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Observation {
    /// How files and reports name it (`7:w`, `x=0.176:w`, a DOF-table label).
    pub label: String,
    /// Direction.
    pub direction: Direction,
    /// Abscissa along the chain (or the DOF's x), m.
    pub x: f64,
    /// Nonzero terms of c, ascending DOF.
    pub terms: Vec<(usize, f64)>,
}

impl Observation {
    /// The observation of a single DOF.
    pub fn dof(map: &DofMap, index: usize) -> Self {
        let info = map.get(index);
        Self {
            label: info.label.clone(),
            direction: info.direction,
            x: info.position[0],
            terms: vec![(index, 1.0)],
        }
    }

    /// c^T v for a vector v of all DOFs.
    pub fn read(&self, v: &[f64]) -> f64 {
        self.terms.iter().map(|&(d, c)| c * v[d]).sum()
    }

    /// c^T Y e_col for a column of a matrix of DOF vectors (a single-DOF observation reads the
    /// entry itself, bit for bit).
    pub fn read_column(&self, y: &Mat<f64>, col: usize) -> f64 {
        match self.single_dof() {
            Some(d) => y[(d, col)],
            None => self.terms.iter().map(|&(d, c)| c * y[(d, col)]).sum(),
        }
    }

    /// The lowest DOF it reads (its place in the order of measured points).
    pub fn first_dof(&self) -> usize {
        self.terms.first().map_or(usize::MAX, |t| t.0)
    }

    /// Whether it reads a single DOF with coefficient 1.
    pub fn single_dof(&self) -> Option<usize> {
        match self.terms.as_slice() {
            [(d, c)] if *c == 1.0 => Some(*d),
            _ => None,
        }
    }
}

/// Why a position cannot be observed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LocateError {
    /// The model has no line elements (an external model): positions are not defined.
    #[error(
        "this model reads sensors by DOF label only (it has no beam elements to interpolate along)"
    )]
    NoLines,
    /// x is outside the chain.
    #[error("x = {x} m is outside the chain, which spans {from} to {to} m")]
    Outside {
        /// The abscissa.
        x: f64,
        /// Start of the chain.
        from: f64,
        /// End of the chain.
        to: f64,
    },
    /// Only w and theta exist along a beam.
    #[error("direction {0} does not exist along a planar beam: use w or theta")]
    Direction(Direction),
    /// Every DOF the position reads is removed by a support.
    #[error("x = {x} m sits on a support that holds {direction}: it is always zero there")]
    Constrained {
        /// The abscissa.
        x: f64,
        /// The direction.
        direction: Direction,
    },
}

/// Relative tolerance of an abscissa on an element end (a sensor at a node reads the node).
const ON_NODE: f64 = 1e-9;

impl DofMap {
    /// The observation of `direction` at abscissa `x` along the line elements.
    pub fn at_x(&self, x: f64, direction: Direction) -> Result<Observation, LocateError> {
        let terms = terms_at(self.lines(), x, direction)?;
        // A position on a node reads the node's own DOF: the same observation as by node.
        match terms.as_slice() {
            [(d, c)] if *c == 1.0 && self.get(*d).direction == direction => {
                Ok(Observation::dof(self, *d))
            }
            _ => Ok(Observation {
                label: format!("x={x}:{direction}"),
                direction,
                x,
                terms,
            }),
        }
    }
}

/// The nonzero terms (ascending DOF) of the observation of `direction` at abscissa `x` along
/// the line elements `lines` (module docs).
pub fn terms_at(
    lines: &[LineElement],
    x: f64,
    direction: Direction,
) -> Result<Vec<(usize, f64)>, LocateError> {
    let (Some(first), Some(last)) = (lines.first(), lines.last()) else {
        return Err(LocateError::NoLines);
    };
    if !matches!(direction, Direction::W | Direction::Theta) {
        return Err(LocateError::Direction(direction));
    }
    let (from, to) = (first.x[0], last.x[1]);
    let tol = ON_NODE * (to - from).abs().max(f64::MIN_POSITIVE);
    if !(x.is_finite() && x >= from - tol && x <= to + tol) {
        return Err(LocateError::Outside { x, from, to });
    }
    let element = lines
        .iter()
        .find(|e| x >= e.x[0] - tol && x <= e.x[1] + tol)
        .expect("the elements cover the chain");
    let l = element.x[1] - element.x[0];
    let xi = ((x - element.x[0]) / l).clamp(0.0, 1.0);
    let xi = if xi < ON_NODE {
        0.0
    } else if xi > 1.0 - ON_NODE {
        1.0
    } else {
        xi
    };
    let (x2, x3) = (xi * xi, xi * xi * xi);
    let coefficients = match direction {
        Direction::W => [
            1.0 - 3.0 * x2 + 2.0 * x3,
            l * (xi - 2.0 * x2 + x3),
            3.0 * x2 - 2.0 * x3,
            l * (-x2 + x3),
        ],
        _ => [
            (-6.0 * xi + 6.0 * x2) / l,
            1.0 - 4.0 * xi + 3.0 * x2,
            (6.0 * xi - 6.0 * x2) / l,
            -2.0 * xi + 3.0 * x2,
        ],
    };
    let mut terms: Vec<(usize, f64)> = element
        .dofs
        .iter()
        .zip(coefficients)
        .filter_map(|(d, c)| d.filter(|_| c != 0.0).map(|d| (d, c)))
        .collect();
    terms.sort_by_key(|t| t.0);
    if terms.is_empty() {
        return Err(LocateError::Constrained { x, direction });
    }
    Ok(terms)
}

/// The matrix C Y (points x columns of `y`): every observation read on every column.
pub fn observe(y: &Mat<f64>, points: &[Observation]) -> Mat<f64> {
    Mat::from_fn(points.len(), y.ncols(), |i, j| points[i].read_column(y, j))
}
