//! Dormand-Prince 5(4) (DOPRI5): 7 stages (the last one is F(t+h, y₁), reused as the first stage of
//! the next step, FSAL), fifth-order solution, fourth-order embedded error estimate, and Shampine's
//! fourth-order continuous extension (no extra stage).
//!
//! # References
//! - J. R. Dormand, P. J. Prince, A family of embedded Runge-Kutta formulae, J. Comput. Appl. Math. 6
//!   (1980) 19-26.
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., Table
//!   II.5.2 (coefficients), II.6 (dense output, code DOPRI5).

use super::adaptive::{Adaptive, Controller, EmbeddedPair, Stages};

/// The DOPRI5 tableau (see the [module](self) docs).
#[derive(Debug, Clone, Copy)]
pub struct Dp5;

/// Dormand-Prince 5(4) with error control and dense output, stepping any [`Dynamics`](crate::Dynamics).
pub type Dopri5<S> = Adaptive<S, Dp5>;

/// e_i = b_i − b̂_i (fifth minus fourth order), over the 7 stages.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// Dense-output weights d_i.
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

impl EmbeddedPair for Dp5 {
    const NAME: &'static str = "Dormand-Prince 5(4)";
    const ORDER: u32 = 5;
    const CONTROL_ORDER: f64 = 5.0;
    const CONTROLLER: Controller = Controller::DOPRI5;
    const C: &'static [f64] = &[0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0];
    const A: &'static [&'static [f64]] = &[
        &[],
        &[1.0 / 5.0],
        &[3.0 / 40.0, 9.0 / 40.0],
        &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
    ];
    const B: &'static [f64] = &[
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ];
    const DENSE_STAGES: &'static [(f64, &'static [f64])] = &[];
    const DENSE_LEN: usize = 4;
    const DENSE_ORDER: u32 = 4;

    const ERROR: &'static [&'static [f64]] = &[&E];

    /// err = |h| sqrt(S/m): the root mean square of the scaled estimate h Σ_j e_j k_j over the m
    /// components of y.
    fn error_norm(h: f64, sums: [f64; 2], m: usize) -> f64 {
        // No components (a system of 0 degrees of freedom): no error, not 0/0.
        h.abs() * (sums[0] / m.max(1) as f64).sqrt()
    }

    /// r₁ = y₁ − y₀, r₂ = h k₁ − r₁, r₃ = r₁ − h k₇ − r₂, r₄ = h Σ d_i k_i.
    fn dense_coefficients(h: f64, k: Stages<'_>, y0: &[f64], y1: &[f64], out: &mut [Vec<f64>]) {
        for i in 0..y0.len() {
            let dy = y1[i] - y0[i];
            let bspl = h * k.get(0, i) - dy;
            out[0][i] = dy;
            out[1][i] = bspl;
            out[2][i] = dy - h * k.get(6, i) - bspl;
            out[3][i] = h * k.weighted(&D, i);
        }
    }

    /// y(t₀ + θh) = y₀ + θ(r₁ + (1−θ)(r₂ + θ(r₃ + (1−θ) r₄))).
    fn dense_eval(theta: f64, y0: &[f64], c: &[Vec<f64>], out: &mut [f64]) {
        let s = 1.0 - theta;
        for i in 0..y0.len() {
            out[i] = y0[i] + theta * (c[0][i] + s * (c[1][i] + theta * (c[2][i] + s * c[3][i])));
        }
    }
}
