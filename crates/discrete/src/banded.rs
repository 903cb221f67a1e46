//! A banded matrix and its LU factorization with partial pivoting, for the Newton Jacobians of chains
//! (a potential that is a sum of nearest-neighbour and on-site terms gives a tridiagonal Jacobian).
//!
//! Elimination with row interchanges, as LAPACK's `dgbtrf`: with kl sub- and ku super-diagonals, U has
//! kl + ku super-diagonals after pivoting, and the factorization costs O(n·kl·(kl + ku)), linear in n.
//! (nalgebra-sparse offers only a Cholesky factorization, which needs a positive definite Jacobian; the
//! midpoint Jacobian M/h + (h/4)∇²V is indefinite for non-convex potentials at large steps.)
//!
//! ```
//! use noether_discrete::banded::Banded;
//!
//! // [[2, 1, 0], [1, 2, 1], [0, 1, 2]] x = [3, 4, 3]  →  x = [1, 1, 1]
//! let mut a = Banded::zeros(3, 1, 1);
//! for i in 0..3 {
//!     a.add(i, i, 2.0);
//!     if i + 1 < 3 {
//!         a.add(i, i + 1, 1.0);
//!         a.add(i + 1, i, 1.0);
//!     }
//! }
//! let lu = a.factor().unwrap();
//! let mut b = [3.0, 4.0, 3.0];
//! lu.solve(&mut b);
//! assert!(b.iter().all(|x| (x - 1.0).abs() < 1e-15));
//! ```

use noether_core::{Error, Result};

/// An n × n matrix with `kl` sub-diagonals and `ku` super-diagonals, stored by rows with room for the
/// kl extra super-diagonals that pivoting fills in.
#[derive(Debug, Clone, PartialEq)]
pub struct Banded {
    n: usize,
    kl: usize,
    ku: usize,
    /// Row i holds columns i − kl ..= i + kl + ku at offsets 0 ..= 2kl + ku.
    data: Vec<f64>,
}

impl Banded {
    /// The zero matrix of size n with bandwidths (kl, ku).
    pub fn zeros(n: usize, kl: usize, ku: usize) -> Self {
        Banded {
            n,
            kl,
            ku,
            data: vec![0.0; n * (2 * kl + ku + 1)],
        }
    }

    /// Size n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// (kl, ku).
    pub fn bandwidths(&self) -> (usize, usize) {
        (self.kl, self.ku)
    }

    fn width(&self) -> usize {
        2 * self.kl + self.ku + 1
    }

    /// Sets every entry to zero.
    pub fn fill_zero(&mut self) {
        self.data.iter_mut().for_each(|x| *x = 0.0);
    }

    /// `true` when (i, j) lies inside the band.
    pub fn in_band(&self, i: usize, j: usize) -> bool {
        i < self.n && j < self.n && j + self.kl >= i && j <= i + self.ku
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> usize {
        i * self.width() + (j + self.kl - i)
    }

    /// Adds `v` to entry (i, j), which must lie inside the band (panics otherwise: an assembly bug).
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        assert!(
            self.in_band(i, j),
            "entry ({i}, {j}) outside the band ({}, {})",
            self.kl,
            self.ku
        );
        let k = self.at(i, j);
        self.data[k] += v;
    }

    /// Entry (i, j) (zero outside the band).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if self.in_band(i, j) {
            self.data[self.at(i, j)]
        } else {
            0.0
        }
    }

    /// y = A x.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.n) {
            let lo = i.saturating_sub(self.kl);
            let hi = (i + self.ku).min(self.n - 1);
            *yi = (lo..=hi).map(|j| self.data[self.at(i, j)] * x[j]).sum();
        }
    }

    /// LU factorization with partial pivoting (consumes the matrix; the storage becomes the factor).
    /// Errors with [`Error::SingularMatrix`] on a zero or non-finite pivot.
    pub fn factor(mut self) -> Result<BandedLu> {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        let mut piv = vec![0usize; n];
        let mut mult = vec![0.0; n * kl];
        let scale = self.data.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for k in 0..n {
            let last_row = (k + kl).min(n - 1);
            let last_col = (k + kl + ku).min(n - 1);
            let mut p = k;
            let mut best = self.data[self.at(k, k)].abs();
            for i in k + 1..=last_row {
                let v = self.data[self.at(i, k)].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if !best.is_finite() || best <= f64::EPSILON * scale * 1e-3 || best == 0.0 {
                return Err(Error::SingularMatrix {
                    what: "banded Newton Jacobian",
                });
            }
            piv[k] = p;
            if p != k {
                for j in k..=last_col {
                    let (a, b) = (self.at(k, j), self.at(p, j));
                    self.data.swap(a, b);
                }
            }
            let d = self.data[self.at(k, k)];
            for i in k + 1..=last_row {
                let ik = self.at(i, k);
                let l = self.data[ik] / d;
                self.data[ik] = 0.0;
                mult[k * kl + (i - k - 1)] = l;
                if l != 0.0 {
                    for j in k + 1..=last_col {
                        let kj = self.data[self.at(k, j)];
                        let ij = self.at(i, j);
                        self.data[ij] -= l * kj;
                    }
                }
            }
        }
        Ok(BandedLu { u: self, piv, mult })
    }
}

/// The factor P A = L U of a [`Banded`] matrix.
#[derive(Debug, Clone)]
pub struct BandedLu {
    u: Banded,
    piv: Vec<usize>,
    mult: Vec<f64>,
}

impl BandedLu {
    /// Overwrites `b` with A⁻¹ b.
    pub fn solve(&self, b: &mut [f64]) {
        let (n, kl, ku) = (self.u.n, self.u.kl, self.u.ku);
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                b.swap(k, p);
            }
            let bk = b[k];
            let last = (k + kl).min(n - 1);
            for (bi, l) in b[k + 1..=last].iter_mut().zip(&self.mult[k * kl..]) {
                *bi -= l * bk;
            }
        }
        for k in (0..n).rev() {
            let last_col = (k + kl + ku).min(n - 1);
            let mut s = b[k];
            for (j, bj) in b.iter().enumerate().take(last_col + 1).skip(k + 1) {
                s -= self.u.data[self.u.at(k, j)] * bj;
            }
            b[k] = s / self.u.data[self.u.at(k, k)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    /// A random-ish non-symmetric banded matrix that needs pivoting (small diagonal) against nalgebra's
    /// dense LU on the same matrix.
    #[test]
    fn regress_banded_lu_vs_dense() {
        let (n, kl, ku) = (23, 2, 3);
        let mut a = Banded::zeros(n, kl, ku);
        let mut dense = DMatrix::zeros(n, n);
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                let v = if i == j { 1e-3 * rnd() } else { rnd() };
                a.add(i, j, v);
                dense[(i, j)] = v;
            }
        }
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut x = b.clone();
        a.clone().factor().unwrap().solve(&mut x);
        let xd = dense
            .clone()
            .lu()
            .solve(&nalgebra::DVector::from_vec(b.clone()))
            .unwrap();
        for i in 0..n {
            assert!(
                (x[i] - xd[i]).abs() < 1e-10 * (1.0 + xd[i].abs()),
                "{i}: {} vs {}",
                x[i],
                xd[i]
            );
        }
        let mut y = vec![0.0; n];
        a.mul_vec(&x, &mut y);
        for i in 0..n {
            assert!((y[i] - b[i]).abs() < 1e-12);
        }
    }

    #[test]
    fn bad_input_singular_banded() {
        let a = Banded::zeros(4, 1, 1);
        assert!(matches!(a.factor(), Err(Error::SingularMatrix { .. })));
    }
}
