//! A long run: 10⁷ steps of Störmer-Verlet on the Kepler problem (e = 0.5, h = T/200, 50 000
//! orbits). A symplectic method keeps the energy error bounded (it oscillates at O(h²) about a
//! modified Hamiltonian, with no drift) and, being the flow of a rotation-invariant splitting,
//! conserves the angular momentum up to rounding, which accumulates like a random walk.

use super::problems::KeplerV;
use noether_core::prelude::*;

#[test]
fn soak_ten_million_verlet_steps_keep_energy_bounded_and_momentum() {
    // Periapsis of a = 1, e = 0.5: r = 0.5, speed sqrt((1 + e)/(1 − e)) = √3; T = 2π.
    let kepler = Natural::unit(KeplerV);
    let (e, steps, per_orbit) = (0.5f64, 10_000_000usize, 200usize);
    let h = 2.0 * std::f64::consts::PI / per_orbit as f64;
    let mut s = State::new(0.0, [1.0 - e, 0.0], [0.0, ((1.0 + e) / (1.0 - e)).sqrt()]);
    let energy = |s: &State| kepler.energy(s.q.as_slice(), s.v.as_slice()).unwrap();
    let lz = |s: &State| s.q[0] * s.v[1] - s.q[1] * s.v[0];
    let (e0, l0) = (energy(&s), lz(&s));
    let mut verlet = Composition::stormer_verlet(&kepler);
    // Largest |ΔE| over the first and over the last 10⁶ steps, and the largest |ΔL|.
    let (mut first, mut last, mut dl) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..steps {
        verlet.step(&mut s, h).unwrap();
        let de = (energy(&s) - e0).abs();
        if k < steps / 10 {
            first = first.max(de);
        } else if k >= steps - steps / 10 {
            last = last.max(de);
        }
        dl = dl.max((lz(&s) - l0).abs());
    }
    // Bounded: the O(h²) oscillation, set by the periapsis passage, has the same amplitude at the end
    // as at the start (no secular growth).
    eprintln!("soak: |ΔE| first {first:e}, last {last:e}, |ΔL| {dl:e}, E0 {e0}");
    assert!(
        first > 0.0 && last <= 1.02 * first,
        "energy error first {first:e}, last {last:e}"
    );
    // Rounding only: 10⁷ steps of ε-sized errors in a random walk give ~ sqrt(10⁷)·1e-16 ≈ 3e-13.
    assert!(dl < 2e-12 * l0.abs(), "angular momentum drift {dl:e}");
}
