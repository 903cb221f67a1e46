//! The system traits of [`EulerLagrange`]: Lagrange's equations on (q, q̇).

use crate::{EulerLagrange, Lagrangian, Result, Velocities};
use nalgebra::DMatrix;

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
        if out.nrows() != 2 * n || out.ncols() != 2 * n {
            return Err(crate::Error::Dimension {
                what: "Jacobian of Lagrange's equations (rows and columns)",
                expected: 2 * n,
                got: if out.nrows() != 2 * n {
                    out.nrows()
                } else {
                    out.ncols()
                },
            });
        }
        let l = self.lagrangian();
        let jac = match n {
            0 => Ok(DMatrix::zeros(0, 0)),
            1 => lagrange_jacobian::<_, 1>(l, t, q, v),
            2 => lagrange_jacobian::<_, 2>(l, t, q, v),
            3 => lagrange_jacobian::<_, 3>(l, t, q, v),
            4 => lagrange_jacobian::<_, 4>(l, t, q, v),
            5 => lagrange_jacobian::<_, 5>(l, t, q, v),
            6 => lagrange_jacobian::<_, 6>(l, t, q, v),
            7 => lagrange_jacobian::<_, 7>(l, t, q, v),
            8 => lagrange_jacobian::<_, 8>(l, t, q, v),
            9 => lagrange_jacobian::<_, 9>(l, t, q, v),
            10 => lagrange_jacobian::<_, 10>(l, t, q, v),
            _ => Err(crate::Error::Unsupported(
                "the Jacobian of Lagrange's equations for more than 10 degrees of freedom",
            )),
        }?;
        out.copy_from(&jac);
        Ok(())
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

/// J of Lagrange's equations for N degrees of freedom, column by column (see the
/// [`LinearizedDynamics`](LinearizedDynamics) impl of `EulerLagrange`).
fn lagrange_jacobian<L: Lagrangian, const N: usize>(
    l: &L,
    t: f64,
    q: &[f64],
    v: &[f64],
) -> Result<DMatrix<f64>> {
    let f = crate::lagrange::LagrangianField(l);
    let zeros = [0.0; N];
    let mut jac = DMatrix::zeros(2 * N, 2 * N);
    jac.view_mut((0, N), (N, N)).fill_with_identity();
    let columns: Vec<_> = (0..2 * N)
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
            (b, m)
        })
        .collect();
    let Some((b0, m0)) = columns.first() else {
        return Ok(jac);
    };
    // M and q̈ = M⁻¹b from the real parts (the same in every column).
    let factor = crate::linalg::factor_positive_mass(DMatrix::from_fn(N, N, |r, c| m0[(r, c)].re), t)?;
    let acc = factor.solve_matrix(&DMatrix::from_fn(N, 1, |r, _| b0[r].re));
    for (j, (b, m)) in columns.iter().enumerate() {
        // δb − (δM) q̈, then M⁻¹.
        let rhs = DMatrix::from_fn(N, 1, |r, _| {
            b[r].eps - (0..N).map(|c| m[(r, c)].eps * acc[(c, 0)]).sum::<f64>()
        });
        jac.view_mut((N, j), (N, 1)).copy_from(&factor.solve_matrix(&rhs));
    }
    crate::error::check_result("Jacobian of Lagrange's equations", t, jac.as_slice())?;
    Ok(jac)
}
