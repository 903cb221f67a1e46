//! Property tests of the error contract (docs/error-contract.md) over noether-particles: random
//! numbers of particles, masses, laws and positions (coincident, far apart, huge, NaN). Every call
//! returns Ok with finite values or a typed error, never panics, and a failed step leaves the state
//! as it was.

use noether_core::State;
use noether_particles::prelude::*;
use noether_particles::Interaction;
use proptest::prelude::*;

/// Mostly ordinary numbers, often the ones that break code.
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -3.0..3.0f64,
        1 => prop_oneof![
            Just(0.0),
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(5e-324),
            Just(1e-300),
            Just(1e20),
            Just(1e300),
            Just(f64::MAX),
        ],
    ]
}

fn vec3() -> impl Strategy<Value = Vec3> {
    [number(), number(), number()]
}

/// Bit patterns, so that a NaN compares equal to itself.
fn bits(s: &State) -> Vec<u64> {
    std::iter::once(s.t)
        .chain(s.q.iter().copied())
        .chain(s.v.iter().copied())
        .map(f64::to_bits)
        .collect()
}

/// Runs the evaluations and a step of one system; `Ok` results must be finite.
fn exercise<I: Interaction>(sys: &System<I>, x: &[Vec3], v: &[Vec3], h: f64) {
    let (xf, vf) = (x.concat(), v.concat());
    let mut f = vec![7.0; xf.len()];
    if let Ok(e) = sys.potential_forces(0.0, &xf, &mut f) {
        assert!(
            e.is_finite() && f.iter().all(|c| c.is_finite()),
            "forces {e} {f:?}"
        );
    }
    if let Ok(e) = sys.potential_energy(0.0, &xf) {
        assert!(e.is_finite());
    }
    if let Ok(t) = sys.kinetic_energy(&vf) {
        assert!(t.is_finite());
    }
    if let Ok(p) = sys.momentum(&vf) {
        assert!(p.iter().all(|c| c.is_finite()));
    }
    if let Ok(c) = sys.centre_of_mass(&xf) {
        assert!(c.iter().all(|c| c.is_finite()));
    }
    if let Ok(mut s) = sys.state(0.0, x, v) {
        if let Ok(e) = sys.total_energy(&s) {
            assert!(e.is_finite());
        }
        let before = bits(&s);
        match sys.step(Method::VelocityVerlet, &mut s, h) {
            Ok(_) => assert!(s.is_finite()),
            Err(_) => assert_eq!(bits(&s), before, "state changed on error"),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    /// Gravity over all pairs, a spring chain and a Lennard-Jones cell list, with random particles.
    #[test]
    fn prop_particle_systems(
        masses in prop::collection::vec(number(), 0..5),
        x in prop::collection::vec(vec3(), 0..6),
        v in prop::collection::vec(vec3(), 0..6),
        g in number(),
        h in number(),
    ) {
        let particles: Vec<Particle> = masses.iter().map(|&m| Particle::new(m)).collect();
        let Ok(base) = System::new(particles) else { return Ok(()) };
        let n = base.len();
        if let Ok(sys) = System::new(base.particles().to_vec()).and_then(|s| s.with(AllPairs::new(Gravity { g }))) {
            exercise(&sys, &x, &v, h);
        }
        let chain: Vec<(usize, usize)> = (1..n).map(|i| (i - 1, i)).collect();
        if let Ok(sys) = System::new(base.particles().to_vec())
            .and_then(|s| s.with(Internal::new(Spring { k: 1.0, re: g }, chain)))
        {
            exercise(&sys, &x, &v, h);
        }
        if let Ok(lj) = ShortRange::new(LennardJones::with_cutoff(1.0, 1.0, 2.5)) {
            if let Ok(sys) = System::new(base.particles().to_vec()).and_then(|s| s.with(lj)) {
                exercise(&sys, &x, &v, h);
            }
        }
    }
}
