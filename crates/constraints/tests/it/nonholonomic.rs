//! Velocity constraints (Lagrange-d'Alembert): the knife edge on an inclined plane.

use noether_constraints::prelude::*;

/// A knife edge (skate) on a plane tilted so that gravity pulls along +x with g' = g sin α:
/// q = (x, y, φ), L = ½ m (ẋ² + ẏ²) + ½ I φ̇² + m g' x, no sideways slip −ẋ sin φ + ẏ cos φ = 0.
struct Skate {
    m: f64,
    i: f64,
    g: f64,
}

impl Lagrangian for Skate {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m) + v[2] * v[2] * (0.5 * self.i) + q[0] * (self.m * self.g)
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

struct NoSideSlip;

impl Nonholonomic for NoSideSlip {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        1
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], v: &[D], out: &mut [D]) {
        out[0] = v[1] * q[2].cos() - v[0] * q[2].sin();
    }
}

/// Released at rest at the origin, blade along x, spinning at φ̇ = ω: φ = ωt and the speed along the
/// blade u obeys u̇ = g' cos φ, so (Bloch, Nonholonomic Mechanics and Control, §1.6)
/// x = g'/(2ω²) sin²ωt,  y = g'/(2ω) (t − sin 2ωt/(2ω)) — the skate drifts sideways across the slope
/// instead of sliding down it. RK4 with h = 1e-3 over 5 s reproduces this to 1e-9; the energy
/// E = ½ m u² + ½ I ω² − m g' x is conserved (the constraint force does no work).
#[test]
fn closed_form_knife_edge_on_incline() {
    let (m, i, g, w) = (1.0, 0.2, 3.0, 2.0);
    let sys = Constrained::nonholonomic(Skate { m, i, g }, NoSideSlip).unwrap();
    let start = State::new(0.0, [0.0, 0.0, 0.0], [0.0, 0.0, w]);
    sys.check_state(&start, 1e-14).unwrap();
    let e0 = sys.energy(0.0, start.q.as_slice(), start.v.as_slice()).unwrap();
    let run = Driver::with_step(Projected::new(Rk4::new(&sys), sys.constraints()), start, 1e-3).unwrap();
    let (mut dx, mut de) = (0.0_f64, 0.0_f64);
    for s in run.take(5000) {
        let s = s.unwrap();
        let t = s.t;
        let x = g / (2.0 * w * w) * (w * t).sin().powi(2);
        let y = g / (2.0 * w) * (t - (2.0 * w * t).sin() / (2.0 * w));
        dx = dx
            .max((s.q[0] - x).abs())
            .max((s.q[1] - y).abs())
            .max((s.q[2] - w * t).abs());
        de = de.max((sys.energy(t, s.q.as_slice(), s.v.as_slice()).unwrap() - e0).abs());
    }
    assert!(dx < 1e-9, "position error {dx:e}");
    assert!(de < 1e-10, "energy drift {de:e}");
}

/// The multiplier is the sideways force of the ice on the blade. Along e⊥ = (−sin φ, cos φ) the skate
/// accelerates by u ω (it turns at ω with speed u = (g'/ω) sin ωt) under λ and gravity's share
/// −m g' sin φ, so λ = m u ω + m g' sin ωt = 2 m u ω.
#[test]
fn closed_form_knife_edge_side_force() {
    let (m, i, g, w) = (1.5, 0.2, 3.0, 2.0);
    let sys = Constrained::nonholonomic(Skate { m, i, g }, NoSideSlip).unwrap();
    for t in [0.1, 0.7, 1.3] {
        let u = g / w * (w * t).sin();
        let phi = w * t;
        let q = [0.0, 0.0, phi];
        let v = [u * phi.cos(), u * phi.sin(), w];
        let f = sys.constraint_forces(t, &q, &v).unwrap();
        assert!(
            (f.lambda[0] - 2.0 * m * u * w).abs() < 1e-12,
            "λ = {} vs {}",
            f.lambda[0],
            2.0 * m * u * w
        );
        // The force is perpendicular to the blade: (−sin φ, cos φ) λ.
        assert!((f.generalized[0] + phi.sin() * f.lambda[0]).abs() < 1e-12);
        assert!(f.generalized[2].abs() < 1e-15);
    }
}
