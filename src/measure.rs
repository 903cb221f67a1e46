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
