//! A law file evaluated (`stiction law eval`): one point or a file of points, as a table,
//! CSV or JSON.

use crate::render::{self, Render};
use serde::Serialize;
use std::fmt::Write as _;

/// Units of `stiction law eval`.
#[derive(Debug, Clone, Serialize)]
pub struct EvalUnits {
    /// Of d and d_min.
    pub d: &'static str,
    /// Of the pressure.
    pub pressure: &'static str,
    /// Of the tangent.
    pub tangent: &'static str,
}

/// The units `stiction law eval` reports in (SI).
pub const UNITS: EvalUnits = EvalUnits {
    d: "m",
    pressure: "Pa",
    tangent: "Pa/m",
};

/// One evaluated point of `stiction law eval`.
#[derive(Debug, Clone, Serialize)]
pub struct EvalPoint {
    /// Pressure (Pa), compressive positive, adhesive negative.
    pub pressure: f64,
    /// dp/dd (Pa/m) at fixed history.
    pub tangent: f64,
    /// The history after the call (m): d if the call deepened it.
    pub d_min: f64,
    /// The path after the call (`approach` when the history deepened).
    pub path: &'static str,
    /// The curve evaluated: `virgin`, `approach` or `retract`.
    pub curve: &'static str,
    /// Where the point lies: `measured` (inside the tabulated histories and the curve's
    /// reach: the file's measured error applies), `beyond_reach` (exactly zero: no asperity
    /// in contact) or `above_table` (a history shallower than the table: the law's blend to
    /// zero, not measured). A public contract.
    pub region: &'static str,
    /// The separation asked (m).
    pub d: f64,
    /// The history given (m), absent for a virgin surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub d_min_given: Option<f64>,
    /// The path given.
    pub path_given: &'static str,
}

/// `stiction law eval` at one point.
#[derive(Debug, Clone, Serialize)]
pub struct EvalReport {
    /// The point.
    #[serde(flatten)]
    pub point: EvalPoint,
    /// The tabulated histories of the law (m).
    pub law_d_min_range: [f64; 2],
    /// The law file.
    pub law: String,
    /// Units.
    pub units: EvalUnits,
}

/// `stiction law eval --points-file`.
#[derive(Debug, Clone, Serialize)]
pub struct EvalBatch {
    /// The points, in the order of the file.
    pub points: Vec<EvalPoint>,
    /// How many lie outside the measured region.
    pub outside_measured: usize,
    /// The tabulated histories of the law (m).
    pub law_d_min_range: [f64; 2],
    /// The law file.
    pub law: String,
    /// Units.
    pub units: EvalUnits,
}

/// The words of a region for the table.
fn region_words(region: &str) -> &'static str {
    match region {
        "measured" => "measured (the file's measured error applies)",
        "beyond_reach" => "beyond_reach (no asperity in contact: exactly zero)",
        _ => "above_table (a history shallower than the table: the law's blend to zero, NOT measured against the surface)",
    }
}

/// The CSV columns: d, the history and path after the call, pressure, tangent, region,
/// the history and path given.
const CSV_HEADER: &str =
    "d_m,d_min_m,path,pressure_pa,tangent_pa_per_m,region,d_min_given_m,path_given\n";

fn csv_row(p: &EvalPoint) -> String {
    format!(
        "{:e},{:e},{},{:e},{:e},{},{},{}\n",
        p.d,
        p.d_min,
        p.path,
        p.pressure,
        p.tangent,
        p.region,
        p.d_min_given
            .map_or("virgin".to_string(), |v| format!("{v:e}")),
        p.path_given
    )
}

impl Render for EvalReport {
    fn table(&self) -> String {
        let p = &self.point;
        let mut s = String::new();
        let given = p.d_min_given.map_or("virgin surface".to_string(), |v| {
            format!("d_min = {}", render::si(v, "m", 6))
        });
        let _ = writeln!(
            s,
            "law {} at d = {}, {}, path {}",
            self.law,
            render::si(p.d, "m", 6),
            given,
            p.path_given
        );
        let curve = match p.curve {
            "virgin" => "the virgin envelope (the history deepens)",
            "approach" => "the approach branch of d_min",
            _ => "the retract branch of d_min",
        };
        let _ = writeln!(s, "on {curve}");
        let _ = writeln!(
            s,
            "pressure = {:e} Pa ({}, compressive positive)",
            p.pressure,
            render::pressure(p.pressure)
        );
        let _ = writeln!(
            s,
            "tangent  = {:e} Pa/m (dp/dd at fixed history)",
            p.tangent
        );
        let _ = writeln!(
            s,
            "d_min    = {:e} m, path {} after the call",
            p.d_min, p.path
        );
        let _ = writeln!(s, "region   = {}", region_words(p.region));
        s
    }

    fn csv(&self) -> String {
        format!("{CSV_HEADER}{}", csv_row(&self.point))
    }
}

impl Render for EvalBatch {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "law {}: {} points, {} outside the measured region",
            self.law,
            self.points.len(),
            self.outside_measured
        );
        let _ = writeln!(
            s,
            "{:>13} {:>13} {:>8} {:>14} {:>14} {:>13} {:>8}  region",
            "d [m]", "d_min [m]", "path", "p [Pa]", "dp/dd [Pa/m]", "d_min after", "path"
        );
        for p in &self.points {
            let _ = writeln!(
                s,
                "{:>13.6e} {:>13} {:>8} {:>14.6e} {:>14.6e} {:>13.6e} {:>8}  {}",
                p.d,
                p.d_min_given
                    .map_or("virgin".to_string(), |v| format!("{v:.6e}")),
                p.path_given,
                p.pressure,
                p.tangent,
                p.d_min,
                p.path,
                p.region
            );
        }
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from(CSV_HEADER);
        for p in &self.points {
            s += &csv_row(p);
        }
        s
    }
}
