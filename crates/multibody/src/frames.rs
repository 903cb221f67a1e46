//! Frames in space as generic code: 3-vectors and rotation matrices over any scalar, so that the
//! positions, orientations and velocities of a kinematic tree carry dual numbers and every derivative
//! of the Lagrangian built from them is exact.
//!
//! A vector is `[D; 3]`, a matrix `[[D; 3]; 3]` (rows). Constants (placements, axes) stay `f64` and
//! enter products without being lifted.

use noether_core::Scalar;

/// A 3-vector over D.
pub type V3<D> = [D; 3];
/// A 3 × 3 matrix over D, by rows.
pub type M3<D> = [[D; 3]; 3];

/// The zero vector.
pub fn zero<D: Scalar>() -> V3<D> {
    [D::zero(); 3]
}

/// The identity matrix.
pub fn identity<D: Scalar>() -> M3<D> {
    let (o, z) = (D::one(), D::zero());
    [[o, z, z], [z, o, z], [z, z, o]]
}

/// a + b.
pub fn add<D: Scalar>(a: V3<D>, b: V3<D>) -> V3<D> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// a − b.
pub fn sub<D: Scalar>(a: V3<D>, b: V3<D>) -> V3<D> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// a · b.
pub fn dot<D: Scalar>(a: V3<D>, b: V3<D>) -> D {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a × b.
pub fn cross<D: Scalar>(a: V3<D>, b: V3<D>) -> V3<D> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// s a for a constant vector a.
pub fn scaled<D: Scalar>(a: [f64; 3], s: D) -> V3<D> {
    [s * a[0], s * a[1], s * a[2]]
}

/// R x for a constant vector x.
pub fn apply_const<D: Scalar>(r: &M3<D>, x: [f64; 3]) -> V3<D> {
    let mut y = [D::zero(); 3];
    for i in 0..3 {
        y[i] = r[i][0] * x[0] + r[i][1] * x[1] + r[i][2] * x[2];
    }
    y
}

/// R x.
pub fn apply<D: Scalar>(r: &M3<D>, x: V3<D>) -> V3<D> {
    let mut y = [D::zero(); 3];
    for i in 0..3 {
        y[i] = r[i][0] * x[0] + r[i][1] * x[1] + r[i][2] * x[2];
    }
    y
}

/// Rᵀ x.
pub fn apply_transpose<D: Scalar>(r: &M3<D>, x: V3<D>) -> V3<D> {
    let mut y = [D::zero(); 3];
    for i in 0..3 {
        y[i] = r[0][i] * x[0] + r[1][i] * x[1] + r[2][i] * x[2];
    }
    y
}

/// R C for a constant matrix C.
pub fn compose_const<D: Scalar>(r: &M3<D>, c: &[[f64; 3]; 3]) -> M3<D> {
    let mut m = [[D::zero(); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = r[i][0] * c[0][j] + r[i][1] * c[1][j] + r[i][2] * c[2][j];
        }
    }
    m
}

/// R S.
pub fn compose<D: Scalar>(r: &M3<D>, s: &M3<D>) -> M3<D> {
    let mut m = [[D::zero(); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = r[i][0] * s[0][j] + r[i][1] * s[1][j] + r[i][2] * s[2][j];
        }
    }
    m
}

/// The rotation by the angle θ about the unit axis a (Rodrigues):
/// R = cos θ I + sin θ \[a\]× + (1 − cos θ) a aᵀ.
pub fn rotation<D: Scalar>(a: [f64; 3], theta: D) -> M3<D> {
    let (s, c) = (theta.sin(), theta.cos());
    let k = D::one() - c;
    let skew = [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]];
    let mut r = [[D::zero(); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let diagonal = if i == j { c } else { D::zero() };
            r[i][j] = diagonal + s * skew[i][j] + k * (a[i] * a[j]);
        }
    }
    r
}
