//! Tests of noether-particles: forces against hand-written laws, the third law, the Lagrangian path
//! against the term-by-term path, sparse Hessians, cell lists, determinism of the parallel path,
//! convergence orders, bad input.

use noether_core::ad::{self, Block, Field};
use noether_core::{EulerLagrange, Lagrangian, Scalar};
use noether_particles::prelude::*;
use noether_particles::{CellList, Error};
use rand::{rngs::StdRng, Rng, SeedableRng};

fn random_positions(n: usize, box_len: f64, rng: &mut StdRng) -> Vec<Vec3> {
    (0..n)
        .map(|_| std::array::from_fn(|_| rng.random_range(0.0..box_len)))
        .collect()
}

fn forces_of<I: noether_particles::Interaction>(sys: &System<I>, x: &[Vec3]) -> (f64, Vec<f64>) {
    let flat = x.concat();
    let mut f = vec![0.0; flat.len()];
    let e = sys.potential_forces(0.0, &flat, &mut f).unwrap();
    (e, f)
}

/// Force on particle 2 of a pair from the AD path.
fn f21<P: PairPotential>(pot: P, r: Vec3, m: [f64; 2], q: [f64; 2]) -> Vec3 {
    let sys = System::new(vec![Particle::charged(m[0], q[0]), Particle::charged(m[1], q[1])])
        .unwrap()
        .with(Internal::new(pot, [(0, 1)]))
        .unwrap();
    let (_, f) = forces_of(&sys, &[[0.3, -0.2, 0.1], [0.3 + r[0], -0.2 + r[1], 0.1 + r[2]]]);
    for k in 0..3 {
        assert_eq!(f[k], -f[3 + k], "third law");
    }
    [f[3], f[4], f[5]]
}

fn close(a: Vec3, b: Vec3, tol: f64) {
    let scale = b.iter().fold(1e-300_f64, |m, v| m.max(v.abs()));
    for k in 0..3 {
        assert!((a[k] - b[k]).abs() <= tol * scale, "{a:?} vs {b:?}");
    }
}

/// The seed's force laws written by hand, F21 on particle 2 with r21 = r2 − r1; AD agrees to rounding.
#[test]
fn ad_vs_hand_force_laws() {
    let r: Vec3 = [0.7, -0.4, 1.1];
    let d: f64 = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    let u = r.map(|c| c / d);
    // Gravity: −G m1 m2 r21/r³.
    let s = -2.0 * 3.0 * 5.0 / (d * d);
    close(
        f21(Gravity { g: 2.0 }, r, [3.0, 5.0], [0.0; 2]),
        u.map(|c| s * c),
        1e-14,
    );
    // Coulomb: k e1 e2 r21 / r³.
    let s = 4.0 * 1.5 * -2.0 / (d * d);
    close(
        f21(Coulomb { k: 4.0 }, r, [1.0; 2], [1.5, -2.0]),
        u.map(|c| s * c),
        1e-14,
    );
    // Constant repulsion: F r̂.
    close(
        f21(ConstantRepulsion { f: 3.0 }, r, [1.0; 2], [0.0; 2]),
        u.map(|c| 3.0 * c),
        1e-14,
    );
    // Spring: −k (r − re) r̂.
    let s = -2.5 * (d - 0.8);
    close(
        f21(Spring { k: 2.5, re: 0.8 }, r, [1.0; 2], [0.0; 2]),
        u.map(|c| s * c),
        1e-14,
    );
    // Billiard: a compressed spring inside re, nothing outside.
    let s = -7.0 * (d - 2.0);
    close(
        f21(Billiard { k: 7.0, re: 2.0 }, r, [1.0; 2], [0.0; 2]),
        u.map(|c| s * c),
        1e-14,
    );
    assert_eq!(f21(Billiard { k: 7.0, re: 1.0 }, r, [1.0; 2], [0.0; 2]), [0.0; 3]);
    // Lennard-Jones: F21 = −U'(r) r̂, U' = De (−12 re¹²/r¹³ + 12 re⁶/r⁷).
    let (de, re) = (0.9_f64, 1.2_f64);
    let du = de * (-12.0 * re.powi(12) / d.powi(13) + 12.0 * re.powi(6) / d.powi(7));
    close(
        f21(LennardJones::new(de, re), r, [1.0; 2], [0.0; 2]),
        u.map(|c| -du * c),
        1e-13,
    );
    // Gaussian coupling: U = k2 exp(−r²/2σ²), F21 = k2 r21/σ² exp(−r²/2σ²).
    let (k2, sg) = (0.3, 0.9);
    let s = k2 / (sg * sg) * (-d * d / (2.0 * sg * sg)).exp();
    close(
        f21(GaussianCoupling { k2, sigma: sg }, r, [1.0; 2], [0.0; 2]),
        r.map(|c| s * c),
        1e-14,
    );
}

#[test]
fn ad_vs_hand_one_body_and_given_forces() {
    let p = [Particle::new(2.0), Particle::new(3.0)];
    let x = [[0.1, 0.2, 0.3], [1.0, -1.0, 2.0]];
    let v = [[1.0, 2.0, 3.0], [-1.0, 0.5, 0.0]];
    let sys = System::new(p.to_vec())
        .unwrap()
        .with(External::new(UniformGravity { g: 9.81 }, [0, 1]))
        .unwrap()
        .with(External::new(
            FixedEnd::new(Spring { k: 4.0, re: 0.0 }, [1.0, 1.0, 1.0]),
            [1],
        ))
        .unwrap()
        .with(ExternalForce::new(LinearDrag { b: 0.5 }, [0]))
        .unwrap()
        .with(InternalForce::new(CentralForce { k: 1.0, n: -1.0 }, [(0, 1)]))
        .unwrap();
    let mut f = vec![0.0; 6];
    sys.forces(0.0, &x.concat(), &v.concat(), &mut f).unwrap();
    // Central force 1/r on particle 1 (on) from particle 0 (by): r̂/r; −that on particle 0.
    let r = [0.9, -1.2, 1.7];
    let d2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    let c = r.map(|a| a / d2);
    let want0 = [
        0.0 - 0.5 * 1.0 - c[0],
        -0.5 * 2.0 - c[1],
        -2.0 * 9.81 - 0.5 * 3.0 - c[2],
    ];
    let want1 = [
        -4.0 * (1.0 - 1.0) + c[0],
        -4.0 * (-1.0 - 1.0) + c[1],
        -3.0 * 9.81 - 4.0 * (2.0 - 1.0) + c[2],
    ];
    close([f[0], f[1], f[2]], want0, 1e-14);
    close([f[3], f[4], f[5]], want1, 1e-14);
}

/// A user-defined potential in generic code: U = a r⁴ (forces by duals), F21 = −4 a r² r21.
#[test]
fn ad_vs_hand_user_potential() {
    struct Quartic(f64);
    impl PairPotential for Quartic {
        fn energy<D: Scalar>(&self, r: [D; 3], _: &Particle, _: &Particle) -> D {
            let s = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
            s * s * self.0
        }
    }
    let r = [0.5, 1.5, -0.25];
    let s = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    close(
        f21(Quartic(0.7), r, [1.0; 2], [0.0; 2]),
        r.map(|c| -4.0 * 0.7 * s * c),
        1e-14,
    );
}

fn random_system(n: usize, seed: u64) -> (System<impl noether_particles::Interaction>, Vec<Vec3>) {
    let mut rng = StdRng::seed_from_u64(seed);
    let ps: Vec<Particle> = (0..n)
        .map(|_| Particle::new(rng.random_range(0.5..2.0)))
        .collect();
    let springs: Vec<(usize, usize)> = (0..2 * n)
        .map(|_| {
            let i = rng.random_range(0..n);
            (i, (i + rng.random_range(1..n)) % n)
        })
        .collect();
    let sys = System::new(ps)
        .unwrap()
        .with(Internal::new(Spring { k: 1.3, re: 0.7 }, springs.clone()))
        .unwrap()
        .with(Internal::new(GaussianCoupling { k2: 0.2, sigma: 0.5 }, springs))
        .unwrap()
        .with(AllPairs::new(Gravity { g: 0.01 }))
        .unwrap();
    (sys, random_positions(n, 3.0, &mut rng))
}

/// Third law: the internal forces of any system add up to zero (to rounding of the sum).
#[test]
fn conserves_momentum_forces_sum_to_zero() {
    let (sys, x) = random_system(30, 1);
    let (_, f) = forces_of(&sys, &x);
    let scale: f64 = f.iter().map(|a| a.abs()).sum();
    for k in 0..3 {
        let s: f64 = f.iter().skip(k).step_by(3).sum();
        assert!(s.abs() < 1e-14 * scale, "Σ F_{k} = {s}");
    }
}

/// The system as a core Lagrangian (generic AD path through EulerLagrange) gives the same
/// accelerations as the term-by-term forces, drag included.
#[test]
fn ad_vs_ad_lagrangian_path_matches_term_by_term() {
    let mut rng = StdRng::seed_from_u64(2);
    let n = 6;
    let ps: Vec<Particle> = (0..n).map(|i| Particle::new(1.0 + i as f64)).collect();
    let sys = System::new(ps)
        .unwrap()
        .with(Internal::chain(Spring { k: 3.0, re: 0.5 }, n))
        .unwrap()
        .with(AllPairs::new(LennardJones::new(0.1, 0.8)))
        .unwrap()
        .with(External::new(
            Trap {
                k2: 0.5,
                k4: 0.1,
                center: [0.0; 3],
            },
            0..n,
        ))
        .unwrap()
        .with(ExternalForce::new(LinearDrag { b: 0.3 }, [1, 2]))
        .unwrap();
    let x = random_positions(n, 2.0, &mut rng).concat();
    let v = random_positions(n, 1.0, &mut rng).concat();
    let mut a1 = vec![0.0; 3 * n];
    let mut a2 = vec![0.0; 3 * n];
    EulerLagrange::new(&sys)
        .accelerations(0.0, &x, &v, &mut a1)
        .unwrap();
    sys.accelerations(0.0, &x, &v, &mut a2).unwrap();
    for k in 0..3 * n {
        assert!(
            (a1[k] - a2[k]).abs() < 1e-11 * (1.0 + a2[k].abs()),
            "{k}: {} {}",
            a1[k],
            a2[k]
        );
    }
}

/// V of the system as an AD field, for the dense reference Hessian.
struct PotentialField<'a, I>(&'a System<I>);
impl<I: noether_particles::Interaction> Field for PotentialField<'_, I> {
    fn eval<D: Scalar>(&self, t: D, x: &[D], _y: &[D]) -> D {
        let zero = vec![D::zero(); x.len()];
        -self.0.lagrangian(t, x, &zero)
    }
}

/// The sparse term-by-term Hessian equals core's dense AD Hessian of V; a chain stores O(N) entries.
#[test]
fn ad_vs_ad_sparse_hessian_matches_dense() {
    let (sys, x) = random_system(8, 3);
    let x = x.concat();
    let h = sys.hessian(0.0, &x).unwrap();
    let mut dense = nalgebra::DMatrix::zeros(24, 24);
    ad::hessian(
        &PotentialField(&sys),
        0.0,
        &x,
        &[],
        Block::X,
        Block::X,
        &mut dense,
    );
    let d = h.to_dense();
    assert!((d - &dense).amax() < 1e-10 * dense.amax());

    let n = 1000;
    let chain = System::new(vec![Particle::new(1.0); n])
        .unwrap()
        .with(Internal::chain(Spring { k: 1.0, re: 1.0 }, n))
        .unwrap();
    let xs: Vec<f64> = (0..n)
        .flat_map(|i| [i as f64 * 1.1, 0.01 * i as f64, 0.0])
        .collect();
    let h = chain.hessian(0.0, &xs).unwrap();
    assert_eq!(h.nnz(), 9 * (n + 2 * (n - 1)));
}

/// The cell list finds exactly the pairs within the cutoff: same energy and forces as all pairs.
#[test]
fn regress_cell_list_matches_all_pairs() {
    let mut rng = StdRng::seed_from_u64(4);
    let n = 400;
    let x = random_positions(n, 8.0, &mut rng);
    let lj = LennardJones::with_cutoff(1.0, 1.0, 2.5);
    let a = System::new(vec![Particle::new(1.0); n])
        .unwrap()
        .with(AllPairs::new(lj))
        .unwrap()
        .parallel(Parallel::Serial);
    let b = System::new(vec![Particle::new(1.0); n])
        .unwrap()
        .with(ShortRange::new(lj).unwrap())
        .unwrap();
    let (ea, fa) = forces_of(&a, &x);
    let (eb, fb) = forces_of(&b, &x);
    assert!((ea - eb).abs() < 1e-10 * ea.abs().max(1.0));
    let scale = fa.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for k in 0..3 * n {
        assert!((fa[k] - fb[k]).abs() < 1e-10 * scale);
    }
    assert!((b.potential_energy(0.0, &x.concat()).unwrap() - eb).abs() < 1e-10 * eb.abs());
}

fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

/// Serial and parallel force evaluations agree bit for bit, for 1, 2 and 3 threads.
#[test]
fn regress_parallel_is_bit_identical() {
    let mut rng = StdRng::seed_from_u64(5);
    let n = 6000;
    let x = random_positions(n, 20.0, &mut rng);
    let build = |par| {
        System::new(vec![Particle::new(1.0); n])
            .unwrap()
            .with(Internal::chain(Spring { k: 1.0, re: 0.5 }, n))
            .unwrap()
            .with(External::new(
                Trap {
                    k2: 0.1,
                    k4: 0.01,
                    center: [10.0; 3],
                },
                0..n,
            ))
            .unwrap()
            .with(ShortRange::new(LennardJones::with_cutoff(0.5, 0.8, 2.0)).unwrap())
            .unwrap()
            .parallel(par)
    };
    let serial = forces_of(&build(Parallel::Serial), &x);
    for threads in [1, 2, 3] {
        let par = in_pool(threads, || forces_of(&build(Parallel::Rayon), &x));
        assert_eq!(serial.0.to_bits(), par.0.to_bits(), "energy, {threads} threads");
        assert!(serial
            .1
            .iter()
            .zip(&par.1)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
    }
    let m = 300;
    let y = random_positions(m, 5.0, &mut rng);
    let grav = |par| {
        System::new(vec![Particle::new(1.0); m])
            .unwrap()
            .with(AllPairs::new(Gravity { g: 1.0 }))
            .unwrap()
            .parallel(par)
    };
    let serial = forces_of(&grav(Parallel::Serial), &y);
    let par = in_pool(3, || forces_of(&grav(Parallel::Rayon), &y));
    assert_eq!(serial.0.to_bits(), par.0.to_bits());
    assert!(serial
        .1
        .iter()
        .zip(&par.1)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
}

/// A chain listed as consecutive pairs and one-body terms on a range of particles take the streaming
/// serial path: bit-identical to the parallel path (which applies the list), and equal to rounding
/// (1e-14 relative: a few ulps of the summed forces) to the same terms listed in another order.
#[test]
fn regress_streaming_chain_matches_list() {
    let mut rng = StdRng::seed_from_u64(11);
    let n = 12;
    let x = random_positions(n, 3.0, &mut rng);
    let spring = Spring { k: 1.3, re: 0.7 };
    let trap = Trap {
        k2: 0.4,
        k4: 0.05,
        center: [1.0, -0.5, 0.2],
    };
    let build = |pairs: Vec<(usize, usize)>, sites: Vec<usize>, par| {
        System::new(vec![Particle::new(1.0); n])
            .unwrap()
            .with(Internal::new(spring, pairs))
            .unwrap()
            .with(External::new(trap, sites))
            .unwrap()
            .parallel(par)
    };
    // Pairs (3,4) … (8,9) and sites 2 … 6: a chain and a range away from both ends.
    let chain: Vec<_> = (3..9).map(|i| (i, i + 1)).collect();
    let sites: Vec<_> = (2..7).collect();
    let streaming = forces_of(&build(chain.clone(), sites.clone(), Parallel::Serial), &x);
    let listed = in_pool(2, || {
        forces_of(&build(chain.clone(), sites.clone(), Parallel::Rayon), &x)
    });
    assert_eq!(streaming.0.to_bits(), listed.0.to_bits());
    assert!(streaming
        .1
        .iter()
        .zip(&listed.1)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    // The same terms in reverse order, each pair reversed (U is symmetric): the list path.
    let reversed: Vec<_> = chain.iter().rev().map(|&(i, j)| (j, i)).collect();
    let other = forces_of(
        &build(reversed, sites.iter().rev().copied().collect(), Parallel::Serial),
        &x,
    );
    assert!((streaming.0 - other.0).abs() <= 1e-14 * other.0.abs());
    for (p, (a, b)) in streaming.1.chunks(3).zip(other.1.chunks(3)).enumerate() {
        close([a[0], a[1], a[2]], [b[0], b[1], b[2]], 1e-14);
        let touched = (2..=9).contains(&p);
        assert_eq!(a.iter().any(|v| *v != 0.0), touched, "particle {p}");
    }
}

/// Orders of the methods on a spring pair (reduced mass μ = ½, ω = sqrt(k/μ)): the closed form
/// r(t) = re + A cos ωt; the error ratio between h and h/2 is 2^order (tolerance: ±0.3 on the order).
#[test]
fn order_of_methods_on_spring_pair() {
    let sys = System::new(vec![Particle::new(1.0); 2])
        .unwrap()
        .with(Internal::new(Spring { k: 2.0, re: 1.0 }, [(0, 1)]))
        .unwrap();
    let w = 2.0_f64; // sqrt(k/μ) = sqrt(2/0.5)
    let t_end = 2.0;
    let exact = 1.0 + 0.2 * (w * t_end).cos();
    for m in [
        Method::Euler,
        Method::EulerCromer,
        Method::Rk4,
        Method::VelocityVerlet,
        Method::Yoshida4,
    ] {
        let err = |h: f64| {
            let s0 = sys.state_1d(0.0, &[0.0, 1.2], &[0.0, 0.0]).unwrap();
            let n = (t_end / h).round() as usize;
            let s = sys.run(m, s0, h, n).unwrap();
            (s.q[3] - s.q[0] - exact).abs()
        };
        let h = if m.order() >= 4 { 0.05 } else { 0.01 };
        let p = (err(h) / err(h / 2.0)).log2();
        assert!((p - m.order() as f64).abs() < 0.3, "{m:?}: observed order {p}");
    }
}

/// The evolver yields the sequence of states; the symplectic method keeps the energy bounded.
#[test]
fn conserves_energy_velocity_verlet_evolver() {
    let sys = System::new(vec![Particle::new(1.0); 3])
        .unwrap()
        .with(Internal::chain(Spring { k: 1.0, re: 1.0 }, 3))
        .unwrap();
    let s0 = sys
        .state_2d(
            0.0,
            &[[0.0, 0.0], [1.2, 0.1], [2.0, 0.0]],
            &[[0.0, 0.3], [0.0; 2], [0.1, 0.0]],
        )
        .unwrap();
    let e0 = sys.total_energy(&s0).unwrap();
    let mut worst = 0.0_f64;
    for s in sys
        .evolver(Method::VelocityVerlet, s0, 0.01)
        .unwrap()
        .take(20_000)
    {
        let s = s.unwrap();
        worst = worst.max((sys.total_energy(&s).unwrap() - e0).abs());
        assert_eq!(s.q[2], 0.0); // 2D stays 2D
    }
    // Verlet's modified energy: |ΔE| ~ (h ω)² E / 8-ish, far below 1e-4 E here.
    assert!(worst < 1e-4 * e0, "{worst}");
}

#[test]
fn bad_input_unknown_index_self_interaction_mass() {
    let ps = vec![Particle::new(1.0); 3];
    let e = System::new(ps.clone())
        .unwrap()
        .with(Internal::new(Spring { k: 1.0, re: 1.0 }, [(0, 3)]));
    assert!(matches!(
        e.err(),
        Some(Error::UnknownParticle { index: 3, n: 3, .. })
    ));
    let e = System::new(ps.clone())
        .unwrap()
        .with(External::new(UniformGravity { g: 1.0 }, [5]));
    assert!(matches!(e.err(), Some(Error::UnknownParticle { index: 5, .. })));
    let e = System::new(ps.clone())
        .unwrap()
        .with(Internal::new(Gravity { g: 1.0 }, [(0, 1), (2, 2)]));
    assert!(matches!(
        e.err(),
        Some(Error::SelfInteraction {
            interaction: 1,
            index: 2
        })
    ));
    for m in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = System::new(vec![Particle::new(1.0), Particle::new(m)]);
        assert!(
            matches!(e.err(), Some(Error::InvalidMass { index: 1, .. })),
            "mass {m}"
        );
    }
    let e = ShortRange::new(LennardJones::new(1.0, 1.0));
    assert!(matches!(
        e.err(),
        Some(Error::Core(noether_core::Error::InvalidParameter { .. }))
    ));
}

#[test]
fn bad_input_coincident_particles_reported_not_nan() {
    let sys = System::new(vec![Particle::new(1.0); 3])
        .unwrap()
        .with(AllPairs::new(Gravity { g: 1.0 }))
        .unwrap();
    let x = [[0.0; 3], [1.0, 2.0, 3.0], [1.0, 2.0, 3.0]];
    let mut f = vec![0.0; 9];
    let e = sys.potential_forces(0.0, &x.concat(), &mut f);
    assert_eq!(
        e,
        Err(Error::Coincident {
            a: 1,
            b: 2,
            distance: 0.0
        })
    );
    // A step from that state fails and leaves the state unchanged.
    let mut s = sys.state(0.0, &x, &[[0.0; 3]; 3]).unwrap();
    let before = s.clone();
    assert!(sys.step(Method::VelocityVerlet, &mut s, 0.1).is_err());
    assert_eq!(s, before);
    // Through core's Dynamics interface too, with the indices kept (issue 15, case 10: the stepping
    // path used to report `InvalidParameter { "|r21|", 0 }`).
    for m in [Method::Euler, Method::EulerCromer, Method::Rk4, Method::Yoshida4] {
        let mut st = noether_particles::ParticleStepper::new(&sys, m);
        let e = noether_core::Stepper::step(&mut st, &mut s, 0.1).unwrap_err();
        assert_eq!(
            Error::from(e),
            Error::Coincident {
                a: 1,
                b: 2,
                distance: 0.0
            },
            "{m:?}"
        );
        assert_eq!(s, before);
    }
}

/// Issue 15, case 10: a law with a NaN parameter was reported as two coincident particles.
#[test]
fn regress_nan_parameter_is_not_a_coincidence() {
    let sys = System::new(vec![Particle::new(1.0); 2])
        .unwrap()
        .with(AllPairs::new(Gravity { g: f64::NAN }))
        .unwrap();
    let x = [[0.0; 3], [0.0, 2.0, 0.0]].concat();
    let mut f = vec![0.0; 6];
    let expected = Error::NonFiniteInteraction {
        a: 0,
        b: 1,
        distance: 2.0,
    };
    assert_eq!(sys.potential_forces(0.0, &x, &mut f), Err(expected.clone()));
    assert_eq!(sys.potential_energy(0.0, &x), Err(expected));
}

/// Issue 15, case 10: a mass of 5e-324 was accepted (1/m = ∞) and failed later as non-finite
/// positions; kinetic energy and momentum truncated a velocity vector of the wrong length; an empty
/// system had a NaN centre of mass.
#[test]
fn regress_tiny_mass_wrong_lengths_and_empty_system() {
    assert!(matches!(
        System::new(vec![Particle::new(1.0), Particle::new(5e-324)]),
        Err(Error::InvalidMass { index: 1, .. })
    ));
    let sys = System::new(vec![Particle::new(2.0); 2]).unwrap();
    let dim = |r: Result<f64, Error>| {
        assert!(
            matches!(r, Err(Error::Core(noether_core::Error::Dimension { .. }))),
            "{r:?}"
        )
    };
    dim(sys.kinetic_energy(&[1.0; 5]));
    dim(sys.momentum(&[1.0; 7]).map(|p| p[0]));
    dim(sys.angular_momentum(&[1.0; 6], &[1.0; 3]).map(|l| l[0]));
    dim(sys.centre_of_mass(&[1.0; 3]).map(|c| c[0]));
    // T = 2 · ½ · 2 · 3 = 6 for unit velocity components: exact.
    assert_eq!(sys.kinetic_energy(&[1.0; 6]), Ok(6.0));
    let empty = System::new(vec![]).unwrap();
    assert_eq!(
        empty.centre_of_mass(&[]),
        Err(Error::Empty {
            what: "centre of mass"
        })
    );
}

/// Issue 15, case 9: the cell list panicked (integer overflow of the cell counts) with one particle
/// far away (x = 1e20) or all at huge coordinates. Forces are now computed: only the near pair
/// interacts, and the two forces are opposite (third law).
#[test]
fn regress_cell_list_far_and_huge_coordinates() {
    let sys = System::new(vec![Particle::new(1.0); 3])
        .unwrap()
        .with(ShortRange::new(LennardJones::with_cutoff(1.0, 1.0, 2.5)).unwrap())
        .unwrap();
    for offset in [0.0, 1e20] {
        let x = [
            [offset, 0.0, 0.0],
            [offset + 1.1, 0.0, 0.0],
            [offset + 1e20, 0.0, 0.0],
        ]
        .concat();
        let mut f = vec![0.0; 9];
        let r = sys.potential_forces(0.0, &x, &mut f);
        if offset == 0.0 {
            r.unwrap();
            assert!(f[0] != 0.0 && f[0] == -f[3], "{f:?}");
            assert_eq!(&f[6..], &[0.0; 3]);
        } else {
            // At 1e20 the spacing 1.1 is below the coordinates' resolution (ulp 16384): the two
            // near particles coincide in f64, which is what the error says.
            assert!(matches!(r, Err(Error::Coincident { a: 0, b: 1, .. })), "{r:?}");
        }
    }
}

#[test]
fn bad_input_dimensions_nonfinite_step_and_drag_with_verlet() {
    let sys = System::new(vec![Particle::new(1.0); 2])
        .unwrap()
        .with(Internal::new(Spring { k: 1.0, re: 1.0 }, [(0, 1)]))
        .unwrap();
    assert!(matches!(
        sys.state(0.0, &[[0.0; 3]], &[[0.0; 3]; 2]),
        Err(Error::Core(noether_core::Error::Dimension { .. }))
    ));
    assert!(matches!(
        sys.state(0.0, &[[0.0; 3], [f64::NAN, 0.0, 0.0]], &[[0.0; 3]; 2]),
        Err(Error::Core(noether_core::Error::NonFinite { .. }))
    ));
    let mut f = vec![0.0; 5];
    assert!(sys.potential_forces(0.0, &[0.0; 6], &mut f).is_err());
    let mut s = sys.state_1d(0.0, &[0.0, 1.5], &[0.0, 0.0]).unwrap();
    for h in [0.0, -0.1, f64::NAN] {
        assert!(matches!(
            sys.step(Method::Euler, &mut s, h),
            Err(Error::Core(noether_core::Error::InvalidStep { .. }))
        ));
    }
    let drag = System::new(vec![Particle::new(1.0)])
        .unwrap()
        .with(ExternalForce::new(LinearDrag { b: 1.0 }, [0]))
        .unwrap();
    let mut s = drag.state(0.0, &[[0.0; 3]], &[[1.0, 0.0, 0.0]]).unwrap();
    assert!(matches!(
        drag.step(Method::Yoshida4, &mut s, 0.1),
        Err(Error::Core(noether_core::Error::Unsupported(_)))
    ));
    // RK4 handles drag: v(t) = v0 e^{−bt/m}.
    let s = drag.run(Method::Rk4, s, 0.01, 100).unwrap();
    assert!((s.v[0] - (-1.0_f64).exp()).abs() < 1e-9);
}

/// The radial fast path (one `Dual64` in |r|²) agrees with the 3-slot dual path of the same law.
#[test]
fn ad_vs_ad_radial_path_matches_vector_path() {
    struct Vector<P>(P);
    impl<P: PairPotential> PairPotential for Vector<P> {
        fn energy<D: Scalar>(&self, r: [D; 3], p1: &Particle, p2: &Particle) -> D {
            self.0.energy(r, p1, p2)
        }
    }
    fn both<P: PairPotential + Copy>(pot: P) {
        let (p1, p2) = (Particle::charged(2.0, 1.0), Particle::charged(3.0, -0.5));
        let r = [0.6, -0.3, 0.9];
        let (u, g) = noether_particles::potential::pair_gradient(&pot, r, &p1, &p2);
        let (v, h) = noether_particles::potential::pair_gradient(&Vector(pot), r, &p1, &p2);
        assert!((u - v).abs() <= 1e-14 * u.abs().max(1e-300));
        close(g, h, 1e-14);
    }
    both(Gravity { g: 1.5 });
    both(Coulomb { k: 2.0 });
    both(ConstantRepulsion { f: 0.7 });
    both(Spring { k: 2.0, re: 0.4 });
    both(Spring { k: 2.0, re: 0.0 });
    both(Billiard { k: 5.0, re: 1.5 });
    both(LennardJones::new(1.0, 0.9));
    both(LennardJones::with_cutoff(1.0, 0.9, 2.0));
    both(GaussianCoupling { k2: 0.4, sigma: 0.6 });
}

/// The centred one-body fast path agrees with the 3-slot dual path (trap, spring to a wall, gravity).
#[test]
fn ad_vs_ad_centred_one_body_path_matches_vector_path() {
    struct Vector<P>(P);
    impl<P: OnePotential> OnePotential for Vector<P> {
        fn energy<D: Scalar>(&self, t: f64, r: [D; 3], p: &Particle) -> D {
            self.0.energy(t, r, p)
        }
    }
    fn both<P: OnePotential + Copy>(pot: P) {
        let p = Particle::new(2.0);
        let r = [0.6, -0.3, 0.9];
        let (u, g) = noether_particles::potential::one_gradient(&pot, 0.0, r, &p);
        let (v, h) = noether_particles::potential::one_gradient(&Vector(pot), 0.0, r, &p);
        assert!((u - v).abs() <= 1e-14 * u.abs());
        close(g, h, 1e-14);
    }
    both(Trap {
        k2: 0.7,
        k4: 0.2,
        center: [0.1, 0.2, -0.3],
    });
    both(FixedEnd::new(Spring { k: 3.0, re: 0.5 }, [1.0, -1.0, 0.5]));
    both(FixedEnd::new(Gravity { g: 2.0 }, [1.0, -1.0, 0.5]));
}

/// Core's Runge-Kutta-Nyström pairs step a particle system (q̈ = f(q), a split system with q̇ = v). Two
/// equal masses (m = 1, G = 1, total mass M = 2) on a relative Kepler orbit with a = 1, e = 0.6, from
/// pericentre: separation 1 − e = 0.4, relative speed √(GM(1 + e)/(a(1 − e))) = √8 (each particle √2
/// about the centre of mass); both return to their start after one period T = 2π√(a³/(GM)) = π√2.
#[test]
fn closed_form_nystrom_on_particles() {
    use noether_core::integrators::{Dprkn12, Dprkn8};
    use noether_core::{Driver, Save};
    let sys = System::new(vec![Particle::new(1.0); 2])
        .unwrap()
        .with(AllPairs::new(Gravity { g: 1.0 }))
        .unwrap();
    let v = 2f64.sqrt();
    let start = sys
        .state(
            0.0,
            &[[-0.2, 0.0, 0.0], [0.2, 0.0, 0.0]],
            &[[0.0, -v, 0.0], [0.0, v, 0.0]],
        )
        .unwrap();
    let period = std::f64::consts::PI * 2f64.sqrt();
    let back = |sol: noether_core::Solution| {
        let end = sol.last();
        end.q
            .iter()
            .zip(start.q.iter())
            .chain(end.v.iter().zip(start.v.iter()))
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
    };
    let run8 = Driver::new(
        Dprkn8::new(&sys).unwrap().tolerances(1e-10, 1e-10).unwrap(),
        start.clone(),
    )
    .unwrap()
    .save(Save::End)
    .unwrap()
    .run_until(period)
    .unwrap();
    let run12 = Driver::new(
        Dprkn12::new(&sys).unwrap().tolerances(1e-10, 1e-10).unwrap(),
        start.clone(),
    )
    .unwrap()
    .save(Save::End)
    .unwrap()
    .run_until(period)
    .unwrap();
    // Measured at tolerances 1e-10: 1.38e-10 (DPRKN8) and 1.29e-11 (DPRKN12); bounds ~3× those.
    let (e8, e12) = (back(run8), back(run12));
    eprintln!("DPRKN8 {e8:.2e}, DPRKN12 {e12:.2e}");
    assert!(e8 < 4e-10 && e12 < 4e-11, "{e8:e} {e12:e}");
}

/// Core's IAS15 on a particle system, one block of 3 coordinates per particle (as REBOUND groups
/// them): two bodies of mass ½ under G = 1 move so that r = x₂ − x₁ follows a Kepler ellipse with
/// μ = G(m₁ + m₂) = 1, a = 1, e = 0.6 (period 2π). Over 10 periods at the default ε = 1e-9 the
/// relative vector returns to its start and the energy holds to machine precision: measured
/// |r(20π) − r₀| = 8.1e-14 (579 steps; rounding decides its size, checked to 5e-13) and
/// |ΔE| = 2.2e-16 (E = −1/8 is the sum of terms of size 0.5 at pericentre, whose ulp is 1.1e-16).
#[test]
fn closed_form_ias15_two_body_kepler() {
    use noether_core::prelude::{Driver, Ias15, Save};
    let e = 0.6_f64;
    let sys = System::new(vec![Particle::new(0.5); 2])
        .unwrap()
        .with(AllPairs::new(Gravity { g: 1.0 }))
        .unwrap();
    let (x, v) = ((1.0 - e) / 2.0, ((1.0 + e) / (1.0 - e)).sqrt() / 2.0);
    let s0 = sys
        .state(
            0.0,
            &[[-x, 0.0, 0.0], [x, 0.0, 0.0]],
            &[[0.0, -v, 0.0], [0.0, v, 0.0]],
        )
        .unwrap();
    let e0 = sys.total_energy(&s0).unwrap();
    let ias = Ias15::new(&sys).unwrap().block_size(3).unwrap();
    let sol = Driver::new(ias, s0.clone())
        .unwrap()
        .save(Save::End)
        .unwrap()
        .run_until(20.0 * std::f64::consts::PI)
        .unwrap();
    let end = sol.last();
    let r = |q: &[f64]| [q[3] - q[0], q[4] - q[1], q[5] - q[2]];
    let (r0, r1) = (r(s0.q.as_slice()), r(end.q.as_slice()));
    let closure = (0..3).map(|i| (r1[i] - r0[i]).abs()).fold(0.0, f64::max);
    let de = (sys.total_energy(end).unwrap() - e0).abs();
    eprintln!(
        "IAS15 two bodies, 10 periods: |r − r₀| {closure:.1e}, |ΔE| {de:.1e}, {:?}",
        sol.stats()
    );
    assert!(closure < 5e-13 && de < 1e-15, "{closure:e} {de:e}");
}

/// Issue 29 item 6: a NaN position under a short-range law returned Ok(0.0) (the cell list found no
/// pair for it, so nothing was NaN). Now it is `NonFinite` naming the position, as under every other
/// interaction, and the energy too.
#[test]
fn regress_short_range_nan_position_is_an_error() {
    let sys = System::new(vec![Particle::new(1.0); 3])
        .unwrap()
        .with(ShortRange::new(LennardJones::with_cutoff(1.0, 1.0, 2.5)).unwrap())
        .unwrap();
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for k in 0..9 {
            let mut x = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [5.0, 0.0, 0.0]].concat();
            x[k] = bad;
            let mut f = vec![0.0; 9];
            let r = sys.potential_forces(0.0, &x, &mut f);
            assert!(
                matches!(r, Err(Error::Core(noether_core::Error::NonFinite { index, .. })) if index == k),
                "x[{k}] = {bad}: {r:?}"
            );
            assert!(sys.potential_energy(0.0, &x).is_err());
            let mut a = vec![0.0; 9];
            assert!(sys.accelerations(0.0, &x, &[0.0; 9], &mut a).is_err());
        }
    }
}

/// Issue 29 item 11: particles at ±1e308 made the cell list's extent overflow (a panic), and
/// `CellList::build` with a cutoff of 0, NaN or −1 indexed out of bounds. Now the far particles are
/// gridded at half scale (they are 2e308 apart: no pair, zero forces), and a bad cutoff or position
/// is a typed error.
#[test]
fn regress_cell_list_at_the_ends_of_f64_and_bad_cutoffs() {
    let sys = System::new(vec![Particle::new(1.0); 4])
        .unwrap()
        .with(ShortRange::new(LennardJones::with_cutoff(1.0, 1.0, 2.5)).unwrap())
        .unwrap();
    for (a, b) in [
        (-1e308, 1e308),
        (-f64::MAX, f64::MAX),
        (0.0, f64::MAX),
        (-f64::MAX, 1.0),
    ] {
        // Two far particles and a near pair next to one of them.
        let x = [[a, 0.0, 0.0], [b, 0.0, 0.0], [b, 1.0, 0.0], [b, 2.2, 0.0]].concat();
        let mut f = vec![7.0; 12];
        let e = sys.potential_forces(0.0, &x, &mut f).unwrap();
        let (e12, e23) = (lj(1.0), lj(1.2));
        assert_eq!(&f[..3], &[0.0; 3], "the lone far particle at {a}");
        assert!(f.iter().all(|c| c.is_finite()));
        // Particles 1, 2, 3: pairs (1,2) at 1.0 and (2,3) at 1.2 (1,3 at 2.2 < 2.5 too).
        let e13 = lj(2.2);
        assert!(
            (e - (e12 + e23 + e13)).abs() < 1e-12,
            "{e} vs {}",
            e12 + e23 + e13
        );
        assert_eq!(sys.potential_energy(0.0, &x).unwrap().to_bits(), e.to_bits());
        let mut cells = CellList::default();
        cells.build(&x, 2.5).unwrap();
        assert!(cells.cells() >= 1);
    }
    let x = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]].concat();
    let mut cells = CellList::default();
    for rc in [0.0, -1.0, f64::NAN, f64::INFINITY, -0.0] {
        let r = cells.build(&x, rc);
        assert!(
            matches!(r, Err(Error::Core(noether_core::Error::InvalidParameter { .. }))),
            "cutoff {rc}: {r:?}"
        );
    }
    assert!(matches!(
        cells.build(&[0.0, f64::NAN, 0.0], 1.0),
        Err(Error::Core(noether_core::Error::NonFinite { index: 1, .. }))
    ));
    assert!(matches!(
        cells.build(&[0.0; 4], 1.0),
        Err(Error::Core(noether_core::Error::Dimension { .. }))
    ));
    assert_eq!(
        cells.cells(),
        0,
        "a failed build leaves the list as it was (empty)"
    );
    cells.build(&x, 5e-324).unwrap();
    cells.build(&x, 1e308).unwrap();
    assert_eq!(cells.cells(), 1);
}

/// The truncated and shifted Lennard-Jones energy of `LennardJones::with_cutoff(1.0, 1.0, 2.5)`.
fn lj(r: f64) -> f64 {
    let u = |r: f64| r.powi(-12) - 2.0 * r.powi(-6);
    u(r) - u(2.5)
}
