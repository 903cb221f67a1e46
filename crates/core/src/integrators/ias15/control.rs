//! The step-size control of IAS15 (see the [module](super) docs): the proposal after a converged
//! step, by either criterion of [`Ias15Control`], and the initial step size.

use super::{Ias15, Ias15Control, Ias15System, SAFETY};
use crate::integrators::step_control::{finite_stage, initial_step_size, start_accelerations_by};
use crate::{Result, State};

impl<S: Ias15System> Ias15<S> {
    /// The step size the control proposes after a converged step of size h.
    pub(super) fn proposal(&self, h: f64) -> f64 {
        match self.settings.control.criterion {
            Ias15Control::Prs23 => self.prs23_proposal(h),
            Ias15Control::Global => self.global_proposal(h),
        }
    }

    /// The number of blocks of the control (0 without coordinates).
    fn blocks(&self) -> usize {
        if self.n == 0 {
            0
        } else {
            self.n / self.settings.control.block
        }
    }

    /// Pham, Rein & Spiegel's criterion: with the acceleration a₁, jerk j and snap s at the end of the
    /// step (from a₀ and b), y₂ = |a₁|², y₃ = |j|², y₄ = |s|² per block,
    /// h_new = h √(min over blocks of 2y₂/(y₃ + √(y₄y₂))) (5040 ε)^{1/7}; h/[`SAFETY`] when no block
    /// gives a timescale.
    fn prs23_proposal(&self, h: f64) -> f64 {
        let d = self.settings.control.block;
        let mut min_t2 = f64::INFINITY;
        for blk in 0..self.blocks() {
            let (mut a0i, mut y2, mut y3, mut y4) = (0.0, 0.0, 0.0, 0.0);
            for k in blk * d..(blk + 1) * d {
                let b = &self.b[k];
                a0i += self.a0[k] * self.a0[k];
                let a1 = self.a0[k] + b[0] + b[1] + b[2] + b[3] + b[4] + b[5] + b[6];
                y2 += a1 * a1;
                let j = b[0] + 2.0 * b[1] + 3.0 * b[2] + 4.0 * b[3] + 5.0 * b[4] + 6.0 * b[5] + 7.0 * b[6];
                y3 += j * j;
                let s = 2.0 * b[1] + 6.0 * b[2] + 12.0 * b[3] + 20.0 * b[4] + 30.0 * b[5] + 42.0 * b[6];
                y4 += s * s;
            }
            if !a0i.is_normal() {
                // No acceleration (or a non-finite one): no timescale.
                continue;
            }
            let t2 = 2.0 * y2 / (y3 + (y4 * y2).sqrt());
            if t2.is_normal() && t2 < min_t2 {
                min_t2 = t2;
            }
        }
        if min_t2.is_normal() {
            min_t2.sqrt() * h * (5040.0 * self.settings.control.epsilon).powf(1.0 / 7.0)
        } else {
            h / SAFETY
        }
    }

    /// Rein & Spiegel's global criterion: h_new = h (ε max|a| / max|b₆|)^{1/7} over the coordinates
    /// of the blocks that move (v²h²/q² ≥ 1e-16); h/[`SAFETY`] when that ratio is not a normal number.
    fn global_proposal(&self, h: f64) -> f64 {
        let d = self.settings.control.block;
        let (mut max_a, mut max_b6) = (0.0_f64, 0.0_f64);
        for blk in 0..self.blocks() {
            let range = blk * d..(blk + 1) * d;
            let v2: f64 = self.v0[range.clone()].iter().map(|v| v * v).sum();
            let x2: f64 = self.x0[range.clone()].iter().map(|x| x * x).sum();
            // Skip slowly varying accelerations.
            if (v2 * h * h / x2).abs() < 1e-16 {
                continue;
            }
            for k in range {
                let (a, b6) = (self.at[k].abs(), self.b[k][6].abs());
                if a.is_normal() && a > max_a {
                    max_a = a;
                }
                if b6.is_normal() && b6 > max_b6 {
                    max_b6 = b6;
                }
            }
        }
        let error = max_b6 / max_a;
        if error.is_normal() {
            h * (self.settings.control.epsilon / error).powf(1.0 / 7.0)
        } else {
            h / SAFETY
        }
    }

    /// An initial step size at `state` by Hairer's rule ([`initial_step_size`], as the embedded pairs
    /// choose it) with order 15 and atol = rtol = ε, on y = (q, v), F = (v, f(t, q, v)): F₁ − F₀ at the
    /// explicit Euler step is (h₀ f₀, f(t + h₀, q₀ + h₀v₀, v₀ + h₀f₀) − f₀). f₀ is kept for the first
    /// step.
    pub(super) fn hinit(&mut self, state: &State<S::Partner>) -> Result<f64> {
        state.validate(self.n)?;
        let n = self.n;
        let (t, q, v) = (state.t, state.q.as_slice(), state.v.as_slice());
        self.have_cached = false;
        self.cached_t = t;
        self.cached_q.copy_from_slice(q);
        self.cached_v.copy_from_slice(v);
        let (system, scratch) = (&self.system, &mut self.scratch);
        start_accelerations_by(&mut self.evaluations, t, &mut self.cached_a, |out| {
            system.accelerations(t, q, v, scratch, out)
        })?;
        self.have_cached = true;
        let a = &self.cached_a;
        let y0: Vec<f64> = q.iter().chain(v).copied().collect();
        let f0: Vec<f64> = v.iter().chain(a).copied().collect();
        let eps = self.settings.control.epsilon;
        let evaluations = &mut self.evaluations;
        let (xs, vs, at) = (&mut self.xs, &mut self.vs, &mut self.at);
        initial_step_size(15, (eps, eps), &y0, &f0, |h0, d| {
            for k in 0..n {
                xs[k] = q[k] + h0 * v[k];
                vs[k] = v[k] + h0 * a[k];
            }
            *evaluations += 1;
            if !finite_stage(system.accelerations(t + h0, xs, vs, scratch, at), at)? {
                return Ok(false);
            }
            for k in 0..n {
                d[k] = h0 * a[k];
                d[n + k] = at[k] - a[k];
            }
            Ok(true)
        })
    }
}
