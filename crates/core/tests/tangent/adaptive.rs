//! DOPRI5 and DOP853: Ψ of the accepted step with h frozen.

use super::*;

#[test]
fn fixed_step_dormand_prince_tangents_match_central_differences() {
    let sys = HamiltonEquations::new(HenonHeiles);
    let s = henon_heiles_state();
    let e5 = tangent_vs_differences(&mut Dopri5::new(&sys).fixed_step(true), &s, 0.1);
    let e8 = tangent_vs_differences(&mut Dop853::new(&sys).fixed_step(true), &s, 0.1);
    println!("DOPRI5 {e5:e}, DOP853 {e8:e}");
    // Measured 2.1e-12, 2.3e-12: the central differences' own error (see FD_REL).
    assert!(e5 < 1e-11 && e8 < 1e-11, "{e5:e} {e8:e}");
}

#[test]
fn an_accepted_adaptive_step_has_the_tangent_of_its_step_size() {
    // With error control on, Ψ is the derivative at the h the step took (the controller's choice
    // of h is frozen). h = 0.02 is accepted at the default tolerances from y₀ and from every
    // perturbed start of the reference, so both take the same h.
    let sys = HamiltonEquations::new(HenonHeiles);
    let s = henon_heiles_state();
    let mut dp = Dopri5::new(&sys);
    let mut probe = s.clone();
    let info = dp.step(&mut probe, 0.02).unwrap();
    assert_eq!((info.h, info.rejected), (0.02, 0));
    let e5 = tangent_vs_differences(&mut dp, &s, 0.02);
    let e8 = tangent_vs_differences(&mut Dop853::new(&sys), &s, 0.02);
    println!("adaptive DOPRI5 {e5:e}, DOP853 {e8:e}");
    // Measured 1.9e-12, 1.9e-12: the central differences' own error.
    assert!(e5 < 1e-11 && e8 < 1e-11, "{e5:e} {e8:e}");
}

#[test]
fn after_a_rejection_the_tangent_is_that_of_the_step_taken() {
    // A first trial of h = 1 is rejected at tight tolerances; Ψ must be the one of the smaller h
    // actually taken (compared with the fixed-step method at that h).
    let sys = HamiltonEquations::new(HenonHeiles);
    let s = henon_heiles_state();
    let mut dp = Dopri5::new(&sys).tolerances(1e-12, 1e-12).unwrap();
    let (mut a, mut psi) = (s.clone(), DMatrix::zeros(4, 4));
    let info = dp.step_tangent(&mut a, 1.0, &mut psi).unwrap();
    assert!(info.rejected > 0 && info.h < 1.0);
    let (mut b, mut fixed_psi) = (s.clone(), DMatrix::zeros(4, 4));
    Dopri5::new(&sys)
        .fixed_step(true)
        .step_tangent(&mut b, info.h, &mut fixed_psi)
        .unwrap();
    assert_eq!(a, b);
    assert_eq!(psi, fixed_psi);
}

#[test]
fn adaptive_tangent_error_contract() {
    let sys = HamiltonEquations::new(HenonHeiles);
    error_contract(&mut Dop853::new(&sys), &henon_heiles_state(), 0.1);
}
