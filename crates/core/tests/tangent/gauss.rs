//! Gauss-Legendre collocation (implicit midpoint, Gauss 4, Gauss 6): Ψ by the implicit-function
//! theorem at the converged stages.

use super::*;

#[test]
fn gauss_tangents_match_central_differences() {
    let sys = HamiltonEquations::new(HenonHeiles);
    let s = henon_heiles_state();
    for stages in 1..=3 {
        let mut g = Gauss::new(&sys, stages).unwrap();
        let e = tangent_vs_differences(&mut g, &s, 0.1);
        println!("Gauss {stages} stages: |Ψ − Ψ_fd| = {e:e}");
        // Measured 1.2e-12, 5.0e-12, 4.3e-12: the reference's own error (FD_REL) plus the Newton
        // tolerance of the perturbed solves (1e-15 relative, divided by 2δ = 2e-5: up to 1e-10 in
        // principle, a few 1e-12 in practice since Newton ends at rounding).
        assert!(e < 1e-11, "Gauss {stages}: |Ψ − Ψ_fd| = {e:e}");
    }
}

/// Harmonic oscillator H = ½(p² + q²): y' = A y with A = [[0, 1], [−1, 0]], A² = −I.
struct Oscillator;
impl Hamiltonian for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + q[0] * q[0]) * 0.5
    }
}

#[test]
fn gauss_tangents_on_a_linear_system_are_the_pade_stability_functions() {
    // For y' = Ay a Gauss step is y₁ = R(hA) y₀ with R the diagonal Padé approximant of exp
    // (Hairer-Wanner II, IV.3): R₁(z) = (1 + z/2)/(1 − z/2), R₂(z) = (1 + z/2 + z²/12)/(1 − z/2 + z²/12),
    // so Ψ = R(hA) exactly. With A² = −I: P(±hA) = (1 − h²/12) I ± (h/2) A for Gauss 4.
    let h = 0.3;
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.0]);
    let id = DMatrix::<f64>::identity(2, 2);
    let expected = [
        (&id - &a * (h / 2.0)).try_inverse().unwrap() * (&id + &a * (h / 2.0)),
        (&id * (1.0 - h * h / 12.0) - &a * (h / 2.0))
            .try_inverse()
            .unwrap()
            * (&id * (1.0 - h * h / 12.0) + &a * (h / 2.0)),
    ];
    for (stages, r) in (1..=2).zip(expected) {
        let mut g = Gauss::new(HamiltonEquations::new(Oscillator), stages).unwrap();
        let (mut s, mut psi) = (State::with_momenta(0.0, [0.7], [-0.2]), DMatrix::zeros(2, 2));
        g.step_tangent(&mut s, h, &mut psi).unwrap();
        let e = (psi - r).abs().max();
        println!("Gauss {stages} on the oscillator: |Ψ − R(hA)| = {e:e}");
        // Measured 5.6e-17, 1.1e-16: rounding (the linear stage system is solved exactly).
        assert!(e < 1e-15, "{e:e}");
    }
}

#[test]
fn gauss_tangents_are_symplectic() {
    // Gauss collocation is symplectic: ΨᵀΩΨ = Ω, so det Ψ = 1 (Liouville).
    let sys = HamiltonEquations::new(HenonHeiles);
    for stages in 1..=3 {
        let mut g = Gauss::new(&sys, stages).unwrap();
        let mut s = henon_heiles_state();
        let mut psi = DMatrix::zeros(4, 4);
        g.step_tangent(&mut s, 0.1, &mut psi).unwrap();
        let (det, sym) = (psi.determinant(), symplecticity_defect(&psi));
        println!(
            "Gauss {stages}: det Ψ − 1 = {:e}, |ΨᵀΩΨ − Ω| = {sym:e}",
            det - 1.0
        );
        // Measured det Ψ − 1 = 0, −2.2e-16, −2.2e-16 and |ΨᵀΩΨ − Ω| = 8.6e-18, 1.1e-16, 1.1e-16:
        // rounding (the map is symplectic exactly when the stages are solved exactly).
        assert!((det - 1.0).abs() < 1e-14 && sym < 1e-14);
    }
}

#[test]
fn gauss_tangent_error_contract() {
    let sys = HamiltonEquations::new(HenonHeiles);
    error_contract(&mut Gauss::gauss4(&sys), &henon_heiles_state(), 0.1);
}
