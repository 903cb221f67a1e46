//! Interactions as sums of terms: the [`Interaction`] trait every group of terms implements, and the
//! listed groups (external one-body terms, internal two-body terms listed once).
//!
//! A system's potential is V(t, x) = Σ_external V_k(t, r_i) + Σ_internal U_k(r_j − r_i). Each group
//! evaluates its terms with 3-slot duals and adds the forces into a flat array of length 3N, so a force
//! evaluation costs one small dual evaluation per term (linear in the number of terms).
//!
//! Determinism: the parallel path evaluates fixed chunks of [`CHUNK`] terms on rayon's pool into a buffer
//! and then adds them to the particles in list order, exactly the additions the serial path performs; the
//! partial energies are summed per chunk and then over chunks in order on both paths. Results are
//! therefore bit-identical for any number of threads. A chain listed as consecutive pairs (s, s+1),
//! (s+1, s+2), … and one-body terms on a range of particles s, s+1, … take a streaming serial path that
//! walks through the arrays in order (no index list, no bounds check per term) and performs the same
//! additions in the same order.

use crate::error::{Error, Result};
use crate::particle::{add3, get3, sub3, Particle, Vec3};
use crate::potential::{
    one_gradient, one_hessian, pair_gradient, pair_hessian, sep, sep64, Body, OneBodyForce, OnePotential,
    PairPotential, TwoBodyForce,
};
use crate::terms::{chain_forces, chain_start, range_forces, range_start, run_terms, span};
use noether_core::Scalar;
use std::sync::Mutex;

/// Terms per parallel work item (fixed: it does not depend on the number of threads).
pub const CHUNK: usize = 2048;

/// Entries (row, column, value) of a sparse symmetric matrix; repeated entries add up.
pub type Triplets = Vec<(usize, usize, f64)>;

/// A group of interaction terms. Implemented by the groups of this crate; the system holds a
/// type-level list of groups (`()`, `(A, B)`), so every evaluation is statically dispatched.
pub trait Interaction: Sync + Send {
    /// Checks particle indices against the number of particles `n`.
    fn validate(&self, n: usize) -> Result<()>;

    /// Number of terms (an estimate for neighbour-list groups) in a system of `n` particles: decides
    /// whether [`Parallel::Auto`](crate::Parallel::Auto) goes parallel.
    fn terms(&self, n: usize) -> usize;

    /// The potential energy of the group, generic over the scalar (the Lagrangian path).
    fn potential<D: Scalar>(&self, t: f64, x: &[D], ps: &[Particle]) -> D;

    /// The potential energy at real positions.
    fn energy(&self, t: f64, x: &[f64], ps: &[Particle]) -> f64 {
        self.potential(t, x, ps)
    }

    /// Adds the conservative forces −∇V into `f` (length 3N); returns V.
    fn add_forces(&self, t: f64, x: &[f64], ps: &[Particle], f: &mut [f64], parallel: bool) -> f64;

    /// `false` when a potential of the group depends on time explicitly.
    fn autonomous(&self) -> bool {
        true
    }

    /// `true` when the group has forces that are not gradients of a potential.
    fn has_nonpotential(&self) -> bool {
        false
    }

    /// Adds the non-potential forces (drag, given two-body forces) into `f`, generic over the scalar
    /// (the generalized force of the Lagrangian path).
    fn add_nonpotential<D: Scalar>(&self, _t: f64, _x: &[D], _v: &[D], _ps: &[Particle], _f: &mut [D]) {}

    /// Appends the group's Hessian entries ∂²V/∂x∂x (3×3 blocks per particle pair) to `out`.
    fn add_hessian(&self, t: f64, x: &[f64], ps: &[Particle], out: &mut Triplets);

    /// After a non-finite force: the first term whose gradient is not finite, as an error.
    fn find_singular(&self, t: f64, x: &[f64], ps: &[Particle]) -> Option<Error>;
}

impl Interaction for () {
    fn validate(&self, _n: usize) -> Result<()> {
        Ok(())
    }
    fn terms(&self, _n: usize) -> usize {
        0
    }
    fn potential<D: Scalar>(&self, _t: f64, _x: &[D], _ps: &[Particle]) -> D {
        D::zero()
    }
    fn add_forces(&self, _: f64, _: &[f64], _: &[Particle], _: &mut [f64], _: bool) -> f64 {
        0.0
    }
    fn add_hessian(&self, _: f64, _: &[f64], _: &[Particle], _: &mut Triplets) {}
    fn find_singular(&self, _: f64, _: &[f64], _: &[Particle]) -> Option<Error> {
        None
    }
}

impl<A: Interaction, B: Interaction> Interaction for (A, B) {
    fn validate(&self, n: usize) -> Result<()> {
        self.0.validate(n)?;
        self.1.validate(n)
    }
    fn terms(&self, n: usize) -> usize {
        self.0.terms(n).saturating_add(self.1.terms(n))
    }
    fn potential<D: Scalar>(&self, t: f64, x: &[D], ps: &[Particle]) -> D {
        self.0.potential(t, x, ps) + self.1.potential(t, x, ps)
    }
    fn energy(&self, t: f64, x: &[f64], ps: &[Particle]) -> f64 {
        self.0.energy(t, x, ps) + self.1.energy(t, x, ps)
    }
    fn add_forces(&self, t: f64, x: &[f64], ps: &[Particle], f: &mut [f64], par: bool) -> f64 {
        let a = self.0.add_forces(t, x, ps, f, par);
        a + self.1.add_forces(t, x, ps, f, par)
    }
    fn has_nonpotential(&self) -> bool {
        self.0.has_nonpotential() || self.1.has_nonpotential()
    }
    fn autonomous(&self) -> bool {
        self.0.autonomous() && self.1.autonomous()
    }
    fn add_nonpotential<D: Scalar>(&self, t: f64, x: &[D], v: &[D], ps: &[Particle], f: &mut [D]) {
        self.0.add_nonpotential(t, x, v, ps, f);
        self.1.add_nonpotential(t, x, v, ps, f);
    }
    fn add_hessian(&self, t: f64, x: &[f64], ps: &[Particle], out: &mut Triplets) {
        self.0.add_hessian(t, x, ps, out);
        self.1.add_hessian(t, x, ps, out);
    }
    fn find_singular(&self, t: f64, x: &[f64], ps: &[Particle]) -> Option<Error> {
        self.0
            .find_singular(t, x, ps)
            .or_else(|| self.1.find_singular(t, x, ps))
    }
}

/// Appends the blocks of a pair term: (i,i) and (j,j) get +H, (i,j) and (j,i) get −H.
pub(crate) fn push_pair_block(out: &mut Triplets, i: usize, j: usize, h: [[f64; 3]; 3]) {
    for (a, row) in h.iter().enumerate() {
        for (b, &v) in row.iter().enumerate() {
            out.push((3 * i + a, 3 * i + b, v));
            out.push((3 * j + a, 3 * j + b, v));
            out.push((3 * i + a, 3 * j + b, -v));
            out.push((3 * j + a, 3 * i + b, -v));
        }
    }
}

fn check_index(interaction: usize, index: usize, n: usize) -> Result<()> {
    if index >= n {
        Err(Error::UnknownParticle {
            interaction,
            index,
            n,
        })
    } else {
        Ok(())
    }
}

/// Converts user indices to the compact stored form (an index beyond u32 becomes u32::MAX, which
/// `validate` rejects).
fn to_indices(indices: impl IntoIterator<Item = usize>) -> Vec<u32> {
    indices
        .into_iter()
        .map(|i| u32::try_from(i).unwrap_or(u32::MAX))
        .collect()
}

/// Converts user pairs to the compact stored form.
fn to_pairs(pairs: impl IntoIterator<Item = (usize, usize)>) -> Vec<[u32; 2]> {
    pairs
        .into_iter()
        .map(|(i, j)| {
            [
                u32::try_from(i).unwrap_or(u32::MAX),
                u32::try_from(j).unwrap_or(u32::MAX),
            ]
        })
        .collect()
}

fn validate_indices(indices: &[u32], n: usize) -> Result<()> {
    for (k, &i) in indices.iter().enumerate() {
        check_index(k, i as usize, n)?;
    }
    Ok(())
}

fn validate_pairs(pairs: &[[u32; 2]], n: usize) -> Result<()> {
    for (k, &[i, j]) in pairs.iter().enumerate() {
        check_index(k, i as usize, n)?;
        check_index(k, j as usize, n)?;
        if i == j {
            return Err(Error::SelfInteraction {
                interaction: k,
                index: i as usize,
            });
        }
    }
    Ok(())
}

/// Internal (two-body) potential terms, each pair listed once: U(r_j − r_i) for every (i, j).
pub struct Internal<P> {
    potential: P,
    pairs: Vec<[u32; 2]>,
    chain: Option<usize>,
    scratch: Mutex<Vec<Vec3>>,
}

impl<P: PairPotential> Internal<P> {
    /// The potential `potential` between each pair (i, j) of `pairs` (particle i plays particle 1).
    pub fn new(potential: P, pairs: impl IntoIterator<Item = (usize, usize)>) -> Self {
        let pairs = to_pairs(pairs);
        Internal {
            potential,
            chain: chain_start(&pairs),
            pairs,
            scratch: Mutex::new(Vec::new()),
        }
    }

    /// Nearest neighbours of a chain of `n` particles: pairs (0,1), (1,2), …, (n−2, n−1).
    pub fn chain(potential: P, n: usize) -> Self {
        Self::new(potential, (1..n).map(|i| (i - 1, i)))
    }

    /// The pairs, in list order.
    pub fn pairs(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.pairs.iter().map(|p| (p[0] as usize, p[1] as usize))
    }
}

impl<P: PairPotential> Interaction for Internal<P> {
    fn validate(&self, n: usize) -> Result<()> {
        validate_pairs(&self.pairs, n)
    }
    fn terms(&self, _n: usize) -> usize {
        self.pairs.len()
    }
    fn potential<D: Scalar>(&self, _t: f64, x: &[D], ps: &[Particle]) -> D {
        self.pairs.iter().fold(D::zero(), |acc, &[i, j]| {
            let (i, j) = (i as usize, j as usize);
            acc + self.potential.energy(sep(x, i, j), &ps[i], &ps[j])
        })
    }
    fn energy(&self, _t: f64, x: &[f64], ps: &[Particle]) -> f64 {
        self.pairs.iter().fold(0.0, |acc, &[i, j]| {
            let (i, j) = (i as usize, j as usize);
            acc + self.potential.energy(sep64(x, i, j), &ps[i], &ps[j])
        })
    }
    fn add_forces(&self, _t: f64, x: &[f64], ps: &[Particle], f: &mut [f64], parallel: bool) -> f64 {
        if let (Some(s), false) = (self.chain, parallel) {
            let (x, ps, f) = span(x, ps, f, s, self.pairs.len() + 1);
            return chain_forces(&self.potential, x, ps, f);
        }
        run_terms!(
            &self.pairs,
            |&[i, j]| {
                let (i, j) = (i as usize, j as usize);
                pair_gradient(&self.potential, sep64(x, i, j), &ps[i], &ps[j])
            },
            |&[i, j], g| {
                // F on 1 = +∇U, F on 2 = −∇U: Newton's third law by construction.
                add3(f, i as usize, g);
                sub3(f, j as usize, g);
            },
            parallel,
            &self.scratch,
        )
    }
    fn add_hessian(&self, _t: f64, x: &[f64], ps: &[Particle], out: &mut Triplets) {
        for &[i, j] in &self.pairs {
            let (i, j) = (i as usize, j as usize);
            let h = pair_hessian(&self.potential, sep64(x, i, j), &ps[i], &ps[j]);
            push_pair_block(out, i, j, h);
        }
    }
    fn find_singular(&self, _t: f64, x: &[f64], ps: &[Particle]) -> Option<Error> {
        self.pairs.iter().find_map(|&[i, j]| {
            let (i, j) = (i as usize, j as usize);
            let r = sep64(x, i, j);
            let (u, g) = pair_gradient(&self.potential, r, &ps[i], &ps[j]);
            (!(u.is_finite() && g.iter().all(|v| v.is_finite()))).then(|| Error::pair(i, j, r))
        })
    }
}

/// External (one-body) potential terms: V(t, r_i) for every listed particle i.
pub struct External<P> {
    potential: P,
    indices: Vec<u32>,
    range: Option<usize>,
    scratch: Mutex<Vec<Vec3>>,
}

impl<P: OnePotential> External<P> {
    /// The potential `potential` acting on each particle of `indices`.
    pub fn new(potential: P, indices: impl IntoIterator<Item = usize>) -> Self {
        let indices = to_indices(indices);
        External {
            potential,
            range: range_start(&indices),
            indices,
            scratch: Mutex::new(Vec::new()),
        }
    }
}

impl<P: OnePotential> Interaction for External<P> {
    fn autonomous(&self) -> bool {
        !P::TIME_DEPENDENT
    }
    fn validate(&self, n: usize) -> Result<()> {
        validate_indices(&self.indices, n)
    }
    fn terms(&self, _n: usize) -> usize {
        self.indices.len()
    }
    fn potential<D: Scalar>(&self, t: f64, x: &[D], ps: &[Particle]) -> D {
        self.indices.iter().fold(D::zero(), |acc, &i| {
            let i = i as usize;
            acc + self
                .potential
                .energy(t, [x[3 * i], x[3 * i + 1], x[3 * i + 2]], &ps[i])
        })
    }
    fn energy(&self, t: f64, x: &[f64], ps: &[Particle]) -> f64 {
        self.indices.iter().fold(0.0, |acc, &i| {
            acc + self.potential.energy(t, get3(x, i as usize), &ps[i as usize])
        })
    }
    fn add_forces(&self, t: f64, x: &[f64], ps: &[Particle], f: &mut [f64], parallel: bool) -> f64 {
        if let (Some(s), false) = (self.range, parallel) {
            let (x, ps, f) = span(x, ps, f, s, self.indices.len());
            return range_forces(&self.potential, t, x, ps, f);
        }
        run_terms!(
            &self.indices,
            |&i| one_gradient(&self.potential, t, get3(x, i as usize), &ps[i as usize]),
            |&i, g| sub3(f, i as usize, g),
            parallel,
            &self.scratch,
        )
    }
    fn add_hessian(&self, t: f64, x: &[f64], ps: &[Particle], out: &mut Triplets) {
        for &i in &self.indices {
            let i = i as usize;
            let h = one_hessian(&self.potential, t, get3(x, i), &ps[i]);
            for (a, row) in h.iter().enumerate() {
                for (b, &v) in row.iter().enumerate() {
                    out.push((3 * i + a, 3 * i + b, v));
                }
            }
        }
    }
    fn find_singular(&self, t: f64, x: &[f64], ps: &[Particle]) -> Option<Error> {
        self.indices.iter().find_map(|&i| {
            let i = i as usize;
            let (u, g) = one_gradient(&self.potential, t, get3(x, i), &ps[i]);
            (!(u.is_finite() && g.iter().all(|v| v.is_finite()))).then_some(Error::Core(
                noether_core::Error::NonFinite {
                    what: "one-body potential or its force",
                    index: i,
                },
            ))
        })
    }
}

/// The [`Interaction`] methods of a group of forces that are not gradients: no potential, no
/// conservative forces, no Hessian, nothing singular; `has_nonpotential` is true.
macro_rules! forces_only {
    () => {
        fn potential<D: Scalar>(&self, _: f64, _: &[D], _: &[Particle]) -> D {
            D::zero()
        }
        fn add_forces(&self, _: f64, _: &[f64], _: &[Particle], _: &mut [f64], _: bool) -> f64 {
            0.0
        }
        fn has_nonpotential(&self) -> bool {
            true
        }
        fn add_hessian(&self, _: f64, _: &[f64], _: &[Particle], _: &mut Triplets) {}
        fn find_singular(&self, _: f64, _: &[f64], _: &[Particle]) -> Option<Error> {
            None
        }
    };
}

/// External forces that are not gradients (drag): F(t, r_i, v_i) on each listed particle i.
pub struct ExternalForce<F> {
    force: F,
    indices: Vec<u32>,
}

impl<F: OneBodyForce> ExternalForce<F> {
    /// The force `force` on each particle of `indices`.
    pub fn new(force: F, indices: impl IntoIterator<Item = usize>) -> Self {
        ExternalForce {
            force,
            indices: to_indices(indices),
        }
    }
}

impl<F: OneBodyForce> Interaction for ExternalForce<F> {
    fn validate(&self, n: usize) -> Result<()> {
        validate_indices(&self.indices, n)
    }
    fn terms(&self, _n: usize) -> usize {
        self.indices.len()
    }
    forces_only!();
    fn add_nonpotential<D: Scalar>(&self, t: f64, x: &[D], v: &[D], ps: &[Particle], f: &mut [D]) {
        for &i in &self.indices {
            let i = i as usize;
            add3(f, i, self.force.force(t, get3(x, i), get3(v, i), &ps[i]));
        }
    }
}

/// Internal forces given as a by-on two-body force, each pair (by, on) listed once: `+F(by, on)` acts on
/// `on` and `−F(by, on)` on `by`.
pub struct InternalForce<F> {
    force: F,
    pairs: Vec<[u32; 2]>,
}

impl<F: TwoBodyForce> InternalForce<F> {
    /// The force `force` for each pair (by, on) of `pairs`.
    pub fn new(force: F, pairs: impl IntoIterator<Item = (usize, usize)>) -> Self {
        InternalForce {
            force,
            pairs: to_pairs(pairs),
        }
    }
}

impl<F: TwoBodyForce> Interaction for InternalForce<F> {
    fn validate(&self, n: usize) -> Result<()> {
        validate_pairs(&self.pairs, n)
    }
    fn terms(&self, _n: usize) -> usize {
        self.pairs.len()
    }
    forces_only!();
    fn add_nonpotential<D: Scalar>(&self, t: f64, x: &[D], v: &[D], ps: &[Particle], f: &mut [D]) {
        for &[by, on] in &self.pairs {
            let (by, on) = (by as usize, on as usize);
            let g = self.force.force(
                t,
                Body {
                    r: get3(x, by),
                    v: get3(v, by),
                    p: &ps[by],
                },
                Body {
                    r: get3(x, on),
                    v: get3(v, on),
                    p: &ps[on],
                },
            );
            add3(f, on, g);
            sub3(f, by, g);
        }
    }
}
