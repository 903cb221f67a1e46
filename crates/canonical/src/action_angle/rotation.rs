//! Rotations (see the [module](super) docs): the action J = (1/2π) ∮ p dq over a coordinate period
//! and the period T, by the midpoint rule on the energy level h(q, p) = E, nodes doubled until J and
//! T settle.

use super::{check_orbit, finite, fourier, positive, velocity, Curve, Extras, Pass, Rotation, Settings};
use crate::{Error, Result};
use noether_core::newton::{solve_dense, DenseProblem, Newton};
use std::f64::consts::PI;

/// h(q, p) = E solved for p by Newton from `guess`.
fn momentum_on_branch<C: Curve>(c: &C, q: f64, e: f64, guess: f64) -> Result<f64> {
    struct Level<'a, C> {
        c: &'a C,
        q: f64,
        e: f64,
    }
    impl<C: Curve> DenseProblem for Level<'_, C> {
        fn dim(&self) -> usize {
            1
        }
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
            r[0] = self.c.h(self.q, x[0]) - self.e;
            Ok(())
        }
        fn jacobian(&mut self, x: &[f64], j: &mut nalgebra::DMatrix<f64>) -> noether_core::Result<()> {
            j[(0, 0)] = velocity(self.c, self.q, x[0]);
            Ok(())
        }
    }
    let (x, _) = solve_dense(&Newton::default(), Level { c, q, e }, &[guess])?;
    // Polish as in `bottom`: one more Newton step from |H − E| ≤ 1e-12 to rounding.
    let hp = velocity(c, q, x[0]);
    let p = x[0] - (c.h(q, x[0]) - e) / hp;
    Ok(if p.is_finite() { p } else { x[0] })
}

/// One midpoint pass over a rotation: (J, signed T, time integrand in s).
fn rotation_pass<C: Curve>(
    c: &C,
    e: f64,
    q0: f64,
    period: f64,
    p_guess: f64,
    n: usize,
    extras: Extras,
) -> Result<Pass> {
    let mut g = vec![0.0; n];
    let mut extra = vec![(0.0, 0.0); extras.len()];
    let mut sum_p = 0.0;
    let mut p = momentum_on_branch(c, q0, e, p_guess)?;
    for (j, gj) in g.iter_mut().enumerate() {
        let q = q0 + (j as f64 + 0.5) * period / n as f64;
        p = momentum_on_branch(c, q, e, p)?;
        sum_p += p;
        for (x, f) in extra.iter_mut().zip(extras) {
            let v = f(q, p);
            *x = (x.0 + v, x.1 + v.abs());
        }
        *gj = 1.0 / velocity(c, q, p);
    }
    let dq = period / n as f64;
    Ok(Pass {
        action: sum_p * dq / (2.0 * PI),
        period: g.iter().sum::<f64>() * dq,
        upper: g,
        lower: Vec::new(),
        extras: extra.into_iter().map(|(a, b)| (a * dq, b * dq)).collect(),
    })
}

/// The rotation at energy `e` from `q0` over one coordinate period `period` (p on the branch of
/// `p_guess`), with the quadrature settings `s`.
pub(super) fn rotation<C: Curve>(
    c: &C,
    e: f64,
    q0: f64,
    period: f64,
    p_guess: f64,
    s: &Settings,
) -> Result<Rotation> {
    Ok(rotation_with(c, e, q0, period, p_guess, s, &[])?.0)
}

/// The rotation and the integrals ∮ f dq of the `extras`.
pub(crate) fn rotation_with<C: Curve>(
    c: &C,
    e: f64,
    q0: f64,
    period: f64,
    p_guess: f64,
    s: &Settings,
    extras: Extras,
) -> Result<(Rotation, Vec<f64>)> {
    finite("action-angle energy", e)?;
    finite("rotation q0", q0)?;
    positive("rotation coordinate period", period)?;
    let mut n = s.nodes;
    let mut last = rotation_pass(c, e, q0, period, p_guess, n, extras)?;
    loop {
        if 2 * n > s.max_nodes {
            return Err(Error::QuadratureNotConverged {
                what: "rotation action",
                nodes: n,
                previous: f64::NAN,
                estimate: last.action,
            });
        }
        n *= 2;
        let pass = rotation_pass(c, e, q0, period, p_guess, n, extras)?;
        let (j1, t1) = (pass.action, pass.period);
        let change = (j1 - last.action).abs();
        if pass.settled(&last, s.tolerance) {
            check_orbit(e, t1.abs(), j1)?;
            let (a, b) = fourier(&pass.upper);
            let rot = Rotation {
                energy: e,
                q0,
                coordinate_period: period,
                action: j1,
                period: t1.abs(),
                frequency: 2.0 * PI / t1,
                nodes: n,
                action_change: change,
                series: (a, b),
            };
            return Ok((rot, pass.extras.iter().map(|x| x.0).collect()));
        }
        last = pass;
    }
}
