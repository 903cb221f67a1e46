//! The exact step Jacobians Ψ = ∂(q₁, p₁)/∂(q₀, p₀) of the variational integrators (implicit-function
//! theorem at the converged solution) against central differences of the step, and the self-checks
//! of `noether_core::selfcheck` on them: symplecticity, observed order, reversibility.

use crate::models::{kepler_start, pendulum_period, Kepler, Pendulum};
use nalgebra::DMatrix;
use noether_core::integrators::{Composition, Weights};
use noether_core::selfcheck::{observed_order, reversibility, symplecticity};
use noether_core::tangent::central_difference;
use noether_core::{Error, Momenta, Scalar, TangentStepper};
use noether_discrete::{
    LocalPotential, Mass, Mechanical, MechanicalMidpoint, Midpoint, Trapezoidal, VariationalIntegrator,
    Verlet,
};

type State = noether_core::State<Momenta>;

/// Relative difference step δ of the reference: Richardson's combination (4 D(δ) − D(2δ))/3 of two
/// central differences cancels their δ² truncation term, leaving O(δ⁴) (≈ 1e-16 × fifth derivatives)
/// and rounding ≈ ε|y|/δ ≈ 1e-12 (times the conditioning of the Newton solve). Plain central
/// differences with δ = 1e-5 agree only to 1.5e-9 near the Kepler pericentre, whose third
/// derivatives are large (r = 0.5).
const FD_REL: f64 = 1e-4;

/// max |Ψ − Ψ_ref| over the entries, Ψ_ref by Richardson-extrapolated central differences, and the
/// check that the tangent step takes the plain step bit for bit.
fn tangent_vs_differences<S: TangentStepper<Partner = Momenta>>(
    stepper: &mut S,
    state: &State,
    h: f64,
) -> f64 {
    let n = stepper.dof();
    let d1 = central_difference(stepper, state, h, FD_REL).unwrap();
    let d2 = central_difference(stepper, state, h, 2.0 * FD_REL).unwrap();
    let reference = (4.0 * d1 - d2) / 3.0;
    let mut psi = DMatrix::zeros(2 * n, 2 * n);
    let mut s = state.clone();
    stepper.step_tangent(&mut s, h, &mut psi).unwrap();
    let mut plain = state.clone();
    stepper.step(&mut plain, h).unwrap();
    assert_eq!(
        (&s.q, &s.v, s.t),
        (&plain.q, &plain.v, plain.t),
        "the tangent step must take the same step"
    );
    (psi - reference).abs().max()
}

/// Kepler states (q, p = q̇) on orbits of eccentricity 0.3 to 0.6, pericentre and off it.
fn kepler_states() -> Vec<State> {
    let mut v = Vec::new();
    for e in [0.3, 0.5, 0.6] {
        let (q, p) = kepler_start(e);
        v.push(State::with_momenta(0.0, q, p));
    }
    v.push(State::with_momenta(0.0, [0.3, -0.8], [0.9, 0.4]));
    v
}

/// Three masses with anharmonic springs k(x) = x²/2 + x⁴/4 between neighbours and between the ends
/// (a dense ∇²V), masses 1, 2, 1.5.
#[derive(Clone)]
struct Anharmonic;
impl LocalPotential for Anharmonic {
    fn dof(&self) -> usize {
        3
    }
    fn terms(&self) -> usize {
        3
    }
    fn support(&self, k: usize, idx: &mut Vec<usize>) {
        idx.extend(match k {
            0 => [0, 1],
            1 => [1, 2],
            _ => [0, 2],
        })
    }
    #[inline]
    fn term<D: Scalar>(&self, _k: usize, x: &[D]) -> D {
        let d = x[1] - x[0] - 1.0;
        d * d * 0.5 + d.powi(4) * 0.25
    }
}

fn anharmonic() -> Mechanical<Anharmonic> {
    Mechanical::new(Mass::Diagonal(vec![1.0, 2.0, 1.5]), Anharmonic).unwrap()
}

fn anharmonic_states() -> Vec<State> {
    vec![
        State::with_momenta(0.0, [0.0, 1.3, 2.1], [0.2, -0.1, 0.3]),
        State::with_momenta(0.0, [0.1, 0.9, 2.4], [-0.5, 0.4, 0.0]),
        State::with_momenta(0.0, [-0.2, 1.0, 1.7], [0.0, 0.0, 0.6]),
    ]
}

#[test]
fn variational_integrator_tangents_match_central_differences() {
    let s = &kepler_states()[1];
    let errs = [
        tangent_vs_differences(&mut VariationalIntegrator::new(Midpoint::new(Kepler)), s, 0.1),
        tangent_vs_differences(&mut VariationalIntegrator::new(Trapezoidal::new(Kepler)), s, 0.1),
        tangent_vs_differences(
            &mut Composition::new(
                VariationalIntegrator::new(Midpoint::new(Kepler)),
                Weights::yoshida4(),
            ),
            s,
            0.1,
        ),
    ];
    eprintln!("VI midpoint, trapezoidal, composition 4 vs differences: {errs:?}");
    // Measured 1.3e-12, 6.1e-13, 3.9e-12: the reference's own rounding (FD_REL).
    for e in errs {
        assert!(e < 1e-11, "|Ψ − Ψ_fd| = {e:e}");
    }
}

#[test]
fn mechanical_tangents_match_central_differences() {
    let s = &anharmonic_states()[0];
    let damped = || anharmonic().damping(vec![0.3, 0.0, 0.1]).unwrap();
    let errs = [
        tangent_vs_differences(&mut MechanicalMidpoint::new(anharmonic()), s, 0.1),
        tangent_vs_differences(&mut Verlet::new(anharmonic()), s, 0.1),
        tangent_vs_differences(&mut MechanicalMidpoint::new(damped()), s, 0.1),
        tangent_vs_differences(&mut Verlet::new(damped()), s, 0.1),
        tangent_vs_differences(
            &mut Composition::new(Verlet::new(anharmonic()), Weights::yoshida4()),
            s,
            0.1,
        ),
    ];
    eprintln!("mechanical midpoint, Verlet, damped midpoint, damped Verlet, composed Verlet vs differences: {errs:?}");
    // Measured 2.7e-12, 1.3e-12, 1.6e-12, 1.9e-12, 4.4e-12: the reference's own rounding (FD_REL).
    for e in errs {
        assert!(e < 1e-11, "|Ψ − Ψ_fd| = {e:e}");
    }
}

#[test]
fn variational_integrators_are_symplectic() {
    let ks = kepler_states();
    let ms = anharmonic_states();
    let defects = [
        symplecticity(&mut VariationalIntegrator::new(Midpoint::new(Kepler)), &ks, 0.1)
            .unwrap()
            .worst,
        symplecticity(
            &mut VariationalIntegrator::new(Trapezoidal::new(Kepler)),
            &ks,
            0.1,
        )
        .unwrap()
        .worst,
        symplecticity(
            &mut Composition::new(
                VariationalIntegrator::new(Midpoint::new(Kepler)),
                Weights::yoshida4(),
            ),
            &ks,
            0.1,
        )
        .unwrap()
        .worst,
        symplecticity(&mut MechanicalMidpoint::new(anharmonic()), &ms, 0.1)
            .unwrap()
            .worst,
        symplecticity(&mut Verlet::new(anharmonic()), &ms, 0.1)
            .unwrap()
            .worst,
        symplecticity(
            &mut Composition::new(Verlet::new(anharmonic()), Weights::yoshida4()),
            &ms,
            0.1,
        )
        .unwrap()
        .worst,
    ];
    eprintln!("symplecticity defects: {defects:?}");
    // Symplectic to rounding: measured 2.2e-16 (five of them) and 6.7e-16 (the composition of VI
    // midpoint steps), a few ε for entries of Ψ of unit size.
    for d in defects {
        assert!(d <= 1e-14, "‖ΨᵀΩΨ − Ω‖_max = {d:e}");
    }
}

#[test]
fn observed_order_and_reversibility_of_the_midpoint_integrator() {
    // Pendulum released from rest at θ₀ = 1: after one period T = 4K(sin(θ₀/2)) it is back at
    // (θ₀, 0) (models::pendulum_period, K by the AGM to rounding).
    let (theta0, t_end) = (1.0, pendulum_period(1.0));
    let start = State::with_momenta(0.0, [theta0], [0.0]);
    let mut vi = VariationalIntegrator::new(Midpoint::new(Pendulum));
    let fit = observed_order(
        &mut vi,
        &start,
        t_end,
        &[50, 100, 200, 400],
        &State::with_momenta(t_end, [theta0], [0.0]),
    )
    .unwrap();
    eprintln!(
        "midpoint VI: order {:.4}, r = {:.9}, {:?}",
        fit.slope, fit.r, fit.points
    );
    // Measured slope 1.9996, r = 1 − 7e-9 (errors 6.0e-3 .. 9.3e-5).
    assert!((fit.slope - 2.0).abs() < 0.01 && fit.r > 0.99999, "{fit:?}");

    let mut vi = VariationalIntegrator::new(Midpoint::new(Kepler));
    let (q, p) = kepler_start(0.5);
    let rev = reversibility(&mut vi, &State::with_momenta(0.0, q, p), 0.1).unwrap();
    eprintln!("midpoint VI round trip: {:e} ({} ulps)", rev.distance, rev.ulps);
    // The midpoint rule is symmetric and Kepler reversible: back to the start to rounding and the
    // Newton tolerance (solved to rounding); measured 0 ulps.
    assert!(rev.ulps <= 4.0, "{rev:?}");
}

/// A forced integrator's tangent includes the derivatives of the discrete forces f±: testkit's damped,
/// driven Duffing oscillator (Q = −cq̇ + F cos ωt) through the midpoint and trapezoidal rules matches
/// Richardson-extrapolated differences of the step.
#[test]
fn forced_variational_tangents_match_central_differences() {
    let osc = noether_testkit::systems::DrivenOscillator::default();
    let s = State::with_momenta(0.3, [0.8], [-0.5 * osc.m]);
    let e_mid = tangent_vs_differences(&mut VariationalIntegrator::new(Midpoint::new(osc)), &s, 0.05);
    let e_trap = tangent_vs_differences(&mut VariationalIntegrator::new(Trapezoidal::new(osc)), &s, 0.05);
    println!("forced Duffing: |Ψ − Ψ_ref| midpoint {e_mid:e}, trapezoidal {e_trap:e}");
    // Measured 6.9e-13 and 8.5e-13: the reference's own error (ε/δ rounding of the O(1) entries,
    // ~1e-12). Without ∂f±/∂q the error would be of the force's derivative, h·c/2 ≈ 6e-3.
    assert!(e_mid < 3e-12 && e_trap < 3e-12, "{e_mid:e} {e_trap:e}");
}

#[test]
fn wrong_shapes_of_the_tangent_are_refused() {
    let mut vi = VariationalIntegrator::new(Midpoint::new(Kepler));
    let mut s = kepler_states()[0].clone();
    let before = s.clone();
    let mut psi = DMatrix::zeros(4, 3);
    let err = vi.step_tangent(&mut s, 0.1, &mut psi).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Dimension {
                expected: 4,
                got: 3,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(s, before);
}
