//! # noether-gallery
//!
//! The worked examples of noether, each a complete program in `examples/` that runs a textbook system
//! and checks it against closed forms. `cargo run --release` runs them all and prints one table;
//! `cargo run --release --features examples --example pendulum` runs one. This library is what they share: the [`Check`]
//! of a computed value against its closed form, the [`Report`] of an example, the registry [`all`],
//! and a few closed forms and measurements.
//!
//! To add an example: write `examples/NAME.rs` with `pub fn run(opts: &Options) -> Result<Report,
//! BoxError>` and `fn main() -> ExitCode { noether_gallery::example_main("NAME", run) }`, then list it
//! in the `examples!` registry at the end of this file.

// The examples refer to this library by its name, also when they are compiled into it.
extern crate self as noether_gallery;

mod check;
/// The special functions of the closed forms (K, E, sn, cn, dn, Kepler's equation) and the free top,
/// shared with the crates' tests through noether-testkit.
pub use noether_testkit::closed_form;
pub mod measure;
pub mod page;

pub use check::{Check, Tolerance};

use noether::plot::Figure;
use std::path::PathBuf;
use std::process::ExitCode;

/// The error an example returns: whatever went wrong, from noether or from drawing.
pub type BoxError = Box<dyn std::error::Error + Send + Sync>;

/// Options shared by all examples.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Folder for SVG pictures; `None` writes no pictures.
    pub out_dir: Option<PathBuf>,
}

/// What an example produced.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// Checks against closed forms.
    pub checks: Vec<Check>,
    /// Pictures written.
    pub figures: Vec<PathBuf>,
    /// Measurements worth reading beside the checks (one line each): shown on the gallery's page,
    /// by `--notes`, and by the example run alone.
    pub notes: Vec<String>,
}

impl Report {
    /// Saves `figure` as `file` in the options' output folder (if any) and records its path.
    pub fn save(&mut self, opts: &Options, figure: &Figure, file: &str) -> Result<(), BoxError> {
        if let Some(dir) = &opts.out_dir {
            std::fs::create_dir_all(dir)?;
            self.figures.push(figure.save(dir.join(file))?);
        }
        Ok(())
    }

    /// Records a line of measurements (see [`notes`](Self::notes)).
    pub fn note(&mut self, line: impl Into<String>) {
        self.notes.push(line.into());
    }
}

/// What running an example gave: its report, or the error (or panic) that stopped it.
pub type Outcome = Result<Report, String>;

/// Runs one example, turning a panic into that example's error.
pub fn run_caught(ex: &Example, opts: &Options) -> Outcome {
    std::panic::catch_unwind(|| (ex.run)(opts))
        .map_err(|p| format!("panicked: {}", panic_message(&p)))
        .and_then(|r| r.map_err(|e| e.to_string()))
}

fn panic_message(p: &Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown".into())
}

/// A worked example of the gallery.
#[derive(Debug, Clone, Copy)]
pub struct Example {
    /// Short name (`--only NAME`), the name of its file in `examples/`.
    pub name: &'static str,
    /// One line on what it shows.
    pub about: &'static str,
    /// Runs it.
    pub run: fn(&Options) -> Result<Report, BoxError>,
}

/// Runs an example as a program (the `main` of each `examples/*.rs`): prints its checks and pictures,
/// and fails if a check fails or the example returns an error. Pictures go to `gallery-out/`.
pub fn example_main(name: &str, run: fn(&Options) -> Result<Report, BoxError>) -> ExitCode {
    let opts = Options {
        out_dir: Some(PathBuf::from("gallery-out")),
    };
    match run(&opts) {
        Ok(report) => {
            for n in &report.notes {
                println!("{n}");
            }
            for c in &report.checks {
                println!("{c}");
            }
            for f in &report.figures {
                println!("figure {}", f.display());
            }
            if report.checks.iter().all(Check::passed) {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Err(e) => {
            eprintln!("{name} failed: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Declares each example file as a module of this library and lists it in [`all`], in the order a
/// newcomer should read them.
macro_rules! examples {
    ($($name:ident: $about:literal,)*) => {
        /// The example programs (`examples/*.rs`), compiled into the library so the gallery runner and
        /// the tests can run them (their `main` is for `cargo run --example`).
        #[path = "../examples"]
        pub mod examples {
            $(
                #[allow(dead_code)]
                pub mod $name;
            )*
        }

        /// Every example of the gallery, in the order a newcomer should read them.
        pub fn all() -> Vec<Example> {
            vec![$(Example { name: stringify!($name), about: $about, run: examples::$name::run },)*]
        }
    };
}

examples! {
    pendulum: "simple pendulum: period at large amplitude vs 4 sqrt(l/g) K(sin(θ0/2))",
    export_trajectory: "your own model, sampled at chosen times, energy recorded, saved to CSV, read back, drawn",
    bouncing_ball: "bouncing ball: impacts as events with a reset, impact times and apex heights vs free fall",
    harmonic_oscillator: "harmonic oscillator: exact solution over 1000 periods",
    kepler: "Kepler orbit e = 0.6: period, energy, angular momentum, Runge-Lenz after 100 orbits",
    double_pendulum: "double pendulum: energy conservation over a chaotic run",
    driven_pendulum: "driven damped pendulum (generalized force): resonance amplitude and phase vs the linear closed form, energy balance",
    galerkin_orders: "Galerkin variational integrators of order 4 and 6 on Kepler: observed orders, angular momentum kept, no energy drift",
    cart_pole_lqr: "cart-pole balanced by LQR: textbook linearisation, closed-loop eigenvalues, cost x₀ᵀXx₀, a sampled design",
    satellite_slew: "spacecraft slewed rest to rest by a reaction wheel (DMOC, free wheel angle, conserved momentum): least effort and bounded torque vs closed forms",
    swing_up: "cart-pole swung up by discrete optimal control (DMOC), with a bounded force, tracked by time-varying LQR, caught by LQR: the double integrator's discrete optimum in closed form, order 2",
    equations_of_motion: "equations of motion derived on the graph and printed: double pendulum, heavy top, Hénon-Heiles as in the textbooks",
    compiled_chain: "a 40-link chain compiled and by dual numbers: the same run, the compiled one faster",
    charged_particle: "charge in uniform B: cyclotron frequency and radius, uniform motion along B",
    exb_drift: "charge in uniform E ⊥ B: the guiding centre drifts at E × B / B², energy with E",
    pendulum_cartesian: "pendulum in Cartesian coordinates with a rod constraint: angle motion and rod tension",
    spherical_pendulum: "spherical pendulum, Cartesian vs angles: same motion, E and L_z, turning points",
    bead_rotating_hoop: "bead on a rotating hoop (time-dependent constraint): Cartesian vs angle, hoop force, Jacobi integral",
    hoop_equilibria: "bead on a rotating hoop: equilibria and their frequencies, by argmin on U and by simulation",
    bead_helix: "bead on a helix under gravity: constant z̈ = −g a²/(a²+b²), wire force",
    bead_cycloid: "the tautochrone: period 4π sqrt(a/g) from every release height (singular mass matrix)",
    rolling_disk: "disk rolling without slipping (nonholonomic): constant rates, circular path, energy",
    heavy_top: "heavy symmetric top in Euler angles: the conserved p_φ, p_ψ, E and the precession rate",
    top_nutation: "heavy top: θ nutates between the roots of the cubic in cos θ, period by quadrature",
    fast_top: "the fast top: slow precession at M g ℓ/(I₃ ω₃), exactly the quadrature's Δφ/T",
    sleeping_top: "the sleeping top (Cardan angles): stable above I₃²ω₃² = 4I₁Mgℓ, falls below; the Euler chart's pole",
    normal_modes: "equilibria (argmin) and normal modes: coupled pendula, chain, triangle",
    three_body: "restricted three-body problem: Lagrange points, their linear stability, Routh's limit",
    trojan_orbits: "restricted three-body problem: orbits from L4 below and above Routh's limit, Jacobi integral",
    two_springs: "wall - m1 - m2 with two springs (particles): normal modes and the modal solution",
    binary_star: "binary star under gravity (particles): two-body Kepler orbit, centre of mass at rest",
    billiard: "billiard collision of equal balls (particles): momentum, energy, velocity exchange",
    third_law: "random internal interactions (particles): momentum and angular momentum to 1e-13",
    lj_cluster: "Lennard-Jones cluster of 100 atoms (particles): bounded energy error over 1e5 steps",
    rutherford: "Coulomb scattering: deflection angle vs impact parameter, Rutherford cross section",
    bertrand: "Bertrand's theorem: 1/r and r² orbits close, r^-1.1 precesses at the near-circular rate",
    high_order_orbits: "DPRKN 6/8/12 and IAS15 on Kepler at e = 0.99 (100 orbits, vs Kepler's equation) and the outer solar system (vs a reference run)",
    mercury_perihelion: "Mercury's perihelion advance (1PN, IAS15 with velocity-dependent forces): 6πGM/(c²a(1 − e²)) per orbit, 43″ per century",
    cyclotron: "relativistic charge in a uniform B: cyclotron frequency eB/(γm), radius, p_φ, energy",
    coupled_chains: "coupled mass-spring chains (midpoint variational): the paper's collision and its energy ratio",
    coupled_chains_momentum: "coupled chains: momentum to rounding, the mirror symmetry of the two chains (Figs. 5-7)",
    coupled_chains_transfer: "coupled chains: momentum transferred in a collision against v0 (the paper's Fig. 8)",
    coupled_chains_heat: "coupled chains, attractive: equilibrium, random heating, energy of each chain, spectra",
    struck_rod: "impulsive motion: a struck rod, a caught rod, a peg at the centre of percussion",
    collision_lab_cm: "two unequal masses collide: lab angles, recoil, energy transfer, lab cross section from CM",
    action_angle: "action-angle variables by quadrature: pendulum (elliptic K, E), Kepler's radial and Delaunay actions",
    poisson_brackets: "Poisson brackets by AD: {L_x, L_y} = L_z, Kepler's L and Runge-Lenz A commute with H, {A_x, A_y} = −2mH L_z",
    canonical_transformation: "canonical maps and generating functions: oscillator to action-angle (K = ωP), polar coordinates, rotating frame (K = H − ωL_z)",
    hamilton_jacobi: "Hamilton-Jacobi: Kepler's separated complete integral, the orbit from Jacobi's theorem vs DOP853 and the conic",
    poincare_henon_heiles: "Poincaré sections of Hénon-Heiles at E = 1/12 and 1/6: points on H = E; a separable system's on its second integral",
    routh_reduction: "Routh's reduction: Kepler to r, the heavy top to θ against the full model, cyclic angles by quadrature",
    adiabatic_invariant: "adiabatic invariance: an oscillator's frequency ramped 1 → 4, E × 4 while J moves by O(ε)",
    free_rigid_body: "free asymmetric body in quaternions (LGVI): Ω by sn, cn, dn, period 4K/rate, |L| and E to rounding",
    intermediate_axis: "the Dzhanibekov flip: a body spun about its middle axis turns over, period 4K(k)/rate near the separatrix",
    top_quaternion: "heavy top in quaternions (LGVI): turning points and precession as in Euler angles, sleeping and over the vertical",
    gibbs_appell: "quasi-velocities and the Gibbs-Appell equations: Euler's equations, the rolling disk without multipliers",
    rolling_sphere: "sphere rolling without slipping (Gibbs-Appell): turntable orbit at 2Ω/7, periods in a bowl",
    periodic_orbits: "periodic orbits by shooting: pendulum period vs 4K, Lyapunov orbits about L1 unstable with λ ≈ 2700",
    figure_eight: "the figure-eight of three bodies by shooting from a rough guess vs the published orbit; linearly stable",
    lyapunov_spectrum: "Lyapunov spectra (Benettin, exact tangents): oscillator and torus → 0 like ln t/t, chaotic Hénon-Heiles and double pendulum λ₁ > 0, pairing",
    halo_orbits: "halo orbits of the Earth-Moon L1 point: the Lyapunov family continued to its branch point (vertical trace 2, C = 3.1743), both halo families switched onto, mirror images, the flow's orbits",
    lyapunov_family: "the Earth-Moon L1 Lyapunov family by multiple shooting and pseudo-arclength continuation to 58 000 km from L1: period → 2π/ω as T₀ + κA², one unstable family, the flow's orbits",
    megno_map: "MEGNO stability map of Hénon-Heiles at E = 1/8 (an ensemble over the section): ⟨Y⟩ → 2 on tori, the chaotic cells those one sea orbit visits, time-reversal symmetric",
    sensitivity: "sensitivities of a run: the pendulum's θ(T) in g and θ₀ by tangents, vs differences of runs and the small-amplitude closed form",
    symplecticity_check: "self-checks of integrators: ‖ΨᵀΩΨ − Ω‖ (RK4 h⁶/72 on the oscillator, O(h⁵)), observed orders, reversibility",
    boundary_value: "boundary-value problems by the discrete Hamilton principle: projectile, oscillator conjugate points, sphere geodesic, figure-eight",
    scattering_monte_carlo: "Rutherford scattering as a Monte Carlo ensemble: 10⁵ random impact parameters, dσ/dΩ per bin vs (κ/4E)²/sin⁴(Θ/2), χ²",
    flip_map: "double pendulum: time to first flip over a grid of (θ₁, θ₂) (an ensemble), none where the energy forbids it",
    joints_double_pendulum: "double pendulum from two hinges (multibody): its written-for-you L, M and q̈ are the hand-written ones, same motion, energy",
    slider_crank: "slider-crank with a loop closure (multibody): piston position and holding crank torque vs closed forms, RATTLE keeps the loop",
    four_bar: "four-bar linkage (multibody, loop closed by a constraint): Grashof crank-rocker, closure to rounding over 10⁵ RATTLE steps, the rocker's toggle angles",
    reaction_wheel_pendulum: "reaction-wheel pendulum from bodies and joints: (A, B) upright vs the closed form, balanced by LQR, the momentum balance",
    spherical_joint: "spherical pendulum through a ball joint (multibody, exponential coordinates): straight through both poles, swing and loop periods vs 4K, the conical rate g/(l cos α), E, L_z, L₃ through chart renewals",
    rolling_coin: "a coin from a rolling joint (multibody, no-slip written for you): the hand-written coin, a steady turn and its wobble vs Routh's closed forms, upright above ω₃² = g/(3a)",
    planar_arm: "three-link planar arm from bodies and joints: mass matrix and tip vs the textbook, gravity, (A, B) upright, balanced by LQR",
}

/// The README's examples, compiled and run as doc-tests so that they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

// The guide (docs/guide.md) is the facade's `noether::guide` and is doc-tested there.
