//! A tall N x r matrix held as blocks of columns that copies share: the basis of a reduced
//! model ([`super::reduced`]) and its products with K and M. An enrichment adds a few columns
//! to a basis of a hundred; with the columns in shared blocks, the enriched copy holds only
//! the new block and the old ones by reference, where a plain matrix would be copied whole
//! (1.2 GB per copy of the three N x r matrices at half a million DOFs and r = 100, one copy
//! per fit that enriches, each kept alive by the solutions made on it).
//!
//! Layer 1 (foundations), like [`super`].

use std::sync::Arc;

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatMut, MatRef, Par};

/// The columns of a tall matrix in shared blocks (module docs).
#[derive(Clone, Debug)]
pub struct Columns {
    nrows: usize,
    blocks: Vec<Arc<Mat<f64>>>,
}

impl Columns {
    /// N x 0.
    pub fn empty(nrows: usize) -> Self {
        Self {
            nrows,
            blocks: Vec::new(),
        }
    }

    /// N.
    pub fn nrows(&self) -> usize {
        self.nrows
    }

    /// r.
    pub fn ncols(&self) -> usize {
        self.blocks.iter().map(|b| b.ncols()).sum()
    }

    /// These columns followed by those of `block` (N rows); the blocks held already are
    /// shared, not copied.
    ///
    /// # Panics
    /// When `block` has another number of rows (a caller's bug).
    pub fn joined(&self, block: Mat<f64>) -> Self {
        assert_eq!(block.nrows(), self.nrows, "a block of another height");
        let mut blocks = self.blocks.clone();
        if block.ncols() > 0 {
            blocks.push(Arc::new(block));
        }
        Self {
            nrows: self.nrows,
            blocks,
        }
    }

    /// The block joined last.
    ///
    /// # Panics
    /// When no block is held (a caller's bug).
    pub fn last_block(&self) -> &Mat<f64> {
        self.blocks.last().expect("a block joined")
    }

    /// out = beta out + alpha A y (y: r x c; `accum` Replace for beta = 0, Add for 1).
    pub fn times_into(
        &self,
        mut out: MatMut<'_, f64>,
        accum: Accum,
        y: MatRef<'_, f64>,
        alpha: f64,
    ) {
        if self.blocks.is_empty() && accum == Accum::Replace {
            out.fill(0.0);
        }
        let mut offset = 0;
        for (b, block) in self.blocks.iter().enumerate() {
            let w = block.ncols();
            let accum = if b == 0 { accum } else { Accum::Add };
            matmul(
                out.as_mut(),
                accum,
                block.as_ref(),
                y.subrows(offset, w),
                alpha,
                Par::Seq,
            );
            offset += w;
        }
    }

    /// A y (y: r x c).
    pub fn times(&self, y: MatRef<'_, f64>) -> Mat<f64> {
        let mut out = Mat::zeros(self.nrows, y.ncols());
        self.times_into(out.as_mut(), Accum::Replace, y, 1.0);
        out
    }

    /// A^T w (w: N x c), r x c.
    pub fn transpose_times(&self, w: MatRef<'_, f64>) -> Mat<f64> {
        let mut out = Mat::zeros(self.ncols(), w.ncols());
        let mut offset = 0;
        for block in &self.blocks {
            let width = block.ncols();
            matmul(
                out.as_mut().subrows_mut(offset, width),
                Accum::Replace,
                block.transpose(),
                w,
                1.0,
                Par::Seq,
            );
            offset += width;
        }
        out
    }

    /// Row i into `row` (r entries).
    pub fn row_into(&self, i: usize, row: &mut [f64]) {
        let mut q = 0;
        for block in &self.blocks {
            for c in 0..block.ncols() {
                row[q] = block[(i, c)];
                q += 1;
            }
        }
    }

    /// Row i.
    pub fn row(&self, i: usize) -> Vec<f64> {
        let mut row = vec![0.0; self.ncols()];
        self.row_into(i, &mut row);
        row
    }

    /// Column j (a copy).
    pub fn column(&self, j: usize) -> Vec<f64> {
        let mut j = j;
        for block in &self.blocks {
            if j < block.ncols() {
                return block.col_as_slice(j).to_vec();
            }
            j -= block.ncols();
        }
        panic!("column index beyond the columns held");
    }

    /// How many blocks no other copy holds beside this one (for tests of the sharing).
    pub fn shared_blocks(&self) -> usize {
        self.blocks
            .iter()
            .filter(|b| Arc::strong_count(b) > 1)
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dense(a: &Columns) -> Mat<f64> {
        let cols: Vec<Vec<f64>> = (0..a.ncols()).map(|j| a.column(j)).collect();
        Mat::from_fn(a.nrows(), a.ncols(), |i, j| cols[j][i])
    }

    fn sample() -> (Columns, Mat<f64>) {
        let first = Mat::from_fn(7, 3, |i, j| (i * 3 + j) as f64 * 0.5 - 4.0);
        let second = Mat::from_fn(7, 2, |i, j| ((i + 1) * (j + 2)) as f64 / 7.0);
        let whole = Mat::from_fn(7, 5, |i, j| {
            if j < 3 {
                first[(i, j)]
            } else {
                second[(i, j - 3)]
            }
        });
        (Columns::empty(7).joined(first).joined(second), whole)
    }

    #[test]
    fn products_over_blocks_are_the_whole_matrix_products() {
        let (a, whole) = sample();
        assert_eq!((a.nrows(), a.ncols()), (7, 5));
        assert_eq!(dense(&a), whole);
        let y = Mat::from_fn(5, 2, |i, j| (i as f64 - 2.0) * (j as f64 + 0.5));
        let want = &whole * &y;
        let got = a.times(y.as_ref());
        assert!((&got - &want).norm_max() <= 1e-12 * want.norm_max());
        let w = Mat::from_fn(7, 3, |i, j| ((i * j) % 4) as f64 - 1.5);
        let want = whole.transpose() * &w;
        let got = a.transpose_times(w.as_ref());
        assert!((&got - &want).norm_max() <= 1e-12 * want.norm_max());
        let mut out = Mat::from_fn(7, 2, |i, j| (i + j) as f64);
        let before = out.clone();
        a.times_into(out.as_mut(), Accum::Add, y.as_ref(), -2.0);
        let expect = &before - (&whole * &y) * faer::Scale(2.0);
        assert!((&out - &expect).norm_max() <= 1e-12 * expect.norm_max());
        assert_eq!(a.row(4), (0..5).map(|j| whole[(4, j)]).collect::<Vec<_>>());
    }

    #[test]
    fn a_joined_copy_shares_the_blocks_it_had() {
        let (a, _) = sample();
        assert_eq!(a.shared_blocks(), 0);
        let b = a.joined(Mat::from_fn(7, 1, |i, _| i as f64));
        assert_eq!(a.shared_blocks(), 2);
        assert_eq!(b.ncols(), 6);
        assert_eq!(b.column(5), (0..7).map(|i| i as f64).collect::<Vec<_>>());
        drop(b);
        assert_eq!(a.shared_blocks(), 0);
    }

    #[test]
    fn an_empty_store_multiplies_to_zero() {
        let a = Columns::empty(4);
        let mut out = Mat::from_fn(4, 2, |_, _| 3.0);
        a.times_into(out.as_mut(), Accum::Replace, Mat::zeros(0, 2).as_ref(), 1.0);
        assert_eq!(out, Mat::<f64>::zeros(4, 2));
        assert_eq!(a.transpose_times(out.as_ref()), Mat::<f64>::zeros(0, 2));
    }
}
