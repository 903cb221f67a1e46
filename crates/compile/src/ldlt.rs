//! The solve of M x = b for a symmetric positive definite M, written into the graph as an unrolled
//! LDLᵀ factorisation (no square root; the structural zeros of M fold away):
//!
//! ```text
//! d_j  = m_jj − Σ_{k<j} l_jk (l_jk d_k)
//! l_ij = (m_ij − Σ_{k<j} l_ik (l_jk d_k)) / d_j            i > j
//! y_i  = b_i − Σ_{k<i} l_ik y_k,    z_i = y_i / d_i,    x_i = z_i − Σ_{k>i} l_ki x_k
//! ```
//!
//! (Golub & Van Loan, *Matrix Computations*, 4th ed., §4.1.2.) The pivots d_j are returned too: M is
//! positive definite exactly when every d_j > 0, which the compiled model checks at every call before
//! it trusts x, with the singularity criterion of [`linalg`](noether_core::linalg).

use crate::graph::{Graph, Id};

/// x and the pivots d of M x = b, M given by its lower triangle (`m[i][j]` for j ≤ i).
pub fn solve(g: &mut Graph, m: &[Vec<Id>], b: &[Id]) -> (Vec<Id>, Vec<Id>) {
    let n = b.len();
    let mut l: Vec<Vec<Id>> = vec![Vec::new(); n];
    let mut d: Vec<Id> = Vec::with_capacity(n);
    for j in 0..n {
        // w_k = l_jk d_k for k < j, shared by the pivot and by column j of L.
        let w: Vec<Id> = (0..j).map(|k| g.mul(l[j][k], d[k])).collect();
        let terms: Vec<Id> = (0..j).map(|k| g.mul(l[j][k], w[k])).collect();
        let s = g.sum(terms);
        let dj = g.sub(m[j][j], s);
        d.push(dj);
        for i in j + 1..n {
            let terms: Vec<Id> = (0..j).map(|k| g.mul(l[i][k], w[k])).collect();
            let s = g.sum(terms);
            let r = g.sub(m[i][j], s);
            let lij = g.div(r, dj);
            l[i].push(lij);
        }
    }
    let mut y: Vec<Id> = Vec::with_capacity(n);
    for i in 0..n {
        let terms: Vec<Id> = (0..i).map(|k| g.mul(l[i][k], y[k])).collect();
        let s = g.sum(terms);
        y.push(g.sub(b[i], s));
    }
    let mut x: Vec<Id> = (0..n).map(|i| g.div(y[i], d[i])).collect();
    for i in (0..n).rev() {
        let terms: Vec<Id> = (i + 1..n).map(|k| g.mul(l[k][i], x[k])).collect();
        let s = g.sum(terms);
        x[i] = g.sub(x[i], s);
    }
    (x, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 3 symmetric positive definite system with the solution x = (1, −2, 3): M x = b exactly
    /// in integers, so the unrolled solve must give x to a few roundings.
    #[test]
    fn solves_a_small_system() {
        let mut g = Graph::new();
        let m = [[4.0, 1.0, 2.0], [1.0, 5.0, -1.0], [2.0, -1.0, 6.0]];
        let x_true = [1.0, -2.0, 3.0];
        let b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| m[i][j] * x_true[j]).sum())
            .collect();
        let mm: Vec<Vec<Id>> = (0..3)
            .map(|i| (0..=i).map(|j| g.input((3 * i + j) as u32)).collect())
            .collect();
        let bb: Vec<Id> = (0..3).map(|i| g.input(9 + i as u32)).collect();
        let (x, d) = solve(&mut g, &mm, &bb);
        let mut inputs = vec![0.0; 12];
        for i in 0..3 {
            for j in 0..=i {
                inputs[3 * i + j] = m[i][j];
            }
            inputs[9 + i] = b[i];
        }
        let last = *x.iter().chain(&d).max().unwrap();
        let v = g.evaluate(&inputs, last);
        for i in 0..3 {
            assert!(
                (v[x[i] as usize] - x_true[i]).abs() < 1e-14,
                "x{i} = {}",
                v[x[i] as usize]
            );
        }
        assert_eq!(v[d[0] as usize], 4.0);
    }
}
