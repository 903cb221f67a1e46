//! The system traits of [`EulerLagrange`]: Lagrange's equations on (q, q̇).

use crate::{EulerLagrange, Lagrangian, Result, Velocities};
use nalgebra::{DMatrix, DVector};

use super::{Dynamics, LinearizedDynamics};

impl<L: Lagrangian> Dynamics for EulerLagrange<L> {
    type Partner = Velocities;
    fn dof(&self) -> usize {
        EulerLagrange::dof(self)
    }
    fn rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
        self.accelerations(t, q, v, dv)?;
        dq.copy_from_slice(v);
        Ok(())
    }
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        EulerLagrange::energy(self, t, q, v)
    }
    fn position_rates(&self, _t: f64, _q: &[f64], v: &[f64], dq: &mut [f64]) -> Result<()> {
        crate::error::check_len("q̇", v, self.dof())?;
        crate::error::check_len("q̇ (output)", dq, self.dof())?;
        dq.copy_from_slice(v);
        Ok(())
    }
}

/// The exact Jacobian of Lagrange's equations on (q, q̇), for any Lagrangian (configuration- and
/// velocity-dependent mass matrix included):
///
/// ```text
/// J = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]],   M q̈ = b,   b = ∂L/∂q − (∂²L/∂q̇∂q) q̇ − ∂²L/∂q̇∂t,
/// ∂q̈·δ = M⁻¹ (δb − (δM) q̈)   for δ = (δq, δq̇),
/// ```
///
/// which needs third derivatives of L. Column j of J comes from one evaluation of L with the
/// [`LagrangeJet`](crate::ad::LagrangeJet) of [`ad::lagrange_terms`](crate::ad::lagrange_terms) over an
/// inner `Dual64` seeded along δ = e_j: the jet gives b and M, the inner dual their derivatives δb and
/// δM. M is factored once per call by [`linalg`](crate::linalg). Up to 10 degrees of freedom (the
/// jet's stack range, as `EulerLagrange::accelerations`); more give [`Error::Unsupported`](crate::Error::Unsupported).
///
/// Generalized forces Q(t, q, q̇) enter b, so δb gains δQ = ∂Q/∂q·δq + ∂Q/∂q̇·δq̇: one evaluation
/// of the generic [`generalized_force`](crate::Lagrangian::generalized_force) over `Dual64` per
/// column.
impl<L: crate::Lagrangian> LinearizedDynamics for crate::EulerLagrange<L> {
    fn jacobian(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        let n = self.dof();
        crate::error::check_phase_point(n, t, q, v, "q̇")?;
        crate::error::check_shape(
            "Jacobian of Lagrange's equations (rows and columns)",
            out,
            2 * n,
            2 * n,
        )?;
        let columns = directional_terms(self.lagrangian(), t, q, v)?;
        out.fill(0.0);
        out.view_mut((0, n), (n, n)).fill_with_identity();
        let Some((b0, m0)) = columns.first() else {
            return Ok(());
        };
        // M and q̈ = M⁻¹b from the real parts (the same in every column).
        let factor = crate::linalg::factor_positive_mass(m0.map(|x| x.re), t)?;
        let acc = factor.solve_matrix(&DMatrix::from_fn(n, 1, |r, _| b0[r].re));
        let mut residual = DMatrix::zeros(n, 2 * n);
        residual_columns(&columns, acc.as_slice(), &mut residual);
        // ∂q̈/∂x = −M⁻¹ ∂E/∂x.
        let dqdd = -factor.solve_matrix(&residual);
        out.view_mut((n, 0), (n, 2 * n)).copy_from(&dqdd);
        crate::error::check_result("Jacobian of Lagrange's equations", t, out.as_slice())
    }
}

impl<L: Lagrangian> crate::EulerLagrange<L> {
    /// The Jacobian ∂E/∂(q, q̇) (n × 2n, into `out`) of the residual of Lagrange's equations
    ///
    /// ```text
    /// E(t, q, q̇, q̈) = M(t, q, q̇) q̈ − b(t, q, q̇) = d/dt(∂L/∂q̇) − ∂L/∂q − Q
    /// ```
    ///
    /// at a fixed acceleration q̈ (any, not only the one Lagrange's equations give): column j is
    /// (δM) q̈ − δb along δ = e_j, exact (third derivatives of L by the jets of the
    /// [`LinearizedDynamics`] impl). It is what implicit differentiation of a larger system built on
    /// Lagrange's equations needs: the saddle-point system of a constrained model, [M Aᵀ; A 0], is
    /// differentiated this way by noether-constraints. Errors: dimensions, non-finite input or
    /// result, more than 10 degrees of freedom ([`Error::Unsupported`](crate::Error::Unsupported)).
    pub fn residual_jacobian(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        qdd: &[f64],
        out: &mut DMatrix<f64>,
    ) -> Result<()> {
        let n = self.dof();
        crate::error::check_phase_point(n, t, q, v, "q̇")?;
        crate::error::check_len("q̈", qdd, n)?;
        crate::error::check_finite("q̈", qdd)?;
        crate::error::check_shape("Jacobian of the Euler-Lagrange residual (rows)", out, n, 2 * n)?;
        let columns = directional_terms(self.lagrangian(), t, q, v)?;
        residual_columns(&columns, qdd, out);
        crate::error::check_result("Jacobian of the Euler-Lagrange residual", t, out.as_slice())
    }
}

/// (b, M) with their derivatives along each δ = e_j, j < 2n (q directions first, then q̇), over
/// `Dual64`: [`lagrange_terms_along`] (and the generalized force's derivatives) for n ≤ 10.
type Directional = Vec<(DVector<num_dual::Dual64>, DMatrix<num_dual::Dual64>)>;

fn directional_terms<L: Lagrangian>(l: &L, t: f64, q: &[f64], v: &[f64]) -> Result<Directional> {
    match l.dof() {
        0 => Ok(Vec::new()),
        1 => Ok(directional_terms_n::<_, 1>(l, t, q, v)),
        2 => Ok(directional_terms_n::<_, 2>(l, t, q, v)),
        3 => Ok(directional_terms_n::<_, 3>(l, t, q, v)),
        4 => Ok(directional_terms_n::<_, 4>(l, t, q, v)),
        5 => Ok(directional_terms_n::<_, 5>(l, t, q, v)),
        6 => Ok(directional_terms_n::<_, 6>(l, t, q, v)),
        7 => Ok(directional_terms_n::<_, 7>(l, t, q, v)),
        8 => Ok(directional_terms_n::<_, 8>(l, t, q, v)),
        9 => Ok(directional_terms_n::<_, 9>(l, t, q, v)),
        10 => Ok(directional_terms_n::<_, 10>(l, t, q, v)),
        _ => Err(crate::Error::Unsupported(
            "the Jacobian of Lagrange's equations for more than 10 degrees of freedom",
        )),
    }
}

/// Column j of ∂E/∂x at the acceleration `qdd`: (δM) q̈ − δb from the dual parts.
fn residual_columns(columns: &Directional, qdd: &[f64], out: &mut DMatrix<f64>) {
    for (j, (b, m)) in columns.iter().enumerate() {
        for r in 0..b.len() {
            out[(r, j)] = (0..qdd.len()).map(|c| m[(r, c)].eps * qdd[c]).sum::<f64>() - b[r].eps;
        }
    }
}

/// (b, M) of Lagrange's equations M q̈ = b and their derivatives along δ = (δq, δq̇): one evaluation of
/// f with a [`LagrangeJet`](crate::ad::LagrangeJet) over `Dual64`, seeded like
/// [`ad::lagrange_terms`](crate::ad::lagrange_terms) at (t + s, x + s·y + ·, y + ·) with
/// x = q + ε δq, y = q̇ + ε δq̇.
fn lagrange_terms_along<F: crate::ad::Field, const N: usize>(
    f: &F,
    t: f64,
    (x, y): (&[f64], &[f64]),
    (dx, dy): (&[f64], &[f64]),
) -> (
    nalgebra::SVector<num_dual::Dual64, N>,
    nalgebra::SMatrix<num_dual::Dual64, N, N>,
) {
    use crate::ad::{LagrangeJet, Part};
    use nalgebra::{Const, SVector};
    use num_dual::Dual64;
    type J<const N: usize> = LagrangeJet<Dual64, f64, Const<N>>;
    let unit = |i: usize| Part::unit(Const::<N>, i);
    let zero = Dual64::from(0.0);
    let mut xs = [J::<N>::from_re(zero); N];
    let mut ys = [J::<N>::from_re(zero); N];
    for i in 0..N {
        let (xi, yi) = (Dual64::new(x[i], dx[i]), Dual64::new(y[i], dy[i]));
        xs[i] = J::new(xi, unit(i), yi, Part::none(), Part::none(), Part::none());
        ys[i] = J::new(yi, Part::none(), zero, unit(i), Part::none(), Part::none());
    }
    let tt = J::new(
        Dual64::from(t),
        Part::none(),
        Dual64::from(1.0),
        Part::none(),
        Part::none(),
        Part::none(),
    );
    let r = f.eval(tt, &xs, &ys);
    let row = |p: &Part<Dual64, f64, nalgebra::U1, Const<N>>| {
        p.get()
            .map_or_else(SVector::<Dual64, N>::zeros, |m| m.transpose())
    };
    (row(&r.gx) - row(&r.hsw), r.hww.matrix(Const::<N>))
}

/// Q(t, q + ε δq, q̇ + ε δq̇) over `Dual64`: the generalized force and its derivative along δ.
fn force_along<L: Lagrangian, const N: usize>(
    l: &L,
    t: f64,
    (q, v): (&[f64], &[f64]),
    (dq, dv): (&[f64], &[f64]),
) -> nalgebra::SVector<num_dual::Dual64, N> {
    use num_dual::Dual64;
    let x: [Dual64; N] = std::array::from_fn(|i| Dual64::new(q[i], dq[i]));
    let y: [Dual64; N] = std::array::from_fn(|i| Dual64::new(v[i], dv[i]));
    let mut out = [Dual64::from(0.0); N];
    l.generalized_force(Dual64::from(t), &x, &y, &mut out);
    out.into()
}

/// (b, M) and their derivatives along every unit direction of (q, q̇) for N degrees of freedom.
fn directional_terms_n<L: Lagrangian, const N: usize>(l: &L, t: f64, q: &[f64], v: &[f64]) -> Directional {
    let f = crate::lagrange::LagrangianField(l);
    let zeros = [0.0; N];
    (0..2 * N)
        .map(|j| {
            let mut e = [0.0; N];
            e[j % N] = 1.0;
            let dir = if j < N {
                (&e[..], &zeros[..])
            } else {
                (&zeros[..], &e[..])
            };
            let (mut b, m) = lagrange_terms_along::<_, N>(&f, t, (q, v), dir);
            if l.has_generalized_force() {
                b += force_along::<L, N>(l, t, (q, v), dir);
            }
            (
                DVector::from_column_slice(b.as_slice()),
                DMatrix::from_column_slice(N, N, m.as_slice()),
            )
        })
        .collect()
}
