//! IAS15 with forces that depend on time and velocities ([`VelocityDependent`]): the damped and the
//! driven oscillator against their closed forms, a velocity blow-up against its closed form and the
//! error contract at it, and the velocity-dependent path on a velocity-independent system against
//! the fast path.

use super::problems::*;
use noether_core::integrators::VelocityDependent;
use noether_core::prelude::*;

/// q̈ = −ω²q − 2γq̇ + F cos(Ωt), a hand-written vector field on (q, q̇).
struct Oscillator {
    omega: f64,
    gamma: f64,
    force: f64,
    drive: f64,
}

impl Dynamics for Oscillator {
    type Partner = Velocities;
    fn dof(&self) -> usize {
        1
    }
    fn rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
        dq[0] = v[0];
        dv[0] =
            -self.omega * self.omega * q[0] - 2.0 * self.gamma * v[0] + self.force * (self.drive * t).cos();
        Ok(())
    }
    fn energy(&self, _t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        Ok(0.5 * (v[0] * v[0] + self.omega * self.omega * q[0] * q[0]))
    }
}

impl Oscillator {
    /// The closed form (q, q̇)(t) from (q₀, v₀) at t = 0, underdamped (γ < ω), off resonance: the
    /// steady state q_p = A cos Ωt + B sin Ωt with D = (ω² − Ω²)² + 4γ²Ω², A = F(ω² − Ω²)/D,
    /// B = 2γΩF/D, plus the transient e^{−γt}(C₁ cos ω_d t + C₂ sin ω_d t), ω_d = √(ω² − γ²),
    /// C₁ = q₀ − A, C₂ = (v₀ + γC₁ − ΩB)/ω_d (e.g. Landau & Lifshitz, *Mechanics*, §25-26).
    fn exact(&self, (q0, v0): (f64, f64), t: f64) -> (f64, f64) {
        let (w, g, f, o) = (self.omega, self.gamma, self.force, self.drive);
        let d = (w * w - o * o).powi(2) + 4.0 * g * g * o * o;
        let (a, b) = (f * (w * w - o * o) / d, 2.0 * g * o * f / d);
        let wd = (w * w - g * g).sqrt();
        let c1 = q0 - a;
        let c2 = (v0 + g * c1 - o * b) / wd;
        let (c, s) = ((wd * t).cos(), (wd * t).sin());
        let decay = (-g * t).exp();
        let q = decay * (c1 * c + c2 * s) + a * (o * t).cos() + b * (o * t).sin();
        let v = decay * ((-g * c1 + wd * c2) * c + (-g * c2 - wd * c1) * s) - a * o * (o * t).sin()
            + b * o * (o * t).cos();
        (q, v)
    }
}

/// The damped oscillator (F = 0: q̈ = −ω²q − 2γq̇, velocity-dependent) and the driven one (F ≠ 0:
/// explicit time dependence as well) against the closed form [`Oscillator::exact`], at t = 1, 2, …,
/// 40 (six periods) at the default ε = 1e-9. IAS15 converges each step to machine precision, so
/// the error is rounding: a few ulps of the amplitude (≤ 1.4) per step, growing like √N over N ≈ 10²
/// steps to ~1e-14; the closed form itself carries a few ulps of its terms. Measured max |Δq|,
/// |Δq̇| 1.2e-15 (damped, 259 steps) and 8.6e-15 (driven, 329 steps), checked at 2e-14. Velocities
/// not predicted at the nodes (v₀ in f everywhere) would leave an error O(γh²) per step, far above.
///
/// The step control is [`Global`](Ias15Control::Global): with one coordinate the acceleration
/// passes through zero, and there [`Prs23`](Ias15Control::Prs23)'s timescale √(2|a(1)|²/|ȧ(1)|²) of
/// a step from a(0) ≈ 0 is proportional to the step itself, so every trial is redone smaller until
/// the step underflows (at t = π/2 on q̈ = −q from q = 1, with or without this wrapper, as on a
/// pendulum through Natural: a limit of the criterion for one-dimensional blocks, whose |a| vanishes,
/// that particles in space do not meet).
#[test]
fn closed_form_ias15_damped_and_driven_oscillator() {
    for (force, what) in [(0.0, "damped"), (0.5, "driven")] {
        let osc = Oscillator {
            omega: 1.0,
            gamma: 0.1,
            force,
            drive: 1.3,
        };
        let y0 = (1.0, 0.0);
        let mut exact = Vec::new();
        for k in 1..=40 {
            exact.push(osc.exact(y0, k as f64));
        }
        let ias = Ias15::new(VelocityDependent(osc))
            .unwrap()
            .control(Ias15Control::Global);
        let mut d = Driver::new(ias, State::new(0.0, [y0.0], [y0.1]))
            .unwrap()
            .save(Save::End)
            .unwrap();
        let (mut worst, mut steps) = (0.0_f64, 0);
        for (k, (q, v)) in exact.iter().enumerate() {
            let sol = d.run_until((k + 1) as f64).unwrap();
            steps += sol.stats().steps;
            let s = sol.last();
            worst = worst.max((s.q[0] - q).abs()).max((s.v[0] - v).abs());
        }
        eprintln!("IAS15 {what} oscillator to t = 40: max error {worst:.2e}, {steps} steps");
        assert!(worst < 2e-14, "{what}: {worst:e}");
    }
}

/// q̈ = q̇² from q = 0, q̇ = 1: q̇ = 1/(1 − t), q = −ln(1 − t), a blow-up of the velocity at t = 1
/// that only the velocities see. Up to t = 0.99 (q̇ = 100) the adaptive steps follow it to a relative
/// error of rounding: 57 steps of a few ulps each, the velocity's amplified by the equation's
/// instability (∂f/∂q̇ = 2q̇ grows to 200). Measured 1.6e-15 in q, 7.3e-15 in q̇, checked at 2e-14
/// and 5e-14.
/// Then the steps shrink until they pass h_min = 1e-8 and the step that gives up leaves the state
/// as it was, with a typed [`Error::StepSizeUnderflow`].
#[test]
fn closed_form_ias15_velocity_blow_up_and_error_contract() {
    struct BlowUp;
    impl Dynamics for BlowUp {
        type Partner = Velocities;
        fn dof(&self) -> usize {
            1
        }
        fn rates(&self, _t: f64, _q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
            dq[0] = v[0];
            dv[0] = v[0] * v[0];
            Ok(())
        }
        fn energy(&self, _t: f64, _q: &[f64], v: &[f64]) -> Result<f64> {
            Ok(0.5 * v[0] * v[0])
        }
    }
    let ias = Ias15::new(VelocityDependent(BlowUp)).unwrap();
    let mut d = Driver::new(ias, State::new(0.0, [0.0], [1.0])).unwrap();
    let sol = d.run_until(0.99).unwrap();
    let s = sol.last();
    let (eq, ev) = ((s.q[0] / 100f64.ln() - 1.0).abs(), (s.v[0] / 100.0 - 1.0).abs());
    eprintln!(
        "IAS15 q̈ = q̇² to t = 0.99: relative errors {eq:.1e} (q) {ev:.1e} (q̇), {:?}",
        sol.stats()
    );
    assert!(eq < 2e-14 && ev < 5e-14, "{eq:e} {ev:e}");

    let mut s = Ias15::new(VelocityDependent(BlowUp))
        .unwrap()
        .h_min(1e-8)
        .unwrap();
    let mut state = State::new(0.0, [0.0], [1.0]);
    let failure = step_until_failure(&mut s, &mut state, 0.01, 1.0, "the blow-up");
    assert!(matches!(failure, Error::StepSizeUnderflow { .. }), "{failure:?}");
    assert!(state.t > 0.999, "{}", state.t);
    // In fixed-step mode a step across the blow-up is a typed error, the state untouched.
    let mut s = Ias15::new(VelocityDependent(BlowUp)).unwrap().fixed_step(true);
    let mut state = State::new(0.0, [0.0], [1.0]);
    let before = state.clone();
    let r = s.step(&mut state, 2.0);
    assert!(
        matches!(
            r,
            Err(Error::NonFiniteResult { .. } | Error::NewtonDiverged { .. })
        ),
        "{r:?}"
    );
    assert_eq!(state, before);
}

/// On a system whose forces depend on q alone, the velocity-dependent path (which also predicts v
/// at the nodes and passes t and v to the rates) computes the same accelerations at the same
/// positions: the same steps, evaluations and state, bit for bit, as the fast path (Kepler e = 0.6,
/// 10 orbits).
#[test]
fn regress_ias15_velocity_path_matches_the_fast_path() {
    let start = kepler_start::<Velocities>(0.6);
    let t_end = 20.0 * std::f64::consts::PI;
    let fast = Driver::new(Ias15::new(Natural::unit(KeplerV)).unwrap(), start.clone())
        .unwrap()
        .save(Save::End)
        .unwrap()
        .run_until(t_end)
        .unwrap();
    let full = Driver::new(
        Ias15::new(VelocityDependent(Natural::unit(KeplerV))).unwrap(),
        start,
    )
    .unwrap()
    .save(Save::End)
    .unwrap()
    .run_until(t_end)
    .unwrap();
    assert_eq!(fast.last(), full.last());
    assert_eq!(fast.stats().steps, full.stats().steps);
    assert_eq!(fast.stats().evaluations, full.stats().evaluations);
}
