//! The gallery of worked examples: each example runs a textbook system and returns its checks
//! against closed forms. `examples/*.rs` print one example's checks; `cargo run --release` runs them all.
//!
//! To add an example: write a module here with `pub fn run(opts: &Options) -> Result<Report, Error>`,
//! and list it in [`all`].

use std::fmt;
use std::path::PathBuf;

// Helpers shared by the examples.
pub mod measure;
pub mod plot;

// The examples.
pub mod bead_cycloid;
pub mod bead_helix;
pub mod bead_rotating_hoop;
pub mod bertrand;
pub mod billiard;
pub mod binary_star;
pub mod charged_particle;
pub mod coupled_chains;
pub mod cyclotron;
pub mod double_pendulum;
pub mod harmonic_oscillator;
pub mod heavy_top;
pub mod kepler;
pub mod lj_cluster;
pub mod normal_modes;
pub mod pendulum;
pub mod pendulum_cartesian;
pub mod rolling_disk;
pub mod rutherford;
pub mod spherical_pendulum;
pub mod third_law;
pub mod three_body;
pub mod two_springs;

/// How a computed value is compared with the expected one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tolerance {
    /// |computed − expected| / |expected| ≤ tol.
    Relative(f64),
    /// |computed − expected| ≤ tol (for quantities whose expected value is 0, such as a drift).
    Absolute(f64),
}

/// One check of a computed quantity against its closed form.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// Example name, e.g. "pendulum".
    pub example: &'static str,
    /// Quantity, e.g. "period(θ0=1)".
    pub quantity: String,
    /// Value noether computed.
    pub computed: f64,
    /// Closed-form value.
    pub expected: f64,
    /// Allowed error.
    pub tolerance: Tolerance,
}

impl Check {
    /// A check with a relative tolerance.
    pub fn rel(
        example: &'static str,
        quantity: impl Into<String>,
        computed: f64,
        expected: f64,
        tol: f64,
    ) -> Self {
        Self::new(example, quantity, computed, expected, Tolerance::Relative(tol))
    }

    /// A check with an absolute tolerance.
    pub fn abs(
        example: &'static str,
        quantity: impl Into<String>,
        computed: f64,
        expected: f64,
        tol: f64,
    ) -> Self {
        Self::new(example, quantity, computed, expected, Tolerance::Absolute(tol))
    }

    fn new(
        example: &'static str,
        quantity: impl Into<String>,
        computed: f64,
        expected: f64,
        tolerance: Tolerance,
    ) -> Self {
        Check {
            example,
            quantity: quantity.into(),
            computed,
            expected,
            tolerance,
        }
    }

    /// The error measured in the check's own norm (relative or absolute).
    pub fn error(&self) -> f64 {
        let d = (self.computed - self.expected).abs();
        match self.tolerance {
            Tolerance::Relative(_) => d / self.expected.abs(),
            Tolerance::Absolute(_) => d,
        }
    }

    /// The tolerance value.
    pub fn tol(&self) -> f64 {
        match self.tolerance {
            Tolerance::Relative(t) | Tolerance::Absolute(t) => t,
        }
    }

    /// `true` when the error is finite and within tolerance.
    pub fn passed(&self) -> bool {
        let e = self.error();
        e.is_finite() && e <= self.tol()
    }
}

impl fmt::Display for Check {
    /// `check <example>/<quantity>: computed=<v> expected=<v> rel_err=<v> tol=<v> PASS|FAIL`
    /// (`abs_err` in place of `rel_err` for absolute checks).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.tolerance {
            Tolerance::Relative(_) => "rel_err",
            Tolerance::Absolute(_) => "abs_err",
        };
        write!(
            f,
            "check {}/{}: computed={:.12e} expected={:.12e} {}={:.3e} tol={:.1e} {}",
            self.example,
            self.quantity,
            self.computed,
            self.expected,
            kind,
            self.error(),
            self.tol(),
            if self.passed() { "PASS" } else { "FAIL" }
        )
    }
}

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
}

/// A worked example of the gallery.
#[derive(Debug, Clone, Copy)]
pub struct Example {
    /// Short name (`--only NAME`).
    pub name: &'static str,
    /// One line on what it shows.
    pub about: &'static str,
    /// Runs it.
    pub run: fn(&Options) -> Result<Report, Box<dyn std::error::Error + Send + Sync>>,
}

/// Every example of the gallery, in the order a newcomer should read them.
pub fn all() -> Vec<Example> {
    vec![
        Example {
            name: "pendulum",
            about: "simple pendulum: period at large amplitude vs 4 sqrt(l/g) K(sin(θ0/2))",
            run: pendulum::run,
        },
        Example {
            name: "harmonic_oscillator",
            about: "harmonic oscillator: exact solution over 1000 periods",
            run: harmonic_oscillator::run,
        },
        Example {
            name: "kepler",
            about: "Kepler orbit e = 0.6: period, energy, angular momentum, Runge-Lenz after 100 orbits",
            run: kepler::run,
        },
        Example {
            name: "double_pendulum",
            about: "double pendulum: energy conservation over a chaotic run",
            run: double_pendulum::run,
        },
        Example {
            name: "charged_particle",
            about: "charge in uniform B (and E): cyclotron frequency and radius, E×B drift",
            run: charged_particle::run,
        },
        Example {
            name: "pendulum_cartesian",
            about: "pendulum in Cartesian coordinates with a rod constraint: angle motion and rod tension",
            run: pendulum_cartesian::run,
        },
        Example {
            name: "spherical_pendulum",
            about: "spherical pendulum, Cartesian vs angles: same motion, E and L_z, turning points",
            run: spherical_pendulum::run,
        },
        Example {
            name: "bead_rotating_hoop",
            about: "bead on a rotating hoop (time-dependent constraint): equilibria, frequencies, hoop force",
            run: bead_rotating_hoop::run,
        },
        Example {
            name: "bead_helix",
            about: "bead on a helix under gravity: constant z̈ = −g a²/(a²+b²), wire force",
            run: bead_helix::run,
        },
        Example {
            name: "bead_cycloid",
            about: "the tautochrone: period 4π sqrt(a/g) from every release height (singular mass matrix)",
            run: bead_cycloid::run,
        },
        Example {
            name: "rolling_disk",
            about: "disk rolling without slipping (nonholonomic): constant rates, circular path, energy",
            run: rolling_disk::run,
        },
        Example {
            name: "heavy_top",
            about: "heavy symmetric top in Euler angles: constants, nutation cubic, precession, sleeping top",
            run: heavy_top::run,
        },
        Example {
            name: "normal_modes",
            about: "equilibria (argmin) and normal modes: coupled pendula, chain, rotating hoop, triangle",
            run: normal_modes::run,
        },
        Example {
            name: "three_body",
            about: "restricted three-body problem: Jacobi integral, Lagrange points, Routh's stability limit",
            run: three_body::run,
        },
        Example {
            name: "two_springs",
            about: "wall - m1 - m2 with two springs (particles): normal modes and the modal solution",
            run: two_springs::run,
        },
        Example {
            name: "binary_star",
            about: "binary star under gravity (particles): two-body Kepler orbit, centre of mass at rest",
            run: binary_star::run,
        },
        Example {
            name: "billiard",
            about: "billiard collision of equal balls (particles): momentum, energy, velocity exchange",
            run: billiard::run,
        },
        Example {
            name: "third_law",
            about: "random internal interactions (particles): momentum and angular momentum to 1e-13",
            run: third_law::run,
        },
        Example {
            name: "lj_cluster",
            about: "Lennard-Jones cluster of 100 atoms (particles): bounded energy error over 1e5 steps",
            run: lj_cluster::run,
        },
        Example {
            name: "rutherford",
            about: "Coulomb scattering: deflection angle vs impact parameter, Rutherford cross section",
            run: rutherford::run,
        },
        Example {
            name: "bertrand",
            about: "Bertrand's theorem: 1/r and r² orbits close, r^-1.1 precesses at the near-circular rate",
            run: bertrand::run,
        },
        Example {
            name: "cyclotron",
            about: "relativistic charge in a uniform B: cyclotron frequency eB/(γm), radius, p_φ, energy",
            run: cyclotron::run,
        },
        Example {
            name: "coupled_chains",
            about: "coupled mass-spring chains (midpoint variational): momentum to rounding, transfer, heat",
            run: coupled_chains::run,
        },
    ]
}

/// Runs one example and prints its check lines; exits non-zero if a check fails (for `examples/*.rs`).
pub fn main_for(name: &str) {
    let Some(ex) = all().into_iter().find(|e| e.name == name) else {
        eprintln!("no example named {name}");
        std::process::exit(2);
    };
    let opts = Options {
        out_dir: Some(PathBuf::from("gallery-out")),
    };
    match (ex.run)(&opts) {
        Ok(report) => {
            for c in &report.checks {
                println!("{c}");
            }
            for f in &report.figures {
                println!("figure {}", f.display());
            }
            if report.checks.iter().any(|c| !c.passed()) {
                std::process::exit(1);
            }
        }
        Err(e) => {
            eprintln!("{name} failed: {e}");
            std::process::exit(1);
        }
    }
}
