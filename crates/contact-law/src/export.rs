//! The law's virgin loading as a pressure-overclosure table for an FE code's tabular
//! contact (`*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR` of CalculiX and Abaqus;
//! issue 46, docs/contact-law.md section 6).
//!
//! A table holds one curve: the overclosure h = d_ref - d against the compressive pressure
//! of a never-pressed surface, from (0, 0) at d_ref (where the virgin loading turns
//! compressive) down to the deepest separation the law covers. The rows are placed so that
//! *linear* interpolation between them (what the FE codes do) stays within a tolerance of
//! the law in the law's own error metric, |p_lin - p| / (|p| + |p_pull_out| + floor), with
//! the virgin curve's most tensile pressure as the pull-out: the law's 184 cubic nodes are
//! not a linear table. What a table cannot carry (unloading and reloading with the history
//! d_min, the adhesive tension above d_ref, the pressure beyond the deepest row) is said in
//! the block's comments.

use crate::error::{fmt_num, LawError};
use crate::ContactLaw;

/// The most rows an exported table holds: CalculiX's node-to-surface contact resamples a
/// table of more than 200 points without a word.
pub const MAX_ROWS: usize = 200;

/// The default tolerance of the linear table, in the law's error metric.
pub const EXPORT_TOLERANCE: f64 = 1e-3;

/// Interior points per interval at which the linear table is checked against the law.
const CHECKS: usize = 16;
/// Samples of the virgin loading that place the rows.
const DENSE: usize = 4000;

/// A pressure-overclosure table of the virgin loading (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct OverclosureTable {
    /// The separation (m) where the virgin loading turns compressive: overclosure 0.
    pub d_ref: f64,
    /// (overclosure h = d_ref - d in m, pressure in Pa), from (0, 0), h increasing.
    pub rows: Vec<(f64, f64)>,
    /// The largest error of linear interpolation found at the checks, in the law's metric.
    pub max_error: f64,
    /// The tolerance the rows were placed for.
    pub tolerance: f64,
    /// The virgin curve's most tensile pressure (Pa, <= 0): the adhesion a table drops.
    pub tension: f64,
}

/// The units of an exported block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InpUnits {
    /// Micrometres and megapascals (the default: CalculiX moves table spacings under 1e-10
    /// model units, which a table in metres has).
    MicrometreMegapascal,
    /// Metres and pascals.
    Si,
}

impl InpUnits {
    /// (length per metre, pressure per pascal, the comment's words).
    fn scales(self) -> (f64, f64, &'static str) {
        match self {
            InpUnits::MicrometreMegapascal => (1e6, 1e-6, "um, MPa"),
            InpUnits::Si => (1.0, 1.0, "m, Pa"),
        }
    }
}

/// The FE code whose keyword block is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InpDialect {
    /// CalculiX (ccx).
    Calculix,
    /// Abaqus/Standard.
    Abaqus,
}

impl ContactLaw {
    /// The virgin loading as a linear pressure-overclosure table within `tolerance` (in
    /// (0, 0.1]) of the law in its own error metric, in at most `max_rows` rows (2 to
    /// [`MAX_ROWS`]), every interval checked at 16 interior points. An error where the
    /// virgin loading never turns
    /// compressive, or where the rows cannot meet the tolerance.
    ///
    /// The rows equidistribute the interpolation error estimate w^2 |p''| / 8 (w an
    /// interval's width) relative to the metric's scale, as many as it takes.
    pub fn overclosure_table(
        &self,
        tolerance: f64,
        max_rows: usize,
    ) -> Result<OverclosureTable, LawError> {
        if !(tolerance > 0.0 && tolerance <= 0.1) {
            return Err(LawError::Invalid {
                name: "tolerance",
                value: fmt_num(tolerance),
                allowed: "in (0, 0.1]",
            });
        }
        if !(2..=MAX_ROWS).contains(&max_rows) {
            return Err(LawError::Invalid {
                name: "rows",
                value: max_rows.to_string(),
                allowed: "in [2, 200]",
            });
        }
        let v = &self.virgin;
        let (d, p) = (v.d(), v.pressure());
        let deepest = d[0];
        if !(p[0] > 0.0) {
            return Err(LawError::OutOfRange(format!(
                "the virgin loading is not compressive at the deepest separation tabulated, {} m: no pressure-overclosure table",
                fmt_num(deepest)
            )));
        }
        // d_ref: where the virgin loading last turns compressive, going in (the nodes
        // compressive from the deepest up to `i`, the root between i and i + 1)
        let i = p
            .iter()
            .position(|&x| !(x > 0.0))
            .map_or(d.len() - 1, |k| k - 1);
        let pv = |x: f64| self.virgin_pressure(x).map(|(p, _)| p);
        let d_ref = if i + 1 < d.len() {
            let (mut lo, mut hi) = (d[i], d[i + 1]);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if pv(mid)? > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            hi
        } else {
            d[i]
        };
        let tension = v.most_tensile().pressure.min(0.0);
        let scale = |p: f64| p.abs() + tension.abs() + self.floor;
        // the law at overclosure h, clamped to the compressive side (0 at and above d_ref)
        let at = |h: f64| -> Result<f64, LawError> {
            if h <= 0.0 {
                return Ok(0.0);
            }
            // never below the deepest node by a rounding of d_ref - h
            Ok(pv((d_ref - h).max(deepest))?.max(0.0))
        };
        let h_max = d_ref - deepest;
        // the worst check of the chord between (a, pa) and (b, pb)
        let worst = |a: f64, pa: f64, b: f64, pb: f64| -> Result<f64, LawError> {
            let mut e: f64 = 0.0;
            for k in 1..=CHECKS {
                let t = k as f64 / (CHECKS + 1) as f64;
                let h = a + t * (b - a);
                let exact = at(h)?;
                let lin = pa + t * (pb - pa);
                e = e.max((lin - exact).abs() / scale(exact));
            }
            Ok(e)
        };
        // rows where linear interpolation errs alike: an interval of width w errs by about
        // w^2 |p''|/8, so the rows are equidistributed in the integral of
        // sqrt(|p''| / (8 tolerance S(p))) (from dense samples, with a floor that keeps a row
        // in every stretch), and their number grows by 15 % until every interval, checked at
        // 16 interior points, is within the tolerance
        let n = DENSE;
        let hs: Vec<f64> = (0..=n).map(|k| h_max * k as f64 / n as f64).collect();
        let ps: Vec<f64> = hs.iter().map(|&h| at(h)).collect::<Result<_, _>>()?;
        let dh = h_max / n as f64;
        let mut density: Vec<f64> = (0..=n)
            .map(|k| {
                let (a, b) = (k.saturating_sub(1), (k + 1).min(n));
                let second = if b - a == 2 {
                    (ps[b] - 2.0 * ps[k] + ps[a]) / (dh * dh)
                } else {
                    0.0
                };
                (second.abs() / (8.0 * tolerance * scale(ps[k]))).sqrt()
            })
            .collect();
        let total: f64 = density.iter().sum::<f64>() * dh;
        let floor = 0.02 * total.max(1.0) / h_max;
        density.iter_mut().for_each(|d| *d += floor);
        let mut cumulative = vec![0.0; n + 1];
        for k in 1..=n {
            cumulative[k] = cumulative[k - 1] + 0.5 * (density[k] + density[k - 1]) * dh;
        }
        let whole = cumulative[n];
        let mut count = (whole.ceil() as usize + 2).clamp(2, max_rows);
        loop {
            let mut rows: Vec<(f64, f64)> = Vec::with_capacity(count);
            let mut k = 0;
            for r in 0..count {
                let target = whole * r as f64 / (count - 1) as f64;
                while k + 1 < n && cumulative[k + 1] < target {
                    k += 1;
                }
                let span = cumulative[k + 1] - cumulative[k];
                let t = if span > 0.0 {
                    ((target - cumulative[k]) / span).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let h = if r == 0 {
                    0.0
                } else if r == count - 1 {
                    h_max
                } else {
                    hs[k] + t * dh
                };
                rows.push((h, at(h)?));
            }
            rows.dedup_by(|b, a| b.0 <= a.0);
            let errors: Vec<f64> = rows
                .windows(2)
                .map(|w| worst(w[0].0, w[0].1, w[1].0, w[1].1))
                .collect::<Result<_, _>>()?;
            let e = errors.iter().copied().fold(0.0, f64::max);
            if e <= tolerance {
                return Ok(OverclosureTable {
                    d_ref,
                    rows,
                    max_error: e,
                    tolerance,
                    tension,
                });
            }
            if count >= max_rows {
                return Err(LawError::OutOfRange(format!(
                    "{max_rows} rows cannot hold the virgin loading within {} by linear interpolation (worst {}): raise the tolerance",
                    fmt_num(tolerance),
                    fmt_num(e)
                )));
            }
            count = ((count as f64 * 1.15).ceil() as usize).min(max_rows);
        }
    }
}

impl OverclosureTable {
    /// The keyword block for `dialect` in `units`: comments with d_ref (m), the units, the
    /// tolerance met and what the table cannot carry, then
    /// `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR` and one `pressure, overclosure`
    /// line per row (the keyword's order in both codes), the first `0, 0`.
    pub fn inp_block(&self, dialect: InpDialect, units: InpUnits) -> String {
        let (ls, ps, words) = units.scales();
        let code = match dialect {
            InpDialect::Calculix => "CalculiX",
            InpDialect::Abaqus => "Abaqus",
        };
        let (h_last, _) = *self.rows.last().expect("at least two rows");
        let mut s = String::new();
        s += &format!(
            "** stiction contact law: the virgin loading of the rough surface as a pressure-overclosure table ({code})\n"
        );
        s += &format!("** d_ref = {:e} m\n", self.d_ref);
        s += &format!("** units: {words}\n");
        s += "** overclosure h = d_ref - d, d the separation from the mean plane of the asperity heights to the flat\n";
        s += &format!(
            "** {} rows; linear interpolation within {:.3e} of the law (|p_lin - p| / (|p| + |p_pull_out| + floor)), largest found {:.3e}\n",
            self.rows.len(),
            self.tolerance,
            self.max_error
        );
        s += "** not carried by this table:\n";
        s += "**   unloading and reloading: the law's branches depend on the deepest separation d_min reached (law.json, the C ABI)\n";
        s += &format!(
            "**   adhesion: tension down to {:e} {} above d_ref (a table holds compressive pressures only)\n",
            self.tension * ps,
            words.split(", ").nth(1).unwrap_or("Pa")
        );
        s += &format!(
            "**   the law beyond the deepest row, h > {:e} {}: the FE code extends the table on its own\n",
            h_last * ls,
            words.split(", ").next().unwrap_or("m")
        );
        if units == InpUnits::Si && self.rows.windows(2).any(|w| (w[1].0 - w[0].0) * ls < 1e-10) {
            s += "**   CalculiX moves table spacings under 1e-10 model units: this table in m has such spacings; use um and MPa\n";
        }
        s += "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR\n";
        for &(h, p) in &self.rows {
            if h == 0.0 && p == 0.0 {
                s += "0, 0\n";
            } else {
                s += &format!("{:.10e}, {:.10e}\n", p * ps, h * ls);
            }
        }
        s
    }
}
