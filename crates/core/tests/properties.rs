//! Property tests of the error contract (docs/error-contract.md) over core's public API: random models
//! from a small generator of expressions, random sizes, and NaN, ±∞, subnormal and huge numbers in
//! states, steps and times. Every call must return Ok with finite values or a typed error, never panic
//! or hang, and leave its state or output untouched on error.

use noether_core::prelude::*;
use noether_core::{HamiltonEquations, Hamiltonian, Natural, Potential};
use proptest::prelude::*;
use std::time::{Duration, Instant};

/// An expression in t, q, v (v is q̇ or p) built from the operations a model is written with.
#[derive(Debug, Clone)]
enum Expr {
    T,
    Q(usize),
    V(usize),
    C(f64),
    Add(Box<Expr>, Box<Expr>),
    Mul(Box<Expr>, Box<Expr>),
    Div(Box<Expr>, Box<Expr>),
    Sin(Box<Expr>),
    Exp(Box<Expr>),
    Ln(Box<Expr>),
    Sqrt(Box<Expr>),
    Powi(Box<Expr>, i32),
}

impl Expr {
    fn eval<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        use Expr::*;
        match self {
            T => t,
            Q(i) => q[*i],
            V(i) => v[*i],
            C(c) => D::from(*c),
            Add(a, b) => a.eval(t, q, v) + b.eval(t, q, v),
            Mul(a, b) => a.eval(t, q, v) * b.eval(t, q, v),
            Div(a, b) => a.eval(t, q, v) / b.eval(t, q, v),
            Sin(a) => a.eval(t, q, v).sin(),
            Exp(a) => a.eval(t, q, v).exp(),
            Ln(a) => a.eval(t, q, v).ln(),
            Sqrt(a) => a.eval(t, q, v).sqrt(),
            Powi(a, n) => a.eval(t, q, v).powi(*n),
        }
    }
}

/// Mostly ordinary numbers, often the ones that break code: 0, −0, NaN, ±∞, subnormal, huge.
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -3.0..3.0f64,
        1 => prop_oneof![
            Just(0.0),
            Just(-0.0),
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            Just(5e-324),
            Just(f64::MIN_POSITIVE),
            Just(1e-300),
            Just(1e20),
            Just(1e300),
            Just(f64::MAX),
            Just(-1e15),
        ],
    ]
}

fn expr(dof: usize) -> impl Strategy<Value = Expr> {
    let leaf = prop_oneof![
        Just(Expr::T),
        (0..dof).prop_map(Expr::Q),
        (0..dof).prop_map(Expr::V),
        (-2.0..2.0f64).prop_map(Expr::C),
    ];
    leaf.prop_recursive(4, 24, 2, |e| {
        prop_oneof![
            (e.clone(), e.clone()).prop_map(|(a, b)| Expr::Add(Box::new(a), Box::new(b))),
            (e.clone(), e.clone()).prop_map(|(a, b)| Expr::Mul(Box::new(a), Box::new(b))),
            (e.clone(), e.clone()).prop_map(|(a, b)| Expr::Div(Box::new(a), Box::new(b))),
            e.clone().prop_map(|a| Expr::Sin(Box::new(a))),
            e.clone().prop_map(|a| Expr::Exp(Box::new(a))),
            e.clone().prop_map(|a| Expr::Ln(Box::new(a))),
            e.clone().prop_map(|a| Expr::Sqrt(Box::new(a))),
            (e, -3..4i32).prop_map(|(a, n)| Expr::Powi(Box::new(a), n)),
        ]
    })
}

/// L = ½ |q̇|² (when `kinetic`) + E(t, q, q̇); also H(t, q, p) and V(q) with the same expression.
#[derive(Debug, Clone)]
struct Model {
    dof: usize,
    kinetic: bool,
    e: Expr,
}

impl Model {
    fn kinetic<D: Scalar>(&self, v: &[D]) -> D {
        let mut k = D::zero();
        if self.kinetic {
            v.iter().for_each(|w| k += *w * *w * 0.5);
        }
        k
    }
}

impl Lagrangian for Model {
    fn dof(&self) -> usize {
        self.dof
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        self.kinetic(v) + self.e.eval(t, q, v)
    }
}

impl Hamiltonian for Model {
    fn dof(&self) -> usize {
        self.dof
    }
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
        self.kinetic(p) + self.e.eval(t, q, p)
    }
}

impl Potential for Model {
    fn dof(&self) -> usize {
        self.dof
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        // v in the expression reads q: a potential sees positions only.
        self.e.eval(D::zero(), q, q)
    }
}

fn model() -> impl Strategy<Value = Model> {
    (1..4usize, any::<bool>())
        .prop_flat_map(|(dof, kinetic)| expr(dof).prop_map(move |e| Model { dof, kinetic, e }))
}

/// A model with a vector of length dof most of the time, sometimes one too short or too long.
fn model_and_point() -> impl Strategy<Value = (Model, f64, Vec<f64>, Vec<f64>)> {
    model().prop_flat_map(|m| {
        let n = m.dof;
        let len = prop_oneof![8 => Just(n), 1 => Just(n - 1), 1 => Just(n + 1)];
        (
            Just(m),
            number(),
            len.clone().prop_flat_map(|l| prop::collection::vec(number(), l)),
            len.prop_flat_map(|l| prop::collection::vec(number(), l)),
        )
    })
}

/// `Ok` only with finite numbers.
fn finite_ok<T: std::fmt::Debug>(what: &str, r: &Result<T>, values: impl IntoIterator<Item = f64>) {
    if r.is_ok() {
        assert!(
            values.into_iter().all(f64::is_finite),
            "{what}: Ok with a non-finite value: {r:?}"
        );
    }
}

/// Bit patterns, so that a NaN compares equal to itself.
fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

fn state_bits<K: noether_core::Partner>(s: &State<K>) -> (u64, Vec<u64>, Vec<u64>) {
    (s.t.to_bits(), bits(s.q.as_slice()), bits(s.v.as_slice()))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    /// Every evaluation of the Euler-Lagrange equations: Ok and finite, or an error with the output
    /// untouched (issue 15, cases 7 and 9).
    #[test]
    fn prop_lagrangian_evaluations((m, t, q, v) in model_and_point()) {
        let el = EulerLagrange::new(m);
        let r = el.value(t, &q, &v);
        finite_ok("value", &r, r.clone().ok());
        let r = el.energy(t, &q, &v);
        finite_ok("energy", &r, r.clone().ok());
        let r = el.mass_matrix(t, &q, &v);
        finite_ok("mass matrix", &r, r.iter().flat_map(|m| m.iter().copied()).collect::<Vec<_>>());
        type Eval<'a> = Box<dyn Fn(&mut [f64]) -> Result<()> + 'a>;
        let evals: [(&str, Eval); 3] = [
            ("momenta", Box::new(|out| el.momenta(t, &q, &v, out))),
            ("∂L/∂q", Box::new(|out| el.gradient_q(t, &q, &v, out))),
            ("accelerations", Box::new(|out| el.accelerations(t, &q, &v, out))),
        ];
        for (what, f) in evals {
            let mut out = vec![7.0; q.len()];
            let r = f(&mut out);
            finite_ok(what, &r, out.clone());
            if r.is_err() {
                prop_assert_eq!(&out, &vec![7.0; q.len()], "{} wrote its output on error", what);
            }
        }
    }

    /// The same for Hamilton's equations.
    #[test]
    fn prop_hamiltonian_evaluations((m, t, q, p) in model_and_point()) {
        let h = HamiltonEquations::new(m);
        let r = h.energy(t, &q, &p);
        finite_ok("H", &r, r.clone().ok());
        let r = h.hessian(t, &q, &p);
        finite_ok("Hessian", &r, r.iter().flat_map(|m| m.iter().copied()).collect::<Vec<_>>());
        let (mut dq, mut dp) = (vec![7.0; q.len()], vec![7.0; q.len()]);
        let r = h.rates(t, &q, &p, &mut dq, &mut dp);
        finite_ok("rates", &r, dq.iter().chain(&dp).copied().collect::<Vec<_>>());
    }

    /// A natural system T = ½|q̇|², V(q) (issue 15, cases 7 and 9: wrong lengths were panics).
    #[test]
    fn prop_natural_evaluations((m, _t, q, v) in model_and_point()) {
        let nat = Natural::unit(m);
        let r = nat.energy(&q, &v);
        finite_ok("energy", &r, r.clone().ok());
        let r = nat.potential_energy(&q);
        finite_ok("V", &r, r.clone().ok());
        let r = nat.kinetic_energy(&v);
        finite_ok("T", &r, r.clone().ok());
        let mut out = vec![7.0; v.len()];
        let r = nat.momenta(&v, &mut out);
        finite_ok("momenta", &r, out.clone());
        let r = nat.forces(&q, &mut out);
        finite_ok("forces", &r, out.clone());
        let mut b = vec![1.0; v.len()];
        let r = nat.solve_mass(&mut b);
        prop_assert!(r.is_ok() == (b.len() == nat.dof()), "{:?}", r);
    }

    /// One step of an explicit, an adaptive and an implicit method from a random state with a random
    /// step: Ok with a finite state, or an error with the state bit for bit as it was.
    #[test]
    fn prop_one_step_keeps_state_on_error((m, t, q, v) in model_and_point(), h in number()) {
        let el = EulerLagrange::new(m.clone());
        let start = State::new(t, q.clone(), v.clone());
        let check = |name: &str, r: Result<StepInfo>, s: &State, before: &State| {
            match r {
                Ok(_) => assert!(s.is_finite(), "{name}: Ok with a non-finite state {s:?}"),
                Err(_) => assert_eq!(state_bits(s), state_bits(before), "{name}: state changed on error"),
            }
        };
        let mut s = start.clone();
        check("RK4", Rk4::new(&el).step(&mut s, h), &s, &start);
        let mut s = start.clone();
        check("DOPRI5", Dopri5::new(&el).step(&mut s, h), &s, &start);
        let nat = Natural::unit(m);
        let mut s = start.clone();
        check("Gauss 4", Gauss::gauss4(&nat).step(&mut s, h), &s, &start);
    }

    /// A run of the harmonic oscillator from any start time to any end time with any step: it
    /// returns, quickly, with the end time reached exactly or an error (issue 15, cases 4 and 6: Ok
    /// without stepping, a hang at t + h == t).
    #[test]
    fn prop_driver_times(t0 in number(), t_end in number(), h in number(), adaptive in any::<bool>()) {
        let osc = Natural::unit(Oscillator);
        let start = State::new(t0, [1.0], [0.0]);
        let clock = Instant::now();
        let end = if adaptive {
            Driver::new(Dopri5::new(&osc), start)
                .map(|d| d.max_steps(2000))
                .and_then(|mut d| d.run_until(t_end).map(|s| s.last().clone()))
        } else {
            Driver::with_step(Rk4::new(&osc), start, h)
                .map(|d| d.max_steps(2000))
                .and_then(|mut d| d.run_until(t_end).map(|s| s.last().clone()))
        };
        // 2000 steps of a one-dimensional oscillator take microseconds: a second means a hang.
        prop_assert!(clock.elapsed() < Duration::from_secs(1), "took {:?}", clock.elapsed());
        if let Ok(s) = end {
            prop_assert_eq!(s.t, t_end);
            prop_assert!(s.is_finite());
        }
    }
}

/// V = ½ q².
struct Oscillator;
impl Potential for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        q[0] * q[0] * 0.5
    }
}

/// V = g y for a ball in free fall (g = 9.81).
struct Fall;
impl Potential for Fall {
    fn dof(&self) -> usize {
        1
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        q[0] * 9.81
    }
}

/// Runs `driver` to `t_end` again and again, continuing after each terminal stop; the stop times.
fn stops<S: Stepper<Partner = Velocities>>(mut driver: Driver<'_, S>, t_end: f64) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for _ in 0..100 {
        let sol = driver.run_until(t_end)?;
        if sol.stop() == Stop::EndTime {
            return Ok(out);
        }
        out.push(sol.last().t);
    }
    Err(Error::Unsupported(
        "more than 100 stops: a terminal event fires again when continued",
    ))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// The driver's events against the closed form (issue 29): q = A cos(t + φ) crosses the level c
    /// downwards where t + φ = α + 2πk and upwards where t + φ = 2π − α + 2πk, α = acos(c/A). A
    /// terminal event continued after each stop must stop at each crossing once, in order, whatever
    /// the method, the step, the phase and the level. DOP853 at 1e-12 and RK4 at h ≤ 0.02 (phase
    /// error ≤ h⁴t/120 ≈ 3e-8 at t = 20) put the crossings within 1e-6.
    #[test]
    fn prop_terminal_events_continue_once_each(
        amp in 0.1f64..10.0,
        level in -0.9f64..0.9,
        phase in 0.0f64..std::f64::consts::TAU,
        rising in any::<bool>(),
        h in 0.001f64..0.02,
        adaptive in any::<bool>(),
    ) {
        let (tau, t_end) = (std::f64::consts::TAU, 20.0);
        let alpha = level.acos();
        let first = if rising { tau - alpha } else { alpha };
        let mut expected = Vec::new();
        let mut k = ((phase - first) / tau).ceil();
        loop {
            let t = first + k * tau - phase;
            if t > t_end {
                break;
            }
            if t > 0.0 {
                expected.push(t);
            }
            k += 1.0;
        }
        prop_assume!(expected.iter().all(|t| t > &1e-4 && (t_end - t).abs() > 1e-4));
        let start = State::new(0.0, [amp * phase.cos()], [-amp * phase.sin()]);
        let c = level * amp;
        let dir = if rising { Direction::Rising } else { Direction::Falling };
        let event = Event::new("q = c", move |s: &State| s.q[0] - c).direction(dir).terminal();
        let osc = Natural::unit(Oscillator);
        let found = if adaptive {
            let m = Dop853::new(&osc).tolerances(1e-12, 1e-12).unwrap();
            stops(Driver::new(m, start).unwrap().event(event), t_end)
        } else {
            stops(Driver::with_step(Rk4::new(&osc), start, h).unwrap().event(event), t_end)
        };
        let found = found.unwrap();
        prop_assert_eq!(found.len(), expected.len(), "{:?} vs {:?}", found, expected);
        for (t, e) in found.iter().zip(&expected) {
            prop_assert!((t - e).abs() < 1e-6, "{} vs {}", t, e);
        }
    }

    /// A bouncing ball with random height, restitution (≥ 0.7: the impacts accumulate after
    /// t₁(1 + 2e/(1 − e)) ≥ 5.6 t₁, beyond the run's 4 t₁), method and step finds every impact of the
    /// closed form (free fall t₁ = √(2h₀/g), then flights of 2eᵏu/g, u = √(2gh₀)) and never ends
    /// below the floor (issue 29 item 1: an adaptive method's long step over a flight missed the next
    /// landing). A parabola is integrated and interpolated exactly, so the times agree to rounding.
    #[test]
    fn prop_bouncing_ball_finds_every_impact(
        h0 in 0.1f64..10.0,
        e in 0.7f64..0.95,
        method in 0usize..4,
        h in 0.01f64..1.0,
    ) {
        let g = 9.81;
        let (u, t1) = ((2.0 * g * h0).sqrt(), (2.0 * h0 / g).sqrt());
        let t_end = 4.0 * t1;
        let mut expected = vec![t1];
        let mut k = 1;
        loop {
            let t = expected[expected.len() - 1] + 2.0 * e.powi(k) * u / g;
            if t > t_end {
                break;
            }
            expected.push(t);
            k += 1;
        }
        prop_assume!(expected.iter().all(|t| (t_end - t).abs() > 1e-6));
        let bounce = Event::new("floor", |s: &State| s.q[0]).falling().reset(move |s| s.v[0] *= -e);
        let start = State::new(0.0, [h0], [0.0]);
        let sol = match method {
            0 => Driver::new(Dopri5::new(Natural::unit(Fall)), start).unwrap().event(bounce).run_until(t_end),
            1 => Driver::new(Dop853::new(Natural::unit(Fall)), start).unwrap().event(bounce).run_until(t_end),
            2 => Driver::new(Dprkn8::new(Natural::unit(Fall)).unwrap(), start).unwrap().event(bounce).run_until(t_end),
            _ => Driver::with_step(Rk4::new(Natural::unit(Fall)), start, h).unwrap().event(bounce).run_until(t_end),
        }
        .unwrap();
        let found = sol.event_times("floor").unwrap();
        prop_assert_eq!(found.len(), expected.len(), "{:?} vs {:?}", found, expected);
        for (t, x) in found.iter().zip(&expected) {
            // Rounding of a few operations per bounce on values of size t_end (≤ 6 s).
            prop_assert!((t - x).abs() < 1e-12 * t_end.max(1.0) * (1.0 + k as f64), "{} vs {}", t, x);
        }
        prop_assert!(sol.last().q[0] > -1e-9 * h0, "ended at {}", sol.last().q[0]);
    }
}
