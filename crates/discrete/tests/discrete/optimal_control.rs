//! Optimal control by discrete mechanics: the double integrator's discrete optimum in closed form and
//! its second-order convergence to the continuous one; a nonlinear, underactuated transfer (the
//! cart-pole's cart moved with the pole hanging) replayed through the forced variational integrator
//! and converging at second order; bad input.

use noether_core::control::{Actuated, ClosedLoop, OpenLoop};
use noether_core::{Error, Stepper};
use noether_discrete::optimal_control::{Effort, OptimalControl, OptimalPath};
use noether_discrete::{DiscreteActuated, Midpoint, Trapezoidal, VariationalIntegrator};
use noether_testkit::control::{CartPole, DoubleIntegrator, ReactionWheel};
use std::f64::consts::PI;

/// The least-effort problem (∫u² dt) of a one-input model, by the midpoint rule.
pub(crate) fn least_effort<L: Actuated>(model: L) -> OptimalControl<Midpoint<L>, Effort> {
    OptimalControl::new(Midpoint::new(model), Effort::new(vec![1.0]).unwrap())
}

/// The cart-pole swung up by `problem` from hanging at rest to upright at rest, the cart back at
/// x = 0, in `t_end` with N = 100 steps, from the straight line.
pub(crate) fn swing_up(
    problem: &OptimalControl<Midpoint<CartPole>, Effort>,
    t_end: f64,
) -> noether_core::Result<OptimalPath> {
    problem.solve(
        0.0,
        (&[0.0, PI], &[0.0, 0.0]),
        t_end,
        (&[0.0, 0.0], &[0.0, 0.0]),
        100,
    )
}

/// The minimum-effort transfer of q̈ = u from rest at 0 to rest at 1 in time T, N steps.
fn double_integrator(t_end: f64, steps: usize) -> OptimalPath {
    let problem = least_effort(DoubleIntegrator);
    problem
        .solve(0.0, (&[0.0], &[0.0]), t_end, (&[1.0], &[0.0]), steps)
        .unwrap()
}

/// For q̈ = u the midpoint rule is exact for inputs constant on each step: q_{k+1} − 2q_k + q_{k−1} =
/// h²(u_{k−1} + u_k)/2 is the exact motion, and p₀ = (q₁ − q₀)/h − (h/2)u₀ the exact start velocity.
/// The discrete problem is so min Σ h u_k² over piecewise-constant u with the exact end conditions
/// ∫(T − s)u ds = 1, ∫u ds = 0: the minimum-norm solution u = Gᵀ(GGᵀ)⁻¹b with the Gram matrix
/// GGᵀ = [[T³/3 − Th²/12, T²/2], [T²/2, T]] (the midpoint sums of (T − s)², T − s and 1), which gives
///
///   u_k = u(t_k + h/2) / (1 − (h/T)²),   J_d = 12 / (T (T² − h²)),
///
/// u(t) = (6/T²)(1 − 2t/T) and J = 12/T³ the continuous optimum (Bryson and Ho §5.2). The solver
/// must meet both to rounding (measured at most 1.3e-15 relative for the cost and 9e-16 for the inputs,
/// N = 1000 a banded KKT solve of 3000 unknowns), and so converges to the continuous optimum at exactly
/// second order. (12/T³ itself is met to (h/T)² = 1e-6 relative at N = 1000, not better: the floor of
/// a second-order discretisation.)
#[test]
fn double_integrator_meets_the_discrete_closed_form() {
    let t_end = 2.0;
    for steps in [10, 100, 1000] {
        let path = double_integrator(t_end, steps);
        let h = t_end / steps as f64;
        let shrink = 1.0 - (h / t_end).powi(2);
        let cost = 12.0 / (t_end * (t_end * t_end - h * h));
        let cost_error = (path.cost - cost).abs() / cost;
        let input_error = path
            .u
            .iter()
            .enumerate()
            .map(|(k, u)| {
                let t = (k as f64 + 0.5) * h;
                (u[0] - 6.0 / t_end.powi(2) * (1.0 - 2.0 * t / t_end) / shrink).abs()
            })
            .fold(0.0, f64::max);
        let continuous = (path.cost - 12.0 / t_end.powi(3)) / (12.0 / t_end.powi(3));
        println!(
            "N = {steps}: cost {:.15}, relative error to the discrete closed form {cost_error:.1e}, inputs \
             {input_error:.1e}; to 12/T³: {continuous:.3e}; {} Newton iterations",
            path.cost, path.newton.iterations
        );
        assert!(cost_error < 1e-14, "N = {steps}: cost off by {cost_error:e}");
        assert!(input_error < 1e-13, "N = {steps}: inputs off by {input_error:e}");
        assert_eq!(path.q[0][0], 0.0);
        assert_eq!(path.q[steps][0], 1.0);
    }
}

/// Moves the cart-pole's cart from x = 0 to x = 1 in T = 2 with the pole hanging (θ = π), at rest at
/// both ends, with minimum ∫u² dt, N steps of the discretisation `rule`: the pole swings on the way
/// (the cart's acceleration drives it through cos θ), so the constraints are nonlinear and the system
/// underactuated.
fn transfer_by<M: DiscreteActuated>(rule: M, steps: usize) -> OptimalPath {
    let problem = OptimalControl::new(rule, Effort::new(vec![1.0]).unwrap());
    problem
        .solve(
            0.0,
            (&[0.0, PI], &[0.0, 0.0]),
            2.0,
            (&[1.0, PI], &[0.0, 0.0]),
            steps,
        )
        .unwrap()
}

/// The transfer by the midpoint rule.
fn cart_transfer(steps: usize) -> OptimalPath {
    transfer_by(Midpoint::new(CartPole::default()), steps)
}

/// Feeds the optimal inputs of `path` (from `start` velocities) open loop to the forced midpoint
/// variational integrator of the cart-pole (an independent code path: its own Newton per step from
/// the start state) and returns the largest distance of its nodes from the path's and its velocity
/// at the end.
pub(crate) fn replay(path: &OptimalPath, v0: &[f64]) -> (f64, f64) {
    replay_of(CartPole::default(), path, v0)
}

/// [`replay`] for any actuated model with one input.
pub(crate) fn replay_of<L: Actuated>(actuated: L, path: &OptimalPath, v0: &[f64]) -> (f64, f64) {
    let steps = path.u.len();
    let h = path.t[1] - path.t[0];
    let inputs: Vec<f64> = path.u.iter().map(|u| u[0]).collect();
    // u_k on [t_k, t_{k+1}); the midpoint rule evaluates it at t_k + h/2.
    let schedule = OpenLoop::new(1, move |t: f64, u: &mut [f64]| {
        u[0] = inputs[((t / h).floor() as usize).min(steps - 1)];
    });
    let model = ClosedLoop::new(actuated, schedule).unwrap();
    let mut vi = VariationalIntegrator::new(Midpoint::new(model));
    let mut s = vi.state_from_velocities(0.0, path.q[0].as_slice(), v0).unwrap();
    let mut worst = 0.0_f64;
    for q in &path.q[1..] {
        vi.step(&mut s, h).unwrap();
        worst = worst.max((&s.q - q).amax());
    }
    (worst, vi.velocities(&s).unwrap().amax())
}

/// The optimal transfer is a motion of the discrete dynamics: replayed open loop (`replay`) it
/// reproduces each node to the Newton tolerances of the two solves (measured 9e-16 over 50 steps; the
/// replay's Newton stops at a momentum residual of 1e-12, which moves a node by ~h²·1e-12) and ends
/// at rest likewise (measured 3e-15). Newton on the KKT system converges quadratically from the
/// straight line (measured 5 iterations).
#[test]
fn cart_transfer_is_a_motion_of_the_forced_variational_integrator() {
    let path = cart_transfer(50);
    println!(
        "cart transfer: cost {:.6}, {} Newton iterations, largest |u| {:.3}",
        path.cost,
        path.newton.iterations,
        path.u.iter().map(|u| u[0].abs()).fold(0.0, f64::max)
    );
    assert!(path.newton.iterations <= 6, "{}", path.newton.iterations);
    let (worst, v_end) = replay(&path, &[0.0, 0.0]);
    println!("replay: nodes within {worst:.1e}, end velocity {v_end:.1e}");
    assert!(worst < 1e-13, "{worst:e}");
    assert!(v_end < 1e-13, "{v_end}");
    // The pole really swings: this is not the linear problem in disguise.
    let swing = path.q.iter().map(|q| (q[1] - PI).abs()).fold(0.0, f64::max);
    assert!(swing > 0.1, "{swing}");
}

/// The cart-pole swung up from hanging (θ = π) to upright (θ = 0), at rest at both ends with the cart
/// back at x = 0, in T = 2 with N = 100 steps and minimum ∫u² dt: Newton from the
/// straight line converges (measured 12 iterations), and the replay ends upright at rest (nodes within
/// 1e-13 as above, measured 8e-15 after the swing; end velocity measured 3e-14).
#[test]
fn cart_pole_swing_up_reaches_the_top() {
    let path = swing_up(&least_effort(CartPole::default()), 2.0).unwrap();
    let (worst, v_end) = replay(&path, &[0.0, 0.0]);
    println!(
        "swing-up: cost {:.6}, {} Newton iterations, largest |u| {:.3}; replay within {worst:.1e}, end \
         velocity {v_end:.1e}",
        path.cost,
        path.newton.iterations,
        path.u.iter().map(|u| u[0].abs()).fold(0.0, f64::max)
    );
    assert!(worst < 1e-13 && v_end < 1e-12, "{worst:e} {v_end:e}");
}

/// The discrete optimum converges to the continuous one at the midpoint rule's second order: the
/// cost differences between N = 50, 100, 200 shrink by 2² = 4 (measured order 2.015, and 2.004 from
/// N = 100 on: the remainder is the next term of the error, O(h²) relative to the first).
#[test]
fn cart_transfer_converges_at_second_order() {
    let costs: Vec<f64> = [50, 100, 200].iter().map(|&n| cart_transfer(n).cost).collect();
    let order = ((costs[0] - costs[1]) / (costs[1] - costs[2])).log2();
    println!("cart transfer costs {costs:?}: observed order {order:.4}");
    assert!((order - 2.0).abs() < 0.03, "{order}");
}

/// The trapezoidal rule (its own L_d, input forces at both ends of a step) is a different second-order
/// discretisation of the same problem: its optimal costs converge to the same continuous optimum.
/// Richardson's extrapolation (4J(2N) − J(N))/3 of each removes the h² terms, and the two
/// extrapolations agree to the remaining O(h⁴): measured 8.9e-7 relative from N = 100, 200 (and 1.4e-5
/// from N = 50, 100: a factor 16 = 2⁴), against a difference of 3.7e-4 between the rules at N = 200.
#[test]
fn trapezoidal_and_midpoint_transfers_share_their_limit() {
    let richardson = |coarse: f64, fine: f64| (4.0 * fine - coarse) / 3.0;
    let mid = [cart_transfer(100).cost, cart_transfer(200).cost];
    let trap = [100, 200].map(|n| transfer_by(Trapezoidal::new(CartPole::default()), n).cost);
    let (a, b) = (richardson(mid[0], mid[1]), richardson(trap[0], trap[1]));
    let agree = (a - b).abs() / a;
    println!(
        "transfer: midpoint {mid:?}, trapezoidal {trap:?}; extrapolated {a:.10} and {b:.10}, relative {agree:.1e}"
    );
    assert!(agree < 3e-6, "{agree:e}");
    assert!(
        (mid[1] - trap[1]).abs() / a > 1e-4,
        "the rules should differ at N = 200"
    );
}

#[test]
fn bad_input_is_refused_with_its_data() {
    let problem = least_effort(DoubleIntegrator);
    let (start, end) = ((&[0.0][..], &[0.0][..]), (&[1.0][..], &[0.0][..]));
    assert!(matches!(
        problem.solve(0.0, start, 1.0, end, 0),
        Err(Error::InvalidParameter {
            name: "optimal-control steps",
            ..
        })
    ));
    assert!(matches!(
        problem.solve(1.0, start, 1.0, end, 10),
        Err(Error::InvalidParameter { value, .. }) if value == 1.0
    ));
    assert!(matches!(
        problem.solve(0.0, (&[0.0, 0.0], &[0.0]), 1.0, end, 10),
        Err(Error::Dimension {
            expected: 1,
            got: 2,
            ..
        })
    ));
    assert!(matches!(
        problem.solve(0.0, start, 1.0, (&[f64::NAN], &[0.0]), 10),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        problem.solve_from(0.0, start, 1.0, end, &vec![vec![0.0]; 3], &vec![vec![0.0]; 3]),
        Err(Error::Dimension {
            expected: 4,
            got: 3,
            ..
        })
    ));
    let two_weights = OptimalControl::new(
        Midpoint::new(DoubleIntegrator),
        Effort::new(vec![1.0, 1.0]).unwrap(),
    );
    assert!(matches!(
        two_weights.solve(0.0, start, 1.0, end, 10),
        Err(Error::Dimension {
            expected: 1,
            got: 2,
            ..
        })
    ));
    assert!(matches!(
        problem.solve(f64::NAN, start, 1.0, end, 10),
        Err(Error::InvalidParameter {
            name: "optimal-control start time t₀",
            ..
        })
    ));
    assert!(matches!(
        Effort::new(vec![1.0, -2.0]),
        Err(Error::InvalidParameter { value, .. }) if value == -2.0
    ));
}

/// A rest-to-rest slew of the reaction-wheel spacecraft (`testkit::control::ReactionWheel`: J = 12,
/// I_w = 0.4) by Θ = 1 in T = 10, the wheel's end angle left free. The body angle θ is cyclic and
/// unforced, so the discrete equations conserve p_θ (Σ_k c_k^θ = p₀ − p_N whatever the path: one
/// equation is implied by the others, which the solver finds and drops). J θ̈ = −u makes the body a
/// double integrator driven by −u/J, and the midpoint rule is exact for this quadratic L with
/// piecewise-constant u, so the double integrator's discrete closed form carries over scaled:
///
///   u_k = −J Θ u₁(t_k + h/2)/(1 − (h/T)²),   J_d = 12 J² Θ²/(T(T² − h²)),
///
/// u₁(t) = (6/T²)(1 − 2t/T), and the conserved momentum (J + I_w)θ + I_w α = 0 puts the free wheel at
/// α_N = −(J + I_w)Θ/I_w = −31. All three are met to rounding (measured 1.2e-15, 0 and 1.3e-14
/// relative; bound 1e-13). (Fixing the wheel's end at −31 instead is singular: with constant inertias
/// the conserved momentum integrates to (J + I_w)θ + I_w α = const, so a second equation, a weighted
/// sum of the c_k^θ, is implied by the ends — the wheel's end is the free one.)
#[test]
fn reaction_wheel_slew_meets_its_closed_form() {
    let wheel = ReactionWheel::default();
    let (t_end, steps, angle) = (10.0, 50, 1.0);
    let h = t_end / steps as f64;
    let rest = [0.0, 0.0];
    let problem = || least_effort(wheel);
    let free = problem()
        .free_end_positions(&[1])
        .unwrap()
        .solve(0.0, (&rest, &rest), t_end, (&[angle, 0.0], &rest), steps)
        .unwrap();
    let cost = 12.0 * (wheel.body * angle).powi(2) / (t_end * (t_end * t_end - h * h));
    let alpha = -(wheel.body + wheel.wheel) * angle / wheel.wheel;
    let shrink = 1.0 - (h / t_end).powi(2);
    let input_error = free
        .u
        .iter()
        .enumerate()
        .map(|(k, u)| {
            let t = (k as f64 + 0.5) * h;
            let exact = -wheel.body * angle * 6.0 / (t_end * t_end) * (1.0 - 2.0 * t / t_end) / shrink;
            (u[0] - exact).abs() / exact.abs().max(1e-300)
        })
        .fold(0.0, f64::max);
    println!(
        "slew: cost {} vs {cost} ({:.1e}), wheel end {} vs {alpha}, inputs within {input_error:.1e} \
         relative, {} Newton iterations",
        free.cost,
        (free.cost - cost).abs() / cost,
        free.q[steps][1],
        free.newton.iterations
    );
    assert!((free.cost - cost).abs() < 1e-13 * cost);
    assert!((free.q[steps][1] - alpha).abs() < 1e-13 * alpha.abs());
    assert!(input_error < 1e-13, "{input_error:e}");
}

/// The ends may not ask a conserved momentum to change: the slew ending with the body turning at
/// θ̇ = 0.1 and the wheel at rest relative to it needs p_θ = (J + I_w)·0.1 = 1.24 from 0, which no
/// internal torque gives — refused with the change. A free end position the end momenta depend on,
/// and a free end component out of range or repeated, are refused too.
#[test]
fn a_conserved_momentum_cannot_change() {
    let wheel = ReactionWheel::default();
    let problem = || least_effort(wheel);
    let err = problem()
        .solve(
            0.0,
            (&[0.0, 0.0], &[0.0, 0.0]),
            10.0,
            (&[1.0, -31.0], &[0.1, 0.0]),
            50,
        )
        .unwrap_err();
    match err {
        Error::InvalidParameter { value, .. } => {
            assert!(
                (value - (wheel.body + wheel.wheel) * 0.1).abs() < 1e-14,
                "{value}"
            )
        }
        other => panic!("{other:?}"),
    }
    // A free end position on which the end momenta depend: the cart-pole's pole angle left free with
    // the cart moving at the end (p_θ = m l ẋ cos θ + m l² θ̇ changes with θ) is refused after the
    // solve, as the momenta were taken at the given θ_N.
    let moving = least_effort(CartPole::default())
        .free_end_positions(&[1])
        .unwrap()
        .solve(0.0, (&[0.0, PI], &[0.0, 0.0]), 2.0, (&[1.0, PI], &[0.5, 0.0]), 50);
    assert!(matches!(moving, Err(Error::Unsupported(_))), "{moving:?}");
    for components in [&[2][..], &[1, 1][..]] {
        assert!(matches!(
            problem().free_end_positions(components).err(),
            Some(Error::InvalidParameter { .. })
        ));
    }
}
