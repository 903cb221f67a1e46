//! The cart-pole balanced upright by the linear-quadratic regulator.
//!
//! The cart-pole (`noether_testkit::control::CartPole`: cart M = 1, bob m = 0.3 on a rod l = 0.8,
//! θ from the upward vertical, a force u on the cart) is linearised at the top by dual numbers, the
//! gain K that minimises ∫ (xᵀQx + uᵀRu) dt (Q = diag(10, 10, 1, 1), R = 0.1) comes from the
//! continuous Riccati equation AᵀX + XA − XBR⁻¹BᵀX + Q = 0, and u = −Kx runs on the nonlinear model.
//!
//! Checks:
//! 1. **The textbook linearisation.** From (M + m)ẍ + m l θ̈ = u, m l ẍ + m l² θ̈ − m g l θ = 0:
//!    ẍ = −(mg/M)θ + u/M, θ̈ = (M + m)gθ/(Ml) − u/(Ml) (`CartPole::upright_linearization`).
//! 2. **The closed loop's eigenvalues.** The Jacobian of the nonlinear closed loop at the top — third
//!    derivatives of L and the feedback's derivatives, by dual numbers through the policy — has the
//!    eigenvalues of A − BK of the design.
//! 3. **The value function.** From a small lean θ₀ the cost of the nonlinear closed-loop run,
//!    ∫₀^∞ (xᵀQx + uᵀRu) dt, is x₀ᵀXx₀ (Anderson and Moore, *Optimal Control: Linear Quadratic
//!    Methods*, §3.3), up to the pendulum's nonlinearity, O(θ₀²) relative. The cost is integrated with
//!    the motion by a bookkeeping coordinate w (L_w = ½ẇ², pushed by the running cost); doubling θ₀
//!    multiplies the difference by 4.
//! 4. **The balance.** From a 0.3 rad lean the nonlinear closed loop comes to rest upright.
//! 5. **Sampled.** The design for a controller that samples every h = 0.01 (one RK4 step's exact
//!    Jacobian with the input held, the discrete Riccati equation with weights Qh, Rh) stabilises the
//!    step, and its gain is within O(h) of the continuous one.
//!
//! Run: `cargo run --release --features examples --example cart_pole_lqr`.

use noether::analysis::{dlqr, linearize, linearize_step, lqr, Lqr};
use noether::core::control::{Actuated, ClosedLoop, LinearFeedback};
use noether::core::integrators::Rk4;
use noether::core::system::LinearizedDynamics;
use noether::nalgebra::{DMatrix, DVector};
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::control::CartPole;
use std::process::ExitCode;

const NAME: &str = "cart_pole_lqr";
/// The diagonal of the state weight Q, on (x, θ, ẋ, θ̇).
const STATE_WEIGHTS: [f64; 4] = [10.0, 10.0, 1.0, 1.0];
/// The input weight R.
const INPUT_WEIGHT: f64 = 0.1;

/// The cart-pole under u = −Kx with its running cost xᵀQx + uᵀRu as the bookkeeping coordinate w:
/// L' = L + ½ẇ², Q_w = xᵀQx + uᵀRu, so ẇ(t) − ẇ(0) is the cost so far.
struct Ledger {
    cart_pole: CartPole,
    gain: [f64; 4],
}

impl Lagrangian for Ledger {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        self.cart_pole.lagrangian(t, &q[..2], &v[..2]) + v[2] * v[2] * 0.5
    }
    fn has_generalized_force(&self) -> bool {
        true
    }
    fn generalized_force<D: Scalar>(&self, t: D, q: &[D], v: &[D], out: &mut [D]) {
        let x = [q[0], q[1], v[0], v[1]];
        let u = x
            .iter()
            .zip(&self.gain)
            .fold(D::zero(), |s, (xi, ki)| s - *xi * *ki);
        self.cart_pole
            .input_force(t, &q[..2], &v[..2], &[u], &mut out[..2]);
        out[2] = x
            .iter()
            .zip(STATE_WEIGHTS)
            .fold(u * u * INPUT_WEIGHT, |s, (xi, w)| s + *xi * *xi * w);
    }
}

/// The LQR design at the top.
fn design(cp: &CartPole) -> Result<Lqr, BoxError> {
    let lin = linearize(cp, 0.0, &[0.0, 0.0], &[0.0, 0.0], &[0.0])?;
    Ok(lqr(
        &lin,
        &DMatrix::from_diagonal(&DVector::from_column_slice(&STATE_WEIGHTS)),
        &DMatrix::from_element(1, 1, INPUT_WEIGHT),
    )?)
}

/// The cost of the nonlinear closed-loop run from a lean θ₀ and its prediction x₀ᵀXx₀ (check 3).
fn value(cp: CartPole, design: &Lqr, theta0: f64) -> Result<(f64, f64), BoxError> {
    let gain = [0, 1, 2, 3].map(|j| design.gain[(0, j)]);
    let ledger = EulerLagrange::new(Ledger { cart_pole: cp, gain });
    let sol = Driver::new(
        Dop853::new(&ledger).tolerances(1e-13, 1e-13)?,
        State::new(0.0, [0.0, theta0, 0.0], [0.0, 0.0, 0.0]),
    )?
    .run_until(20.0)?;
    Ok((sol.last().v[2], design.riccati[(1, 1)] * theta0 * theta0))
}

/// Runs the example.
///
/// Tolerances: the linearisation and the closed-loop Jacobian are exact to rounding (measured 2e-16
/// and 1e-14 relative; tolerances 1e-15 and 1e-12, the eigenvalues of a 4 × 4 nonsymmetric matrix
/// amplifying rounding by its condition). The value function at θ₀ = 1e-3 differs by the pendulum's
/// nonlinearity, O(θ₀²) = 1e-6 relative times a constant of order one (measured 1.14e-6; tolerance
/// 1e-5), which the ratio at 2θ₀ confirms to be of order θ₀²: 4 up to the next order, O(θ₀²)
/// relative, and the integration's ~1e-12 over a difference of ~1e-6 (measured 1.5e-7; tolerance 1e-5). The balance: from 0.3 rad the loop, slowest
/// rate σ = −2.0, decays as e^{σt} beyond its transient: e^{10σ}·0.3 = 5.5e-10 times the transient's
/// growth, measured 1.1e-8 after 10 s (tolerance 1e-6). The
/// sampled gain differs from the continuous by O(h): 3.5 of 74 at h = 0.01 (tolerance 10 %).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let cp = CartPole::default();

    let lin = linearize(&cp, 0.0, &[0.0, 0.0], &[0.0, 0.0], &[0.0])?;
    let (a, b) = cp.upright_linearization();
    let a = DMatrix::from_fn(4, 4, |i, j| a[i][j]);
    let b = DMatrix::from_column_slice(4, 1, &b);
    report.checks.push(Check::abs(
        NAME,
        "A vs the textbook's (largest difference, relative)",
        (&lin.a - &a).amax() / a.amax(),
        0.0,
        1e-15,
    ));
    report.checks.push(Check::abs(
        NAME,
        "B vs the textbook's (largest difference, relative)",
        (&lin.b - &b).amax() / b.amax(),
        0.0,
        1e-15,
    ));

    let lqr = design(&cp)?;
    report.note(format!("K = {:.4?}", lqr.gain.as_slice()));
    let feedback = LinearFeedback::new(lqr.gain.clone(), &[0.0, 0.0], &[0.0, 0.0], &[0.0])?;
    let closed = EulerLagrange::new(ClosedLoop::new(cp, feedback)?);
    let mut jac = DMatrix::zeros(4, 4);
    closed.jacobian(0.0, &[0.0, 0.0], &[0.0, 0.0], &mut jac)?;
    let mut designed: Vec<_> = lqr.closed_loop.clone();
    let mut measured: Vec<_> = jac.complex_eigenvalues().iter().copied().collect();
    for set in [&mut designed, &mut measured] {
        set.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
    }
    let scale = designed.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let worst = designed
        .iter()
        .zip(&measured)
        .map(|(x, y)| (x - y).norm() / scale)
        .fold(0.0, f64::max);
    let listed: Vec<String> = designed
        .iter()
        .map(|l| format!("{:.4}{:+.4}i", l.re, l.im))
        .collect();
    report.note(format!("closed-loop eigenvalues: {}", listed.join(", ")));
    report.checks.push(Check::abs(
        NAME,
        "eigenvalues of the nonlinear closed loop's Jacobian vs A − BK (relative)",
        worst,
        0.0,
        1e-12,
    ));
    let sigma = designed.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max);

    let (cost, predicted) = value(cp, &lqr, 1e-3)?;
    report.checks.push(Check::rel(
        NAME,
        "cost ∫(xᵀQx + uᵀRu)dt from θ₀ = 1e-3 vs x₀ᵀXx₀",
        cost,
        predicted,
        1e-5,
    ));
    // The difference is the nonlinearity's: doubling θ₀ multiplies it by 4.
    let (cost2, predicted2) = value(cp, &lqr, 2e-3)?;
    let growth = ((cost2 - predicted2) / predicted2) / ((cost - predicted) / predicted);
    report.checks.push(Check::rel(
        NAME,
        "(cost − x₀ᵀXx₀)/x₀ᵀXx₀ at θ₀ = 2e-3 over θ₀ = 1e-3 (order θ₀²)",
        growth,
        4.0,
        1e-5,
    ));

    let balance = Driver::new(
        Dop853::new(&closed).tolerances(1e-11, 1e-11)?,
        State::new(0.0, [0.0, 0.3], [0.0, 0.0]),
    )?
    .observe("u", |s| {
        closed.lagrangian().inputs_at(s.t, s.q.as_slice(), s.v.as_slice())[0]
    })
    .run_until(10.0)?;
    let last = balance.last();
    let rest = last.q.amax().max(last.v.amax());
    report.note(format!(
        "balance from 0.3 rad: largest |x|, |θ|, |ẋ|, |θ̇| after 10 s = {rest:.1e} (slowest rate σ = {sigma:.3})"
    ));
    report.checks.push(Check::abs(
        NAME,
        "balanced from a 0.3 rad lean: at rest upright after 10 s",
        rest,
        0.0,
        1e-6,
    ));

    let h = 0.01;
    let step = linearize_step(
        &cp,
        |l| Rk4::new(EulerLagrange::new(l)),
        0.0,
        (&[0.0, 0.0], &[0.0, 0.0]),
        &[0.0],
        h,
    )?;
    let sampled = dlqr(
        &step,
        &(DMatrix::from_diagonal(&DVector::from_column_slice(&STATE_WEIGHTS)) * h),
        &DMatrix::from_element(1, 1, INPUT_WEIGHT * h),
    )?;
    let radius = sampled.closed_loop.iter().map(|l| l.norm()).fold(0.0, f64::max);
    report.note(format!(
        "sampled design (h = {h}): spectral radius of the step's closed loop {radius:.6}"
    ));
    report.checks.push(Check::abs(
        NAME,
        "sampled gain (h = 0.01) vs the continuous one (relative)",
        (&sampled.gain - &lqr.gain).amax() / lqr.gain.amax(),
        0.0,
        0.1,
    ));

    let theta: Vec<(f64, f64)> = (0..balance.len())
        .map(|i| (balance.times()[i], balance.q(i)[1]))
        .collect();
    let cart: Vec<(f64, f64)> = (0..balance.len())
        .map(|i| (balance.times()[i], balance.q(i)[0]))
        .collect();
    let force: Vec<(f64, f64)> = balance
        .times()
        .iter()
        .zip(balance.observed("u")?)
        .map(|(&t, u)| (t, u / 100.0))
        .collect();
    let fig = Figure::new("Cart-pole balanced by LQR from a 0.3 rad lean")
        .x_label("t")
        .y_label("θ, x, u/100")
        .series("pole angle θ", theta)
        .series("cart position x", cart)
        .series("force on the cart u/100 (recorded by an observer)", force);
    report.save(opts, &fig, "cart_pole_lqr.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
