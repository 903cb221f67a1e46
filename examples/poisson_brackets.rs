//! Poisson brackets of the Kepler problem, computed exactly by dual numbers from the functions
//! themselves: the fundamental brackets, the angular-momentum algebra {L_x, L_y} = L_z, the
//! conservation of L and of the Runge-Lenz vector A ({L, H} = {A, H} = 0, the hidden symmetry that
//! closes the orbits), the algebra {A_x, A_y} = −2mH L_z, Jacobi's identity, and a constant of the
//! motion that depends on time explicitly (df/dt = {f, H} + ∂f/∂t).
//!
//! Run: `cargo run --release --features examples --example poisson_brackets`.

use noether::canonical::poisson::{self, BracketOf, PhaseFunction};
use noether::canonical::{bracket, constant_of_motion, time_derivative};
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::canonical::{AngularMomentum, Coordinates, Kepler3, RungeLenz};
use rand::{rngs::StdRng, Rng, SeedableRng};
use std::process::ExitCode;

/// The free particle's "initial position" m q − p t (a boost generator): it depends on t explicitly,
/// and is conserved because ∂f/∂t = −p cancels {f, H} = p.
struct InitialPosition {
    m: f64,
}

impl PhaseFunction for InitialPosition {
    fn phase_dof(&self) -> usize {
        3
    }
    fn outputs(&self) -> usize {
        3
    }
    fn values<D: Scalar>(&self, t: D, q: &[D], p: &[D], out: &mut [D]) {
        for i in 0..3 {
            out[i] = q[i] * self.m - p[i] * t;
        }
    }
}

/// Free particle H = |p|²/2m.
struct Free {
    m: f64,
}

impl Hamiltonian for Free {
    fn dof(&self) -> usize {
        3
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, _q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) * (0.5 / self.m)
    }
}

/// A random phase point with 0.3 ≤ |q| ≤ 2 and |pᵢ| ≤ 1.5.
fn point(rng: &mut StdRng) -> (f64, Vec<f64>, Vec<f64>) {
    loop {
        let q: Vec<f64> = (0..3).map(|_| rng.random_range(-2.0..2.0)).collect();
        let r = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        if (0.3..=2.0).contains(&r) {
            return (0.0, q, (0..3).map(|_| rng.random_range(-1.5..1.5)).collect());
        }
    }
}

/// Runs the example.
///
/// Every bracket is a sum of products of exact derivatives, so each check is at the rounding of the
/// terms that cancel; the tolerances are a few ε times those terms (measured values in each comment).
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    const EX: &str = "poisson_brackets";
    let kepler = Kepler3 { m: 1.3, k: 2.1 };
    let mut rng = StdRng::seed_from_u64(17);
    let mut report = Report::default();

    // {qᵢ, pⱼ} = δᵢⱼ, {qᵢ, qⱼ} = {pᵢ, pⱼ} = 0: the bracket matrix of z is Ω, exactly (measured 0).
    let (t, q, p) = point(&mut rng);
    let omega = noether::canonical::transform::omega(3);
    let fundamental = (bracket(&Coordinates(3), &Coordinates(3), t, &q, &p)? - omega).amax();
    report
        .checks
        .push(Check::abs(EX, "max |{z_a, z_b} − Ω_ab|", fundamental, 0.0, 0.0));

    // {L_x, L_y} = L_z (cyclic): the derivatives are exact ±qᵢ, ±pᵢ and the products reproduce L_z's
    // own; measured error 0, tolerance 1e-15 (one rounding of a product of size |q||p|).
    let l = poisson::values(&AngularMomentum, t, &q, &p)?;
    let ll = bracket(&AngularMomentum, &AngularMomentum, t, &q, &p)?;
    report
        .checks
        .push(Check::abs(EX, "{L_x, L_y} − L_z", ll[(0, 1)], l[2], 1e-15));
    report
        .checks
        .push(Check::abs(EX, "{L_y, L_z} − L_x", ll[(1, 2)], l[0], 1e-15));

    // L and A are constants of the motion: the worst |{f, H}| over 2000 random points, relative to the
    // size of the terms that cancel there. Measured L 1.8e-16, A 2.0e-16; tolerance 4ε.
    let samples: Vec<_> = (0..2000).map(|_| point(&mut rng)).collect();
    for (name, c) in [
        (
            "L",
            constant_of_motion(&AngularMomentum, &kepler, samples.iter().cloned())?,
        ),
        (
            "A",
            constant_of_motion(&RungeLenz(kepler), &kepler, samples.iter().cloned())?,
        ),
    ] {
        report.checks.push(Check::abs(
            EX,
            format!("max |{{{name}, H}}| / scale over 2000 points"),
            c.worst / c.scale,
            0.0,
            4.0 * f64::EPSILON,
        ));
    }

    // The so(4) algebra of the bound Kepler problem: {A_x, A_y} = −2mH L_z (Goldstein §9.7). Terms of
    // size ~|A|²; measured relative error 3.4e-16, tolerance 4e-15.
    let h = HamiltonEquations::new(kepler).energy(t, &q, &p)?;
    let aa = bracket(&RungeLenz(kepler), &RungeLenz(kepler), t, &q, &p)?;
    report.checks.push(Check::rel(
        EX,
        "{A_x, A_y} = −2mH L_z",
        aa[(0, 1)],
        -2.0 * kepler.m * h * l[2],
        4e-15,
    ));

    // Jacobi's identity on (L_x, A_y, x), with the inner brackets as exact phase functions (not on
    // (L_x, A_y, H): there every term is a bracket with a conserved quantity, zero up to rounding):
    // measured |sum| / Σ|terms| 0 at this point, tolerance 8ε.
    struct Component<F>(F, usize);
    impl<F: PhaseFunction> Hamiltonian for Component<F> {
        fn dof(&self) -> usize {
            self.0.phase_dof()
        }
        fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
            let mut out = vec![D::zero(); self.0.outputs()];
            self.0.values(t, q, p, &mut out);
            out[self.1]
        }
    }
    let (f, g, x) = (
        Component(AngularMomentum, 0),
        Component(RungeLenz(kepler), 1),
        Component(Coordinates(3), 0),
    );
    let terms = [
        bracket(&f, &BracketOf(&g, &x), t, &q, &p)?[(0, 0)],
        bracket(&g, &BracketOf(&x, &f), t, &q, &p)?[(0, 0)],
        bracket(&x, &BracketOf(&f, &g), t, &q, &p)?[(0, 0)],
    ];
    let size: f64 = terms.iter().map(|x| x.abs()).sum();
    report.checks.push(Check::abs(
        EX,
        "Jacobi identity (L_x, A_y, x) / Σ|terms|",
        terms.iter().sum::<f64>().abs() / size.max(f64::MIN_POSITIVE),
        0.0,
        8.0 * f64::EPSILON,
    ));

    // A time-dependent constant: f = m q − p t for the free particle, df/dt = {f, H} + ∂f/∂t = p − p = 0
    // exactly (measured 0), while {f, H} alone is p (measured exact).
    let free = Free { m: 2.0 };
    let boost = InitialPosition { m: 2.0 };
    let (t1, q1, p1) = (0.7, [0.3, -0.2, 1.0], [0.4, 1.1, -0.6]);
    let dfdt = time_derivative(&boost, &free, t1, &q1, &p1)?;
    let fh = poisson::bracket_with(&boost, &free, t1, &q1, &p1)?;
    report.checks.push(Check::abs(
        EX,
        "d(mq − pt)/dt = {f, H} + ∂f/∂t",
        dfdt.iter().fold(0.0, |m, x| m.max(x.abs())),
        0.0,
        1e-16,
    ));
    report
        .checks
        .push(Check::abs(EX, "{m q_x − p_x t, H} = p_x", fh[0], p1[0], 1e-16));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main("poisson_brackets", run)
}
