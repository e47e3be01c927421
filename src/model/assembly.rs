//! Global stiffness and mass matrices of the chain, and the parameter derivatives of eq. (8).
//!
//! K is linear in the joint stiffnesses: K = K_beams + sum_i p_i dK/dp_i, so the first-order
//! expansion (8) is exact for k1 and k2.

use faer::Mat;

use super::joint::{JointStiffness, parameter_name};
use super::{Dof, Model, SparseSym, dof_index};

/// Global K (N x N, symmetric positive semidefinite) and M (symmetric positive definite).
#[derive(Debug, Clone)]
pub struct Matrices {
    /// Stiffness matrix K.
    pub k: Mat<f64>,
    /// Mass matrix M.
    pub m: Mat<f64>,
}

/// A model parameter p_i with the derivatives of the global matrices with respect to it.
#[derive(Debug, Clone)]
pub struct Parameter {
    /// Name in output files (`k1`, `joint2.k2`, ...).
    pub name: String,
    /// Unit of the parameter, for reports.
    pub unit: &'static str,
    /// Current value p_i.
    pub value: f64,
    /// dK/dp_i.
    pub stiffness: SparseSym,
    /// dM/dp_i (zero for a stiffness parameter).
    pub mass: SparseSym,
}

impl Model {
    /// Assembles K and M: beam elements, then the joints of eq. (17).
    pub fn assemble(&self) -> Matrices {
        let n = self.dof_count();
        let mut k = Mat::<f64>::zeros(n, n);
        let mut m = Mat::<f64>::zeros(n, n);
        for (b, beam) in self.beams().iter().enumerate() {
            let ke = beam.element_stiffness();
            let me = beam.element_mass();
            let first = self.first_node(b);
            for e in 0..beam.elements {
                let base = dof_index(first + e, Dof::W);
                for i in 0..4 {
                    for j in 0..4 {
                        k[(base + i, base + j)] += ke[i][j];
                        m[(base + i, base + j)] += me[i][j];
                    }
                }
            }
        }
        for p in self.joint_parameters() {
            p.stiffness.add_to(&mut k, p.value);
        }
        Matrices { k, m }
    }

    /// The identified parameters: k1 and k2 of every joint, in joint order (q = 2 per joint).
    pub fn joint_parameters(&self) -> Vec<Parameter> {
        let count = self.joints().len();
        let mut out = Vec::with_capacity(2 * count);
        for (j, joint) in self.joints().iter().enumerate() {
            let (a, b) = self.joint_nodes(j);
            for kind in JointStiffness::ALL {
                let dof = match kind {
                    JointStiffness::Transversal => Dof::W,
                    JointStiffness::Rotational => Dof::Theta,
                };
                out.push(Parameter {
                    name: parameter_name(j, count, kind),
                    unit: kind.unit(),
                    value: kind.of(joint),
                    stiffness: SparseSym::spring(dof_index(a, dof), dof_index(b, dof), 1.0),
                    mass: SparseSym::zero(),
                });
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::fixtures::paper_model;

    #[test]
    fn paper_model_has_38_dofs_and_symmetric_matrices() {
        let model = paper_model(1e7, 1e4);
        let mats = model.assemble();
        assert_eq!(model.dof_count(), 38);
        for i in 0..38 {
            for j in 0..38 {
                assert_eq!(mats.k[(i, j)], mats.k[(j, i)]);
                assert_eq!(mats.m[(i, j)], mats.m[(j, i)]);
            }
        }
    }

    #[test]
    fn joint_block_is_eq_17() {
        let model = paper_model(3.0e7, 5.0e4);
        let bare = paper_model(0.0, 0.0).assemble();
        let mats = model.assemble();
        let (a, b) = model.joint_nodes(0);
        assert_eq!((a, b), (7, 8));
        let dofs = [
            dof_index(a, Dof::W),
            dof_index(a, Dof::Theta),
            dof_index(b, Dof::W),
            dof_index(b, Dof::Theta),
        ];
        let expected = [
            [3.0e7, 0.0, -3.0e7, 0.0],
            [0.0, 5.0e4, 0.0, -5.0e4],
            [-3.0e7, 0.0, 3.0e7, 0.0],
            [0.0, -5.0e4, 0.0, 5.0e4],
        ];
        for (i, &di) in dofs.iter().enumerate() {
            for (j, &dj) in dofs.iter().enumerate() {
                let joint = mats.k[(di, dj)] - bare.k[(di, dj)];
                assert_eq!(joint, expected[i][j], "entry ({i}, {j})");
            }
        }
        // Nothing else changes.
        let changed = (0..38)
            .flat_map(|i| (0..38).map(move |j| (i, j)))
            .filter(|&(i, j)| mats.k[(i, j)] != bare.k[(i, j)])
            .count();
        assert_eq!(changed, 8);
    }

    #[test]
    fn mass_matrix_carries_the_total_mass() {
        let model = paper_model(1e7, 1e4);
        let m = model.assemble().m;
        let n = model.dof_count();
        let heave: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 1.0 } else { 0.0 }).collect();
        let mut e = 0.0;
        for i in 0..n {
            for j in 0..n {
                e += heave[i] * m[(i, j)] * heave[j];
            }
        }
        let total = 7850.0 * 2.4e-3 * 0.5;
        assert!((e - total).abs() < 1e-12 * total);
        assert!((model.mass() - total).abs() < 1e-12 * total);
    }
}
