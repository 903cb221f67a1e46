//! # noether-plot
//!
//! Pictures of noether runs, written as SVG by `plotters`: a [`Figure`] of named line series with a
//! legend and axis labels whose ticks tell neighbouring values apart, and the usual pictures of a
//! [`Solution`](noether_core::Solution) in one call ([`time_series`], [`phase_portrait`],
//! [`observed`], [`relative_drift`]), and a [`Heatmap`] of values on a grid (an ensemble's scan).
//!
//! ```no_run
//! use noether_plot::Figure;
//!
//! let circle: Vec<(f64, f64)> = (0..=100)
//!     .map(|i| (i as f64 * 0.0628).cos())
//!     .zip((0..=100).map(|i| (i as f64 * 0.0628).sin()))
//!     .collect();
//! Figure::new("A circle")
//!     .x_label("x")
//!     .y_label("y")
//!     .equal_aspect()
//!     .series("unit circle", circle)
//!     .save("circle.svg")
//!     .unwrap();
//! ```

mod heatmap;
mod solution;

pub use heatmap::Heatmap;

pub use solution::{observed, phase_portrait, relative_drift, time_series};

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// What can go wrong when drawing.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The figure has no finite point to draw.
    #[error("figure '{title}' has no point to draw")]
    Empty {
        /// Title of the figure.
        title: String,
    },
    /// A series asked of a solution does not exist (a component index or an observer name).
    #[error("no {what} in the solution")]
    NoSuchSeries {
        /// What was asked for.
        what: String,
    },
    /// A heat map's grid does not fit its values (centres not sorted or not finite, or not
    /// x.len() × y.len() values).
    #[error("heat map '{title}': {reason}")]
    Shape {
        /// Title of the figure.
        title: String,
        /// What does not fit.
        reason: &'static str,
    },
    /// The drawing backend failed (a font).
    #[error("drawing failed: {0}")]
    Draw(String),
    /// The picture could not be written to `path` (its folder does not exist, no permission).
    #[error("cannot write the picture to {}: {reason}", path.display())]
    Write {
        /// The path asked for.
        path: PathBuf,
        /// Why.
        reason: String,
    },
}

/// Result alias of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

fn draw_error<E: std::fmt::Display>(e: E) -> Error {
    Error::Draw(e.to_string())
}

/// Checks, before anything is drawn, that the folder `path` is to be written into exists
/// ([`Error::Write`] naming both otherwise).
fn check_folder(path: &Path) -> Result<()> {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => Err(Error::Write {
            path: path.to_path_buf(),
            reason: format!("the folder {} does not exist", dir.display()),
        }),
        _ => Ok(()),
    }
}

/// The error of writing the finished picture to `path` (the backend's message kept).
fn write_error<E: std::fmt::Display>(path: &Path) -> impl FnOnce(E) -> Error + '_ {
    move |e| Error::Write {
        path: path.to_path_buf(),
        reason: e.to_string(),
    }
}

/// Series longer than this are thinned (every k-th point kept) before drawing, so the SVG stays small.
pub const MAX_POINTS: usize = 4000;

/// One named curve.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry.
    pub name: String,
    /// The points (x, y), drawn joined in order (or as dots when `dots`).
    pub points: Vec<(f64, f64)>,
    /// Drawn as unjoined dots (a scatter: a Poincaré section) instead of a line.
    pub dots: bool,
}

/// A line plot of several series.
#[derive(Debug, Clone)]
pub struct Figure {
    title: String,
    x_label: String,
    y_label: String,
    series: Vec<Series>,
    equal_aspect: bool,
    log_y: bool,
    size: (u32, u32),
}

impl Figure {
    /// An empty figure with a title.
    pub fn new(title: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            x_label: String::new(),
            y_label: String::new(),
            series: Vec::new(),
            equal_aspect: false,
            log_y: false,
            size: (800, 600),
        }
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

    /// Adds a series (thinned to at most [`MAX_POINTS`] points; non-finite points are dropped). An empty
    /// name leaves it out of the legend.
    pub fn series(mut self, name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        let points: Vec<_> = points
            .into_iter()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        self.series.push(Series {
            name: name.into(),
            points: thin(points, MAX_POINTS),
            dots: false,
        });
        self
    }

    /// Adds a series drawn as unjoined dots (a scatter), otherwise as [`series`](Self::series).
    pub fn dots(mut self, name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        self = self.series(name, points);
        if let Some(s) = self.series.last_mut() {
            s.dots = true;
        }
        self
    }

    /// Same scale on both axes (orbits, trajectories in the plane).
    pub fn equal_aspect(mut self) -> Self {
        self.equal_aspect = true;
        self
    }

    /// Logarithmic vertical axis (errors spanning decades); points with y ≤ 0 are dropped.
    pub fn log_y(mut self) -> Self {
        self.log_y = true;
        self
    }

    /// Size in pixels (default 800 × 600).
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    /// Writes the figure as SVG to `path` (a `&str`, `String`, `Path` or `PathBuf`) and returns the
    /// path written. A folder that does not exist is [`Error::Write`] naming the path; no folder is
    /// created.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<PathBuf> {
        let path = path.as_ref();
        check_folder(path)?;
        let (mut x0, mut x1, mut y0, mut y1) = self.bounds()?;
        let named = self.series.iter().any(|s| !s.name.is_empty());
        let (mut legend, covered) = self.legend_corner((x0, x1, y0, y1));
        if named && covered > 0 {
            // Every corner has curves in it: add headroom so the data fill the lower 72%.
            if self.log_y {
                y1 = y0 * (y1 / y0).powf(1.0 / 0.72);
            } else {
                y1 = y0 + (y1 - y0) / 0.72;
            }
            legend = SeriesLabelPosition::UpperRight;
        }
        if self.equal_aspect {
            // Widen the shorter side so one unit has the same length on both axes (plot area ≈ size − margins).
            let (w, h) = (self.size.0 as f64 - 110.0, self.size.1 as f64 - 110.0);
            let scale = ((x1 - x0) / w).max((y1 - y0) / h);
            let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
            (x0, x1) = (cx - 0.5 * scale * w, cx + 0.5 * scale * w);
            (y0, y1) = (cy - 0.5 * scale * h, cy + 0.5 * scale * h);
        }
        let root = SVGBackend::new(path, self.size).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let ticks = (Ticks::new(x0, x1, false), Ticks::new(y0, y1, self.log_y));
        if self.log_y {
            self.draw(&root, x0..x1, (y0..y1).log_scale(), legend, ticks)?;
        } else {
            self.draw(&root, x0..x1, y0..y1, legend, ticks)?;
        }
        root.present().map_err(write_error(path))?;
        Ok(path.to_path_buf())
    }

    fn visible(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        let log = self.log_y;
        self.series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .filter(move |&(_, y)| !log || y > 0.0)
    }

    fn bounds(&self) -> Result<(f64, f64, f64, f64)> {
        let mut b = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for (x, y) in self.visible() {
            b = (b.0.min(x), b.1.max(x), b.2.min(y), b.3.max(y));
        }
        if !b.0.is_finite() {
            return Err(Error::Empty {
                title: self.title.clone(),
            });
        }
        let pad = |lo: f64, hi: f64, log: bool| {
            if log {
                let (lo, hi) = if hi > lo { (lo, hi) } else { (lo / 10.0, hi * 10.0) };
                (lo / 1.5, hi * 1.5)
            } else {
                let d = if hi > lo {
                    0.05 * (hi - lo)
                } else {
                    0.5 * lo.abs().max(1.0)
                };
                (lo - d, hi + d)
            }
        };
        let (x0, x1) = pad(b.0, b.1, false);
        let (y0, y1) = pad(b.2, b.3, self.log_y);
        Ok((x0, x1, y0, y1))
    }

    /// The corner of the plot area whose legend-sized box covers the fewest curve points (and how many).
    fn legend_corner(&self, (x0, x1, y0, y1): (f64, f64, f64, f64)) -> (SeriesLabelPosition, usize) {
        let ny = |y: f64| {
            if self.log_y {
                (y.ln() - y0.ln()) / (y1.ln() - y0.ln())
            } else {
                (y - y0) / (y1 - y0)
            }
        };
        let corners = [
            (SeriesLabelPosition::UpperRight, true, true),
            (SeriesLabelPosition::UpperLeft, false, true),
            (SeriesLabelPosition::LowerRight, true, false),
            (SeriesLabelPosition::LowerLeft, false, false),
        ];
        // Legend size estimated from its text (14 px font, ~7.5 px per character, 20 px per entry).
        let named: Vec<_> = self.series.iter().filter(|s| !s.name.is_empty()).collect();
        let chars = named.iter().map(|s| s.name.chars().count()).max().unwrap_or(0);
        let (w, h) = (self.size.0 as f64 - 110.0, self.size.1 as f64 - 110.0);
        let bw = ((chars as f64 * 7.5 + 60.0) / w).min(1.0);
        let bh = ((named.len() as f64 * 20.0 + 25.0) / h).min(1.0);
        let count = |right: bool, upper: bool| {
            self.visible()
                .filter(|&(x, y)| {
                    let (u, v) = ((x - x0) / (x1 - x0), ny(y));
                    (if right { u > 1.0 - bw } else { u < bw }) && (if upper { v > 1.0 - bh } else { v < bh })
                })
                .count()
        };
        let mut best = (SeriesLabelPosition::UpperRight, usize::MAX);
        for (pos, right, upper) in corners {
            let c = count(right, upper);
            if c < best.1 {
                best = (pos, c);
            }
        }
        best
    }

    fn draw<Y>(
        &self,
        root: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
        xr: std::ops::Range<f64>,
        yr: Y,
        legend: SeriesLabelPosition,
        (xt, yt): (Ticks, Ticks),
    ) -> Result<()>
    where
        Y: AsRangedCoord<Value = f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 24))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(xr, yr)
            .map_err(draw_error)?;
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .x_label_formatter(&|v| xt.label(*v))
            .y_label_formatter(&|v| yt.label(*v))
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(draw_error)?;
        for (i, s) in self.series.iter().enumerate() {
            let color = color(i);
            let log = self.log_y;
            let pts = s.points.iter().copied().filter(move |&(_, y)| !log || y > 0.0);
            let drawn = if s.dots {
                chart
                    .draw_series(pts.map(|p| Circle::new(p, 1, color.filled())))
                    .map_err(draw_error)?
            } else {
                chart
                    .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                    .map_err(draw_error)?
            };
            if !s.name.is_empty() {
                // The swatch looks like the series: a dot for dots, a line for a line.
                let dots = s.dots;
                drawn.label(s.name.as_str()).legend(move |(x, y)| {
                    if dots {
                        Circle::new((x + 10, y), 4, color.filled()).into_dyn()
                    } else {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(3)).into_dyn()
                    }
                });
            }
        }
        if self.series.iter().any(|s| !s.name.is_empty()) {
            chart
                .configure_series_labels()
                .position(legend)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.4))
                .label_font(("sans-serif", 14))
                .draw()
                .map_err(draw_error)?;
        }
        Ok(())
    }
}

/// A color-blind-friendly palette (Okabe-Ito), cycled.
fn color(i: usize) -> RGBColor {
    const P: [RGBColor; 7] = [
        RGBColor(0, 114, 178),
        RGBColor(213, 94, 0),
        RGBColor(0, 158, 115),
        RGBColor(204, 121, 167),
        RGBColor(230, 159, 0),
        RGBColor(86, 180, 233),
        RGBColor(0, 0, 0),
    ];
    P[i % P.len()]
}

/// Tick labels for an axis over [lo, hi]: as many digits as the tick spacing needs, so that
/// neighbouring ticks read differently (an axis from 0.0220 to 0.0224 is labelled 0.02200, 0.02205, …,
/// not 0.022 five times), plain for magnitudes in [10⁻³, 10⁴) and scientific otherwise; a tick within
/// 10⁻⁶ spacings of zero reads 0 (not −1e-16).
#[derive(Debug, Clone, Copy)]
struct Ticks {
    /// Spacing of about ten ticks across the axis.
    step: f64,
    /// Largest magnitude on the axis.
    magnitude: f64,
    log: bool,
}

impl Ticks {
    fn new(lo: f64, hi: f64, log: bool) -> Self {
        Ticks {
            step: ((hi - lo).abs() / 10.0).max(f64::MIN_POSITIVE),
            magnitude: lo.abs().max(hi.abs()),
            log,
        }
    }

    fn label(&self, v: f64) -> String {
        if self.log {
            // Decades: one significant digit is what tells them apart.
            return format!("{v:.0e}");
        }
        if v.abs() < 1e-6 * self.step {
            return "0".into();
        }
        let label = if !(1e-3..1e4).contains(&self.magnitude) {
            // Mantissa digits to resolve the spacing relative to the largest value on the axis.
            let digits = (self.magnitude / self.step).log10().ceil().clamp(0.0, 15.0) as usize;
            format!("{v:.digits$e}")
        } else {
            let decimals = (-self.step.log10().floor()).clamp(0.0, 15.0) as usize;
            format!("{v:.decimals$}")
        };
        trim_zeros(&label)
    }
}

/// `x` to `digits` significant digits, plain for magnitudes in [10⁻³, 10⁴) and scientific otherwise,
/// without trailing zeros: the label of a colour-bar tick on a log scale (0.0032, 0.01, 1.5e-6).
fn significant(x: f64, digits: usize) -> String {
    let digits = digits.max(1);
    let label = if x == 0.0 || !x.is_finite() {
        format!("{x}")
    } else if (1e-3..1e4).contains(&x.abs()) {
        let decimals = (digits as i32 - 1 - x.abs().log10().floor() as i32).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.prec$e}", prec = digits - 1)
    };
    trim_zeros(&label)
}

/// Drops trailing zeros of the fractional part ("0.02500" → "0.025", "1.50e-3" → "1.5e-3").
fn trim_zeros(s: &str) -> String {
    let (mantissa, exponent) = match s.find('e') {
        Some(i) => s.split_at(i),
        None => (s, ""),
    };
    let mantissa = if mantissa.contains('.') {
        mantissa.trim_end_matches('0').trim_end_matches('.')
    } else {
        mantissa
    };
    format!("{mantissa}{exponent}")
}

/// Keeps every k-th point (and the last) so that at most about `max` remain.
pub fn thin(points: Vec<(f64, f64)>, max: usize) -> Vec<(f64, f64)> {
    if points.len() <= max || max < 2 {
        return points;
    }
    let k = points.len().div_ceil(max);
    let last = *points.last().expect("non-empty");
    let mut out: Vec<_> = points.into_iter().step_by(k).collect();
    if out.last() != Some(&last) {
        out.push(last);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thin_keeps_ends_and_bounds_length() {
        let pts: Vec<_> = (0..10_001).map(|i| (i as f64, 0.0)).collect();
        let t = thin(pts, 1000);
        assert!(t.len() <= 1001);
        assert_eq!(t[0].0, 0.0);
        assert_eq!(t.last().unwrap().0, 10_000.0);
    }

    #[test]
    fn colour_bar_labels_are_short_and_plain_where_they_can_be() {
        // Issue 30 item 15: the log colour bar read 1.00e-3, 3.16e-3, … on every tick.
        assert_eq!(significant(1e-3, 2), "0.001");
        assert_eq!(significant(10f64.powf(-2.5), 2), "0.0032");
        assert_eq!(significant(0.1, 2), "0.1");
        assert_eq!(significant(31.6227766, 2), "32");
        assert_eq!(significant(1.5e-6, 2), "1.5e-6");
        assert_eq!(significant(2.0e7, 2), "2e7");
        assert_eq!(significant(0.0, 2), "0");
    }

    #[test]
    fn ticks_tell_neighbours_apart() {
        // The coupled-chains heat plot: an axis from 0.0220 to 0.0224 (ticks every 4e-5).
        let t = Ticks::new(0.0220, 0.0224, false);
        let labels: Vec<String> = (0..=10).map(|i| t.label(0.0220 + 4e-5 * i as f64)).collect();
        let mut unique = labels.clone();
        unique.dedup();
        assert_eq!(unique.len(), labels.len(), "{labels:?}");
        // The heavy-top apex plot: zero computed as -1e-16 reads 0.
        assert_eq!(Ticks::new(-1.0, 1.0, false).label(-1e-16), "0");
        // Large and small magnitudes in scientific form, still distinct.
        let big = Ticks::new(1.0e6, 1.001e6, false);
        assert_ne!(big.label(1.0e6), big.label(1.0001e6));
        assert_eq!(Ticks::new(0.0, 1.0, false).label(0.5), "0.5");
    }

    #[test]
    fn bad_input_empty_figure_is_an_error() {
        let dir = std::env::temp_dir().join("noether-plot-test-empty.svg");
        assert!(Figure::new("empty").save(&dir).is_err());
        let nan = Figure::new("nan").series("s", vec![(f64::NAN, 1.0)]);
        assert!(nan.save(&dir).is_err());
    }

    #[test]
    fn bad_input_save_into_a_missing_folder_names_the_path() {
        // Issue 30 item 12: the error said "drawing failed" with no path. Both pictures refuse before
        // drawing, naming the file and the missing folder; a &str, a String and a PathBuf are accepted
        // (impl AsRef<Path>), and a folder that exists is written into.
        let missing = std::env::temp_dir()
            .join("noether-plot-no-such-folder")
            .join("fig.svg");
        let fig = Figure::new("line").series("s", vec![(0.0, 0.0), (1.0, 1.0)]);
        let err = fig.save(&missing).unwrap_err();
        assert!(
            matches!(&err, Error::Write { path, .. } if path == &missing),
            "{err}"
        );
        let msg = err.to_string();
        assert!(
            msg.contains(&missing.display().to_string()) && msg.contains("does not exist"),
            "{msg}"
        );
        let map = Heatmap::new("map", vec![0.0, 1.0], vec![0.0, 1.0], vec![0.0, 1.0, 2.0, 3.0]).unwrap();
        let as_str = missing.to_str().unwrap();
        assert!(matches!(map.save(as_str), Err(Error::Write { .. })));
        let ok = std::env::temp_dir().join(format!("noether-plot-test-{}.svg", std::process::id()));
        assert_eq!(fig.save(ok.clone()).unwrap(), ok);
        // An owned String is a path too (`impl AsRef<Path>`).
        let owned: String = ok.to_str().unwrap().into();
        assert_eq!(map.save(owned).unwrap(), ok);
        std::fs::remove_file(&ok).unwrap();
    }
}
