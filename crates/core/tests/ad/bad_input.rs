//! Degenerate Lagrangians, wrong dimensions and non-finite input give their errors, never a panic or
//! a NaN state.

use super::systems::{Chain, DoublePendulum};
use noether_core::{Error, EulerLagrange, HamiltonEquations, Hamiltonian, Lagrangian, Scalar};

/// L = q̇₁ q₂ − ½ (q₁² + q₂²): linear in q̇, M = 0 (a first-order, degenerate Lagrangian).
struct LinearInVelocity;
impl Lagrangian for LinearInVelocity {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * q[1] - (q[0] * q[0] + q[1] * q[1]) * 0.5
    }
}

/// L = ½ (q̇₁ + q̇₂)² − ½ q₁²: M = [[1, 1], [1, 1]], rank one (a gauge-like redundancy).
struct RankDeficient;
impl Lagrangian for RankDeficient {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let s = v[0] + v[1];
        s * s * 0.5 - q[0] * q[0] * 0.5
    }
}

/// 14 coordinates where the last velocity does not appear: M singular on the taped path.
struct Degenerate14;
impl Lagrangian for Degenerate14 {
    fn dof(&self) -> usize {
        14
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (0..13).fold(D::zero(), |acc, i| acc + v[i] * v[i] * 0.5 - q[i] * q[i] * 0.5) + q[13] * v[0]
    }
}

fn singular<T: std::fmt::Debug>(r: noether_core::Result<T>) {
    assert!(
        matches!(r, Err(Error::SingularMassMatrix { .. })),
        "expected SingularMassMatrix, got {r:?}"
    );
}

#[test]
fn bad_input_singular_mass_matrix_linear_in_velocity() {
    let el = EulerLagrange::new(LinearInVelocity);
    let mut a = [0.0; 2];
    singular(el.accelerations(0.0, &[0.3, 0.4], &[0.1, 0.2], &mut a));
    singular(el.mass_factor(0.0, &[0.3, 0.4], &[0.1, 0.2]));
    singular(el.velocities(0.0, &[0.3, 0.4], &[1.0, 2.0]));
    assert_eq!(a, [0.0; 2], "no NaN written on error");
}

#[test]
fn bad_input_singular_mass_matrix_rank_deficient() {
    let el = EulerLagrange::new(RankDeficient);
    let mut a = [0.0; 2];
    singular(el.accelerations(0.0, &[0.3, 0.4], &[0.1, 0.2], &mut a));
    singular(el.velocities(0.0, &[0.3, 0.4], &[1.0, 2.0]));
}

#[test]
fn bad_input_singular_mass_matrix_taped_path() {
    let el = EulerLagrange::new(Degenerate14);
    let mut a = [0.0; 14];
    singular(el.accelerations(0.0, &[0.1; 14], &[0.2; 14], &mut a));
    singular(el.mass_factor(0.0, &[0.1; 14], &[0.2; 14]));
    assert_eq!(a, [0.0; 14], "nothing written on error");
}

/// 12 free relativistic coordinates, L = −Σ_i sqrt(1 − q̇_i²) − ½ Σ_i q_i² (c = m = 1): NaN for
/// |q̇_i| > 1, on the taped path (more than 10 dof).
struct Relativistic12;
impl Lagrangian for Relativistic12 {
    fn dof(&self) -> usize {
        12
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (0..12).fold(D::zero(), |acc, i| {
            acc - (-v[i] * v[i] + 1.0).sqrt() - q[i] * q[i] * 0.5
        })
    }
}

#[test]
fn bad_input_model_returns_nan_taped_path() {
    let el = EulerLagrange::new(Relativistic12);
    let mut a = [0.0; 12];
    let mut v = [0.3; 12];
    el.accelerations(0.0, &[0.1; 12], &v, &mut a).unwrap();
    // q̈_i = −q_i (1 − q̇_i²)^{3/2}: the sqrt's curvature enters M = diag((1 − q̇_i²)^{−3/2}).
    let expected = -0.1 * (1.0 - 0.09_f64).powf(1.5);
    assert!(
        a.iter().all(|ai| (ai - expected).abs() < 1e-14 * expected.abs()),
        "{a:?}"
    );
    v[7] = 1.2;
    let mut a = [0.0; 12];
    let r = el.accelerations(0.0, &[0.1; 12], &v, &mut a);
    assert!(matches!(r, Err(Error::NonFiniteResult { .. })), "{r:?}");
    assert_eq!(a, [0.0; 12], "nothing written on error");
}

#[test]
fn bad_input_wrong_dimensions() {
    let el = EulerLagrange::new(DoublePendulum::default());
    let mut a2 = [0.0; 2];
    let mut a3 = [0.0; 3];
    let dim = |r: noether_core::Result<()>| assert!(matches!(r, Err(Error::Dimension { .. })), "{r:?}");
    dim(el.accelerations(0.0, &[0.1], &[0.1, 0.2], &mut a2));
    dim(el.accelerations(0.0, &[0.1, 0.2], &[0.1, 0.2, 0.3], &mut a2));
    dim(el.accelerations(0.0, &[0.1, 0.2], &[0.1, 0.2], &mut a3));
    dim(el.momenta(0.0, &[0.1, 0.2], &[0.1, 0.2], &mut a3));
    dim(el.energy(0.0, &[0.1, 0.2, 0.3], &[0.1, 0.2]).map(|_| ()));
    dim(el.mass_matrix(0.0, &[0.1], &[0.1, 0.2]).map(|_| ()));
    dim(el.velocities(0.0, &[0.1, 0.2], &[1.0]).map(|_| ()));

    let chain = EulerLagrange::new(Chain::<15>::default());
    let mut a = [0.0; 15];
    dim(chain.accelerations(0.0, &[0.1; 14], &[0.1; 15], &mut a));

    let h = HamiltonEquations::new(Spring);
    let (mut dq, mut dp) = ([0.0; 1], [0.0; 2]);
    dim(h.rates(0.0, &[0.1], &[0.2], &mut dq, &mut dp));
    dim(h.rates(0.0, &[0.1, 0.2], &[0.2], &mut dq, &mut [0.0]));
}

/// H = ½ p² + ½ q².
struct Spring;
impl Hamiltonian for Spring {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + q[0] * q[0]) * 0.5
    }
}

#[test]
fn bad_input_non_finite_state() {
    let el = EulerLagrange::new(DoublePendulum::default());
    let mut a = [0.0; 2];
    let nf = |r: noether_core::Result<()>| assert!(matches!(r, Err(Error::NonFinite { .. })), "{r:?}");
    nf(el.accelerations(f64::NAN, &[0.1, 0.2], &[0.1, 0.2], &mut a));
    nf(el.accelerations(0.0, &[0.1, f64::NAN], &[0.1, 0.2], &mut a));
    nf(el.accelerations(0.0, &[0.1, 0.2], &[f64::INFINITY, 0.2], &mut a));
    nf(el.momenta(0.0, &[0.1, 0.2], &[f64::NAN, 0.2], &mut a));
    nf(el.energy(0.0, &[f64::NEG_INFINITY, 0.2], &[0.1, 0.2]).map(|_| ()));
    nf(el.velocities(0.0, &[0.1, 0.2], &[f64::NAN, 0.2]).map(|_| ()));
    assert_eq!(a, [0.0; 2], "no NaN written on error");

    let h = HamiltonEquations::new(Spring);
    let (mut dq, mut dp) = ([0.0], [0.0]);
    nf(h.rates(0.0, &[f64::NAN], &[0.2], &mut dq, &mut dp));
    nf(h.rates(0.0, &[0.1], &[f64::INFINITY], &mut dq, &mut dp));
}

#[test]
fn bad_input_model_returns_nan() {
    // The relativistic L at |v| > c takes the square root of a negative number: the model itself
    // produces NaN, which must come back as an error, not as NaN accelerations.
    let el = EulerLagrange::new(super::legendre::Relativistic {
        m: 1.0,
        c: 1.0,
        k: 1.0,
    });
    let mut a = [0.0; 3];
    let r = el.accelerations(0.0, &[0.1, 0.2, 0.3], &[1.5, 0.0, 0.0], &mut a);
    assert!(matches!(r, Err(Error::NonFiniteResult { .. })), "{r:?}");
    assert_eq!(a, [0.0; 3]);
}

/// L = ½ q̇² − √q: defined for q ≥ 0 only.
struct RootPotential;
impl Lagrangian for RootPotential {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * 0.5 - q[0].sqrt()
    }
}

/// Issue 15, case 7: outside the model's domain (√ of a negative number) the value-based evaluations
/// used to return Ok with NaN entries, while `accelerations` erred. Each now names the quantity that
/// came out non-finite, and leaves its output untouched; what does not involve √q (p = q̇, M = 1) is
/// still defined there and returned.
#[test]
fn regress_ok_nan_from_every_evaluation() {
    let el = EulerLagrange::new(RootPotential);
    let (q, v) = ([-1.0], [1.0]);
    let non_finite = |r: Result<(), Error>, name: &str| match r {
        Err(Error::NonFiniteResult { what, t, .. }) => assert!(what == name && t == 0.5, "{what} at {t}"),
        other => panic!("{name}: {other:?}"),
    };
    non_finite(el.energy(0.5, &q, &v).map(drop), "energy");
    non_finite(el.value(0.5, &q, &v).map(drop), "Lagrangian");
    let mut out = [7.0];
    non_finite(el.gradient_q(0.5, &q, &v, &mut out), "∂L/∂q");
    assert_eq!(out, [7.0], "nothing written on error");
    el.momenta(0.5, &q, &v, &mut out).unwrap();
    assert_eq!(out, [1.0]);
    assert_eq!(el.mass_matrix(0.5, &q, &v).unwrap()[(0, 0)], 1.0);
    // Inside the domain the same calls succeed: h = ½ q̇² + √q = 0.5 + 2 at q = 4.
    assert_eq!(el.energy(0.5, &[4.0], &v), Ok(2.5));
}

/// Issue 15, case 8: at q = 0, where √q has an infinite derivative, the energy h = ½ q̇² + √q = ½
/// needs no q-derivative and must not be poisoned by one (0·∞ = NaN in a tangent that is zero).
#[test]
fn regress_energy_not_poisoned_by_an_unused_derivative() {
    let el = EulerLagrange::new(RootPotential);
    assert_eq!(el.energy(0.0, &[0.0], &[1.0]), Ok(0.5));
    let mut p = [0.0];
    el.momenta(0.0, &[0.0], &[1.0], &mut p).unwrap();
    assert_eq!(p, [1.0]);
}

/// Issue 15, case 9: `EulerLagrange::value` with an empty q indexed out of bounds inside the model.
#[test]
fn regress_value_checks_its_input() {
    let el = EulerLagrange::new(RootPotential);
    assert!(matches!(el.value(0.0, &[], &[1.0]), Err(Error::Dimension { .. })));
    assert!(matches!(
        el.value(f64::NAN, &[1.0], &[1.0]),
        Err(Error::NonFinite { .. })
    ));
}

/// V(q) = √q₀ + q₁²: the natural system checks its input and output like the Lagrangian one.
struct RootPotentialField;
impl noether_core::Potential for RootPotentialField {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        q[0].sqrt() + q[1] * q[1]
    }
}

/// Issue 15, cases 7 and 9: `Natural::energy`, `momenta` and `potential_energy` indexed out of bounds
/// on wrong lengths and returned NaN outside the potential's domain.
#[test]
fn regress_natural_sizes_and_domain() {
    let nat = noether_core::Natural::unit(RootPotentialField);
    let dim = |r: Result<f64, Error>| assert!(matches!(r, Err(Error::Dimension { .. })), "{r:?}");
    dim(nat.energy(&[1.0], &[0.0, 0.0]));
    dim(nat.energy(&[1.0, 0.0], &[0.0]));
    dim(nat.potential_energy(&[]));
    dim(nat.kinetic_energy(&[1.0, 2.0, 3.0]));
    let mut p = [0.0; 3];
    assert!(matches!(
        nat.momenta(&[1.0, 2.0], &mut p),
        Err(Error::Dimension { .. })
    ));
    assert!(matches!(nat.solve_mass(&mut p), Err(Error::Dimension { .. })));
    assert!(matches!(
        nat.potential_energy(&[-1.0, 0.0]),
        Err(Error::NonFiniteResult {
            what: "potential energy",
            ..
        })
    ));
    // V(4, 1) = 2 + 1, T = ½ (1 + 4): exact in binary.
    assert_eq!(nat.energy(&[4.0, 1.0], &[1.0, 2.0]), Ok(5.5));
}

/// Issue 29, item 11: `EulerLagrange::solve_mass` indexed out of bounds (a panic in the solve) when
/// the right-hand side b had the wrong length, on both the varying and the constant-mass path; a
/// non-finite b came back as Ok(NaN). Now `Dimension` / `NonFinite`, and b is left as it was.
#[test]
fn regress_solve_mass_wrong_length() {
    /// L = ½ (q̇₀² + 2 q̇₁²) − q₀²: M = diag(1, 2), declared constant.
    struct ConstantMass;
    impl Lagrangian for ConstantMass {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
            (v[0] * v[0] + v[1] * v[1] * 2.0) * 0.5 - q[0] * q[0]
        }
        fn constant_mass_matrix(&self) -> bool {
            true
        }
    }
    fn check<L: Lagrangian>(el: &EulerLagrange<L>, q: &[f64], v: &[f64]) {
        // Twice: on the constant path the second call finds the factor cached.
        for _ in 0..2 {
            for len in [0, 1, 3] {
                let mut b = vec![1.0; len];
                let r = el.solve_mass(0.0, q, v, &mut b);
                assert!(matches!(r, Err(Error::Dimension { expected: 2, .. })), "{r:?}");
                assert_eq!(b, vec![1.0; len]);
            }
            let mut b = [f64::NAN, 1.0];
            let r = el.solve_mass(0.0, q, v, &mut b);
            assert!(matches!(r, Err(Error::NonFinite { .. })), "{r:?}");
            assert!(b[0].is_nan() && b[1] == 1.0);
            let mut b = [1.0, 1.0];
            el.solve_mass(0.0, q, v, &mut b).unwrap();
            assert!(b.iter().all(|x| x.is_finite()));
        }
    }
    let cm = EulerLagrange::new(ConstantMass);
    let (q, v) = ([0.1, 0.2], [0.3, -0.1]);
    check(&EulerLagrange::new(DoublePendulum::default()), &q, &v);
    check(&cm, &q, &v);
    // A wrong q on the cached constant path is still refused.
    let mut b = [1.0, 1.0];
    let r = cm.solve_mass(0.0, &[0.1], &v, &mut b);
    assert!(matches!(r, Err(Error::Dimension { .. })), "{r:?}");
    // M = diag(1, 2).
    cm.solve_mass(0.0, &q, &v, &mut b).unwrap();
    assert!((b[0] - 1.0).abs() < 1e-15 && (b[1] - 0.5).abs() < 1e-15, "{b:?}");
}

/// L = ½q̇² − c·q^k (and − c·|q|^k, the error contract's advice), for the issue-29 powers.
struct Power {
    k: f64,
    abs: bool,
}
impl Lagrangian for Power {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let base = if self.abs { q[0].abs() } else { q[0] };
        v[0] * v[0] * 0.5 - base.powf(self.k)
    }
}
impl Hamiltonian for Power {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let base = if self.abs { q[0].abs() } else { q[0] };
        p[0] * p[0] * 0.5 + base.powf(self.k)
    }
}
impl noether_core::Potential for Power {
    fn dof(&self) -> usize {
        1
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        let base = if self.abs { q[0].abs() } else { q[0] };
        base.powf(self.k)
    }
}

/// Issue 29 item 13b: num-dual's `powf` forms xⁿ as x^(n−3)·x³, ∞·0 = NaN at x = 0 even for the
/// value, so the energy of ½v² − q^0.5 or ½v² − q^1.5 at q = 0 was refused (`NonFiniteResult`), and
/// the accelerations of ½v² − q^1.5 (and of the contract's own |q|^1.5) too although V′(0) = 0.
/// noether's jets now take each power by itself at 0: the energy is ½v², the force of q^1.5 is 0
/// (closed form), and only the genuinely infinite force of q^0.5 is refused.
#[test]
fn regress_powf_at_zero_energy_and_forces() {
    let (q, v) = ([0.0], [0.6]);
    for k in [0.5, 1.5, 2.5] {
        for abs in [false, true] {
            let el = EulerLagrange::new(Power { k, abs });
            assert_eq!(el.energy(0.0, &q, &v).unwrap(), 0.18, "k = {k}, abs = {abs}");
            let ham = HamiltonEquations::new(Power { k, abs });
            assert_eq!(ham.energy(0.0, &q, &v).unwrap(), 0.18, "k = {k}, abs = {abs}");
            let nat = noether_core::Natural::unit(Power { k, abs });
            assert_eq!(nat.energy(&q, &v).unwrap(), 0.18, "k = {k}, abs = {abs}");
            let mut a = [f64::NAN];
            let acc = el.accelerations(0.0, &q, &v, &mut a);
            let (mut dq, mut dp) = ([f64::NAN], [f64::NAN]);
            let rates = ham.rates(0.0, &q, &v, &mut dq, &mut dp);
            let mut f = [f64::NAN];
            let forces = nat.forces(&q, &mut f);
            if k > 1.0 {
                // V′(0) = k·0^(k−1) = 0.
                acc.unwrap();
                rates.unwrap();
                forces.unwrap();
                assert_eq!(
                    (a[0], dq[0], dp[0], f[0]),
                    (0.0, 0.6, 0.0, 0.0),
                    "k = {k}, abs = {abs}"
                );
            } else {
                // V′(0) = ½·0^(−½) = ∞: refused, not NaN.
                for r in [acc, rates, forces] {
                    assert!(matches!(r, Err(Error::NonFiniteResult { .. })), "k = {k}: {r:?}");
                }
            }
        }
    }
    // Away from 0 the jets' powf is num-dual's to the bit: V′(q) = 1.5·q^0.5.
    let el = EulerLagrange::new(Power { k: 1.5, abs: false });
    let mut a = [0.0];
    el.accelerations(0.0, &[0.3], &[0.0], &mut a).unwrap();
    use num_dual::DualNum;
    let d = num_dual::first_derivative(|x: num_dual::Dual64| x.powf(1.5), 0.3).1;
    assert_eq!(a[0], -d);
}
