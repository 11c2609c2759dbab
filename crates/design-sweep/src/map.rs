//! Maps: evaluate a grid (or one shard of it) in parallel, write CSV/JSON, merge shards.

use crate::grid::{Grid, Level};
use crate::point::{guarded, DesignPoint, PointError, Status};
use crate::requirement::Requirement;
use crate::shard::Shard;
use crate::DesignError;
use rayon::prelude::*;
use serde::{Deserialize, Serialize, Serializer};
use serde_json::Value;
use std::collections::BTreeMap;
use std::io::Read;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The `format` tag of `map.json`.
pub const MAP_FORMAT: &str = "stiction-design-map";
/// The `version` of `map.json` written by this crate.
pub const MAP_VERSION: u32 = 1;

/// Largest `map.json` that [`Map::read_path`] reads (bytes): a map of the largest grid
/// ([`crate::MAX_GRID_POINTS`] points, about 300 bytes each with their failure messages)
/// fits; anything larger is not a map and is refused unread.
pub const MAX_MAP_BYTES: u64 = 1 << 30;

/// A file type in words, for an error.
fn kind(m: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = m.file_type();
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if m.is_dir() {
        "a folder"
    } else {
        "not a file"
    }
}

/// Reads a result file of at most [`MAX_MAP_BYTES`] bytes as UTF-8 text, refusing unread a
/// path that is not a regular file (a FIFO, a device, a folder) or is too large; `file` is
/// what the file should be ("a map.json"), `writer` the command that writes it, `noun`
/// what it is not otherwise ("a design map"). Errors ([`DesignError::MapFile`]) name it.
pub(crate) fn read_bounded(
    path: &Path,
    file: &str,
    writer: &str,
    noun: &str,
) -> Result<String, DesignError> {
    let shown = path.display().to_string();
    let fail = |reason: String| DesignError::MapFile {
        path: shown.clone(),
        reason,
    };
    // the type first, from the path: opening a FIFO would block until a writer comes
    let meta = std::fs::metadata(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    let regular = |m: &std::fs::Metadata| -> Result<(), DesignError> {
        if !m.is_file() {
            return Err(fail(format!(
                "not a regular file ({}): {file} is a file written by {writer}",
                kind(m)
            )));
        }
        if m.len() > MAX_MAP_BYTES {
            return Err(fail(format!(
                "{} bytes, larger than {MAX_MAP_BYTES} bytes: not {noun}",
                m.len()
            )));
        }
        Ok(())
    };
    regular(&meta)?;
    let handle = std::fs::File::open(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    // the same checks on the file opened (the path may have changed in between)
    regular(
        &handle
            .metadata()
            .map_err(|e| fail(format!("cannot read: {e}")))?,
    )?;
    let mut bytes = Vec::new();
    handle
        .take(MAX_MAP_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| fail(format!("cannot read: {e}")))?;
    if bytes.len() as u64 > MAX_MAP_BYTES {
        return Err(fail(format!(
            "larger than {MAX_MAP_BYTES} bytes (it grew while read): not {noun}"
        )));
    }
    String::from_utf8(bytes).map_err(|e| {
        fail(format!(
            "not UTF-8 text (byte {}): not {noun}",
            e.utf8_error().valid_up_to()
        ))
    })
}

/// The columns of `map.csv` after the varied fields, in order.
pub const CSV_COLUMNS: [&str; 12] = [
    "pull_out_ratio",
    "largest_pull_out_pa",
    "restoring_pressure_pa",
    "cycles_to_accommodation",
    "first_sticking_cycle",
    "sticks",
    "closes",
    "validity_holds",
    "accommodation_cause",
    "contact_resistance",
    "real_contact_fraction",
    "status",
];

/// What to compute: the grid, which part of it, and what to echo into `map.json`.
#[derive(Debug, Clone, PartialEq)]
pub struct MapRequest {
    /// The scene as run (echoed verbatim; merge compares it exactly).
    pub scene: Value,
    /// The grid.
    pub grid: Grid,
    /// The accuracy mode's name (echoed; merge compares it).
    pub accuracy: String,
    /// Part of the grid to run; `None` runs it whole.
    pub shard: Option<Shard>,
}

/// One evaluated grid point.
#[derive(Debug, Clone, PartialEq)]
pub struct MapPoint {
    /// Index in the grid (see [`Grid`] for the order).
    pub index: usize,
    /// The field values, one per axis ([`Grid::values`]: on a categorical axis the code of
    /// the word; [`Grid::levels`] of `index` gives the words).
    pub values: Vec<f64>,
    /// What became of the point.
    pub status: Status,
    /// The design point; present exactly when the status is `Ok` or `DoesNotClose`.
    pub design: Option<DesignPoint>,
}

impl MapPoint {
    /// The pull-out ratio when the point has a design (0 for `DoesNotClose`).
    pub fn ratio(&self) -> Option<f64> {
        self.design.map(|d| d.pull_out_ratio)
    }

    /// `Some(true)` if the point is free (it closes and its ratio is below 1), `Some(false)`
    /// if not (it sticks, or it does not close), `None` if failed.
    pub fn free(&self) -> Option<bool> {
        self.design.map(|d| d.free())
    }
}

/// An evaluated map (whole or one shard). Points are in ascending index order.
#[derive(Debug, Clone, PartialEq)]
pub struct Map {
    scene: Value,
    grid: Grid,
    accuracy: String,
    shard: Option<Shard>,
    points: Vec<MapPoint>,
    requirement: Option<Requirement>,
}

/// Evaluates the points of `request` (all, or its shard's) in parallel on the current
/// rayon pool and collects them in index order, so the map does not depend on the number
/// of threads or on sharding as long as `eval` is deterministic.
///
/// `eval` receives `(field, value)` per axis, the value a number or the word of a
/// categorical axis ([`Level`]). A point whose evaluator returns an error,
/// panics or gives a non-finite number gets a status and the map goes on. `progress(done,
/// total)` is called once with `done = 0` and after every point, from worker threads.
pub fn run_map<F, E, P>(request: MapRequest, eval: F, progress: P) -> Map
where
    F: Fn(&[(&str, Level<'_>)]) -> Result<DesignPoint, E> + Sync,
    E: Into<PointError>,
    P: Fn(usize, usize) + Sync,
{
    let MapRequest {
        scene,
        grid,
        accuracy,
        shard,
    } = request;
    let indices: Vec<usize> = match shard {
        Some(s) => s.indices(grid.len()).collect(),
        None => (0..grid.len()).collect(),
    };
    let total = indices.len();
    progress(0, total);
    let done = AtomicUsize::new(0);
    let points = indices
        .par_iter()
        .map(|&index| {
            let values = grid.values(index);
            let args: Vec<(&str, Level<'_>)> = grid
                .axes()
                .iter()
                .map(|a| a.field.as_str())
                .zip(grid.levels(index))
                .collect();
            let (status, design) = guarded(|| eval(&args));
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            MapPoint {
                index,
                values,
                status,
                design,
            }
        })
        .collect();
    Map {
        scene,
        grid,
        accuracy,
        shard,
        points,
        requirement: None,
    }
}

impl Map {
    /// The scene echo.
    pub fn scene(&self) -> &Value {
        &self.scene
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The accuracy mode's name.
    pub fn accuracy(&self) -> &str {
        &self.accuracy
    }

    /// The map with a second requirement beside freedom from stiction
    /// (`--require contact_resistance<1`): `map.json` echoes it and marks each point's
    /// `meets_requirement` and `in_window` (free of stiction and meeting it).
    pub fn with_requirement(mut self, requirement: Option<Requirement>) -> Self {
        self.requirement = requirement;
        self
    }

    /// The second requirement, if any.
    pub fn requirement(&self) -> Option<&Requirement> {
        self.requirement.as_ref()
    }

    /// The points in the design window: free of stiction and meeting the requirement
    /// (empty without one).
    pub fn window(&self) -> Vec<&MapPoint> {
        match &self.requirement {
            Some(r) => self
                .points
                .iter()
                .filter(|p| p.design.is_some_and(|d| r.in_window(&d)))
                .collect(),
            None => Vec::new(),
        }
    }

    /// The shard this map is part of (`None` for a whole or merged map).
    pub fn shard(&self) -> Option<Shard> {
        self.shard
    }

    /// The evaluated points, ascending index.
    pub fn points(&self) -> &[MapPoint] {
        &self.points
    }

    /// The point of grid index `i`, if this map holds it.
    pub fn point(&self, i: usize) -> Option<&MapPoint> {
        self.points
            .binary_search_by_key(&i, |p| p.index)
            .ok()
            .map(|k| &self.points[k])
    }

    /// `map.json`, pretty-printed with a final newline. No `null` and no NaN: absent values
    /// are omitted. The shard appears only in a shard's map.
    pub fn to_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(self).expect("a map always serialises");
        s.push('\n');
        s
    }

    /// Reads a `map.json` file with [`Map::from_json`], refusing before reading it whole
    /// what cannot be one: a path that is not a regular file (a FIFO, a device such as
    /// `/dev/zero`, a folder) and a file larger than [`MAX_MAP_BYTES`] (a file that grows
    /// while read is stopped at the cap). Errors ([`DesignError::MapFile`]) name the file.
    pub fn read_path(path: impl AsRef<Path>) -> Result<Map, DesignError> {
        let path = path.as_ref();
        let text = read_bounded(path, "a map.json", "`design map`", "a design map")?;
        Map::from_json(&text).map_err(|e| DesignError::MapFile {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
    }

    /// Reads a `map.json` back (numbers bit-identical), checking it is consistent: known
    /// format, valid grid and shard, points ascending, belonging to the shard, with the
    /// grid's values (and no other field), the status agreeing with the values present
    /// and each point's values agreeing with each other ([`DesignPoint::check`]). Errors
    /// name the point index and the key.
    pub fn from_json(text: &str) -> Result<Map, DesignError> {
        let m: MapIn =
            serde_json::from_str(text).map_err(|e| DesignError::MapJson(e.to_string()))?;
        let bad = |m: String| DesignError::MapJson(m);
        if m.format != MAP_FORMAT || m.version != MAP_VERSION {
            return Err(bad(format!(
                "format `{}` version {}, expected `{MAP_FORMAT}` version {MAP_VERSION}",
                m.format, m.version
            )));
        }
        m.grid.validate()?;
        if let Some(s) = m.shard {
            Shard::new(s.k, s.n)?;
        }
        let mut points = Vec::with_capacity(m.points.len());
        let mut last = None;
        for p in m.points {
            let i = p.index;
            if i >= m.grid.len() {
                return Err(bad(format!(
                    "point index {i} outside the grid of {} points",
                    m.grid.len()
                )));
            }
            if last.is_some_and(|l| i <= l) {
                return Err(bad(format!("point index {i} out of order or repeated")));
            }
            last = Some(i);
            if let Some(s) = m.shard {
                if !s.contains(i) {
                    return Err(bad(format!("point {i} does not belong to shard {s}")));
                }
            }
            let values = m.grid.values(i);
            for (a, level) in m.grid.axes().iter().zip(m.grid.levels(i)) {
                let same = match (p.values.get(&a.field), level) {
                    (Some(ValueIn::Number(x)), Level::Number(v)) => *x == v,
                    (Some(ValueIn::Word(w)), Level::Word(v)) => w == v,
                    _ => false,
                };
                if !same {
                    return Err(bad(format!(
                        "point {i}: {} is not the grid value {level}",
                        a.field
                    )));
                }
            }
            if let Some(k) = p
                .values
                .keys()
                .find(|k| !m.grid.axes().iter().any(|a| &a.field == *k))
            {
                return Err(bad(format!(
                    "point {i}: values.{k}: not a field of the grid"
                )));
            }
            let (status, design) = point_design(i, &p).map_err(bad)?;
            // the window marks are derived: present exactly with a requirement, and true
            let marks = match (&m.requirement, &design) {
                (Some(r), Some(d)) => (r.met(d), Some(r.in_window(d))),
                (Some(_), None) => (None, Some(false)),
                (None, _) => (None, None),
            };
            if (p.meets_requirement, p.in_window) != marks {
                return Err(bad(format!(
                    "point {i}: meets_requirement = {:?}, in_window = {:?} do not follow from its values and the map's requirement ({:?}, {:?} expected)",
                    p.meets_requirement, p.in_window, marks.0, marks.1
                )));
            }
            points.push(MapPoint {
                index: i,
                values,
                status,
                design,
            });
        }
        Ok(Map {
            scene: m.scene,
            grid: m.grid,
            accuracy: m.accuracy,
            shard: m.shard,
            points,
            requirement: m.requirement,
        })
    }

    /// Counts by status and the extreme ratios of the closing points.
    pub fn summary(&self) -> MapSummary {
        let mut s = MapSummary {
            grid_points: self.grid.len(),
            points: self.points.len(),
            ok: 0,
            does_not_close: 0,
            out_of_domain: 0,
            failed: 0,
            sticking: 0,
            min_ratio: None,
            max_ratio: None,
            in_window: self.requirement.map(|_| self.window().len()),
        };
        for p in &self.points {
            match &p.status {
                Status::Ok => s.ok += 1,
                Status::DoesNotClose => s.does_not_close += 1,
                Status::OutOfDomain(_) => s.out_of_domain += 1,
                Status::Failed(_) => s.failed += 1,
            }
            if let (Status::Ok, Some(d)) = (&p.status, &p.design) {
                if d.sticks {
                    s.sticking += 1;
                }
                let r = d.pull_out_ratio;
                if s.min_ratio.is_none_or(|(_, m)| r < m) {
                    s.min_ratio = Some((p.index, r));
                }
                if s.max_ratio.is_none_or(|(_, m)| r > m) {
                    s.max_ratio = Some((p.index, r));
                }
            }
        }
        s
    }
}

/// The status and design point of a point record (of `map.json` or `probability.json`),
/// checked: a known status, a detail exactly with `out_of_domain` and `failed`, the values
/// present matching the status, and the design point consistent
/// ([`DesignPoint::check`]). The error names the point index and the key.
pub(crate) fn point_design(i: usize, p: &PointIn) -> Result<(Status, Option<DesignPoint>), String> {
    let status = Status::from_parts(&p.status, p.detail.clone())
        .ok_or_else(|| format!("point {i}: unknown status `{}`", p.status))?;
    // a detail exactly where the writer puts one: with out_of_domain and failed
    match (status.detail().is_some(), &p.detail) {
        (true, None) => {
            return Err(format!(
                "point {i}: detail missing: status `{}` says why in `detail`",
                p.status
            ))
        }
        (false, Some(d)) => {
            return Err(format!(
                "point {i}: detail = {:?}: status `{}` has no detail",
                d.chars().take(60).collect::<String>(),
                p.status
            ))
        }
        _ => {}
    }
    let design = match (
        status.has_design(),
        p.pull_out_ratio,
        p.largest_pull_out_pa,
        p.restoring_pressure_pa,
        p.sticks,
        p.closes,
    ) {
        (true, Some(r), Some(po), Some(rp), Some(sticks), Some(closes)) => {
            let d = DesignPoint {
                pull_out_ratio: r,
                largest_pull_out_pa: po,
                restoring_pressure_pa: rp,
                cycles_to_accommodation: p.cycles_to_accommodation,
                first_sticking_cycle: p.first_sticking_cycle,
                sticks,
                closes,
                validity_holds: p.validity_holds.unwrap_or(true),
                accommodation_cause: p.accommodation_cause,
                contact_resistance: p.contact_resistance,
                real_contact_fraction: p.real_contact_fraction,
            };
            if closes != (status == Status::Ok) {
                return Err(format!(
                    "point {i}: closes = {closes} with status `{}`: a point is `ok` \
                     exactly when the switch closes (`does_not_close` otherwise)",
                    p.status
                ));
            }
            d.check().map_err(|m| format!("point {i}: {m}"))?;
            Some(d)
        }
        (false, None, None, None, None, None)
            if p.cycles_to_accommodation.is_none()
                && p.first_sticking_cycle.is_none()
                && p.contact_resistance.is_none()
                && p.real_contact_fraction.is_none() =>
        {
            None
        }
        _ => {
            return Err(format!(
                "point {i}: status `{}` does not match the values present",
                p.status
            ))
        }
    };
    Ok((status, design))
}

/// Counts of a map's points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapSummary {
    /// Points of the whole grid.
    pub grid_points: usize,
    /// Points in this map (fewer than `grid_points` for a shard).
    pub points: usize,
    /// Points with status `ok`.
    pub ok: usize,
    /// Points that do not close.
    pub does_not_close: usize,
    /// Points out of a field's domain.
    pub out_of_domain: usize,
    /// Points whose run failed.
    pub failed: usize,
    /// Closing points that stick (as flagged by the evaluator).
    pub sticking: usize,
    /// (index, ratio) of the smallest ratio among closing points.
    pub min_ratio: Option<(usize, f64)>,
    /// (index, ratio) of the largest ratio among closing points.
    pub max_ratio: Option<(usize, f64)>,
    /// Points free of stiction and meeting the requirement (with a requirement).
    pub in_window: Option<usize>,
}

/// Joins the shards of one map into exactly the map of an unsharded run (its CSV, JSON and
/// SVG are byte-identical to those of the whole run). Each shard comes with a label, the
/// directory it was read from, which errors name. Refuses: no shards, an unsharded map,
/// differing scene, grid or accuracy, differing N, a repeated or missing part.
pub fn merge<I>(shards: I) -> Result<Map, DesignError>
where
    I: IntoIterator<Item = (String, Map)>,
{
    let shards: Vec<(String, Map)> = shards.into_iter().collect();
    let Some((first_label, first)) = shards.first() else {
        return Err(DesignError::Merge {
            shard: "(nothing)".into(),
            reason: "no shards given".into(),
        });
    };
    let refuse = |label: &str, reason: String| DesignError::Merge {
        shard: label.to_owned(),
        reason,
    };
    let part = |label: &str, m: &Map| {
        m.shard.ok_or_else(|| {
            refuse(
                label,
                "holds an unsharded map (parts are made by a sharded run, K/N)".into(),
            )
        })
    };
    let n = part(first_label, first)?.n;
    // parts seen so far (a map: N comes from a file and may be anything)
    let mut owner: BTreeMap<usize, &str> = BTreeMap::new();
    for (label, m) in &shards {
        let s = part(label, m)?;
        if s.n != n {
            return Err(refuse(
                label,
                format!(
                    "is part {s} (of {} parts) but {first_label} is one of {n} parts",
                    s.n
                ),
            ));
        }
        if m.scene != first.scene {
            return Err(refuse(
                label,
                format!(
                    "its scene differs from {first_label}'s at {}",
                    first_difference(&first.scene, &m.scene, String::new())
                ),
            ));
        }
        if m.grid != first.grid {
            return Err(refuse(
                label,
                grid_difference(&m.grid, &first.grid, first_label),
            ));
        }
        if m.accuracy != first.accuracy {
            return Err(refuse(
                label,
                format!(
                    "accuracy `{}` differs from {first_label}'s `{}`",
                    m.accuracy, first.accuracy
                ),
            ));
        }
        if m.requirement != first.requirement {
            return Err(refuse(
                label,
                format!(
                    "requirement {} differs from {first_label}'s {}",
                    m.requirement.map_or("(none)".into(), |r| r.to_string()),
                    first.requirement.map_or("(none)".into(), |r| r.to_string())
                ),
            ));
        }
        if let Some(other) = owner.insert(s.k, label) {
            return Err(refuse(label, format!("part {s} is also in {other}")));
        }
        let expected: Vec<usize> = s.indices(m.grid.len()).collect();
        let got: Vec<usize> = m.points.iter().map(|p| p.index).collect();
        if got != expected {
            return Err(refuse(
                label,
                format!(
                    "part {s} holds {} points, expected {} (an incomplete or altered shard)",
                    got.len(),
                    expected.len()
                ),
            ));
        }
    }
    if owner.len() < n {
        let missing: Vec<String> = (1..=n)
            .filter(|k| !owner.contains_key(k))
            .take(20)
            .map(|k| format!("{k}/{n}"))
            .collect();
        let more = n - owner.len() - missing.len();
        return Err(refuse(
            &shards
                .iter()
                .map(|(l, _)| l.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            format!(
                "missing part(s) {}{}",
                missing.join(", "),
                if more > 0 {
                    format!(" and {more} more")
                } else {
                    String::new()
                }
            ),
        ));
    }
    let (scene, grid, accuracy, requirement) = (
        first.scene.clone(),
        first.grid.clone(),
        first.accuracy.clone(),
        first.requirement,
    );
    let mut points: Vec<MapPoint> = shards.into_iter().flat_map(|(_, m)| m.points).collect();
    points.sort_by_key(|p| p.index);
    Ok(Map {
        scene,
        grid,
        accuracy,
        shard: None,
        points,
        requirement,
    })
}

fn describe(g: &Grid) -> String {
    g.axes()
        .iter()
        .map(|a| a.describe())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Why two grids differ, in words: the words of a categorical axis of the same field by
/// name, else both grids in full.
fn grid_difference(g: &Grid, first: &Grid, first_label: &str) -> String {
    let same_fields = g.dim() == first.dim()
        && g.axes()
            .iter()
            .zip(first.axes())
            .all(|(a, b)| a.field == b.field);
    if same_fields {
        for (a, b) in g.axes().iter().zip(first.axes()) {
            if (a.is_categorical() || b.is_categorical()) && a != b {
                let words = |x: &crate::Axis| {
                    if x.is_categorical() {
                        x.words.join(", ")
                    } else {
                        format!("numbers, {}", x.describe())
                    }
                };
                return format!(
                    "the words of {} ({}) differ from {first_label}'s ({}): parts of one map \
                     list the same words in the same order",
                    a.field,
                    words(a),
                    words(b)
                );
            }
        }
    }
    format!(
        "its grid ({}) differs from {first_label}'s ({})",
        describe(g),
        describe(first)
    )
}

/// The JSON pointer of the first place where `a` and `b` differ.
pub(crate) fn first_difference(a: &Value, b: &Value, at: String) -> String {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            for (k, v) in x {
                match y.get(k) {
                    Some(w) if w == v => {}
                    Some(w) => return first_difference(v, w, format!("{at}/{k}")),
                    None => return format!("{at}/{k} (absent in one)"),
                }
            }
            match y.keys().find(|k| !x.contains_key(*k)) {
                Some(k) => format!("{at}/{k} (absent in one)"),
                None => at,
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (i, (v, w)) in x.iter().zip(y).enumerate() {
                if v != w {
                    return first_difference(v, w, format!("{at}/{i}"));
                }
            }
            at
        }
        _ => format!("{} ({a} vs {b})", if at.is_empty() { "/" } else { &at }),
    }
}

// ------------------------------------------------------------ JSON records

#[derive(Serialize)]
struct MapOut<'a> {
    format: &'static str,
    version: u32,
    accuracy: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    shard: Option<Shard>,
    grid: &'a Grid,
    #[serde(skip_serializing_if = "Option::is_none")]
    requirement: Option<Requirement>,
    scene: &'a Value,
    points: Vec<PointOut<'a>>,
}

#[derive(Serialize)]
struct PointOut<'a> {
    index: usize,
    values: Named<'a>,
    status: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    detail: Option<&'a str>,
    #[serde(flatten)]
    design: Option<&'a DesignPoint>,
    #[serde(skip_serializing_if = "Option::is_none")]
    meets_requirement: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    in_window: Option<bool>,
}

/// Field values of a point (its index) as a JSON object in axis order: numbers, and the
/// words of categorical axes.
struct Named<'a>(&'a Grid, usize);

impl Serialize for Named<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(Some(self.0.dim()))?;
        for (a, v) in self.0.axes().iter().zip(self.0.levels(self.1)) {
            m.serialize_entry(&a.field, &v)?;
        }
        m.end()
    }
}

impl Serialize for Map {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        MapOut {
            format: MAP_FORMAT,
            version: MAP_VERSION,
            accuracy: &self.accuracy,
            shard: self.shard,
            grid: &self.grid,
            requirement: self.requirement,
            scene: &self.scene,
            points: self
                .points
                .iter()
                .map(|p| PointOut {
                    index: p.index,
                    values: Named(&self.grid, p.index),
                    status: p.status.word(),
                    detail: p.status.detail(),
                    design: p.design.as_ref(),
                    meets_requirement: self
                        .requirement
                        .and_then(|r| p.design.and_then(|d| r.met(&d))),
                    in_window: self
                        .requirement
                        .map(|r| p.design.is_some_and(|d| r.in_window(&d))),
                })
                .collect(),
        }
        .serialize(s)
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MapIn {
    format: String,
    version: u32,
    accuracy: String,
    #[serde(default)]
    shard: Option<Shard>,
    grid: Grid,
    #[serde(default)]
    requirement: Option<Requirement>,
    scene: Value,
    points: Vec<PointIn>,
}

/// A field value of a point record: a number, or the word of a categorical axis.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
pub(crate) enum ValueIn {
    Number(f64),
    Word(String),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PointIn {
    pub(crate) index: usize,
    pub(crate) values: BTreeMap<String, ValueIn>,
    status: String,
    #[serde(default)]
    detail: Option<String>,
    #[serde(default)]
    pull_out_ratio: Option<f64>,
    #[serde(default)]
    largest_pull_out_pa: Option<f64>,
    #[serde(default)]
    restoring_pressure_pa: Option<f64>,
    #[serde(default)]
    cycles_to_accommodation: Option<usize>,
    #[serde(default)]
    first_sticking_cycle: Option<usize>,
    #[serde(default)]
    sticks: Option<bool>,
    #[serde(default)]
    closes: Option<bool>,
    #[serde(default)]
    validity_holds: Option<bool>,
    #[serde(default)]
    accommodation_cause: Option<crate::AccommodationCause>,
    #[serde(default)]
    contact_resistance: Option<f64>,
    #[serde(default)]
    real_contact_fraction: Option<f64>,
    #[serde(default)]
    meets_requirement: Option<bool>,
    #[serde(default)]
    in_window: Option<bool>,
}
