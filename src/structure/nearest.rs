//! Sensors given by coordinates in space (x, y, z and a direction): resolved to the DOF of
//! that direction nearest to the point, when it lies within the model's sensor tolerance.
//!
//! The tolerance: `sensor_tolerance` of an external model's file, else
//! [`DEFAULT_TOLERANCE`] times the diagonal of the box that holds every DOF's position. A
//! sensor sits on the structure's surface, and a mesh has a node there within half an
//! element: what the tolerance catches is a sensor off the model, from coordinates in
//! another unit (mm for m: 1000 times off), another origin or swapped axes; and what it must
//! let through is the rounding of the coordinates (single precision, about 1e-5 relative, in
//! a UFF 15 geometry), a position measured by hand to a few millimetres, or an accelerometer's
//! centre a few millimetres off the surface. One percent of the size does both on a specimen
//! (5 mm on one 0.5 m long).
//!
//! Two DOFs of the direction at the same position (coincident nodes, as the two faces of a
//! lap tied by springs) make a point there ambiguous: it is refused with both labels, to be
//! named by label instead.
//!
//! The search: the DOFs sorted by x once, then from the point's x outwards on both sides,
//! stopping where |dx| alone exceeds the best distance (a few cross-sections of a bar-like
//! model, not the whole table).

use super::dofs::{Direction, DofMap};
use super::observation::Observation;
use crate::input::Number;

/// The default tolerance, relative to the diagonal of the model's bounding box.
pub const DEFAULT_TOLERANCE: f64 = 1e-2;

/// Why a point in space does not resolve to a DOF.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NearestError {
    /// No DOF has the direction.
    #[error("direction {direction} is not one of the model's DOFs (it has {present})")]
    Direction {
        /// The direction asked for.
        direction: Direction,
        /// The directions the model has, comma separated.
        present: String,
    },
    /// The nearest DOF is farther than the tolerance.
    #[error(
        "the point ({}, {}, {}) m is {distance:.3e} m from the nearest {direction} DOF `{label}`, over the sensor tolerance {tolerance:.3e} m ({origin}): check the point's unit, origin and axes",
        Number(point[0]), Number(point[1]), Number(point[2])
    )]
    Far {
        /// The point.
        point: [f64; 3],
        /// The direction.
        direction: Direction,
        /// The nearest DOF's label.
        label: String,
        /// Its position.
        position: [f64; 3],
        /// The distance, m.
        distance: f64,
        /// The tolerance, m.
        tolerance: f64,
        /// Where the tolerance comes from.
        origin: String,
    },
    /// Two DOFs of the direction share the nearest position.
    #[error(
        "the point ({}, {}, {}) m is nearest to `{first}` and `{second}`, two {direction} DOFs at the same position (coincident nodes): name the one measured by label",
        Number(point[0]), Number(point[1]), Number(point[2])
    )]
    Coincident {
        /// The point.
        point: [f64; 3],
        /// The direction.
        direction: Direction,
        /// The first DOF's label (lower index).
        first: String,
        /// The second's.
        second: String,
    },
}

impl DofMap {
    /// The distance a sensor given by coordinates may lie from its DOF, m, and where it comes
    /// from (for messages).
    pub fn sensor_tolerance(&self) -> (f64, String) {
        match self.sensor_tolerance_set() {
            Some(t) => (t, "its sensor_tolerance".to_string()),
            None => (
                DEFAULT_TOLERANCE * self.index_by_x().diagonal(),
                format!("{}% of its size", DEFAULT_TOLERANCE * 100.0),
            ),
        }
    }

    /// The observation of the DOF of `direction` nearest to `point` (m), if it lies within
    /// [`DofMap::sensor_tolerance`] and no other DOF of that direction shares its position.
    pub fn nearest(
        &self,
        point: [f64; 3],
        direction: Direction,
    ) -> Result<Observation, NearestError> {
        let index = self.index_by_x();
        let sorted = index.sorted();
        let start = sorted.partition_point(|e| e.0 < point[0]);
        let mut best: Option<(f64, usize)> = None;
        let consider = |best: &mut Option<(f64, usize)>, i: usize| {
            let d = self.get(i);
            if d.direction != direction {
                return;
            }
            let dist2: f64 = (0..3).map(|k| (d.position[k] - point[k]).powi(2)).sum();
            if best.is_none_or(|(b, j)| dist2 < b || (dist2 == b && i < j)) {
                *best = Some((dist2, i));
            }
        };
        // Outwards from the point's x on both sides, while |dx|^2 can still beat the best.
        let (mut left, mut right) = (start, start);
        loop {
            let bound = best.map_or(f64::INFINITY, |b| b.0);
            let go_left = left > 0 && (point[0] - sorted[left - 1].0).powi(2) <= bound;
            let go_right = right < sorted.len() && (sorted[right].0 - point[0]).powi(2) <= bound;
            if !(go_left || go_right) {
                break;
            }
            if go_left {
                left -= 1;
                consider(&mut best, sorted[left].1);
            }
            if go_right {
                consider(&mut best, sorted[right].1);
                right += 1;
            }
        }
        let Some((_, i)) = best else {
            let mut present: Vec<&str> = Direction::ALL
                .iter()
                .filter(|d| self.dofs().iter().any(|x| x.direction == **d))
                .map(|d| d.name())
                .collect();
            present.dedup();
            return Err(NearestError::Direction {
                direction,
                present: present.join(", "),
            });
        };
        let found = self.get(i);
        let (tolerance, origin) = self.sensor_tolerance();
        // |found - point| without the overflow of its square (a point 1e200 m away)
        let distance = (0..3)
            .map(|k| found.position[k] - point[k])
            .fold(0.0, f64::hypot);
        if distance.is_nan() || distance > tolerance {
            return Err(NearestError::Far {
                point,
                direction,
                label: found.label.clone(),
                position: found.position,
                distance,
                tolerance,
                origin,
            });
        }
        if let Some(twin) = (left..right).map(|k| sorted[k].1).find(|&j| {
            j != i && self.get(j).direction == direction && self.get(j).position == found.position
        }) {
            let (a, b) = (i.min(twin), i.max(twin));
            return Err(NearestError::Coincident {
                point,
                direction,
                first: self.get(a).label.clone(),
                second: self.get(b).label.clone(),
            });
        }
        Ok(Observation::dof(self, i))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::structure::DofInfo;

    fn map(points: &[([f64; 3], Direction)]) -> DofMap {
        let dofs = points
            .iter()
            .enumerate()
            .map(|(i, &(position, direction))| DofInfo {
                label: format!("d{i}"),
                position,
                direction,
                node: None,
            })
            .collect();
        DofMap::new(dofs, Vec::new(), Vec::new())
    }

    #[test]
    fn the_nearest_dof_of_the_direction_is_found_from_either_side() {
        // A 1 m x 0.1 m x 0.1 m box of nodes every 0.1 m along x, x and z DOFs.
        let mut points = Vec::new();
        for i in 0..11 {
            for (y, z) in [(0.0, 0.0), (0.1, 0.1)] {
                let p = [0.1 * f64::from(i), y, z];
                points.push((p, Direction::X));
                points.push((p, Direction::Z));
            }
        }
        let m = map(&points);
        let (tolerance, _) = m.sensor_tolerance();
        assert!((tolerance - 0.01 * 1.02f64.sqrt()).abs() < 1e-15);
        let label = |p: [f64; 3], d| m.nearest(p, d).map(|o| o.label);
        assert_eq!(label([0.501, 0.099, 0.1], Direction::Z), Ok("d23".into()));
        assert_eq!(label([0.499, 0.001, 0.0], Direction::X), Ok("d20".into()));
        assert_eq!(label([1.005, 0.0, 0.0], Direction::X), Ok("d40".into()));
        assert!(matches!(
            m.nearest([0.55, 0.0, 0.0], Direction::X),
            Err(NearestError::Far { distance, .. }) if (distance - 0.05).abs() < 1e-12
        ));
        assert_eq!(
            m.nearest([0.5, 0.0, 0.0], Direction::Y)
                .unwrap_err()
                .to_string(),
            "direction y is not one of the model's DOFs (it has x, z)"
        );
        let m = m.with_sensor_tolerance(Some(0.1));
        assert_eq!(m.sensor_tolerance().0, 0.1);
        assert_eq!(
            m.nearest([0.55, 0.0, 0.0], Direction::X).map(|o| o.label),
            Ok("d20".into()),
            "a tie goes to the lower DOF"
        );
    }

    #[test]
    fn coincident_dofs_make_a_point_ambiguous() {
        let p = [0.2, 0.0, 0.0];
        let m = map(&[
            ([0.0; 3], Direction::X),
            (p, Direction::X),
            (p, Direction::X),
        ]);
        assert_eq!(
            m.nearest([0.2, 0.0, 0.001], Direction::X)
                .unwrap_err()
                .to_string(),
            "the point (0.2, 0, 0.001) m is nearest to `d1` and `d2`, two x DOFs at the same position (coincident nodes): name the one measured by label"
        );
    }
}
