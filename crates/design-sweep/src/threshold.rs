//! The critical value(s) of one field where the pull-out ratio crosses 1.

use crate::grid::{spaced, Spacing};
use crate::point::{check_field, guarded, DesignPoint, PointError};
use crate::requirement::Requirement;
use crate::DesignError;
use contact_core::numeric::{zeroin, Sample, ZeroinStop};
use rayon::prelude::*;
use serde::Serialize;

/// The side of a crossing (in increasing value) where the ratio is below 1, or, without a
/// crossing, whether the whole range is free.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FreeSide {
    /// Free (ratio < 1) for values above the critical value.
    Above,
    /// Free for values below the critical value.
    Below,
    /// No crossing: every evaluated point of the range is free.
    WholeRange,
    /// No crossing: no evaluated point of the range is free (a switch that does not close
    /// is not free).
    Nowhere,
    /// No crossing: every closing point of the range is free, but some points do not
    /// close (see the closure boundary).
    WhereItCloses,
}

impl FreeSide {
    /// `above`, `below`, `whole_range`, `nowhere`.
    pub fn word(&self) -> &'static str {
        match self {
            FreeSide::Above => "above",
            FreeSide::Below => "below",
            FreeSide::WholeRange => "whole_range",
            FreeSide::Nowhere => "nowhere",
            FreeSide::WhereItCloses => "where_it_closes",
        }
    }
}

/// How the ratio crosses 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CrossingKind {
    /// The ratio passes continuously through 1.
    Continuous,
    /// The ratio jumps across 1 (e.g. from 0, does not close, to a sticking point).
    Jump,
    /// A point failed while the crossing was being refined: the bracket is reported.
    Unresolved,
}

impl CrossingKind {
    /// `continuous`, `jump`, `unresolved`.
    pub fn word(&self) -> &'static str {
        match self {
            CrossingKind::Continuous => "continuous",
            CrossingKind::Jump => "jump",
            CrossingKind::Unresolved => "unresolved",
        }
    }
}

/// Settings of a threshold search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThresholdOptions {
    /// Relative tolerance on the critical value (in (0, 0.1]). On a lin scan whose range
    /// contains 0 it is at least `tolerance * 1e-6 * max(|from|, |to|)` in absolute terms.
    pub tolerance: f64,
    /// Relative error of the ratio itself, from the accuracy mode (see
    /// [`ratio_rel_error`]); enters the reported uncertainty.
    pub ratio_rel_error: f64,
    /// Scan points; `None` chooses 9 (lin) or 9 to 17 (log, 4 per decade).
    pub scan_points: Option<usize>,
}

impl ThresholdOptions {
    /// The scan points of a search over [`from`, `to`] (before its refinement): the given
    /// count, or 9 on a lin scan and 4 per decade (9 to 17) on a log scan, the scan being
    /// log when both ends are positive and a decade or more apart.
    pub fn scan_points_over(&self, from: f64, to: f64) -> usize {
        let (lo, hi) = (from.min(to), from.max(to));
        let log = lo > 0.0 && hi / lo >= 10.0;
        match self.scan_points {
            Some(n) => n,
            None if log => (4 * (hi / lo).log10().ceil() as usize + 1).clamp(9, 17),
            None => 9,
        }
    }
}

impl Default for ThresholdOptions {
    fn default() -> Self {
        ThresholdOptions {
            tolerance: 1e-6,
            ratio_rel_error: 1e-6,
            scan_points: None,
        }
    }
}

/// The relative error of the pull-out ratio for an accuracy mode: `accurate` 1e-8,
/// `balanced` 1e-6, `fast` 1e-4; `None` for another name.
pub fn ratio_rel_error(accuracy: &str) -> Option<f64> {
    match accuracy {
        "accurate" => Some(1e-8),
        "balanced" => Some(1e-6),
        "fast" => Some(1e-4),
        _ => None,
    }
}

/// One evaluated scan point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScanPoint {
    /// The field value.
    pub value: f64,
    /// `ok`, `does_not_close`, `out_of_domain` or `failed`.
    pub status: &'static str,
    /// The failure message, for `out_of_domain` and `failed`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
    /// The ratio, for `ok` and `does_not_close`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pull_out_ratio: Option<f64>,
    /// Whether the switch closes, for `ok` and `does_not_close`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub closes: Option<bool>,
    /// Whether the model holds at the point, for `ok` and `does_not_close`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub validity_holds: Option<bool>,
    /// Contact resistance under the hold voltage (ohm), when computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_resistance: Option<f64>,
    /// Real contact area fraction under the hold voltage, when computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub real_contact_fraction: Option<f64>,
    /// Whether it meets the requirement, with one (absent where the quantity is).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meets_requirement: Option<bool>,
}

/// One crossing of ratio = 1.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Crossing {
    /// The critical value (secant estimate in the final bracket; its midpoint for a jump).
    pub critical_value: f64,
    /// The side where the ratio is below 1.
    pub free_side: FreeSide,
    /// Continuous, jump or unresolved.
    pub kind: CrossingKind,
    /// Uncertainty of the critical value, same unit: ratio error / |d ln ratio / d ln
    /// value| × value + the root tolerance; half the bracket for a jump or unresolved.
    pub uncertainty: f64,
    /// The final bracket, ascending.
    pub bracket: [f64; 2],
    /// The ratios at the bracket ends.
    pub ratio_at_bracket: [f64; 2],
    /// d ln(ratio) / d ln(value) across the final bracket (continuous crossings only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slope: Option<f64>,
    /// Evaluations spent refining this crossing (after the scan).
    pub evaluations: usize,
    /// Why an unresolved crossing could not be refined.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
}

/// Where the switch stops closing (the electrode no longer reaches contact), between two
/// evaluated points: a design boundary of its own, never a stiction boundary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClosureBoundary {
    /// The value: the midpoint of the final bracket.
    pub value: f64,
    /// The side where the switch closes (`above` or `below` the value).
    pub closes_side: FreeSide,
    /// Half the final bracket.
    pub uncertainty: f64,
    /// The final bracket, ascending.
    pub bracket: [f64; 2],
    /// Evaluations spent refining it (after the scan).
    pub evaluations: usize,
    /// Why it could not be refined, if it could not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
}

/// Where a second requirement (`--require contact_resistance<1`) flips along the field,
/// and the window where the design is both free of stiction and meets it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RequirementReport {
    /// The requirement, as `contact_resistance<1e0`.
    pub requirement: Requirement,
    /// Every value where the requirement flips, ascending.
    pub crossings: Vec<RequirementCrossing>,
    /// The intervals [lo, hi] of the range where the switch closes, is free of stiction
    /// and meets the requirement, ascending (empty: no such design in the range). Their
    /// ends are crossings and closure boundaries, within their uncertainties.
    pub window: Vec<[f64; 2]>,
}

/// One value where the requirement flips.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RequirementCrossing {
    /// The value (secant estimate in the final bracket).
    pub value: f64,
    /// The side where the requirement is met (`above` or `below`).
    pub met_side: FreeSide,
    /// Half the final bracket, plus the root tolerance.
    pub uncertainty: f64,
    /// The final bracket, ascending.
    pub bracket: [f64; 2],
    /// Why it could not be refined, if it could not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
}

/// The answer of a threshold search. Top-level `critical_value`, `free_side`, `kind` and
/// `uncertainty` are those of the first crossing of ratio = 1 between closing designs
/// (lowest value); without one, `critical_value` is null, `kind` and `uncertainty` are
/// absent and `free_side` is `whole_range`, `where_it_closes` or `nowhere`. A switch that
/// does not close is never on the free side: where the switch stops closing is
/// `closure_boundary` (null when it closes everywhere or nowhere in the range).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Threshold {
    /// The varied field.
    pub parameter: String,
    /// Critical value of the first crossing (null: none between closing designs).
    pub critical_value: Option<f64>,
    /// Free side of the first crossing, or of the whole range.
    pub free_side: FreeSide,
    /// Kind of the first crossing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kind: Option<CrossingKind>,
    /// Uncertainty of the first crossing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub uncertainty: Option<f64>,
    /// Ratio at `from` (absent if that point failed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio_at_from: Option<f64>,
    /// Ratio at `to` (absent if that point failed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio_at_to: Option<f64>,
    /// Evaluator calls in all (scan and refinement).
    pub evaluations: usize,
    /// Range start as given.
    pub from: f64,
    /// Range end as given.
    pub to: f64,
    /// Spacing of the scan (and coordinate of the refinement: ln(value) for log).
    pub spacing: Spacing,
    /// Relative tolerance on the critical value.
    pub tolerance: f64,
    /// Relative error of the ratio assumed for the uncertainty.
    pub ratio_rel_error: f64,
    /// Every crossing, ascending value.
    pub crossings: Vec<Crossing>,
    /// Where the switch stops closing, the first (lowest value) of `closure_boundaries`
    /// (null: it closes everywhere or nowhere in the range).
    pub closure_boundary: Option<f64>,
    /// Every closure boundary, ascending value.
    pub closure_boundaries: Vec<ClosureBoundary>,
    /// The scan, ascending value.
    pub scan: Vec<ScanPoint>,
    /// The second requirement, its crossings and the design window (absent without one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub requirement: Option<RequirementReport>,
}

impl Threshold {
    /// The scan points that failed (status `out_of_domain` or `failed`).
    pub fn failed_points(&self) -> impl Iterator<Item = &ScanPoint> {
        self.scan.iter().filter(|p| p.pull_out_ratio.is_none())
    }

    /// Pretty JSON with a final newline.
    pub fn to_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(self).expect("a threshold always serialises");
        s.push('\n');
        s
    }
}

/// Largest evaluations spent on refining one crossing.
const MAX_REFINE_EVALUATIONS: usize = 200;

/// The zeroin refinement of one sign change of `f` between `a` and `b` (to `width`), and
/// why it stopped early if it did: a failed point, or the evaluation cap.
fn refine(
    f: impl FnMut(f64) -> Result<f64, String>,
    a: Sample,
    b: Sample,
    width: &dyn Fn(f64) -> f64,
) -> (contact_core::numeric::Bracket, Option<String>) {
    match zeroin(f, a, b, width, MAX_REFINE_EVALUATIONS) {
        Ok(b) => (b, None),
        Err(ZeroinStop::Failed(m, b)) => (b, Some(m)),
        Err(ZeroinStop::NoConvergence(b)) => {
            let m = format!("no convergence after {} evaluations", b.evaluations);
            (b, Some(m))
        }
    }
}

/// Finds where `pull_out_ratio = 1` as `field` goes from `from` to `to`.
///
/// Scans the range (log-spaced when both ends are > 0 and span a decade or more; the scan
/// points are evaluated in parallel on the current rayon pool), then refines every sign
/// change of ln(ratio) between neighbouring successful scan points with a Brent-Dekker
/// zero-in in ln(value) (log) or value (lin), falling back to bisection where a point does
/// not close (ratio 0). Where the switch stops closing between two scan points, the closure
/// boundary is refined and the ratio at its closing side is compared with the closing scan
/// point's, so a design free of stiction just where the switch starts (or stops) closing is
/// found even with no scan point in it. Failed scan points are reported and skipped. Other
/// pairs of crossings closer than the scan spacing can be missed. Errors only on invalid input or when every scan point
/// fails.
pub fn threshold<F, E>(
    field: &str,
    from: f64,
    to: f64,
    eval: F,
    options: &ThresholdOptions,
) -> Result<Threshold, DesignError>
where
    F: Fn(f64) -> Result<DesignPoint, E> + Sync,
    E: Into<PointError>,
{
    threshold_with(field, from, to, eval, options, None)
}

/// [`threshold`] with a second requirement: besides the crossings of ratio = 1, every
/// sign change of the requirement's margin ln(q / limit) between neighbouring closing
/// scan points is refined the same way, and the range is cut at every crossing and closure
/// boundary into pieces whose state is read at a scan point inside (or evaluated at the
/// piece's middle): the window is the union of the pieces free of stiction that meet the
/// requirement.
pub fn threshold_with<F, E>(
    field: &str,
    from: f64,
    to: f64,
    eval: F,
    options: &ThresholdOptions,
    requirement: Option<&Requirement>,
) -> Result<Threshold, DesignError>
where
    F: Fn(f64) -> Result<DesignPoint, E> + Sync,
    E: Into<PointError>,
{
    let bad = |m: String| DesignError::Threshold(m);
    check_field(field).map_err(bad)?;
    if !(from.is_finite() && to.is_finite()) {
        return Err(bad(format!(
            "the ends of the range {from:e} and {to:e} must be finite numbers"
        )));
    }
    if from == to {
        return Err(bad(format!(
            "both ends of the range are {from:e}: they must differ"
        )));
    }
    let ThresholdOptions {
        tolerance,
        ratio_rel_error,
        scan_points,
    } = *options;
    if !(tolerance.is_finite() && tolerance > 0.0 && tolerance <= 0.1) {
        return Err(bad(format!("tolerance {tolerance} must be in (0, 0.1]")));
    }
    if !(ratio_rel_error.is_finite() && ratio_rel_error >= 0.0) {
        return Err(bad(format!(
            "ratio relative error {ratio_rel_error} must be finite and >= 0"
        )));
    }
    let (lo, hi) = (from.min(to), from.max(to));
    let log = lo > 0.0 && hi / lo >= 10.0;
    let spacing = if log { Spacing::Log } else { Spacing::Lin };
    let n = match scan_points {
        Some(n) if !(3..=1001).contains(&n) => {
            return Err(bad(format!("scan points {n} must be in 3..=1001")))
        }
        _ => options.scan_points_over(from, to),
    };
    let to_u = |x: f64| if log { x.ln() } else { x };
    let from_u = |u: f64| if log { u.exp() } else { u };
    let floor = tolerance * 1e-6 * lo.abs().max(hi.abs());
    let tol_u = |u: f64| {
        if log {
            tolerance
        } else {
            (tolerance * u.abs()).max(floor)
        }
    };

    let xs = spaced(lo, hi, spacing, n);
    let evaluated: Vec<_> = xs.par_iter().map(|&x| guarded(|| eval(x))).collect();
    // (u, closes, ln ratio) of the points that ran
    let ran: Vec<(f64, bool, f64)> = xs
        .iter()
        .zip(&evaluated)
        .filter_map(|(&x, (_, d))| d.map(|d| (to_u(x), d.closes, d.pull_out_ratio.ln())))
        .collect();
    let scan: Vec<ScanPoint> = xs
        .iter()
        .zip(&evaluated)
        .map(|(&value, (status, design))| ScanPoint {
            value,
            status: status.word(),
            detail: status.detail().map(str::to_owned),
            pull_out_ratio: design.map(|d| d.pull_out_ratio),
            closes: design.map(|d| d.closes),
            validity_holds: design.map(|d| d.validity_holds),
            contact_resistance: design.and_then(|d| d.contact_resistance),
            real_contact_fraction: design.and_then(|d| d.real_contact_fraction),
            meets_requirement: requirement.and_then(|r| design.and_then(|d| r.met(&d))),
        })
        .collect();
    if ran.is_empty() {
        return Err(DesignError::ScanFailed {
            parameter: field.to_owned(),
            points: n,
            value: scan[0].value,
            detail: scan[0].detail.clone().unwrap_or_default(),
        });
    }

    // ln ratio of a closing design; a design that does not close has no ratio to cross 1
    let g = |u: f64| -> Result<f64, String> {
        let x = from_u(u);
        match guarded(|| eval(x)) {
            (_, Some(d)) if d.closes => Ok(d.pull_out_ratio.ln()),
            (_, Some(_)) => Err(format!(
                "does_not_close at {x:e}: the switch stops closing inside the bracket"
            )),
            (s, None) => Err(format!(
                "{} at {x:e}: {}",
                s.word(),
                s.detail().unwrap_or_default()
            )),
        }
    };
    // +1 where the switch closes, -1 where it does not
    let c = |u: f64| -> Result<f64, String> {
        let x = from_u(u);
        match guarded(|| eval(x)) {
            (_, Some(d)) => Ok(if d.closes { 1.0 } else { -1.0 }),
            (s, None) => Err(format!(
                "{} at {x:e}: {}",
                s.word(),
                s.detail().unwrap_or_default()
            )),
        }
    };
    let mut evaluations = n;
    // the crossing of ratio = 1 refined between two closing designs (u, ln ratio) whose
    // ratios lie on either side of 1
    let crossing = |(ua, ga): (f64, f64), (ub, gb): (f64, f64)| -> Crossing {
        let free_side = if ga < 0.0 {
            FreeSide::Below
        } else {
            FreeSide::Above
        };
        let (found, detail) = refine(g, Sample { x: ua, f: ga }, Sample { x: ub, f: gb }, &tol_u);
        let (near, far) = (found.best, found.other);
        let (u1, g1, u2, g2) = if near.x <= far.x {
            (near.x, near.f, far.x, far.f)
        } else {
            (far.x, far.f, near.x, near.f)
        };
        let (x1, x2) = (from_u(u1), from_u(u2));
        let half = 0.5 * (x2 - x1).abs();
        let mid = from_u(0.5 * (u1 + u2));
        let scan_slope = ((gb - ga) / (ub - ua)).abs();
        let jump_limit = if scan_slope.is_finite() {
            0.05f64.max(100.0 * scan_slope * (u2 - u1))
        } else {
            0.05
        };
        let kind = if detail.is_some() {
            CrossingKind::Unresolved
        } else if !(g1.is_finite() && g2.is_finite()) || (g2 - g1).abs() > jump_limit {
            CrossingKind::Jump
        } else {
            CrossingKind::Continuous
        };
        let (critical_value, uncertainty, slope) = match kind {
            CrossingKind::Continuous => {
                let u = if g2 == g1 {
                    found.best.x
                } else {
                    (u1 - g1 * (u2 - u1) / (g2 - g1)).clamp(u1, u2)
                };
                let x = from_u(u);
                let du = u2 - u1;
                // d ln ratio / d ln x
                let s = if du > 0.0 {
                    let d = (g2 - g1) / du;
                    if log {
                        d
                    } else {
                        d * x
                    }
                } else {
                    f64::NAN
                };
                let tol_x = if log { tolerance * x.abs() } else { tol_u(x) };
                let unc = if s.is_finite() && s != 0.0 {
                    ratio_rel_error / s.abs() * x.abs() + tol_x
                } else {
                    tol_x.max(half)
                };
                (x, unc, s.is_finite().then_some(s))
            }
            _ => (mid, half, None),
        };
        Crossing {
            critical_value,
            free_side,
            kind,
            uncertainty,
            bracket: [x1, x2],
            ratio_at_bracket: [g1.exp(), g2.exp()],
            slope,
            evaluations: found.evaluations,
            detail,
        }
    };
    let mut crossings = Vec::new();
    let mut closure_boundaries = Vec::new();
    for w in ran.windows(2) {
        let ((ua, ca, ga), (ub, cb, gb)) = (w[0], w[1]);
        if ca != cb {
            let closes_side = if ca { FreeSide::Below } else { FreeSide::Above };
            let sa = if ca { 1.0 } else { -1.0 };
            let (found, detail) =
                refine(c, Sample { x: ua, f: sa }, Sample { x: ub, f: -sa }, &tol_u);
            evaluations += found.evaluations;
            let (x1, x2) = (from_u(found.best.x), from_u(found.other.x));
            let (x1, x2) = (x1.min(x2), x1.max(x2));
            closure_boundaries.push(ClosureBoundary {
                value: from_u(0.5 * (to_u(x1) + to_u(x2))),
                closes_side,
                uncertainty: 0.5 * (x2 - x1),
                bracket: [x1, x2],
                evaluations: found.evaluations,
                detail: detail.clone(),
            });
            // between the closure boundary and the closing scan point the ratio may cross
            // 1 too (a design free of stiction just where the switch starts to close): the
            // closing end of the final bracket is a closing design, whose ratio is compared
            // with the scan point's
            if detail.is_none() {
                let (u_scan, g_scan) = if ca { (ua, ga) } else { (ub, gb) };
                let u_edge = if found.best.f > 0.0 {
                    found.best.x
                } else {
                    found.other.x
                };
                evaluations += 1;
                if let Ok(g_edge) = g(u_edge) {
                    if (g_edge < 0.0) != (g_scan < 0.0) {
                        let (a, b) = if u_edge < u_scan {
                            ((u_edge, g_edge), (u_scan, g_scan))
                        } else {
                            ((u_scan, g_scan), (u_edge, g_edge))
                        };
                        let found = crossing(a, b);
                        evaluations += found.evaluations;
                        crossings.push(found);
                    }
                }
            }
            continue;
        }
        if !ca || (ga < 0.0) == (gb < 0.0) {
            continue;
        }
        let found = crossing((ua, ga), (ub, gb));
        evaluations += found.evaluations;
        crossings.push(found);
    }
    crossings.sort_by(|a, b| a.critical_value.total_cmp(&b.critical_value));

    let requirement = match requirement {
        None => None,
        Some(r) => {
            let report = requirement_report(
                r,
                &xs,
                &evaluated,
                &crossings,
                &closure_boundaries,
                &eval,
                log,
                &tol_u,
                &mut evaluations,
            );
            Some(report)
        }
    };
    let ratio_of = |i: usize| scan[i].pull_out_ratio;
    let (ratio_at_from, ratio_at_to) = if from < to {
        (ratio_of(0), ratio_of(n - 1))
    } else {
        (ratio_of(n - 1), ratio_of(0))
    };
    let first = crossings.first();
    let closing: Vec<&(f64, bool, f64)> = ran.iter().filter(|r| r.1).collect();
    let free_side = match first {
        Some(c) => c.free_side,
        None if closing.is_empty() || closing[0].2 >= 0.0 => FreeSide::Nowhere,
        None if closing.len() == ran.len() => FreeSide::WholeRange,
        None => FreeSide::WhereItCloses,
    };
    Ok(Threshold {
        parameter: field.to_owned(),
        critical_value: first.map(|c| c.critical_value),
        free_side,
        kind: first.map(|c| c.kind),
        uncertainty: first.map(|c| c.uncertainty),
        ratio_at_from,
        ratio_at_to,
        evaluations,
        from,
        to,
        spacing,
        tolerance,
        ratio_rel_error,
        crossings,
        closure_boundary: closure_boundaries.first().map(|b| b.value),
        closure_boundaries,
        scan,
        requirement,
    })
}

/// The crossings of a requirement and the design window (see [`threshold_with`]).
#[allow(clippy::too_many_arguments)]
fn requirement_report<F, E>(
    r: &Requirement,
    xs: &[f64],
    evaluated: &[(crate::point::Status, Option<DesignPoint>)],
    crossings: &[Crossing],
    closures: &[ClosureBoundary],
    eval: &F,
    log: bool,
    tol_u: &dyn Fn(f64) -> f64,
    evaluations: &mut usize,
) -> RequirementReport
where
    F: Fn(f64) -> Result<DesignPoint, E> + Sync,
    E: Into<PointError>,
{
    let to_u = |x: f64| if log { x.ln() } else { x };
    let from_u = |u: f64| if log { u.exp() } else { u };
    // (u, margin) of the scan points that close and have the quantity
    let with_margin: Vec<(f64, f64)> = xs
        .iter()
        .zip(evaluated)
        .filter_map(|(&x, (_, d))| {
            let d = d.as_ref()?;
            d.closes
                .then(|| r.margin(d))
                .flatten()
                .map(|m| (to_u(x), m))
        })
        .collect();
    let margin = |u: f64| -> Result<f64, String> {
        let x = from_u(u);
        match guarded(|| eval(x)) {
            (_, Some(d)) if d.closes => r.margin(&d).ok_or_else(|| {
                format!(
                    "no {} at {x:e} (the switch opens under the hold voltage)",
                    r.quantity.name()
                )
            }),
            (_, Some(_)) => Err(format!("does_not_close at {x:e}")),
            (s, None) => Err(format!(
                "{} at {x:e}: {}",
                s.word(),
                s.detail().unwrap_or_default()
            )),
        }
    };
    let mut found = Vec::new();
    for w in with_margin.windows(2) {
        let ((ua, ma), (ub, mb)) = (w[0], w[1]);
        if (ma < 0.0) == (mb < 0.0) {
            continue;
        }
        let met_side = if ma < 0.0 {
            FreeSide::Below
        } else {
            FreeSide::Above
        };
        let (b, detail) = refine(
            margin,
            Sample { x: ua, f: ma },
            Sample { x: ub, f: mb },
            &tol_u,
        );
        *evaluations += b.evaluations;
        let (p, q) = if b.best.x <= b.other.x {
            (b.best, b.other)
        } else {
            (b.other, b.best)
        };
        let u = if q.f != p.f && detail.is_none() {
            (p.x - p.f * (q.x - p.x) / (q.f - p.f)).clamp(p.x, q.x)
        } else {
            0.5 * (p.x + q.x)
        };
        let (x1, x2) = (from_u(p.x), from_u(q.x));
        let value = from_u(u);
        found.push(RequirementCrossing {
            value,
            met_side,
            uncertainty: 0.5 * (x2 - x1) + if log { tol_u(u) * value } else { tol_u(u) },
            bracket: [x1, x2],
            detail,
        });
    }
    // cut the range at every boundary; read each piece's state
    let (lo, hi) = (xs[0], xs[xs.len() - 1]);
    let mut cuts: Vec<f64> = crossings
        .iter()
        .map(|c| c.critical_value)
        .chain(closures.iter().map(|c| c.value))
        .chain(found.iter().map(|c| c.value))
        .filter(|v| *v > lo && *v < hi)
        .collect();
    cuts.push(lo);
    cuts.push(hi);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut window: Vec<[f64; 2]> = Vec::new();
    for piece in cuts.windows(2) {
        let (a, b) = (piece[0], piece[1]);
        let inside = xs
            .iter()
            .zip(evaluated)
            .find(|(x, (_, d))| **x > a && **x < b && d.is_some())
            .and_then(|(_, (_, d))| *d);
        let design = match inside {
            Some(d) => Some(d),
            None => {
                *evaluations += 1;
                guarded(|| eval(from_u(0.5 * (to_u(a) + to_u(b))))).1
            }
        };
        if design.is_some_and(|d| r.in_window(&d)) {
            match window.last_mut() {
                Some(last) if last[1] == a => last[1] = b,
                _ => window.push([a, b]),
            }
        }
    }
    RequirementReport {
        requirement: *r,
        crossings: found,
        window,
    }
}
