//! `map.svg`: the ratio over a 1-D grid, or a colour map of log10 ratio over a 2-D grid
//! with the stiction boundary as a contour; over a categorical and a numeric axis one
//! curve per word. Drawn in plotted coordinates (log10 of the value on a log axis, the
//! code 0, 1, ... of a word on a categorical axis) with our own tick marks, so every axis
//! type is one chart type.

use super::{FREE, NO_CLOSE, REFERENCE, SERIES, STICK};
use crate::ReportError;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::ops::Range;
use stiction_model::design_sweep::{contour_plotted, Axis, Labels, Map, MapPoint, Spacing, Status};

const FONT: &str = "sans-serif";
/// Stroke width of the ratio = 1 contour (tests look for it).
pub const CONTOUR_WIDTH: u32 = 3;

fn plot_err(e: impl std::fmt::Display) -> ReportError {
    ReportError::Plot {
        path: "map.svg".into(),
        message: e.to_string(),
    }
}

/// `map.svg` as a string. 1-D: the ratio against the field with the line ratio = 1 (log x
/// for a log grid, log ratio when the ratios and 1 span a decade or more; points that do
/// not close or fail are drawn as markers at the axis floor). 2-D: a colour map of log10
/// ratio with a colour bar, the contour ratio = 1, grey cells that do not close and
/// crossed cells that failed. Titles and axis labels come from `labels`.
///
/// A categorical axis is drawn as its words, one tick each: 1-D, the ratio of each word
/// (no line joins them); 2-D over a categorical and a numeric axis, one curve of the ratio
/// against the numeric field per word, each in its own colour of the palette
/// ([`super::SERIES`]; filled markers stick, open ones are free); 2-D over two categorical
/// axes, the colour map without a contour.
pub fn map_svg(map: &Map, labels: &Labels) -> Result<String, ReportError> {
    let mut buf = String::new();
    let g = map.grid();
    match g.dim() {
        1 => draw_1d(map, labels, &mut buf)?,
        _ if g.axes()[0].is_categorical() != g.axes()[1].is_categorical() => {
            draw_by_word(map, labels, &mut buf)?
        }
        _ => draw_2d(map, labels, &mut buf)?,
    }
    Ok(super::portable(&buf))
}

/// A plotted axis: range, tick marks and how to label them.
struct Scale {
    lo: f64,
    hi: f64,
    log: bool,
    bold: Vec<f64>,
    light: Vec<f64>,
    digits: usize,
    /// The words of a categorical axis: tick `k` is labelled `words[k]`.
    words: Vec<String>,
}

impl Scale {
    /// An axis over plotted values `lo..hi` (log10 of the value when `log`).
    fn new(lo: f64, hi: f64, log: bool) -> Scale {
        let (bold, light, digits) = if log {
            log_ticks(lo, hi)
        } else {
            let (t, step) = lin_ticks(lo, hi, 8);
            let digits = digits_for(&t, step);
            (t, Vec::new(), digits)
        };
        Scale {
            lo,
            hi,
            log,
            bold,
            light,
            digits,
            words: Vec::new(),
        }
    }

    /// The axis of a categorical axis's words: one tick per word at its code, half a code
    /// of margin on either side.
    fn of_words(axis: &Axis) -> Scale {
        Scale {
            lo: -0.5,
            hi: axis.n as f64 - 0.5,
            log: false,
            bold: axis.values.clone(),
            light: Vec::new(),
            digits: 1,
            words: axis.words.clone(),
        }
    }

    /// The axis of a grid's values, padded by half a cell (a categorical axis: its words).
    fn of_axis(axis: &Axis, pad_fraction: f64) -> Scale {
        if axis.is_categorical() {
            return Scale::of_words(axis);
        }
        let ts: Vec<f64> = axis.values.iter().map(|&v| axis.plotted(v)).collect();
        let (lo, hi) = min_max(&ts);
        let (lo, hi) = if hi > lo {
            let pad = pad_fraction * (hi - lo);
            (lo - pad, hi + pad)
        } else {
            let half = match axis.spacing {
                Spacing::Log => 0.5,
                Spacing::Lin if lo != 0.0 => 0.1 * lo.abs(),
                Spacing::Lin => 1.0,
            };
            (lo - half, hi + half)
        };
        Scale::new(lo, hi, axis.spacing == Spacing::Log)
    }

    fn coord(&self) -> Ticked {
        Ticked {
            lo: self.lo,
            hi: self.hi,
            bold: self.bold.clone(),
            light: self.light.clone(),
        }
    }

    fn label(&self, t: f64) -> String {
        if !self.words.is_empty() {
            let k = t.round();
            return if k >= 0.0 && (k as usize) < self.words.len() {
                self.words[k as usize].clone()
            } else {
                String::new()
            };
        }
        if self.log {
            fmt_sig(10f64.powf(t), self.digits)
        } else {
            fmt_sig(t, self.digits)
        }
    }
}

/// A linear plotters axis with our own bold and light tick marks.
struct Ticked {
    lo: f64,
    hi: f64,
    bold: Vec<f64>,
    light: Vec<f64>,
}

impl Ranged for Ticked {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let f = (v - self.lo) / (self.hi - self.lo);
        let px = f64::from(limit.1 - limit.0) * f;
        limit.0 + (px + 1e-3).floor().clamp(-1e6, 1e6) as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.light.clone()
        } else {
            self.bold.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

fn min_max(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        })
}

/// Evenly spaced ticks with a 1-2-5 step, at most about `max_n`.
fn lin_ticks(lo: f64, hi: f64, max_n: usize) -> (Vec<f64>, f64) {
    let raw = (hi - lo) / max_n as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    // a tick on an end survives rounding (1.2 / 0.2 = 5.999...)
    let (k0, k1) = (
        (lo / step - 1e-9).ceil() as i64,
        (hi / step + 1e-9).floor() as i64,
    );
    ((k0..=k1).map(|k| k as f64 * step).collect(), step)
}

/// Significant digits that tell ticks `step` apart.
fn digits_for(ticks: &[f64], step: f64) -> usize {
    let big = ticks.iter().fold(0f64, |m, t| m.max(t.abs()));
    if big == 0.0 || step <= 0.0 {
        return 1;
    }
    ((big.log10().floor() - step.log10().floor()) as i64 + 1).clamp(1, 10) as usize
}

/// Ticks of a log axis over log10 values `lo..hi`: decades (with 2..9 light lines) when
/// two or more lie inside, else 1-2-5 mantissas, else linear ticks of the values.
fn log_ticks(lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>, usize) {
    let (k0, k1) = (lo.ceil() as i64, hi.floor() as i64);
    if k1 > k0 {
        let count = (k1 - k0 + 1) as usize;
        let step = count.div_ceil(8);
        let bold = (k0..=k1).step_by(step).map(|k| k as f64).collect();
        let light = if step == 1 {
            (lo.floor() as i64..=k1)
                .flat_map(|k| (2..=9).map(move |m| k as f64 + f64::from(m).log10()))
                .filter(|t| (lo..=hi).contains(t))
                .collect()
        } else {
            Vec::new()
        };
        return (bold, light, 1);
    }
    let mantissas: Vec<f64> = (lo.floor() as i64..=hi.ceil() as i64)
        .flat_map(|k| [1.0f64, 2.0, 5.0].map(|m| k as f64 + m.log10()))
        .filter(|t| (lo..=hi).contains(t))
        .collect();
    if mantissas.len() >= 3 {
        return (mantissas, Vec::new(), 1);
    }
    let (xs, step) = lin_ticks(10f64.powf(lo), 10f64.powf(hi), 6);
    let digits = digits_for(&xs, step);
    (
        xs.iter().filter(|&&x| x > 0.0).map(|x| x.log10()).collect(),
        Vec::new(),
        digits,
    )
}

/// `x` with `sig` significant digits, trailing zeros dropped; plain between 1e-3 and 1e5.
pub fn fmt_sig(x: f64, sig: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { x.to_string() };
    }
    let sig = sig.max(1);
    let e = x.abs().log10().floor() as i64;
    if (-3..5).contains(&e) {
        let decimals = (sig as i64 - 1 - e).max(0) as usize;
        trim_zeros(&format!("{x:.decimals$}"))
    } else {
        let s = format!("{:.*e}", sig - 1, x);
        match s.split_once('e') {
            Some((m, ex)) => format!("{}e{ex}", trim_zeros(m)),
            None => s,
        }
    }
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s.to_owned()
    }
}

/// The ratio axis of a plot of ratios: logarithmic when the positive ratios (and 1) span a
/// decade or more; `floor` (plotted) is where points of ratio 0 and failed points sit.
struct RatioAxis {
    scale: Scale,
    floor: f64,
    log: bool,
}

impl RatioAxis {
    fn of<'a>(points: impl Iterator<Item = &'a MapPoint>) -> RatioAxis {
        let positive: Vec<f64> = points
            .filter_map(|p| p.ratio().filter(|r| *r > 0.0))
            .collect();
        let (rmin, rmax) = min_max(&positive);
        let (rmin, rmax) = (rmin.min(1.0), rmax.max(1.0));
        if rmax / rmin >= 10.0 {
            let (lo, hi) = (rmin.log10(), rmax.log10());
            let span = (hi - lo).max(0.2);
            let (ylo, yhi) = (lo - 0.12 * span, hi + 0.06 * span);
            RatioAxis {
                scale: Scale::new(ylo, yhi, true),
                floor: lo - 0.08 * span,
                log: true,
            }
        } else {
            let top = (1.15 * rmax).max(1.2);
            RatioAxis {
                scale: Scale::new(-0.05 * top, top, false),
                floor: 0.0,
                log: false,
            }
        }
    }

    /// The axis raised so that the top `rows` legend rows (of a plot 620 px high) sit
    /// above every point: the legend box in the upper right then hides none of them.
    fn with_legend_rows(self, rows: usize) -> RatioAxis {
        let f = ((rows as f64 * 20.0 + 20.0) / 510.0).min(0.5);
        let (lo, hi) = (self.scale.lo, self.scale.hi);
        RatioAxis {
            scale: Scale::new(lo, hi + (hi - lo) * f / (1.0 - f), self.scale.log),
            ..self
        }
    }
}

fn draw_1d(map: &Map, labels: &Labels, buf: &mut String) -> Result<(), ReportError> {
    let axis = &map.grid().axes()[0];
    let xs = Scale::of_axis(axis, 0.03);
    // (plotted x, point)
    let pts: Vec<(f64, &MapPoint)> = map
        .points()
        .iter()
        .map(|p| (axis.plotted(p.values[0]), p))
        .collect();
    let mut ratio_axis = RatioAxis::of(pts.iter().map(|(_, p)| *p));
    if axis.is_categorical() {
        // the legend's rows: the line, the markers, rings, crosses, the window
        ratio_axis = ratio_axis.with_legend_rows(5);
    }
    let RatioAxis {
        scale: ys,
        floor,
        log: log_y,
    } = ratio_axis;
    let to_y = |r: f64| if log_y { r.log10() } else { r };

    let title = labels.title.clone().unwrap_or_else(|| {
        format!(
            "Pull-out / restoring pressure vs {} ({})",
            axis.field,
            map.accuracy()
        )
    });
    let root = SVGBackend::with_string(buf, (900, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let mut chart = ratio_frame(
        &root,
        title,
        (&xs, &ys, log_y),
        labels.axis_label(&axis.field),
        "ratio = 1: sticks above",
    )?;

    // the curve, broken where a point has no positive ratio (none between words: they
    // have no order)
    let categorical = axis.is_categorical();
    let mut runs = positive_runs(&pts, to_y);
    let line = BLACK.stroke_width(2);
    if categorical {
        runs.clear();
    }
    for (k, run) in runs.iter().filter(|r| !r.is_empty()).enumerate() {
        let s = chart
            .draw_series(LineSeries::new(run.iter().copied(), line))
            .map_err(plot_err)?;
        if k == 0 {
            s.label("pull-out ratio (red: sticks, blue: free)")
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], line));
        }
    }
    let markers = chart
        .draw_series(pts.iter().filter_map(|(x, p)| {
            let d = p
                .design
                .filter(|d| p.status == Status::Ok && d.validity_holds)?;
            (d.pull_out_ratio > 0.0).then(|| {
                let c = if d.pull_out_ratio < 1.0 { FREE } else { STICK };
                let size = if categorical { 7 } else { 4 };
                Circle::new((*x, to_y(d.pull_out_ratio)), size, c.filled())
            })
        }))
        .map_err(plot_err)?;
    if categorical {
        markers
            .label("pull-out ratio of each word (red: sticks, blue: free)")
            .legend(|(x, y)| Circle::new((x + 10, y), 5, STICK.filled()));
    }
    draw_invalid(
        &mut chart,
        pts.iter().map(|(x, p)| (*x, *p)),
        &to_y,
        if categorical { 7 } else { 5 },
    )?;
    if let Some(r) = map.requirement() {
        let ring = GREEN.stroke_width(2);
        chart
            .draw_series(pts.iter().filter_map(|(x, p)| {
                let d = p.design.filter(|d| r.in_window(d))?;
                Some(Circle::new((*x, to_y(d.pull_out_ratio)), 8, ring))
            }))
            .map_err(plot_err)?
            .label(format!("free and {r}"))
            .legend(move |(x, y)| Circle::new((x + 10, y), 8, ring));
    }
    let no_close: Vec<f64> = pts
        .iter()
        .filter(|(_, p)| p.status.has_design() && p.ratio() == Some(0.0))
        .map(|(x, _)| *x)
        .collect();
    if !no_close.is_empty() {
        let st = RGBColor(110, 110, 110).stroke_width(2);
        chart
            .draw_series(no_close.iter().map(|&x| Circle::new((x, floor), 5, st)))
            .map_err(plot_err)?
            .label("does not close (ratio 0)")
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, st));
    }
    let failed: Vec<f64> = pts
        .iter()
        .filter(|(_, p)| !p.status.has_design())
        .map(|(x, _)| *x)
        .collect();
    if !failed.is_empty() {
        let st = BLACK.stroke_width(2);
        chart
            .draw_series(failed.iter().map(|&x| Cross::new((x, floor), 6, st)))
            .map_err(plot_err)?
            .label("failed or out of domain")
            .legend(move |(x, y)| Cross::new((x + 10, y), 6, st));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 14))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(plot_err)?;
    root.present().map_err(plot_err)
}

/// A chart with `title` on `area` over the scales (x, y), `(y_label_width,
/// bottom_margin)` in pixels: what both the ratio plots and the 2-D map start from.
fn chart_on<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, plotters::coord::Shift>,
    title: String,
    (xs, ys): (&Scale, &Scale),
    (y_label_width, bottom_margin): (u32, u32),
) -> Result<ChartContext<'a, SVGBackend<'b>, Cartesian2d<Ticked, Ticked>>, ReportError> {
    // the title, wrapped to the area's width
    let (w, _) = area.dim_in_pixel();
    let lines = super::wrap(&title, f64::from(w.saturating_sub(30)), 22.0);
    let style = (FONT, 22)
        .into_text_style(area)
        .pos(Pos::new(HPos::Center, VPos::Top));
    for (k, line) in lines.iter().enumerate() {
        area.draw_text(line, &style, ((w / 2) as i32, 10 + 28 * k as i32))
            .map_err(plot_err)?;
    }
    ChartBuilder::on(area)
        .margin(15)
        .margin_top(15 + 28 * lines.len() as u32)
        .margin_bottom(bottom_margin)
        .x_label_area_size(50)
        .y_label_area_size(y_label_width)
        .build_cartesian_2d(xs.coord(), ys.coord())
        .map_err(plot_err)
}

/// The frame both ratio plots share: the title, the axes (`scales`: x, y, and whether y
/// is log10 of the ratio), the mesh with its labels, and the line ratio = 1 with
/// `boundary_label` in the legend.
fn ratio_frame<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, plotters::coord::Shift>,
    title: String,
    (xs, ys, log_y): (&Scale, &Scale, bool),
    x_desc: String,
    boundary_label: &str,
) -> Result<ChartContext<'a, SVGBackend<'b>, Cartesian2d<Ticked, Ticked>>, ReportError> {
    let mut chart = chart_on(root, title, (xs, ys), (85, 15))?;
    let xf = |t: &f64| xs.label(*t);
    let yf = |t: &f64| ys.label(*t);
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(if log_y {
            "pull-out ratio [-] (log scale)"
        } else {
            "pull-out ratio [-]"
        })
        .x_label_formatter(&xf)
        .y_label_formatter(&yf)
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 16))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(plot_err)?;
    let boundary = REFERENCE.stroke_width(2);
    let one = if log_y { 0.0 } else { 1.0 };
    chart
        .draw_series(DashedLineSeries::new(
            [(xs.lo, one), (xs.hi, one)],
            8,
            5,
            boundary,
        ))
        .map_err(plot_err)?
        .label(boundary_label)
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], boundary));
    Ok(chart)
}

/// The runs of consecutive points with a positive ratio, as (plotted x, plotted y): a
/// curve is broken where a point has none.
fn positive_runs(pts: &[(f64, &MapPoint)], to_y: impl Fn(f64) -> f64) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for (x, p) in pts {
        match p.ratio().filter(|r| *r > 0.0) {
            Some(r) => runs.last_mut().expect("non-empty").push((*x, to_y(r))),
            None => runs.push(Vec::new()),
        }
    }
    runs
}

/// The colour of a point outside the model's validity: a hollow grey ring.
pub const INVALID: RGBColor = RGBColor(120, 120, 120);

/// A design point that closes but lies outside the model's validity (a guard fired): its
/// ratio is the model's answer where the model does not hold.
fn invalid(p: &MapPoint) -> bool {
    p.status == Status::Ok
        && p.design
            .is_some_and(|d| !d.validity_holds && d.pull_out_ratio > 0.0)
}

/// Hollow grey rings (radius `size`) on the points outside the model's validity, with
/// their legend entry; nothing when every point is valid.
fn draw_invalid<'a, 'b, 'p>(
    chart: &mut ChartContext<'a, SVGBackend<'b>, Cartesian2d<Ticked, Ticked>>,
    pts: impl Iterator<Item = (f64, &'p MapPoint)>,
    to_y: &dyn Fn(f64) -> f64,
    size: i32,
) -> Result<(), ReportError> {
    let rings: Vec<(f64, f64)> = pts
        .filter(|(_, p)| invalid(p))
        .filter_map(|(x, p)| Some((x, to_y(p.ratio()?))))
        .collect();
    if rings.is_empty() {
        return Ok(());
    }
    let st = INVALID.stroke_width(2);
    chart
        .draw_series(rings.iter().map(|&c| Circle::new(c, size, st)))
        .map_err(plot_err)?
        .label("outside the model's validity (hollow grey)")
        .legend(move |(x, y)| Circle::new((x + 10, y), 5, st));
    Ok(())
}

/// A map over a categorical and a numeric axis: the ratio against the numeric field, one
/// curve per word (its colour in the legend), the line ratio = 1; filled markers stick,
/// open ones are free; points that do not close (rings) and failed points (crosses) sit at
/// the bottom in their word's colour.
fn draw_by_word(map: &Map, labels: &Labels, buf: &mut String) -> Result<(), ReportError> {
    let g = map.grid();
    let (c, x) = if g.axes()[0].is_categorical() {
        (0, 1)
    } else {
        (1, 0)
    };
    let (cat, num) = (&g.axes()[c], &g.axes()[x]);
    let xs = Scale::of_axis(num, 0.03);
    // per word: (plotted x, point), ascending along the numeric axis
    let curves: Vec<Vec<(f64, &MapPoint)>> = (0..cat.n)
        .map(|w| {
            (0..num.n)
                .filter_map(|j| {
                    let mut idx = [0; 2];
                    idx[c] = w;
                    idx[x] = j;
                    map.point(g.index(&idx))
                        .map(|p| (num.plotted(num.values[j]), p))
                })
                .collect()
        })
        .collect();
    // the legend's rows: the line, the words, the markers at the bottom, the window
    let RatioAxis {
        scale: ys,
        floor,
        log: log_y,
    } = RatioAxis::of(map.points().iter()).with_legend_rows(cat.n + 3);
    let to_y = |r: f64| if log_y { r.log10() } else { r };

    let title = labels.title.clone().unwrap_or_else(|| {
        format!(
            "Pull-out / restoring pressure vs {} by {} ({})",
            num.field,
            cat.field,
            map.accuracy()
        )
    });
    let root = SVGBackend::with_string(buf, (900, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let mut chart = ratio_frame(
        &root,
        title,
        (&xs, &ys, log_y),
        labels.axis_label(&num.field),
        "ratio = 1: sticks above (filled: sticks, open: free)",
    )?;

    for (w, pts) in curves.iter().enumerate() {
        let colour = SERIES[w % SERIES.len()];
        let line = colour.stroke_width(2);
        // the curve, broken where a point has no positive ratio
        let runs = positive_runs(pts, to_y);
        let label = format!("{} = {}", cat.field, cat.words[w]);
        let mut labelled = false;
        for run in runs.iter().filter(|r| !r.is_empty()) {
            let s = chart
                .draw_series(LineSeries::new(run.iter().copied(), line))
                .map_err(plot_err)?;
            if !labelled {
                s.label(label.clone())
                    .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], line));
                labelled = true;
            }
        }
        chart
            .draw_series(pts.iter().filter_map(|(x, p)| {
                let d = p.design.filter(|_| p.status == Status::Ok)?;
                (d.pull_out_ratio > 0.0).then(|| {
                    let style = if d.pull_out_ratio < 1.0 {
                        colour.stroke_width(2)
                    } else {
                        colour.filled()
                    };
                    Circle::new((*x, to_y(d.pull_out_ratio)), 4, style)
                })
            }))
            .map_err(plot_err)?;
        let no_close: Vec<f64> = pts
            .iter()
            .filter(|(_, p)| p.status.has_design() && p.ratio() == Some(0.0))
            .map(|(x, _)| *x)
            .collect();
        let failed: Vec<f64> = pts
            .iter()
            .filter(|(_, p)| !p.status.has_design())
            .map(|(x, _)| *x)
            .collect();
        let st = colour.stroke_width(2);
        let s = chart
            .draw_series(no_close.iter().map(|&x| Circle::new((x, floor), 5, st)))
            .map_err(plot_err)?;
        if !labelled && !no_close.is_empty() {
            s.label(label.clone())
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, st));
            labelled = true;
        }
        let s = chart
            .draw_series(failed.iter().map(|&x| Cross::new((x, floor), 6, st)))
            .map_err(plot_err)?;
        if !labelled && !failed.is_empty() {
            s.label(label)
                .legend(move |(x, y)| Cross::new((x + 10, y), 6, st));
        }
    }
    draw_invalid(
        &mut chart,
        curves.iter().flatten().map(|(x, p)| (*x, *p)),
        &to_y,
        7,
    )?;
    if map
        .points()
        .iter()
        .any(|p| p.ratio() == Some(0.0) || !p.status.has_design())
    {
        // what the markers at the bottom mean, once
        let grey = RGBColor(110, 110, 110).stroke_width(2);
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(plot_err)?
            .label("at the bottom: ring does not close, cross failed")
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, grey));
    }
    if let Some(r) = map.requirement() {
        let ring = GREEN.stroke_width(2);
        chart
            .draw_series(curves.iter().flatten().filter_map(|(x, p)| {
                let d = p.design.filter(|d| r.in_window(d))?;
                Some(Circle::new((*x, to_y(d.pull_out_ratio)), 8, ring))
            }))
            .map_err(plot_err)?
            .label(format!("free and {r}"))
            .legend(move |(x, y)| Circle::new((x + 10, y), 8, ring));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 14))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(plot_err)?;
    root.present().map_err(plot_err)
}

/// Diverging blue-white-red colour for `v` in [-1, 1].
fn diverging(v: f64) -> RGBColor {
    const STOPS: [(f64, (f64, f64, f64)); 5] = [
        (-1.0, (33.0, 102.0, 172.0)),
        (-0.5, (146.0, 197.0, 222.0)),
        (0.0, (247.0, 247.0, 247.0)),
        (0.5, (244.0, 165.0, 130.0)),
        (1.0, (178.0, 24.0, 43.0)),
    ];
    let v = v.clamp(-1.0, 1.0);
    let k = STOPS
        .windows(2)
        .position(|w| v <= w[1].0)
        .unwrap_or(STOPS.len() - 2);
    let ((a, ca), (b, cb)) = (STOPS[k], STOPS[k + 1]);
    let f = (v - a) / (b - a);
    let mix = |x: f64, y: f64| (x + f * (y - x)).round().clamp(0.0, 255.0) as u8;
    RGBColor(mix(ca.0, cb.0), mix(ca.1, cb.1), mix(ca.2, cb.2))
}

/// Cell edges (plotted) around each grid value of an axis: midpoints between neighbours.
fn cell_edges(axis: &Axis, scale: &Scale) -> Vec<(f64, f64)> {
    let t: Vec<f64> = axis.values.iter().map(|&v| axis.plotted(v)).collect();
    let n = t.len();
    (0..n)
        .map(|i| {
            if n == 1 {
                return (scale.lo, scale.hi);
            }
            let left = if i == 0 {
                t[0] - 0.5 * (t[1] - t[0])
            } else {
                0.5 * (t[i - 1] + t[i])
            };
            let right = if i == n - 1 {
                t[n - 1] + 0.5 * (t[n - 1] - t[n - 2])
            } else {
                0.5 * (t[i] + t[i + 1])
            };
            (left.min(right), left.max(right))
        })
        .collect()
}

fn draw_2d(map: &Map, labels: &Labels, buf: &mut String) -> Result<(), ReportError> {
    let g = map.grid();
    let [ax, ay] = [&g.axes()[0], &g.axes()[1]];
    let (xs0, ys0) = (Scale::of_axis(ax, 0.0), Scale::of_axis(ay, 0.0));
    let (ex, ey) = (cell_edges(ax, &xs0), cell_edges(ay, &ys0));
    let span = |e: &[(f64, f64)]| {
        e.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(l, r)| {
                (a.min(l), b.max(r))
            })
    };
    let ((xlo, xhi), (ylo, yhi)) = (span(&ex), span(&ey));
    let scale = |a: &Axis, lo: f64, hi: f64| {
        if a.is_categorical() {
            Scale::of_words(a)
        } else {
            Scale::new(lo, hi, a.spacing == Spacing::Log)
        }
    };
    let (xs, ys) = (scale(ax, xlo, xhi), scale(ay, ylo, yhi));
    let levels: Vec<f64> = map
        .points()
        .iter()
        .filter(|p| p.status == Status::Ok)
        .filter_map(|p| p.ratio().filter(|r| *r > 0.0).map(f64::log10))
        .collect();
    // each side of ratio = 1 scaled by its own extreme, so that neither is pale when the
    // other reaches far
    let lo = levels.iter().fold(-0.1f64, |m, &l| m.min(l));
    let hi = levels.iter().fold(0.1f64, |m, &l| m.max(l));
    let shade = |l: f64| {
        if l < 0.0 {
            diverging(l / -lo)
        } else {
            diverging(l / hi)
        }
    };

    let title = labels.title.clone().unwrap_or_else(|| {
        format!(
            "log10 pull-out ratio over {} and {} ({})",
            ax.field,
            ay.field,
            map.accuracy()
        )
    });
    // the legend under the map, wrapped; what it names is known before drawing
    let any_no_close = map.points().iter().any(|p| {
        matches!(p.status, Status::Ok | Status::DoesNotClose)
            && p.ratio()
                .is_some_and(|r| !(p.status == Status::Ok && r > 0.0))
    });
    let any_failed = map
        .points()
        .iter()
        .any(|p| !(matches!(p.status, Status::Ok | Status::DoesNotClose) && p.ratio().is_some()));
    let any_invalid = map.points().iter().any(invalid);
    let any_window = !map.window().is_empty();
    let mut legend = String::from(if g.has_categorical() {
        "red sticks, blue free, white at ratio = 1 (no contour between words)"
    } else {
        "black line: ratio = 1 (stiction boundary); red sticks, blue free"
    });
    if any_no_close {
        legend.push_str("; grey: does not close (not free)");
    }
    if any_failed {
        legend.push_str("; x: failed or out of domain");
    }
    if any_invalid {
        legend.push_str("; grey ring: outside the model's validity");
    }
    if let Some(r) = map.requirement() {
        legend.push_str(&if any_window {
            format!("; green frame: free and {r}")
        } else {
            format!("; no point free and {r}")
        });
    }
    let legend_lines = super::wrap(&legend, 740.0, 14.0);
    let root = SVGBackend::with_string(buf, (980, 720)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let (main, bar) = root.split_horizontally(850);
    let mut chart = chart_on(
        &main,
        title,
        (&xs, &ys),
        (90, 17 + 18 * legend_lines.len() as u32),
    )?;
    let xf = |t: &f64| xs.label(*t);
    let yf = |t: &f64| ys.label(*t);
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(labels.axis_label(&ax.field))
        .y_desc(labels.axis_label(&ay.field))
        .x_label_formatter(&xf)
        .y_label_formatter(&yf)
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 16))
        .draw()
        .map_err(plot_err)?;

    let mut cells = Vec::new();
    let mut crosses = Vec::new();
    for p in map.points() {
        let idx = g.indices(p.index);
        let ((x0, x1), (y0, y1)) = (ex[idx[0]], ey[idx[1]]);
        let fill = match (&p.status, p.ratio()) {
            (Status::Ok, Some(r)) if r > 0.0 => shade(r.log10()),
            (Status::Ok | Status::DoesNotClose, Some(_)) => NO_CLOSE,
            _ => {
                crosses.push((0.5 * (x0 + x1), 0.5 * (y0 + y1)));
                WHITE
            }
        };
        cells.push(Rectangle::new([(x0, y0), (x1, y1)], fill.filled()));
    }
    chart.draw_series(cells).map_err(plot_err)?;
    // the design window (free and meeting the requirement): framed cells
    let window: Vec<_> = map
        .window()
        .iter()
        .map(|p| {
            let idx = g.indices(p.index);
            let ((x0, x1), (y0, y1)) = (ex[idx[0]], ey[idx[1]]);
            Rectangle::new([(x0, y0), (x1, y1)], GREEN.stroke_width(3))
        })
        .collect();
    chart.draw_series(window).map_err(plot_err)?;
    chart
        .draw_series(
            crosses
                .iter()
                .map(|&c| Cross::new(c, 6, BLACK.stroke_width(2))),
        )
        .map_err(plot_err)?;
    // points outside the model's validity: a hollow grey ring in the cell
    let rings: Vec<(f64, f64)> = map
        .points()
        .iter()
        .filter(|p| invalid(p))
        .map(|p| {
            let idx = g.indices(p.index);
            let ((x0, x1), (y0, y1)) = (ex[idx[0]], ey[idx[1]]);
            (0.5 * (x0 + x1), 0.5 * (y0 + y1))
        })
        .collect();
    chart
        .draw_series(
            rings
                .iter()
                .map(|&c| Circle::new(c, 5, INVALID.stroke_width(2))),
        )
        .map_err(plot_err)?;
    for line in contour_plotted(map) {
        chart
            .draw_series(std::iter::once(PathElement::new(
                line,
                BLACK.stroke_width(CONTOUR_WIDTH),
            )))
            .map_err(plot_err)?;
    }
    for (k, line) in legend_lines.iter().enumerate() {
        main.draw_text(
            line,
            &(FONT, 14).into_text_style(&main),
            (95, 720 - 22 - 18 * (legend_lines.len() - 1 - k) as i32),
        )
        .map_err(plot_err)?;
    }

    // colour bar
    let bs = Scale::new(lo, hi, false);
    let mut cb = ChartBuilder::on(&bar)
        .margin_top(60)
        .margin_bottom(80)
        .margin_right(30)
        .x_label_area_size(0)
        .y_label_area_size(60)
        .build_cartesian_2d(0f64..1f64, bs.coord())
        .map_err(plot_err)?;
    let bf = |t: &f64| bs.label(*t);
    cb.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("log10 ratio [-] (pull-out over restoring)")
        .y_label_formatter(&bf)
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 16))
        .draw()
        .map_err(plot_err)?;
    let steps = 120;
    cb.draw_series((0..steps).map(|k| {
        let (a, b) = (
            lo + (hi - lo) * k as f64 / steps as f64,
            lo + (hi - lo) * (k + 1) as f64 / steps as f64,
        );
        Rectangle::new([(0.0, a), (1.0, b)], shade(0.5 * (a + b)).filled())
    }))
    .map_err(plot_err)?;
    cb.draw_series(std::iter::once(PathElement::new(
        [(0.0, 0.0), (1.0, 0.0)],
        BLACK.stroke_width(2),
    )))
    .map_err(plot_err)?;
    root.present().map_err(plot_err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_exact_enough() {
        assert_eq!(fmt_sig(1000.0000000000001, 1), "1000");
        assert_eq!(fmt_sig(0.30000000000000004, 1), "0.3");
        assert_eq!(fmt_sig(10f64.powf(-9.0), 1), "1e-9");
        assert_eq!(fmt_sig(1e-9 * (1.0 + 2.0 * f64::EPSILON), 1), "1e-9");
        assert_eq!(fmt_sig(2.5e-9, 2), "2.5e-9");
        assert_eq!(fmt_sig(-1.25e6, 3), "-1.25e6");
        assert_eq!(fmt_sig(0.0, 3), "0");
        assert_eq!(fmt_sig(1414.2135, 6), "1414.21");
    }

    #[test]
    fn every_axis_gets_ticks_inside_it() {
        for (lo, hi) in [
            (2f64.log10(), 5f64.log10()),
            (-9.3, -8.9),
            (0.2, 7.9),
            (-12.0, 12.0),
        ] {
            let (bold, _, _) = log_ticks(lo, hi);
            assert!(bold.len() >= 2, "{lo}..{hi}: {bold:?}");
            assert!(bold.len() <= 13, "{lo}..{hi}: {bold:?}");
            assert!(bold.iter().all(|t| (lo - 1e-12..=hi + 1e-12).contains(t)));
        }
        let (t, step) = lin_ticks(-0.05, 1.2, 8);
        assert_eq!(step, 0.2);
        assert_eq!(t.len(), 7);
        assert_eq!(digits_for(&t, step), 2); // "1.2"
    }

    #[test]
    fn the_colour_map_is_white_at_ratio_one() {
        assert_eq!(diverging(0.0), RGBColor(247, 247, 247));
        assert_eq!(diverging(1.0), STICK);
        assert_eq!(diverging(-3.0), FREE);
    }
}
