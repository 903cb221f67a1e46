//! Symplectic Euler and the compositions of Störmer-Verlet: Ψ as the product of kick and drift
//! Jacobians.

use super::*;
use noether_core::natural::{Natural, Potential};

/// Hénon-Heiles with a nonlinear kinetic energy, H = T(p) + V(q), T = ½|p|² + p₁⁴/12, so that the
/// drift Jacobian ∇²T(p) is not constant.
#[derive(Debug, Clone, Copy)]
struct QuarticKinetic;
impl Separable for QuarticKinetic {
    fn dof(&self) -> usize {
        2
    }
    fn kinetic<D: Scalar>(&self, p: &[D]) -> D {
        (p[0] * p[0] + p[1] * p[1]) * 0.5 + p[0].powi(4) / 12.0
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        (q[0] * q[0] + q[1] * q[1]) * 0.5 + q[0] * q[0] * q[1] - q[1].powi(3) / 3.0
    }
}

/// The Hénon-Heiles potential for a natural system L = ½ q̇ᵀMq̇ − V(q).
#[derive(Debug, Clone, Copy)]
struct HenonHeilesPotential;
impl Potential for HenonHeilesPotential {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        (q[0] * q[0] + q[1] * q[1]) * 0.5 + q[0] * q[0] * q[1] - q[1].powi(3) / 3.0
    }
}

/// Every split method on `sys`: (name, |Ψ − Ψ_fd|, det Ψ − 1, |ΨᵀΩΨ − Ω|).
fn all_methods<S>(sys: &S, state: &State<S::Partner>, h: f64) -> Vec<(&'static str, f64, f64, f64)>
where
    S: noether_core::integrators::SplitDynamics + noether_core::integrators::LinearizedDynamics,
    S::Partner: std::fmt::Debug,
{
    fn one<T: TangentStepper>(m: &mut T, s: &State<T::Partner>, h: f64) -> (&'static str, f64, f64, f64)
    where
        T::Partner: std::fmt::Debug,
    {
        let e = tangent_vs_differences(m, s, h);
        let (mut s1, mut psi) = (s.clone(), DMatrix::zeros(2 * m.dof(), 2 * m.dof()));
        m.step_tangent(&mut s1, h, &mut psi).unwrap();
        (m.name(), e, psi.determinant() - 1.0, symplecticity_defect(&psi))
    }
    vec![
        one(&mut SymplecticEuler::new(sys), state, h),
        one(&mut Composition::stormer_verlet(sys), state, h),
        one(&mut Composition::yoshida4(sys), state, h),
        one(&mut Composition::suzuki4(sys), state, h),
        one(&mut Composition::yoshida6(sys), state, h),
        one(&mut Composition::kahan_li6(sys), state, h),
        one(&mut Composition::kahan_li8(sys), state, h),
    ]
}

#[test]
fn split_tangents_match_central_differences_and_are_symplectic() {
    // On (q, p) of a separable H every kick and drift is a symplectic shear, so Ψ is symplectic and
    // det Ψ = 1 (Liouville) to rounding.
    let sys = SeparableHamiltonian(QuarticKinetic);
    for (name, e, det, sym) in all_methods(&sys, &henon_heiles_state(), 0.1) {
        println!("{name}: |Ψ − Ψ_fd| = {e:e}, det Ψ − 1 = {det:e}, |ΨᵀΩΨ − Ω| = {sym:e}");
        // Measured |Ψ − Ψ_fd| 2.7e-12 (Verlet) to 9.7e-12 (Yoshida 6, whose large substeps make the
        // third derivatives the reference's truncation error sees larger): the central
        // differences' own error (FD_REL). det Ψ − 1 at most 3.3e-16 and |ΨᵀΩΨ − Ω| at most 3.3e-16:
        // rounding of up to 35 shears.
        assert!(e < 2e-11, "{name}: {e:e}");
        assert!(det.abs() < 2e-15 && sym < 2e-15, "{name}: {det:e} {sym:e}");
    }
}

#[test]
fn split_tangents_of_a_natural_system_match_central_differences() {
    // On (q, q̇) with a constant M, Ψ is conjugate to a symplectic map by diag(I, M): det Ψ = 1 still.
    let m = DMatrix::from_row_slice(2, 2, &[2.0, 0.5, 0.5, 1.0]);
    let sys = Natural::dense(HenonHeilesPotential, m).unwrap();
    let s = State::new(0.0, [0.1, -0.2], [0.25, 0.1]);
    for (name, e, det, _) in all_methods(&sys, &s, 0.1) {
        println!("natural {name}: |Ψ − Ψ_fd| = {e:e}, det Ψ − 1 = {det:e}");
        // Measured |Ψ − Ψ_fd| 1.2e-12 to 6.6e-12 (Kahan-Li 8), det Ψ − 1 at most 6.7e-16.
        assert!(e < 2e-11, "{name}: {e:e}");
        assert!(det.abs() < 2e-15, "{name}: {det:e}");
    }
}

#[test]
fn split_tangent_error_contract() {
    let sys = SeparableHamiltonian(QuarticKinetic);
    error_contract(&mut Composition::yoshida4(&sys), &henon_heiles_state(), 0.1);
    error_contract(&mut SymplecticEuler::new(&sys), &henon_heiles_state(), 0.1);
}
