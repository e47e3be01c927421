//! Products A x of a sparse symmetric matrix accumulated in twice the working precision and
//! rounded once, for the refinement ([`super::refine`]) and the residuals
//! ([`super::residual`]) of the sparse eigensolver.
//!
//! In the stiffness matrix of a finely meshed structure the entries are of the element scale
//! while K y for a low mode is smaller by up to the condition number: a product in double
//! precision carries a round-off of eps |K| |y| per entry. Here each entry is accumulated with
//! error-free transformations (Dekker's product and Knuth's sum, the "Dot2" of Ogita, Rump &
//! Oishi, "Accurate sum and dot product", SIAM J. Sci. Comput. 26 (2005)). Four vectors share
//! one pass over A, and the error of each product comes from one fused multiply-add where the
//! processor has it: the same error term as Dekker's product (exactly representable), so the
//! same results either way.
//!
//! Layer 2 (eigensolution), like [`super`]: may import the layers below.

use faer::sparse::SparseColMatRef;

/// `y = A x` for a symmetric matrix stored with both triangles, every entry accumulated in
/// twice the working precision and rounded once.
pub fn accurate_mul(a: SparseColMatRef<'_, usize, f64>, x: &[f64], y: &mut [f64]) {
    accurate_block::<1>(a, [x], [y]);
}

/// [`accurate_mul`], returning also || |A| |x| ||_2 (the scale of the rounding of A x).
pub fn accurate_mul_bounded(a: SparseColMatRef<'_, usize, f64>, x: &[f64], y: &mut [f64]) -> f64 {
    accurate_block::<1>(a, [x], [y])[0].sqrt()
}

/// [`accurate_mul`] of W vectors at once (one pass over A for all of them; the same
/// operations per vector, so the same results), into the W columns `y`; returns
/// || |A| |x_r| ||^2 of every vector.
pub fn accurate_block<const W: usize>(
    a: SparseColMatRef<'_, usize, f64>,
    x: [&[f64]; W],
    y: [&mut [f64]; W],
) -> [f64; W] {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the processor has FMA (checked just above).
        return unsafe { accurate_block_fma::<W>(a, x, y) };
    }
    accurate_block_with::<false, W>(a, x, y)
}

/// [`accurate_block`] with the error of each product from one fused multiply-add: the same
/// error term as Dekker's product (it is exactly representable), in 2 operations for 17.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
unsafe fn accurate_block_fma<const W: usize>(
    a: SparseColMatRef<'_, usize, f64>,
    x: [&[f64]; W],
    y: [&mut [f64]; W],
) -> [f64; W] {
    accurate_block_with::<true, W>(a, x, y)
}

#[inline(always)]
fn accurate_block_with<const FMA: bool, const W: usize>(
    a: SparseColMatRef<'_, usize, f64>,
    x: [&[f64]; W],
    mut y: [&mut [f64]; W],
) -> [f64; W] {
    let n = a.ncols();
    let mut squares = [0.0; W];
    for j in 0..n {
        // Column j of a symmetric matrix is its row j.
        let rows = a.symbolic().row_idx_of_col_raw(j);
        let (mut s, mut c, mut bound) = ([0.0_f64; W], [0.0_f64; W], [0.0_f64; W]);
        for (&i, &v) in rows.iter().zip(a.val_of_col(j)) {
            for r in 0..W {
                let (p, e) = if FMA {
                    let p = v * x[r][i];
                    (p, v.mul_add(x[r][i], -p))
                } else {
                    two_product(v, x[r][i])
                };
                let (t, f) = two_sum(s[r], p);
                s[r] = t;
                c[r] += e + f;
                bound[r] += p.abs();
            }
        }
        for (r, column) in y.iter_mut().enumerate() {
            column[j] = s[r] + c[r];
            squares[r] += bound[r] * bound[r];
        }
    }
    squares
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::sparse_mul;
    use crate::structure::SymMatrix;

    /// Row 0 of A x sums 1 + 1e16 - 1e16: the plain product loses the 1, the accurate one
    /// keeps it (exact value by hand).
    #[test]
    fn accurate_product_survives_cancellation() {
        let a = SymMatrix::from_entries(
            3,
            &[
                (0, 0, 1.0),
                (0, 1, 1e16),
                (1, 0, 1e16),
                (0, 2, -1e16),
                (2, 0, -1e16),
                (1, 1, 1.0),
                (2, 2, 1.0),
            ],
        );
        let x = [1.0, 1.0, 1.0];
        let (mut plain, mut accurate) = ([0.0; 3], [0.0; 3]);
        sparse_mul(a.as_faer(), &x, &mut plain);
        accurate_mul(a.as_faer(), &x, &mut accurate);
        assert_eq!(plain[0], 0.0);
        assert_eq!(accurate, [1.0, 1e16 + 1.0, 1.0 - 1e16]);
    }

    /// Four vectors in one pass, one at a time, with and without FMA: bitwise the same
    /// products (the error term of a product is exact either way), and the bound
    /// || |A| |x| || by hand.
    #[test]
    fn block_and_fma_products_equal_the_single_ones() {
        let a = SymMatrix::from_entries(
            3,
            &[
                (0, 0, 4.0),
                (0, 1, -1e16),
                (1, 0, -1e16),
                (1, 1, 3.0),
                (1, 2, 0.1),
                (2, 1, 0.1),
                (2, 2, 1.0 / 3.0),
            ],
        );
        let xs: Vec<[f64; 3]> = vec![
            [1.0, 1e-16, 0.3],
            [0.1, 0.2, 0.7],
            [-1.0, 1.0, 1e-8],
            [1.0 / 3.0, 2.0 / 3.0, 1.0],
        ];
        let mut block = [[0.0; 3]; 4];
        let [b0, b1, b2, b3] = &mut block;
        accurate_block::<4>(
            a.as_faer(),
            std::array::from_fn(|r| &xs[r][..]),
            [b0, b1, b2, b3],
        );
        for (r, x) in xs.iter().enumerate() {
            let (mut one, mut generic) = ([0.0; 3], [0.0; 3]);
            let bound = accurate_mul_bounded(a.as_faer(), x, &mut one);
            accurate_block_with::<false, 1>(a.as_faer(), [&x[..]], [&mut generic]);
            assert_eq!(one, generic, "vector {r}");
            assert_eq!(block[r], one, "vector {r}");
            let by_hand = [
                4.0 * x[0].abs() + 1e16 * x[1].abs(),
                1e16 * x[0].abs() + 3.0 * x[1].abs() + 0.1 * x[2].abs(),
                0.1 * x[1].abs() + x[2].abs() / 3.0,
            ];
            let norm = by_hand.iter().map(|v| v * v).sum::<f64>().sqrt();
            assert!((bound - norm).abs() <= 1e-15 * norm, "vector {r}");
        }
    }
}
