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
/// A reference line (a map's ratio = 1, the 100 % of a contact area): dark grey and
/// dashed wherever it is drawn, so that no data series' colour can be taken for it.
pub const REFERENCE: RGBColor = RGBColor(80, 80, 80);

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
        // one value: a tenth of it either side (a count or a zero: one either side)
        let c = if lo.is_finite() { lo } else { 0.0 };
        let counted = if axis == 0 {
            panel.x_label.starts_with("cycle")
        } else {
            panel.y_label.contains("[count]")
        };
        let pad = if counted || c == 0.0 {
            1.0
        } else {
            0.1 * c.abs()
        };
        return (c - pad, c + pad);
    }
    if axis == 1 {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    } else {
        (lo, hi)
    }
}

/// A tick label as plotters writes it (up to 5 decimals), without the sign of a zero
/// ("-0.0" where rounding left a tick a hair below zero).
fn tick(v: &f64) -> String {
    let s = plotters::data::float::FloatPrettyPrinter {
        allow_scientific: false,
        min_decimal: 1,
        max_decimal: 5,
    }
    .print(*v);
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_owned(),
        _ => s,
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
    // a count (cycles on x, "[count]" on y) is labelled at whole numbers only
    let counted = panel.x_label.starts_with("cycle");
    let y_counted = panel.y_label.contains("[count]");
    let whole = |step: f64| {
        move |x: &f64| {
            let k = (x / step).round();
            if (x - k * step).abs() < 1e-9 * step.max(1.0) {
                format!("{:.0}", k * step)
            } else {
                String::new()
            }
        }
    };
    let (x_step, y_step) = (whole_step(xr.1 - xr.0), whole_step(yr.1 - yr.0));
    let (x_whole, y_whole) = (whole(x_step), whole(y_step));
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .x_label_formatter(&tick)
        .y_label_formatter(&tick);
    // enough key points that plotters' own choice lands on every whole step
    let keys = |span: f64, step: f64| ((span / step).ceil() as usize * 2 + 1).min(41);
    if counted {
        mesh.x_labels(keys(xr.1 - xr.0, x_step))
            .x_label_formatter(&x_whole);
    }
    if y_counted {
        mesh.y_labels(keys(yr.1 - yr.0, y_step))
            .y_label_formatter(&y_whole);
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
        let mut labelled = false;
        for run in runs.iter().filter(|r| r.len() > 1) {
            let drawn = if c == REFERENCE {
                chart.draw_series(DashedLineSeries::new(
                    run.iter().copied(),
                    8,
                    5,
                    c.stroke_width(2),
                ))
            } else {
                chart.draw_series(LineSeries::new(run.iter().copied(), c.stroke_width(2)))
            }
            .map_err(|x| e(&x))?;
            if !labelled {
                labelled = true;
                drawn.label(s.name.clone()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
            }
        }
        // a value per cycle is marked at each cycle, and a lone point is drawn at all
        let inside = |p: &&(f64, f64)| {
            p.0.is_finite()
                && p.1.is_finite()
                && (xr.0..=xr.1).contains(&p.0)
                && (yr.0..=yr.1).contains(&p.1)
        };
        let marks: Vec<(f64, f64)> = s.points.iter().filter(inside).copied().collect();
        if (counted || s.points.len() == 1) && !marks.is_empty() {
            let drawn = chart
                .draw_series(marks.iter().map(|&p| Circle::new(p, 3, c.filled())))
                .map_err(|x| e(&x))?;
            if !labelled {
                drawn
                    .label(s.name.clone())
                    .legend(move |(x, y)| Circle::new((x + 10, y), 3, c.filled()));
            }
        }
    }
    // the legend in the corner where it hides the least of the data
    let (xs, ys) = chart.plotting_area().get_pixel_range();
    let pixels: Vec<(i32, i32)> = panel
        .series
        .iter()
        .flat_map(|s| clip(&s.points, xr, yr))
        .chain(panel.bands.iter().flat_map(|b| {
            let lo: Vec<(f64, f64)> = b.points.iter().map(|p| (p.0, p.1)).collect();
            let hi: Vec<(f64, f64)> = b.points.iter().map(|p| (p.0, p.2)).collect();
            [clip(&lo, xr, yr), clip(&hi, xr, yr)].concat()
        }))
        .flat_map(|run| {
            let px: Vec<(i32, i32)> = run.iter().map(|p| chart.backend_coord(p)).collect();
            sample_pixels(&px)
        })
        .collect();
    let names = panel
        .series
        .iter()
        .map(|s| s.name.as_str())
        .chain(panel.bands.iter().map(|b| b.name.as_str()));
    let (rows, longest) = names.fold((0usize, 0usize), |(n, w), name| {
        (n + 1, w.max(name.chars().count()))
    });
    let size = (
        (longest as f64 * CHAR_WIDTH * LEGEND_FONT + 45.0) as i32,
        (rows as f64 * 15.0 + 12.0) as i32,
    );
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(legend_corner((xs, ys), size, &pixels))
        .draw()
        .map_err(|x| e(&x))?;
    Ok(())
}

/// The legend's font size in the SVG (plotters' default label font, 12 pt).
const LEGEND_FONT: f64 = 9.7;

/// Points every 4 pixels along a polyline given in pixels (its corners included).
fn sample_pixels(px: &[(i32, i32)]) -> Vec<(i32, i32)> {
    let mut out: Vec<(i32, i32)> = px.first().copied().into_iter().collect();
    for w in px.windows(2) {
        let (a, b) = (w[0], w[1]);
        let n = ((b.0 - a.0).abs().max((b.1 - a.1).abs()) / 4).max(1);
        for k in 1..=n {
            let t = f64::from(k) / f64::from(n);
            out.push((
                a.0 + (t * f64::from(b.0 - a.0)).round() as i32,
                a.1 + (t * f64::from(b.1 - a.1)).round() as i32,
            ));
        }
    }
    out
}

/// The corner of the plotting area (`x` and `y` pixel ranges) where a legend of `size`
/// pixels covers the fewest of `pixels` (the data drawn), lower right on a tie.
fn legend_corner(
    (x, y): (std::ops::Range<i32>, std::ops::Range<i32>),
    size: (i32, i32),
    pixels: &[(i32, i32)],
) -> SeriesLabelPosition {
    // plotters puts the box 5 px from the area's edges; counted with 2 px to spare
    let (margin, pad) = (5, 2);
    let size = (size.0 + 2 * pad, size.1 + 2 * pad);
    let (left, right) = (x.start + margin - pad, x.end - margin - size.0 + pad);
    let (top, bottom) = (y.start + margin - pad, y.end - margin - size.1 + pad);
    [
        (SeriesLabelPosition::LowerRight, right, bottom),
        (SeriesLabelPosition::UpperRight, right, top),
        (SeriesLabelPosition::UpperLeft, left, top),
        (SeriesLabelPosition::LowerLeft, left, bottom),
    ]
    .into_iter()
    .map(|(pos, x0, y0)| {
        let hidden = pixels
            .iter()
            .filter(|p| (x0..=x0 + size.0).contains(&p.0) && (y0..=y0 + size.1).contains(&p.1))
            .count();
        (hidden, pos)
    })
    .min_by_key(|(hidden, _)| *hidden)
    .map_or(SeriesLabelPosition::LowerRight, |(_, pos)| pos)
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
    fn a_zero_tick_has_no_sign() {
        assert_eq!(tick(&-1e-17), "0.0");
        assert_eq!(tick(&-0.0), "0.0");
        assert_eq!(tick(&-0.5), "-0.5");
        assert_eq!(tick(&2.0), "2.0");
    }

    #[test]
    fn one_value_is_padded_by_a_tenth_or_a_whole_count() {
        let panel = |x: &str, y: &str, v: f64| Panel {
            x_label: x.into(),
            y_label: y.into(),
            series: vec![Series {
                name: "s".into(),
                points: vec![(1.0, v)],
                colour: None,
            }],
            ..Default::default()
        };
        let r = data_range(&panel("cycle [count]", "E [J/m^2]", 6.5e-3), 1);
        assert!((r.0 - 5.85e-3).abs() < 1e-15 && (r.1 - 7.15e-3).abs() < 1e-15);
        assert_eq!(
            data_range(&panel("cycle [count]", "bounces [count]", 4.0), 1),
            (3.0, 5.0)
        );
        assert_eq!(
            data_range(&panel("cycle [count]", "E [J/m^2]", 0.0), 1),
            (-1.0, 1.0)
        );
        assert_eq!(
            data_range(&panel("cycle [count]", "E [J/m^2]", 0.0), 0),
            (0.0, 2.0)
        );
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
