//! The particle system: particles plus a type-level list of interaction groups; forces, energies,
//! momenta; the system as a core [`Lagrangian`] and as a core [`Dynamics`] with term-by-term forces.
//!
//! L(x, ẋ) = Σ_i ½ m_i |ẋ_i|² − V(t, x), V = Σ one-body terms + Σ two-body terms; non-potential forces
//! (drag, given two-body forces) are the generalized forces Q. The equations of motion are
//! m_i ẍ_i = F_i = −∂V/∂x_i + Q_i.

use crate::error::{Error, Result};
use crate::hessian::SparseHessian;
use crate::interaction::Interaction;
use crate::particle::{Particle, Vec3};
use noether_core::error::{check_finite, check_len, check_result, finite_result};
use noether_core::{Dynamics, Lagrangian, Scalar, State};

/// When force evaluations use rayon's thread pool. All choices give bit-identical results.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Parallel {
    /// Parallel when the pool has more than one thread and the system has at least 16384 terms.
    #[default]
    Auto,
    /// Always one thread.
    Serial,
    /// Always on rayon's pool.
    Rayon,
}

/// Terms from which [`Parallel::Auto`] goes parallel.
pub const AUTO_PARALLEL_TERMS: usize = 16384;

/// Particles and their interactions.
///
/// ```
/// use noether_particles::prelude::*;
///
/// // Two unit masses joined by a spring of rest length 1, stretched to 1.5.
/// let sys = System::new(vec![Particle::new(1.0); 2]).unwrap()
///     .with(Internal::new(Spring { k: 2.0, re: 1.0 }, [(0, 1)])).unwrap();
/// let s = sys.state(0.0, &[[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]], &[[0.0; 3]; 2]).unwrap();
/// let mut f = vec![0.0; 6];
/// let v = sys.forces(0.0, s.q.as_slice(), s.v.as_slice(), &mut f).unwrap();
/// assert!((v - 0.25).abs() < 1e-15);                 // ½ k (r − re)²
/// assert_eq!((f[0], f[3]), (1.0, -1.0));             // ∓k (r − re) along x: third law
/// ```
pub struct System<I = ()> {
    particles: Vec<Particle>,
    inv_mass: Vec<f64>,
    interactions: I,
    parallel: Parallel,
}

impl System<()> {
    /// A system of `particles` without interactions (add them with [`System::with`]).
    pub fn new(particles: Vec<Particle>) -> Result<Self> {
        for (i, p) in particles.iter().enumerate() {
            p.validate(i)?;
        }
        let inv_mass = particles.iter().map(|p| 1.0 / p.mass).collect();
        Ok(System {
            particles,
            inv_mass,
            interactions: (),
            parallel: Parallel::Auto,
        })
    }
}

impl<I: Interaction> System<I> {
    /// Adds a group of interaction terms, checking its particle indices.
    pub fn with<J: Interaction>(self, group: J) -> Result<System<(I, J)>> {
        group.validate(self.particles.len())?;
        Ok(System {
            particles: self.particles,
            inv_mass: self.inv_mass,
            interactions: (self.interactions, group),
            parallel: self.parallel,
        })
    }

    /// Sets the parallel policy.
    pub fn parallel(mut self, parallel: Parallel) -> Self {
        self.parallel = parallel;
        self
    }

    /// The particles.
    pub fn particles(&self) -> &[Particle] {
        &self.particles
    }

    /// The interaction groups.
    pub fn interactions(&self) -> &I {
        &self.interactions
    }

    /// Number of particles N.
    pub fn len(&self) -> usize {
        self.particles.len()
    }

    /// `true` for a system without particles.
    pub fn is_empty(&self) -> bool {
        self.particles.is_empty()
    }

    /// `true` when some force is not the gradient of a potential.
    pub fn has_nonpotential_forces(&self) -> bool {
        self.interactions.has_nonpotential()
    }

    /// A state from positions and velocities per particle (checked: N of each, all finite).
    pub fn state(&self, t: f64, positions: &[Vec3], velocities: &[Vec3]) -> Result<State> {
        let n = self.len();
        for (what, a) in [("positions", positions), ("velocities", velocities)] {
            if a.len() != n {
                return Err(noether_core::Error::Dimension {
                    what,
                    expected: n,
                    got: a.len(),
                }
                .into());
            }
        }
        let s = State::new(t, positions.concat(), velocities.concat());
        s.validate(3 * n)?;
        Ok(s)
    }

    /// A state of motion along x (1D: y = z = 0).
    pub fn state_1d(&self, t: f64, x: &[f64], v: &[f64]) -> Result<State> {
        let p: Vec<Vec3> = x.iter().map(|&a| [a, 0.0, 0.0]).collect();
        let w: Vec<Vec3> = v.iter().map(|&a| [a, 0.0, 0.0]).collect();
        self.state(t, &p, &w)
    }

    /// A state of motion in the xy plane (2D: z = 0).
    pub fn state_2d(&self, t: f64, x: &[[f64; 2]], v: &[[f64; 2]]) -> Result<State> {
        let p: Vec<Vec3> = x.iter().map(|a| [a[0], a[1], 0.0]).collect();
        let w: Vec<Vec3> = v.iter().map(|a| [a[0], a[1], 0.0]).collect();
        self.state(t, &p, &w)
    }

    fn check(&self, x: &[f64], v: Option<&[f64]>) -> Result<()> {
        self.check_vector("positions", x)?;
        match v {
            Some(v) => self.check_vector("velocities", v),
            None => Ok(()),
        }
    }

    fn use_parallel(&self) -> bool {
        match self.parallel {
            Parallel::Serial => false,
            Parallel::Rayon => true,
            Parallel::Auto => {
                rayon::current_num_threads() > 1 && self.interactions.terms(self.len()) >= AUTO_PARALLEL_TERMS
            }
        }
    }

    /// Writes the conservative forces F = −∇V into `f` (length 3N); returns V. Two particles at the
    /// same position under a singular potential give [`Error::Coincident`], not NaN.
    pub fn potential_forces(&self, t: f64, x: &[f64], f: &mut [f64]) -> Result<f64> {
        // Non-finite positions are caught after the evaluation (one pass over f instead of two).
        check_len("positions", x, 3 * self.len())?;
        check_len("forces", f, x.len())?;
        f.iter_mut().for_each(|a| *a = 0.0);
        let v = self
            .interactions
            .add_forces(t, x, &self.particles, f, self.use_parallel());
        self.finite_or_singular(t, x, f, v)?;
        Ok(v)
    }

    /// Writes the total forces (potential and non-potential) into `f`; returns V.
    pub fn forces(&self, t: f64, x: &[f64], v: &[f64], f: &mut [f64]) -> Result<f64> {
        check_len("velocities", v, 3 * self.len())?;
        let e = self.potential_forces(t, x, f)?;
        if self.interactions.has_nonpotential() {
            self.interactions.add_nonpotential(t, x, v, &self.particles, f);
            if !all_finite(f) {
                check_finite("velocities", v)?;
                self.finite_or_singular(t, x, f, e)?;
            }
        }
        Ok(e)
    }

    fn finite_or_singular(&self, t: f64, x: &[f64], f: &[f64], v: f64) -> Result<()> {
        if v.is_finite() && all_finite(f) {
            return Ok(());
        }
        check_finite("positions", x)?;
        Err(self
            .interactions
            .find_singular(t, x, &self.particles)
            .unwrap_or(Error::Core(noether_core::Error::NonFiniteResult {
                what: "forces",
                t,
                component: None,
            })))
    }

    /// Writes the accelerations a_i = F_i / m_i into `a`.
    pub fn accelerations(&self, t: f64, x: &[f64], v: &[f64], a: &mut [f64]) -> Result<()> {
        self.forces(t, x, v, a)?;
        self.divide_by_mass(a);
        Ok(())
    }

    /// Accelerations from the conservative forces only, a = −M⁻¹∇V (for symplectic methods).
    pub fn potential_accelerations(&self, t: f64, x: &[f64], a: &mut [f64]) -> Result<f64> {
        let e = self.potential_forces(t, x, a)?;
        self.divide_by_mass(a);
        Ok(e)
    }

    fn divide_by_mass(&self, a: &mut [f64]) {
        for (ai, w) in a.chunks_exact_mut(3).zip(&self.inv_mass) {
            ai.iter_mut().for_each(|c| *c *= w);
        }
    }

    /// Kinetic energy T = Σ ½ m_i |v_i|².
    pub fn kinetic_energy(&self, v: &[f64]) -> Result<f64> {
        self.check_vector("velocities", v)?;
        let t = v
            .chunks_exact(3)
            .zip(&self.particles)
            .map(|(w, p)| 0.5 * p.mass * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]))
            .sum();
        Ok(finite_result("kinetic energy", f64::NAN, t)?)
    }

    /// Potential energy V(t, x); coincident particles under a singular law are
    /// [`Error::Coincident`], not an infinite energy.
    pub fn potential_energy(&self, t: f64, x: &[f64]) -> Result<f64> {
        self.check(x, None)?;
        let e = self.interactions.energy(t, x, &self.particles);
        if !e.is_finite() {
            return Err(self
                .interactions
                .find_singular(t, x, &self.particles)
                .unwrap_or(Error::Core(noether_core::Error::NonFiniteResult {
                    what: "potential energy",
                    t,
                    component: None,
                })));
        }
        Ok(e)
    }

    /// Total mechanical energy T + V of a state.
    pub fn total_energy(&self, s: &State) -> Result<f64> {
        self.mechanical_energy(s.t, s.q.as_slice(), s.v.as_slice())
    }

    /// T + V at (t, x, v).
    fn mechanical_energy(&self, t: f64, x: &[f64], v: &[f64]) -> Result<f64> {
        let e = self.kinetic_energy(v)? + self.potential_energy(t, x)?;
        Ok(finite_result("total energy", t, e)?)
    }

    /// Total momentum P = Σ m_i v_i.
    pub fn momentum(&self, v: &[f64]) -> Result<Vec3> {
        self.check_vector("velocities", v)?;
        let mut p = [0.0; 3];
        for (w, q) in v.chunks_exact(3).zip(&self.particles) {
            (0..3).for_each(|k| p[k] += q.mass * w[k]);
        }
        check_result("momentum", f64::NAN, &p)?;
        Ok(p)
    }

    /// Total angular momentum about the origin, L = Σ m_i r_i × v_i.
    pub fn angular_momentum(&self, x: &[f64], v: &[f64]) -> Result<Vec3> {
        self.check_vector("positions", x)?;
        self.check_vector("velocities", v)?;
        let mut l = [0.0; 3];
        for ((r, w), q) in x.chunks_exact(3).zip(v.chunks_exact(3)).zip(&self.particles) {
            l[0] += q.mass * (r[1] * w[2] - r[2] * w[1]);
            l[1] += q.mass * (r[2] * w[0] - r[0] * w[2]);
            l[2] += q.mass * (r[0] * w[1] - r[1] * w[0]);
        }
        check_result("angular momentum", f64::NAN, &l)?;
        Ok(l)
    }

    /// Total mass M = Σ m_i.
    pub fn total_mass(&self) -> f64 {
        self.particles.iter().map(|p| p.mass).sum()
    }

    /// Centre of mass R = Σ m_i r_i / M (also the centre-of-mass velocity when given velocities);
    /// [`Error::Empty`] for a system without particles.
    pub fn centre_of_mass(&self, x: &[f64]) -> Result<Vec3> {
        if self.is_empty() {
            return Err(Error::Empty {
                what: "centre of mass",
            });
        }
        let p = self.momentum(x)?;
        let m = self.total_mass();
        let c = [p[0] / m, p[1] / m, p[2] / m];
        check_result("centre of mass", f64::NAN, &c)?;
        Ok(c)
    }

    /// Checks a per-particle vector (positions or velocities): length 3N, finite.
    fn check_vector(&self, what: &'static str, x: &[f64]) -> Result<()> {
        check_len(what, x, 3 * self.len())?;
        Ok(check_finite(what, x)?)
    }

    /// The Hessian ∂²V/∂x∂x (3N × 3N), assembled term by term from 3×3 blocks (sparse).
    pub fn hessian(&self, t: f64, x: &[f64]) -> Result<SparseHessian> {
        self.check(x, None)?;
        let mut trip = Vec::new();
        self.interactions.add_hessian(t, x, &self.particles, &mut trip);
        Ok(SparseHessian::from_triplets(x.len(), trip))
    }
}

/// `true` when every entry is finite, branch-free in 8 lanes (x·0 is 0 for finite x, NaN otherwise).
fn all_finite(f: &[f64]) -> bool {
    let mut acc = [0.0_f64; 8];
    let chunks = f.chunks_exact(8);
    let rest = chunks.remainder();
    for c in chunks {
        for k in 0..8 {
            acc[k] += c[k] * 0.0;
        }
    }
    acc.iter().chain(rest).all(|a| a.is_finite())
}

/// The system as a Lagrangian L = Σ ½ m |ẋ|² − V(t, x) with generalized forces Q = non-potential
/// forces: every integrator of core (and discrete) applies. This path differentiates the whole L with
/// chunked duals (cost O(N × terms)); [`Dynamics`] below is the fast term-by-term path.
impl<I: Interaction> Lagrangian for System<I> {
    fn dof(&self) -> usize {
        3 * self.particles.len()
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        // A direct call with the wrong sizes (the equations of motion check them first) is NaN, not
        // an index out of bounds inside an interaction.
        let n = 3 * self.particles.len();
        if q.len() != n || v.len() != n {
            return D::from(f64::NAN);
        }
        let mut kin = D::zero();
        for (w, p) in v.chunks_exact(3).zip(&self.particles) {
            kin += (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) * (0.5 * p.mass);
        }
        kin - self.interactions.potential(t.re(), q, &self.particles)
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
    fn has_generalized_force(&self) -> bool {
        self.interactions.has_nonpotential()
    }
    fn generalized_force<D: Scalar>(&self, t: D, q: &[D], v: &[D], out: &mut [D]) {
        out.iter_mut().for_each(|a| *a = D::zero());
        self.interactions
            .add_nonpotential(t.re(), q, v, &self.particles, out);
    }
}

/// q̇ = v, v̇ = F/m with forces assembled term by term (cost linear in the number of terms).
impl<I: Interaction> Dynamics for System<I> {
    type Partner = noether_core::Velocities;
    fn dof(&self) -> usize {
        3 * self.particles.len()
    }
    fn rates(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        dq: &mut [f64],
        dv: &mut [f64],
    ) -> noether_core::Result<()> {
        check_len("dq", dq, q.len())?;
        self.accelerations(t, q, v, dv)?;
        dq.copy_from_slice(v);
        Ok(())
    }
    fn position_rates(&self, _t: f64, _q: &[f64], v: &[f64], dq: &mut [f64]) -> noether_core::Result<()> {
        check_len("velocities", v, 3 * self.len())?;
        check_len("dq", dq, 3 * self.len())?;
        dq.copy_from_slice(v);
        Ok(())
    }
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        Ok(self.mechanical_energy(t, q, v)?)
    }
}
