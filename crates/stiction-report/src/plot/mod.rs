//! Every plot of every result, as an SVG string (plotters, no system libraries), in one
//! palette: [`SERIES`] for lines (the i-th line of a panel, the i-th word of a map),
//! [`STICK`] and [`FREE`] for a verdict (and the ends of the diverging scale of a map's
//! log ratio), [`NO_CLOSE`] for a switch that does not close.
//!
//! Line figures ([`svg`]): panels stacked under a title; points outside a panel's range
//! are clipped at its border, never dropped, so a curve leaves the panel where it really
//! does. Maps of the pull-out ratio: [`map::map_svg`].

pub mod map;
mod portable;

pub use portable::portable;

use plotters::prelude::*;

/// One named line.
#[derive(Debug, Clone, Default)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// (x, y) in plot units.
    pub points: Vec<(f64, f64)>,
    /// Its colour; else the panel's next of [`SERIES`]. A quantity drawn in several panels
    /// (a cycle) is given the same colour in each.
    pub colour: Option<RGBColor>,
}

/// A shaded band between two lines (a confidence interval), drawn under the lines.
#[derive(Debug, Clone, Default)]
pub struct Band {
    /// Legend text.
    pub name: String,
    /// (x, lower, upper) in plot units.
    pub points: Vec<(f64, f64, f64)>,
    /// Its colour (shaded at a quarter); else the first of [`SERIES`].
    pub colour: Option<RGBColor>,
}

/// One panel of a figure.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    /// Panel caption (wrapped to the panel's width).
    pub caption: String,
    /// x-axis label with unit; one that starts with "cycle" is a count, labelled at whole
    /// numbers only.
    pub x_label: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// The lines.
    pub series: Vec<Series>,
    /// Shaded bands under the lines.
    pub bands: Vec<Band>,
    /// Warnings drawn in red under the caption (an impossible value, a point outside the
    /// model's validity).
    pub flags: Vec<String>,
    /// Fixed x range (else the data's).
    pub x_range: Option<(f64, f64)>,
    /// Fixed y range (else the data's, padded).
    pub y_range: Option<(f64, f64)>,
}

/// The colours of a panel's lines (and of a map's words), in order; more lines cycle.
pub const SERIES: [RGBColor; 8] = [
    BLACK,
    RGBColor(200, 30, 30),
    RGBColor(30, 60, 200),
    RGBColor(20, 140, 40),
    RGBColor(170, 0, 170),
    RGBColor(0, 150, 160),
    RGBColor(200, 120, 0),
    RGBColor(120, 0, 200),
];

/// A design that sticks (a map's marker and the high end of its diverging scale).
pub const STICK: RGBColor = RGBColor(178, 24, 43);
/// A design that is free of stiction (the low end of the diverging scale).
pub const FREE: RGBColor = RGBColor(33, 102, 172);
/// A design point that does not close.
pub const NO_CLOSE: RGBColor = RGBColor(190, 190, 190);

/// The parts of the polyline inside [x0, x1] x [y0, y1], each segment clipped at the
/// border (Liang-Barsky).
pub fn clip(
    points: &[(f64, f64)],
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        if !(finite(&a) && finite(&b)) {
            if current.len() > 1 {
                runs.push(std::mem::take(&mut current));
            }
            current.clear();
            continue;
        }
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let mut inside = true;
        for (p, q) in [
            (-dx, a.0 - x0),
            (dx, x1 - a.0),
            (-dy, a.1 - y0),
            (dy, y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    inside = false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        if !inside || t0 >= t1 {
            if current.len() > 1 {
                runs.push(std::mem::take(&mut current));
            }
            current.clear();
            continue;
        }
        let pa = (a.0 + t0 * dx, a.1 + t0 * dy);
        let pb = (a.0 + t1 * dx, a.1 + t1 * dy);
        if current.last() != Some(&pa) {
            if current.len() > 1 {
                runs.push(std::mem::take(&mut current));
            }
            current.clear();
            current.push(pa);
        }
        current.push(pb);
        if t1 < 1.0 {
            runs.push(std::mem::take(&mut current));
        }
    }
    if current.len() > 1 {
        runs.push(current);
    }
    runs
}

fn data_range(panel: &Panel, axis: usize) -> (f64, f64) {
    let bands = panel
        .bands
        .iter()
        .flat_map(|b| b.points.iter().flat_map(|&(x, lo, hi)| [(x, lo), (x, hi)]));
    let vals = panel
        .series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .chain(bands)
        .map(|p| if axis == 0 { p.0 } else { p.1 })
        .filter(|v| v.is_finite());
    let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !(lo < hi) {
        let c = if lo.is_finite() { lo } else { 0.0 };
        return (c - 1.0, c + 1.0);
    }
    if axis == 1 {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    } else {
        (lo, hi)
    }
}

/// The width of a character of sans-serif text, over the font size: an estimate on the
/// wide side (DejaVu Sans, what rsvg picks, averages about 0.55 on words), so that text
/// measured with it fits.
pub const CHAR_WIDTH: f64 = 0.6;

/// `text` broken at spaces (or, for a word too long, inside it) into lines that fit `width`
/// pixels at `font` pixels, by the estimate [`CHAR_WIDTH`].
pub fn wrap(text: &str, width: f64, font: f64) -> Vec<String> {
    let most = ((width / (CHAR_WIDTH * font)).floor() as usize).max(8);
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let mut word: Vec<char> = word.chars().collect();
        while word.len() > most {
            if !line.is_empty() {
                lines.push(std::mem::take(&mut line));
            }
            lines.push(word.drain(..most).collect());
        }
        let word: String = word.into_iter().collect();
        let n = line.chars().count();
        if n > 0 && n + 1 + word.chars().count() > most {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&word);
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

/// Figure width (px).
const WIDTH: u32 = 960;
/// Height of one panel's chart (px), beside its caption and flags.
const PANEL: u32 = 520;
/// Line height of the title, a caption, a flag (px).
const TITLE_LINE: u32 = 30;
const CAPTION_LINE: u32 = 23;

/// Where a count on the x axis is labelled: whole numbers, at most about 10 of them.
fn whole_step(span: f64) -> f64 {
    let raw = (span / 10.0).max(1.0);
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw - 1e-9)
        .unwrap_or(10.0 * mag)
}

/// An SVG of `panels` stacked vertically under `title`; the title and captions wrap to the
/// figure's width, a panel's flags are drawn in red under its caption, its bands shaded
/// under its lines.
pub fn svg(title: &str, panels: &[Panel]) -> Result<String, String> {
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let inner = f64::from(WIDTH - 40);
    let title_lines = wrap(title, inner, 24.0);
    let captions: Vec<Vec<String>> = panels
        .iter()
        .map(|p| {
            if p.caption.is_empty() {
                Vec::new()
            } else {
                wrap(&p.caption, inner, 18.0)
            }
        })
        .collect();
    let flags: Vec<Vec<String>> = panels
        .iter()
        .map(|p| p.flags.iter().flat_map(|f| wrap(f, inner, 16.0)).collect())
        .collect();
    let heights: Vec<u32> = captions
        .iter()
        .zip(&flags)
        .map(|(c, f)| PANEL + CAPTION_LINE * (c.len() + f.len()) as u32)
        .collect();
    let mut out = String::new();
    {
        let height = 20 + TITLE_LINE * title_lines.len() as u32 + heights.iter().sum::<u32>();
        let root = SVGBackend::with_string(&mut out, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let mut root = root.margin(10, 0, 0, 0);
        for line in &title_lines {
            root = root.titled(line, ("sans-serif", 24)).map_err(|x| e(&x))?;
        }
        let mut rest = root;
        for (k, panel) in panels.iter().enumerate() {
            let (mut area, below) = rest.split_vertically(heights[k]);
            rest = below;
            for line in &captions[k] {
                area = area.titled(line, ("sans-serif", 18)).map_err(|x| e(&x))?;
            }
            for line in &flags[k] {
                let style = ("sans-serif", 16).into_font().color(&STICK);
                area = area.titled(line, style).map_err(|x| e(&x))?;
            }
            draw_panel(&area, panel).map_err(|x| e(&x))?;
        }
        rest.present().map_err(|x| e(&x))?;
    }
    Ok(portable(&out))
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

fn draw_panel(area: &Area<'_>, panel: &Panel) -> Result<(), String> {
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let xr = panel.x_range.unwrap_or_else(|| data_range(panel, 0));
    let yr = panel.y_range.unwrap_or_else(|| data_range(panel, 1));
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(|x| e(&x))?;
    // a count on the x axis (cycles) is labelled at whole numbers only
    let counted = panel.x_label.starts_with("cycle");
    let step = whole_step(xr.1 - xr.0);
    let whole = |x: &f64| {
        let k = (x / step).round();
        if (x - k * step).abs() < 1e-9 * step.max(1.0) {
            format!("{:.0}", k * step)
        } else {
            String::new()
        }
    };
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(&panel.x_label).y_desc(&panel.y_label);
    if counted {
        // enough key points that plotters' own choice lands on every whole step
        let n = (((xr.1 - xr.0) / step).ceil() as usize * 2 + 1).min(41);
        mesh.x_labels(n).x_label_formatter(&whole);
    }
    mesh.draw().map_err(|x| e(&x))?;
    for band in &panel.bands {
        let c = band.colour.unwrap_or(SERIES[0]);
        let shade = c.mix(0.25);
        let mut ring: Vec<(f64, f64)> = band
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite() && p.2.is_finite())
            .map(|&(x, lo, _)| (x.clamp(xr.0, xr.1), lo.clamp(yr.0, yr.1)))
            .collect();
        ring.extend(
            band.points
                .iter()
                .rev()
                .filter(|p| p.0.is_finite() && p.1.is_finite() && p.2.is_finite())
                .map(|&(x, _, hi)| (x.clamp(xr.0, xr.1), hi.clamp(yr.0, yr.1))),
        );
        if ring.len() < 3 {
            continue;
        }
        chart
            .draw_series(std::iter::once(Polygon::new(ring, shade.filled())))
            .map_err(|x| e(&x))?
            .label(band.name.clone())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], shade.filled()));
    }
    for (i, s) in panel.series.iter().enumerate() {
        let c = s.colour.unwrap_or(SERIES[i % SERIES.len()]);
        let runs = clip(&s.points, xr, yr);
        for (k, run) in runs.iter().enumerate() {
            let drawn = chart
                .draw_series(LineSeries::new(run.iter().copied(), c.stroke_width(2)))
                .map_err(|x| e(&x))?;
            if k == 0 {
                drawn.label(s.name.clone()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
            }
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerRight)
        .draw()
        .map_err(|x| e(&x))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapped_lines_fit_and_keep_every_word() {
        let text = "a validity subtitle that is much too long for one line of a figure 960 pixels wide, with more words";
        let lines = wrap(text, 300.0, 18.0);
        assert!(lines.len() > 1);
        for l in &lines {
            assert!(l.chars().count() as f64 * CHAR_WIDTH * 18.0 <= 300.0, "{l}");
        }
        assert_eq!(lines.join(" "), text);
        assert_eq!(wrap("short", 300.0, 18.0), vec!["short".to_owned()]);
    }

    #[test]
    fn whole_steps_are_whole_and_few() {
        assert_eq!(whole_step(9.0), 1.0);
        assert_eq!(whole_step(1.0), 1.0);
        assert_eq!(whole_step(99.0), 10.0);
        assert_eq!(whole_step(250.0), 50.0);
    }

    #[test]
    fn clipping_keeps_the_part_inside_and_cuts_at_the_border() {
        // a line from (0, 0) to (4, 4) through a box [1, 3] x [0, 2]
        let runs = clip(
            &[(0.0, 0.0), (2.0, 2.0), (4.0, 4.0)],
            (1.0, 3.0),
            (0.0, 2.0),
        );
        assert_eq!(runs, vec![vec![(1.0, 1.0), (2.0, 2.0)]]);
        // a spike leaving and re-entering gives two runs, both ending on the border
        let runs = clip(
            &[(0.0, 0.0), (1.0, 10.0), (2.0, 0.0)],
            (0.0, 2.0),
            (-1.0, 1.0),
        );
        assert_eq!(runs.len(), 2);
        assert_eq!(runs[0].last().unwrap().1, 1.0);
        assert_eq!(runs[1].first().unwrap().1, 1.0);
        // nothing inside: nothing drawn
        assert!(clip(&[(0.0, 5.0), (1.0, 6.0)], (0.0, 1.0), (0.0, 1.0)).is_empty());
    }
}
