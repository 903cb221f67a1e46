//! Three bodies: the figure-eight choreography of three equal masses, and the circular restricted
//! problem with its collinear point L1.
//!
//! Used by noether-analysis' tests (`tests/periodic.rs`) and the gallery's `figure_eight` and
//! `periodic_orbits` examples.

use noether_core::ad::Field;
use noether_core::{Hamiltonian, Lagrangian, Momenta, Scalar, State, Stepper};

/// Three equal masses (G = m = 1) in the plane, q = (x₁, y₁, x₂, y₂, x₃, y₃), p likewise:
/// H = |p|²/2 − Σ_{i<j} 1/r_ij.
#[derive(Debug, Clone, Copy)]
pub struct ThreeBody;

impl Hamiltonian for ThreeBody {
    fn dof(&self) -> usize {
        6
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let mut h = p.iter().fold(D::zero(), |acc, &pi| acc + pi * pi) * 0.5;
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            let (dx, dy) = (q[2 * i] - q[2 * j], q[2 * i + 1] - q[2 * j + 1]);
            h -= (dx * dx + dy * dy).sqrt().recip();
        }
        h
    }
}

/// Total momentum along x (k = 0) or y (k = 1), and the angular momentum (k = 2), as AD fields.
#[derive(Debug, Clone, Copy)]
pub struct Momentum(pub usize);

impl Field for Momentum {
    fn eval<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (0..3).fold(D::zero(), |acc, i| match self.0 {
            0 => acc + p[2 * i],
            1 => acc + p[2 * i + 1],
            _ => acc + q[2 * i] * p[2 * i + 1] - q[2 * i + 1] * p[2 * i],
        })
    }
}

/// Simó's / Moore's symmetric configuration of the figure-eight: x₁ = −x₂, x₃ = 0,
/// v₃ = −2v₁ = −2v₂ (at t = 0, p = v for unit masses).
pub fn figure_eight(x1: [f64; 2], v3: [f64; 2]) -> State<Momenta> {
    let v1 = [-0.5 * v3[0], -0.5 * v3[1]];
    State::with_momenta(
        0.0,
        [x1[0], x1[1], -x1[0], -x1[1], 0.0, 0.0],
        [v1[0], v1[1], v1[0], v1[1], v3[0], v3[1]],
    )
}

/// The circular restricted three-body problem in the rotating frame (unit distance, unit angular
/// velocity, masses 1 − μ at (−μ, 0) and μ at (1 − μ, 0)):
/// H = ½(p_x² + p_y²) + y p_x − x p_y − (1 − μ)/r₁ − μ/r₂ = −C/2 (C the Jacobi constant).
#[derive(Debug, Clone, Copy)]
pub struct Cr3bp {
    /// Mass ratio μ.
    pub mu: f64,
}

impl Hamiltonian for Cr3bp {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        restricted_hamiltonian(self.mu, q, p)
    }
}

/// The spatial circular restricted three-body problem, the same frame with z out of the primaries'
/// plane: H = ½|p|² + y p_x − x p_y − (1 − μ)/r₁ − μ/r₂, r₁² = (x + μ)² + y² + z²,
/// r₂² = (x − 1 + μ)² + y² + z². Its planar orbits (z = p_z = 0) are [`Cr3bp`]'s; the vertical
/// variations about them decouple and decide where the halo families branch off.
#[derive(Debug, Clone, Copy)]
pub struct SpatialCr3bp {
    /// Mass ratio μ.
    pub mu: f64,
}

impl Hamiltonian for SpatialCr3bp {
    fn dof(&self) -> usize {
        3
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        restricted_hamiltonian(self.mu, q, p)
    }
}

/// H of the restricted problem for q = (x, y) or (x, y, z): ½|p|² + y p_x − x p_y − (1 − μ)/r₁ − μ/r₂.
fn restricted_hamiltonian<D: Scalar>(mu: f64, q: &[D], p: &[D]) -> D {
    let (x, y) = (q[0], q[1]);
    let off_axis = q[1..].iter().fold(D::zero(), |s, &c| s + c * c);
    let r1 = ((x + mu) * (x + mu) + off_axis).sqrt();
    let r2 = ((x - (1.0 - mu)) * (x - (1.0 - mu)) + off_axis).sqrt();
    let kinetic = p.iter().fold(D::zero(), |s, &c| s + c * c) * 0.5;
    kinetic + y * p[0] - x * p[1] - r1.recip() * (1.0 - mu) - r2.recip() * mu
}

/// L1 (by bisection of ∂Ω/∂x on the axis between the primaries) and c₂ = (1 − μ)/r₁³ + μ/r₂³ there.
pub fn l1(mu: f64) -> (f64, f64) {
    let dphi = |x: f64| x - (1.0 - mu) / (x + mu).powi(2) + mu / (x - 1.0 + mu).powi(2);
    let (mut a, mut b) = (0.5, 1.0 - mu - 1e-3);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if dphi(a) * dphi(m) <= 0.0 {
            b = m;
        } else {
            a = m;
        }
    }
    let x = 0.5 * (a + b);
    (x, (1.0 - mu) / (x + mu).powi(3) + mu / (1.0 - mu - x).powi(3))
}

/// The same three equal masses as a Lagrangian (G = m = 1):
/// L = ½Σ|q̇_i|² + Σ_{i<j} 1/|q_i − q_j|, q = (x₁, y₁, x₂, y₂, x₃, y₃).
pub struct ThreeBodyLagrangian;

impl Lagrangian for ThreeBodyLagrangian {
    fn dof(&self) -> usize {
        6
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let mut l = v.iter().fold(D::zero(), |a, x| a + *x * *x) * 0.5;
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            let (dx, dy) = (q[2 * i] - q[2 * j], q[2 * i + 1] - q[2 * j + 1]);
            l += (dx * dx + dy * dy).sqrt().recip();
        }
        l
    }
}

/// The published figure-eight (Chenciner & Montgomery, Ann. Math. 152, 2000; initial conditions of
/// Simó 2002, Moore 1993): at the Euler configuration x₃ = 0, x₁ = −x₂ = `EIGHT_X1`.
pub const EIGHT_X1: [f64; 2] = [0.97000436, -0.24308753];
/// The published figure-eight's v₃ = −2v₁ = −2v₂ (see [`EIGHT_X1`]).
pub const EIGHT_V3: [f64; 2] = [-0.93240737, -0.86473146];
/// The published figure-eight's period (see [`EIGHT_X1`]).
pub const EIGHT_T: f64 = 6.32591398;

/// The directions of the figure-eight's continuous symmetries at `guess`, as shooting's phase
/// conditions: (translation along x, translation along y, rotation), each on z = (q, p).
pub fn figure_eight_symmetries(guess: &State<Momenta>) -> [Vec<f64>; 3] {
    let rotation: Vec<f64> = (0..3)
        .flat_map(|i| [-guess.q[2 * i + 1], guess.q[2 * i]])
        .chain((0..3).flat_map(|i| [-guess.v[2 * i + 1], guess.v[2 * i]]))
        .collect();
    let tx: Vec<f64> = (0..12)
        .map(|i| if i < 6 && i % 2 == 0 { 1.0 } else { 0.0 })
        .collect();
    let ty: Vec<f64> = (0..12)
        .map(|i| if i < 6 && i % 2 == 1 { 1.0 } else { 0.0 })
        .collect();
    [tx, ty, rotation]
}

/// The figure-eight's shooting problem: [`ThreeBody`] at the energy `e0`, momentum (2) and angular
/// momentum (1) unfolded, a phase condition for each translation and the rotation
/// ([`figure_eight_symmetries`] of `guess`), and the time phase x₃ = 0 (body 3 at the centre of mass).
#[cfg(feature = "analysis")]
pub fn figure_eight_shooting<S: noether_core::TangentStepper>(
    shooting: noether_analysis::Shooting<S>,
    guess: &State<Momenta>,
    e0: f64,
) -> noether_analysis::Shooting<S> {
    use noether_analysis::periodic::{Energy, Integral};
    let [tx, ty, rotation] = figure_eight_symmetries(guess);
    shooting
        .level(Energy(ThreeBody), e0)
        .unfold(Integral(Momentum(0)))
        .unfold(Integral(Momentum(1)))
        .unfold(Integral(Momentum(2)))
        .symmetry(tx)
        .symmetry(ty)
        .symmetry(rotation)
        .phase_coordinate(4, 0.0)
}

/// The linearisation about L1 (Richardson 1980): x = x_L − A cos ωt, y = k A sin ωt with
/// ω² = (2 − c₂ + sqrt(9c₂² − 8c₂))/2 and k = (ω² + 1 + 2c₂)/(2ω) (c₂ from [`l1`]); returns (ω, k).
pub fn l1_linear(c2: f64) -> (f64, f64) {
    let omega = ((2.0 - c2 + (9.0 * c2 * c2 - 8.0 * c2).sqrt()) / 2.0).sqrt();
    let k = (omega * omega + 1.0 + 2.0 * c2) / (2.0 * omega);
    (omega, k)
}

/// A found Lyapunov orbit of the continuation: (amplitude, initial state, period).
pub type L1Orbit = (f64, State<Momenta>, f64);

/// The guess (state, period) for the planar Lyapunov orbit of `amplitude` about L1 at x_L = `xl`,
/// continued from the orbits found so far: with none, the linearisation ([`l1_linear`]'s ω and k;
/// x = x_L − A, y = 0, ẋ = 0, ẏ = k A ω, so p_x = ẋ − y, p_y = ẏ + x, and T = `t0` = 2π/ω); with one
/// (`last`), its offsets from L1 (q = (x_L, 0), p = (0, x_L)) scaled by the amplitude ratio and the
/// period as T₀ + cA²; with two (`last`, `before`), the secant through them.
pub fn l1_guess(
    (xl, omega, k, t0): (f64, f64, f64, f64),
    amplitude: f64,
    last: &Option<L1Orbit>,
    before: &Option<L1Orbit>,
) -> (State<Momenta>, f64) {
    let x0 = xl - amplitude;
    match (last, before) {
        (None, _) => (
            State::with_momenta(0.0, [x0, 0.0], [0.0, k * amplitude * omega + x0]),
            t0,
        ),
        (Some((a, o, t)), None) => {
            let r = amplitude / a;
            let q = [xl + r * (o.q[0] - xl), r * o.q[1]];
            let p = [r * o.v[0], xl + r * (o.v[1] - xl)];
            (State::with_momenta(0.0, q, p), t0 + (t - t0) * r * r)
        }
        (Some((a1, o1, t1)), Some((a0, o0, t_0))) => {
            let s = (amplitude - a1) / (a1 - a0);
            let q = [
                o1.q[0] + s * (o1.q[0] - o0.q[0]),
                o1.q[1] + s * (o1.q[1] - o0.q[1]),
            ];
            let p = [
                o1.v[0] + s * (o1.v[0] - o0.v[0]),
                o1.v[1] + s * (o1.v[1] - o0.v[1]),
            ];
            (State::with_momenta(0.0, q, p), t1 + s * (t1 - t_0))
        }
    }
}

/// [`l1_guess`]'s linear guess of the planar Lyapunov orbit of `amplitude` about L1 as a state of the
/// spatial problem ([`SpatialCr3bp`], z = p_z = 0), with its period 2π/ω.
pub fn l1_spatial_guess(mu: f64, amplitude: f64) -> (State<Momenta>, f64) {
    let (xl, c2) = l1(mu);
    let (omega, k) = l1_linear(c2);
    let t0 = 2.0 * std::f64::consts::PI / omega;
    let (planar, period) = l1_guess((xl, omega, k, t0), amplitude, &None, &None);
    let (q, p) = (&planar.q, &planar.v);
    (
        State::with_momenta(0.0, [q[0], q[1], 0.0], [p[0], p[1], 0.0]),
        period,
    )
}

/// max |H − e| over every step of a periodic orbit given by its `nodes` (one per arc of multiple
/// shooting, `steps` steps of T/`steps` in all, split as the shooting splits them: the first
/// `steps` mod m arcs one step longer), each arc stepped from its node by `stepper`: how well the
/// method holds the energy (the Jacobi constant −2H) along the orbit.
pub fn energy_drift<H: Hamiltonian, S: Stepper<Partner = Momenta>>(
    model: &H,
    stepper: &mut S,
    nodes: &[State<Momenta>],
    (period, steps): (f64, usize),
    e: f64,
) -> noether_core::Result<f64> {
    let h = period / steps as f64;
    let mut drift = 0.0_f64;
    let m = nodes.len();
    for (j, node) in nodes.iter().enumerate() {
        let mut st = node.clone();
        for _ in 0..steps / m + usize::from(j < steps % m) {
            stepper.step(&mut st, h)?;
            let value = model.hamiltonian(st.t, st.q.as_slice(), st.v.as_slice());
            drift = drift.max((value - e).abs());
        }
    }
    Ok(drift)
}

/// The states of one period of the orbit from `start` ((period T, steps N): N steps of T/N by
/// `stepper`), `start` first and then every `every`-th step: its points for a picture, its closest
/// approach to a primary.
pub fn sample_orbit<S: Stepper<Partner = Momenta>>(
    stepper: &mut S,
    start: &State<Momenta>,
    (period, steps): (f64, usize),
    every: usize,
) -> noether_core::Result<Vec<State<Momenta>>> {
    let h = period / steps as f64;
    let mut st = start.clone();
    let mut points = vec![st.clone()];
    for i in 1..=steps {
        stepper.step(&mut st, h)?;
        if i % every.max(1) == 0 {
            points.push(st.clone());
        }
    }
    Ok(points)
}

/// max |y(T) − y₀| over the coordinates and momenta of `start` run once round the period `period` by
/// DOP853 at tolerance `tol` on `model`'s Hamilton equations: how far an orbit found on a method's
/// discrete map is from closing under the flow.
pub fn flow_closure<H: Hamiltonian>(
    model: H,
    start: &State<Momenta>,
    period: f64,
    tol: f64,
) -> noether_core::Result<f64> {
    use noether_core::prelude::{Dop853, Driver, HamiltonEquations, Save};
    let dop = Dop853::new(HamiltonEquations::new(model)).tolerances(tol, tol)?;
    let round = Driver::new(dop, start.clone())?
        .save(Save::End)?
        .run_until(start.t + period)?;
    let end = round.last();
    Ok(end
        .q
        .iter()
        .zip(&start.q)
        .chain(end.v.iter().zip(&start.v))
        .fold(0.0, |m, (a, b)| m.max((a - b).abs())))
}

/// The largest difference between the state `b` and the mirror image of `a` in the primaries' plane
/// of [`SpatialCr3bp`], (z, p_z) ↦ (−z, −p_z): zero when `b` starts the mirror image of `a`'s orbit.
pub fn mirror_defect(a: &State<Momenta>, b: &State<Momenta>) -> f64 {
    let sign = |i: usize| if i == 2 { -1.0 } else { 1.0 };
    (0..a.q.len())
        .map(|i| {
            (b.q[i] - sign(i) * a.q[i])
                .abs()
                .max((b.v[i] - sign(i) * a.v[i]).abs())
        })
        .fold(0.0, f64::max)
}
