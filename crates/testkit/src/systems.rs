//! Test systems: each model is written once as a generic Lagrangian (what a user writes) next to its
//! hand-derived equations of motion, momenta and mass matrix (what a textbook writes). The hand
//! formulas are the truth the AD results are compared with; each one states its derivation.
//!
//! Used by noether-core's `ad` tests, its `accelerations`, `accelerations_min` and `legendre`
//! benchmarks, and the gallery's `work_precision` benchmark (the 40-link chain). The hand-written
//! functions are `#[inline]`, as they were when each bench binary compiled this file itself.

// Index loops read like the textbook formulas they transcribe.
#![allow(clippy::needless_range_loop)]

use noether_core::{Hamiltonian, Lagrangian, Scalar};

/// Solves the small SPD system M x = b in place (Cholesky, row-major, lower triangle of `m` used).
/// The hand-written baselines use this; it is the textbook algorithm with no allocation.
#[inline]
pub fn cholesky_solve<const N: usize>(m: &mut [[f64; N]; N], b: &mut [f64; N]) {
    for j in 0..N {
        let mut d = m[j][j];
        for k in 0..j {
            d -= m[j][k] * m[j][k];
        }
        let d = d.sqrt();
        m[j][j] = d;
        let inv = 1.0 / d;
        for i in j + 1..N {
            let mut s = m[i][j];
            for k in 0..j {
                s -= m[i][k] * m[j][k];
            }
            m[i][j] = s * inv;
        }
    }
    for i in 0..N {
        let mut s = b[i];
        for k in 0..i {
            s -= m[i][k] * b[k];
        }
        b[i] = s / m[i][i];
    }
    for i in (0..N).rev() {
        let mut s = b[i];
        for k in i + 1..N {
            s -= m[k][i] * b[k];
        }
        b[i] = s / m[i][i];
    }
}

// ---------------------------------------------------------------------------------------------------
/// Planar double pendulum: masses m1, m2 on massless rods l1, l2, angles θ1, θ2 from the downward
/// vertical, Δ = θ1 − θ2:
/// L = ½(m1+m2) l1² θ̇1² + ½ m2 l2² θ̇2² + m2 l1 l2 θ̇1 θ̇2 cos Δ + (m1+m2) g l1 cos θ1 + m2 g l2 cos θ2.
#[derive(Debug, Clone, Copy)]
pub struct DoublePendulum {
    /// Mass m1 (upper bob).
    pub m1: f64,
    /// Mass m2 (lower bob).
    pub m2: f64,
    /// Rod length l1.
    pub l1: f64,
    /// Rod length l2.
    pub l2: f64,
    /// Gravity g.
    pub g: f64,
}

impl Default for DoublePendulum {
    fn default() -> Self {
        DoublePendulum {
            m1: 1.3,
            m2: 0.7,
            l1: 1.1,
            l2: 0.8,
            g: 9.81,
        }
    }
}

impl Lagrangian for DoublePendulum {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        v[0] * v[0] * (0.5 * (m1 + m2) * l1 * l1)
            + v[1] * v[1] * (0.5 * m2 * l2 * l2)
            + v[0] * v[1] * (q[0] - q[1]).cos() * (m2 * l1 * l2)
            + q[0].cos() * ((m1 + m2) * g * l1)
            + q[1].cos() * (m2 * g * l2)
    }
}

impl DoublePendulum {
    /// Hand-derived: with c = cos Δ, s = sin Δ, Lagrange's equations are
    /// (m1+m2) l1² θ̈1 + m2 l1 l2 c θ̈2 = −m2 l1 l2 s θ̇2² − (m1+m2) g l1 sin θ1,
    /// m2 l1 l2 c θ̈1 + m2 l2² θ̈2     =  m2 l1 l2 s θ̇1² − m2 g l2 sin θ2,
    /// solved by Cramer's rule; det = m2 l1² l2² (m1 + m2 s²) > 0.
    #[inline]
    pub fn hand_accelerations(&self, q: &[f64; 2], v: &[f64; 2]) -> [f64; 2] {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        let (s, c) = (q[0] - q[1]).sin_cos();
        let a11 = (m1 + m2) * l1 * l1;
        let a12 = m2 * l1 * l2 * c;
        let a22 = m2 * l2 * l2;
        let b1 = -m2 * l1 * l2 * s * v[1] * v[1] - (m1 + m2) * g * l1 * q[0].sin();
        let b2 = m2 * l1 * l2 * s * v[0] * v[0] - m2 * g * l2 * q[1].sin();
        let inv = 1.0 / (a11 * a22 - a12 * a12);
        [(a22 * b1 - a12 * b2) * inv, (a11 * b2 - a12 * b1) * inv]
    }

    /// M = [[(m1+m2) l1², m2 l1 l2 c], [m2 l1 l2 c, m2 l2²]].
    #[inline]
    pub fn hand_mass(&self, q: &[f64; 2]) -> [[f64; 2]; 2] {
        let c = (q[0] - q[1]).cos();
        let a12 = self.m2 * self.l1 * self.l2 * c;
        [
            [(self.m1 + self.m2) * self.l1 * self.l1, a12],
            [a12, self.m2 * self.l2 * self.l2],
        ]
    }

    /// p = M θ̇; h = T + V = ½ θ̇ᵀ M θ̇ − (m1+m2) g l1 cos θ1 − m2 g l2 cos θ2.
    #[inline]
    pub fn hand_momenta_energy(&self, q: &[f64; 2], v: &[f64; 2]) -> ([f64; 2], f64) {
        let m = self.hand_mass(q);
        let p = [m[0][0] * v[0] + m[0][1] * v[1], m[1][0] * v[0] + m[1][1] * v[1]];
        let t = 0.5 * (p[0] * v[0] + p[1] * v[1]);
        let pot =
            -(self.m1 + self.m2) * self.g * self.l1 * q[0].cos() - self.m2 * self.g * self.l2 * q[1].cos();
        (p, t + pot)
    }
}

/// The double pendulum's Hamiltonian by hand: H = ½ pᵀ M(q)⁻¹ p − (m1+m2) g l1 cos θ1 − m2 g l2 cos θ2,
/// with M = [[a11, a12 c], [a12 c, a22]] ([`DoublePendulum::hand_mass`]), M⁻¹ by the 2×2 adjugate.
#[derive(Debug, Clone, Copy)]
pub struct DoublePendulumH(pub DoublePendulum);

impl Hamiltonian for DoublePendulumH {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let s = &self.0;
        let a11 = (s.m1 + s.m2) * s.l1 * s.l1;
        let a22 = s.m2 * s.l2 * s.l2;
        let a12 = (q[0] - q[1]).cos() * (s.m2 * s.l1 * s.l2);
        let det = -a12 * a12 + a11 * a22;
        (p[0] * p[0] * a22 - p[0] * p[1] * a12 * 2.0 + p[1] * p[1] * a11) / (det * 2.0)
            - q[0].cos() * ((s.m1 + s.m2) * s.g * s.l1)
            - q[1].cos() * (s.m2 * s.g * s.l2)
    }
}

impl DoublePendulumH {
    /// Hamilton's equations written out by hand. With a₁₁ = (m1+m2) l1², a₂₂ = m2 l2², a₁₂ =
    /// k cos Δ (k = m2 l1 l2, Δ = θ1 − θ2), det = a₁₁a₂₂ − a₁₂² and N = a₂₂p₁² − 2a₁₂p₁p₂ + a₁₁p₂²
    /// (so H = N/(2 det) + V): q̇₁ = (a₂₂p₁ − a₁₂p₂)/det, q̇₂ = (a₁₁p₂ − a₁₂p₁)/det, and with
    /// C = k sin Δ (p₁p₂/det − N a₁₂/det²) = ∂(N/2det)/∂θ₂ = −∂(N/2det)/∂θ₁,
    /// ṗ₁ = −C − (m1+m2) g l1 sin θ1, ṗ₂ = C − m2 g l2 sin θ2.
    #[inline]
    pub fn hand_rates(&self, q: &[f64; 2], p: &[f64; 2]) -> ([f64; 2], [f64; 2]) {
        let s = &self.0;
        let (a11, a22, k) = (
            (s.m1 + s.m2) * s.l1 * s.l1,
            s.m2 * s.l2 * s.l2,
            s.m2 * s.l1 * s.l2,
        );
        let (sd, cd) = (q[0] - q[1]).sin_cos();
        let a12 = k * cd;
        let inv = 1.0 / (a11 * a22 - a12 * a12);
        let n = a22 * p[0] * p[0] - 2.0 * a12 * p[0] * p[1] + a11 * p[1] * p[1];
        let c = k * sd * inv * (p[0] * p[1] - n * a12 * inv);
        (
            [(a22 * p[0] - a12 * p[1]) * inv, (a11 * p[1] - a12 * p[0]) * inv],
            [
                -c - (s.m1 + s.m2) * s.g * s.l1 * q[0].sin(),
                c - s.m2 * s.g * s.l2 * q[1].sin(),
            ],
        )
    }
}

// ---------------------------------------------------------------------------------------------------
/// Heavy symmetric top, Euler angles q = (θ, φ, ψ):
/// L = ½ I1 (θ̇² + φ̇² sin²θ) + ½ I3 (ψ̇ + φ̇ cos θ)² − M g ℓ cos θ.
#[derive(Debug, Clone, Copy)]
pub struct HeavyTop {
    /// Transverse moment of inertia I1 about the fixed point.
    pub i1: f64,
    /// Axial moment of inertia I3.
    pub i3: f64,
    /// M g ℓ (ℓ: fixed point to centre of mass).
    pub mgl: f64,
}

impl Default for HeavyTop {
    fn default() -> Self {
        HeavyTop {
            i1: 1.2,
            i3: 0.45,
            mgl: 2.5,
        }
    }
}

impl Lagrangian for HeavyTop {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (s, c) = q[0].sin_cos();
        let w3 = v[2] + v[1] * c;
        (v[0] * v[0] + v[1] * v[1] * s * s) * (0.5 * self.i1) + w3 * w3 * (0.5 * self.i3) - c * self.mgl
    }
}

impl HeavyTop {
    /// Hand-derived, with s = sin θ, c = cos θ, ω3 = ψ̇ + φ̇ c:
    /// θ: I1 θ̈ = I1 φ̇² s c − I3 ω3 φ̇ s + M g ℓ s;
    /// ψ cyclic: ṗ_ψ = I3 ω̇3 = 0, so ψ̈ = φ̇ θ̇ s − φ̈ c;
    /// φ cyclic: ṗ_φ = d/dt(I1 φ̇ s² + I3 ω3 c) = I1 φ̈ s² + 2 I1 φ̇ θ̇ s c − I3 ω3 θ̇ s = 0,
    /// so φ̈ = θ̇ (I3 ω3 − 2 I1 φ̇ c) / (I1 s).
    #[inline]
    pub fn hand_accelerations(&self, q: &[f64; 3], v: &[f64; 3]) -> [f64; 3] {
        let (s, c) = q[0].sin_cos();
        let (td, pd, sd) = (v[0], v[1], v[2]);
        let w3 = sd + pd * c;
        let inv_i1 = 1.0 / self.i1;
        let tdd = pd * pd * s * c - (self.i3 * w3 * pd - self.mgl) * s * inv_i1;
        let pdd = td * (self.i3 * w3 - 2.0 * self.i1 * pd * c) * inv_i1 / s;
        let sdd = pd * td * s - pdd * c;
        [tdd, pdd, sdd]
    }

    /// M = [[I1, 0, 0], [0, I1 s² + I3 c², I3 c], [0, I3 c, I3]].
    #[inline]
    pub fn hand_mass(&self, q: &[f64; 3]) -> [[f64; 3]; 3] {
        let (s, c) = q[0].sin_cos();
        [
            [self.i1, 0.0, 0.0],
            [0.0, self.i1 * s * s + self.i3 * c * c, self.i3 * c],
            [0.0, self.i3 * c, self.i3],
        ]
    }

    /// p_θ = I1 θ̇, p_φ = I1 φ̇ s² + I3 ω3 c, p_ψ = I3 ω3; h = T + V = ½ I1 (θ̇² + φ̇² s²) + ½ I3 ω3² + M g ℓ c.
    #[inline]
    pub fn hand_momenta_energy(&self, q: &[f64; 3], v: &[f64; 3]) -> ([f64; 3], f64) {
        let (s, c) = q[0].sin_cos();
        let w3 = v[2] + v[1] * c;
        let p = [
            self.i1 * v[0],
            self.i1 * v[1] * s * s + self.i3 * w3 * c,
            self.i3 * w3,
        ];
        let h = 0.5 * self.i1 * (v[0] * v[0] + v[1] * v[1] * s * s) + 0.5 * self.i3 * w3 * w3 + self.mgl * c;
        (p, h)
    }
}

// ---------------------------------------------------------------------------------------------------
/// Planar chain of N point masses m_k on massless rods l_k, angles θ_k from the downward vertical.
/// Positions x_k = Σ_{i≤k} l_i sin θ_i, y_k = −Σ_{i≤k} l_i cos θ_i;
/// L = Σ_k ½ m_k (ẋ_k² + ẏ_k²) − Σ_k m_k g y_k (written by the user as running sums: O(N) operations).
#[derive(Debug, Clone, Copy)]
pub struct Chain<const N: usize> {
    /// Masses m_k.
    pub m: [f64; N],
    /// Rod lengths l_k.
    pub l: [f64; N],
    /// Gravity g.
    pub g: f64,
}

impl<const N: usize> Default for Chain<N> {
    fn default() -> Self {
        Chain {
            m: std::array::from_fn(|k| 1.0 + 0.1 * k as f64),
            l: std::array::from_fn(|k| 0.5 + 0.05 * ((3 * k) % 5) as f64),
            g: 9.81,
        }
    }
}

impl<const N: usize> Lagrangian for Chain<N> {
    fn dof(&self) -> usize {
        N
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (mut vx, mut vy, mut y) = (D::zero(), D::zero(), D::zero());
        let (mut t, mut u) = (D::zero(), D::zero());
        for k in 0..N {
            let (s, c) = q[k].sin_cos();
            let w = v[k] * self.l[k];
            vx += w * c;
            vy += w * s;
            y -= c * self.l[k];
            t += (vx * vx + vy * vy) * (0.5 * self.m[k]);
            u += y * (self.m[k] * self.g);
        }
        t - u
    }
}

impl<const N: usize> Chain<N> {
    /// μ_k = Σ_{j≥k} m_j, the mass hanging from rod k.
    fn mu(&self) -> [f64; N] {
        let mut mu = [0.0; N];
        let mut acc = 0.0;
        for k in (0..N).rev() {
            acc += self.m[k];
            mu[k] = acc;
        }
        mu
    }

    /// Hand-derived: T = ½ Σ_ij μ_max(i,j) l_i l_j cos(θ_i − θ_j) θ̇_i θ̇_j, V = −g Σ_i μ_i l_i cos θ_i, so
    /// M_ij = μ_max(i,j) l_i l_j cos(θ_i − θ_j) and Lagrange's equations read
    /// Σ_j M_ij θ̈_j = −Σ_j μ_max(i,j) l_i l_j sin(θ_i − θ_j) θ̇_j² − g μ_i l_i sin θ_i.
    /// cos/sin of differences from one sin_cos per angle; Cholesky on the stack.
    #[inline]
    pub fn hand_accelerations(&self, q: &[f64; N], v: &[f64; N]) -> [f64; N] {
        let mut mu = [0.0; N];
        let mut acc = 0.0;
        for k in (0..N).rev() {
            acc += self.m[k];
            mu[k] = acc;
        }
        let mut s = [0.0; N];
        let mut c = [0.0; N];
        for k in 0..N {
            (s[k], c[k]) = q[k].sin_cos();
        }
        let mut m = [[0.0; N]; N];
        let mut b = [0.0; N];
        for i in 0..N {
            b[i] = -self.g * mu[i] * self.l[i] * s[i];
        }
        for i in 0..N {
            for j in 0..i {
                // mu[max(i, j)] = mu[i] for j < i
                let k = mu[i] * self.l[i] * self.l[j];
                let cij = c[i] * c[j] + s[i] * s[j];
                let sij = s[i] * c[j] - c[i] * s[j];
                m[i][j] = k * cij;
                b[i] -= k * sij * v[j] * v[j];
                b[j] += k * sij * v[i] * v[i];
            }
            m[i][i] = mu[i] * self.l[i] * self.l[i];
        }
        cholesky_solve(&mut m, &mut b);
        b
    }

    /// M_ij = μ_max(i,j) l_i l_j cos(θ_i − θ_j).
    #[inline]
    pub fn hand_mass(&self, q: &[f64; N]) -> [[f64; N]; N] {
        let mu = self.mu();
        std::array::from_fn(|i| {
            std::array::from_fn(|j| mu[i.max(j)] * self.l[i] * self.l[j] * (q[i] - q[j]).cos())
        })
    }
}

// ---------------------------------------------------------------------------------------------------
/// Charged particle (mass m, charge e) in a uniform but time-dependent magnetic field
/// B(t) = B0 (1 + ε sin ωt) ẑ, vector potential A = ½ B(t) (−y, x, 0), plus a scalar potential
/// φ(r, t) = ½ κ (x² + y²) + E0 z cos ωt:
/// L = ½ m |ṙ|² + e ṙ·A(r, t) − e φ(r, t) (a velocity-dependent potential with explicit t).
#[derive(Debug, Clone, Copy)]
pub struct ChargeInField {
    /// Mass m.
    pub m: f64,
    /// Charge e.
    pub e: f64,
    /// Field strength B0.
    pub b0: f64,
    /// Modulation depth ε of B.
    pub eps: f64,
    /// Angular frequency ω of the modulation and of E.
    pub omega: f64,
    /// Curvature κ of the scalar potential.
    pub kappa: f64,
    /// Amplitude E0 of the axial electric field.
    pub e0: f64,
}

impl Default for ChargeInField {
    fn default() -> Self {
        ChargeInField {
            m: 1.7,
            e: -0.9,
            b0: 2.3,
            eps: 0.4,
            omega: 1.3,
            kappa: 0.6,
            e0: 0.8,
        }
    }
}

impl Lagrangian for ChargeInField {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        let b = ((t * self.omega).sin() * self.eps + 1.0) * self.b0;
        let (x, y, z) = (q[0], q[1], q[2]);
        let kin = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * (0.5 * self.m);
        let va = (v[1] * x - v[0] * y) * b * 0.5;
        let phi = (x * x + y * y) * (0.5 * self.kappa) + z * (t * self.omega).cos() * self.e0;
        kin + (va - phi) * self.e
    }
}

impl ChargeInField {
    /// B(t) and dB/dt.
    #[inline]
    pub fn field(&self, t: f64) -> (f64, f64) {
        let (s, c) = (self.omega * t).sin_cos();
        (
            self.b0 * (1.0 + self.eps * s),
            self.b0 * self.eps * self.omega * c,
        )
    }

    /// Hand-derived Lorentz force m r̈ = e (E + ṙ × B) with E = −∇φ − ∂A/∂t:
    /// E = (−κ x + ½ Ḃ y, −κ y − ½ Ḃ x, −E0 cos ωt), ṙ × B ẑ = (ẏ B, −ẋ B, 0).
    #[inline]
    pub fn hand_accelerations(&self, t: f64, q: &[f64; 3], v: &[f64; 3]) -> [f64; 3] {
        let (b, bdot) = self.field(t);
        let ex = -self.kappa * q[0] + 0.5 * bdot * q[1];
        let ey = -self.kappa * q[1] - 0.5 * bdot * q[0];
        let ez = -self.e0 * (self.omega * t).cos();
        let k = self.e / self.m;
        [k * (ex + v[1] * b), k * (ey - v[0] * b), k * ez]
    }

    /// Canonical momenta p = m ṙ + e A (not the kinetic momentum); h = ½ m |ṙ|² + e φ (the
    /// magnetic term is linear in ṙ and drops out of h).
    #[inline]
    pub fn hand_momenta_energy(&self, t: f64, q: &[f64; 3], v: &[f64; 3]) -> ([f64; 3], f64) {
        let (b, _) = self.field(t);
        let a = [-0.5 * b * q[1], 0.5 * b * q[0], 0.0];
        let p = std::array::from_fn(|i| self.m * v[i] + self.e * a[i]);
        let phi = 0.5 * self.kappa * (q[0] * q[0] + q[1] * q[1]) + self.e0 * q[2] * (self.omega * t).cos();
        (
            p,
            0.5 * self.m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + self.e * phi,
        )
    }
}

// ---------------------------------------------------------------------------------------------------
/// Damped, driven Duffing oscillator: L = ½ m q̇² − ½ k q² − ¼ β q⁴ with the non-potential generalized
/// force Q = −c q̇ + F cos ωt (Lagrange's equations with Q, as Desloge writes them).
#[derive(Debug, Clone, Copy)]
pub struct DrivenOscillator {
    /// Mass m.
    pub m: f64,
    /// Spring constant k.
    pub k: f64,
    /// Cubic stiffness β.
    pub beta: f64,
    /// Damping c.
    pub c: f64,
    /// Drive amplitude F.
    pub f: f64,
    /// Drive angular frequency ω.
    pub omega: f64,
}

impl Default for DrivenOscillator {
    fn default() -> Self {
        DrivenOscillator {
            m: 0.8,
            k: 3.0,
            beta: 0.7,
            c: 0.25,
            f: 1.4,
            omega: 1.9,
        }
    }
}

impl Lagrangian for DrivenOscillator {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let q2 = q[0] * q[0];
        v[0] * v[0] * (0.5 * self.m) - q2 * (0.5 * self.k) - q2 * q2 * (0.25 * self.beta)
    }
    fn has_generalized_force(&self) -> bool {
        true
    }
    fn generalized_force<D: Scalar>(&self, t: D, _q: &[D], v: &[D], out: &mut [D]) {
        out[0] = v[0] * (-self.c) + (t * self.omega).cos() * self.f;
    }
}

impl DrivenOscillator {
    /// The linear (β = 0), underdamped (c² < 4mk) oscillator: `Default` with β = 0.
    pub fn linear() -> Self {
        DrivenOscillator {
            beta: 0.0,
            ..Default::default()
        }
    }

    /// The closed-form motion (q, q̇)(t) from q(0) = q0, q̇(0) = v0 of the linear oscillator
    /// m q̈ + c q̇ + k q = F cos ωt (β must be 0, c² < 4mk): the steady response
    /// A cos ωt + B sin ωt with (A, B) = F (k − mω², cω) / ((k − mω²)² + (cω)²) plus the transient
    /// e^{−γt}(C₁ cos ω_d t + C₂ sin ω_d t), γ = c/2m, ω_d = √(k/m − γ²), C₁ = q0 − A,
    /// C₂ = (v0 − ωB + γC₁)/ω_d (any text on forced oscillations, e.g. Taylor, *Classical Mechanics*,
    /// §5.5–5.6).
    pub fn linear_solution(&self, t: f64, q0: f64, v0: f64) -> (f64, f64) {
        assert!(self.beta == 0.0 && self.c * self.c < 4.0 * self.m * self.k);
        let (m, k, c, w) = (self.m, self.k, self.c, self.omega);
        let det = (k - m * w * w).powi(2) + (c * w).powi(2);
        let (a, b) = (self.f * (k - m * w * w) / det, self.f * c * w / det);
        let gamma = c / (2.0 * m);
        let wd = (k / m - gamma * gamma).sqrt();
        let c1 = q0 - a;
        let c2 = (v0 - w * b + gamma * c1) / wd;
        let (e, cs, sn) = ((-gamma * t).exp(), (wd * t).cos(), (wd * t).sin());
        let q = a * (w * t).cos() + b * (w * t).sin() + e * (c1 * cs + c2 * sn);
        let v = -a * w * (w * t).sin()
            + b * w * (w * t).cos()
            + e * (-gamma * (c1 * cs + c2 * sn) + wd * (-c1 * sn + c2 * cs));
        (q, v)
    }

    /// m q̈ = −k q − β q³ − c q̇ + F cos ωt.
    #[inline]
    pub fn hand_acceleration(&self, t: f64, q: f64, v: f64) -> f64 {
        (-self.k * q - self.beta * q * q * q - self.c * v + self.f * (self.omega * t).cos()) / self.m
    }
}

// ---------------------------------------------------------------------------------------------------
/// Spherical pendulum, q = (θ, φ) with θ from the downward vertical:
/// L = ½ m l² (θ̇² + sin²θ φ̇²) + m g l cos θ.
#[derive(Debug, Clone, Copy)]
pub struct SphericalPendulum {
    /// Mass m.
    pub m: f64,
    /// Length l.
    pub l: f64,
    /// Gravity g.
    pub g: f64,
}

impl Default for SphericalPendulum {
    fn default() -> Self {
        SphericalPendulum {
            m: 0.9,
            l: 1.4,
            g: 9.81,
        }
    }
}

impl Lagrangian for SphericalPendulum {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let s = q[0].sin();
        (v[0] * v[0] + s * s * v[1] * v[1]) * (0.5 * self.m * self.l * self.l)
            + q[0].cos() * (self.m * self.g * self.l)
    }
}

impl SphericalPendulum {
    /// θ̈ = sin θ cos θ φ̇² − (g/l) sin θ; φ̈ = −2 cot θ θ̇ φ̇ (from ṗ_φ = d/dt(m l² sin²θ φ̇) = 0).
    #[inline]
    pub fn hand_accelerations(&self, q: &[f64; 2], v: &[f64; 2]) -> [f64; 2] {
        let (s, c) = q[0].sin_cos();
        [
            s * c * v[1] * v[1] - self.g / self.l * s,
            -2.0 * c / s * v[0] * v[1],
        ]
    }
}

// ---------------------------------------------------------------------------------------------------
/// Kepler problem in plane polar coordinates q = (r, φ): L = ½ m (ṙ² + r² φ̇²) + k / r.
#[derive(Debug, Clone, Copy)]
pub struct KeplerPolar {
    /// Mass m.
    pub m: f64,
    /// Strength k of the attraction k/r.
    pub k: f64,
}

impl Default for KeplerPolar {
    fn default() -> Self {
        KeplerPolar { m: 1.1, k: 2.7 }
    }
}

impl Lagrangian for KeplerPolar {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let r = q[0];
        (v[0] * v[0] + r * r * v[1] * v[1]) * (0.5 * self.m) + r.recip() * self.k
    }
}

impl KeplerPolar {
    /// r̈ = r φ̇² − k / (m r²); φ̈ = −2 ṙ φ̇ / r (from ṗ_φ = d/dt(m r² φ̇) = 0).
    #[inline]
    pub fn hand_accelerations(&self, q: &[f64; 2], v: &[f64; 2]) -> [f64; 2] {
        let r = q[0];
        [
            r * v[1] * v[1] - self.k / (self.m * r * r),
            -2.0 * v[0] * v[1] / r,
        ]
    }

    /// p = (m ṙ, m r² φ̇); h = ½ m (ṙ² + r² φ̇²) − k / r.
    #[inline]
    pub fn hand_momenta_energy(&self, q: &[f64; 2], v: &[f64; 2]) -> ([f64; 2], f64) {
        let r = q[0];
        let p = [self.m * v[0], self.m * r * r * v[1]];
        (p, 0.5 * self.m * (v[0] * v[0] + r * r * v[1] * v[1]) - self.k / r)
    }
}
