//! Every plot of every result, as an SVG string (plotters, no system libraries), in one
//! palette: [`SERIES`] for lines (the i-th line of a panel, the i-th word of a map),
//! [`STICK`] and [`FREE`] for a verdict (and the ends of the diverging scale of a map's
//! log ratio), [`NO_CLOSE`] for a switch that does not close.
//!
//! Line figures ([`svg`]): panels stacked under a title; points outside a panel's range
//! are clipped at its border, never dropped, so a curve leaves the panel where it really
//! does. Maps of the pull-out ratio: [`map::map_svg`].

pub mod map;

use plotters::prelude::*;

/// One named line.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// (x, y) in plot units.
    pub points: Vec<(f64, f64)>,
}

/// One panel of a figure.
#[derive(Debug, Clone)]
pub struct Panel {
    /// Panel caption.
    pub caption: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// The lines.
    pub series: Vec<Series>,
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
    let vals = panel
        .series
        .iter()
        .flat_map(|s| s.points.iter())
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

/// An SVG of `panels` stacked vertically under `title`.
pub fn svg(title: &str, panels: &[Panel]) -> Result<String, String> {
    let mut out = String::new();
    {
        let height = 80 + 520 * panels.len() as u32;
        let root = SVGBackend::with_string(&mut out, (960, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let root = root
            .titled(title, ("sans-serif", 24))
            .map_err(|e| e.to_string())?;
        let areas = root.split_evenly((panels.len(), 1));
        for (panel, area) in panels.iter().zip(areas.iter()) {
            let xr = panel.x_range.unwrap_or_else(|| data_range(panel, 0));
            let yr = panel.y_range.unwrap_or_else(|| data_range(panel, 1));
            let mut chart = ChartBuilder::on(area)
                .caption(&panel.caption, ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(45)
                .y_label_area_size(80)
                .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
                .map_err(|e| e.to_string())?;
            // a count on the x axis (cycles) is labelled at whole numbers only
            let counted = panel.x_label == "cycle";
            let whole = |x: &f64| {
                if x.fract().abs() < 1e-9 {
                    format!("{x:.0}")
                } else {
                    String::new()
                }
            };
            let span = (xr.1 - xr.0).round().max(1.0) as usize;
            let mut mesh = chart.configure_mesh();
            mesh.x_desc(&panel.x_label).y_desc(&panel.y_label);
            if counted {
                mesh.x_labels(2 * span + 1).x_label_formatter(&whole);
            }
            mesh.draw().map_err(|e| e.to_string())?;
            for (i, s) in panel.series.iter().enumerate() {
                let c = SERIES[i % SERIES.len()];
                let runs = clip(&s.points, xr, yr);
                for (k, run) in runs.iter().enumerate() {
                    let drawn = chart
                        .draw_series(LineSeries::new(run.iter().copied(), c.stroke_width(2)))
                        .map_err(|e| e.to_string())?;
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
                .map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

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
