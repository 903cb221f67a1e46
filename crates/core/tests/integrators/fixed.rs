//! Regressions of issue 16 (item 1): the fixed-size loop of `Composition` for systems of up to six
//! coordinates (q, v and the force in arrays, the kernel of `Natural` inlined) performs the same
//! operations in the same order as the general loop, so its result is the same to the bit. The
//! reference below is that general loop written out with `kick_rate` on vectors: kicks of a_i h and
//! drifts of b_i h, adjacent half kicks merged (`kicks` are the a_i, `coefficients` the b_i).

use noether_core::integrators::{Composition, SplitDynamics};
use noether_core::prelude::*;

/// Hénon-Heiles, V = ½(x² + y²) + x²y − y³/3.
struct HenonHeiles;
impl Potential for HenonHeiles {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        let (x, y) = (q[0], q[1]);
        (x * x + y * y) * 0.5 + x * x * y - y * y * y / 3.0
    }
}

/// `steps` Kahan-Li 8 steps of size h by the general algorithm on vectors.
fn reference<S: SplitDynamics>(
    sys: &S,
    gammas: &[f64],
    q: &[f64],
    v: &[f64],
    h: f64,
    steps: usize,
) -> (Vec<f64>, Vec<f64>) {
    let mut kicks = vec![0.0; gammas.len() + 1];
    for (i, g) in gammas.iter().enumerate() {
        kicks[i] += 0.5 * g;
        kicks[i + 1] += 0.5 * g;
    }
    let (mut q, mut v, mut f) = (q.to_vec(), v.to_vec(), vec![0.0; q.len()]);
    sys.kick_rate(&q, &mut f).unwrap();
    for _ in 0..steps {
        for (a, b) in kicks.iter().zip(gammas) {
            let c = a * h;
            v.iter_mut().zip(&f).for_each(|(v, f)| *v += c * f);
            let c = b * h;
            q.iter_mut().zip(&v).for_each(|(q, v)| *q += c * v);
            sys.kick_rate(&q, &mut f).unwrap();
        }
        let c = kicks[gammas.len()] * h;
        v.iter_mut().zip(&f).for_each(|(v, f)| *v += c * f);
    }
    (q, v)
}

/// The fixed-size loop against the reference, for a diagonal and a dense mass matrix (the dense
/// one takes the kernel's general path inside the fixed loop).
#[test]
fn regress_composition_fixed_loop_same_bits() {
    let dense = nalgebra::DMatrix::from_row_slice(2, 2, &[2.0, 0.3, 0.3, 1.0]);
    let systems = [
        ("unit", Natural::unit(HenonHeiles)),
        ("diagonal", Natural::diagonal(HenonHeiles, &[1.0, 2.5]).unwrap()),
        ("dense", Natural::dense(HenonHeiles, dense).unwrap()),
    ];
    let (q0, v0, h, steps) = ([0.1, 0.0], [0.0, 0.5], 0.01, 200);
    for (name, sys) in &systems {
        let mut kl8 = Composition::kahan_li8(sys);
        let gammas = kl8.coefficients().to_vec();
        let mut s = State::new(0.0, q0, v0);
        for _ in 0..steps {
            kl8.step(&mut s, h).unwrap();
        }
        let (q, v) = reference(sys, &gammas, &q0, &v0, h, steps);
        assert_eq!(s.q.as_slice(), q.as_slice(), "{name}: q");
        assert_eq!(s.v.as_slice(), v.as_slice(), "{name}: q̇");
        // And the run moved: 200 steps of 0.01 on an orbit of period ≈ 2π.
        assert!((s.q[0] - q0[0]).abs() > 1e-2, "{name}");
    }
}
