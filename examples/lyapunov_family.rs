//! The planar Lyapunov family about L1 of the Earth-Moon system, followed by pseudo-arclength
//! continuation from a 380 km orbit to one reaching 58 000 km from L1, far past where single shooting
//! from extrapolated guesses loses it.
//!
//! ```text
//! H = ½(p_x² + p_y²) + y p_x − x p_y − (1 − μ)/r₁ − μ/r₂ = −C/2,   μ = 0.01215
//! ```
//!
//! Every member is strongly unstable: its saddle pair of multipliers λ, 1/λ has λ from 2700 down to ≈ 115 at the largest, so
//! single shooting multiplies a guess error by λ over one period and its Newton basin shrinks as the
//! orbits grow (it fails from amplitude ≈ 0.0076 on; the test `lyapunov_family_by_multiple_shooting`).
//! Here the period is cut into 10 arcs (multiple shooting: each arc grows an error by only λ^{1/10}),
//! the Jacobi constant C becomes an unknown, and each member is found a step Δs along the family's
//! tangent from the last (`noether::analysis::Continuation`), stepping by Gauss-Legendre collocation
//! of order 6 (symplectic).
//!
//! **Checks.**
//! - *The linear limit:* as the amplitude A → 0 the period tends to the linearisation's 2π/ω,
//!   ω² = (2 − c₂ + √(9c₂² − 8c₂))/2 with c₂ = (1 − μ)/r₁³ + μ/r₂³ at L1 (Richardson 1980), as
//!   T₀ + κA².
//! - *One family, no bifurcation in the plane:* C falls and T grows monotonically, no special point is
//!   met, every member is unstable with a real pair λ > 1, 1/λ.
//! - *The flow's orbits:* the energy held along each orbit, the monodromy symplectic, and the largest
//!   orbit, run once round by DOP853 at tolerance 1e-13, closes.
//!
//! Run: `cargo run --release -- --only lyapunov_family --checks --notes` (the family goes to
//! `gallery-out/`).

use noether::analysis::periodic::{Energy, FirstIntegral, PeriodicOrbit, Shooting, Stability};
use noether::analysis::Continuation;
use noether::core::integrators::Gauss;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::canonical::relative_symplectic_defect;
use noether_testkit::three_body::{energy_drift, flow_closure, l1, l1_guess, l1_linear, sample_orbit, Cr3bp};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "lyapunov_family";

/// Earth-Moon mass ratio (Doedel et al. 2007's).
const MU: f64 = 0.01215;
/// Steps a period (Gauss-Legendre 6), in 10 arcs.
const STEPS: usize = 1200;
/// The members before the family's orbits reach close to the Moon, where uniform steps in time resolve
/// them worst.
const NEAR: usize = 30;

/// Runs the example: `members` orbits from amplitude 0.001.
pub fn run_members(members: usize, opts: &Options) -> Result<Report, BoxError> {
    let model = Cr3bp { mu: MU };
    let (xl, c2) = l1(MU);
    let (omega, k) = l1_linear(c2);
    let t_linear = 2.0 * PI / omega;
    let energy = Energy(model);
    // Two small orbits for the linear limit, the first the family's start.
    let mut small = Vec::new();
    let shooting = |e: f64| -> Result<_, BoxError> {
        Ok(
            Shooting::new(Gauss::gauss6(HamiltonEquations::new(model)), STEPS)?
                .segments(10)?
                .level(Energy(model), e),
        )
    };
    for amplitude in [0.001, 0.0005] {
        let (guess, period) = l1_guess((xl, omega, k, t_linear), amplitude, &None, &None);
        let e = energy.value(guess.q.as_slice(), guess.v.as_slice())?;
        let mut s = shooting(e)?;
        let orbit = s.solve(&guess, period)?;
        small.push((amplitude, e, orbit, s));
    }
    // T − T₀ = κA² + O(A⁴): the two estimates of κ agree to O(A²).
    let kappa: Vec<f64> = small
        .iter()
        .map(|(a, _, o, _)| (o.period - t_linear) / (a * a))
        .collect();
    let (_, e0, start, mut family_shooting) = small.swap_remove(0);
    let branch =
        Continuation::new(0.01, 1e-5, 0.1)?.follow(&mut family_shooting, &start, e0, members, true)?;
    if let Some(lost) = &branch.lost {
        return Err(format!("the family was lost: {lost}").into());
    }
    let (mut drift, mut drift_near) = (0.0_f64, 0.0_f64);
    let (mut symplectic, mut pair) = (0.0_f64, 0.0_f64);
    let (mut monotone, mut unstable) = (true, true);
    let mut last = (-2.0 * e0, start.period);
    for (i, (h, orbit)) in branch.members.iter().enumerate() {
        let run = (orbit.period, orbit.steps);
        let d = energy_drift(&model, family_shooting.stepper_mut(), &orbit.nodes, run, *h)?;
        drift = drift.max(d);
        if i < NEAR {
            drift_near = drift_near.max(d);
        }
        symplectic = symplectic.max(relative_symplectic_defect(&orbit.monodromy));
        let nontrivial = orbit.floquet.nontrivial();
        let (big, small) = (nontrivial[0], nontrivial[1]);
        pair = pair.max((big * small - 1.0).norm());
        unstable &= orbit.floquet.stability == Stability::Unstable && big.im == 0.0 && big.re > 1.0;
        let c = -2.0 * h;
        monotone &= c < last.0 && orbit.period > last.1;
        last = (c, orbit.period);
    }
    let (_, end) = branch.members.last().ok_or("no member found")?;
    let closure = |orbit: &PeriodicOrbit<Momenta>| flow_closure(model, &orbit.initial, orbit.period, 1e-13);
    let near = &branch.members[NEAR.min(branch.members.len()) - 1].1;
    let (closure_near, closure_end) = (closure(near)?, closure(end)?);
    let reach = end.initial.q[0] - xl;

    let mut report = Report::default();
    report.note(format!(
        "{} members from C = {:.5} (A = 0.001, T = {:.5}) to C = {:.5}, T = {:.5}, x₀ − x_L1 = {reach:.4} \
         ({:.0} km); κ = (T − 2π/ω)/A² = {:.4} (A = 0.001), {:.4} (A = 0.0005); λ at the last {:.1}; \
         member {NEAR} at C = {:.5}",
        branch.members.len(),
        -2.0 * e0,
        start.period,
        last.0,
        last.1,
        reach.abs() * 384_400.0,
        kappa[0],
        kappa[1],
        end.floquet.nontrivial()[0].re,
        -2.0 * branch.members[NEAR.min(branch.members.len()) - 1].0
    ));
    let yes = |b: bool| f64::from(u8::from(b));
    report.checks = vec![
        // T₀ + κA²: the two estimates of κ differ by the A⁴ term, O(A²) relative (measured 5.0e-4:
        // κ = 206.85 at A = 0.001, 206.75 at 0.0005); tolerance 2e-3.
        Check::rel(
            NAME,
            "κ = (T − 2π/ω)/A² at A = 0.0005 against A = 0.001",
            kappa[1],
            kappa[0],
            2e-3,
        ),
        Check::abs(
            NAME,
            "C falls and T grows along the family",
            yes(monotone),
            1.0,
            0.5,
        ),
        Check::abs(
            NAME,
            "special points in the plane",
            branch.special.len() as f64,
            0.0,
            0.5,
        ),
        Check::abs(
            NAME,
            "every member unstable with a real pair λ > 1",
            yes(unstable),
            1.0,
            0.5,
        ),
        // The family reaches far past single shooting's amplitude 0.0076: measured x₀ − x_L1 = −0.150.
        Check::abs(
            NAME,
            "x₀ − x_L1 of the last member below −0.1",
            yes(reach < -0.1),
            1.0,
            0.5,
        ),
        // Gauss-Legendre 6 at h = T/1200: measured 2.2e-12 over the first 30 members (to C = 2.984), 3.4e-9
        // over all: the largest orbits swing close to the Moon, where uniform steps in time resolve
        // them worst.
        Check::abs(
            NAME,
            format!("max |H − E| along each of the first {NEAR} orbits"),
            drift_near,
            0.0,
            1e-11,
        ),
        Check::abs(NAME, "max |H − E| along each orbit", drift, 0.0, 1e-8),
        // λ·(1/λ) = 1: the small multiplier is rounded to ε‖M‖ (measured 1.5e-9).
        Check::abs(NAME, "|λ·(1/λ) − 1|", pair, 0.0, 5e-9),
        // Gauss is symplectic: measured 3.5e-17.
        Check::abs(
            NAME,
            "symplectic defect of the monodromies",
            symplectic,
            0.0,
            1e-16,
        ),
        // Once round by DOP853: the map's orbit is the flow's to O(h⁶) amplified by λ; measured
        // 8.3e-11 at member 30, 1.3e-7 at the last (λ ≈ 115, and the near passes of the Moon).
        Check::abs(
            NAME,
            format!("orbit {NEAR}, once round by DOP853: |y(T) − y₀|"),
            closure_near,
            0.0,
            3e-10,
        ),
        Check::abs(
            NAME,
            "last orbit, once round by DOP853: |y(T) − y₀|",
            closure_end,
            0.0,
            5e-7,
        ),
    ];
    if opts.out_dir.is_some() {
        let mut fig = Figure::new("The L1 Lyapunov family, Earth-Moon, rotating frame")
            .x_label("x − x_L1")
            .y_label("y");
        for (h, orbit) in branch.members.iter().step_by(5) {
            let run = (orbit.period, orbit.steps);
            let points = sample_orbit(family_shooting.stepper_mut(), &orbit.initial, run, 6)?;
            let pts = points.iter().map(|st| (st.q[0] - xl, st.q[1])).collect();
            fig = fig.series(format!("C = {:.4}, T = {:.3}", -2.0 * h, orbit.period), pts);
        }
        report.save(opts, &fig, "lyapunov_family.svg")?;
    }
    Ok(report)
}

/// Runs the example (45 members).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    run_members(45, opts)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
