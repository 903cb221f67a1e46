//! The constrained variational integrator: constraint residuals, discrete Noether momenta, energy
//! behaviour, order, multipliers, bad input.

use crate::models::*;
use noether_constraints::prelude::*;
use noether_core::Error as CoreError;
use noether_core::Newton;
use noether_discrete::momentum::{noether_momentum, PlanarRotation};
use noether_discrete::{Midpoint, Trapezoidal};

/// Spherical pendulum (one mass, 3D, rod from the origin) started off-plane with angular momentum.
fn spherical_start(l: f64) -> (Vec<f64>, Vec<f64>) {
    let (th, om) = (1.0_f64, 2.5_f64);
    (
        vec![l * th.sin(), 0.0, -l * th.cos()],
        vec![0.0, l * th.sin() * om, 0.0],
    )
}

/// Over 10⁴ steps: ‖φ‖ < 1e-12 after every step (Newton to rounding on (q, Λ)); L_z = x p_y − y p_x is
/// the discrete Noether momentum of rotations about z, which preserve L_d and the rod, so it is
/// conserved up to rounding: each step's residual is at the rounding floor of (q₁ − q₀)/h, a few ε,
/// and these add up like a random walk, ~ε·sqrt(10⁴)·(a few) ≈ 1e-13 relative; the test allows 1e-12.
/// The energy error of a symplectic second-order method stays bounded, O(h²), with no drift.
/// Runs `steps` steps of h and returns the states, their energies, and the largest residuals seen.
fn run_rattle<Ld>(
    mut r: Rattle<Ld, Rod>,
    q: &[f64],
    v: &[f64],
    h: f64,
    steps: usize,
) -> (Vec<State<Momenta>>, f64, Vec<f64>, (f64, f64))
where
    Ld: noether_discrete::DiscreteLagrangian + noether_discrete::FromLagrangian,
{
    let mut s = r.state_from_velocities(0.0, q, v).unwrap();
    let e0 = r.energy(&s).unwrap();
    let mut states = Vec::with_capacity(steps);
    for _ in 0..steps {
        r.step(&mut s, h).unwrap();
        // ‖φ‖∞ < 1e-12 after every single step.
        assert!(r.last_step().position_residual < 1e-12, "{:?}", r.last_step());
        states.push(s.clone());
    }
    let energies = states.iter().map(|s| r.energy(s).unwrap()).collect();
    (states, e0, energies, r.max_residual())
}

#[test]
fn conserves_l_z_and_constraint_spherical_pendulum() {
    let (m, l, g) = (1.0, 1.0, 9.81);
    let (q, v) = spherical_start(l);
    let rod = || Rod { d: 3, l, copies: 1 };
    let model = || Masses { n: 1, d: 3, m, g };
    let h = 1e-2;
    for midpoint in [true, false] {
        let (states, e0, energies, worst) = if midpoint {
            run_rattle(
                Rattle::new(Midpoint::new(model()), rod()).unwrap(),
                &q,
                &v,
                h,
                10_000,
            )
        } else {
            run_rattle(
                Rattle::new(Trapezoidal::new(model()), rod()).unwrap(),
                &q,
                &v,
                h,
                10_000,
            )
        };
        assert!(worst.0 < 1e-12 && worst.1 < 1e-12, "residuals {worst:?}");
        let rot = PlanarRotation::new(vec![(0, 1)]);
        let lz0 = m * q[0] * v[1];
        let dl = states
            .iter()
            .map(|s| (noether_momentum(&rot, s.q.as_slice(), s.v.as_slice()) - lz0).abs() / lz0)
            .fold(0.0, f64::max);
        assert!(dl < 1e-12, "L_z drift {dl:e} (midpoint: {midpoint})");
        // Energy: bounded O(h²) oscillation; the first and the last thousand steps have the same range.
        let de: Vec<f64> = energies.iter().map(|e| (e - e0) / e0.abs()).collect();
        let max_all = de.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let max_last = de[9000..].iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let max_first = de[..1000].iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        eprintln!("midpoint {midpoint}: L_z {dl:e}, energy {max_first:e} {max_last:e}, residuals {worst:?}");
        assert!(max_all < 2e-3, "energy error {max_all:e}");
        assert!(
            max_last < 1.5 * max_first,
            "energy drifts: {max_first:e} → {max_last:e}"
        );
    }
}

/// Second order: the planar Cartesian pendulum against the angle formulation integrated by RK4 with
/// a tiny step (error ~1e-14), without and with a drag −c ṙ on the bob (c = 0.8; the angle model's
/// force −c l² θ̇): halving h divides the RATTLE error by 4 (ratio within [3.5, 4.5]).
#[test]
fn order_two_cartesian_pendulum() {
    let (m, l, g) = (1.0, 1.0, 9.81);
    let (th0, om0) = (1.0_f64, 0.0_f64);
    let t_end = 1.0;
    for c in [0.0, 0.8] {
        let reference = {
            let angle = Dragged {
                model: AnglePendulum { m, l, g },
                c: c * l * l,
            };
            let el = EulerLagrange::new(angle);
            let mut tr = Driver::with_step(Rk4::new(el), State::new(0.0, [th0], [om0]), 1e-4).unwrap();
            tr.run_until(t_end).unwrap().last().q[0]
        };
        let err = |h: f64| {
            let masses = Dragged {
                model: Masses { n: 1, d: 2, m, g },
                c,
            };
            let mut r = Rattle::new(Midpoint::new(masses), Rod { d: 2, l, copies: 1 }).unwrap();
            let s = pendulum_state(l, th0, om0);
            let mut s = r
                .state_from_velocities(0.0, s.q.as_slice(), s.v.as_slice())
                .unwrap();
            let steps = (t_end / h).round() as usize;
            for _ in 0..steps {
                r.step(&mut s, h).unwrap();
                assert!(r.last_step().position_residual < 1e-12, "{:?}", r.last_step());
            }
            (s.q[0].atan2(-s.q[1]) - reference).abs()
        };
        let (e1, e2) = (err(0.02), err(0.01));
        let ratio = e1 / e2;
        println!("RATTLE pendulum, drag {c}: errors {e1:e} {e2:e}, ratio {ratio}");
        assert!(
            (3.5..4.5).contains(&ratio),
            "drag {c}: errors {e1:e} {e2:e} ratio {ratio}"
        );
    }
}

/// Tension from the discrete multipliers against T = m g cos θ + m l θ̇² evaluated on the discrete
/// state: the one-sided estimates 2Λ/h, 2Μ/h are first order (halving h halves the error), the
/// symmetric one (Μ_{k−1} + Λ_k)/h is second order (halving h quarters it). Ratios within ±0.3 of 2
/// and 4 (measured over 0.5 s, the error constants are smooth in h).
#[test]
fn order_rattle_tension_estimates() {
    let (m, l, g) = (2.0, 0.5, 9.81);
    let tension = |s: &State<Momenta>, v: &[f64]| {
        let theta = s.q[0].atan2(-s.q[1]);
        let rate = (s.q[0] * v[1] - s.q[1] * v[0]) / (l * l);
        m * g * theta.cos() + m * l * rate * rate
    };
    let errors = |h: f64| {
        let mut r = Rattle::new(
            Midpoint::new(Masses { n: 1, d: 2, m, g }),
            Rod { d: 2, l, copies: 1 },
        )
        .unwrap();
        let s0 = pendulum_state(l, 0.8, 1.0);
        let mut s = r
            .state_from_velocities(0.0, s0.q.as_slice(), s0.v.as_slice())
            .unwrap();
        let (mut one_sided, mut symmetric) = (0.0_f64, 0.0_f64);
        for k in 0..(0.5 / h).round() as usize {
            let before = s.clone();
            let v_before = r.velocities(&before).unwrap();
            r.step(&mut s, h).unwrap();
            let v = r.velocities(&s).unwrap();
            let t_end = tension(&s, v.as_slice());
            one_sided = one_sided.max((-r.multipliers().1[0] - t_end).abs() / t_end);
            match r.multipliers_symmetric() {
                Some((t, lam)) => {
                    assert_eq!(t, before.t);
                    let t_start = tension(&before, v_before.as_slice());
                    symmetric = symmetric.max((-lam[0] - t_start).abs() / t_start);
                }
                None => assert_eq!(k, 0),
            }
        }
        (one_sided, symmetric)
    };
    let ((a1, b1), (a2, b2)) = (errors(2e-3), errors(1e-3));
    assert!((a1 / a2 - 2.0).abs() < 0.3, "one-sided {a1:e} {a2:e}");
    assert!((b1 / b2 - 4.0).abs() < 0.3, "symmetric {b1:e} {b2:e}");
}

#[test]
fn bad_input_rattle_violating_state_redundant_and_newton_failure() {
    let (m, l, g) = (1.0, 1.0, 9.81);
    let mut r = Rattle::new(
        Midpoint::new(Masses { n: 1, d: 2, m, g }),
        Rod { d: 2, l, copies: 1 },
    )
    .unwrap();
    // Off the circle: error names the residual φ = (1.21 − 1)/2.
    let mut s = State::with_momenta(0.0, [0.0, -1.1], [0.0, 0.0]);
    let before = s.clone();
    // A step is core's interface: the error travels as core's `Model` and `Error::from` gives it back.
    match Error::from(r.step(&mut s, 0.01).unwrap_err()) {
        Error::ConstraintViolated { what, residual, .. } => {
            assert_eq!(what, "position");
            assert!((residual - 0.105).abs() < 1e-12);
        }
        e => panic!("unexpected {e}"),
    }
    assert_eq!(s, before);
    // Radial momentum: a velocity violation.
    let mut s = State::with_momenta(0.0, [0.0, -1.0], [0.0, 0.5]);
    assert!(matches!(
        r.step(&mut s, 0.01).map_err(Error::from),
        Err(Error::ConstraintViolated { what: "velocity", .. })
    ));
    // Bad step.
    let mut s = r.state_from_velocities(0.0, &[0.0, -1.0], &[1.0, 0.0]).unwrap();
    assert!(matches!(r.step(&mut s, -0.1), Err(CoreError::InvalidStep { .. })));
    // Newton capped at one iteration cannot solve the nonlinear constraint: the core error, state kept.
    let mut capped = Rattle::new(
        Midpoint::new(Masses { n: 1, d: 2, m, g }),
        Rod { d: 2, l, copies: 1 },
    )
    .unwrap()
    .newton(Newton::default().max_iterations(1).unwrap());
    let s0 = s.clone();
    assert!(matches!(
        capped.step(&mut s, 0.1),
        Err(CoreError::NewtonDiverged { iterations: 1, .. })
    ));
    assert_eq!(s, s0);
    // The same rod twice: rank 1 < 2 constraints.
    let mut red = Rattle::new(
        Midpoint::new(Masses { n: 1, d: 2, m, g }),
        Rod { d: 2, l, copies: 2 },
    )
    .unwrap();
    match Error::from(red.step(&mut s, 0.01).unwrap_err()) {
        Error::RankDeficientConstraints { rank, count, .. } => assert_eq!((rank, count), (1, 2)),
        e => panic!("unexpected {e}"),
    }
    // Dimensions.
    assert!(matches!(
        Rattle::new(
            Midpoint::new(Masses { n: 1, d: 3, m, g }),
            Rod { d: 2, l, copies: 1 }
        ),
        Err(Error::Core(CoreError::Dimension { .. }))
    ));
}

/// The 10-link Cartesian chain of the benchmark (20 coordinates, 10 rods): over 300 steps every rod
/// length holds to 1e-12, and the motion agrees with the unconstrained variational integrator in angle
/// coordinates to O(h²) (both second order, different discretizations): 1e-3 at h = 1e-3 over 0.3 s.
#[test]
fn conserves_rods_ten_link_chain_and_matches_angles() {
    use crate::chain::*;
    use noether_discrete::VariationalIntegrator;
    let (n, m, l, g) = (10, 1.0, 0.5, 9.81);
    let (angles, cart) = chain_states(n, l);
    let mut r = Rattle::new(Midpoint::new(CartesianChain { n, m, g }), Rods { n, l }).unwrap();
    let mut s = r
        .state_from_velocities(0.0, cart.q.as_slice(), cart.v.as_slice())
        .unwrap();
    let mut vi = VariationalIntegrator::new(Midpoint::new(AngleChain { n, m, l, g }));
    let mut a = vi
        .state_from_velocities(0.0, angles.q.as_slice(), angles.v.as_slice())
        .unwrap();
    for _ in 0..300 {
        r.step(&mut s, 1e-3).unwrap();
        vi.step(&mut a, 1e-3).unwrap();
    }
    assert!(r.max_residual().0 < 1e-12, "{:?}", r.max_residual());
    let (mut x, mut y, mut worst) = (0.0, 0.0, 0.0_f64);
    for i in 0..n {
        x += l * a.q[i].sin();
        y -= l * a.q[i].cos();
        worst = worst.max((s.q[2 * i] - x).abs()).max((s.q[2 * i + 1] - y).abs());
    }
    assert!(worst < 1e-3, "Cartesian vs angles {worst:e}");
}

/// A time-dependent constraint: the bead on a hoop of radius a spinning at ω about the vertical,
/// φ₁ = (|r|² − a²)/(2a), φ₂ = y cos ωt − x sin ωt. RATTLE keeps both to rounding and converges at
/// second order to the one-coordinate motion a θ̈ = a ω² sin θ cos θ − g sin θ (RK4, h = 1e-4).
#[test]
fn order_two_rattle_time_dependent_hoop() {
    struct Hoop {
        a: f64,
        w: f64,
    }
    impl Holonomic for Hoop {
        fn dof(&self) -> usize {
            3
        }
        fn count(&self) -> usize {
            2
        }
        fn constraints<D: Scalar>(&self, t: D, q: &[D], out: &mut [D]) {
            out[0] = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - self.a * self.a) * (0.5 / self.a);
            let wt = t * self.w;
            out[1] = q[1] * wt.cos() - q[0] * wt.sin();
        }
    }
    struct HoopAngle {
        a: f64,
        w: f64,
        g: f64,
    }
    impl Lagrangian for HoopAngle {
        fn dof(&self) -> usize {
            1
        }
        fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
            let s = q[0].sin();
            (v[0] * v[0] + s * s * (self.w * self.w)) * (0.5 * self.a * self.a)
                + q[0].cos() * (self.g * self.a)
        }
    }
    let (a, w, g, th0) = (1.0_f64, 5.0, 9.81, 0.3_f64);
    let t_end = 1.0;
    let reference = {
        let el = EulerLagrange::new(HoopAngle { a, w, g });
        let mut tr = Driver::with_step(Rk4::new(el), State::new(0.0, [th0], [0.0]), 1e-4).unwrap();
        tr.run_until(t_end).unwrap().last().q[0]
    };
    let err = |h: f64| {
        let mut r = Rattle::new(
            Midpoint::new(Masses {
                n: 1,
                d: 3,
                m: 1.0,
                g,
            }),
            Hoop { a, w },
        )
        .unwrap();
        // On the hoop at θ₀, at rest relative to it: velocity ω × r.
        let q = [a * th0.sin(), 0.0, -a * th0.cos()];
        let v = [0.0, w * a * th0.sin(), 0.0];
        let mut s = r.state_from_velocities(0.0, &q, &v).unwrap();
        for _ in 0..(t_end / h).round() as usize {
            r.step(&mut s, h).unwrap();
        }
        assert!(
            r.max_residual().0 < 1e-12 && r.max_residual().1 < 1e-12,
            "{:?}",
            r.max_residual()
        );
        let (sw, cw) = (w * s.t).sin_cos();
        ((s.q[0] * cw + s.q[1] * sw).atan2(-s.q[2]) - reference).abs()
    };
    let (e1, e2) = (err(2e-3), err(1e-3));
    assert!((e1 / e2 - 4.0).abs() < 0.5, "errors {e1:e} {e2:e}");
}
