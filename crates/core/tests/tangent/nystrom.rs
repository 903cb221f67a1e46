//! Runge-Kutta-Nyström pairs (DPRKN 6, 8, 12): Ψ of the accepted step with h frozen.

use super::*;
use noether_core::natural::{Natural, Potential};

/// The Hénon-Heiles potential.
#[derive(Debug, Clone, Copy)]
struct HhPotential;
impl Potential for HhPotential {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        (q[0] * q[0] + q[1] * q[1]) * 0.5 + q[0] * q[0] * q[1] - q[1].powi(3) / 3.0
    }
}

fn natural() -> Natural<HhPotential> {
    Natural::dense(HhPotential, DMatrix::from_row_slice(2, 2, &[2.0, 0.5, 0.5, 1.0])).unwrap()
}

fn start() -> State<Velocities> {
    State::new(0.0, [0.1, -0.2], [0.25, 0.1])
}

#[test]
fn nystrom_tangents_match_central_differences() {
    let sys = natural();
    let s = start();
    let errs = [
        tangent_vs_differences(&mut Dprkn6::new(&sys).unwrap().fixed_step(true), &s, 0.2),
        tangent_vs_differences(&mut Dprkn8::new(&sys).unwrap().fixed_step(true), &s, 0.2),
        tangent_vs_differences(&mut Dprkn12::new(&sys).unwrap().fixed_step(true), &s, 0.2),
        // Error control on: Ψ of the h taken (the same from y₀ and the perturbed starts, or the
        // differences would not agree).
        tangent_vs_differences(&mut Dprkn8::new(&sys).unwrap(), &s, 0.05),
    ];
    println!("DPRKN 6, 8, 12 (fixed), 8 (adaptive): {errs:?}");
    // Measured 1.4e-12, 1.5e-12, 1.3e-12, 8.5e-13: the central differences' own error (FD_REL).
    for e in errs {
        assert!(e < 1e-11, "{e:e}");
    }
}

#[test]
fn nystrom_tangent_error_contract() {
    let sys = natural();
    error_contract(&mut Dprkn8::new(&sys).unwrap(), &start(), 0.1);
}
