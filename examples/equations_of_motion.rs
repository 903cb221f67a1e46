//! Equations of motion derived, simplified and printed: the double pendulum, the heavy symmetric top
//! and Hénon-Heiles, each compiled from its Lagrangian or potential as written for noether, its
//! equations shown as text and LaTeX and checked against the textbook's.
//!
//! `EulerLagrange::new(l).compile()` records L once as an expression graph, derives on the graph
//! M(q, q̇) = ∂²L/∂q̇² and b = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t of Lagrange's equations M q̈ = b, and
//! simplifies them (constants folded, common subexpressions shared). `equations()` writes those
//! graphs out as formulas, with products distributed and like terms collected for reading.
//!
//! The checks, for each system:
//! - the printed equations are, character for character, the textbook's (with unit parameters, so
//!   that the coefficients are the textbook's numbers: for the double pendulum with m = l = 1,
//!   b₁ = −2g sin θ₁ − θ̇₂² sin(θ₁ − θ₂), b₂ = −g sin θ₂ + θ̇₁² sin(θ₁ − θ₂) [Taylor, Classical
//!   Mechanics, §11.4; Goldstein §1.6]); the top's are Goldstein §5.7 / Landau-Lifshitz §35, L =
//!   ½I₁(θ̇² + φ̇² sin²θ) + ½I₃(ψ̇ + φ̇ cos θ)² − Mgℓ cos θ;
//! - the derived M and b (evaluated from the graph) equal the textbook formulas with general
//!   parameters at 1000 random states.
//!
//! Run: `cargo run --release --features examples --example equations_of_motion`.

use noether::compile::{Compile, Equations};
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::agreement::uniform;
use noether_testkit::henon_heiles::HenonHeiles;
use noether_testkit::systems::{DoublePendulum, HeavyTop};
use std::process::ExitCode;

/// The double pendulum with unit masses and rods in gravity 9.81, as Taylor writes its equations
/// (M q̈ = b, M's lower triangle then b).
const DOUBLE_PENDULUM: [&str; 5] = [
    "M₁₁ = 2",
    "M₂₁ = cos(θ₁ − θ₂)",
    "M₂₂ = 1",
    "b₁ = −19.62·sin(θ₁) − θ̇₂²·sin(θ₁ − θ₂)",
    "b₂ = −9.81·sin(θ₂) + θ̇₁²·sin(θ₁ − θ₂)",
];

/// The heavy top with I₁ = 2, I₃ = 1, Mgℓ = 3, coordinates (θ, φ, ψ):
/// M = [[I₁, 0, 0], [0, I₁ sin²θ + I₃ cos²θ, I₃ cos θ], [0, I₃ cos θ, I₃]],
/// b_θ = Mgℓ sin θ − I₃ φ̇ψ̇ sin θ + (I₁ − I₃) φ̇² sin θ cos θ,
/// b_φ = −2(I₁ − I₃) θ̇φ̇ sin θ cos θ + I₃ θ̇ψ̇ sin θ,   b_ψ = I₃ θ̇φ̇ sin θ.
const HEAVY_TOP: [&str; 9] = [
    "M₁₁ = 2",
    "M₂₁ = 0",
    "M₂₂ = 2·sin(θ)² + cos(θ)²",
    "M₃₁ = 0",
    "M₃₂ = cos(θ)",
    "M₃₃ = 1",
    "b₁ = 3·sin(θ) − φ̇·ψ̇·sin(θ) + φ̇²·cos(θ)·sin(θ)",
    "b₂ = −2·θ̇·φ̇·cos(θ)·sin(θ) + θ̇·ψ̇·sin(θ)",
    "b₃ = θ̇·φ̇·sin(θ)",
];

/// Hénon-Heiles, V = ½(x² + y²) + x²y − y³/3: ẍ = −x − 2xy, ÿ = −y − x² + y² (the dots are combining
/// marks, U+0308, as noether prints them over any name).
const HENON_HEILES: [&str; 2] = ["x\u{308} = −2·x·y − x", "y\u{308} = −y + y² − x²"];

/// The lines of `printed` that differ from `expected` (and any missing or extra line), as notes.
fn compare(printed: &str, expected: &[&str]) -> Vec<String> {
    let lines: Vec<&str> = printed.lines().collect();
    let mut wrong: Vec<String> = lines
        .iter()
        .zip(expected)
        .filter(|(a, b)| a != b)
        .map(|(a, b)| format!("printed {a:?}, textbook {b:?}"))
        .collect();
    if lines.len() != expected.len() {
        wrong.push(format!(
            "{} lines printed, {} in the textbook",
            lines.len(),
            expected.len()
        ));
    }
    wrong
}

/// Records the printed equations as notes and the check that they are the textbook's.
fn check_printed(report: &mut Report, what: &str, equations: &Equations, names: &[&str], textbook: &[&str]) {
    let printed = equations.text(names);
    report.note(format!("{what}:"));
    printed.lines().for_each(|l| report.note(format!("    {l}")));
    let wrong = compare(&printed, textbook);
    wrong
        .iter()
        .for_each(|w| report.note(format!("    MISMATCH {w}")));
    report.checks.push(Check::abs(
        "equations_of_motion",
        format!("{what}: printed lines unlike the textbook's"),
        wrong.len() as f64,
        0.0,
        0.0,
    ));
}

/// The double pendulum's M (lower triangle) and b in Taylor's form, Δ = θ₁ − θ₂:
/// M = [[(m₁ + m₂) l₁², m₂ l₁ l₂ cos Δ], [·, m₂ l₂²]],
/// b₁ = −(m₁ + m₂) g l₁ sin θ₁ − m₂ l₁ l₂ θ̇₂² sin Δ,   b₂ = −m₂ g l₂ sin θ₂ + m₂ l₁ l₂ θ̇₁² sin Δ.
fn double_pendulum_textbook(p: &DoublePendulum, q: &[f64], v: &[f64]) -> [f64; 5] {
    let (m, k) = (p.m1 + p.m2, p.m2 * p.l1 * p.l2);
    let d = q[0] - q[1];
    [
        m * p.l1 * p.l1,
        k * d.cos(),
        p.m2 * p.l2 * p.l2,
        -m * p.g * p.l1 * q[0].sin() - k * v[1] * v[1] * d.sin(),
        -p.m2 * p.g * p.l2 * q[1].sin() + k * v[0] * v[0] * d.sin(),
    ]
}

/// The heavy top's M (lower triangle) and b as in [`HEAVY_TOP`], general I₁, I₃, Mgℓ.
fn heavy_top_textbook(p: &HeavyTop, q: &[f64], v: &[f64]) -> [f64; 9] {
    let (s, c) = q[0].sin_cos();
    let (td, pd, sd) = (v[0], v[1], v[2]);
    let di = p.i1 - p.i3;
    [
        p.i1,
        0.0,
        p.i1 * s * s + p.i3 * c * c,
        0.0,
        p.i3 * c,
        p.i3,
        p.mgl * s - p.i3 * pd * sd * s + di * pd * pd * s * c,
        -2.0 * di * td * pd * s * c + p.i3 * td * sd * s,
        p.i3 * td * pd * s,
    ]
}

/// The largest difference between the derived terms and the textbook's at `states` random states,
/// relative to the largest textbook term there.
fn largest_difference<const K: usize>(
    equations: &Equations,
    n: usize,
    states: usize,
    textbook: impl Fn(&[f64], &[f64]) -> [f64; K],
) -> f64 {
    let mut rnd = uniform(17);
    let mut worst = 0.0_f64;
    for _ in 0..states {
        let x: Vec<f64> = (0..1 + 2 * n).map(|_| rnd(-3.0, 3.0)).collect();
        let derived = equations.evaluate(&x);
        let expected = textbook(&x[1..=n], &x[n + 1..]);
        let scale = expected.iter().fold(0.0_f64, |m, e| m.max(e.abs()));
        let diff = derived
            .iter()
            .zip(&expected)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        worst = worst.max(diff / scale);
    }
    worst
}

/// Runs the example.
///
/// Tolerance of the evaluated terms: the derived graph and the textbook formula round differently
/// (different association of the same products and sums), a few ulps of the largest term; measured
/// at most 1.1e-15 (double pendulum) and 1.5e-15 (top) relative over 1000 states, checked at 4e-15.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let unit = DoublePendulum {
        m1: 1.0,
        m2: 1.0,
        l1: 1.0,
        l2: 1.0,
        g: 9.81,
    };
    let dp = EulerLagrange::new(unit).compile()?;
    check_printed(
        &mut report,
        "double pendulum, M q̈ = b",
        &dp.equations(),
        &["θ₁", "θ₂"],
        &DOUBLE_PENDULUM,
    );
    report.note("    in LaTeX:");
    let latex = dp.equations().latex(&["\\theta_1", "\\theta_2"]);
    latex.lines().for_each(|l| report.note(format!("    {l}")));
    let top = HeavyTop {
        i1: 2.0,
        i3: 1.0,
        mgl: 3.0,
    };
    let compiled_top = EulerLagrange::new(top).compile()?;
    check_printed(
        &mut report,
        "heavy top, M q̈ = b",
        &compiled_top.equations(),
        &["θ", "φ", "ψ"],
        &HEAVY_TOP,
    );
    let hh = Natural::unit(HenonHeiles).compile()?;
    check_printed(
        &mut report,
        "Hénon-Heiles, q̈ = −∇V",
        &hh.equations(),
        &["x", "y"],
        &HENON_HEILES,
    );

    // General parameters: the derived terms against the textbook formulas.
    let p = DoublePendulum::default();
    let derived = EulerLagrange::new(p).compile()?.equations();
    let e = largest_difference(&derived, 2, 1000, |q, v| double_pendulum_textbook(&p, q, v));
    report.checks.push(Check::abs(
        "equations_of_motion",
        "double pendulum: M and b vs Taylor's, max relative",
        e,
        0.0,
        4e-15,
    ));
    let p = HeavyTop::default();
    let derived = EulerLagrange::new(p).compile()?.equations();
    let e = largest_difference(&derived, 3, 1000, |q, v| heavy_top_textbook(&p, q, v));
    report.checks.push(Check::abs(
        "equations_of_motion",
        "heavy top: M and b vs Goldstein's, max relative",
        e,
        0.0,
        4e-15,
    ));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main("equations_of_motion", run)
}
