//! Lyapunov spectra by Benettin's method: the mean exponential growth rates of the tangent space
//! along one orbit, from the exact Jacobians of the numerical flow.
//!
//! **Method** (Benettin, Galgani, Giorgilli & Strelcyn, *Meccanica* 15, 9–20 and 21–30, 1980). Take k
//! orthonormal tangent vectors, the columns of W (2n × k). Every step of the method maps them by the
//! step's Jacobian, W ← Ψ W, Ψ = ∂y₁/∂y₀ from a [`TangentStepper`]; every m steps W is factored as
//! W = Q R (Householder QR, R with positive or negative diagonal), the growth of the i-th volume
//! factor ln|R_ii| is added to a sum S_i and W is replaced by Q. After the time t of N
//! re-orthonormalisations,
//!
//! ```text
//! λ_i(t) = S_i / t = (1/t) Σ ln|R_ii|,   λ₁ ≥ λ₂ ≥ … ≥ λ_k (as t → ∞, Oseledets),
//! ```
//!
//! the k largest Lyapunov exponents. The sum λ₁ + … + λ_k is the growth rate of k-volumes, so for k = 2n
//! it is the mean of ln det Ψ per unit time: zero for a symplectic method (det Ψ = 1 to rounding), a
//! tiny negative number for RK4 (det Ψ = 1 − O(h⁶) per step on the oscillator). For a Hamiltonian flow
//! the spectrum pairs, λ_i + λ_{2n+1−i} = 0, and an autonomous one has at least two zero exponents
//! (along the flow and across the energy surface).
//!
//! The initial vectors need a while to turn into the Oseledets directions; what they gain or lose
//! meanwhile is a fixed amount D_i in S_i, a bias D_i / t that decays like 1/t (visible as a pairing
//! defect λ_i + λ_{2n+1−i} = (D_i + D_{2n+1−i})/t); [`Lyapunov::discard_transient`] drops it.
//!
//! The running estimate λ(t) is kept at every re-orthonormalisation (the convergence picture); on a
//! regular orbit (a torus) the tangent vectors grow linearly by the shear of the torus and λ(t) decays
//! like ln t / t, on a chaotic one λ₁(t) settles at a positive value. The statistical error is the
//! spread over blocks: the run's re-orthonormalisations are cut into B consecutive blocks of equal
//! length, each gives its own estimate λ_i^(b), and the error of the mean is their standard deviation
//! over √B (the batch-means estimate; it assumes the blocks are longer than the correlation time).
//!
//! The interval m trades cost against overflow and the loss of the weaker directions: W's columns all
//! turn towards the most unstable direction at rate e^{(λ₁−λ_k) m h}, so m h (λ₁ − λ_k) of a few units
//! at most; m = 1 is always safe.
//!
//! ```
//! use noether_analysis::Lyapunov;
//! use noether_core::prelude::*;
//!
//! /// Harmonic oscillator H = ½(p² + q²): the flow is a rotation, every exponent is zero.
//! struct Oscillator;
//! impl Hamiltonian for Oscillator {
//!     fn dof(&self) -> usize { 1 }
//!     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
//!         (p[0] * p[0] + q[0] * q[0]) * 0.5
//!     }
//! }
//! let rk4 = Rk4::new(HamiltonEquations::new(Oscillator));
//! let mut lyap = Lyapunov::new(rk4, State::with_momenta(0.0, [1.0], [0.0]), 2, 0.05, 10).unwrap();
//! lyap.advance_to(200.0).unwrap();
//! let spectrum = lyap.spectrum(4).unwrap();
//! assert!(spectrum.exponents.iter().all(|l| l.abs() < 1e-2));
//! ```

use crate::{Error, Result};
use nalgebra::DMatrix;
use noether_core::tangent::propagate;
use noether_core::{State, TangentStepper};

/// Benettin's method running on one orbit: the stepper, the state, the tangent vectors and the
/// accumulated ln|R_ii|.
///
/// Steps are of fixed size `h`; for an adaptive stepper each step's Ψ is that of the step it took.
#[derive(Debug, Clone)]
pub struct Lyapunov<S: TangentStepper> {
    stepper: S,
    state: State<S::Partner>,
    /// Tangent vectors, 2n × k.
    w: DMatrix<f64>,
    /// Scratch: Ψ of the last step and Ψ W.
    h: f64,
    every: usize,
    /// Steps since the last re-orthonormalisation.
    since: usize,
    /// Time at the start (of the sums).
    t0: f64,
    /// Time of each re-orthonormalisation.
    times: Vec<f64>,
    /// ln|R_ii| of each re-orthonormalisation, k per record, flat.
    logs: Vec<f64>,
}

/// A Lyapunov spectrum with its statistical error.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Spectrum {
    /// λ₁ ≥ … ≥ λ_k (in the order of the tangent vectors; Benettin's QR sorts them by itself), per
    /// unit time.
    pub exponents: Vec<f64>,
    /// Statistical error of each exponent: standard deviation of the block estimates over √B.
    pub errors: Vec<f64>,
    /// λ_i + λ_{k+1−i} for i = 1 … ⌊k/2⌋: zero for a Hamiltonian flow when k = 2n (the pairing).
    pub pair_sums: Vec<f64>,
    /// Statistical error of each pair sum (from the block estimates of the sum itself, which are
    /// strongly anti-correlated within a pair: much smaller than the errors of the two exponents added).
    pub pair_errors: Vec<f64>,
    /// λ₁ + … + λ_k: the growth rate of k-volumes (for k = 2n, the mean of ln det Ψ per unit time).
    pub sum: f64,
    /// Statistical error of the sum, by blocks.
    pub sum_error: f64,
    /// Length of the run the estimate covers (start to the last re-orthonormalisation).
    pub time: f64,
    /// Number of blocks of the error estimate.
    pub blocks: usize,
}

impl<S: TangentStepper> Lyapunov<S> {
    /// Starts Benettin's method at `state` with `vectors` tangent vectors (1 ≤ k ≤ 2n), steps of size `h`
    /// and a re-orthonormalisation every `every` steps.
    ///
    /// The initial tangent vectors are a fixed, generic orthonormal frame (QR of a deterministic
    /// pseudo-random matrix) so that no vector starts in a special subspace (the flow direction, a
    /// symmetry plane); [`initial_vectors`](Self::initial_vectors) sets one's own.
    pub fn new(stepper: S, state: State<S::Partner>, vectors: usize, h: f64, every: usize) -> Result<Self> {
        let n = stepper.dof();
        state.validate(n)?;
        noether_core::error::check_step(h)?;
        if vectors == 0 || vectors > 2 * n {
            return Err(Error::TangentVectors {
                requested: vectors,
                dimension: 2 * n,
            });
        }
        if every == 0 {
            return Err(Error::ReorthonormalizationInterval { every });
        }
        let w = generic_frame(2 * n, vectors);
        Ok(Lyapunov {
            stepper,
            t0: state.t,
            state,
            w,
            h,
            every,
            since: 0,
            times: Vec::new(),
            logs: Vec::new(),
        })
    }

    /// Replaces the tangent vectors by the columns of `w` (2n × k, orthonormalised here) and restarts
    /// the sums at the current time.
    pub fn initial_vectors(mut self, w: DMatrix<f64>) -> Result<Self> {
        let dim = 2 * self.stepper.dof();
        if w.nrows() != dim {
            return Err(noether_core::Error::Dimension {
                what: "tangent vectors (rows)",
                expected: dim,
                got: w.nrows(),
            }
            .into());
        }
        if w.ncols() == 0 || w.ncols() > dim {
            return Err(Error::TangentVectors {
                requested: w.ncols(),
                dimension: dim,
            });
        }
        noether_core::error::check_finite("tangent vectors", w.as_slice())?;
        let t = self.state.t;
        let k = w.ncols();
        let scale = column_scale(&w);
        let qr = w.qr();
        let r = qr.r();
        if let Some(index) = (0..k).find(|&i| collapsed(r[(i, i)], scale)) {
            return Err(Error::TangentCollapse {
                t,
                index,
                r: r[(index, index)],
            });
        }
        self.w = qr.q();
        self.t0 = t;
        self.since = 0;
        self.times.clear();
        self.logs.clear();
        Ok(self)
    }

    /// Takes `steps` steps, re-orthonormalising every m of them (the count carries over between calls).
    ///
    /// The vectors are carried by core's [`propagate`] between re-orthonormalisations. On error the
    /// run stops at the last re-orthonormalisation (or the start of this call, if later): the state,
    /// vectors and sums are those there.
    pub fn advance(&mut self, mut steps: usize) -> Result<()> {
        while steps > 0 {
            let chunk = steps.min(self.every - self.since);
            propagate(&mut self.stepper, &mut self.state, self.h, chunk, &mut self.w)?;
            self.since += chunk;
            steps -= chunk;
            if self.since == self.every {
                self.reorthonormalize()?;
            }
        }
        Ok(())
    }

    /// Steps until the time is `t_end` (rounded to a whole number of steps; nothing when `t_end` is not
    /// ahead).
    pub fn advance_to(&mut self, t_end: f64) -> Result<()> {
        self.advance(steps_to(self.state.t, t_end, self.h)?)
    }

    /// Forgets the sums so far (keeping the orbit and the tangent vectors): the estimate restarts at
    /// the current time. Call it after a transient, once the vectors have turned into the Oseledets
    /// directions: the start-up contributions (which decay only like 1/t, and make the pairing
    /// λ_i + λ_{2n+1−i} = 0 hold only to D/t) then no longer enter. Re-orthonormalises first when the
    /// vectors are not orthonormal (steps were taken since the last re-orthonormalisation).
    pub fn discard_transient(&mut self) -> Result<()> {
        if self.since != 0 {
            self.reorthonormalize()?;
        }
        self.t0 = self.state.t;
        self.times.clear();
        self.logs.clear();
        Ok(())
    }

    /// W = Q R, S_i += ln|R_ii|, W ← Q.
    fn reorthonormalize(&mut self) -> Result<()> {
        let t = self.state.t;
        let k = self.w.ncols();
        let scale = column_scale(&self.w);
        let qr = self.w.clone().qr();
        let r = qr.r();
        let mut logs = Vec::with_capacity(k);
        for i in 0..k {
            let rii = r[(i, i)].abs();
            if collapsed(rii, scale) {
                return Err(Error::TangentCollapse {
                    t,
                    index: i,
                    r: r[(i, i)],
                });
            }
            logs.push(rii.ln());
        }
        self.w = qr.q();
        self.logs.extend(logs);
        self.times.push(t);
        self.since = 0;
        Ok(())
    }

    /// The current state of the orbit.
    pub fn state(&self) -> &State<S::Partner> {
        &self.state
    }

    /// The current (orthonormal after a re-orthonormalisation) tangent vectors, 2n × k.
    pub fn vectors(&self) -> &DMatrix<f64> {
        &self.w
    }

    /// The stepper.
    pub fn stepper(&self) -> &S {
        &self.stepper
    }

    /// Number of tangent vectors k.
    pub fn k(&self) -> usize {
        self.w.ncols()
    }

    /// Number of re-orthonormalisations recorded.
    pub fn reorthonormalizations(&self) -> usize {
        self.times.len()
    }

    /// The running estimate: (t − t₀, λ(t)) at every re-orthonormalisation, λ_i(t) = S_i(t) / (t − t₀).
    pub fn history(&self) -> Vec<(f64, Vec<f64>)> {
        let k = self.k();
        let mut sums = vec![0.0; k];
        self.times
            .iter()
            .zip(self.logs.chunks_exact(k))
            .map(|(&t, logs)| {
                for (s, l) in sums.iter_mut().zip(logs) {
                    *s += l;
                }
                let dt = t - self.t0;
                (dt, sums.iter().map(|s| s / dt).collect())
            })
            .collect()
    }

    /// The spectrum over the whole run so far (to the last re-orthonormalisation), with errors from
    /// `blocks` ≥ 2 blocks of consecutive re-orthonormalisations (the last few, when their number is
    /// not a multiple of `blocks`, are spread over the blocks: blocks differ by at most one record).
    pub fn spectrum(&self, blocks: usize) -> Result<Spectrum> {
        let records = self.times.len();
        if blocks < 2 || records < blocks {
            return Err(Error::TooShort {
                reorthonormalizations: records,
                blocks,
            });
        }
        let k = self.k();
        let npairs = k / 2;
        // Per block: the k exponents, the pair sums and the total, each a growth over the block's time.
        let mut per_block: Vec<Vec<f64>> = Vec::with_capacity(blocks);
        let mut totals = vec![0.0; k];
        for b in 0..blocks {
            let (first, last) = (b * records / blocks, (b + 1) * records / blocks);
            let start = if first == 0 {
                self.t0
            } else {
                self.times[first - 1]
            };
            let dt = self.times[last - 1] - start;
            let mut sums = vec![0.0; k];
            for logs in self.logs[first * k..last * k].chunks_exact(k) {
                for (s, l) in sums.iter_mut().zip(logs) {
                    *s += l;
                }
            }
            for (t, s) in totals.iter_mut().zip(&sums) {
                *t += s;
            }
            per_block.push(derived(&sums, npairs).into_iter().map(|x| x / dt).collect());
        }
        let time = self.times[records - 1] - self.t0;
        let overall: Vec<f64> = derived(&totals, npairs).into_iter().map(|x| x / time).collect();
        let errors: Vec<f64> = (0..overall.len())
            .map(|j| {
                let mean = per_block.iter().map(|v| v[j]).sum::<f64>() / blocks as f64;
                let var = per_block.iter().map(|v| (v[j] - mean).powi(2)).sum::<f64>() / (blocks - 1) as f64;
                (var / blocks as f64).sqrt()
            })
            .collect();
        Ok(Spectrum {
            exponents: overall[..k].to_vec(),
            errors: errors[..k].to_vec(),
            pair_sums: overall[k..k + npairs].to_vec(),
            pair_errors: errors[k..k + npairs].to_vec(),
            sum: overall[k + npairs],
            sum_error: errors[k + npairs],
            time,
            blocks,
        })
    }
}

/// The number of fixed steps h from t to `t_end`, rounded to the nearest (0 when `t_end` is not ahead;
/// `as` saturates for absurd values): what `advance_to` of a fixed-step run takes.
pub(crate) fn steps_to(t: f64, t_end: f64, h: f64) -> Result<usize> {
    let ahead = (t_end - t) / h;
    if !ahead.is_finite() {
        return Err(noether_core::Error::NonFinite {
            what: "t_end",
            index: 0,
        }
        .into());
    }
    Ok(if ahead > 0.0 { ahead.round() as usize } else { 0 })
}

/// (S₁ … S_k, S_i + S_{k+1−i} for i ≤ k/2, Σ S_i).
fn derived(sums: &[f64], npairs: usize) -> Vec<f64> {
    let k = sums.len();
    let mut out = sums.to_vec();
    out.extend((0..npairs).map(|i| sums[i] + sums[k - 1 - i]));
    out.push(sums.iter().sum());
    out
}

/// Relative size of |R_ii| (to the largest column of W) below which the i-th vector is lost: its part
/// orthogonal to the others is then of the order of the rounding of the others (Householder QR
/// computes it to about ε times the largest column), and ln|R_ii| would measure noise.
const COLLAPSE: f64 = 1e-10;

/// The largest Euclidean norm of a column of `w`.
fn column_scale(w: &DMatrix<f64>) -> f64 {
    w.column_iter().map(|c| c.norm()).fold(0.0, f64::max)
}

/// |R_ii| not finite, or below [`COLLAPSE`] times the largest column.
fn collapsed(rii: f64, scale: f64) -> bool {
    !(rii.is_finite() && scale.is_finite()) || rii.abs() <= COLLAPSE * scale
}

/// A fixed generic orthonormal frame: the thin Q of a matrix of xorshift numbers in (−1, 1).
fn generic_frame(dim: usize, k: usize) -> DMatrix<f64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let a = DMatrix::from_fn(dim, k, |_, _| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    });
    a.qr().q()
}
