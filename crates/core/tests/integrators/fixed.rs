//! Regressions of issue 16 (item 1): the fixed-size loops for systems of up to six degrees of freedom
//! (the state and the stages in arrays, the kernel of `Natural` inlined) perform the same operations
//! in the same order as the general algorithm, so their results are the same to the bit:
//! - `Composition`: against its loop written out with `kick_rate` on vectors (kicks of a_i h and
//!   drifts of b_i h, adjacent half kicks merged; `kicks` are the a_i, `coefficients` the b_i);
//! - the embedded Runge-Kutta pairs (DOPRI5, DOP853): against one trial step written out from the
//!   public tableau of [`EmbeddedPair`] with `Dynamics::rates` on vectors;
//! - the Runge-Kutta-Nyström pairs (DPRKN8, DPRKN12): likewise from [`NystromPair`] with
//!   `kick_rate`.

use noether_core::integrators::{
    Composition, Dop853, Dopri5, Dprkn12, Dprkn8, EmbeddedPair, NystromPair, SplitDynamics,
};
use noether_core::prelude::*;

/// Hénon-Heiles, V = ½(x² + y²) + x²y − y³/3.
struct HenonHeiles;
impl Potential for HenonHeiles {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        let (x, y) = (q[0], q[1]);
        (x * x + y * y) * 0.5 + x * x * y - y * y * y / 3.0
    }
}

/// `steps` Kahan-Li 8 steps of size h by the general algorithm on vectors.
fn reference<S: SplitDynamics>(
    sys: &S,
    gammas: &[f64],
    q: &[f64],
    v: &[f64],
    h: f64,
    steps: usize,
) -> (Vec<f64>, Vec<f64>) {
    let mut kicks = vec![0.0; gammas.len() + 1];
    for (i, g) in gammas.iter().enumerate() {
        kicks[i] += 0.5 * g;
        kicks[i + 1] += 0.5 * g;
    }
    let (mut q, mut v, mut f) = (q.to_vec(), v.to_vec(), vec![0.0; q.len()]);
    let mut d = vec![0.0; q.len()];
    sys.kick_rate(&q, &mut f).unwrap();
    for _ in 0..steps {
        for (a, b) in kicks.iter().zip(gammas) {
            let c = a * h;
            v.iter_mut().zip(&f).for_each(|(v, f)| *v += c * f);
            let c = b * h;
            sys.drift_rate(&v, &mut d).unwrap();
            q.iter_mut().zip(&d).for_each(|(q, d)| *q += c * d);
            sys.kick_rate(&q, &mut f).unwrap();
        }
        let c = kicks[gammas.len()] * h;
        v.iter_mut().zip(&f).for_each(|(v, f)| *v += c * f);
    }
    (q, v)
}

/// 200 Kahan-Li 8 steps of the fixed-size loop on `sys` against the reference, to the bit.
fn check_composition<S: SplitDynamics>(name: &str, sys: &S) {
    let (q0, v0, h, steps) = ([0.1, 0.0], [0.0, 0.5], 0.01, 200);
    let mut kl8 = Composition::kahan_li8(sys);
    let gammas = kl8.weights().as_slice().to_vec();
    let mut s = State::<S::Partner>::from_parts(0.0, q0, v0);
    for _ in 0..steps {
        kl8.step(&mut s, h).unwrap();
    }
    let (q, v) = reference(sys, &gammas, &q0, &v0, h, steps);
    assert_eq!(s.q.as_slice(), q.as_slice(), "{name}: q");
    assert_eq!(s.v.as_slice(), v.as_slice(), "{name}: v");
    // And the run moved: 200 steps of 0.01 on an orbit of period ≈ 2π.
    assert!((s.q[0] - q0[0]).abs() > 1e-2, "{name}");
}

/// The fixed-size loop against the reference, for a unit, a diagonal and a dense mass matrix (the
/// dense one takes the kernel's general path inside the fixed loop) and for the separable
/// Hamiltonian on (q, p) (drift ∇T(p) on the vectors, kick by its own fixed-size kernel).
#[test]
fn regress_composition_fixed_loop_same_bits() {
    let dense = nalgebra::DMatrix::from_row_slice(2, 2, &[2.0, 0.3, 0.3, 1.0]);
    check_composition("unit", &Natural::unit(HenonHeiles));
    check_composition("diagonal", &Natural::diagonal(HenonHeiles, &[1.0, 2.5]).unwrap());
    check_composition("dense", &Natural::dense(HenonHeiles, dense).unwrap());
    check_composition("separable", &SeparableHamiltonian(HenonHeiles));
}

/// H = ½|p|² + V(q) for `SeparableHamiltonian`.
impl Separable for HenonHeiles {
    fn dof(&self) -> usize {
        2
    }
    fn kinetic<D: Scalar>(&self, p: &[D]) -> D {
        (p[0] * p[0] + p[1] * p[1]) * 0.5
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        Potential::potential(self, q)
    }
}

/// Kepler, μ = 1: V = −1/|q|, in 2 or 3 dimensions.
struct Kepler(usize);
impl Potential for Kepler {
    fn dof(&self) -> usize {
        self.0
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        -q.iter().fold(D::from(0.0), |r2, &x| r2 + x * x).sqrt().recip()
    }
}

/// H = ½|p|² + V(q) for `SeparableHamiltonian`.
impl Separable for Kepler {
    fn dof(&self) -> usize {
        self.0
    }
    fn kinetic<D: Scalar>(&self, p: &[D]) -> D {
        p.iter().fold(D::from(0.0), |t, &x| t + x * x) * 0.5
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        Potential::potential(self, q)
    }
}

/// Kepler in the plane and in space with unit, diagonal and dense masses (the dense one takes the
/// kernel's general path inside the fixed-size step), each started from (q, q̇) = ((0.9, 0.2, −0.1),
/// (0.1, 1.1, 0.2)) cut to its dimension.
fn kepler_systems() -> [(&'static str, Natural<Kepler>); 3] {
    let dense3 = nalgebra::DMatrix::from_row_slice(3, 3, &[2.0, 0.3, 0.0, 0.3, 1.0, 0.1, 0.0, 0.1, 1.5]);
    [
        ("unit 2", Natural::unit(Kepler(2))),
        (
            "diagonal 3",
            Natural::diagonal(Kepler(3), &[1.0, 2.5, 0.5]).unwrap(),
        ),
        ("dense 3", Natural::dense(Kepler(3), dense3).unwrap()),
    ]
}

/// One trial step of the pair `M` of size h from (t, q, v) by the general algorithm: stage i's
/// argument (y₀ + h Σ_{j<l} a_ij k_j) + (h a_il) k_l with l = i − 1 its last (the documented order of
/// `combine_stages`; zero weights skipped), y₁ likewise from the b_j, F(t + h, y₁) as stage s, then
/// the error norm from the sums of the squared scaled estimates Σ_j e_rj k_j. Returns (y₁, err).
fn reference_trial<M: EmbeddedPair, S: Dynamics>(
    sys: &S,
    t: f64,
    q: &[f64],
    v: &[f64],
    h: f64,
    tol: f64,
) -> (Vec<f64>, f64) {
    let (n, s) = (q.len(), M::C.len());
    let y0: Vec<f64> = q.iter().chain(v).copied().collect();
    let mut k = vec![vec![0.0; 2 * n]; s + 1];
    let eval = |t: f64, y: &[f64], out: &mut Vec<f64>| {
        let (dq, dv) = out.split_at_mut(n);
        sys.rates(t, &y[..n], &y[n..], dq, dv).unwrap();
    };
    eval(t, &y0, &mut k[0]);
    let mut y = y0.clone();
    for i in 1..=s {
        let (row, c) = if i < s { (M::A[i], M::C[i]) } else { (M::B, 1.0) };
        let (last, rest) = row.split_last().unwrap();
        for x in 0..2 * n {
            let sum = rest
                .iter()
                .enumerate()
                .filter(|(_, a)| **a != 0.0)
                .fold(0.0, |acc, (j, a)| acc + a * k[j][x]);
            y[x] = (y0[x] + h * sum) + (h * last) * k[rest.len()][x];
        }
        let mut ki = vec![0.0; 2 * n];
        eval(t + c * h, &y, &mut ki);
        k[i] = ki;
    }
    let mut sums = [0.0; 2];
    for x in 0..2 * n {
        let sk = tol + tol * y0[x].abs().max(y[x].abs());
        for (sum, row) in sums.iter_mut().zip(M::ERROR) {
            let e = row
                .iter()
                .enumerate()
                .filter(|(_, a)| **a != 0.0)
                .fold(0.0, |acc, (j, a)| acc + a * k[j][x]);
            *sum += (e / sk) * (e / sk);
        }
    }
    (y, M::error_norm(h, sums, 2 * n))
}

/// One step of `m` of size h from `start`: accepted at once, (q₁, q̇₁) equal to the reference's y₁ to
/// the bit and, when `root` is given (a controller with safety 0.9 and β = 0 whose err^α is `root`),
/// the proposal h_next = h / (root(err)/0.9) from the reference's err to the bit. The step's info.
fn check_accepted<S: Stepper>(
    what: &str,
    mut m: S,
    start: &State<S::Partner>,
    h: f64,
    (y1, err): (Vec<f64>, f64),
    root: Option<fn(f64) -> f64>,
) -> StepInfo {
    let mut s = start.clone();
    let info = m.step(&mut s, h).unwrap();
    assert_eq!((info.h, info.rejected), (h, 0), "{what}");
    assert_eq!([s.q.as_slice(), s.v.as_slice()].concat(), y1, "{what}: y₁");
    if let Some(root) = root {
        assert!(
            err > 1e-11 && root(err) / 0.9 > 1.0 / 6.0,
            "{what}: err {err} (the proposal must not be clamped)"
        );
        assert_eq!(info.h_next, h / (root(err) / 1.0 / 0.9), "{what}: err");
    }
    info
}

/// The fixed-size trial step of DOPRI5 and DOP853 on `sys` from (q, v) against the reference: the
/// state after one accepted step is y₁ to the bit, and DOP853's proposal h_next is h / (err^(1/8)/0.9)
/// (its controller: safety 0.9, β = 0, err^(1/8) as three square roots) with the reference err to the
/// bit. The evaluations are 1 + 11 + 1 for DOP853 (F(t, y₀), the trial, F(t + h, y₁) after the
/// acceptance) and 1 + 6 for DOPRI5 (whose estimate weighs F(t + h, y₁)).
fn check_adaptive<S: Dynamics>(name: &str, sys: &S, q: &[f64], v: &[f64]) {
    use noether_core::integrators::{Dp5, Dp853};
    let (h, tol) = (0.2, 1e-6);
    let start = State::<S::Partner>::from_parts(0.3, q.to_vec(), v.to_vec());
    let reference = reference_trial::<Dp853, _>(sys, 0.3, q, v, h, tol);
    let m = Dop853::new(sys)
        .tolerances(tol, tol)
        .unwrap()
        .dense_interpolant(false);
    let root: fn(f64) -> f64 = |e| e.sqrt().sqrt().sqrt();
    let info = check_accepted(&format!("{name} DOP853"), m, &start, h, reference, Some(root));
    assert_eq!(info.evaluations, 13, "{name}");

    let reference = reference_trial::<Dp5, _>(sys, 0.3, q, v, h, tol);
    let m = Dopri5::new(sys)
        .tolerances(tol, tol)
        .unwrap()
        .dense_interpolant(false);
    let info = check_accepted(&format!("{name} DOPRI5"), m, &start, h, reference, None);
    assert_eq!(info.evaluations, 7, "{name}");
}

/// [`check_adaptive`] for Kepler in the plane and in space with unit, diagonal and dense masses, and
/// as a `SeparableHamiltonian` on (q, p) (its own fixed-size rates, two gradients).
#[test]
fn regress_adaptive_fixed_trial_same_bits() {
    for (name, sys) in &kepler_systems() {
        let n = sys.dof();
        check_adaptive(name, sys, &[0.9, 0.2, -0.1][..n], &[0.1, 1.1, 0.2][..n]);
    }
    for n in [2, 3] {
        let sys = SeparableHamiltonian(Kepler(n));
        check_adaptive(
            &format!("separable {n}"),
            &sys,
            &[0.9, 0.2, -0.1][..n],
            &[0.1, 1.1, 0.2][..n],
        );
    }
}

/// One trial step of the Nyström pair `M` of size h from (q, v) by the general algorithm: stage i at
/// (q₀ + h(c_i q̇₀ + h Σ_{j<l} a_ij k_j)) + (h² a_il) k_l (l = i − 1; zero weights skipped), then
/// q₁ = q₀ + h(q̇₀ + h Σ b_j k_j) (the last stage's position for an FSAL pair), q̇₁ = q̇₀ + h Σ b'_j k_j
/// and err = sqrt(Σ (h² Σ e_j k_j / sk)² + (h Σ e'_j k_j / sk)² over the 2n components / 2n).
fn reference_nystrom<M: NystromPair, S: SplitDynamics>(
    sys: &S,
    q0: &[f64],
    v0: &[f64],
    h: f64,
    tol: f64,
) -> (Vec<f64>, f64) {
    let (n, s) = (q0.len(), M::C.len());
    let mut k = vec![vec![0.0; n]; s];
    sys.kick_rate(q0, &mut k[0]).unwrap();
    let mut qs = q0.to_vec();
    let sum = |w: &[f64], k: &[Vec<f64>], x: usize| {
        w.iter()
            .zip(k)
            .filter(|(a, _)| **a != 0.0)
            .fold(0.0, |acc, (a, kj)| acc + a * kj[x])
    };
    for i in 1..s {
        let (last, rest) = M::A[i].split_last().unwrap();
        for x in 0..n {
            let partial = q0[x] + h * (M::C[i] * v0[x] + h * sum(rest, &k, x));
            qs[x] = partial + (h * h * last) * k[rest.len()][x];
        }
        let mut ki = vec![0.0; n];
        sys.kick_rate(&qs, &mut ki).unwrap();
        k[i] = ki;
    }
    let (mut y1, mut sq) = (vec![0.0; 2 * n], 0.0);
    for x in 0..n {
        let q1 = if M::FSAL {
            qs[x]
        } else {
            q0[x] + h * (v0[x] + h * sum(M::B, &k, x))
        };
        let v1 = v0[x] + h * sum(M::BP, &k, x);
        let eq = h * h * sum(M::B_ERR, &k, x) / (tol + tol * q0[x].abs().max(q1.abs()));
        let ev = h * sum(M::BP_ERR, &k, x) / (tol + tol * v0[x].abs().max(v1.abs()));
        sq += eq * eq + ev * ev;
        (y1[x], y1[n + x]) = (q1, v1);
    }
    (y1, (sq / (2 * n) as f64).sqrt())
}

/// The fixed-size trial step of DPRKN8 and DPRKN12 against the reference, for the same systems as
/// above: the state after one accepted step is (q₁, q̇₁) to the bit, and the proposal h_next is
/// h / (err^(1/q)/0.9) (their controllers: safety 0.9, β = 0, q = 7 and 11) with the reference err to
/// the bit.
#[test]
fn regress_nystrom_fixed_trial_same_bits() {
    use noether_core::integrators::{Rkn12, Rkn8};
    let (h, tol) = (0.2, 1e-8);
    for (name, sys) in &kepler_systems() {
        let n = sys.dof();
        let (q, v) = (&[0.9, 0.2, -0.1][..n], &[0.1, 1.1, 0.2][..n]);
        let start = State::new(0.3, q.to_vec(), v.to_vec());
        let reference = reference_nystrom::<Rkn8, _>(sys, q, v, h, tol);
        let m = Dprkn8::new(sys).unwrap().tolerances(tol, tol).unwrap();
        let root: fn(f64) -> f64 = |e| e.powf(1.0 / 7.0);
        check_accepted(
            &format!("{name} DPRKN8"),
            m.dense_interpolant(false),
            &start,
            h,
            reference,
            Some(root),
        );

        let reference = reference_nystrom::<Rkn12, _>(sys, q, v, h, tol);
        let m = Dprkn12::new(sys).unwrap().tolerances(tol, tol).unwrap();
        let root: fn(f64) -> f64 = |e| e.powf(1.0 / 11.0);
        check_accepted(
            &format!("{name} DPRKN12"),
            m.dense_interpolant(false),
            &start,
            h,
            reference,
            Some(root),
        );
    }
}

/// The fixed-size rates fail as the general ones do (the same error with the same data) where the
/// model is singular (V = −1/|q| at q = 0) or the input is not finite, for `Natural` on (q, q̇) and
/// `SeparableHamiltonian` on (q, p): `rates_fixed` against `rates`, `kick_rate_fixed` against
/// `kick_rate` and `drift_rate_fixed` against `drift_rate`.
#[test]
fn regress_fixed_rates_fail_as_the_general_ones() {
    fn check<S: SplitDynamics>(name: &str, sys: &S) {
        let cases = [
            ([0.0, 0.0], [0.1, 0.2]),
            ([0.5, f64::NAN], [0.1, 0.2]),
            ([0.5, 0.1], [f64::INFINITY, 0.2]),
        ];
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        for (q, v) in cases {
            let fixed = sys.rates_fixed(0.7, q, v).map(|_| ());
            let general = sys.rates(0.7, &q, &v, &mut a, &mut b);
            assert_eq!(
                format!("{fixed:?}"),
                format!("{general:?}"),
                "{name}: rates at {q:?} {v:?}"
            );
            assert!(fixed.is_err(), "{name}: rates at {q:?} {v:?}");
            let fixed = sys.kick_rate_fixed(q).map(|_| ());
            assert_eq!(
                format!("{fixed:?}"),
                format!("{:?}", sys.kick_rate(&q, &mut a)),
                "{name}: kick"
            );
            let fixed = sys.drift_rate_fixed(v).map(|_| ());
            assert_eq!(
                format!("{fixed:?}"),
                format!("{:?}", sys.drift_rate(&v, &mut a)),
                "{name}: drift"
            );
        }
    }
    check("natural", &Natural::unit(Kepler(2)));
    check("separable", &SeparableHamiltonian(Kepler(2)));
}
