//! Control: linearisation (A, B) and LQR against the textbooks' closed forms, and a closed loop.

use nalgebra::{Complex, DMatrix};
use noether_analysis::{
    dlqr, linearize, linearize_step, lqr, tvlqr, Error, HeldInputs, HeldStart, Linearization,
    StepLinearization,
};
use noether_core::control::{Actuated, ClosedLoop, LinearFeedback};
use noether_core::prelude::*;
use noether_core::system::LinearizedDynamics;
use noether_testkit::control::CartPole;

/// One step of size `h` of the integrator `method` builds, linearised at the cart-pole's upright rest
/// point with the force held at zero.
fn upright_step<'m, S, F>(cp: &'m CartPole, method: F, h: f64) -> StepLinearization
where
    F: FnOnce(HeldInputs<'m, CartPole>) -> S,
    S: TangentStepper,
    S::Partner: HeldStart,
{
    linearize_step(cp, method, 0.0, (&[0.0, 0.0], &[0.0, 0.0]), &[0.0], h).unwrap()
}

/// The cart-pole upright: A and B are the textbook matrices (`CartPole::upright_linearization`:
/// ẍ = −(mg/M)θ + u/M, θ̈ = (M + m)gθ/(Ml) − u/(Ml)), exact to rounding, and the drift is zero. Off
/// the rest point, with the pole swinging (θ̇* ≠ 0) and a push u* = 0.4, the drift is the
/// accelerations there and B changes with θ.
#[test]
fn closed_form_cart_pole_upright() {
    let cp = CartPole::default();
    let lin = linearize(&cp, 0.0, &[0.3, 0.0], &[0.0, 0.0], &[0.0]).unwrap();
    let (a, b) = cp.upright_linearization();
    let a = DMatrix::from_fn(4, 4, |i, j| a[i][j]);
    let b = DMatrix::from_column_slice(4, 1, &b);
    let (ea, eb) = ((&lin.a - &a).amax() / a.amax(), (&lin.b - &b).amax() / b.amax());
    println!(
        "cart-pole upright: |A − A_exact| {ea:e}, |B − B_exact| {eb:e}, drift {:e}",
        lin.drift.amax()
    );
    // A: the jet's few operations and the 2×2 solve (measured 2.2e-16); B: one solve (1.8e-16).
    assert!(
        ea < 4.0 * f64::EPSILON && eb < 4.0 * f64::EPSILON,
        "{ea:e} {eb:e}"
    );
    assert_eq!(lin.drift.amax(), 0.0);

    // Off the rest point: M [ẍ, θ̈] = [u + m l θ̇² sin θ, m g l sin θ] with
    // M = [[M + m, m l cos θ], [m l cos θ, m l²]], and B's lower half M⁻¹ (1, 0).
    let (th, w, u) = (0.5_f64, 1.2, 0.4);
    let lin = linearize(&cp, 0.0, &[0.3, th], &[-0.2, w], &[u]).unwrap();
    let (big, m, l, g) = (cp.cart, cp.bob, cp.l, cp.g);
    let (c, s) = (th.cos(), th.sin());
    let det = (big + m) * m * l * l - (m * l * c).powi(2);
    let rhs = [u + m * l * w * w * s, m * g * l * s];
    let acc = [
        (m * l * l * rhs[0] - m * l * c * rhs[1]) / det,
        ((big + m) * rhs[1] - m * l * c * rhs[0]) / det,
    ];
    let exact_b = [m * l * l / det, -m * l * c / det];
    let e_drift = (0..2)
        .map(|i| (lin.drift[2 + i] - acc[i]).abs() / acc[i].abs())
        .fold((lin.drift[0] + 0.2).abs() + (lin.drift[1] - w).abs(), f64::max);
    let e_b = (0..2)
        .map(|i| (lin.b[(2 + i, 0)] - exact_b[i]).abs() / exact_b[i].abs())
        .fold(lin.b[(0, 0)].abs() + lin.b[(1, 0)].abs(), f64::max);
    println!("cart-pole swinging: drift {e_drift:e}, B {e_b:e}");
    // Measured 2.7e-16 and 0: rounding of the jet and of the 2×2 solve.
    assert!(
        e_drift < 8.0 * f64::EPSILON && e_b < 8.0 * f64::EPSILON,
        "{e_drift:e} {e_b:e}"
    );
}

/// The double integrator ẍ = u with Q = diag(q₁, q₂), R = r: the Riccati equation solves by hand
/// (entries (1,1), (2,2) of AᵀX + XA − XBR⁻¹BᵀX + Q = 0 give x₁₂ = √(q₁r), x₂₂ = √(r(q₂ + 2x₁₂)),
/// and (1,2) x₁₁ = x₁₂x₂₂/r), so K = (√(q₁/r), √((q₂ + 2√(q₁r))/r)) and the closed loop's poles are
/// the roots of s² + k₂s + k₁.
#[test]
fn closed_form_lqr_double_integrator() {
    let (q1, q2, r) = (4.0, 0.5, 0.25);
    let lin = Linearization {
        a: DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]),
        b: DMatrix::from_column_slice(2, 1, &[0.0, 1.0]),
        drift: nalgebra::DVector::zeros(2),
    };
    let design = lqr(
        &lin,
        &DMatrix::from_diagonal(&nalgebra::dvector![q1, q2]),
        &DMatrix::from_element(1, 1, r),
    )
    .unwrap();
    let x12 = (q1 * r).sqrt();
    let x22 = (r * (q2 + 2.0 * x12)).sqrt();
    let k = [x12 / r, x22 / r];
    let x = [[x12 * x22 / r, x12], [x12, x22]];
    let e_k = (0..2)
        .map(|j| (design.gain[(0, j)] - k[j]).abs() / k[j])
        .fold(0.0, f64::max);
    let e_x = (0..4)
        .map(|i| (design.riccati[(i / 2, i % 2)] - x[i / 2][i % 2]).abs() / x[i / 2][i % 2])
        .fold(0.0, f64::max);
    // s² + k₂ s + k₁ = 0.
    let disc = k[1] * k[1] - 4.0 * k[0];
    let mut poles: Vec<f64> = design.closed_loop.iter().map(|l| l.re + l.im.abs()).collect();
    poles.sort_by(f64::total_cmp);
    let exact = if disc >= 0.0 {
        [(-k[1] - disc.sqrt()) / 2.0, (-k[1] + disc.sqrt()) / 2.0]
    } else {
        let (re, im) = (-k[1] / 2.0, (-disc).sqrt() / 2.0);
        [re + im, re + im]
    };
    let e_p = (0..2)
        .map(|i| (poles[i] - exact[i]).abs() / exact[i].abs())
        .fold(0.0, f64::max);
    println!("LQR double integrator: K {e_k:e}, X {e_x:e}, poles {e_p:e}");
    // Measured 1.4e-16, 1.4e-16, 1.2e-15: the sign function refined by Newton-Kleinman to rounding
    // (the poles through a 2×2 eigenvalue solve).
    assert!(
        e_k < 1e-15 && e_x < 1e-15 && e_p < 1e-14,
        "{e_k:e} {e_x:e} {e_p:e}"
    );
}

/// The cart-pole balanced by LQR: the closed loop u = −K δx, run as a `ClosedLoop` through noether's
/// Jacobian, linearises exactly to A − BK (the policy differentiated with the model), whose
/// eigenvalues are the design's, all in the left half-plane; from a 0.3 rad lean the nonlinear closed
/// loop comes back upright: after 15 s the slowest pole (Re λ ≈ −2.0) leaves 0.3·e^{−30} ≈ 3e-14
/// times the eigenvectors' conditioning (measured |θ| 2.0e-13, |x| 1.4e-14; bound 1e-11).
#[test]
fn cart_pole_balanced_by_lqr() {
    let cp = CartPole::default();
    let lin = linearize(&cp, 0.0, &[0.0, 0.0], &[0.0, 0.0], &[0.0]).unwrap();
    let q = DMatrix::from_diagonal(&nalgebra::dvector![10.0, 10.0, 1.0, 1.0]);
    let design = lqr(&lin, &q, &DMatrix::from_element(1, 1, 0.1)).unwrap();
    let feedback = LinearFeedback::new(design.gain.clone(), &[0.0, 0.0], &[0.0, 0.0], &[0.0]).unwrap();
    let closed = EulerLagrange::new(ClosedLoop::new(cp, feedback).unwrap());
    let mut jac = DMatrix::zeros(4, 4);
    closed.jacobian(0.0, &[0.0, 0.0], &[0.0, 0.0], &mut jac).unwrap();
    let expected = &lin.a - &lin.b * &design.gain;
    let e_j = (&jac - &expected).amax() / expected.amax();
    let slowest = design
        .closed_loop
        .iter()
        .map(|l| l.re)
        .fold(f64::NEG_INFINITY, f64::max);
    let dop = Dop853::new(&closed).tolerances(1e-12, 1e-12).unwrap();
    let sol = Driver::new(dop, State::new(0.0, [0.0, 0.3], [0.0, 0.0]))
        .unwrap()
        .run_until(15.0)
        .unwrap();
    let end = sol.last();
    println!(
        "cart-pole LQR: |J − (A − BK)| {e_j:e}, slowest pole {slowest:.3}, at t = 15: x {:e}, θ {:e}",
        end.q[0], end.q[1]
    );
    // J: rounding of the jet and the 2×2 solve (measured 1.9e-16).
    assert!(e_j < 2e-15, "{e_j:e}");
    assert!(slowest < 0.0);
    assert!(end.q[0].abs() < 1e-11 && end.q[1].abs() < 1e-11, "{:?}", end.q);
}

/// Typed errors: an unstable mode the input cannot reach has no stabilising solution; an R that is
/// not positive definite is refused.
#[test]
fn lqr_errors_are_typed() {
    let lin = Linearization {
        a: DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 1.0, 0.0]),
        b: DMatrix::zeros(2, 1),
        drift: nalgebra::DVector::zeros(2),
    };
    let q = DMatrix::identity(2, 2);
    let err = lqr(&lin, &q, &DMatrix::from_element(1, 1, 1.0)).unwrap_err();
    assert!(matches!(err, Error::NoStabilizingSolution { .. }), "{err}");
    let cp = CartPole::default();
    let lin = linearize(&cp, 0.0, &[0.0, 0.0], &[0.0, 0.0], &[0.0]).unwrap();
    let err = lqr(&lin, &DMatrix::identity(4, 4), &DMatrix::from_element(1, 1, -1.0)).unwrap_err();
    assert!(
        matches!(err, Error::Core(noether_core::Error::InvalidParameter { .. })),
        "{err}"
    );
}

/// One RK4 step of the cart-pole from the upright rest point with the input held: at an equilibrium
/// every stage of the step sits at the point, so the step's Jacobian is RK4 applied to the
/// continuous linearisation, A_d = Σ_{k=0}^{4} (Ah)^k/k! and B_d = Σ_{k=1}^{4} A^{k−1} h^k/k! B, with
/// A, B the textbook matrices (`closed_form_cart_pole_upright`). Exact to rounding (measured 2e-16
/// relative); the step stays at the rest point.
#[test]
fn rk4_step_linearization_is_rk4_on_the_linearization() {
    let cp = CartPole::default();
    let h = 0.05;
    let step = upright_step(&cp, |l| Rk4::new(EulerLagrange::new(l)), h);
    let lin = linearize(&cp, 0.0, &[0.0, 0.0], &[0.0, 0.0], &[0.0]).unwrap();
    let (mut a_d, mut b_d) = (DMatrix::identity(4, 4), DMatrix::zeros(4, 1));
    let mut power = DMatrix::identity(4, 4); // (Ah)^k / k!
    for k in 1..=4 {
        b_d += &power * &lin.b * (h / k as f64);
        power = &power * &lin.a * (h / k as f64);
        a_d += &power;
    }
    let (ea, eb) = (
        (&step.a - &a_d).amax() / a_d.amax(),
        (&step.b - &b_d).amax() / b_d.amax(),
    );
    println!("RK4 step of the cart-pole upright: |A_d − T₄(Ah)| {ea:e}, |B_d − closed form| {eb:e}");
    assert!(
        ea < 4.0 * f64::EPSILON && eb < 4.0 * f64::EPSILON,
        "{ea:e} {eb:e}"
    );
    assert_eq!(step.next.amax(), 0.0);
}

/// The scalar sampled system δx_{k+1} = a δx_k + b δu_k as a step linearisation.
fn scalar_step(a: f64, b: f64) -> StepLinearization {
    StepLinearization {
        a: DMatrix::from_element(1, 1, a),
        b: DMatrix::from_element(1, 1, b),
        next: nalgebra::DVector::zeros(2),
        h: 1.0,
    }
}

/// The scalar discrete Riccati equation x = a²x − (abx)²/(r + b²x) + q is the quadratic
/// b²x² + (r(1 − a²) − q b²) x − q r = 0, whose positive root is the stabilising solution, with gain
/// k = abx/(r + b²x) and closed loop a − bk inside the unit circle; `dlqr` meets it to rounding
/// (measured 1e-16 relative).
#[test]
fn closed_form_scalar_discrete_riccati() {
    let (a, b, q, r) = (1.2_f64, 0.5_f64, 1.0_f64, 0.3_f64);
    let step = scalar_step(a, b);
    let design = dlqr(
        &step,
        &DMatrix::from_element(1, 1, q),
        &DMatrix::from_element(1, 1, r),
    )
    .unwrap();
    let lin = r * (1.0 - a * a) - q * b * b;
    let x = (-lin + (lin * lin + 4.0 * b * b * q * r).sqrt()) / (2.0 * b * b);
    let k = a * b * x / (r + b * b * x);
    let (ex, ek) = (
        (design.riccati[(0, 0)] - x).abs() / x,
        (design.gain[(0, 0)] - k).abs() / k,
    );
    println!("scalar DARE: x = {x}, |Δx|/x {ex:e}, |Δk|/k {ek:e}");
    assert!(
        ex < 4.0 * f64::EPSILON && ek < 4.0 * f64::EPSILON,
        "{ex:e} {ek:e}"
    );
    assert!((design.closed_loop[0].re - (a - b * k)).abs() < 4.0 * f64::EPSILON);
    // Not stabilisable: an unstable a that no input reaches (b = 0).
    let stuck = StepLinearization {
        b: DMatrix::zeros(1, 1),
        ..step
    };
    assert!(matches!(
        dlqr(
            &stuck,
            &DMatrix::from_element(1, 1, q),
            &DMatrix::from_element(1, 1, r)
        ),
        Err(Error::NoStabilizingSolution { .. })
    ));
}

/// A sampled LQR of the cart-pole (RK4 steps of h, weights Q h and R h: the sums approximate the
/// integrals) stabilises the step (every |λ| < 1) and tends to the continuous design as h → 0 at
/// first order: ‖K_d(h) − K‖ halves with h (measured order 0.976, tolerance 0.05). The constant is
/// large: |K_d − K| = 3.5 at h = 0.01 against |K| = 74, about |K|·h·|A − BK| for the fast closed loop
/// of an inverted pendulum whose unstable rate is √((M + m)g/(Ml)) ≈ 4.
#[test]
fn sampled_lqr_tends_to_the_continuous_design() {
    let cp = CartPole::default();
    let weights = DMatrix::from_diagonal(&nalgebra::dvector![10.0, 10.0, 1.0, 1.0]);
    let r = DMatrix::from_element(1, 1, 0.1);
    let lin = linearize(&cp, 0.0, &[0.0, 0.0], &[0.0, 0.0], &[0.0]).unwrap();
    let continuous = lqr(&lin, &weights, &r).unwrap();
    let distance = |h: f64| {
        let step = upright_step(&cp, |l| Rk4::new(EulerLagrange::new(l)), h);
        let design = dlqr(&step, &(&weights * h), &(&r * h)).unwrap();
        assert!(design.closed_loop.iter().all(|l| l.norm() < 1.0));
        (&design.gain - &continuous.gain).amax()
    };
    let (d1, d2) = (distance(0.01), distance(0.005));
    let order = (d1 / d2).log2();
    println!("sampled LQR: |K_d − K| = {d1:.3e} (h = 0.01), {d2:.3e} (h = 0.005): order {order:.3}");
    assert!((order - 1.0).abs() < 0.05, "{order}");
}

/// The heavy symmetric top in Cardan angles q = (α, β, γ), the body frame R = R_x(α) R_y(β) R_z(γ):
/// ω_body = (α̇ cos β cos γ + β̇ sin γ, −α̇ cos β sin γ + β̇ cos γ, γ̇ + α̇ sin β), the centre of mass at
/// height ℓ cos α cos β, so
///
///   L = ½ I₁ (α̇² cos²β + β̇²) + ½ I₃ (γ̇ + α̇ sin β)² − M g ℓ cos α cos β,
///
/// a chart that is regular at the vertical (Euler angles are not), where the top sleeps.
struct CardanTop {
    i1: f64,
    i3: f64,
    mgl: f64,
}

impl Lagrangian for CardanTop {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (cb, sb) = (q[1].cos(), q[1].sin());
        let spin = v[2] + v[0] * sb;
        (v[0] * v[0] * cb * cb + v[1] * v[1]) * (0.5 * self.i1) + spin * spin * (0.5 * self.i3)
            - q[0].cos() * cb * self.mgl
    }
}

impl Actuated for CardanTop {
    fn inputs(&self) -> usize {
        0
    }
    fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], _u: &[D], out: &mut [D]) {
        out.iter_mut().for_each(|o| *o = D::zero());
    }
}

/// The sleeping top, a steady motion with q̇* = (0, 0, ω₃) ≠ 0, linearised: to first order in the tilts
/// L ≈ ½I₁(α̇² + β̇²) + I₃ω₃ α̇β + ½Mgℓ(α² + β²) + const, so α̈ = (Mgℓ α − I₃ω₃ β̇)/I₁ and
/// β̈ = (Mgℓ β + I₃ω₃ α̇)/I₁: ξ = α + iβ obeys I₁ξ̈ − iI₃ω₃ξ̇ − Mgℓ ξ = 0 (Goldstein, Poole and Safko
/// §5.7), whose solutions e^{iλt} have I₁λ² − I₃ω₃λ + Mgℓ = 0. The tilt block of A is that matrix
/// (checked entry by entry at every ω₃, to rounding) and has the eigenvalues ±iλ: purely imaginary
/// exactly when ω₃² > 4 I₁ Mgℓ / I₃² (the gyroscopic stability threshold; ω₃ > 4 for I₁ = 1, I₃ = ½,
/// Mgℓ = 1), a pair with real parts ±√(4I₁Mgℓ − I₃²ω₃²)/(2I₁) below it. Spin and tilt do not couple to
/// first order (the blocks between them are exactly zero), and the drift is (q̇*, 0). The tilt block
/// comes out exact (measured 0). Its eigenvalues, computed by nalgebra's nonsymmetric QR (backward
/// stable, so within ε times their condition, which grows where the two roots λ nearly meet), are
/// checked against ±iλ where they are well separated (ω₃ = 6 and 3: measured 2e-16 and 1.1e-14
/// relative, tolerance 1e-13), the threshold by the largest real part just above (4.01: zero, measured
/// 1.7e-15, tolerance 1e-13) and just below it (3.99: the closed form's 0.0707, tolerance 1e-11).
#[test]
fn closed_form_sleeping_top_threshold() {
    let top = CardanTop {
        i1: 1.0,
        i3: 0.5,
        mgl: 1.0,
    };
    for spin in [6.0, 4.01, 3.99, 3.0] {
        let lin = linearize(&top, 0.0, &[0.0, 0.0, 0.0], &[0.0, 0.0, spin], &[]).unwrap();
        assert_eq!(lin.drift.as_slice(), &[0.0, 0.0, spin, 0.0, 0.0, 0.0]);
        // (α, β, α̇, β̇) and (γ, γ̇) in x = (α, β, γ, α̇, β̇, γ̇).
        let (tilt, turn) = ([0, 1, 3, 4], [2, 5]);
        for i in tilt {
            for j in turn {
                assert_eq!((lin.a[(i, j)], lin.a[(j, i)]), (0.0, 0.0), "({i}, {j})");
            }
        }
        let block = DMatrix::from_fn(4, 4, |i, j| lin.a[(tilt[i], tilt[j])]);
        let (k, g) = (top.mgl / top.i1, top.i3 * spin / top.i1);
        #[rustfmt::skip]
        let exact = DMatrix::from_row_slice(4, 4, &[
            0.0, 0.0, 1.0, 0.0,
            0.0, 0.0, 0.0, 1.0,
            k, 0.0, 0.0, -g,
            0.0, k, g, 0.0,
        ]);
        let entries = (&block - &exact).amax() / exact.amax();
        assert!(entries < 2.0 * f64::EPSILON, "ω₃ = {spin}: {entries:e}");
        let computed: Vec<Complex<f64>> = block.complex_eigenvalues().iter().copied().collect();
        let largest_real = computed.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max);
        // λ = (I₃ω₃ ± √(I₃²ω₃² − 4I₁Mgℓ))/(2I₁), complex below the threshold.
        let disc = Complex::new((top.i3 * spin).powi(2) - 4.0 * top.i1 * top.mgl, 0.0).sqrt();
        let roots = [
            (top.i3 * spin + disc) / (2.0 * top.i1),
            (top.i3 * spin - disc) / (2.0 * top.i1),
        ];
        let expected: Vec<Complex<f64>> = roots
            .iter()
            .flat_map(|root| {
                let s = Complex::<f64>::i() * root;
                [s, s.conj()]
            })
            .collect();
        let scale = expected.iter().map(|z| z.norm()).fold(0.0, f64::max);
        // Each expected eigenvalue's distance to the nearest computed one.
        let worst = expected
            .iter()
            .map(|e| {
                computed
                    .iter()
                    .map(|c| (c - e).norm())
                    .fold(f64::INFINITY, f64::min)
                    / scale
            })
            .fold(0.0, f64::max);
        println!(
            "sleeping top ω₃ = {spin}: A's tilt block within {entries:.1e}, eigenvalues within {worst:.1e}, \
             largest real part {largest_real:.6e}"
        );
        match spin {
            6.0 | 3.0 => assert!(worst < 1e-13, "ω₃ = {spin}: {worst:e}"),
            _ if spin > 4.0 => assert!(largest_real.abs() < 1e-13, "ω₃ = {spin}: {largest_real:e}"),
            _ => {
                let unstable = (4.0 * top.i1 * top.mgl - (top.i3 * spin).powi(2)).sqrt() / (2.0 * top.i1);
                let error = (largest_real - unstable).abs() / unstable;
                assert!(error < 1e-11, "ω₃ = {spin}: {largest_real:e} vs {unstable:e}");
            }
        }
    }
}

/// One step of the midpoint variational integrator of the cart-pole from the upright rest point, in
/// its own coordinates (q, p), with the input held. At an equilibrium only the quadratic part of L
/// matters, L₂ = ½q̇ᵀMq̇ − ½qᵀKq with M = [[M + m, ml], [ml, ml²]] and K = diag(0, −mgl), and for a
/// quadratic L the midpoint discrete Lagrangian is the implicit midpoint rule on ż = Fz + Gu,
/// F = [[0, M⁻¹], [−K, 0]], G = [0; (1, 0)] (p̄ = M(q₁ − q₀)/h and p₁ − p₀ = −hKq̄ + h(1, 0)u). So
/// A_d = (I − hF/2)⁻¹(I + hF/2) and B_d = (I − hF/2)⁻¹ hG, exact to rounding (measured 4e-16).
#[test]
fn variational_step_linearization_is_the_cayley_transform() {
    use noether_discrete::{Midpoint, VariationalIntegrator};
    let cp = CartPole::default();
    let h = 0.05;
    let step = upright_step(&cp, |l| VariationalIntegrator::new(Midpoint::new(l)), h);
    let (big, m, l, g) = (cp.cart, cp.bob, cp.l, cp.g);
    let mass = DMatrix::from_row_slice(2, 2, &[big + m, m * l, m * l, m * l * l]);
    let mass_inv = mass.try_inverse().unwrap();
    let mut f = DMatrix::zeros(4, 4);
    f.view_mut((0, 2), (2, 2)).copy_from(&mass_inv);
    f[(3, 1)] = m * g * l; // −K
    let gain = DMatrix::from_column_slice(4, 1, &[0.0, 0.0, 1.0, 0.0]);
    let identity = DMatrix::<f64>::identity(4, 4);
    let implicit = (&identity - &f * (0.5 * h)).try_inverse().unwrap();
    let a_d = &implicit * (&identity + &f * (0.5 * h));
    let b_d = &implicit * gain * h;
    let (ea, eb) = (
        (&step.a - &a_d).amax() / a_d.amax(),
        (&step.b - &b_d).amax() / b_d.amax(),
    );
    println!("midpoint VI step of the cart-pole upright: |A_d − Cayley| {ea:e}, |B_d − closed form| {eb:e}");
    assert!(
        ea < 8.0 * f64::EPSILON && eb < 8.0 * f64::EPSILON,
        "{ea:e} {eb:e}"
    );
}

/// A cart-pole written in dependent coordinates q = (x_c, x_b, y_b) — the cart's position and the
/// bob's Cartesian position — with the rod as a holonomic constraint φ = ((x_b − x_c)² + y_b² − l²)/2:
///
///   L = ½ M ẋ_c² + ½ m (ẋ_b² + ẏ_b²) − m g y_b,   Q_u = (u, 0, 0).
pub(crate) struct CartesianCartPole(pub(crate) CartPole);

impl Lagrangian for CartesianCartPole {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let cp = &self.0;
        v[0] * v[0] * (0.5 * cp.cart) + (v[1] * v[1] + v[2] * v[2]) * (0.5 * cp.bob) - q[2] * (cp.bob * cp.g)
    }
}

impl Actuated for CartesianCartPole {
    fn inputs(&self) -> usize {
        1
    }
    fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &[D], out: &mut [D]) {
        out[0] = u[0];
        out[1] = D::zero();
        out[2] = D::zero();
    }
}

/// The rod of [`CartesianCartPole`].
pub(crate) struct Rod(pub(crate) f64);

impl noether_constraints::Holonomic for Rod {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        1
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        let dx = q[1] - q[0];
        out[0] = (dx * dx + q[2] * q[2] - self.0 * self.0) * 0.5;
    }
}

/// The textbook upright (A, B) of the cart-pole (`CartPole::upright_linearization`, in (x, θ)) in
/// the Cartesian cart-pole's independent coordinates (x_c, x_b): x_c = x, x_b = x + l sin θ, so
/// δ(x_c, x_b) = J δ(x, θ) with J = [[1, 0], [1, l]] at θ = 0, and at rest the velocities map by the
/// same J: (S A S⁻¹, S B) with S = diag(J, J).
pub(crate) fn textbook_in_cartesian(cp: &CartPole) -> (DMatrix<f64>, DMatrix<f64>) {
    let (a, b) = cp.upright_linearization();
    let (a, b) = (
        DMatrix::from_fn(4, 4, |i, j| a[i][j]),
        DMatrix::from_column_slice(4, 1, &b),
    );
    let mut s = DMatrix::zeros(4, 4);
    for k in [0, 2] {
        s[(k, k)] = 1.0;
        s[(k + 1, k)] = 1.0;
        s[(k + 1, k + 1)] = cp.l;
    }
    let s_inv = s.clone().try_inverse().unwrap();
    (&s * &a * &s_inv, &s * &b)
}

/// Linearisation with holonomic constraints in dependent coordinates, reduced to independent ones as
/// SymPy's `Linearizer` does: the Cartesian cart-pole upright, in the independent coordinates
/// (x_c, x_b) (y_b the dependent one: ∂φ/∂y_b = l there), against the textbook (A, B) in (x, θ)
/// (`CartPole::upright_linearization`). The coordinates are related by x_c = x, x_b = x + l sin θ, so
/// to first order δ(x_c, x_b) = J δ(x, θ) with J = [[1, 0], [1, l]], and at rest the velocities map by
/// the same J: the reduced (A, B) must be S A_tb S⁻¹ and S B_tb with S = diag(J, J). Exact to rounding
/// (measured 1.4e-16 and 0 relative; bound 16ε = 3.6e-15, for the reduction's three Newton steps in
/// dual arithmetic and small solves on top of the unconstrained jet's rounding).
#[test]
fn constrained_cart_pole_reduces_to_the_textbook_linearization() {
    use noether_constraints::Reduced;
    let cp = CartPole::default();
    let reduced = Reduced::new(CartesianCartPole(cp), Rod(cp.l), &[0, 1], &[0.0, 0.0, cp.l]).unwrap();
    let lin = linearize(&reduced, 0.0, &[0.0, 0.0], &[0.0, 0.0], &[0.0]).unwrap();
    let (a_exact, b_exact) = textbook_in_cartesian(&cp);
    let (ea, eb) = (
        (&lin.a - &a_exact).amax() / a_exact.amax(),
        (&lin.b - &b_exact).amax() / b_exact.amax(),
    );
    println!(
        "constrained cart-pole: A {ea:e}, B {eb:e}, drift {:e}",
        lin.drift.amax()
    );
    assert!(
        ea < 16.0 * f64::EPSILON && eb < 16.0 * f64::EPSILON,
        "{ea:e} {eb:e}"
    );
    assert!(lin.drift.amax() < 1e-15);
    // The full state of a reduced one: the bob back on the rod.
    let (q, _) = reduced.state(0.0, &[0.1, 0.4], &[0.0, 0.0]);
    assert!(((q[1] - q[0]).powi(2) + q[2] * q[2] - cp.l * cp.l).abs() < 1e-15);
}

/// A swinging point off the rest point: the reduced cart-pole's drift (q̇, q̈) at a leaning, moving
/// state agrees with the textbook equations mapped through x_b = x + l sin θ (then
/// ẍ_b = ẍ + l (θ̈ cos θ − θ̇² sin θ)): the reduction's first and second derivatives of y_b(x_c, x_b)
/// at work (measured 2.6e-16 relative; bound 16ε as above). A choice of independent coordinates
/// with ∂φ/∂q_d singular at the reference is refused.
#[test]
fn constrained_cart_pole_moves_as_the_textbook_one() {
    use noether_constraints::Reduced;
    let cp = CartPole::default();
    let reduced = Reduced::new(CartesianCartPole(cp), Rod(cp.l), &[0, 1], &[0.0, 0.0, cp.l]).unwrap();
    let (x, th, xd, w, u) = (0.3_f64, 0.5_f64, -0.2, 1.2, 0.4);
    let textbook = linearize(&cp, 0.0, &[x, th], &[xd, w], &[u]).unwrap();
    let (xdd, thdd) = (textbook.drift[2], textbook.drift[3]);
    let (qi, vi) = ([x, x + cp.l * th.sin()], [xd, xd + cp.l * th.cos() * w]);
    let lin = linearize(&reduced, 0.0, &qi, &vi, &[u]).unwrap();
    let xbdd = xdd + cp.l * (thdd * th.cos() - w * w * th.sin());
    let err = ((lin.drift[2] - xdd).abs() / xdd.abs()).max((lin.drift[3] - xbdd).abs() / xbdd.abs());
    println!("constrained cart-pole moving: accelerations {err:e}");
    assert!(err < 16.0 * f64::EPSILON, "{err:e}");
    // With the bob level with the cart (y_b = 0), ∂φ/∂y_b = 0: y_b is no function of (x_c, x_b) there.
    assert!(Reduced::new(CartesianCartPole(cp), Rod(cp.l), &[0, 1], &[0.0, cp.l, 0.0]).is_err());
}

/// The time-varying LQR recursion, checked two ways. One step of the scalar recursion by hand:
/// K = b p a/(r + b²p), P₀ = q + a p (a − bK) with p = Q_N (exact to rounding). And its long-horizon
/// limit: steps all alike, the recursion run backwards from Q_N = 0 converges to the stabilising root
/// of the discrete Riccati equation (the scalar's closed form of `closed_form_scalar_discrete_riccati`)
/// and, on the cart-pole's upright RK4 step, to `dlqr`'s gain (measured 4.2e-16 and 2.2e-15 relative
/// after 400 and 3000 steps; the difference decays like |a − bk|^{2N}, so what is left is rounding;
/// bounds 32ε = 7e-15 for the scalar, and 2e-14 for the cart-pole's 4 × 4 products).
#[test]
fn tvlqr_recursion_by_hand_and_in_the_limit() {
    let (a, b, q, r, p) = (1.2_f64, 0.5_f64, 1.0_f64, 0.3_f64, 1.5_f64);
    let step = scalar_step(a, b);
    let scalar = |x: f64| DMatrix::from_element(1, 1, x);
    let one = tvlqr(std::slice::from_ref(&step), &scalar(q), &scalar(r), &scalar(p)).unwrap();
    let k = b * p * a / (r + b * b * p);
    assert!((one.gains[0][(0, 0)] - k).abs() < 4.0 * f64::EPSILON * k);
    assert!((one.cost_to_go[0][(0, 0)] - (q + a * p * (a - b * k))).abs() < 8.0 * f64::EPSILON);
    assert_eq!(one.cost_to_go[1][(0, 0)], p);

    let long = tvlqr(&vec![step; 400], &scalar(q), &scalar(r), &scalar(0.0)).unwrap();
    let lin = r * (1.0 - a * a) - q * b * b;
    let x = (-lin + (lin * lin + 4.0 * b * b * q * r).sqrt()) / (2.0 * b * b);
    let e_scalar = (long.cost_to_go[0][(0, 0)] - x).abs() / x;

    let cp = CartPole::default();
    let upright = upright_step(&cp, |l| Rk4::new(EulerLagrange::new(l)), 0.01);
    let (qw, rw) = (
        DMatrix::from_diagonal(&nalgebra::dvector![10.0, 10.0, 1.0, 1.0]),
        DMatrix::from_element(1, 1, 0.1),
    );
    let stationary = dlqr(&upright, &qw, &rw).unwrap();
    let tracked = tvlqr(&vec![upright; 3000], &qw, &rw, &DMatrix::zeros(4, 4)).unwrap();
    let e_cart = (&tracked.gains[0] - &stationary.gain).amax() / stationary.gain.amax();
    println!("tvlqr limits: scalar {e_scalar:e}, cart-pole {e_cart:e}");
    assert!(e_scalar < 32.0 * f64::EPSILON, "{e_scalar:e}");
    assert!(e_cart < 2e-14, "{e_cart:e}");
    // The last gain sees only one step to go: with Q_N = 0 it is zero.
    assert_eq!(tracked.gains[2999].amax(), 0.0);
    assert!(tvlqr(&[], &qw, &rw, &qw).is_err());
}
