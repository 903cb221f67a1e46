//! A sparse symmetric matrix in compressed-row form, assembled from the 3×3 blocks of the terms.

use nalgebra::DMatrix;

/// ∂²V/∂x∂x in compressed sparse rows: only the blocks of interacting particles are stored, so a chain
/// of N particles has O(N) entries, not 9N².
#[derive(Debug, Clone, PartialEq)]
pub struct SparseHessian {
    n: usize,
    indptr: Vec<usize>,
    indices: Vec<usize>,
    values: Vec<f64>,
}

impl SparseHessian {
    /// Sums repeated (row, column) entries of `triplets` into an n × n matrix.
    pub fn from_triplets(n: usize, mut triplets: Vec<(usize, usize, f64)>) -> Self {
        triplets.sort_by_key(|&(i, j, _)| (i, j));
        let mut indptr = vec![0; n + 1];
        let mut indices = Vec::with_capacity(triplets.len());
        let mut values: Vec<f64> = Vec::with_capacity(triplets.len());
        let mut last = None;
        for (i, j, v) in triplets {
            if last == Some((i, j)) {
                *values.last_mut().expect("an entry was pushed") += v;
            } else {
                indices.push(j);
                values.push(v);
                indptr[i + 1] += 1;
                last = Some((i, j));
            }
        }
        for i in 0..n {
            indptr[i + 1] += indptr[i];
        }
        SparseHessian {
            n,
            indptr,
            indices,
            values,
        }
    }

    /// Dimension n (= 3N).
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// Entry (i, j) (0 when not stored).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let r = self.indptr[i]..self.indptr[i + 1];
        match self.indices[r.clone()].binary_search(&j) {
            Ok(k) => self.values[r.start + k],
            Err(_) => 0.0,
        }
    }

    /// y = H x.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.n) {
            let r = self.indptr[i]..self.indptr[i + 1];
            *yi = self.indices[r.clone()]
                .iter()
                .zip(&self.values[r])
                .map(|(&j, v)| v * x[j])
                .sum();
        }
    }

    /// The dense matrix (for small systems and tests).
    pub fn to_dense(&self) -> DMatrix<f64> {
        let mut m = DMatrix::zeros(self.n, self.n);
        for i in 0..self.n {
            for k in self.indptr[i]..self.indptr[i + 1] {
                m[(i, self.indices[k])] = self.values[k];
            }
        }
        m
    }
}
