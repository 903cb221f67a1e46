//! Explicit methods: Ψ by the differentiated stages.

use super::*;

#[test]
fn rk4_and_first_order_tangents_match_central_differences() {
    let sys = HamiltonEquations::new(HenonHeiles);
    let s = henon_heiles_state();
    let errs = [
        tangent_vs_differences(&mut Rk4::new(&sys), &s, 0.1),
        tangent_vs_differences(&mut Euler::new(&sys), &s, 0.1),
        tangent_vs_differences(&mut EulerCromer::new(&sys), &s, 0.1),
    ];
    // Measured 1.4e-12, 1.7e-12, 1.7e-12: the central differences' own error (see FD_REL).
    for e in errs {
        assert!(e < 1e-11, "|Ψ − Ψ_fd| = {e:e}");
    }
}

#[test]
fn a_wrongly_shaped_jacobian_is_refused_and_the_state_kept() {
    let mut rk4 = Rk4::new(HamiltonEquations::new(HenonHeiles));
    let mut s = henon_heiles_state();
    let before = s.clone();
    let mut psi = DMatrix::zeros(3, 4);
    let err = rk4.step_tangent(&mut s, 0.1, &mut psi).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Dimension {
                expected: 4,
                got: 3,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(s, before);
}
