//! Periodic orbits by shooting (RK4 tangents) against closed forms and published orbits: the pendulum's
//! libration period, the figure-eight choreography of three equal masses, a planar Lyapunov orbit
//! about L1 of the circular restricted three-body problem; and the typed errors.

use noether_analysis::periodic::{Energy, FirstIntegral, Shooting, Stability};
use noether_analysis::Error;
use noether_core::prelude::*;
use noether_testkit::closed_form::elliptic_k_complementary;
use noether_testkit::three_body::{
    self, figure_eight, figure_eight_shooting, l1, l1_guess, l1_linear, Cr3bp, ThreeBody, EIGHT_T, EIGHT_V3,
    EIGHT_X1,
};
use std::f64::consts::PI;

/// Pendulum H = p²/2 − g cos q (m = l = 1).
#[derive(Debug, Clone, Copy)]
struct Pendulum {
    g: f64,
}

impl Hamiltonian for Pendulum {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        p[0] * p[0] * 0.5 - q[0].cos() * self.g
    }
}

/// Libration of amplitude θ₀ at the energy E = −g cos θ₀, from a guess 5 % short of the turning
/// point and the small-amplitude period corrected to O(θ₀²). Closed form (the quarter period as an
/// integral over the swing, substituted sin(θ/2) = k sin φ): T = 4 sqrt(l/g) K(sin(θ₀/2)).
#[test]
fn closed_form_pendulum_libration_period() {
    let g: f64 = 9.81;
    // Tolerances: RK4's O(h⁴) period error with h = T/2000, measured 1.55e-12, 1.68e-12, 1.02e-11
    // (with h/2: 5.8e-14, 1.0e-13, 6.7e-13, the factor 16-27 of fourth order).
    for (theta0, tol) in [(0.5_f64, 2e-12), (1.5, 2.5e-12), (2.5, 1.5e-11)] {
        let exact = 4.0 / g.sqrt() * elliptic_k_complementary((0.5 * theta0).cos());
        let rk4 = Rk4::new(HamiltonEquations::new(Pendulum { g }));
        let mut shooting = Shooting::new(rk4, 2000)
            .unwrap()
            .level(Energy(Pendulum { g }), -g * theta0.cos());
        let guess_t = 2.0 * PI / g.sqrt() * (1.0 + theta0 * theta0 / 16.0);
        let orbit = shooting
            .solve(&State::with_momenta(0.0, [0.95 * theta0], [0.0]), guess_t)
            .unwrap();
        let err = (orbit.period - exact).abs();
        println!(
            "θ₀ = {theta0}: T = {:.15} exact {exact:.15} err {err:.2e}; q₀ − θ₀ = {:.2e}, p₀ = {:.2e}, closure {:.2e}, \
             λ = {:.2e}, Newton {:?}, multipliers {:?}",
            orbit.period,
            orbit.initial.q[0] - theta0,
            orbit.initial.v[0],
            orbit.closure,
            orbit.unfolding[0],
            orbit.newton,
            orbit.floquet.multipliers
        );
        assert!(err < tol, "θ₀ = {theta0}: period error {err:e}");
        // The phase plane ⟂ F(guess) = (0, −g sin) is p = 0: the orbit starts at the turning point.
        assert!(orbit.initial.v[0].abs() < 1e-12);
        assert!((orbit.initial.q[0] - theta0).abs() < 1e-12);
        // One degree of freedom: both multipliers are the trivial pair.
        assert_eq!(orbit.floquet.trivial, 2);
        assert_eq!(orbit.floquet.stability, Stability::Marginal);
    }
}

/// The figure-eight choreography (Chenciner & Montgomery, Ann. Math. 152, 2000), found from a rough
/// guess (the published values rounded to three digits, the period to 6.33) at the published energy,
/// and compared with the published initial conditions and period (Simó 2002; Moore 1993):
/// x₁ = −x₂ = (0.97000436, −0.24308753), x₃ = 0, v₃ = −2v₁ = −2v₂ = (−0.93240737, −0.86473146),
/// T = 6.32591398.
///
/// Symmetries: translations (2) and rotations (1) each get a phase condition, momentum (2) and angular
/// momentum (1) an unfolding parameter, the energy a fixed level; the time phase is x₃ = 0 (body 3 at
/// the centre of mass, where the published values are given). The found orbit is rotated so that x₁
/// points along the published direction before the comparison.
///
/// Measured: from the two-digit guess x₁ = (0.97, −0.24), v₃ = (−0.93, −0.86) Newton converges
/// instead (for any period guess 6.30-6.35, either phase condition) to another periodic orbit at the
/// same energy, 0.019 away, with T = 6.3259150 and a real multiplier pair 1.096, 0.912: a hyperbolic
/// orbit next to the eight, whose own basin is correspondingly small in that direction.
#[test]
fn published_figure_eight() {
    let published = figure_eight(EIGHT_X1, EIGHT_V3);
    let t_published = EIGHT_T;
    let energy = Energy(ThreeBody);
    let e0 = energy
        .value(published.q.as_slice(), published.v.as_slice())
        .unwrap();
    let guess = figure_eight([0.97, -0.243], [-0.932, -0.865]);
    let rk4 = Rk4::new(HamiltonEquations::new(ThreeBody));
    let mut shooting = figure_eight_shooting(Shooting::new(rk4, 4000).unwrap(), &guess, e0);
    let orbit = shooting.solve(&guess, 6.33).unwrap();
    // Rotate the solution so that x₁ lies along the published x₁.
    let angle = published.q[1].atan2(published.q[0]) - orbit.initial.q[1].atan2(orbit.initial.q[0]);
    let (c, s) = (angle.cos(), angle.sin());
    let rot = |v: &nalgebra::DVector<f64>| -> Vec<f64> {
        (0..3)
            .flat_map(|i| [c * v[2 * i] - s * v[2 * i + 1], s * v[2 * i] + c * v[2 * i + 1]])
            .collect()
    };
    let (q, p) = (rot(&orbit.initial.q), rot(&orbit.initial.v));
    let dev = q
        .iter()
        .zip(published.q.iter())
        .chain(p.iter().zip(published.v.iter()))
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    let dt = (orbit.period - t_published).abs();
    let circle = orbit
        .floquet
        .nontrivial()
        .iter()
        .fold(0.0_f64, |m, z| m.max((z.norm() - 1.0).abs()));
    println!(
        "figure-eight: T = {:.12} (published {t_published}, diff {dt:.2e}); max IC deviation {dev:.2e}, \
         rotation {angle:.2e}; closure {:.2e}, λ = {:?}, Newton {:?}; trivial multipliers within {:.2e} of 1, \
         the others within {circle:.2e} of the unit circle, arguments {:?}",
        orbit.period,
        orbit.closure,
        orbit.unfolding,
        orbit.newton,
        orbit.floquet.trivial_deviation,
        orbit.floquet.nontrivial().iter().map(|z| z.arg()).collect::<Vec<_>>()
    );
    // The published values carry 8 decimals (±5e-9); measured 1.9e-9.
    assert!(dev < 5e-9, "initial conditions off by {dev:e}");
    // The period at the energy of the 8-decimal initial conditions: their rounding moves E by up to
    // ~1e-8, and T ∝ |E|^(−3/2) by (3/2)·T·δE/|E| ≈ 7e-8; RK4's own error (h = T/4000) is ~1e-11.
    // Measured 3.1e-8.
    assert!(dt < 4e-8, "period off by {dt:e}");
    assert_eq!(orbit.floquet.trivial, 8);
    assert_eq!(orbit.floquet.stability, Stability::Marginal);
    // Linearly stable (Simó): the four non-trivial multipliers on the unit circle, up to RK4's
    // non-symplecticity over one period (h⁴T ≈ 4e-11); measured 3e-12.
    assert!(
        circle < 2e-11,
        "non-trivial multipliers off the unit circle by {circle:e}"
    );
}

/// max |H − e| along the orbit of the restricted problem, each arc stepped by RK4 with the orbit's
/// own steps.
fn energy_drift(mu: f64, orbit: &noether_analysis::PeriodicOrbit<Momenta>, e: f64) -> f64 {
    let mut rk = Rk4::new(HamiltonEquations::new(Cr3bp { mu }));
    let run = (orbit.period, orbit.steps);
    three_body::energy_drift(&Cr3bp { mu }, &mut rk, &orbit.nodes, run, e).unwrap()
}

/// Planar Lyapunov orbits about L1 of the Earth-Moon system (μ = 0.01215), amplitudes 0.001 to 0.005
/// (380 to 1900 km). The linearisation
/// x = x_L − A cos ωt, y = k A sin ωt (ω² = (2 − c₂ + sqrt(9c₂² − 8c₂))/2, k = (ω² + 1 + 2c₂)/(2ω),
/// c₂ = (1 − μ)/r₁³ + μ/r₂³ at L1; Richardson 1980) is the first guess at A = 0.001, each larger
/// amplitude (×1.5) starts from the secant through the last two orbits (the first from the last one
/// scaled about L1). Single shooting over a whole period multiplies a guess error by the saddle's
/// e^{λ_s T} ≈ 2700 and its square in the second-order terms, so Newton's basin is tiny: measured, the
/// continuation fails at A ≈ 0.0076 even from the secant guess (without a line search, as here; with
/// one, and with multiple shooting, the family goes on: `lyapunov_family_by_multiple_shooting`). Each orbit is held at the Jacobi constant of its linear
/// guess. Checks: it closes, its Jacobi constant C = −2H is the one asked for and conserved along the
/// orbit to RK4's accuracy, it is unstable with a real pair λ, 1/λ ≫ 1 of product 1 (symplectic), and
/// as A → 0 its period tends to the linear 2π/ω as T₀ + cA² (the differences shrink by 4 per halving).
#[test]
fn lyapunov_orbits_about_l1() {
    let mu = 0.01215;
    let (xl, c2) = l1(mu);
    let (omega, k) = l1_linear(c2);
    let lambda_s = ((c2 - 2.0 + (9.0 * c2 * c2 - 8.0 * c2).sqrt()) / 2.0).sqrt();
    let t0 = 2.0 * PI / omega;
    let energy = Energy(Cr3bp { mu });
    let mut periods = Vec::new();
    let mut last: Option<(f64, State<Momenta>, f64)> = None;
    let mut before: Option<(f64, State<Momenta>, f64)> = None;
    let mut amplitude = 0.001;
    while amplitude < 0.006 {
        let (guess, t_guess) = l1_guess((xl, omega, k, t0), amplitude, &last, &before);
        let e = energy.value(guess.q.as_slice(), guess.v.as_slice()).unwrap();
        let rk4 = Rk4::new(HamiltonEquations::new(Cr3bp { mu }));
        let mut shooting = Shooting::new(rk4, 4000)
            .unwrap()
            .level(energy, e)
            .newton(noether_core::Newton::default().reuse_jacobian(false));
        let orbit = shooting.solve(&guess, t_guess).unwrap();
        let fl = &orbit.floquet;
        let (big, small) = (fl.nontrivial()[0], fl.nontrivial()[1]);
        // Jacobi constant along the orbit (RK4, the same steps): C = −2H.
        let drift = 2.0 * energy_drift(mu, &orbit, e);
        let c0 = -2.0
            * energy
                .value(orbit.initial.q.as_slice(), orbit.initial.v.as_slice())
                .unwrap();
        println!(
            "A = {amplitude}: T = {:.12} (linear {t0:.12}), C = {c0:.15} (asked {:.15}), C drift {drift:.2e}, \
             closure {:.2e}, λ_H = {:.2e}, Newton {:?}, x₀ − x_L = {:.6}, multipliers {:.3} and {:.3e} \
             (product − 1 = {:.2e}; e^(λ_s T) = {:.1}), trivial within {:.2e}, {:?}",
            orbit.period,
            -2.0 * e,
            orbit.closure,
            orbit.unfolding[0],
            orbit.newton,
            orbit.initial.q[0] - xl,
            big,
            small,
            (big * small).norm() - 1.0,
            (lambda_s * orbit.period).exp(),
            fl.trivial_deviation,
            fl.stability
        );
        // Closes to the rounding of 4000 steps: measured ≤ 9.6e-13.
        assert!(orbit.closure < 2e-12, "closure {:e}", orbit.closure);
        // C is the one asked for (an equation of the system, solved to rounding): measured ≤ 4.4e-16.
        assert!((c0 + 2.0 * e).abs() < 2e-15);
        // Conserved along the discrete orbit to RK4's error at h = T/4000 on these small orbits:
        // measured ≤ 1.3e-15.
        assert!(drift < 5e-15, "Jacobi constant drift {drift:e}");
        assert_eq!(fl.stability, Stability::Unstable);
        assert!(big.im == 0.0 && small.im == 0.0 && big.re > 1000.0);
        // λ · (1/λ) = 1 (M symplectic; RK4's defect is O(h⁴T) ~ 1e-13): limited by the small one's
        // rounding, ε‖M‖/|μ| ≈ 2e-16 · 2700 / 3.7e-4 ≈ 1.5e-9; measured ≤ 6.2e-9.
        assert!(((big * small).norm() - 1.0).abs() < 1e-8);
        periods.push((amplitude, orbit.period));
        before = last.replace((amplitude, orbit.initial.clone(), orbit.period));
        amplitude *= 1.5;
    }
    // T − T₀ = cA²(1 + O(A²)): the ratio over a step A → 1.5 A is 2.25 (1 + O(A²)); measured
    // 2.2513, 2.2523, 2.2543, 2.2582 (the drift is the O(A²) term).
    for w in periods.windows(2) {
        let ratio = (w[1].1 - t0) / (w[0].1 - t0);
        println!("A = {}: (T − T₀) ratio {ratio:.5}", w[1].0);
        assert!((ratio - 2.25).abs() < 0.01, "ratio {ratio}");
    }
}

/// The L1 Lyapunov family by multiple shooting, far past the amplitude where single shooting fails.
/// Single shooting over a whole period multiplies a guess error by e^{λ_s T} ≈ 2700; multiple
/// shooting cuts the period into 10 arcs, each growing an error by only e^{λ_s T/10} ≈ 2.2, and each
/// member of the family starts from the secant through the last two members' nodes (every node
/// extrapolated, not one state run through the unstable flow). RK4 with 4000 steps a period, Newton with
/// its line search, A from 0.001 by factors 1.5 to 0.038 (15 000 km; T from 2.69 to 3.12, C from 3.188
/// to 3.100). Single shooting from the same secant guess of y₀ (with the line search too) is tried at
/// every amplitude: measured, it fails (a typed `ShootingDiverged`) at A = 0.0114, 0.0256 and 0.0384,
/// where multiple shooting takes 3–4 iterations. Checks per orbit: the segments join (continuity
/// defects, measured ≤ 7e-15: rounding of 400-step arcs; checked to 1e-13), the Jacobi constant is the
/// one asked for (measured ≤ 2e-16; 1e-15) and conserved along the orbit to RK4's error (measured ≤
/// 2.9e-14, growing with the orbit; 1e-13), the orbit is unstable with a real pair λ, 1/λ (λ from 2674
/// down to 1115) of product 1 (the monodromy, the product of the segments' Jacobians, is symplectic to
/// RK4's defect and the small one's rounding: measured ≤ 1.7e-9; 1e-8), and along the family T grows
/// and C falls.
#[test]
fn lyapunov_family_by_multiple_shooting() {
    let mu = 0.01215;
    let (xl, c2) = l1(mu);
    let (omega, k) = l1_linear(c2);
    let t0 = 2.0 * PI / omega;
    let energy = Energy(Cr3bp { mu });
    let shooting = |segments: usize, e: f64| {
        Shooting::new(Rk4::new(HamiltonEquations::new(Cr3bp { mu })), 4000)
            .unwrap()
            .segments(segments)
            .unwrap()
            .newton(
                noether_core::Newton::default()
                    .residual_tolerance(1e-14)
                    .unwrap()
                    .line_search(true),
            )
            .level(Energy(Cr3bp { mu }), e)
    };
    type Member = (f64, Vec<State<Momenta>>, f64);
    let (mut last, mut before): (Option<Member>, Option<Member>) = (None, None);
    let mut family: Vec<(f64, f64, f64)> = Vec::new();
    let mut single_fails_from: Option<f64> = None;
    let mut amplitude = 0.001;
    while amplitude < 0.05 {
        // The secant guess of every node (the linearisation when there is no member yet).
        let node = |j: usize| {
            let pick = |m: &Option<Member>| m.as_ref().map(|(a, nodes, t)| (*a, nodes[j].clone(), *t));
            l1_guess((xl, omega, k, t0), amplitude, &pick(&last), &pick(&before))
        };
        let (guess, t_guess) = node(0);
        let e = energy.value(guess.q.as_slice(), guess.v.as_slice()).unwrap();
        let single = shooting(1, e).solve(&guess, t_guess);
        if single.is_err() && single_fails_from.is_none() {
            println!(
                "single shooting fails at A = {amplitude}: {:?}",
                single.as_ref().err()
            );
            single_fails_from = Some(amplitude);
        }
        let mut multiple = shooting(10, e);
        let orbit = match &last {
            None => multiple.solve(&guess, t_guess),
            Some(_) => multiple.solve_nodes(&(0..10).map(|j| node(j).0).collect::<Vec<_>>(), t_guess),
        }
        .unwrap();
        let fl = &orbit.floquet;
        let (big, small) = (fl.nontrivial()[0], fl.nontrivial()[1]);
        let drift = energy_drift(mu, &orbit, e);
        let level = energy
            .value(orbit.initial.q.as_slice(), orbit.initial.v.as_slice())
            .unwrap()
            - e;
        println!(
            "A = {amplitude:.5}: T = {:.10}, C = {:.12}, defects {:.1e}, level {level:.1e}, H drift {drift:.1e}, \
             Newton {}/{:.1e}, multipliers {:.1} · {:.3e} − 1 = {:.1e}, trivial within {:.1e}, single {}",
            orbit.period,
            -2.0 * e,
            orbit.closure,
            orbit.newton.iterations,
            orbit.newton.residual,
            big.re,
            small.re,
            (big * small).norm() - 1.0,
            fl.trivial_deviation,
            if single.is_ok() { "ok" } else { "failed" }
        );
        assert_eq!(orbit.nodes.len(), 10);
        assert!(orbit.closure < 1e-13, "defects {:e}", orbit.closure);
        assert!(level.abs() < 1e-15);
        assert!(drift < 1e-13, "H drift {drift:e}");
        assert_eq!(fl.stability, Stability::Unstable);
        assert!(big.im == 0.0 && small.im == 0.0 && big.re > 1000.0);
        assert!(((big * small).norm() - 1.0).abs() < 1e-8);
        family.push((amplitude, orbit.period, -2.0 * e));
        before = last.replace((amplitude, orbit.nodes.clone(), orbit.period));
        amplitude *= 1.5;
    }
    println!("single shooting fails from A = {single_fails_from:?}");
    assert!(single_fails_from.is_some_and(|a| a < 0.03));
    assert_eq!(family.len(), 10);
    for w in family.windows(2) {
        assert!(
            w[1].1 > w[0].1 && w[1].2 < w[0].2,
            "T and C along the family: {w:?}"
        );
    }
}

/// Typed errors: a bad period, an equilibrium as guess, unbalanced declarations, no convergence.
#[test]
fn errors_are_typed() {
    let g = 9.81;
    let rk4 = || Rk4::new(HamiltonEquations::new(Pendulum { g }));
    let mut shooting = Shooting::new(rk4(), 100)
        .unwrap()
        .level(Energy(Pendulum { g }), -g * 0.5f64.cos());
    let guess = State::with_momenta(0.0, [0.5], [0.0]);
    assert!(matches!(
        shooting.solve(&guess, -1.0),
        Err(Error::InvalidPeriod { .. })
    ));
    assert!(matches!(
        shooting.solve(&guess, f64::NAN),
        Err(Error::InvalidPeriod { .. })
    ));
    let rest = State::with_momenta(0.0, [0.0], [0.0]);
    assert!(matches!(
        shooting.solve(&rest, 2.0),
        Err(Error::Equilibrium { .. })
    ));
    // Multiple shooting: between 1 and N segments, one node per segment.
    assert!(Shooting::new(rk4(), 100).unwrap().segments(0).is_err());
    assert!(Shooting::new(rk4(), 100).unwrap().segments(101).is_err());
    let mut four = Shooting::new(rk4(), 100)
        .unwrap()
        .segments(4)
        .unwrap()
        .level(Energy(Pendulum { g }), -g * 0.5f64.cos());
    assert!(matches!(
        four.solve_nodes(&[guess.clone(), guess.clone()], 2.0),
        Err(Error::Core(noether_core::Error::Dimension {
            expected: 4,
            got: 2,
            ..
        }))
    ));
    // And it finds the same orbit of the same discrete map as single shooting (the same 100 steps of
    // h = T/100): period, start and closure (here the unfolding's O(h⁴) share, 2e-8), to Newton's
    // residual tolerance (1e-12; the closures differ by 1e-13, through the unfolding parameter).
    let orbit = four.solve(&guess, 2.0).unwrap();
    let one = shooting.solve(&guess, 2.0).unwrap();
    assert_eq!(orbit.nodes.len(), 4);
    assert!((orbit.period - one.period).abs() < 1e-12);
    assert!((orbit.initial.q[0] - one.initial.q[0]).abs() < 1e-12);
    assert!((orbit.closure - one.closure).abs() < 1e-12);
    // An energy level and the fixed period: one equation too many.
    let mut over = Shooting::new(rk4(), 100)
        .unwrap()
        .level(Energy(Pendulum { g }), -g * 0.5f64.cos())
        .fixed_period();
    assert!(matches!(
        over.solve(&guess, 2.0),
        Err(Error::ShootingSetup {
            unknowns: 3,
            equations: 4
        })
    ));
    // A Hamiltonian orbit without its integral declared: RK4's non-conservation breaks the family, and
    // Newton goes to the rest point inside it (measured: q₀ = −5e-14 after a few iterations).
    let mut bare = Shooting::new(rk4(), 100).unwrap();
    let err = bare.solve(&guess, 2.0).unwrap_err();
    println!("undeclared energy: {err}");
    assert!(
        matches!(
            err,
            Error::Equilibrium { .. } | Error::DegenerateOrbit { .. } | Error::ShootingDiverged { .. }
        ),
        "{err:?}"
    );
    // Two iterations from far away: no convergence, with the count and the residual.
    let mut capped = Shooting::new(rk4(), 100)
        .unwrap()
        .level(Energy(Pendulum { g }), -g * 2.5f64.cos())
        .newton(noether_core::Newton::default().max_iterations(2).unwrap());
    match capped.solve(&guess, 2.0) {
        Err(Error::ShootingDiverged {
            iterations, residual, ..
        }) => {
            assert_eq!(iterations, 2);
            assert!(residual > 1e-6);
        }
        other => panic!("{other:?}"),
    }
    assert!(Shooting::new(rk4(), 0).is_err());
}

/// The pendulum's libration family by pseudo-arclength continuation in the energy (g = l = 1, RK4 with
/// 4000 steps a period in 4 arcs), from amplitude 0.5 for 40 members, to near the separatrix (E → g,
/// T → ∞): every member's period against the closed form T(θ₀) = 4√(l/g) K(sin(θ₀/2)),
/// θ₀ = arccos(−E/g) (the quarter period as an integral over the swing; Landau & Lifshitz §11
/// problem 1; K by Gauss's AGM from k′ = cos(θ₀/2), exact near k = 1). Measured: the family reaches
/// E = 0.993 (θ₀ = 3.023, T = 16.9) with the step growing to its cap, periods within 1.4e-11 relative
/// (RK4's O(h⁴) at h ≤ 0.0042 and Newton's residual tolerance 1e-12 magnified by ∂T/∂E ~ 1/(1 − E)
/// near the separatrix; checked to 1e-10), |H(y₀) − E| ≤ 1.3e-13 (Newton's tolerance 1e-12 on the
/// level row; checked to it), T increasing along the family. And the typed end of a continuation that
/// cannot go on (a corrector allowed one Newton iteration does not converge from a predictor 0.1 or 0.05
/// away: the step halves below its floor 0.05), and a continuation without a level to follow.
#[test]
fn pendulum_family_by_continuation() {
    let g = 1.0;
    let level = |theta: f64| -g * theta.cos();
    let shooting = || {
        Shooting::new(Rk4::new(HamiltonEquations::new(Pendulum { g })), 4000)
            .unwrap()
            .segments(4)
            .unwrap()
            .level(Energy(Pendulum { g }), level(0.5))
    };
    let mut pendulum = shooting();
    let start = pendulum
        .solve(&State::with_momenta(0.0, [0.5], [0.0]), 6.4)
        .unwrap();
    let continuation = noether_analysis::Continuation::new(0.1, 1e-4, 1.0).unwrap();
    let branch = continuation
        .follow(&mut pendulum, &start, level(0.5), 40, true)
        .unwrap();
    // One degree of freedom: no multipliers beyond the trivial pair, and E rises monotonically.
    assert!(branch.special.is_empty());
    let family = branch.members;
    let (mut worst, mut worst_level) = (0.0_f64, 0.0_f64);
    let mut last_t = start.period;
    for (e, orbit) in &family {
        let theta0 = (-e / g).acos();
        let exact = 4.0 * elliptic_k_complementary((0.5 * theta0).cos()) / g.sqrt();
        let rel = (orbit.period - exact).abs() / exact;
        let h0 = Energy(Pendulum { g })
            .value(orbit.initial.q.as_slice(), orbit.initial.v.as_slice())
            .unwrap();
        println!(
            "E = {e:.6}: θ₀ = {theta0:.5}, T = {:.10} (closed form {exact:.10}, relative {rel:.1e}), \
             H(y₀) − E = {:.1e}, Newton {}",
            orbit.period,
            h0 - e,
            orbit.newton.iterations
        );
        worst = worst.max(rel);
        worst_level = worst_level.max((h0 - e).abs());
        assert!(orbit.period > last_t);
        last_t = orbit.period;
    }
    println!("worst relative period error {worst:e}, worst level {worst_level:e}");
    assert!(family.last().is_some_and(|(e, _)| *e > 0.99));
    assert!(worst < 1e-10);
    assert!(worst_level < 1e-12);

    let mut stubborn = shooting().newton(noether_core::Newton::default().max_iterations(1).unwrap());
    let start = shooting()
        .solve(&State::with_momenta(0.0, [0.5], [0.0]), 6.4)
        .unwrap();
    let coarse = noether_analysis::Continuation::new(0.1, 0.05, 1.0).unwrap();
    assert!(matches!(
        coarse.follow(&mut stubborn, &start, level(0.5), 3, true),
        Err(Error::BranchLost { .. })
    ));
    // A family lost after some members keeps them: a corrector allowed three Newton iterations
    // finds the first members, and stops where the growing step needs more than three and the
    // halved one falls below the floor.
    let mut hasty = shooting().newton(noether_core::Newton::default().max_iterations(3).unwrap());
    let short = noether_analysis::Continuation::new(0.1, 0.1, 1.0)
        .unwrap()
        .follow(&mut hasty, &start, level(0.5), 40, true)
        .unwrap();
    println!(
        "three Newton iterations: {} members, lost: {:?}",
        short.members.len(),
        short.lost
    );
    assert!(!short.members.is_empty() && short.members.len() < 40);
    assert!(matches!(short.lost, Some(Error::BranchLost { .. })));
    let mut free = Shooting::new(Rk4::new(HamiltonEquations::new(Pendulum { g })), 400)
        .unwrap()
        .unfold(Energy(Pendulum { g }))
        .fixed_period();
    assert!(continuation
        .follow(&mut free, &start, level(0.5), 3, true)
        .is_err());
    assert!(noether_analysis::Continuation::new(0.1, 1.0, 0.5).is_err());
}

/// The Earth-Moon L1 Lyapunov family by pseudo-arclength continuation in the energy (Jacobi constant
/// C = −2H falling), from the orbit of amplitude 0.001 for 45 members: 10 arcs of RK4, 4000 steps a
/// period. Measured: C from 3.188 to 2.933 (x₀ − x_L to −0.150, 58 000 km; T from 2.69 to 6.05), far
/// past where single shooting fails (C ≈ 3.18, `lyapunov_family_by_multiple_shooting`), 2–10 corrector
/// iterations a member, 7 s. Checks over the family: the level is the continuation's (measured 2.7e-14;
/// checked to Newton's tolerance 1e-12); RK4's own errors, which grow as the orbits reach towards the
/// Moon (h = T/4000 grows with T, and the Moon's pull with it): H conserved along each orbit to 1.9e-8,
/// the arcs joining but for the unfolding term λ∇H that absorbs that non-conservation (7.0e-9), the
/// multipliers' product 1 to 1.4e-6 (RK4's monodromy is symplectic only to O(h⁴)) — checked to 3× these;
/// every member unstable with a real pair; along the family C falls and T grows.
#[test]
fn lyapunov_family_by_arclength() {
    let mu = 0.01215;
    let (xl, c2) = l1(mu);
    let (omega, k) = l1_linear(c2);
    let t0 = 2.0 * PI / omega;
    let (guess, t_guess) = l1_guess((xl, omega, k, t0), 0.001, &None, &None);
    let energy = Energy(Cr3bp { mu });
    let e = energy.value(guess.q.as_slice(), guess.v.as_slice()).unwrap();
    let mut shooting = Shooting::new(Rk4::new(HamiltonEquations::new(Cr3bp { mu })), 4000)
        .unwrap()
        .segments(10)
        .unwrap()
        .level(Energy(Cr3bp { mu }), e);
    let start = shooting.solve(&guess, t_guess).unwrap();
    let continuation = noether_analysis::Continuation::new(0.01, 1e-5, 0.1).unwrap();
    let branch = continuation.follow(&mut shooting, &start, e, 45, true).unwrap();
    // In the plane the non-trivial pair stays real and positive, C falls throughout: no bifurcation.
    assert!(branch.special.is_empty());
    let family = branch.members;
    let (mut defect, mut level, mut drift, mut pair) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    let (mut last_c, mut last_t) = (-2.0 * e, start.period);
    for (h, orbit) in &family {
        let fl = &orbit.floquet;
        let (big, small) = (fl.nontrivial()[0], fl.nontrivial()[1]);
        let c = -2.0 * h;
        defect = defect.max(orbit.closure);
        level = level.max(
            (energy
                .value(orbit.initial.q.as_slice(), orbit.initial.v.as_slice())
                .unwrap()
                - h)
                .abs(),
        );
        drift = drift.max(energy_drift(mu, orbit, *h));
        pair = pair.max(((big * small).norm() - 1.0).abs());
        assert_eq!(fl.stability, Stability::Unstable);
        assert!(big.im == 0.0 && small.im == 0.0 && big.re > 50.0);
        assert!(
            c < last_c && orbit.period > last_t,
            "C {c} after {last_c}, T {} after {last_t}",
            orbit.period
        );
        (last_c, last_t) = (c, orbit.period);
    }
    let (c_end, end) = (
        family.last().map(|(h, _)| -2.0 * h).unwrap(),
        &family.last().unwrap().1,
    );
    println!(
        "L1 family to C = {c_end:.6}, T = {:.6}, x₀ − x_L = {:.5}: defects {defect:.1e}, level {level:.1e}, \
         H drift {drift:.1e}, pair {pair:.1e}",
        end.period,
        end.initial.q[0] - xl
    );
    assert!(c_end < 2.95);
    assert!(level < 1e-12);
    assert!(drift < 6e-8 && defect < 2e-8 && pair < 4e-6);
}
