//! Analytic evaluators with known stiction boundaries.
#![allow(dead_code, missing_docs)]

use design_sweep::{DesignPoint, Level, PointError};

/// A design point of the given ratio and restoring pressure.
pub fn point(ratio: f64, restoring: f64) -> DesignPoint {
    DesignPoint {
        pull_out_ratio: ratio,
        largest_pull_out_pa: ratio * restoring,
        restoring_pressure_pa: restoring,
        cycles_to_accommodation: Some(3),
        first_sticking_cycle: (ratio > 1.0).then_some(1),
        sticks: ratio > 1.0,
        closes: true,
        validity_holds: true,
        accommodation_cause: None,
        contact_resistance: None,
        real_contact_fraction: None,
    }
}

/// ratio = (x0 / x)^p: critical value x0, free above.
pub fn power(x0: f64, p: f64) -> impl Fn(f64) -> Result<DesignPoint, PointError> + Sync {
    move |x| Ok(point((x0 / x).powf(p), x))
}

/// The number of axis `k` of a numeric grid point.
pub fn num(values: &[(&str, Level)], k: usize) -> f64 {
    values[k].1.number().expect("a numeric axis")
}

/// 2-D: ratio = (x0/x)^2 * (y/y0): boundary y = y0 (x/x0)^2.
pub fn product(values: &[(&str, Level)]) -> Result<DesignPoint, PointError> {
    let (x, y) = (num(values, 0), num(values, 1));
    Ok(point((2e3 / x).powi(2) * (y / 1e-8), x))
}

/// 1-D: ratio = (x0/x)^1.5 with a few failing points and one out of domain.
pub fn flaky(values: &[(&str, Level)]) -> Result<DesignPoint, PointError> {
    let x = num(values, 0);
    if (x - 500.0).abs() < 1e-9 {
        return Err(PointError::Failed("solver did not converge".into()));
    }
    if x < 150.0 {
        return Err(PointError::OutOfDomain(format!(
            "switch.k_s = {x} below 150"
        )));
    }
    if (x - 900.0).abs() < 1e-9 {
        panic!("a bug in the evaluator");
    }
    if x > 1800.0 {
        return Ok(DesignPoint::does_not_close(x));
    }
    Ok(point((1e3 / x).powf(1.5), x))
}

/// The trimmed text of every `<text>` element of an SVG document.
pub fn svg_texts<'a>(doc: &'a roxmltree::Document) -> Vec<&'a str> {
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(str::trim))
        .collect()
}
