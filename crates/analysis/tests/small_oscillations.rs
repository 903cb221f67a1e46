//! Equilibria and normal modes against closed forms, and the errors for bad input.
//!
//! Tolerances: M and K are exact (dual numbers), so frequencies carry only the rounding of a symmetric
//! eigen-solver, a few ulps times the condition of M; 1e-10 relative leaves room for that and nothing
//! else. Equilibria found by minimisation are polished by Newton to ‖∇V‖ ≈ 1e-12 of the gradient scale.

use approx::assert_relative_eq;
use nalgebra::DMatrix;
use noether_analysis::{
    linear_stability, normal_modes, EffectivePotential, Equilibrium, EquilibriumFinder, Error, Kind,
};
use noether_core::{Lagrangian, Scalar};
use std::f64::consts::PI;

/// Two pendula (mass m, length l) whose bobs are joined by a spring k (horizontal stretch l(sinθ₁ − sinθ₂)).
struct CoupledPendula {
    m: f64,
    l: f64,
    g: f64,
    k: f64,
}

impl Lagrangian for CoupledPendula {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (m, l) = (self.m, self.l);
        let t = (v[0] * v[0] + v[1] * v[1]) * (0.5 * m * l * l);
        let gravity = (q[0].cos() + q[1].cos()) * (m * self.g * l);
        let stretch = (q[0].sin() - q[1].sin()) * l;
        t + gravity - stretch * stretch * (0.5 * self.k)
    }
}

/// N masses m at positions x_i on a line between walls at 0 and (N+1)a, springs k of natural length a.
struct Chain {
    n: usize,
    m: f64,
    k: f64,
    a: f64,
}

impl Lagrangian for Chain {
    fn dof(&self) -> usize {
        self.n
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let mut t = D::zero();
        for vi in v {
            t += *vi * *vi;
        }
        let wall = D::from((self.n + 1) as f64 * self.a);
        let mut pot = D::zero();
        let mut prev = D::zero();
        for x in q.iter().copied().chain(std::iter::once(wall)) {
            let s = x - prev - self.a;
            pot += s * s;
            prev = x;
        }
        t * (0.5 * self.m) - pot * (0.5 * self.k)
    }
}

/// Bead on a hoop of radius a rotating at ω about its vertical diameter.
struct Hoop {
    a: f64,
    g: f64,
    omega: f64,
}

impl Lagrangian for Hoop {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let s = q[0].sin();
        (v[0] * v[0] + s * s * self.omega.powi(2)) * (0.5 * self.a * self.a) + q[0].cos() * (self.g * self.a)
    }
}

/// Three equal masses in the plane joined pairwise by equal springs (natural length a).
struct Triangle {
    m: f64,
    k: f64,
    a: f64,
}

impl Lagrangian for Triangle {
    fn dof(&self) -> usize {
        6
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let mut t = D::zero();
        for vi in v {
            t += *vi * *vi;
        }
        let mut pot = D::zero();
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            let dx = q[2 * i] - q[2 * j];
            let dy = q[2 * i + 1] - q[2 * j + 1];
            let s = (dx * dx + dy * dy).sqrt() - self.a;
            pot += s * s;
        }
        t * (0.5 * self.m) - pot * (0.5 * self.k)
    }
}

fn minimum<L: Lagrangian>(l: &L, q0: &[f64]) -> Equilibrium {
    EquilibriumFinder::default()
        .minimize(&EffectivePotential::new(l), q0)
        .unwrap()
}

/// ω² = g/l (in phase, spring idle) and g/l + 2k/m (out of phase).
#[test]
fn closed_form_coupled_pendula() {
    let p = CoupledPendula {
        m: 0.7,
        l: 1.3,
        g: 9.81,
        k: 2.5,
    };
    let eq = minimum(&p, &[0.4, -0.2]);
    assert_eq!(eq.kind, Kind::Minimum);
    assert!(eq.q.amax() < 1e-12);
    let modes = normal_modes(&p, eq.q.as_slice()).unwrap();
    assert_relative_eq!(modes.omega2[0], p.g / p.l, max_relative = 1e-12);
    assert_relative_eq!(modes.omega2[1], p.g / p.l + 2.0 * p.k / p.m, max_relative = 1e-12);
    // In-phase and out-of-phase shapes, M-normalised: X = (1, ±1)/sqrt(2 m l²).
    let x = 1.0 / (2.0 * p.m * p.l * p.l).sqrt();
    let s0 = modes.shapes.column(0);
    let s1 = modes.shapes.column(1);
    assert_relative_eq!(s0[0].abs(), x, max_relative = 1e-12);
    assert_relative_eq!(s0[1], s0[0], max_relative = 1e-12);
    assert_relative_eq!(s1[1], -s1[0], max_relative = 1e-12);
}

/// ω_j = 2 sqrt(k/m) sin(jπ / (2(N+1))), j = 1..N; N = 20 exercises the chunked Hessian (W = 8).
#[test]
fn closed_form_chain_fixed_ends() {
    for n in [5, 20] {
        let c = Chain {
            n,
            m: 0.5,
            k: 3.0,
            a: 0.25,
        };
        // Start away from equilibrium: x_i = i·a + a/3·sin(i).
        let q0: Vec<f64> = (1..=n)
            .map(|i| i as f64 * c.a + c.a / 3.0 * (i as f64).sin())
            .collect();
        let eq = minimum(&c, &q0);
        for (i, x) in eq.q.iter().enumerate() {
            assert_relative_eq!(*x, (i + 1) as f64 * c.a, max_relative = 1e-12);
        }
        let modes = normal_modes(&c, eq.q.as_slice()).unwrap();
        let w = modes.frequencies();
        for j in 1..=n {
            let exact = 2.0 * (c.k / c.m).sqrt() * (j as f64 * PI / (2.0 * (n + 1) as f64)).sin();
            assert_relative_eq!(w[j - 1], exact, max_relative = 1e-10);
        }
        // Shapes are M-orthonormal and K X = M X Ω².
        let x = &modes.shapes;
        let id = x.transpose() * &modes.mass * x;
        assert!((id - DMatrix::identity(n, n)).amax() < 1e-10);
        let lhs = &modes.stiffness * x;
        let rhs = &modes.mass * x * DMatrix::from_diagonal(&modes.omega2);
        assert!((lhs - rhs).amax() < 1e-10 * modes.stiffness.amax());
    }
}

/// Bead on the rotating hoop: for aω² > g the bottom θ = 0 is a maximum of U with ω² = g/a − ω² < 0, and
/// the bead rests at cos θ₀ = g/(aω²) with ω² = ω_hoop² sin²θ₀; for aω² < g the bottom is stable with
/// ω² = g/a − ω².
#[test]
fn closed_form_rotating_hoop() {
    let fast = Hoop {
        a: 0.5,
        g: 9.81,
        omega: 6.0,
    };
    let finder = EquilibriumFinder::default();
    let pot = EffectivePotential::new(&fast);
    let bottom = finder.stationary_point(&pot, &[0.05]).unwrap();
    assert!(bottom.q[0].abs() < 1e-12);
    assert_eq!(bottom.kind, Kind::Maximum);
    let modes = normal_modes(&fast, &[0.0]).unwrap();
    assert_relative_eq!(modes.omega2[0], fast.g / fast.a - 36.0, max_relative = 1e-12);
    assert_eq!(modes.unstable_modes, 1);
    assert!(!modes.is_stable());
    let side = finder.minimize(&pot, &[1.2]).unwrap();
    assert_eq!(side.kind, Kind::Minimum);
    let cos0 = fast.g / (fast.a * 36.0);
    assert_relative_eq!(side.q[0].cos(), cos0, max_relative = 1e-12);
    let modes = normal_modes(&fast, side.q.as_slice()).unwrap();
    assert_relative_eq!(modes.omega2[0], 36.0 * (1.0 - cos0 * cos0), max_relative = 1e-11);

    let slow = Hoop {
        a: 0.5,
        g: 9.81,
        omega: 3.0,
    };
    let eq = minimum(&slow, &[0.8]);
    assert!(eq.q[0].abs() < 1e-12);
    let modes = normal_modes(&slow, eq.q.as_slice()).unwrap();
    assert_relative_eq!(modes.omega2[0], slow.g / slow.a - 9.0, max_relative = 1e-12);
}

/// Equilateral triangle, equal masses m and springs k: 3 zero modes (2 translations, 1 rotation),
/// the doubly degenerate ω² = 3k/(2m) and the breathing mode ω² = 3k/m (trace check: Σω² = 6k/m).
#[test]
fn closed_form_triangle_zero_modes() {
    let tri = Triangle {
        m: 2.0,
        k: 5.0,
        a: 1.5,
    };
    // A distorted, shifted and rotated start.
    let q0 = [0.1, -0.2, 1.7, 0.1, 0.6, 1.2];
    let eq = minimum(&tri, &q0);
    assert_eq!(eq.kind, Kind::Minimum);
    assert_eq!(eq.zero_modes, 3);
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let d = ((eq.q[2 * i] - eq.q[2 * j]).powi(2) + (eq.q[2 * i + 1] - eq.q[2 * j + 1]).powi(2)).sqrt();
        assert_relative_eq!(d, tri.a, max_relative = 1e-12);
    }
    let modes = normal_modes(&tri, eq.q.as_slice()).unwrap();
    assert_eq!(modes.zero_modes, 3);
    assert!(modes.is_stable());
    for k in 0..3 {
        assert!(modes.omega2[k].abs() < 1e-12 * modes.omega2[5]);
    }
    let (m, k) = (tri.m, tri.k);
    assert_relative_eq!(modes.omega2[3], 1.5 * k / m, max_relative = 1e-12);
    assert_relative_eq!(modes.omega2[4], 1.5 * k / m, max_relative = 1e-12);
    assert_relative_eq!(modes.omega2[5], 3.0 * k / m, max_relative = 1e-12);
}

/// A particle in a rotating frame with the isotropic harmonic potential ½ k r²: in the inertial frame it
/// oscillates at sqrt(k/m), so in the frame rotating at Ω the eigenvalues are λ = ±i(sqrt(k/m) ± Ω).
/// The Coriolis term is gyroscopic: normal_modes refuses, linear_stability handles it.
struct RotatingOscillator {
    k: f64,
    omega: f64,
}

impl Lagrangian for RotatingOscillator {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (x, y, vx, vy) = (q[0], q[1], v[0], v[1]);
        let (ux, uy) = (vx - y * self.omega, vy + x * self.omega);
        (ux * ux + uy * uy) * 0.5 - (x * x + y * y) * (0.5 * self.k)
    }
}

#[test]
fn closed_form_gyroscopic_rotating_oscillator() {
    let r = RotatingOscillator { k: 4.0, omega: 0.7 };
    assert!(matches!(
        normal_modes(&r, &[0.0, 0.0]),
        Err(Error::Gyroscopic { .. })
    ));
    let st = linear_stability(&r, &[0.0, 0.0]).unwrap();
    assert!(st.stable);
    assert!(st.growth_rate.abs() < 1e-12);
    let mut im: Vec<f64> = st.eigenvalues.iter().map(|l| l.im.abs()).collect();
    im.sort_by(f64::total_cmp);
    let w0 = r.k.sqrt();
    assert_relative_eq!(im[0], w0 - r.omega, max_relative = 1e-12);
    assert_relative_eq!(im[2], w0 + r.omega, max_relative = 1e-12);
}

/// A Lagrangian whose mass matrix is singular (the second coordinate has no kinetic energy).
struct Degenerate;
impl Lagrangian for Degenerate {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * 0.5 - (q[0] * q[0] + q[1] * q[1]) * 0.5
    }
}

#[test]
fn bad_input_singular_mass_matrix() {
    let e = normal_modes(&Degenerate, &[0.0, 0.0]).unwrap_err();
    assert!(
        matches!(e, Error::Core(noether_core::Error::SingularMassMatrix { .. })),
        "{e}"
    );
    assert!(linear_stability(&Degenerate, &[0.0, 0.0]).is_err());
}

#[test]
fn bad_input_not_an_equilibrium() {
    let p = CoupledPendula {
        m: 1.0,
        l: 1.0,
        g: 9.81,
        k: 1.0,
    };
    let e = normal_modes(&p, &[0.1, 0.0]).unwrap_err();
    match &e {
        // |∂U/∂θ₁| = m g l sin 0.1 + k l² sin 0.1 cos 0.1 (the spring pulls too).
        Error::NotEquilibrium { gradient_norm, .. } => {
            let expected = 9.81 * 0.1f64.sin() + 0.1f64.sin() * 0.1f64.cos();
            assert_relative_eq!(*gradient_norm, expected, max_relative = 1e-12);
        }
        other => panic!("expected NotEquilibrium, got {other}"),
    }
    assert!(e.to_string().contains("gradient"), "{e}");
}

#[test]
fn bad_input_wrong_length_nan_and_bad_tolerance() {
    let c = Chain {
        n: 3,
        m: 1.0,
        k: 1.0,
        a: 1.0,
    };
    assert!(matches!(
        normal_modes(&c, &[1.0, 2.0]),
        Err(Error::Core(noether_core::Error::Dimension { .. }))
    ));
    assert!(matches!(
        normal_modes(&c, &[1.0, f64::NAN, 3.0]),
        Err(Error::Core(noether_core::Error::NonFinite { .. }))
    ));
    let pot = EffectivePotential::new(&c);
    assert!(matches!(
        EquilibriumFinder::default().minimize(&pot, &[f64::INFINITY, 2.0, 3.0]),
        Err(Error::Core(noether_core::Error::NonFinite { .. }))
    ));
    // A bad setting is refused when it is set (the fields are private: no other way in).
    assert!(matches!(
        EquilibriumFinder::default().gradient_tolerance(-1.0),
        Err(Error::Core(noether_core::Error::InvalidParameter { .. }))
    ));
}

/// V = −q² has no minimum: the minimiser must report failure, not return a point.
struct Unbounded;
impl noether_analysis::Potential for Unbounded {
    fn dof(&self) -> usize {
        1
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        -(q[0] * q[0]) + q[0]
    }
}

#[test]
fn bad_input_unbounded_potential_does_not_converge() {
    let r = EquilibriumFinder::default()
        .max_iterations(50)
        .unwrap()
        .minimize(&Unbounded, &[1.0]);
    assert!(matches!(r, Err(Error::NotConverged { .. })), "{r:?}");
    // Newton still finds the stationary point (a maximum) at q = ½.
    let top = EquilibriumFinder::default()
        .stationary_point(&Unbounded, &[3.0])
        .unwrap();
    assert_relative_eq!(top.q[0], 0.5, max_relative = 1e-14);
    assert_eq!(top.kind, Kind::Maximum);
    // Issue 15, case 10: `minimize` started on that maximum returned it as Ok(kind = Maximum).
    let r = EquilibriumFinder::default().minimize(&Unbounded, &[0.5]);
    assert!(
        matches!(&r, Err(Error::NotMinimum { kind: Kind::Maximum, point }) if point == &[0.5]),
        "{r:?}"
    );
}
