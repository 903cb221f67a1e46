//! Discrete Noether momenta.
//!
//! If the discrete Lagrangian is invariant under the flow of a vector field ξ(q) on configuration space
//! (translations, rotations), the discrete Noether theorem says that the momentum map
//!
//! ```text
//! J(q_k, p_k) = p_k · ξ(q_k),      p_k = −D₁L_d(q_k, q_{k+1}) = D₂L_d(q_{k−1}, q_k)
//! ```
//!
//! is exactly conserved by the variational integrator (up to rounding and the Newton residual's
//! component along ξ). For L = ½|q̇|² − V with V invariant under translating every mass together, the
//! generator is ξ = (1, …, 1) and J is the total momentum.
//!
//! ```
//! use noether_discrete::momentum::{noether_momentum, PlanarRotation, Translation};
//!
//! // Angular momentum x p_y − y p_x of one particle in the plane.
//! let l = noether_momentum(&PlanarRotation::new(vec![(0, 1)]), &[1.0, 2.0], &[3.0, 4.0]);
//! assert_eq!(l, 1.0 * 4.0 - 2.0 * 3.0);
//! // Total momentum of three masses on a line.
//! assert_eq!(noether_momentum(&Translation::uniform(3), &[0.0; 3], &[1.0, 2.0, 3.0]), 6.0);
//! ```

/// The infinitesimal generator ξ(q) of a symmetry of the Lagrangian.
pub trait Symmetry {
    /// Writes ξ(q) into `xi` (same length as q).
    fn generator(&self, q: &[f64], xi: &mut [f64]);
}

impl<F: Fn(&[f64], &mut [f64])> Symmetry for F {
    fn generator(&self, q: &[f64], xi: &mut [f64]) {
        self(q, xi)
    }
}

/// A translation with a constant direction ξ(q) = d.
#[derive(Debug, Clone, PartialEq)]
pub struct Translation {
    /// The direction d (length dof).
    pub direction: Vec<f64>,
}

impl Translation {
    /// Translation of every coordinate together, d = (1, …, 1): masses on a line moving as one.
    pub fn uniform(dof: usize) -> Self {
        Translation {
            direction: vec![1.0; dof],
        }
    }
}

impl Symmetry for Translation {
    fn generator(&self, _q: &[f64], xi: &mut [f64]) {
        xi.copy_from_slice(&self.direction);
    }
}

/// A rotation in the plane of each listed coordinate pair (x, y): ξ = (−y, x) on those pairs, 0 elsewhere.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarRotation {
    /// The (x, y) coordinate index pairs rotated together.
    pub pairs: Vec<(usize, usize)>,
}

impl PlanarRotation {
    /// Rotation of the listed (x, y) pairs.
    pub fn new(pairs: Vec<(usize, usize)>) -> Self {
        PlanarRotation { pairs }
    }
}

impl Symmetry for PlanarRotation {
    fn generator(&self, q: &[f64], xi: &mut [f64]) {
        xi.iter_mut().for_each(|x| *x = 0.0);
        for &(i, j) in &self.pairs {
            xi[i] = -q[j];
            xi[j] = q[i];
        }
    }
}

/// The Noether momentum J = p · ξ(q), summed with Neumaier's compensated summation so that the reported
/// value carries no more rounding than its terms.
pub fn noether_momentum<S: Symmetry + ?Sized>(symmetry: &S, q: &[f64], p: &[f64]) -> f64 {
    let mut xi = vec![0.0; q.len()];
    symmetry.generator(q, &mut xi);
    compensated_sum(p.iter().zip(&xi).map(|(a, b)| a * b))
}

/// Neumaier's compensated sum of `terms`.
pub fn compensated_sum(terms: impl IntoIterator<Item = f64>) -> f64 {
    let (mut s, mut c) = (0.0_f64, 0.0_f64);
    for x in terms {
        let t = s + x;
        c += if s.abs() >= x.abs() {
            (s - t) + x
        } else {
            (x - t) + s
        };
        s = t;
    }
    s + c
}
