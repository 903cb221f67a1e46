//! The cost of one step of a symplectic composition with its exact step Jacobian Ψ (what MEGNO maps,
//! Lyapunov spectra and sensitivities run at every step), against the same step and Ψ written by hand.
//!
//! Yoshida's triple jump of Störmer-Verlet (4 kicks, 3 drifts per step) on Hénon-Heiles,
//! V = (x² + y²)/2 + x²y − y³/3, as a `SeparableHamiltonian` (T(p) = |p|²/2 differentiated too) and
//! as a `Natural` system (the drift's Jacobian is I, no call). The hand-written twin propagates the
//! 4 × 4 Ψ with the closed-form Hessian ∇²V = [[1 + 2y, 2x], [2x, 1 − 2y]]. Each time is the minimum
//! over 30 rounds of 2 000 steps, per step.
//!
//! `cargo bench -p noether-core --bench tangent`; results in docs/benchmarks.md.

#![allow(missing_docs)]

use nalgebra::DMatrix;
use noether_core::integrators::{Composition, Weights};
use noether_core::prelude::*;
use noether_testkit::henon_heiles::{merged_kicks, on_section, HenonHeiles};
use noether_testkit::timing;

const STEPS: usize = 2000;
const H: f64 = 0.1;

/// Yoshida 4 with Ψ on Hénon-Heiles by hand: 4 × 4 Ψ row-major over (x, y, p_x, p_y).
#[allow(clippy::needless_range_loop)] // each column reads two rows of Ψ and writes two others
fn by_hand(gammas: &[f64], q: [f64; 2], p: [f64; 2]) -> f64 {
    let kicks = merged_kicks(gammas);
    let accel = |q: &[f64; 2]| [-q[0] - 2.0 * q[0] * q[1], -q[1] - q[0] * q[0] + q[1] * q[1]];
    let (mut q, mut p) = (q, p);
    let mut total = 0.0;
    for _ in 0..STEPS {
        let mut psi = [[0.0; 4]; 4];
        (0..4).for_each(|i| psi[i][i] = 1.0);
        let kick = |q: &[f64; 2], p: &mut [f64; 2], psi: &mut [[f64; 4]; 4], c: f64| {
            let a = accel(q);
            let k = [[-1.0 - 2.0 * q[1], -2.0 * q[0]], [-2.0 * q[0], -1.0 + 2.0 * q[1]]];
            for col in 0..4 {
                let (d0, d1) = (psi[0][col], psi[1][col]);
                psi[2][col] += c * (k[0][0] * d0 + k[0][1] * d1);
                psi[3][col] += c * (k[1][0] * d0 + k[1][1] * d1);
            }
            *p = [p[0] + c * a[0], p[1] + c * a[1]];
        };
        for (i, &g) in gammas.iter().enumerate() {
            kick(&q, &mut p, &mut psi, kicks[i] * H);
            let c = g * H;
            for col in 0..4 {
                psi[0][col] += c * psi[2][col];
                psi[1][col] += c * psi[3][col];
            }
            q = [q[0] + c * p[0], q[1] + c * p[1]];
        }
        kick(&q, &mut p, &mut psi, kicks[gammas.len()] * H);
        total += psi[0][0];
    }
    total + q[0]
}

fn by_library<S: TangentStepper>(stepper: &mut S, s0: &State<S::Partner>) -> f64 {
    let mut s = s0.clone();
    let n = stepper.dof();
    let mut psi = DMatrix::zeros(2 * n, 2 * n);
    let mut total = 0.0;
    for _ in 0..STEPS {
        stepper.step_tangent(&mut s, H, &mut psi).expect("step");
        total += psi[(0, 0)];
    }
    total + s.q[0]
}

fn main() {
    let s0 = on_section(0.125, 0.1, 0.05).expect("on the energy surface");
    let weights = Weights::yoshida4();
    let mut separable = Composition::yoshida4(SeparableHamiltonian(HenonHeiles));
    let mut natural = Composition::yoshida4(Natural::unit(HenonHeiles));
    let v0: State<Velocities> = State::new(0.0, s0.q.as_slice().to_vec(), s0.v.as_slice().to_vec());
    let (q, p) = ([s0.q[0], s0.q[1]], [s0.v[0], s0.v[1]]);
    // Interleaved rounds; the minimum of each over all of them.
    let (mut hand, mut sep, mut nat) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for _ in 0..5 {
        hand = hand.min(timing::min_ns(30, STEPS, || by_hand(weights.as_slice(), q, p)));
        sep = sep.min(timing::min_ns(30, STEPS, || by_library(&mut separable, &s0)));
        nat = nat.min(timing::min_ns(30, STEPS, || by_library(&mut natural, &v0)));
    }
    println!("Yoshida 4 step with Ψ, Hénon-Heiles (ns per step, minimum of 150 rounds of {STEPS}):");
    println!("  by hand                      {hand:8.1}");
    println!(
        "  SeparableHamiltonian         {sep:8.1}  ({:.1}× by hand)",
        sep / hand
    );
    println!(
        "  Natural                      {nat:8.1}  ({:.1}× by hand)",
        nat / hand
    );
}
