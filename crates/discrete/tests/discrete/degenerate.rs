//! Degenerate Lagrangians (linear in q̇): the momenta are fixed by the position, p = ∂L/∂q̇ = a(q)
//! (the primary constraint), and a state with p off it has no motion. Before the check, such a start
//! took a wild step: for the vortex below with p off by δ = 0.1, the first midpoint step moved by
//! |Δ| = 0.2 ≈ 2|δ| at every h (0.2 at h = 1e-3, 200 times the true step), and the offset came back
//! with the opposite sign after the step (a parasitic mode that never dies out).

use noether_core::integrators::{Composition, SignedStepper, Weights};
use noether_core::{Error, Lagrangian, Scalar, Stepper};
use noether_discrete::VariationalIntegrator;
use noether_discrete::{primary, Midpoint, OffPrimaryConstraint, Trapezoidal};

type State = noether_core::State<noether_core::Momenta>;

/// A point vortex (a guiding centre) in a harmonic potential: L = ½(x ẏ − y ẋ) − ½ω(x² + y²),
/// a(q) = ∂L/∂q̇ = ½(−y, x), ∂²L/∂q̇² = 0, Ω = Da − Daᵀ = [[0, −1], [1, 0]], and Lagrange's equation
/// Ω q̇ = −∇V gives ẋ = −ωy, ẏ = ωx: a rotation at the rate ω.
struct Vortex {
    omega: f64,
}
impl Lagrangian for Vortex {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (q[0] * v[1] - q[1] * v[0]) * 0.5 - (q[0] * q[0] + q[1] * q[1]) * (0.5 * self.omega)
    }
}

/// Partly degenerate: L = ½ẋ² + x ẏ − ½(x² + y²), M = diag(1, 0), so p_x is free and p_y = x.
struct HalfDegenerate;
impl Lagrangian for HalfDegenerate {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * 0.5 + q[0] * v[1] - (q[0] * q[0] + q[1] * q[1]) * 0.5
    }
}

/// The vortex at q = (1, 0) with momenta a(q) = (0, ½) moved by δ along y.
fn vortex_start(delta: f64) -> State {
    State::with_momenta(0.0, [1.0, 0.0], [0.0, 0.5 + delta])
}

fn off(e: &Error) -> OffPrimaryConstraint {
    match noether_discrete::Error::from(e.clone()) {
        noether_discrete::Error::OffPrimaryConstraint(o) => o,
        other => panic!("expected OffPrimaryConstraint, got {other:?}"),
    }
}

/// p off the primary constraint by δ = 1e-3 (10⁵ times the tolerance 1e-8·|p|) is refused before the
/// step by midpoint, trapezoidal and a composition of midpoint steps, with the residual |δ| (p_y =
/// 0.501 carries ~1e-16 of rounding: compared to 1e-15) and the bound τ·|p| = 1e-8·0.501; both null
/// directions of M = 0 are named; the state is left bit for bit.
#[test]
fn bad_input_degenerate_momenta_off_primary_constraint() {
    let check = |e: Error| {
        let o = off(&e);
        assert!((o.residual - 1e-3).abs() < 1e-15, "{o:?}");
        assert!((o.tolerance - 1e-8 * 0.501).abs() < 1e-22, "{o:?}");
        assert_eq!((o.null_directions, o.t), (2, 0.0));
    };
    let before = vortex_start(1e-3);
    let mut s = before.clone();
    let mut mid = VariationalIntegrator::new(Midpoint::new(Vortex { omega: 1.0 }));
    check(mid.step(&mut s, 0.01).unwrap_err());
    let mut trap = VariationalIntegrator::new(Trapezoidal::new(Vortex { omega: 1.0 }));
    check(trap.step(&mut s, 0.01).unwrap_err());
    let mut comp = Composition::new(
        VariationalIntegrator::new(Midpoint::new(Vortex { omega: 1.0 })),
        Weights::yoshida4(),
    );
    check(comp.step(&mut s, 0.01).unwrap_err());
    let mut back = State::with_momenta(0.0, [1.0, 0.0], [0.0, 0.501]);
    check(mid.step_signed(&mut back, -0.01).unwrap_err());
    assert_eq!(back, State::with_momenta(0.0, [1.0, 0.0], [0.0, 0.501]));
    assert_eq!(s, before);
    assert!(
        noether_core::Error::from(off(&mid.step(&mut s, 0.01).unwrap_err()))
            .to_string()
            .contains("primary constraint")
    );
}

/// The check is relative: off by half the bound τ·|p| (τ = 1e-8, |p| = ½) the start is accepted, off
/// by twice the bound it is refused; a tolerance set to 1e-6 accepts the second. Tolerances that are
/// not finite and positive are refused when set.
#[test]
fn bad_input_primary_tolerance_boundary() {
    let bound = primary::DEFAULT_TOLERANCE * 0.5;
    let mut vi = VariationalIntegrator::new(Midpoint::new(Vortex { omega: 1.0 }));
    assert_eq!(vi.get_primary_tolerance(), 1e-8);
    vi.step(&mut vortex_start(0.5 * bound), 0.01).unwrap();
    let mut vi = VariationalIntegrator::new(Midpoint::new(Vortex { omega: 1.0 }));
    assert!(vi.step(&mut vortex_start(2.0 * bound), 0.01).is_err());
    let mut vi = vi.primary_tolerance(1e-6).unwrap();
    vi.step(&mut vortex_start(2.0 * bound), 0.01).unwrap();
    for tol in [0.0, -1e-8, f64::NAN, f64::INFINITY] {
        let vi = VariationalIntegrator::new(Midpoint::new(Vortex { omega: 1.0 }));
        assert!(
            matches!(vi.primary_tolerance(tol), Err(Error::InvalidParameter { .. })),
            "tol {tol}"
        );
    }
}

/// A consistent start (p from the Legendre map) integrates: with p = a(q) the midpoint step solves
/// Ω Δ = −h ∇V(q_mid) exactly, the implicit midpoint rule for q̇ = ωJq, whose step is the Cayley
/// transform of hωJ: a rotation by θ = 2 atan(ωh/2). So q_k = R(kθ) q₀ and r² = x² + y² (and the
/// energy h = V = ½ω r²) is kept, and p stays on the constraint, ε_k = p_k − a(q_k) = 0 (the offset
/// maps as ε_{k+1} = −ε_k for this L). Measured after 1000 steps of h = 0.01 (t = 10, 10/2π turns):
/// |q − R(kθ)q₀| = 2.4e-15, |r² − 1| = 5.1e-15, |ε| = 3.5e-15: rounding accumulated over 1000 steps,
/// bounded at 2e-14. Against the exact rotation by ωt the error is t ω³h²/12 = 8.3e-5 (θ − ωh =
/// −(ωh)³/12 + …), checked to 1 %. A kick (p changed between steps) is checked again and refused;
/// the trapezoidal rule from the same consistent start runs too; its momenta leave the constraint by
/// ε_{k+1} = −ε_k + (h/2)(∇V(q_k) − ∇V(q_{k+1})), measured max |ε| = 5.0e-5 = ωh²r/2 (bounded at 6e-5),
/// so a state of a trapezoidal run handed to a fresh integrator is refused at the default tolerance.
#[test]
fn conserves_vortex_consistent_start() {
    let (omega, h, n) = (1.0, 0.01, 1000);
    let mut vi = VariationalIntegrator::new(Midpoint::new(Vortex { omega }));
    let mut s = vi.state_from_velocities(0.0, &[1.0, 0.0], &[0.3, -2.0]).unwrap();
    assert_eq!(s.v.as_slice(), &[0.0, 0.5]);
    let (mut worst_r, mut worst_e) = (0.0_f64, 0.0_f64);
    for _ in 0..n {
        vi.step(&mut s, h).unwrap();
        let (x, y) = (s.q[0], s.q[1]);
        worst_r = worst_r.max((x * x + y * y - 1.0).abs());
        worst_e = worst_e.max((s.v[0] + 0.5 * y).abs().max((s.v[1] - 0.5 * x).abs()));
    }
    let theta = n as f64 * 2.0 * (0.5 * omega * h).atan();
    let err_q = ((s.q[0] - theta.cos()).powi(2) + (s.q[1] - theta.sin()).powi(2)).sqrt();
    let wt = omega * s.t;
    let err_exact = ((s.q[0] - wt.cos()).powi(2) + (s.q[1] - wt.sin()).powi(2)).sqrt();
    eprintln!("vortex: |q − R(kθ)q₀| {err_q:.3e}, |r² − 1| {worst_r:.3e}, |ε| {worst_e:.3e}, vs exact {err_exact:.4e}");
    assert!(err_q < 2e-14 && worst_r < 2e-14 && worst_e < 2e-14);
    let predicted = s.t * omega.powi(3) * h * h / 12.0;
    assert!(
        (err_exact / predicted - 1.0).abs() < 0.01,
        "{err_exact:e} vs {predicted:e}"
    );

    let kicked = {
        let mut k = s.clone();
        k.v[0] += 1e-3;
        k
    };
    let mut k = kicked.clone();
    assert!(off(&vi.step(&mut k, h).unwrap_err()).residual > 0.9e-3);
    assert_eq!(k, kicked);

    let mut trap = VariationalIntegrator::new(Trapezoidal::new(Vortex { omega }));
    let mut s = trap.state_from_velocities(0.0, &[1.0, 0.0], &[0.0, 0.0]).unwrap();
    let mut worst_e = 0.0_f64;
    for _ in 0..n {
        trap.step(&mut s, h).unwrap();
        worst_e = worst_e.max((s.v[0] + 0.5 * s.q[1]).abs().max((s.v[1] - 0.5 * s.q[0]).abs()));
    }
    eprintln!("vortex trapezoidal: |ε| {worst_e:.3e}");
    assert!(worst_e < 6e-5 && worst_e > 4e-5, "{worst_e:e}");
}

/// Partly degenerate L = ½ẋ² + x ẏ − V: M = diag(1, 0). Any p_x is a velocity; p_y must equal x.
/// p = (0.7, x) steps; p_y = x + 1e-3 is refused with one null direction and residual 1e-3 (rounding
/// of 1.001: compared to 1e-15). A regular Lagrangian never refuses (the rest of the suite).
#[test]
fn bad_input_partly_degenerate() {
    let mut vi = VariationalIntegrator::new(Midpoint::new(HalfDegenerate));
    let mut s = State::with_momenta(0.0, [1.0, 0.0], [0.7, 1.0]);
    vi.step(&mut s, 0.01).unwrap();
    let mut vi = VariationalIntegrator::new(Midpoint::new(HalfDegenerate));
    let before = State::with_momenta(0.0, [1.0, 0.0], [0.7, 1.001]);
    let mut s = before.clone();
    let e = vi.step(&mut s, 0.01).unwrap_err();
    let o = off(&e);
    assert_eq!(o.null_directions, 1);
    assert!((o.residual - 1e-3).abs() < 1e-15, "{o:?}");
    assert_eq!(s, before);
}

/// The Galerkin integrators start their Newton from the velocity of the inverse Legendre map, which a
/// degenerate Lagrangian does not have: they refuse it, consistent start or not, with
/// `SingularMassMatrix` (pivot ratio 0 for M = 0), the state left as it was.
#[test]
fn bad_input_galerkin_degenerate() {
    let mut g = noether_discrete::Galerkin::order4(Vortex { omega: 1.0 }).unwrap();
    let before = vortex_start(0.0);
    let mut s = before.clone();
    assert!(matches!(
        g.step(&mut s, 0.01),
        Err(Error::SingularMassMatrix { pivot_ratio, .. }) if pivot_ratio == 0.0
    ));
    assert_eq!(s, before);
}
