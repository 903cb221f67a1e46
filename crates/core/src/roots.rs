//! The one root finder of noether: a bracketed scalar root by the Illinois method, used for events on
//! the continuous extension of a step ([`DenseOutput::locate`](crate::DenseOutput::locate), the
//! driver's [`Event`](crate::Event)s).
//!
//! Given g(a)·g(b) < 0, the Illinois method (modified regula falsi) takes the secant point
//! c = b − g(b)(b − a)/(g(b) − g(a)), keeps the sub-bracket with the sign change, and halves the
//! function value kept at the end that did not move, which restores superlinear convergence (order
//! ≈ 1.44) where plain regula falsi stalls. A bisection step is taken whenever the secant point would
//! not shrink the bracket by half in two steps, so the bracket always closes: the iteration ends when
//! g(c) = 0 or the bracket is a few ulps wide, at most a few hundred evaluations for any bracket of
//! finite numbers.
//!
//! # References
//! - M. Dowell, P. Jarratt, A modified regula falsi method for computing the root of an equation,
//!   BIT 11 (1971) 168–174.

use crate::{Error, Result};

/// The root of `g` in the bracket [a, b] where `ga = g(a)` and `gb = g(b)` have opposite signs (or one
/// is zero), to the resolution of f64 near the root: the returned t satisfies g(t) = 0 or lies within
/// 4 ulps of a sign change. A g that is not finite at an end or at any point tried is an
/// [`Error::NonFiniteResult`] at that point: a NaN inside the bracket may hide the crossing, so no
/// root is guessed around it.
///
/// ```
/// use noether_core::roots::bracketed_root;
/// let g = |t: f64| t * t - 2.0;
/// let r = bracketed_root(g, (1.0, g(1.0)), (2.0, g(2.0)))?;
/// assert!((r - 2f64.sqrt()).abs() <= 4.0 * f64::EPSILON);
/// # Ok::<(), noether_core::Error>(())
/// ```
pub fn bracketed_root(
    mut g: impl FnMut(f64) -> f64,
    (a, ga): (f64, f64),
    (b, gb): (f64, f64),
) -> Result<f64> {
    for (t, gt) in [(a, ga), (b, gb)] {
        finite_at(t, gt)?;
    }
    if ga == 0.0 {
        return Ok(a);
    }
    if gb == 0.0 {
        return Ok(b);
    }
    let mut g = |t: f64| finite_at(t, g(t));
    // Bracket [lo, hi] with g(lo) of the sign of ga; `side` remembers which end moved last.
    let (mut lo, mut glo, mut hi, mut ghi) = (a, ga, b, gb);
    let mut side = 0i8;
    // Bracket widths one and two iterations ago.
    let (mut width1, mut width2) = ((hi - lo).abs(), (hi - lo).abs());
    for _ in 0..400 {
        let tol = 4.0 * f64::EPSILON * lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE);
        if (hi - lo).abs() <= tol {
            break;
        }
        let secant = hi - ghi * (hi - lo) / (ghi - glo);
        let inside = secant.is_finite() && (secant - lo) * (secant - hi) < 0.0;
        let c = if inside { secant } else { 0.5 * (lo + hi) };
        let gc = g(c)?;
        if gc == 0.0 {
            return Ok(c);
        }
        if gc.signum() == glo.signum() {
            lo = c;
            glo = gc;
            if side == -1 {
                ghi *= 0.5; // Illinois: the other end stayed twice in a row
            }
            side = -1;
        } else {
            hi = c;
            ghi = gc;
            if side == 1 {
                glo *= 0.5;
            }
            side = 1;
        }
        // Safeguard: force a bisection when two steps did not halve the bracket.
        if (hi - lo).abs() > 0.5 * width2 {
            let m = 0.5 * (lo + hi);
            let gm = g(m)?;
            if gm == 0.0 {
                return Ok(m);
            }
            if gm.signum() == glo.signum() {
                (lo, glo) = (m, gm);
            } else {
                (hi, ghi) = (m, gm);
            }
            side = 0;
        }
        (width2, width1) = (width1, (hi - lo).abs());
    }
    // The end nearer to zero in |g|.
    Ok(if glo.abs() < ghi.abs() { lo } else { hi })
}

/// `g` when finite, else the error naming where it was not.
fn finite_at(t: f64, g: f64) -> Result<f64> {
    if g.is_finite() {
        Ok(g)
    } else {
        Err(Error::NonFiniteResult {
            what: "function inside the bracket of a root",
            t,
            component: None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_form_roots_to_rounding() {
        // cos t = 0 at π/2; t³ = 1e-3 at 0.1 (a flat root of a steep function); e^t = 1e6 at ln 1e6.
        /// g, the bracket [a, b], the root.
        type Case = (fn(f64) -> f64, f64, f64, f64);
        let cases: [Case; 3] = [
            (f64::cos, 0.0, 3.0, std::f64::consts::FRAC_PI_2),
            (|t| t * t * t - 1e-3, 0.0, 1.0, 0.1),
            (|t| t.exp() - 1e6, 0.0, 20.0, 1e6f64.ln()),
        ];
        for (g, a, b, root) in cases {
            let mut calls = 0;
            let r = bracketed_root(
                |t| {
                    calls += 1;
                    g(t)
                },
                (a, g(a)),
                (b, g(b)),
            )
            .unwrap();
            // Rounding: within 4 ulps of the root (g's own rounding near it is of the same order).
            assert!(
                (r - root).abs() <= 4.0 * f64::EPSILON * root,
                "root {r} vs {root}"
            );
            assert!(calls < 100, "{calls} evaluations");
        }
    }

    #[test]
    fn regress_root_at_large_times() {
        // An event at t = 1e15 + 0.3 (ulp(1e15) = 0.125): the answer is the nearest representable time.
        let t0 = 1e15;
        let g = |t: f64| (t - t0) - 0.3;
        let r = bracketed_root(g, (t0, g(t0)), (t0 + 1.0, g(t0 + 1.0))).unwrap();
        assert!((r - (t0 + 0.3)).abs() <= 0.125, "{r}");
    }

    #[test]
    fn regress_nan_inside_the_bracket_is_an_error() {
        // Issue 29 item 4: g = t³ − 0.343 on [0, 1] made NaN on [0.3, 0.36), where the first secant
        // point falls. The root finder used to step around it and answer; a NaN may hide the crossing
        // (here it does not, but nothing can tell), so it is reported with where it was met.
        let g = |t: f64| {
            if (0.3..0.36).contains(&t) {
                f64::NAN
            } else {
                t * t * t - 0.343
            }
        };
        let err = bracketed_root(g, (0.0, g(0.0)), (1.0, g(1.0))).unwrap_err();
        assert!(
            matches!(err, Error::NonFiniteResult { t, .. } if (0.3..0.36).contains(&t)),
            "{err}"
        );
        // A NaN at an end as well.
        assert!(bracketed_root(g, (0.0, f64::NAN), (1.0, g(1.0))).is_err());
    }
}
