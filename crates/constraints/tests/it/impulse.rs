//! Impulsive motion (Desloge ch. 57) against closed forms: p⁺ − p⁻ = Ĝ + Φ_qᵀλ̂ with the impact law
//! Φ_q q̇⁺ + φ_t = −e (Φ_q q̇⁻ + φ_t). Every system here has L quadratic in q̇, so the jump equations are
//! linear and the answers are exact up to the rounding of one small linear solve: the tolerances are a
//! few ulps of the quantities compared (measured errors in the comments).

use noether_constraints::impulse::{Impact, StruckPoints};
use noether_constraints::prelude::*;

/// A uniform rod, mass m and length l, free in the plane: centre (x, y), angle θ from the x axis.
/// L = ½ m (ẋ² + ẏ²) + ½ (m l²/12) θ̇² (no gravity: the instant does not see finite forces).
struct Rod {
    m: f64,
    l: f64,
}
impl Lagrangian for Rod {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m) + v[2] * v[2] * (self.m * self.l * self.l / 24.0)
    }
}

/// The point of the rod at distance s from its centre along it (s = l/2: the end).
struct OnRod {
    s: f64,
}
impl StruckPoints for OnRod {
    fn dof(&self) -> usize {
        3
    }
    fn dim(&self) -> usize {
        2
    }
    fn positions<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        out[0] = q[0] + q[2].cos() * self.s;
        out[1] = q[1] + q[2].sin() * self.s;
    }
}

/// The same point pinned at `at`: φ = r(q) − at (two constraints).
struct Pin {
    s: f64,
    at: [f64; 2],
}
impl Holonomic for Pin {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        2
    }
    fn constraints<D: Scalar>(&self, t: D, q: &[D], out: &mut [D]) {
        OnRod { s: self.s }.positions(t, q, out);
        out[0] -= self.at[0];
        out[1] -= self.at[1];
    }
}

/// The height of the point at s above the floor y = 0 (one constraint, for a rebound).
struct Floor {
    s: f64,
}
impl Holonomic for Floor {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        1
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        out[0] = q[1] + q[2].sin() * self.s;
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn closed_form_free_rod_struck_at_a_point() {
    // A blow J perpendicular to a rod at rest, at distance s from its centre: the centre moves at
    // J/m, the rod turns at J s / (m l²/12) (linear and angular momentum about the centre).
    let (m, l, j) = (2.0, 1.5, 0.3);
    let rod = EulerLagrange::new(Rod { m, l });
    for s in [0.75, 0.4, -0.2] {
        let point = OnRod { s };
        let r = Impact::new(&rod)
            .blow(&point, &[0.0, j])
            .unwrap()
            .velocities(0.0, &[0.0, 0.0, 0.0], &[0.0, 0.0, 0.0])
            .unwrap();
        assert!(close(r.v[1], j / m, 4e-16), "{:?}", r.v);
        assert!(close(r.v[2], j * s / (m * l * l / 12.0), 4e-16), "{:?}", r.v);
        assert_eq!(r.v[0], 0.0);
        // The energy given is ½ J²/m + ½ (J s)²/I.
        let de = 0.5 * j * j / m + 0.5 * (j * s).powi(2) / (m * l * l / 12.0);
        assert!(close(r.energy_change, de, 1e-15), "{} {de}", r.energy_change);
    }
}

#[test]
fn closed_form_rod_caught_at_its_end() {
    // A rod translating at u perpendicular to itself has one end suddenly fixed (e = 0). Angular
    // momentum about the caught end is kept: m (l/2) u = (m l²/3) ω⁺, so ω⁺ = 3u/(2l), the centre moves
    // at 3u/4, the kinetic energy drops from ½ m u² to 3/8 m u² (a quarter lost) and the pin's impulse
    // is m (3u/4 − u) = −m u/4 along the motion.
    let (m, l, u) = (1.3, 0.8, 2.0);
    let rod = EulerLagrange::new(Rod { m, l });
    let end = [0.5 * l, 0.0];
    let r = Impact::new(&rod)
        .constraints(Pin { s: 0.5 * l, at: end }, 0.0)
        .unwrap()
        .velocities(0.0, &[0.0, 0.0, 0.0], &[0.0, u, 0.0])
        .unwrap();
    let omega = 3.0 * u / (2.0 * l);
    // Measured: all within 1 ulp.
    assert!(close(r.v[2], -omega, 4e-16), "{:?}", r.v);
    assert!(close(r.v[1], 0.75 * u, 4e-16), "{:?}", r.v);
    assert!(r.v[0].abs() < 1e-16, "{:?}", r.v);
    assert!(
        close(r.energy_change, -0.125 * m * u * u, 1e-15),
        "{}",
        r.energy_change
    );
    assert!(close(r.reactions[1], -0.25 * m * u, 1e-15), "{:?}", r.reactions);
    assert!(r.reactions[0].abs() < 1e-16, "{:?}", r.reactions);
}

#[test]
fn closed_form_double_pendulum_struck_at_rest() {
    // A double pendulum hanging at rest, a horizontal blow J on the lower bob: the lower rod is
    // vertical, so it passes only a vertical impulse to the upper bob, which the upper rod takes:
    // θ̇₁⁺ = 0 and θ̇₂⁺ = J/(m₂ l₂). A blow on the upper bob instead: θ̇₁⁺ = J/(m₁ l₁),
    // θ̇₂⁺ = −J/(m₁ l₂), and the lower bob does not move at first (l₁θ̇₁ + l₂θ̇₂ = 0).
    struct Double {
        m: [f64; 2],
        l: [f64; 2],
    }
    impl Lagrangian for Double {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
            let ([m1, m2], [l1, l2]) = (self.m, self.l);
            let c = (q[0] - q[1]).cos();
            v[0] * v[0] * (0.5 * (m1 + m2) * l1 * l1)
                + v[1] * v[1] * (0.5 * m2 * l2 * l2)
                + v[0] * v[1] * c * (m2 * l1 * l2)
                + q[0].cos() * ((m1 + m2) * 9.81 * l1)
                + q[1].cos() * (m2 * 9.81 * l2)
        }
    }
    /// Bob k's position (x, y).
    struct Bob(usize, [f64; 2]);
    impl StruckPoints for Bob {
        fn dof(&self) -> usize {
            2
        }
        fn dim(&self) -> usize {
            2
        }
        fn positions<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
            out[0] = q[0].sin() * self.1[0];
            out[1] = -q[0].cos() * self.1[0];
            if self.0 == 1 {
                out[0] += q[1].sin() * self.1[1];
                out[1] -= q[1].cos() * self.1[1];
            }
        }
    }
    let (m, l, j) = ([1.0, 0.7], [1.2, 0.9], 0.5);
    let el = EulerLagrange::new(Double { m, l });
    let (lower, upper) = (Bob(1, l), Bob(0, l));
    let rest = [0.0, 0.0];
    let r = Impact::new(&el)
        .blow(&lower, &[j, 0.0])
        .unwrap()
        .velocities(0.0, &rest, &rest)
        .unwrap();
    assert!(
        r.v[0].abs() < 1e-16 && close(r.v[1], j / (m[1] * l[1]), 4e-16),
        "{:?}",
        r.v
    );
    let r = Impact::new(&el)
        .blow(&upper, &[j, 0.0])
        .unwrap()
        .velocities(0.0, &rest, &rest)
        .unwrap();
    assert!(close(r.v[0], j / (m[0] * l[0]), 4e-16), "{:?}", r.v);
    assert!(close(r.v[1], -j / (m[0] * l[1]), 4e-16), "{:?}", r.v);
}

#[test]
fn closed_form_rebound_with_restitution() {
    // A tilted rod falls flat (no spin) at speed u onto the floor and its lower end bounces with
    // restitution e: the end's normal velocity is −e times what it was, and for e = 1 the kinetic
    // energy is kept. With the end at angle θ below the centre (s = −l/2 on a rod at angle θ) the end's
    // upward velocity is ẏ + s cos θ θ̇; the floor's impulse P acts on it alone, so
    // ẏ⁺ = −u + P/m and θ̇⁺ = P s cos θ / I, and the law gives P = (1 + e) u / (1/m + s² cos²θ / I).
    let (m, l, u, theta) = (1.0, 2.0, 3.0, 0.4_f64);
    let i = m * l * l / 12.0;
    let rod = EulerLagrange::new(Rod { m, l });
    let s = -0.5 * l;
    let q = [0.0, -s * theta.sin(), theta]; // the end on the floor
    for e in [0.0, 0.5, 1.0] {
        let r = Impact::new(&rod)
            .constraints(Floor { s }, e)
            .unwrap()
            .velocities(0.0, &q, &[0.0, -u, 0.0])
            .unwrap();
        let p = (1.0 + e) * u / (1.0 / m + (s * theta.cos()).powi(2) / i);
        assert!(
            close(r.v[1], -u + p / m, 2e-15),
            "e = {e}: {:?} vs {}",
            r.v,
            -u + p / m
        );
        assert!(
            close(r.v[2], p * s * theta.cos() / i, 2e-15),
            "e = {e}: {:?}",
            r.v
        );
        assert!(
            close(r.reactions[0], p, 2e-15),
            "e = {e}: {:?} vs {p}",
            r.reactions
        );
        let end_after = r.v[1] + s * theta.cos() * r.v[2];
        assert!(close(end_after, e * u, 2e-15), "e = {e}: {end_after}");
        if e == 1.0 {
            // Measured 4.4e-16 of the energy 4.5.
            assert!(r.energy_change.abs() < 2e-15, "{}", r.energy_change);
        }
    }
}

#[test]
fn closed_form_pendulum_bounces_off_a_wall_in_a_run() {
    // A rod pivoted at its end, released horizontal, swings down and hits a wall at the vertical
    // (θ = 0) with restitution e, as a driver event: ω at the wall is sqrt(3g/l) (energy: m g l/2 =
    // ½ (m l²/3) ω²), after it −eω, and the rod rises to cos θ_max = 1 − e² (½ I e²ω² = m g (l/2)(1 − cos θ)).
    struct Pivoted {
        l: f64,
        g: f64,
    }
    impl Lagrangian for Pivoted {
        fn dof(&self) -> usize {
            1
        }
        fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
            v[0] * v[0] * (self.l * self.l / 6.0) + q[0].cos() * (0.5 * self.g * self.l)
        }
    }
    /// The wall's distance along the rod's swing: its tip's x = l sin θ.
    struct Wall {
        l: f64,
    }
    impl Holonomic for Wall {
        fn dof(&self) -> usize {
            1
        }
        fn count(&self) -> usize {
            1
        }
        fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
            out[0] = q[0].sin() * self.l;
        }
    }
    let (l, g, e) = (0.8, 9.81, 0.6);
    let el = EulerLagrange::new(Pivoted { l, g });
    let impact = Impact::new(&el).constraints(Wall { l }, e).unwrap();
    let mut omega_at_wall = Vec::new();
    let event = Event::new("wall", |s: &State| s.q[0]).falling().try_reset(|s| {
        omega_at_wall.push(s.v[0]);
        impact.apply(s).map(|_| ())
    });
    let dp = Dop853::new(&el).tolerances(1e-13, 1e-13).unwrap();
    let top = Event::new("top", |s: &State| s.v[0]).falling();
    let sol = Driver::new(dp, State::new(0.0, [std::f64::consts::FRAC_PI_2], [0.0]))
        .unwrap()
        .event(event)
        .event(top)
        .run_until(1.0)
        .unwrap();
    let t_wall = sol.event_times("wall").unwrap()[0];
    let w = (3.0 * g / l).sqrt();
    // ω at the wall from the event state: measured 1.6e-14 relative (DOP853 at tolerance 1e-13).
    assert!(close(omega_at_wall[0], -w, 1e-13), "{omega_at_wall:?} vs {w}");
    // cos θ_max, measured 1.2e-14 relative.
    let first_top = &sol
        .events_named("top")
        .unwrap()
        .find(|e| e.t > t_wall)
        .unwrap()
        .state;
    assert!(
        close(first_top.q[0].cos(), 1.0 - e * e, 1e-13),
        "{}",
        first_top.q[0]
    );
}

#[test]
fn bad_input_impacts_are_typed_errors() {
    let rod = EulerLagrange::new(Rod { m: 1.0, l: 1.0 });
    let end = OnRod { s: 0.5 };
    // Restitution outside [0, 1].
    let e = Impact::new(&rod)
        .constraints(Floor { s: 0.5 }, 1.5)
        .err()
        .unwrap();
    assert!(
        matches!(
            e,
            Error::Core(noether_core::Error::InvalidParameter {
                name: "restitution",
                ..
            })
        ),
        "{e}"
    );
    // A blow of the wrong length, or not finite.
    assert!(matches!(
        Impact::new(&rod).blow(&end, &[1.0]).err().unwrap(),
        Error::Core(noether_core::Error::Dimension { .. })
    ));
    assert!(matches!(
        Impact::new(&rod).blow(&end, &[f64::NAN, 0.0]).err().unwrap(),
        Error::Core(noether_core::Error::NonFinite { .. })
    ));
    // The same pin twice: redundant impact constraints have no unique reactions.
    struct Twice;
    impl Holonomic for Twice {
        fn dof(&self) -> usize {
            3
        }
        fn count(&self) -> usize {
            2
        }
        fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
            out[0] = q[1];
            out[1] = q[1] * 2.0;
        }
    }
    let e = Impact::new(&rod)
        .constraints(Twice, 0.0)
        .unwrap()
        .velocities(0.0, &[0.0; 3], &[0.0, 1.0, 0.0])
        .err()
        .unwrap();
    assert!(
        matches!(
            e,
            Error::RankDeficientConstraints {
                rank: 1,
                count: 2,
                ..
            }
        ),
        "{e}"
    );
    // A state of the wrong length or not finite.
    let impact = Impact::new(&rod).blow(&end, &[0.0, 1.0]).unwrap();
    assert!(impact.velocities(0.0, &[0.0; 2], &[0.0; 3]).is_err());
    assert!(impact
        .velocities(0.0, &[0.0; 3], &[f64::INFINITY, 0.0, 0.0])
        .is_err());
    // apply leaves the state as it was on an error.
    let redundant = Impact::new(&rod).constraints(Twice, 0.0).unwrap();
    let mut s = State::new(0.0, [0.0; 3], [0.0, 1.0, 0.0]);
    let before = s.clone();
    assert!(redundant.apply(&mut s).is_err());
    assert_eq!(s, before);
}

#[test]
fn closed_form_blow_on_a_locked_point_goes_into_the_reaction() {
    // A blow struck exactly at a point that the impact constraints hold (a rod pinned at its end, hit
    // at the pin): the constraint takes the whole impulse, the rod does not move, and the pin's reaction
    // is −F̂. Not an error: the constraint's reaction is defined and unique (Φ_q has full rank).
    let rod = EulerLagrange::new(Rod { m: 1.5, l: 0.9 });
    let end = OnRod { s: 0.45 };
    let pin = Pin {
        s: 0.45,
        at: [0.45, 0.0],
    };
    let blow = [0.3, -0.7];
    let r = Impact::new(&rod)
        .blow(&end, &blow)
        .unwrap()
        .constraints(pin, 0.0)
        .unwrap()
        .velocities(0.0, &[0.0; 3], &[0.0; 3])
        .unwrap();
    // Measured: v⁺ exactly 0, reactions −F̂ to 1 ulp.
    assert!(r.v.iter().all(|v| v.abs() < 1e-16), "{:?}", r.v);
    assert!(
        close(r.reactions[0], -blow[0], 4e-16) && close(r.reactions[1], -blow[1], 4e-16),
        "{:?}",
        r.reactions
    );
    assert!(r.energy_change.abs() < 1e-16, "{}", r.energy_change);
}
