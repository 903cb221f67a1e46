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

/// The rotation with rotation vector θ (exponential coordinates: by the angle x = |θ| about θ/x),
/// R = exp(\[θ\]×) = I + a \[θ\]× + b \[θ\]×², a = sin x / x, b = (1 − cos x)/x² (Rodrigues).
pub fn exponential<D: Scalar>(theta: V3<D>) -> M3<D> {
    let s = dot(theta, theta);
    let (a, b) = (sinc(s), versine(s));
    let k = skew(theta);
    let k2 = compose(&k, &k);
    let mut r = identity();
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] += a * k[i][j] + b * k2[i][j];
        }
    }
    r
}

/// The angular velocity, in the fixed frame, of the rotation exp(\[θ\]×) when θ moves at θ̇: ω = J θ̇
/// with the left Jacobian of SO(3), J = I + b \[θ\]× + c \[θ\]×², b = (1 − cos x)/x²,
/// c = (x − sin x)/x³ (Ṙ Rᵀ = \[ω\]×). J is invertible while x = |θ| < 2π: the chart of exponential
/// coordinates is regular there.
pub fn exponential_rate<D: Scalar>(theta: V3<D>, rate: V3<D>) -> V3<D> {
    let s = dot(theta, theta);
    let (b, c) = (versine(s), cubic(s));
    let once = cross(theta, rate);
    let twice = cross(theta, once);
    [0, 1, 2].map(|i| rate[i] + b * once[i] + c * twice[i])
}

/// \[x\]×, the matrix of y ↦ x × y.
fn skew<D: Scalar>(x: V3<D>) -> M3<D> {
    let z = D::zero();
    [[z, -x[2], x[1]], [x[2], z, -x[0]], [-x[1], x[0], z]]
}

/// Below x² = 1 the three coefficients of the exponential map are summed as their Taylor series in
/// s = x² (Σ (−s)ᵏ/(2k + m)!, m = 1, 2, 3; 12 terms leave 1/27! ≈ 1e-28 at s = 1), which are exact in
/// their value and every derivative at θ = 0, where the closed forms divide 0 by 0; above it, the
/// closed forms (the cubic one loses at most 6ε/x² ≤ 6ε to cancellation there).
const SERIES_BELOW: f64 = 1.0;
const SERIES_TERMS: usize = 12;

/// The series' coefficients (−1)ᵏ/(2k + m)! for m = 1, 2, 3 (rows), k = 0 … 11, at compile time.
const COEFFICIENTS: [[f64; SERIES_TERMS]; 3] = {
    let mut table = [[0.0; SERIES_TERMS]; 3];
    let mut m = 0;
    while m < 3 {
        // (2k + m + 1)! built up term by term.
        let mut factorial = 1.0;
        let mut n = 1;
        while n <= m + 1 {
            factorial *= n as f64;
            n += 1;
        }
        let mut k = 0;
        while k < SERIES_TERMS {
            table[m][k] = if k % 2 == 0 { 1.0 } else { -1.0 } / factorial;
            factorial *= ((2 * k + m + 2) * (2 * k + m + 3)) as f64;
            k += 1;
        }
        m += 1;
    }
    table
};

/// Σ_{k<12} (−s)ᵏ/(2k + m)! by Horner's rule, m = 1, 2, 3.
fn series<D: Scalar>(s: D, m: usize) -> D {
    let mut sum = D::zero();
    for c in COEFFICIENTS[m - 1].iter().rev() {
        sum = sum * s + *c;
    }
    sum
}

/// sin x / x as a function of s = x².
fn sinc<D: Scalar>(s: D) -> D {
    if s.re() < SERIES_BELOW {
        series(s, 1)
    } else {
        let x = s.sqrt();
        x.sin() / x
    }
}

/// (1 − cos x)/x² = 2 sin²(x/2)/x² as a function of s = x² (the second form has no cancellation).
fn versine<D: Scalar>(s: D) -> D {
    if s.re() < SERIES_BELOW {
        series(s, 2)
    } else {
        let half = s.sqrt() * 0.5;
        let h = half.sin() / half;
        h * h * 0.5
    }
}

/// (x − sin x)/x³ as a function of s = x².
fn cubic<D: Scalar>(s: D) -> D {
    if s.re() < SERIES_BELOW {
        series(s, 3)
    } else {
        let x = s.sqrt();
        (x - x.sin()) / (x * s)
    }
}
