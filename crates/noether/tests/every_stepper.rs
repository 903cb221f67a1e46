//! Every stepper of the workspace — explicit, adaptive, explicit symplectic, Gauss-Legendre,
//! variational, RATTLE, projected, particle — runs through the one driver with output times and a
//! non-terminal event, against the closed form of the harmonic oscillator.
//!
//! Closed form (m = k = 1, x(0) = 1, ẋ(0) = 0): x(t) = cos t, so the event "x crosses zero downwards"
//! fires at t = π/2 and 5π/2 in [0, 10]. The constrained methods run the same motion as uniform motion
//! on the unit circle, x = cos t, y = sin t, and the particle methods as a particle in the isotropic
//! trap U = ½ |r|² on the same circle.
//!
//! Each method's tolerance is 2–4 times its measured error (max over the 41 output times, and over the
//! two event times): what the method's order and the interpolation the driver declares for it give at
//! the step used. Output times between steps come from the method's dense output (DOPRI5, DOP853) or
//! the cubic Hermite interpolant (error ≤ h⁴ max|x⁗|/384 = 2.6e-7 at h = 0.1, which is what Kahan-Li 8
//! and Gauss 6 show at output times while their event times, located on the same interpolant near a
//! zero, are 100 times better); RATTLE, which gives the driver no vector field, is interpolated
//! linearly. A method that lost an order, an event or an output time fails.

use noether::constraints::HolonomicSet;
use noether::constraints::{Constrained, Holonomic, Projected, Rattle};
use noether::core::integrators::{Dopri5, Euler, EulerCromer, Rk4, SymplecticEuler, Weights};
use noether::discrete::{
    Galerkin, LocalPotential, Mass, Mechanical, MechanicalMidpoint, Trapezoidal, Verlet,
};
use noether::particles::{External, Method, Particle, System};
use noether::particles::{ParticleStepper, Trap};
use noether::prelude::*;
use std::f64::consts::PI;

/// x(t) = cos t at the output times and the event times.
struct Measured {
    output_error: f64,
    event_error: f64,
    events: usize,
}

/// Runs `stepper` from `start` to t = 10 (with step `h` when given), saving at t = 0, 0.25, …, 10 with
/// the event x = 0 downwards, and measures the errors against x = cos t.
fn measure<S: Stepper>(stepper: S, start: State<S::Partner>, h: Option<f64>) -> Measured {
    let times: Vec<f64> = (0..=40).map(|i| 0.25 * i as f64).collect();
    let mut driver = Driver::new(stepper, start).expect("valid start");
    if let Some(h) = h {
        driver = driver.step_size(h).expect("valid step");
    }
    let sol = driver
        .save(Save::Times(times.clone()))
        .expect("valid times")
        .event(Event::new("x = 0 downwards", |s: &State<S::Partner>| s.q[0]).falling())
        .run_until(10.0)
        .expect("the run succeeds");
    assert_eq!(sol.times(), &times[..], "{}: output times", sol.method());
    let output_error = (0..sol.len())
        .map(|i| (sol.q(i)[0] - sol.times()[i].cos()).abs())
        .fold(0.0, f64::max);
    let fired = sol
        .event_times("x = 0 downwards")
        .expect("the event is registered");
    let event_error = fired
        .iter()
        .zip([0.5 * PI, 2.5 * PI])
        .map(|(t, exact)| (t - exact).abs())
        .fold(0.0, f64::max);
    Measured {
        output_error,
        event_error,
        events: fired.len(),
    }
}

/// Asserts the measured errors of `name` are within its tolerances and that both events fired.
fn assert_within(name: &str, m: Measured, output_tol: f64, event_tol: f64) {
    eprintln!(
        "{name}: output {:.1e}, event {:.1e}",
        m.output_error, m.event_error
    );
    assert_eq!(m.events, 2, "{name}: events");
    assert!(
        m.output_error <= output_tol,
        "{name}: output error {:e} > {output_tol:e}",
        m.output_error
    );
    assert!(
        m.event_error <= event_tol,
        "{name}: event error {:e} > {event_tol:e}",
        m.event_error
    );
}

/// L = ½ ẋ² − ½ x².
fn oscillator() -> impl Lagrangian {
    lagrangian!(dof = 1, |_t, q, v| (v[0] * v[0] - q[0] * q[0]) * 0.5)
}

/// V = ½ x² for the natural (separable) forms.
struct Spring;
impl Potential for Spring {
    fn dof(&self) -> usize {
        1
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        q[0] * q[0] * 0.5
    }
}

/// H = ½ p² + ½ x², separable.
struct SeparableSpring;
impl Separable for SeparableSpring {
    fn dof(&self) -> usize {
        1
    }
    fn kinetic<D: Scalar>(&self, p: &[D]) -> D {
        p[0] * p[0] * 0.5
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        q[0] * q[0] * 0.5
    }
}

fn rest() -> State {
    State::new(0.0, [1.0], [0.0])
}

fn rest_p() -> State<Momenta> {
    State::with_momenta(0.0, [1.0], [0.0])
}

#[test]
fn closed_form_explicit_and_adaptive_methods_through_the_driver() {
    let el = EulerLagrange::new(oscillator());
    assert_within("Euler", measure(Euler::new(&el), rest(), Some(1e-5)), 1e-4, 1e-9);
    assert_within(
        "Euler-Cromer",
        measure(EulerCromer::new(&el), rest(), Some(1e-4)),
        1e-4,
        1e-4,
    );
    assert_within("RK4", measure(Rk4::new(&el), rest(), Some(1e-2)), 2e-9, 2e-9);
    let dopri5 = Dopri5::new(&el).tolerances(1e-10, 1e-10).unwrap();
    assert_within("DOPRI5", measure(dopri5, rest(), None), 1e-9, 1e-10);
    let dop853 = Dop853::new(&el).tolerances(1e-12, 1e-12).unwrap();
    assert_within("DOP853", measure(dop853, rest(), None), 1e-11, 1e-11);
    let h = HamiltonEquations::new(hamiltonian!(dof = 1, |_t, q, p| (p[0] * p[0] + q[0] * q[0]) * 0.5));
    assert_within(
        "RK4 on Hamilton",
        measure(Rk4::new(&h), rest_p(), Some(1e-2)),
        2e-9,
        2e-9,
    );
}

#[test]
fn closed_form_symplectic_and_gauss_methods_through_the_driver() {
    let natural = Natural::diagonal(Spring, &[1.0]).unwrap();
    let sep = SeparableHamiltonian(SeparableSpring);
    let h = 1e-2;
    assert_within(
        "symplectic Euler",
        measure(SymplecticEuler::new(&natural), rest(), Some(1e-4)),
        1e-4,
        1e-4,
    );
    assert_within(
        "Störmer-Verlet",
        measure(Composition::stormer_verlet(&natural), rest(), Some(h)),
        1e-4,
        1e-4,
    );
    assert_within(
        "Yoshida 4",
        measure(Composition::yoshida4(&natural), rest(), Some(h)),
        2e-8,
        2e-8,
    );
    assert_within(
        "Kahan-Li 8",
        measure(Composition::kahan_li8(&sep), rest_p(), Some(0.1)),
        1e-6,
        1e-8,
    );
    assert_within(
        "implicit midpoint",
        measure(Gauss::implicit_midpoint(&natural), rest(), Some(h)),
        2e-4,
        2e-4,
    );
    assert_within(
        "Gauss 4",
        measure(Gauss::gauss4(&sep), rest_p(), Some(0.1)),
        3e-6,
        3e-6,
    );
    let eqs = HamiltonEquations::new(hamiltonian!(dof = 1, |_t, q, p| (p[0] * p[0] + q[0] * q[0]) * 0.5));
    assert_within(
        "Gauss 6",
        measure(Gauss::gauss6(&eqs), rest_p(), Some(0.1)),
        1e-6,
        1e-8,
    );
}

#[test]
fn closed_form_variational_methods_through_the_driver() {
    let h = 1e-2;
    let midpoint = VariationalIntegrator::new(Midpoint::new(oscillator()));
    assert_within(
        "variational midpoint",
        measure(midpoint, rest_p(), Some(h)),
        2e-4,
        2e-4,
    );
    let trapezoidal = VariationalIntegrator::new(Trapezoidal::new(oscillator()));
    assert_within(
        "variational trapezoidal",
        measure(trapezoidal, rest_p(), Some(h)),
        1e-4,
        1e-4,
    );
    let galerkin = Galerkin::order4(oscillator()).unwrap();
    assert_within("Galerkin 4", measure(galerkin, rest_p(), Some(0.05)), 2e-7, 2e-7);
    let composed = Composition::new(
        VariationalIntegrator::new(Midpoint::new(oscillator())),
        Weights::yoshida4(),
    );
    assert_within(
        "composed midpoint 4",
        measure(composed, rest_p(), Some(0.05)),
        1e-5,
        1e-5,
    );
}

/// V = ½ x² as a sum of local terms (one), for the mechanical variational integrators.
struct LocalSpring;
impl LocalPotential for LocalSpring {
    fn dof(&self) -> usize {
        1
    }
    fn terms(&self) -> usize {
        1
    }
    fn support(&self, _k: usize, idx: &mut Vec<usize>) {
        idx.push(0);
    }
    fn term<D: Scalar>(&self, _k: usize, x: &[D]) -> D {
        x[0] * x[0] * 0.5
    }
}

#[test]
fn closed_form_mechanical_variational_methods_through_the_driver() {
    let mechanical = || Mechanical::new(Mass::Diagonal(vec![1.0]), LocalSpring).unwrap();
    assert_within(
        "Verlet (mechanical)",
        measure(Verlet::new(mechanical()), rest_p(), Some(1e-2)),
        1e-4,
        1e-4,
    );
    let midpoint = MechanicalMidpoint::new(mechanical());
    assert_within(
        "midpoint (mechanical)",
        measure(midpoint, rest_p(), Some(1e-2)),
        2e-4,
        2e-4,
    );
}

/// A free unit mass in the plane on the unit circle, φ = (|r|² − 1)/2.
struct Circle;
impl Holonomic for Circle {
    fn dof(&self) -> usize {
        2
    }
    fn count(&self) -> usize {
        1
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        out[0] = (q[0] * q[0] + q[1] * q[1] - 1.0) * 0.5;
    }
}

fn free_particle() -> impl Lagrangian {
    lagrangian!(dof = 2, |_t, _q, v| (v[0] * v[0] + v[1] * v[1]) * 0.5)
}

#[test]
fn closed_form_constrained_methods_through_the_driver() {
    // Uniform motion on the unit circle at unit speed: x = cos t.
    let rattle = Rattle::new(Midpoint::new(free_particle()), Circle).unwrap();
    let start = rattle
        .state_from_velocities(0.0, &[1.0, 0.0], &[0.0, 1.0])
        .unwrap();
    assert_within(
        "RATTLE (midpoint)",
        measure(rattle, start, Some(1e-2)),
        3e-4,
        3e-4,
    );
    let sys = Constrained::new(free_particle(), HolonomicSet(Circle)).unwrap();
    let projected = Projected::new(Rk4::new(&sys), sys.constraints());
    let start = State::new(0.0, [1.0, 0.0], [0.0, 1.0]);
    assert_within("projected RK4", measure(projected, start, Some(1e-2)), 2e-9, 2e-9);
}

#[test]
fn closed_form_particle_methods_through_the_driver() {
    // One unit mass in the isotropic trap U = ½ |r|², on the circle of radius 1 at unit speed.
    let trap = Trap {
        k2: 1.0,
        k4: 0.0,
        center: [0.0; 3],
    };
    let sys = System::new(vec![Particle::new(1.0)])
        .unwrap()
        .with(External::new(trap, [0]))
        .unwrap();
    let start = || sys.state(0.0, &[[1.0, 0.0, 0.0]], &[[0.0, 1.0, 0.0]]).unwrap();
    // (method, step, tolerance on output and event times): the same errors as the core methods of
    // the same order at the same step (measured 6.6e-10, 3.3e-5, 5.2e-9, 5.0e-5).
    for (method, h, tol) in [
        (Method::Rk4, 1e-2, 2e-9),
        (Method::VelocityVerlet, 1e-2, 1e-4),
        (Method::Yoshida4, 1e-2, 2e-8),
        (Method::EulerCromer, 1e-4, 1e-4),
    ] {
        let name = format!("particles {method:?}");
        assert_within(
            &name,
            measure(ParticleStepper::new(&sys, method), start(), Some(h)),
            tol,
            tol,
        );
    }
}
