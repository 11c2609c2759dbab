//! Plain-text tables for `--format table`.

use crate::plot::map::fmt_sig;
use std::fmt::Write;
use stiction_model::design_sweep::{
    BoundaryPoint, FreeSide, Labels, Level, Map, MapPoint, Status, Threshold,
};

/// Failed points listed by name in a table (the rest are counted).
const LISTED_FAILURES: usize = 10;

/// One crossing of ratio = 1 along `field`: where, between which grid values, the free
/// side and the kind of crossing.
fn crossing_text(field: &str, unit: Option<&str>, p: &BoundaryPoint) -> String {
    format!(
        "{field} ~ {} (between {} and {}), free {}, {}",
        with_unit(p.value, 4, unit),
        fmt_sig(p.between[0], 6),
        fmt_sig(p.between[1], 6),
        p.free_side.word(),
        p.kind.word()
    )
}

fn with_unit(x: f64, digits: usize, unit: Option<&str>) -> String {
    match unit {
        Some(u) => format!("{} {u}", fmt_sig(x, digits)),
        None => fmt_sig(x, digits),
    }
}

/// Where the switch stops closing between neighbouring points `along` one numeric axis
/// ((value, point), in the axis's order): a design boundary of its own, which bounds a free
/// side that reaches it (never "free" beyond it), with what the switch does where it first
/// closes: if it sticks there, the stiction boundary lies at the closure or between it and
/// that point, which the grid cannot tell.
fn closure_rows(s: &mut String, along: &[(f64, &MapPoint)], unit: Option<&str>, prefix: &str) {
    let row = |s: &mut String, k: &str, v: String| {
        let _ = writeln!(s, "{k:<16}{v}");
    };
    let closes = |p: &MapPoint| match p.status {
        Status::Ok => Some(true),
        Status::DoesNotClose => Some(false),
        _ => None,
    };
    for w in along.windows(2) {
        let ((x0, p0), (x1, p1)) = (w[0], w[1]);
        let (Some(c0), Some(c1)) = (closes(p0), closes(p1)) else {
            continue;
        };
        if c0 == c1 {
            continue;
        }
        let (lo, hi) = (x0.min(x1), x0.max(x1));
        let side = if c0 == (x0 < x1) { "below" } else { "above" };
        let (x_closed, closed) = if c0 { (x0, p0) } else { (x1, p1) };
        let there = match closed.ratio() {
            Some(r) if r >= 1.0 => format!(
                "; at {}, where it closes, it sticks (ratio {}): the stiction boundary is at the closure or between it and {}",
                with_unit(x_closed, 6, unit),
                fmt_sig(r, 4),
                with_unit(x_closed, 6, unit)
            ),
            Some(r) => format!(
                "; at {}, where it closes, it is free (ratio {})",
                with_unit(x_closed, 6, unit),
                fmt_sig(r, 4)
            ),
            None => String::new(),
        };
        row(
            s,
            "closure",
            format!(
                "{prefix}the switch stops closing between {} and {} (it closes {side}){there}; a closure boundary, not a stiction boundary: `design threshold` locates both",
                with_unit(lo, 6, unit),
                with_unit(hi, 6, unit)
            ),
        );
    }
}

fn ratio_word(r: Option<f64>) -> String {
    match r {
        Some(0.0) => "0 (does not close)".into(),
        Some(r) if r < 1.0 => format!("{} (free)", fmt_sig(r, 4)),
        Some(r) => format!("{} (sticks)", fmt_sig(r, 4)),
        None => "- (point failed)".into(),
    }
}

/// The answer of a threshold search as a table; values carry `labels`' unit of the field.
pub fn threshold_table(t: &Threshold, labels: &Labels) -> String {
    let unit = labels.unit(&t.parameter);
    let v = |x: f64| with_unit(x, 6, unit);
    let mut s = String::new();
    let row = |s: &mut String, k: &str, v: String| {
        let _ = writeln!(s, "{k:<16}{v}");
    };
    row(&mut s, "parameter", labels.axis_label(&t.parameter));
    row(
        &mut s,
        "range",
        format!(
            "{} .. {}, {} scan of {} points",
            v(t.from),
            v(t.to),
            t.spacing,
            t.scan.len()
        ),
    );
    row(&mut s, "ratio at from", ratio_word(t.ratio_at_from));
    row(&mut s, "ratio at to", ratio_word(t.ratio_at_to));
    match (t.critical_value, t.uncertainty, t.kind) {
        (Some(c), Some(u), Some(kind)) => row(
            &mut s,
            "critical value",
            format!(
                "{} +- {}, free {} ({})",
                v(c),
                with_unit(u, 2, unit),
                t.free_side.word(),
                kind.word()
            ),
        ),
        _ => {
            let closes_anywhere = t.scan.iter().any(|p| p.status == "ok");
            row(
                &mut s,
                "critical value",
                match t.free_side {
                    FreeSide::WholeRange => {
                        "none in range: free (ratio < 1) over the whole range".into()
                    }
                    FreeSide::WhereItCloses => {
                        "none in range: free (ratio < 1) wherever the switch closes".into()
                    }
                    _ if !closes_anywhere => {
                        "none in range: the switch does not close anywhere in the range".into()
                    }
                    _ if t.closure_boundary.is_some() => {
                        "none in range: no closing design is free (every design that closes sticks)"
                            .to_string()
                    }
                    _ => "none in range: sticks (ratio >= 1) over the whole range".into(),
                },
            )
        }
    }
    for b in &t.closure_boundaries {
        row(
            &mut s,
            "stops closing",
            format!(
                "at {} +- {}: the switch closes {} it and does not close {} it (a closure boundary, not a stiction boundary){}",
                v(b.value),
                with_unit(b.uncertainty, 2, unit),
                b.closes_side.word(),
                if b.closes_side == FreeSide::Above { "below" } else { "above" },
                b.detail
                    .as_deref()
                    .map(|d| format!("; unresolved: {d}"))
                    .unwrap_or_default()
            ),
        );
    }
    if let Some(req) = &t.requirement {
        let q = req.requirement.quantity;
        for c in &req.crossings {
            row(
                &mut s,
                "requirement",
                format!(
                    "{} crosses {} at {} +- {}: met {} it{}",
                    q.name(),
                    with_unit(
                        req.requirement.limit,
                        4,
                        Some(q.unit()).filter(|u| !u.is_empty())
                    ),
                    v(c.value),
                    with_unit(c.uncertainty, 2, unit),
                    c.met_side.word(),
                    c.detail
                        .as_deref()
                        .map(|d| format!("; unresolved: {d}"))
                        .unwrap_or_default()
                ),
            );
        }
        if req.crossings.is_empty() {
            let met = t.scan.iter().any(|p| p.meets_requirement == Some(true));
            row(
                &mut s,
                "requirement",
                format!(
                    "{}: {} over the closing range",
                    req.requirement,
                    if met { "met" } else { "not met" }
                ),
            );
        }
        row(
            &mut s,
            "design window",
            if req.window.is_empty() {
                format!(
                    "none: no design of the range is both free of stiction and {}",
                    req.requirement
                )
            } else {
                req.window
                    .iter()
                    .map(|w| format!("{} .. {}", v(w[0]), v(w[1])))
                    .collect::<Vec<_>>()
                    .join(", ")
                    + &format!(" (free of stiction and {})", req.requirement)
            },
        );
    }
    row(&mut s, "evaluations", t.evaluations.to_string());
    if t.crossings.len() > 1 {
        let _ = writeln!(s, "\ncrossings ({}):", t.crossings.len());
        let _ = writeln!(
            s,
            "  {:>2}  {:<22}{:<14}{:<7}{:<12}bracket",
            "#", "critical value", "uncertainty", "free", "kind"
        );
        for (i, c) in t.crossings.iter().enumerate() {
            let _ = writeln!(
                s,
                "  {:>2}  {:<22}{:<14}{:<7}{:<12}{} .. {}",
                i + 1,
                v(c.critical_value),
                fmt_sig(c.uncertainty, 2),
                c.free_side.word(),
                c.kind.word(),
                fmt_sig(c.bracket[0], 8),
                fmt_sig(c.bracket[1], 8)
            );
        }
    }
    for c in t.crossings.iter().filter(|c| c.detail.is_some()) {
        let _ = writeln!(
            s,
            "unresolved near {}: {}",
            v(c.critical_value),
            c.detail.as_deref().unwrap_or_default()
        );
    }
    let failed: Vec<_> = t.failed_points().collect();
    if !failed.is_empty() {
        let _ = writeln!(s, "\nfailed scan points ({}):", failed.len());
        for p in failed.iter().take(LISTED_FAILURES) {
            let _ = writeln!(
                s,
                "  {:<22}{:<15}{}",
                v(p.value),
                p.status,
                p.detail.as_deref().unwrap_or_default()
            );
        }
    }
    s
}

/// A summary of a map as a table: grid, statuses, extreme ratios, the boundary (1-D
/// crossings, or the number of contour lines of a 2-D map) and the failed points.
pub fn map_table(map: &Map, labels: &Labels) -> String {
    let g = map.grid();
    let sum = map.summary();
    let mut s = String::new();
    let row = |s: &mut String, k: &str, v: String| {
        let _ = writeln!(s, "{k:<16}{v}");
    };
    let at = |i: usize| {
        g.axes()
            .iter()
            .zip(g.levels(i))
            .map(|(a, v)| match v {
                Level::Number(x) => {
                    format!("{} = {}", a.field, with_unit(x, 6, labels.unit(&a.field)))
                }
                Level::Word(w) => format!("{} = {w}", a.field),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    row(
        &mut s,
        "map",
        if g.dim() == 1 {
            format!(
                "1-D, {} points (accuracy {})",
                sum.grid_points,
                map.accuracy()
            )
        } else {
            format!(
                "2-D, {} x {} = {} points (accuracy {})",
                g.axes()[0].n,
                g.axes()[1].n,
                sum.grid_points,
                map.accuracy()
            )
        },
    );
    if let Some(sh) = map.shard() {
        row(
            &mut s,
            "shard",
            format!("{sh} ({} of {} points)", sum.points, sum.grid_points),
        );
    }
    for (k, a) in g.axes().iter().enumerate() {
        let unit = labels.unit(&a.field);
        let slowest = if g.dim() == 2 && k == 0 {
            " (varies slowest)"
        } else {
            ""
        };
        if a.is_categorical() {
            row(
                &mut s,
                &format!("axis {}", k + 1),
                format!(
                    "{}: {} ({} word{}){slowest}",
                    a.field,
                    a.words.join(", "),
                    a.n,
                    if a.n == 1 { "" } else { "s" }
                ),
            );
            continue;
        }
        row(
            &mut s,
            &format!("axis {}", k + 1),
            format!(
                "{}: {} .. {}, {}, {} values{}",
                labels.axis_label(&a.field),
                with_unit(a.from, 6, unit),
                with_unit(a.to, 6, unit),
                a.spacing,
                a.n,
                slowest
            ),
        );
    }
    row(
        &mut s,
        "statuses",
        format!(
            "ok {}, does_not_close {}, out_of_domain {}, failed {}",
            sum.ok, sum.does_not_close, sum.out_of_domain, sum.failed
        ),
    );
    row(
        &mut s,
        "sticking",
        format!("{} of {} closing points", sum.sticking, sum.ok),
    );
    if let Some((i, r)) = sum.min_ratio {
        row(
            &mut s,
            "smallest ratio",
            format!("{} at {}", fmt_sig(r, 4), at(i)),
        );
    }
    if let Some((i, r)) = sum.max_ratio {
        row(
            &mut s,
            "largest ratio",
            format!("{} at {}", fmt_sig(r, 4), at(i)),
        );
    }
    if let (Some(r), Some(n)) = (map.requirement(), sum.in_window) {
        row(
            &mut s,
            "design window",
            format!(
                "{n} of {} points free of stiction with {r}{}",
                sum.points,
                match map.window().first() {
                    Some(p) => format!(" (e.g. {})", at(p.index)),
                    None => String::new(),
                }
            ),
        );
    }
    if g.dim() == 1 && g.has_categorical() {
        // each word's ratio: the words have no order, so no crossing between them
        let a = &g.axes()[0];
        for (j, w) in a.words.iter().enumerate() {
            let r = map.point(j).map(|p| match (&p.status, p.ratio()) {
                // no pull-out at all (no adhesion): free, not "does not close"
                (Status::Ok, Some(0.0)) => "0 (free)".to_owned(),
                (Status::Ok | Status::DoesNotClose, r) => ratio_word(r),
                (other, _) => format!("- ({})", other.word()),
            });
            if let Some(r) = r {
                row(&mut s, "ratio", format!("{} = {w}: {r}", a.field));
            }
        }
    } else if g.dim() == 1 {
        let a = &g.axes()[0];
        let unit = labels.unit(&a.field);
        let b = map.boundary_1d();
        if b.is_empty() {
            row(
                &mut s,
                "boundary",
                "no crossing of ratio = 1 on the grid".into(),
            );
        }
        for p in b {
            row(&mut s, "boundary", crossing_text(&a.field, unit, &p));
        }
        let along: Vec<(f64, &MapPoint)> = map.points().iter().map(|p| (p.values[0], p)).collect();
        closure_rows(&mut s, &along, unit, "");
    } else if g.has_categorical() {
        let by_word = map.boundary_by_word();
        if by_word.is_empty() {
            row(
                &mut s,
                "boundary",
                "none drawn: both axes are categorical (each point's ratio in map.csv)".into(),
            );
        }
        let c = usize::from(!g.axes()[0].is_categorical());
        for (w, b) in by_word.into_iter().enumerate() {
            let num = &g.axes()[1 - c];
            let unit = labels.unit(&num.field);
            let at_word = format!("{} = {}", b.field, b.word);
            if b.crossings.is_empty() {
                row(
                    &mut s,
                    "boundary",
                    format!("{at_word}: no crossing of ratio = 1 on the grid"),
                );
            }
            for p in b.crossings {
                let text = crossing_text(&num.field, unit, &p);
                row(&mut s, "boundary", format!("{at_word}: {text}"));
            }
            let along: Vec<(f64, &MapPoint)> = (0..num.n)
                .filter_map(|j| {
                    let mut idx = [0; 2];
                    idx[c] = w;
                    idx[1 - c] = j;
                    map.point(g.index(&idx)).map(|p| (num.values[j], p))
                })
                .collect();
            closure_rows(&mut s, &along, unit, &format!("{at_word}: "));
        }
    } else {
        let lines = map.boundary_2d();
        row(
            &mut s,
            "boundary",
            if lines.is_empty() {
                "no crossing of ratio = 1 on the grid".into()
            } else {
                format!(
                    "{} contour line(s) of ratio = 1, {} vertices (see map.svg)",
                    lines.len(),
                    lines.iter().map(Vec::len).sum::<usize>()
                )
            },
        );
    }
    let failed: Vec<_> = map
        .points()
        .iter()
        .filter(|p| p.status.detail().is_some())
        .collect();
    if !failed.is_empty() {
        let _ = writeln!(
            s,
            "\npoints not run: out of domain or failed ({}):",
            failed.len()
        );
        for p in failed.iter().take(LISTED_FAILURES) {
            let _ = writeln!(
                s,
                "  #{:<6} {}: {} {}",
                p.index,
                at(p.index),
                p.status.word(),
                p.status.detail().unwrap_or_default()
            );
        }
        if failed.len() > LISTED_FAILURES {
            let _ = writeln!(s, "  ... and {} more", failed.len() - LISTED_FAILURES);
        }
    }
    s
}
