//! Reading a result off a run: the mean period from a list of event times, and the envelope of an
//! oscillating error (what a plot of "bounded" against "drifting" should show).

/// The mean period (last − first) / (count − 1) of a list of crossing times; `None` with fewer than two.
pub fn mean_period(times: &[f64]) -> Option<f64> {
    match times {
        [first, .., last] => Some((last - first) / (times.len() - 1) as f64),
        _ => None,
    }
}

/// The largest |y| in each window of `window` consecutive samples, at the abscissa of the window's last
/// sample (a trailing partial window is dropped).
pub fn envelope(x: &[f64], y: &[f64], window: usize) -> Vec<(f64, f64)> {
    let window = window.max(1);
    x.chunks_exact(window)
        .zip(y.chunks_exact(window))
        .map(|(xs, ys)| (xs[window - 1], ys.iter().fold(0.0_f64, |m, v| m.max(v.abs()))))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_period_of_equally_spaced_times() {
        assert_eq!(mean_period(&[1.0, 3.0, 5.0, 7.0]), Some(2.0));
        assert_eq!(mean_period(&[1.0]), None);
    }

    #[test]
    fn envelope_takes_the_largest_magnitude_per_window() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let y = [1.0, -3.0, 2.0, 0.5, 9.0];
        assert_eq!(envelope(&x, &y, 2), vec![(1.0, 3.0), (3.0, 2.0)]);
    }
}
