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

// ---- probability stand-ins

use design_sweep::{run_probability, Correlation, Probability, ProbabilityPlan, Scatter};

/// Cycles of the probability stand-ins.
pub const CYCLES: usize = 10;

/// A switch whose pull-out ratio after accommodation is `ratio`, reached over the cycles as
/// ratio_n = ratio (1 - 2^-n) / (1 - 2^-CYCLES): the first sticking cycle is the first n
/// with ratio_n > 1.
pub fn cycled(ratio: f64, restoring: f64) -> DesignPoint {
    let mut d = point(ratio, restoring);
    let g = |n: usize| (1.0 - 0.5f64.powi(n as i32)) / (1.0 - 0.5f64.powi(CYCLES as i32));
    d.first_sticking_cycle = (1..=CYCLES).find(|&n| ratio * g(n) > 1.0);
    d.sticks = d.first_sticking_cycle.is_some();
    d
}

pub fn plan(scatter: &[&str], samples: usize, seed: u64) -> ProbabilityPlan {
    ProbabilityPlan {
        scene: serde_json::json!({"title": "stand-in"}),
        accuracy: "fast".into(),
        ratio_rel_error: 1e-4,
        scatter: scatter.iter().map(|s| Scatter::parse(s).unwrap()).collect(),
        correlations: Vec::new(),
        seed,
        samples,
        confidence: 0.95,
        cycles: CYCLES,
        target_halfwidth: None,
        shard: None,
        count_outside_validity: false,
    }
}

pub fn run<F>(p: ProbabilityPlan, f: F) -> Probability
where
    F: Fn(&[(&str, f64)]) -> Result<DesignPoint, PointError> + Sync,
{
    run_probability(p, f, |_, _| {}).unwrap()
}

/// A stand-in with every kind of sample: failures, refusals, outside validity, switches
/// that do not close, and a panic.
pub fn mixed(v: &[(&str, f64)]) -> Result<DesignPoint, PointError> {
    let (k, w) = (v[0].1, v[1].1);
    if k < 2.0 {
        return Err(PointError::OutOfDomain(format!("switch.k_s = {k} below 2")));
    }
    if (4.0..4.1).contains(&k) {
        return Err(PointError::Failed("no convergence".into()));
    }
    if (5.0..5.1).contains(&k) {
        panic!("a bug");
    }
    if k > 9.0 {
        return Ok(DesignPoint::does_not_close(k));
    }
    let mut d = cycled(w * 6.0 / k, k);
    if w > 1.3 {
        d.validity_holds = false;
    }
    Ok(d)
}

pub fn mixed_plan(samples: usize) -> ProbabilityPlan {
    let mut p = plan(
        &[
            "switch.k_s=uniform(1.5,10)",
            "contact.work_of_adhesion=lognormal(1,1.2)",
        ],
        samples,
        42,
    );
    p.correlations = vec![Correlation::parse("switch.k_s,contact.work_of_adhesion=0.3").unwrap()];
    p
}

/// The maps' fixtures: the paper-like base scene, a request of grid `specs` in balanced
/// mode, the 13 x 7 grid, and its map of [`product`](super::product).
pub mod maps {
    use design_sweep::{run_map, Grid, Map, MapRequest, Shard};
    use serde_json::{json, Value};

    pub fn scene() -> Value {
        json!({"switch": {"d0": 2e-6, "k_s": 1.234567890123e3}, "name": "paper", "surface": {"sigma_s": 3.1e-9}})
    }

    pub fn request(specs: &[&str], shard: Option<Shard>) -> MapRequest {
        MapRequest {
            scene: scene(),
            grid: Grid::parse(specs).unwrap(),
            accuracy: "balanced".into(),
            shard,
        }
    }

    pub const GRID_2D: [&str; 2] = [
        "switch.k_s=3e2:3e4:log:13",
        "surface.sigma_s=1e-9:9e-9:lin:7",
    ];

    pub fn run(specs: &[&str], shard: Option<Shard>) -> Map {
        run_map(request(specs, shard), super::product, |_, _| {})
    }
}

/// The categorical maps' fixtures: a switch whose law scales the pull-out.
pub mod laws {
    use design_sweep::{run_map, DesignPoint, Grid, Level, Map, MapRequest, PointError, Shard};
    use serde_json::json;

    pub const LAWS: &str = "contact.plasticity_law=etsion_kadin,kogut_etsion,elastic";

    /// A stand-in for a switch whose law scales the pull-out: ratio = c_law (2e3 / k)^2,
    /// with c = 1 (etsion_kadin), 2 (kogut_etsion), 0.5 (elastic); critical k = 2e3 sqrt(c).
    pub fn scale(word: &str) -> Option<f64> {
        match word {
            "etsion_kadin" => Some(1.0),
            "kogut_etsion" => Some(2.0),
            "elastic" => Some(0.5),
            _ => None,
        }
    }

    pub fn by_law(values: &[(&str, Level)]) -> Result<DesignPoint, PointError> {
        let mut c = 1.0;
        let mut k = 1e3;
        for (field, v) in values {
            match (*field, v) {
                ("contact.plasticity_law", Level::Word(w)) => {
                    c = scale(w).ok_or_else(|| PointError::OutOfDomain(format!("no law {w}")))?
                }
                ("switch.k_s", Level::Number(x)) => k = *x,
                ("contact.reload", Level::Word(_)) => {}
                (f, v) => return Err(PointError::Failed(format!("unexpected {f} = {v}"))),
            }
        }
        Ok(super::point(c * (2e3 / k).powi(2), k))
    }

    pub fn request(specs: &[&str], shard: Option<Shard>) -> MapRequest {
        MapRequest {
            scene: json!({"name": "laws"}),
            grid: Grid::parse(specs).unwrap(),
            accuracy: "fast".into(),
            shard,
        }
    }

    pub fn run(specs: &[&str], shard: Option<Shard>) -> Map {
        run_map(request(specs, shard), by_law, |_, _| {})
    }
}
