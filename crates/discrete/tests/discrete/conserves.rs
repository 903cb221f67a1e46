//! Conservation laws of variational integrators: discrete Noether momenta exactly (to rounding), the
//! energy bounded without drift.

use crate::models::{kepler_start, Kepler};
use noether_core::Stepper;
use noether_discrete::momentum::{noether_momentum, PlanarRotation};
use noether_discrete::{Midpoint, VariationalIntegrator};

/// Kepler's problem is invariant under rotations, ξ(q) = (−y, x): the discrete angular momentum
/// J = x p_y − y p_x of the midpoint integrator is conserved up to rounding over N = 10⁵ steps, to the
/// issue's 1e-13 relative.
///
/// In exact arithmetic J_{k+1} − J_k = R·ξ(Δ_k) (Δ_k = q_{k+1} − q_k, R the Newton residual; see the
/// integrator's docs). R cannot go below the quantization of q_{k+1}, |R| ~ ‖D₁₂L_d‖ ½ulp(q) ≈ ε|q|/(2h),
/// so each step changes J by ~ ½ε|q||v|, with random sign: a random walk. Measured over 18 orbits
/// and steps (e = 0.2…0.7, h = 0.03…0.0625): σ ≈ 0.64 ε per step relative, i.e. 0.64·ε·√N = 4.5e-14
/// after N = 10⁵; this run's maximum is 3.3e-14 (before the increment form: 2.5e-13). The bound 1e-13
/// is the issue's; it fails for a systematic drift of more than 1e-18 per step.
#[test]
fn conserves_kepler_angular_momentum() {
    let mut vi = VariationalIntegrator::new(Midpoint::new(Kepler));
    let (q, v) = kepler_start(0.5);
    let mut s = vi.state_from_velocities(0.0, &q, &v).unwrap();
    let rot = PlanarRotation::new(vec![(0, 1)]);
    let l0 = noether_momentum(&rot, s.q.as_slice(), s.v.as_slice());
    let e0 = vi.energy(&s).unwrap();
    let mut worst = 0.0_f64;
    let mut worst_e = 0.0_f64;
    for k in 0..100_000 {
        vi.step(&mut s, 0.0625).unwrap();
        if k % 100 == 0 {
            let l = noether_momentum(&rot, s.q.as_slice(), s.v.as_slice());
            worst = worst.max(((l - l0) / l0).abs());
            worst_e = worst_e.max((vi.energy(&s).unwrap() - e0).abs());
        }
    }
    eprintln!("Kepler: max relative angular momentum error {worst:.3e}, max energy error {worst_e:.3e}");
    assert!(worst < 1e-13, "angular momentum drifted: {worst:e} > 1e-13");
    // Energy: bounded (no secular drift) at the O(h²) level of the method, far from the ~1 drift a
    // non-symplectic second-order method shows over 800 orbits at this step.
    assert!(worst_e < 2e-2, "energy error {worst_e:e}");
}
