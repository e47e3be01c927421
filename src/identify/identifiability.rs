//! What one mode can identify: the resolution of every parameter in the weighted sensitivity
//! system W S_r of eq. (13), and the largest subset of parameters the mode determines.
//!
//! The resolution of parameter i is the part of its column a_i that the other columns cannot
//! produce, relative to its length: rho_i = ||(I - P_others) a_i|| / ||a_i||, with P_others the
//! orthogonal projector on the span of the other columns. rho_i = 1: the mode sees p_i apart
//! from the others; rho_i = 0: a change of p_i is indistinguishable from a change of the others
//! (the system is rank deficient), and noise on the data moves Z_r(i) by about 1/rho_i times
//! its share. With three or four sensors, or a mode with a node at a joint, some parameters of
//! some modes are not determined: they are held at their nominal value on that mode instead of
//! being reported as a rank-deficient row.

/// A parameter whose resolution on a mode is below this is not identified on that mode
/// (noise amplified a thousand times over its share).
pub const MIN_RESOLUTION: f64 = 1e-3;

/// Which parameters a mode identifies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Selection {
    /// All of them (a rank-deficient mode has no corrections).
    All,
    /// The largest subset the mode determines: the least-resolved parameter is held at its
    /// nominal value until every remaining one has a resolution of at least [`MIN_RESOLUTION`].
    Auto,
}

/// The resolution of each column `cols[k]` of the column-major `m x q` matrix `a` against the
/// other columns of `cols` (see the module docs); 0 for a zero column.
pub fn resolution(a: &[f64], m: usize, cols: &[usize]) -> Vec<f64> {
    let column = |j: usize| &a[j * m..(j + 1) * m];
    cols.iter()
        .map(|&i| {
            let own = column(i);
            let norm = own.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm == 0.0 {
                return 0.0;
            }
            // Orthonormal basis of the others by modified Gram-Schmidt, twice for stability.
            let mut basis: Vec<Vec<f64>> = Vec::new();
            for &j in cols.iter().filter(|&&j| j != i) {
                let mut v = column(j).to_vec();
                for _ in 0..2 {
                    for b in &basis {
                        let d: f64 = b.iter().zip(&v).map(|(x, y)| x * y).sum();
                        v.iter_mut().zip(b).for_each(|(x, y)| *x -= d * y);
                    }
                }
                let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
                if n > 1e-14 * column(j).iter().map(|x| x * x).sum::<f64>().sqrt() {
                    basis.push(v.into_iter().map(|x| x / n).collect());
                }
            }
            let mut r = own.to_vec();
            for _ in 0..2 {
                for b in &basis {
                    let d: f64 = b.iter().zip(&r).map(|(x, y)| x * y).sum();
                    r.iter_mut().zip(b).for_each(|(x, y)| *x -= d * y);
                }
            }
            r.iter().map(|x| x * x).sum::<f64>().sqrt() / norm
        })
        .collect()
}

/// The parameters (ascending indices of the `q` columns) a mode identifies under `selection`.
pub fn choose(a: &[f64], m: usize, q: usize, selection: Selection) -> Vec<usize> {
    let mut cols: Vec<usize> = (0..q).collect();
    if selection == Selection::All {
        return cols;
    }
    while !cols.is_empty() {
        let rho = resolution(a, m, &cols);
        let (worst, &value) = rho
            .iter()
            .enumerate()
            .min_by(|x, y| x.1.total_cmp(y.1))
            .expect("a column");
        if value >= MIN_RESOLUTION {
            break;
        }
        cols.remove(worst);
    }
    cols
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolution_is_one_for_orthogonal_columns_and_falls_with_dependence() {
        // Columns (1, 0, 0), (0, 1, 0), (1, eps, 0).
        let eps = 1e-5;
        let a = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, eps, 0.0];
        let rho = resolution(&a, 3, &[0, 1]);
        assert_eq!(rho, vec![1.0, 1.0]);
        let rho = resolution(&a, 3, &[0, 2]);
        // The part of (1, eps, 0) outside (1, 0, 0) is eps, of length ~1: rho = eps.
        assert!((rho[1] - eps).abs() < 1e-12, "{rho:?}");
        assert!((rho[0] - eps).abs() < 1e-10, "{rho:?}");
        // Three columns in a plane: every one is resolved by the other two only partly.
        let all = resolution(&a, 3, &[0, 1, 2]);
        assert!(all.iter().all(|&r| r < 1e-4), "{all:?}");
    }

    #[test]
    fn auto_drops_the_least_resolved_parameter() {
        let eps = 1e-5;
        // Column 1 nearly repeats column 0 scaled; column 2 is independent.
        let a = [1.0, 2.0, 0.0, 3.0, 6.0 + eps, 0.0, 0.0, 0.0, 1.0];
        assert_eq!(choose(&a, 3, 3, Selection::All), vec![0, 1, 2]);
        let kept = choose(&a, 3, 3, Selection::Auto);
        assert_eq!(kept.len(), 2);
        assert!(kept.contains(&2));
        assert_eq!(
            choose(&[0.0; 3], 3, 1, Selection::Auto),
            Vec::<usize>::new()
        );
    }
}
