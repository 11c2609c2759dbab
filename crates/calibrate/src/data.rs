//! Finite-element force-interference curves of one asperity, read from CSV.

pub use crate::branch::Branch;
use crate::error::{CalibError, DataProblem};
use serde::Serialize;
use std::fmt::Write as _;

/// The four required columns, SI units.
pub const COLUMNS: [&str; 4] = ["delta_max_m", "delta_m", "force_n", "branch"];

/// Relative tolerance on delta <= delta_max (rounding in the finite-element export).
pub const DELTA_MAX_TOLERANCE: f64 = 1e-9;

/// One data point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CurvePoint {
    /// Interference delta (m).
    pub delta: f64,
    /// Force (N, compressive > 0).
    pub force: f64,
    /// Line of the point in the file (1-based).
    pub line: usize,
}

/// One force-interference curve, identified by (delta_max, branch).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Curve {
    /// Maximum interference of the finite-element run (m).
    pub delta_max: f64,
    /// The branch.
    pub branch: Branch,
    /// Its points, in file order.
    pub points: Vec<CurvePoint>,
}

impl Curve {
    /// F_peak = max |force| over the curve (N): the scale of its residuals.
    pub fn peak_force(&self) -> f64 {
        self.points.iter().fold(0.0, |m, p| m.max(p.force.abs()))
    }
}

/// Validated finite-element data: curves sorted by delta_max, loading before unloading.
///
/// Format (`FeData::parse_csv`): UTF-8 text, comma-separated. Blank lines and lines whose
/// first non-blank character is `#` are skipped. The first other line is the header; it
/// must contain the four columns of [`COLUMNS`] (exact, case-sensitive names, any order);
/// other columns are ignored (listed by [`FeData::ignored_columns`]). Fields are trimmed
/// and may be wrapped in double quotes (no embedded commas). Numbers are in SI units
/// (m, N); `branch` is `loading` or `unloading` (case-insensitive). Rows with the same
/// `delta_max_m` value (the same number after parsing) and branch form one curve.
///
/// ```
/// use calibrate::FeData;
/// let csv = "delta_max_m,delta_m,force_n,branch\n\
///            2e-8,1e-8,1e-3,loading\n2e-8,2e-8,3e-3,loading\n";
/// let data = FeData::parse_csv(csv)?;
/// assert_eq!(data.curves().len(), 1);
/// let bad = FeData::parse_csv("delta_max_m,delta_m,force_n,branch\n2e-8,1e-8,x,loading\n");
/// assert_eq!(bad.unwrap_err().to_string(), "line 2, column force_n: not a number: \"x\"");
/// # Ok::<(), calibrate::CalibError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FeData {
    curves: Vec<Curve>,
    ignored_columns: Vec<String>,
}

fn data_err(line: usize, column: &str, problem: DataProblem) -> CalibError {
    CalibError::Data {
        line,
        column: column.to_string(),
        problem,
    }
}

/// Trim and remove one pair of surrounding double quotes.
fn clean(field: &str) -> &str {
    let t = field.trim();
    t.strip_prefix('"')
        .and_then(|s| s.strip_suffix('"'))
        .map_or(t, str::trim)
}

fn number(text: &str, line: usize, column: &str) -> Result<f64, CalibError> {
    let v: f64 = text.parse().map_err(|_| {
        data_err(
            line,
            column,
            DataProblem::NotANumber {
                text: text.to_string(),
            },
        )
    })?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(data_err(
            line,
            column,
            DataProblem::NotFinite {
                text: text.to_string(),
            },
        ))
    }
}

/// A parsed row before grouping.
struct Row {
    delta_max: f64,
    delta: f64,
    force: f64,
    branch: Branch,
    line: usize,
}

impl FeData {
    /// Parse CSV text (format in the type's documentation) and validate it.
    pub fn parse_csv(text: &str) -> Result<Self, CalibError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut lines = text
            .split('\n')
            .enumerate()
            .map(|(i, l)| (i + 1, l.strip_suffix('\r').unwrap_or(l)))
            .filter(|(_, l)| {
                let t = l.trim();
                !t.is_empty() && !t.starts_with('#')
            });
        let (header_line, header) = lines
            .next()
            .ok_or_else(|| data_err(1, "header", DataProblem::NoHeader))?;
        let names: Vec<&str> = header.split(',').map(clean).collect();
        // position of each required column
        let mut pos = [0usize; 4];
        for (k, want) in COLUMNS.iter().enumerate() {
            let mut found = names.iter().enumerate().filter(|(_, n)| *n == want);
            match (found.next(), found.next()) {
                (None, _) => {
                    return Err(data_err(header_line, want, DataProblem::MissingColumn));
                }
                (Some((first, _)), Some(_)) => {
                    return Err(data_err(
                        header_line,
                        want,
                        DataProblem::DuplicateColumn { first: first + 1 },
                    ));
                }
                (Some((i, _)), None) => pos[k] = i,
            }
        }
        let ignored_columns = names
            .iter()
            .filter(|n| !COLUMNS.contains(n))
            .map(|n| n.to_string())
            .collect();
        let mut rows = Vec::new();
        for (line, text) in lines {
            let fields: Vec<&str> = text.split(',').map(clean).collect();
            if fields.len() > names.len() {
                return Err(data_err(
                    line,
                    &format!("{}", names.len() + 1),
                    DataProblem::ExtraField,
                ));
            }
            let field = |k: usize| -> Result<&str, CalibError> {
                fields
                    .get(pos[k])
                    .copied()
                    .ok_or_else(|| data_err(line, COLUMNS[k], DataProblem::MissingField))
            };
            let delta_max = number(field(0)?, line, COLUMNS[0])?;
            let delta = number(field(1)?, line, COLUMNS[1])?;
            let force = number(field(2)?, line, COLUMNS[2])?;
            let word = field(3)?;
            let branch = match word.to_ascii_lowercase().as_str() {
                "loading" => Branch::Loading,
                "unloading" => Branch::Unloading,
                _ => {
                    return Err(data_err(
                        line,
                        COLUMNS[3],
                        DataProblem::UnknownBranch {
                            text: word.to_string(),
                        },
                    ))
                }
            };
            rows.push(Row {
                delta_max,
                delta,
                force,
                branch,
                line,
            });
        }
        Self::from_rows(rows, ignored_columns)
    }

    /// Read and parse a CSV file.
    pub fn read_csv(path: &std::path::Path) -> Result<Self, CalibError> {
        let text = std::fs::read_to_string(path).map_err(|source| CalibError::Io {
            path: path.display().to_string(),
            source,
        })?;
        Self::parse_csv(&text)
    }

    /// Data from curves built in memory, validated as a file would be. Each point's `line`
    /// is replaced by its line in [`FeData::to_csv`] (header on line 1).
    pub fn from_curves(curves: Vec<Curve>) -> Result<Self, CalibError> {
        let mut sorted = curves;
        sorted.sort_by(|a, b| {
            a.delta_max
                .total_cmp(&b.delta_max)
                .then(a.branch.cmp(&b.branch))
        });
        let mut rows = Vec::new();
        let mut line = 1;
        for c in &sorted {
            for p in &c.points {
                line += 1;
                for (v, col) in [(c.delta_max, 0), (p.delta, 1), (p.force, 2)] {
                    if !v.is_finite() {
                        return Err(data_err(
                            line,
                            COLUMNS[col],
                            DataProblem::NotFinite {
                                text: v.to_string(),
                            },
                        ));
                    }
                }
                rows.push(Row {
                    delta_max: c.delta_max,
                    delta: p.delta,
                    force: p.force,
                    branch: c.branch,
                    line,
                });
            }
        }
        Self::from_rows(rows, Vec::new())
    }

    fn from_rows(rows: Vec<Row>, ignored_columns: Vec<String>) -> Result<Self, CalibError> {
        let mut curves: Vec<Curve> = Vec::new();
        for r in rows {
            if r.delta_max <= 0.0 {
                return Err(data_err(
                    r.line,
                    COLUMNS[0],
                    DataProblem::NonPositiveDeltaMax { value: r.delta_max },
                ));
            }
            if r.delta > r.delta_max * (1.0 + DELTA_MAX_TOLERANCE) {
                return Err(data_err(
                    r.line,
                    COLUMNS[1],
                    DataProblem::AboveDeltaMax {
                        delta: r.delta,
                        delta_max: r.delta_max,
                    },
                ));
            }
            let point = CurvePoint {
                delta: r.delta,
                force: r.force,
                line: r.line,
            };
            match curves
                .iter_mut()
                .find(|c| c.delta_max == r.delta_max && c.branch == r.branch)
            {
                Some(c) => c.points.push(point),
                None => curves.push(Curve {
                    delta_max: r.delta_max,
                    branch: r.branch,
                    points: vec![point],
                }),
            }
        }
        for c in &curves {
            let first = c.points.first().map_or(0, |p| p.line);
            if c.points.len() < 2 {
                return Err(data_err(
                    first,
                    COLUMNS[0],
                    DataProblem::TooFewCurvePoints {
                        delta_max: c.delta_max,
                        branch: c.branch,
                        points: c.points.len(),
                    },
                ));
            }
            if c.peak_force() == 0.0 {
                return Err(data_err(
                    first,
                    COLUMNS[2],
                    DataProblem::ZeroPeakForce {
                        delta_max: c.delta_max,
                        branch: c.branch,
                    },
                ));
            }
        }
        curves.sort_by(|a, b| {
            a.delta_max
                .total_cmp(&b.delta_max)
                .then(a.branch.cmp(&b.branch))
        });
        Ok(Self {
            curves,
            ignored_columns,
        })
    }

    /// The curves, sorted by delta_max, loading before unloading.
    pub fn curves(&self) -> &[Curve] {
        &self.curves
    }

    /// Total number of points.
    pub fn len(&self) -> usize {
        self.curves.iter().map(|c| c.points.len()).sum()
    }

    /// True when there is no point (never for parsed data).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Header columns that were present but not used.
    pub fn ignored_columns(&self) -> &[String] {
        &self.ignored_columns
    }

    /// The data as CSV (header and one row per point, curves in order, shortest round-trip
    /// number formatting): `FeData::parse_csv(&d.to_csv())` reproduces `d`.
    pub fn to_csv(&self) -> String {
        let mut s = COLUMNS.join(",");
        s.push('\n');
        for c in &self.curves {
            for p in &c.points {
                // writing to a String cannot fail
                let _ = writeln!(
                    s,
                    "{:e},{:e},{:e},{}",
                    c.delta_max, p.delta, p.force, c.branch
                );
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "delta_max_m,delta_m,force_n,branch\n";

    fn err(text: &str) -> (usize, String, DataProblem) {
        match FeData::parse_csv(text).unwrap_err() {
            CalibError::Data {
                line,
                column,
                problem,
            } => (line, column, problem),
            e => panic!("not a data error: {e}"),
        }
    }

    #[test]
    fn any_column_order_comments_quotes_and_extra_columns() {
        let text =
            "\u{feff}# exported by FE\n\n\"branch\", force_n ,time_s,delta_m,delta_max_m\r\n\
                    loading,1e-3,0.1,1e-8,2e-8\r\n\
                    LOADING,3e-3,0.2,2e-8,2e-8\n\
                    # a comment between rows\n\
                    unloading,2e-3,0.3,2e-8,2e-8\n\
                    \"unloading\",-1e-5,0.4,5e-9,2e-8\n";
        let d = FeData::parse_csv(text).unwrap();
        assert_eq!(d.curves().len(), 2);
        assert_eq!(d.ignored_columns(), ["time_s"]);
        let l = &d.curves()[0];
        assert_eq!(
            (l.branch, l.points.len(), l.points[0].line),
            (Branch::Loading, 2, 4)
        );
        assert_eq!(l.points[1].force, 3e-3);
        assert_eq!(d.curves()[1].points[1].line, 8);
        assert_eq!(d.curves()[1].peak_force(), 2e-3);
        assert_eq!(d.len(), 4);
    }

    #[test]
    fn round_trip_through_csv() {
        let text = format!("{HEADER}3e-8,1e-8,1.2345678901234567e-3,loading\n3e-8,3e-8,5e-3,loading\n1e-8,1e-8,1e-3,unloading\n1e-8,0,-2e-5,unloading\n");
        let d = FeData::parse_csv(&text).unwrap();
        let again = FeData::parse_csv(&d.to_csv()).unwrap();
        assert_eq!(d.curves().len(), again.curves().len());
        for (a, b) in d.curves().iter().zip(again.curves()) {
            assert_eq!((a.delta_max, a.branch), (b.delta_max, b.branch));
            for (p, q) in a.points.iter().zip(&b.points) {
                assert_eq!((p.delta, p.force), (q.delta, q.force));
            }
        }
        // from_curves numbers lines as to_csv writes them
        let built = FeData::from_curves(d.curves().to_vec()).unwrap();
        assert_eq!(built, again);
    }

    #[test]
    fn errors_name_line_and_column() {
        let cases: Vec<(String, usize, &str)> = vec![
            ("".into(), 1, "header"),
            ("# only a comment\n".into(), 1, "header"),
            (
                "delta_max_m,delta_m,branch\n1,1,loading\n".into(),
                1,
                "force_n",
            ),
            (
                "delta_max_m,delta_m,force_n,branch,delta_m\n".into(),
                1,
                "delta_m",
            ),
            (
                format!("{HEADER}2e-8,1e-8,abc,loading\n2e-8,1e-8,1,loading\n"),
                2,
                "force_n",
            ),
            (
                format!("{HEADER}2e-8,1e-8,1,loading\n2e-8,,1,loading\n"),
                3,
                "delta_m",
            ),
            (
                format!("{HEADER}2e-8,1e-8,1,loading\n2e-8,NaN,1,loading\n"),
                3,
                "delta_m",
            ),
            (
                format!("{HEADER}2e-8,1e-8,1,loading\ninf,1e-8,1,loading\n"),
                3,
                "delta_max_m",
            ),
            (
                format!("{HEADER}2e-8,1e-8,1,loading\n2e-8,1e-8,1,reloading\n"),
                3,
                "branch",
            ),
            (
                format!("{HEADER}2e-8,1e-8,1,loading\n2e-8,1e-8,1\n"),
                3,
                "branch",
            ),
            (
                format!("{HEADER}2e-8,1e-8,1,loading\n2e-8,1e-8,1,loading,7\n"),
                3,
                "5",
            ),
            (
                format!("{HEADER}2e-8,1e-8,1,loading\n2e-8,2.1e-8,1,loading\n"),
                3,
                "delta_m",
            ),
            (
                format!("{HEADER}0,0,1,loading\n0,0,1,loading\n"),
                2,
                "delta_max_m",
            ),
            (format!("{HEADER}-1e-8,-2e-8,1,loading\n"), 2, "delta_max_m"),
            (
                format!(
                    "{HEADER}2e-8,1e-8,1,loading\n2e-8,2e-8,1,loading\n2e-8,1e-8,1,unloading\n"
                ),
                4,
                "delta_max_m",
            ),
            (
                format!("{HEADER}2e-8,1e-8,0,loading\n2e-8,2e-8,-0,loading\n"),
                2,
                "force_n",
            ),
        ];
        for (text, line, column) in cases {
            let (l, c, p) = err(&text);
            assert_eq!((l, c.as_str()), (line, column), "{text:?}: {p}");
        }
        // delta may exceed delta_max by rounding only
        assert!(FeData::parse_csv(&format!(
            "{HEADER}2e-8,2.00000000001e-8,1,loading\n2e-8,1e-8,1,loading\n"
        ))
        .is_ok());
        let (_, _, p) = err(&format!(
            "{HEADER}2e-8,1e-8,1,loading\n2e-8,1e-8,1,Loadin\n"
        ));
        assert_eq!(
            p.to_string(),
            "unknown branch \"Loadin\" (expected loading or unloading)"
        );
    }
}
