//! The one root finder of noether: a bracketed scalar root by the Illinois method, used for events on
//! the continuous extension of a step ([`DenseOutput::locate`](crate::DenseOutput::locate), the
//! driver's [`Event`](crate::Event)s).
//!
//! Given g(a)·g(b) < 0, the Illinois method (modified regula falsi) takes the secant point
//! c = b − g(b)(b − a)/(g(b) − g(a)), keeps the sub-bracket with the sign change, and halves the
//! function value kept at the end that did not move, which restores superlinear convergence (order
//! ≈ 1.44) where plain regula falsi stalls. A bisection step is taken whenever the secant point would
//! not halve the bracket in two steps, so the bracket always closes: the iteration ends when g(c) = 0
//! or the bracket is a few ulps wide. Its size is counted in floats rather than in length, so a
//! bracket spanning many orders of magnitude (a root at 1e-150 in [0, 0.05]) closes as fast as any
//! other: at most about 130 evaluations for any bracket of finite numbers.
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
pub fn bracketed_root(g: impl FnMut(f64) -> f64, a: (f64, f64), b: (f64, f64)) -> Result<f64> {
    bracketed_root_within(g, a, b, 0.0)
}

/// [`bracketed_root`] that stops once the bracket is at most `width` wide (or at rounding, whichever
/// comes first): for a g that is costly and only as accurate as a solver's tolerance (a test function
/// along a family of orbits), where closing the bracket to the ulp would spend evaluations on noise.
/// A `width` that is not finite or negative counts as 0.
///
/// ```
/// use noether_core::roots::bracketed_root_within;
/// let g = |t: f64| t * t - 2.0;
/// let r = bracketed_root_within(g, (1.0, g(1.0)), (2.0, g(2.0)), 1e-6)?;
/// assert!((r - 2f64.sqrt()).abs() <= 1e-6);
/// # Ok::<(), noether_core::Error>(())
/// ```
pub fn bracketed_root_within(
    mut g: impl FnMut(f64) -> f64,
    (a, ga): (f64, f64),
    (b, gb): (f64, f64),
    width: f64,
) -> Result<f64> {
    let width = if width.is_finite() { width.max(0.0) } else { 0.0 };
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
    // The bracket's size is counted in floats (`floats_between`), not in length: a bracket such as
    // [0, 0.05] around a root at 1e-150 closes in at most 64 halvings of its count, where halving its
    // length needs ~500. Sizes one and two iterations ago.
    let (mut size1, mut size2) = (floats_between(lo, hi), floats_between(lo, hi));
    // Ends: every point tried lies strictly inside the bracket, so its size falls at each iteration,
    // and the safeguard below halves it at least every two iterations: at most ~130 iterations.
    loop {
        let tol = (4.0 * f64::EPSILON * lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE)).max(width);
        if (hi - lo).abs() <= tol || floats_between(lo, hi) <= 1 {
            break;
        }
        let secant = hi - ghi * (hi - lo) / (ghi - glo);
        let inside = secant.is_finite() && (secant - lo) * (secant - hi) < 0.0;
        let c = if inside { secant } else { float_midpoint(lo, hi) };
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
        // Safeguard: force a bisection (of the count of floats) when two steps did not halve it.
        if floats_between(lo, hi) > size2 / 2 {
            let m = float_midpoint(lo, hi);
            if m != lo && m != hi {
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
        }
        (size2, size1) = (size1, floats_between(lo, hi));
    }
    // The end nearer to zero in |g|.
    Ok(if glo.abs() < ghi.abs() { lo } else { hi })
}

/// The position of x among all f64 in increasing order (−0 just below +0): adjacent floats have
/// adjacent keys. The map is its own inverse on the bits.
fn order_key(x: f64) -> i64 {
    let i = x.to_bits() as i64;
    i ^ ((((i >> 63) as u64) >> 1) as i64)
}

/// How many steps from one float to the next separate x and y.
fn floats_between(x: f64, y: f64) -> u64 {
    order_key(x).abs_diff(order_key(y))
}

/// The float halfway between x and y in the order of floats: the arithmetic midpoint within a binade,
/// nearly the geometric mean across many, and 0 for ends of opposite signs of similar size.
fn float_midpoint(x: f64, y: f64) -> f64 {
    let (kx, ky) = (order_key(x) as i128, order_key(y) as i128);
    let k = (kx + (ky - kx) / 2) as i64;
    f64::from_bits((k ^ ((((k >> 63) as u64) >> 1) as i64)) as u64)
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
    fn a_width_stops_early() {
        // cos t on [0, 3]: to a width of 1e-6 the answer is within 1e-6 of π/2 (the root stays in the
        // bracket, the answer is one of its ends) in fewer evaluations than to rounding.
        let solve = |width: f64| {
            let mut calls = 0;
            let r = bracketed_root_within(
                |t| {
                    calls += 1;
                    t.cos()
                },
                (0.0, 1.0),
                (3.0, 3f64.cos()),
                width,
            )
            .unwrap();
            (r, calls)
        };
        let ((coarse, few), (fine, many)) = (solve(1e-6), solve(0.0));
        let root = std::f64::consts::FRAC_PI_2;
        assert!((coarse - root).abs() <= 1e-6, "{coarse}");
        assert!((fine - root).abs() <= 4.0 * f64::EPSILON * root, "{fine}");
        assert!(few < many, "{few} evaluations to 1e-6, {many} to rounding");
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

    #[test]
    fn regress_root_many_orders_of_magnitude_below_the_bracket() {
        // Issue 29 item 12: a turning point at 1.4e-150 in the bracket [0, 0.05]. Halving the length
        // needs ~500 steps, and the old cap of 400 returned the end nearer in |g| (not a root). The
        // count of floats halves instead: g = t − r has its root at r exactly, so the answer is r to
        // 4 ulps (the contract), in well under the 130 evaluations the safeguard allows.
        for r in [1.4e-150, 1e-300, 3e-10, 0.049] {
            let g = |t: f64| t - r;
            let mut calls = 0;
            let root = bracketed_root(
                |t| {
                    calls += 1;
                    g(t)
                },
                (0.0, g(0.0)),
                (0.05, g(0.05)),
            )
            .unwrap();
            assert!((root - r).abs() <= 4.0 * f64::EPSILON * r, "{root} vs {r}");
            assert!(calls <= 130, "{calls} evaluations for the root {r}");
        }
        // Opposite signs of very different sizes: [−1e300, 1e-300] around −1e-200.
        let g = |t: f64| t + 1e-200;
        let root = bracketed_root(g, (-1e300, g(-1e300)), (1e-300, g(1e-300))).unwrap();
        assert!((root + 1e-200).abs() <= 4.0 * f64::EPSILON * 1e-200, "{root}");
    }

    #[test]
    fn float_order_keys_are_monotone_and_midpoints_inside() {
        let xs = [
            -1e300, -2.0, -1.0, -1e-300, -0.0, 0.0, 5e-324, 1e-300, 1.0, 1.5, 2.0, 1e300,
        ];
        for w in xs.windows(2) {
            assert!(order_key(w[0]) < order_key(w[1]), "{} {}", w[0], w[1]);
            let m = float_midpoint(w[0], w[1]);
            assert!(w[0] <= m && m <= w[1], "{m} outside [{}, {}]", w[0], w[1]);
        }
        assert_eq!(float_midpoint(1.0, 2.0), 1.5);
        assert_eq!(floats_between(1.0, 1.0 + f64::EPSILON), 1);
    }
}
