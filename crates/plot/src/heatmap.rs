//! A heat map: values on a rectangular grid of cells drawn as coloured rectangles, with a colour bar.

use crate::{draw_error, Error, Result};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// A drawing area of the SVG file.
type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// The cell edges of centres c: the midpoints between neighbours, and outside the first and last
/// centre as far as the neighbouring midpoint is inside (±1/2 around a single centre).
fn cell_edges(c: &[f64]) -> Vec<f64> {
    let n = c.len();
    let half = |i: usize, j: usize| 0.5 * (c[i] + c[j]);
    let first = if n > 1 {
        c[0] - (half(0, 1) - c[0])
    } else {
        c[0] - 0.5
    };
    let last = if n > 1 {
        c[n - 1] + (c[n - 1] - half(n - 2, n - 1))
    } else {
        c[0] + 0.5
    };
    std::iter::once(first)
        .chain((1..n).map(|i| half(i - 1, i)))
        .chain(std::iter::once(last))
        .collect()
}

/// Values on a grid of cells (x outer, y inner: `values[i * ny + j]` at `(x[i], y[j])`, the order of a
/// two-axis `noether_ensemble::Grid`), drawn as a heat map with a colour bar (viridis; linear or
/// logarithmic). A NaN cell (no value: a pendulum that never flipped) is drawn white.
///
/// ```no_run
/// use noether_plot::Heatmap;
/// let (x, y) = (vec![0.0, 1.0, 2.0], vec![0.0, 1.0]);
/// let values = vec![1.0, 2.0, 3.0, f64::NAN, 5.0, 6.0];
/// Heatmap::new("values", x, y, values)?.x_label("x").y_label("y").save("map.svg")?;
/// # Ok::<(), noether_plot::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Heatmap {
    title: String,
    x_label: String,
    y_label: String,
    bar_label: String,
    x: Vec<f64>,
    y: Vec<f64>,
    values: Vec<f64>,
    log: bool,
    size: (u32, u32),
}

impl Heatmap {
    /// A heat map of `values` (`x.len() * y.len()` of them) at the cell centres `x` and `y` (each
    /// sorted increasing, at least one).
    pub fn new(title: impl Into<String>, x: Vec<f64>, y: Vec<f64>, values: Vec<f64>) -> Result<Self> {
        let title = title.into();
        let sorted =
            |v: &[f64]| !v.is_empty() && v.iter().all(|x| x.is_finite()) && v.windows(2).all(|w| w[0] < w[1]);
        if !sorted(&x) || !sorted(&y) || values.len() != x.len() * y.len() {
            return Err(Error::Shape {
                title,
                reason: "the cell centres must be finite and increasing, with x.len() × y.len() values",
            });
        }
        Ok(Heatmap {
            title,
            x_label: String::new(),
            y_label: String::new(),
            bar_label: String::new(),
            x,
            y,
            values,
            log: false,
            size: (820, 700),
        })
    }

    /// Label of the horizontal axis.
    pub fn x_label(mut self, label: impl Into<String>) -> Self {
        self.x_label = label.into();
        self
    }

    /// Label of the vertical axis.
    pub fn y_label(mut self, label: impl Into<String>) -> Self {
        self.y_label = label.into();
        self
    }

    /// Label of the colour bar (what the colour means).
    pub fn bar_label(mut self, label: impl Into<String>) -> Self {
        self.bar_label = label.into();
        self
    }

    /// Colours by log₁₀ of the value (values ≤ 0 are drawn white, as NaN).
    pub fn log_scale(mut self) -> Self {
        self.log = true;
        self
    }

    /// Picture size in pixels (default 820 × 700).
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    /// The value that sets a cell's colour (None: white).
    fn level(&self, v: f64) -> Option<f64> {
        match (self.log, v) {
            (_, v) if !v.is_finite() => None,
            (true, v) if v <= 0.0 => None,
            (true, v) => Some(v.log10()),
            (false, v) => Some(v),
        }
    }

    /// Writes the heat map as SVG to `path` (a `&str`, `String`, `Path` or `PathBuf`) and returns the
    /// path written. A folder that does not exist is [`Error::Write`] naming the path; no folder is
    /// created.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<PathBuf> {
        let path = path.as_ref();
        super::check_folder(path)?;
        let (lo, hi) = self.level_range()?;
        let root = SVGBackend::new(path, self.size).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let (main, bar) = root.split_horizontally(self.size.0.saturating_sub(130));
        self.draw_cells(&main, (lo, hi))?;
        self.draw_bar(&bar, (lo, hi))?;
        root.present().map_err(super::write_error(path))?;
        Ok(path.to_path_buf())
    }

    /// The range [lo, hi] of the cells' colour levels (hi = lo + 1 when they are all equal);
    /// [`Error::Empty`] when no cell has a level.
    fn level_range(&self) -> Result<(f64, f64)> {
        let levels: Vec<f64> = self.values.iter().filter_map(|&v| self.level(v)).collect();
        let lo = levels.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = levels.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !lo.is_finite() {
            return Err(Error::Empty {
                title: self.title.clone(),
            });
        }
        let hi = if hi > lo { hi } else { lo + 1.0 };
        Ok((lo, hi))
    }

    /// The map proper on `area`: title, axes, and each cell with a level as a rectangle between the
    /// edges of its neighbours' midpoints, coloured by viridis((level − lo)/(hi − lo)).
    fn draw_cells(&self, area: &Area<'_>, (lo, hi): (f64, f64)) -> Result<()> {
        let (xe, ye) = (cell_edges(&self.x), cell_edges(&self.y));
        let mut chart = ChartBuilder::on(area)
            .caption(&self.title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(xe[0]..xe[xe.len() - 1], ye[0]..ye[ye.len() - 1])
            .map_err(draw_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .draw()
            .map_err(draw_error)?;
        let ny = self.y.len();
        chart
            .draw_series(self.values.iter().enumerate().filter_map(|(k, &v)| {
                let (i, j) = (k / ny, k % ny);
                let level = self.level(v)?;
                let color = viridis((level - lo) / (hi - lo));
                Some(Rectangle::new(
                    [(xe[i], ye[j]), (xe[i + 1], ye[j + 1])],
                    color.filled(),
                ))
            }))
            .map_err(draw_error)?;
        Ok(())
    }

    /// The colour bar on `area`: 100 bands from lo to hi, labelled in the values (10^level for a
    /// logarithmic map).
    fn draw_bar(&self, area: &Area<'_>, (lo, hi): (f64, f64)) -> Result<()> {
        let mut scale = ChartBuilder::on(area)
            .margin_top(50)
            .margin_bottom(60)
            .margin_right(10)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..1.0, lo..hi)
            .map_err(draw_error)?;
        let log = self.log;
        let ticks = super::Ticks::new(lo, hi, false);
        scale
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(self.bar_label.as_str())
            .y_label_formatter(&|v| {
                if log {
                    super::significant(10f64.powf(*v), 2)
                } else {
                    ticks.label(*v)
                }
            })
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(draw_error)?;
        let steps = 100;
        scale
            .draw_series((0..steps).map(|k| {
                let (a, b) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
                Rectangle::new(
                    [(0.0, lo + a * (hi - lo)), (1.0, lo + b * (hi - lo))],
                    viridis(a).filled(),
                )
            }))
            .map_err(draw_error)?;
        Ok(())
    }
}

/// The viridis colour map at s ∈ [0, 1] (piecewise linear through 9 of its colours).
fn viridis(s: f64) -> RGBColor {
    const C: [(u8, u8, u8); 9] = [
        (68, 1, 84),
        (71, 44, 122),
        (59, 81, 139),
        (44, 113, 142),
        (33, 144, 141),
        (39, 173, 129),
        (92, 200, 99),
        (170, 220, 50),
        (253, 231, 37),
    ];
    let x = s.clamp(0.0, 1.0) * (C.len() - 1) as f64;
    let k = (x.floor() as usize).min(C.len() - 2);
    let f = x - k as f64;
    let mix = |a: u8, b: u8| (a as f64 + f * (b as f64 - a as f64)).round() as u8;
    RGBColor(
        mix(C[k].0, C[k + 1].0),
        mix(C[k].1, C[k + 1].1),
        mix(C[k].2, C[k + 1].2),
    )
}
