//! The usual pictures of a [`Solution`], one call each: coordinates against time, a phase portrait,
//! an observed quantity against time, and the relative drift of a conserved quantity on a log scale.

use crate::{Error, Figure, Result};
use noether_core::{Partner, Solution};

/// qⱼ(t) for each coordinate index in `coords`, one series each, named `q[j]`.
pub fn time_series<K: Partner>(sol: &Solution<K>, title: &str, coords: &[usize]) -> Result<Figure> {
    let mut fig = Figure::new(title).x_label("t").y_label("q");
    for &j in coords {
        check_coordinate(sol, title, j)?;
        let points = sol.times().iter().copied().zip(sol.q_series(j)).collect();
        fig = fig.series(format!("q[{j}]"), points);
    }
    Ok(fig)
}

/// The phase portrait of coordinate `j`: (qⱼ, vⱼ) for a velocity solution, (qⱼ, pⱼ) for a momentum one.
pub fn phase_portrait<K: Partner>(sol: &Solution<K>, title: &str, j: usize) -> Result<Figure> {
    check_coordinate(sol, title, j)?;
    let points = sol.q_series(j).into_iter().zip(sol.v_series(j)).collect();
    Ok(Figure::new(title)
        .x_label(format!("q[{j}]"))
        .y_label(format!("{}[{j}]", K::SYMBOL))
        .series(sol.method(), points))
}

/// The observed quantity `name` (see `Driver::observe`) against time.
pub fn observed<K: Partner>(sol: &Solution<K>, title: &str, name: &str) -> Result<Figure> {
    let values = observed_values(sol, title, name)?;
    let points = sol.times().iter().copied().zip(values).collect();
    Ok(Figure::new(title).x_label("t").y_label(name).series(name, points))
}

/// |x(t) − x(t₀)| / |x(t₀)| of the observed quantity `name` against time, on a log scale: how a
/// conserved quantity such as the energy drifts. Exact zeros (which a log scale cannot show) are left
/// out; when x(t₀) = 0 the drift is absolute, |x(t) − x(t₀)|.
pub fn relative_drift<K: Partner>(sol: &Solution<K>, title: &str, name: &str) -> Result<Figure> {
    let values = observed_values(sol, title, name)?;
    let x0 = values.first().copied().unwrap_or(0.0);
    let scale = if x0 == 0.0 { 1.0 } else { x0.abs() };
    let points = sol
        .times()
        .iter()
        .zip(&values)
        .map(|(&t, &x)| (t, (x - x0).abs() / scale))
        .filter(|&(_, d)| d > 0.0)
        .collect();
    Ok(Figure::new(title)
        .x_label("t")
        .y_label(format!("relative drift of {name}"))
        .log_y()
        .series(sol.method(), points))
}

fn check_coordinate<K: Partner>(sol: &Solution<K>, title: &str, j: usize) -> Result<()> {
    if j < sol.dof() {
        Ok(())
    } else {
        Err(Error::NoSuchSeries {
            what: format!(
                "coordinate {j} for '{title}' (the system has {} degrees of freedom)",
                sol.dof()
            ),
        })
    }
}

fn observed_values<K: Partner>(sol: &Solution<K>, title: &str, name: &str) -> Result<Vec<f64>> {
    // The core error lists the observers the run recorded.
    sol.observed(name).map_err(|e| Error::NoSuchSeries {
        what: format!("observed quantity '{name}' for '{title}' ({e})"),
    })
}
