//! Canonical transformations given as maps: the symplectic condition, the inverse by Newton, and the
//! new Hamiltonian of a time-dependent map (the rotating frame).

use crate::common::{Planar, Rng};
use noether_canonical::transform::{self, canonicity, invert, new_hamiltonian_defect, CanonicalMap};
use noether_core::Scalar;
use noether_testkit::canonical::{Polar, Rotating, RotatingK};

/// Polar coordinates are canonical: ‖JᵀΩJ − Ω‖ and ‖{Z, Z} − Ω‖ at 200 random points with r ∈
/// [0.3, 2.8], |p| ≲ 2.8. Measured worst 1.8e-15 (Jacobian entries of size up to |p|/r ~ 10, their
/// products rounded); tolerance 4e-15.
#[test]
fn closed_form_polar_is_symplectic() {
    let mut rng = Rng(41);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let (r, th) = (rng.uniform(0.3, 2.8), rng.uniform(-3.0, 3.0));
        let q = [r * th.cos(), r * th.sin()];
        let p = rng.vec(2, -2.0, 2.0);
        let c = canonicity(&Polar, 0.0, &q, &p).unwrap();
        worst = worst.max(c.symplectic).max(c.brackets);
        // The map itself against the closed form.
        let (nq, np) = transform::apply(&Polar, 0.0, &q, &p).unwrap();
        assert!((nq[0] - r).abs() <= 4e-16 * r && (nq[1] - th).abs() <= 1e-15);
        assert!((np[1] - (q[0] * p[1] - q[1] * p[0])).abs() <= 1e-15);
    }
    assert!(worst <= 8e-15, "{worst:e}");
}

/// A map that is not canonical is told apart: Q = 2q, P = p has JᵀΩJ − Ω = [[0, 1], [−1, 0]]
/// (closed form: defect exactly 1) and {Q, P} = 2.
#[test]
fn closed_form_scaling_is_not_canonical() {
    struct Stretch;
    impl CanonicalMap for Stretch {
        fn dof(&self) -> usize {
            1
        }
        fn map<D: Scalar>(&self, _t: D, q: &[D], p: &[D], nq: &mut [D], np: &mut [D]) {
            nq[0] = q[0] * 2.0;
            np[0] = p[0];
        }
    }
    let c = canonicity(&Stretch, 0.0, &[0.3], &[-0.2]).unwrap();
    assert_eq!(c.symplectic, 1.0);
    assert_eq!(c.bracket_matrix[(0, 1)], 2.0);
}

/// The inverse of the polar map by core's Newton from a guess 10% off: the Cartesian point back to
/// rounding. Measured worst 2.4e-16 relative to 1 + r + |p|₁; tolerance 1e-15.
#[test]
fn closed_form_polar_inverse_by_newton() {
    let mut rng = Rng(43);
    for _ in 0..100 {
        let (r, th) = (rng.uniform(0.3, 2.8), rng.uniform(-2.5, 2.5));
        let q = [r * th.cos(), r * th.sin()];
        let p = rng.vec(2, -2.0, 2.0);
        let (nq, np) = transform::apply(&Polar, 0.0, &q, &p).unwrap();
        let guess_q = [q[0] * 1.1 + 0.05, q[1] * 0.9];
        let guess_p = [p[0] * 0.9, p[1] + 0.1];
        let (bq, bp, info) = invert(
            &Polar,
            0.0,
            (&nq, &np),
            (&guess_q, &guess_p),
            &transform::newton_to_rounding(),
        )
        .unwrap();
        let err = (0..2)
            .map(|i| (bq[i] - q[i]).abs().max((bp[i] - p[i]).abs()))
            .fold(0.0, f64::max);
        assert!(
            err <= 1e-15 * (1.0 + r + p[0].abs() + p[1].abs()),
            "{err:e} {info:?}"
        );
    }
}

/// The rotating frame (time-dependent map): the motion of H carried over, J Ω∇H + ∂φ/∂t, is the
/// motion of K = H − ω L_z (closed form) at 200 random points and times; measured worst defect
/// 3.6e-15 (rates of size ≲ 10); tolerance 8e-15. With K = H∘φ⁻¹ = H (wrong for a time-dependent
/// map) the defect is the motion ω L_z generates, ≥ ω max(|q|, |p|)/√2: the check tells them apart.
#[test]
fn closed_form_rotating_frame_new_hamiltonian() {
    let h = Planar {
        m: 1.5,
        w: 1.2,
        eps: 0.3,
    };
    let w = 0.7;
    let (map, k) = (Rotating { w }, RotatingK { h, w });
    let mut rng = Rng(47);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let t = rng.uniform(-5.0, 5.0);
        let (q, p) = (rng.vec(2, -1.5, 1.5), rng.vec(2, -1.5, 1.5));
        worst = worst.max(new_hamiltonian_defect(&map, &h, &k, t, &q, &p).unwrap());
        let wrong = new_hamiltonian_defect(&map, &h, &h, t, &q, &p).unwrap();
        // The difference is X of ω L_z: ω(−Q₂, Q₁, −P₂, P₁), max-norm ≥ ω max(|q|, |p|)/√2.
        let size = q[0].hypot(q[1]).max(p[0].hypot(p[1]));
        assert!(wrong >= w * size / 2f64.sqrt() * (1.0 - 1e-12), "{wrong:e}");
        assert!(canonicity(&map, t, &q, &p).unwrap().symplectic <= 4e-16);
    }
    assert!(worst <= 8e-15, "{worst:e}");
}
