//! `law.json` (read, validate, write) and `law.csv` (write).
//!
//! Reading parses the text into a JSON tree first and then extracts every value with its
//! JSON path, so that each error names the key and the value (`branches[3].retract.d[17]`).

use crate::error::{fmt_num, LawError};
use crate::json::{check_no_null, join};
use crate::law::{BranchError, BranchSet, ContactLaw, Curve, Meta, Point, PositiveTangent};
use crate::meta::{
    from_non_finite_word, non_finite_word, ErrorStats, MeasuredError, PartialReloadError,
    TabulationInfo,
};
use serde_json::{Map, Value};
use std::io::{Read, Write};
use std::path::Path as FsPath;

/// The value of the `format` key.
pub const FORMAT_NAME: &str = "stiction-contact-law";
/// The value of the `version` key this crate reads and writes. Version 2: the scaled cubic
/// rule in d_min, the pressure floor, the regions, the per-branch measured errors and the
/// positive retract tangents (version 1 had the linear rule; tabulate such a law again).
pub const FORMAT_VERSION: u64 = 2;
/// Largest file [`ContactLaw::from_path`] reads (bytes): files are untrusted input, and the
/// JSON tree of a file takes several times its size in memory. A law of 400 histories with
/// 500 nodes per curve is about 18 MiB (the toy law of the tests, 0.9 MiB).
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// Rule name of the interpolation in d.
pub const RULE_IN_D: &str = "steffen-1990";
/// Rule name of the interpolation in d_min.
pub const RULE_IN_D_MIN: &str = "scaled-cubic-at-fixed-x";

const SIGN_CONVENTION: &str = "pressure is force per unit nominal area, compressive positive, \
adhesive (tensile) negative; the tangent is dp/dd at fixed history, so it is negative where \
the contact stiffens as the surfaces approach";
const REFERENCE_PLANE: &str = "d is the separation from the mean plane of asperity heights of \
the equivalent rough surface to the counter-flat; smaller d is deeper contact; d_min is the \
deepest separation reached, the whole history of the surface";
const DESC_IN_D: &str = "Steffen (1990, A&A 239:443) monotone piecewise-cubic Hermite \
interpolation of each curve in x = d - d_min (in d for the virgin envelope): C1, through \
every node, no overshoot, monotone where the nodes are; the tangent is its derivative; \
the pressure is 0 beyond the last node (the reach)";
const DESC_IN_D_MIN: &str = "at fixed x = d - d_min, cubic Lagrange interpolation in \
d_min of the branches normalised by their pressure scales S_j = |p_V(d_j)| + |p_pull_out(d_j)| \
+ pressure_floor, times the scale S(d_min) = exp(sum c_j ln S_j): p = S(d_min) sum_j c_j(d_min) \
P_j(x) / S_j, over the four tabulated histories nearest to d_min that bracket it (the stencil \
shifted inwards at the ends of the grid; three or two when the grid has fewer), so that the \
exponential change of the pressures with d_min is carried by S and the cubic sees shapes \
that change slowly; plus the continuity correction c (1 - x/L)^2 for x < L, c = p_V(d_min) \
minus that value at x = 0, L the fade length of the two bracketing branches (the first node \
where a branch has made half of its largest change from its start value) linear in d_min, \
so that every branch starts on the virgin envelope. At a tabulated d_min the branch itself. \
Above the last branch (region above_table) the last branch times (1 - w), w the fraction of \
the way from it to the virgin reach, with the same correction; below the first branch \
(region below_table) an error";
const METRIC: &str = "|p_interp - p_direct| / (|p_direct| + |p_pull_out(d_min)| + \
pressure_floor), p_pull_out the most tensile retract pressure of the history d_min (for the \
virgin envelope at d: d_min = d, |p_pull_out| linear between the tabulated branches and \
constant beyond them), pressure_floor the floor of interpolation.pressure_floor";
const METHOD: &str = "direct evaluation of the source against the law assembled from its \
data at: the midpoint of every interval of every curve; the mid d_min of every pair of \
neighbouring branches, at the union of their nodes and its midpoints (at most 96 per \
branch) and its pull-out (the tabulator's own checks, with the final law); and held-out \
pseudo-random points from a 64-bit LCG with the stated seed (after the last refinement): \
d_min uniform on the tabulated range with x = d - d_min = reach * u^2 (u uniform), and d \
uniform on the virgin envelope";
const PRESSURE_FLOOR: &str = "pressure_floor (Pa) is added to the denominator of the error \
metric and to every branch's pressure scale: a fraction of the pressure scale of the \
deepest history (its largest |p|), so that pressures far below what the law carries are \
judged against it rather than against themselves";
const REGION_MEASURED: &str = "d_min between the first and the last tabulated history (or \
a deepening d on the virgin envelope between its first node and its reach) and d within \
the curve's reach: interpolated, with the error of interpolation.measured_error";
const REGION_BEYOND_REACH: &str = "d beyond the reach of the curve evaluated (every \
asperity out of contact): pressure and tangent exactly 0, the model's own value (heights \
truncated at 9 sigma_s), not an interpolation";
const REGION_ABOVE_TABLE: &str = "d_min above the last tabulated history (a touch lighter \
than the table's first touch) and d within reach: the last branch blended towards zero at \
the virgin reach; not measured; its pressures are of the order of pressure_floor or less";
const REGION_BELOW_TABLE: &str = "d_min, or a deepening d, below the first tabulated \
history: no data; evaluation is an error (C: SCL_ERR_OUT_OF_RANGE); tabulate deeper";
const POSITIVE_ADVICE: &str = "these retract branches rise before their pull-out: the \
pressure grows as the surfaces separate, a positive tangent dp/dd, which an implicit FE code \
receives as a negative unloading stiffness. On an elasto-plastic surface the cause is the \
eq-12 reload overshoot of asperities pressed beyond about 16 delta_CP (docs/theory.md \
section 2.5); tabulate the scene with contact.reload = \"bounded\" to remove it. With this \
table, use min(dp/dd, 0) as the Newton stiffness on retract branches (the pressure stays the \
law's) and expect slower convergence there";
const RELOAD_METHOD: &str = "retract branch of d_min from the law against the source's \
retraction after a reload that turned at d_turn > d_min, at the separations given to \
measure_partial_reload";

// ------------------------------------------------------------------------------------
// Reading

/// A JSON object with its path, for error messages.
struct Obj<'a> {
    map: &'a Map<String, Value>,
    path: String,
}

fn describe(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => format!("the boolean {b}"),
        Value::Number(n) => format!("the number {n}"),
        Value::String(s) => {
            let short: String = s.chars().take(40).collect();
            format!("the string {short:?}")
        }
        Value::Array(a) => format!("an array of {} items", a.len()),
        Value::Object(_) => "an object".into(),
    }
}

fn as_obj<'a>(v: &'a Value, path: String) -> Result<Obj<'a>, LawError> {
    match v {
        Value::Object(map) => Ok(Obj { map, path }),
        other => Err(LawError::format(
            path,
            format!("expected an object, found {}", describe(other)),
        )),
    }
}

fn as_num(v: &Value, path: &str) -> Result<f64, LawError> {
    match v {
        Value::Number(n) => match n.as_f64() {
            Some(x) if x.is_finite() => Ok(x),
            _ => Err(LawError::format(
                path,
                format!("{n}: must be a finite number"),
            )),
        },
        other => Err(LawError::format(
            path,
            format!("expected a number, found {}", describe(other)),
        )),
    }
}

impl<'a> Obj<'a> {
    fn keys(&self, allowed: &[&str]) -> Result<(), LawError> {
        for k in self.map.keys() {
            if !allowed.contains(&k.as_str()) {
                return Err(LawError::format(
                    join(&self.path, k),
                    format!("unknown key (allowed here: {})", allowed.join(", ")),
                ));
            }
        }
        Ok(())
    }

    fn get(&self, key: &str) -> Result<&'a Value, LawError> {
        self.map
            .get(key)
            .ok_or_else(|| LawError::format(join(&self.path, key), "missing"))
    }

    fn opt(&self, key: &str) -> Option<&'a Value> {
        self.map.get(key)
    }

    fn sub(&self, key: &str) -> Result<Obj<'a>, LawError> {
        as_obj(self.get(key)?, join(&self.path, key))
    }

    fn num(&self, key: &str) -> Result<f64, LawError> {
        as_num(self.get(key)?, &join(&self.path, key))
    }

    fn uint(&self, key: &str) -> Result<u64, LawError> {
        let path = join(&self.path, key);
        match self.get(key)? {
            Value::Number(n) if n.as_u64().is_some() => Ok(n.as_u64().unwrap_or(0)),
            other => Err(LawError::format(
                path,
                format!("expected a non-negative integer, found {}", describe(other)),
            )),
        }
    }

    fn string(&self, key: &str) -> Result<&'a str, LawError> {
        match self.get(key)? {
            Value::String(s) => Ok(s),
            other => Err(LawError::format(
                join(&self.path, key),
                format!("expected a string, found {}", describe(other)),
            )),
        }
    }

    fn boolean(&self, key: &str) -> Result<bool, LawError> {
        match self.get(key)? {
            Value::Bool(b) => Ok(*b),
            other => Err(LawError::format(
                join(&self.path, key),
                format!("expected true or false, found {}", describe(other)),
            )),
        }
    }

    fn array(&self, key: &str) -> Result<&'a Vec<Value>, LawError> {
        match self.get(key)? {
            Value::Array(a) => Ok(a),
            other => Err(LawError::format(
                join(&self.path, key),
                format!("expected an array, found {}", describe(other)),
            )),
        }
    }

    fn numbers(&self, key: &str) -> Result<Vec<f64>, LawError> {
        let path = join(&self.path, key);
        self.array(key)?
            .iter()
            .enumerate()
            .map(|(i, v)| as_num(v, &format!("{path}[{i}]")))
            .collect()
    }

    fn point(&self, key: &str) -> Result<Point, LawError> {
        let o = self.sub(key)?;
        o.keys(&["d", "pressure"])?;
        Ok(Point {
            d: o.num("d")?,
            pressure: o.num("pressure")?,
        })
    }

    fn expect_str(&self, key: &str, expected: &str) -> Result<(), LawError> {
        let s = self.string(key)?;
        if s == expected {
            Ok(())
        } else {
            Err(LawError::format(
                join(&self.path, key),
                format!("{s:?}: expected {expected:?}"),
            ))
        }
    }
}

/// A measured error: a number >= 0, or the string `"inf"` or `"nan"` (what the writer
/// puts for an infinite or undefined error).
fn error_value(o: &Obj<'_>, key: &str) -> Result<f64, LawError> {
    let path = join(&o.path, key);
    let v = match o.get(key)? {
        Value::String(w) => match from_non_finite_word(w) {
            Some(v) if !(v < 0.0) => v,
            _ => {
                return Err(LawError::format(
                    path,
                    format!(
                        "{}: expected a number >= 0, \"inf\" or \"nan\"",
                        describe(o.get(key)?)
                    ),
                ))
            }
        },
        v => as_num(v, &path)?,
    };
    if v < 0.0 {
        return Err(LawError::format(
            path,
            format!("{}: a relative error is >= 0", fmt_num(v)),
        ));
    }
    Ok(v)
}

fn read_stats(o: &Obj<'_>) -> Result<ErrorStats, LawError> {
    let worst = o.sub("worst")?;
    let samples = o.uint("samples")?;
    let (max, p99) = (error_value(o, "max")?, error_value(o, "p99")?);
    if p99 > max {
        return Err(LawError::format(
            join(&o.path, "p99"),
            format!(
                "{}: the 99th percentile cannot exceed the maximum {}",
                fmt_num(p99),
                fmt_num(max)
            ),
        ));
    }
    if samples == 0 {
        return Err(LawError::format(
            join(&o.path, "samples"),
            "0: statistics need at least one sample",
        ));
    }
    Ok(ErrorStats {
        max,
        p99,
        samples: usize::try_from(samples).map_err(|_| {
            LawError::format(join(&o.path, "samples"), format!("{samples}: too large"))
        })?,
        worst_d: worst.num("d")?,
        worst_d_min: worst.num("d_min")?,
    })
}

fn read_curve(
    o: &Obj<'_>,
    origin: f64,
    most_tensile: Option<(Point, String)>,
) -> Result<Curve, LawError> {
    let d = o.numbers("d")?;
    let pressure = o.numbers("pressure")?;
    let reach = o.num("reach")?;
    let (mt, mt_path) = match most_tensile {
        Some(p) => p,
        None => (o.point("most_tensile")?, join(&o.path, "most_tensile")),
    };
    let curve = Curve::new(d, pressure, mt, origin, &o.path, &mt_path)?;
    if reach != curve.reach() {
        return Err(LawError::format(
            join(&o.path, "reach"),
            format!(
                "{} m: must equal the last separation of the curve, {} m",
                fmt_num(reach),
                fmt_num(curve.reach())
            ),
        ));
    }
    Ok(curve)
}

impl ContactLaw {
    /// Reads and validates a law from JSON text.
    pub fn from_json_str(text: &str) -> Result<ContactLaw, LawError> {
        from_value(&parse_strict(text)?)
    }

    /// Reads and validates `law.json` (at most [`MAX_FILE_BYTES`]).
    pub fn from_path(path: impl AsRef<FsPath>) -> Result<ContactLaw, LawError> {
        let path = path.as_ref();
        let shown = path.display().to_string();
        let io = |source| LawError::Io {
            path: shown.clone(),
            source,
        };
        // the type first, from the path: opening a FIFO would wait for a writer, a device
        // may never end
        let meta = std::fs::metadata(path).map_err(io)?;
        if !meta.is_file() {
            let what = if meta.is_dir() {
                "a folder"
            } else {
                "not a regular file (a FIFO, a device or a socket)"
            };
            return Err(io(std::io::Error::other(format!(
                "it is {what}, not a law file"
            ))));
        }
        let file = std::fs::File::open(path).map_err(io)?;
        let mut bytes = Vec::new();
        file.take(MAX_FILE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(io)?;
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(LawError::TooLarge {
                path: shown,
                limit: MAX_FILE_BYTES,
            });
        }
        let text = String::from_utf8(bytes).map_err(|e| {
            LawError::Json(format!(
                "{shown}: not UTF-8 text (byte {})",
                e.utf8_error().valid_up_to()
            ))
        })?;
        ContactLaw::from_json_str(&text).map_err(|e| match e {
            LawError::Json(m) => LawError::Json(format!("{shown}: {m}")),
            other => other,
        })
    }
}

/// Where a value sits in the JSON tree while it is parsed: rendered as a JSON path
/// (`branches[3].retract`) only for an error.
#[derive(Clone, Copy)]
enum At<'a> {
    Root,
    Key(&'a At<'a>, &'a str),
    Index(&'a At<'a>, usize),
}

impl At<'_> {
    fn render(&self) -> String {
        match self {
            At::Root => String::new(),
            At::Key(parent, k) => join(&parent.render(), k),
            At::Index(parent, i) => format!("{}[{i}]", parent.render()),
        }
    }
}

/// Parses JSON text into a tree like `serde_json::from_str::<Value>`, but refuses an
/// object that repeats a key (serde_json keeps the last one silently: a file with two
/// `version`s, or two `pull_out`s, would be read as one of them without a word).
fn parse_strict(text: &str) -> Result<Value, LawError> {
    use serde::de::DeserializeSeed;
    let duplicate = std::cell::RefCell::new(None);
    let mut de = serde_json::Deserializer::from_str(text);
    let parsed = Strict {
        at: At::Root,
        duplicate: &duplicate,
    }
    .deserialize(&mut de)
    .and_then(|v| de.end().map(|()| v));
    match parsed {
        Ok(v) => Ok(v),
        Err(e) => match duplicate.into_inner() {
            Some(path) => Err(LawError::format(
                path,
                format!(
                    "duplicated key (line {}): each key may appear once in an object",
                    e.line()
                ),
            )),
            None => Err(LawError::Json(e.to_string())),
        },
    }
}

/// The seed of [`parse_strict`]: a JSON value at `at`; the path of a duplicated key is
/// left in `duplicate`.
struct Strict<'a> {
    at: At<'a>,
    duplicate: &'a std::cell::RefCell<Option<String>>,
}

impl<'de> serde::de::DeserializeSeed<'de> for Strict<'_> {
    type Value = Value;
    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> serde::de::Visitor<'de> for Strict<'_> {
    type Value = Value;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(Value::Number(v.into()))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(Value::Number(v.into()))
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Value, E> {
        serde_json::Number::from_f64(v)
            .map(Value::Number)
            .ok_or_else(|| E::custom(format!("{}: number out of range", self.at.render())))
    }
    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_owned()))
    }
    fn visit_string<E>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }
    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_none<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut out = Vec::new();
        while let Some(v) = seq.next_element_seed(Strict {
            at: At::Index(&self.at, out.len()),
            duplicate: self.duplicate,
        })? {
            out.push(v);
        }
        Ok(Value::Array(out))
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut out = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if out.contains_key(&key) {
                let path = At::Key(&self.at, &key).render();
                let message = format!("{path}: duplicated key");
                *self.duplicate.borrow_mut() = Some(path);
                return Err(serde::de::Error::custom(message));
            }
            let v = map.next_value_seed(Strict {
                at: At::Key(&self.at, &key),
                duplicate: self.duplicate,
            })?;
            out.insert(key, v);
        }
        Ok(Value::Object(out))
    }
}

fn from_value(root: &Value) -> Result<ContactLaw, LawError> {
    let top = as_obj(root, String::new()).map_err(|_| {
        LawError::format(
            "(top level)",
            format!("expected an object, found {}", describe(root)),
        )
    })?;
    // format and version first: a file of another kind or version says so before anything
    top.expect_str("format", FORMAT_NAME)?;
    let version = top.uint("version")?;
    if version != FORMAT_VERSION {
        let why = if version < FORMAT_VERSION {
            " (an older law, interpolated linearly in d_min: tabulate it again)"
        } else {
            ""
        };
        return Err(LawError::format(
            "version",
            format!("{version}: this reader knows version {FORMAT_VERSION}{why}"),
        ));
    }
    top.keys(&[
        "format",
        "version",
        "units",
        "sign_convention",
        "reference_plane",
        "interpolation",
        "regions",
        "positive_retract_tangent",
        "length_scale",
        "tabulation",
        "d_min_grid",
        "virgin",
        "branches",
        "partial_reload",
        "scene",
    ])?;
    let units = top.sub("units")?;
    units.keys(&["d", "d_min", "pressure", "tangent"])?;
    units.expect_str("d", "m")?;
    units.expect_str("d_min", "m")?;
    units.expect_str("pressure", "Pa")?;
    units.expect_str("tangent", "Pa/m")?;
    top.string("sign_convention")?;
    top.string("reference_plane")?;

    let interp = top.sub("interpolation")?;
    interp.keys(&["in_d", "in_d_min", "pressure_floor", "measured_error"])?;
    for (key, rule) in [("in_d", RULE_IN_D), ("in_d_min", RULE_IN_D_MIN)] {
        let o = interp.sub(key)?;
        o.keys(&["rule", "description"])?;
        o.expect_str("rule", rule)?;
    }
    let floor = {
        let o = interp.sub("pressure_floor")?;
        o.keys(&["value", "description"])?;
        let v = o.num("value")?;
        if v < 0.0 {
            return Err(LawError::format(
                "interpolation.pressure_floor.value",
                format!("{} Pa: must be >= 0", fmt_num(v)),
            ));
        }
        v
    };
    if let Some(v) = top.opt("regions") {
        let o = as_obj(v, "regions".into())?;
        let names = ["measured", "beyond_reach", "above_table", "below_table"];
        o.keys(&names)?;
        for k in names {
            o.string(k)?;
        }
    }
    let measured = match interp.opt("measured_error") {
        None => None,
        Some(v) => {
            let o = as_obj(v, "interpolation.measured_error".into())?;
            o.keys(&["metric", "method", "seed", "virgin", "approach", "retract"])?;
            let stats = |k: &str| -> Result<ErrorStats, LawError> {
                let s = o.sub(k)?;
                s.keys(&["max", "p99", "samples", "worst"])?;
                s.sub("worst")?.keys(&["d", "d_min"])?;
                read_stats(&s)
            };
            Some(MeasuredError {
                virgin: stats("virgin")?,
                approach: stats("approach")?,
                retract: stats("retract")?,
                seed: o.uint("seed")?,
            })
        }
    };
    let length_scale = match top.opt("length_scale") {
        None => None,
        Some(v) => {
            let s = as_num(v, "length_scale")?;
            if s <= 0.0 {
                return Err(LawError::format(
                    "length_scale",
                    format!("{}: must be > 0 (m)", fmt_num(s)),
                ));
            }
            Some(s)
        }
    };
    let tabulation = match top.opt("tabulation") {
        None => None,
        Some(v) => {
            let o = as_obj(v, "tabulation".into())?;
            o.keys(&[
                "tolerance",
                "points_per_branch",
                "d_min_rule",
                "source_evaluations",
                "converged",
            ])?;
            let count = |k: &str| -> Result<usize, LawError> {
                let n = o.uint(k)?;
                usize::try_from(n)
                    .map_err(|_| LawError::format(join("tabulation", k), format!("{n}: too large")))
            };
            Some(TabulationInfo {
                tolerance: o.num("tolerance")?,
                points_per_branch: count("points_per_branch")?,
                d_min_rule: o.string("d_min_rule")?.to_string(),
                source_evaluations: count("source_evaluations")?,
                converged: o.boolean("converged")?,
            })
        }
    };
    if let (Some(t), Some(m)) = (&tabulation, &measured) {
        if t.converged && !m.is_finite() {
            return Err(LawError::format(
                "tabulation.converged",
                format!(
                    "true, but the measured error is not finite (largest {}): a table whose \
                     error is infinite or undefined has not converged",
                    fmt_num(m.max())
                ),
            ));
        }
    }
    let partial_reload = match top.opt("partial_reload") {
        None => None,
        Some(v) => {
            let o = as_obj(v, "partial_reload".into())?;
            o.keys(&["metric", "method", "max", "p99", "samples", "worst"])?;
            let w = o.sub("worst")?;
            w.keys(&["d", "d_min", "d_turn"])?;
            Some(PartialReloadError {
                stats: read_stats(&o)?,
                worst_d_turn: w.num("d_turn")?,
            })
        }
    };
    let scene = match top.opt("scene") {
        None => Value::Object(Map::new()),
        Some(v) => {
            as_obj(v, "scene".into())?;
            check_no_null(v, "scene")?;
            v.clone()
        }
    };

    let grid = top.numbers("d_min_grid")?;
    let virgin_o = top.sub("virgin")?;
    virgin_o.keys(&["reach", "most_tensile", "d", "pressure"])?;
    let virgin = read_curve(&virgin_o, 0.0, None)?;

    let items = top.array("branches")?;
    if items.len() != grid.len() {
        return Err(LawError::format(
            "branches",
            format!(
                "{} branches for {} values in d_min_grid: one branch per d_min",
                items.len(),
                grid.len()
            ),
        ));
    }
    let mut branches = Vec::with_capacity(items.len());
    for (k, item) in items.iter().enumerate() {
        let b = as_obj(item, format!("branches[{k}]"))?;
        b.keys(&["d_min", "pull_out", "measured_error", "approach", "retract"])?;
        let d_min = b.num("d_min")?;
        if d_min != grid[k] {
            return Err(LawError::format(
                format!("branches[{k}].d_min"),
                format!(
                    "{} m: must equal d_min_grid[{k}] = {} m",
                    fmt_num(d_min),
                    fmt_num(grid[k])
                ),
            ));
        }
        let a = b.sub("approach")?;
        a.keys(&["reach", "most_tensile", "d", "pressure"])?;
        let r = b.sub("retract")?;
        r.keys(&["reach", "positive_tangent", "d", "pressure"])?;
        let pull_out = b.point("pull_out")?;
        let approach = read_curve(&a, d_min, None)?;
        let retract = read_curve(
            &r,
            d_min,
            Some((pull_out, format!("branches[{k}].pull_out"))),
        )?;
        let mut set = BranchSet::new(d_min, approach, retract);
        let stored = match r.opt("positive_tangent") {
            None => None,
            Some(v) => {
                let o = as_obj(v, join(&r.path, "positive_tangent"))?;
                o.keys(&["d", "tangent", "rise", "relative_rise"])?;
                Some(PositiveTangent {
                    d: o.num("d")?,
                    tangent: o.num("tangent")?,
                    rise: o.num("rise")?,
                    relative_rise: o.num("relative_rise")?,
                })
            }
        };
        if stored != set.positive_tangent {
            let found = |t: Option<PositiveTangent>| match t {
                None => "none".to_string(),
                Some(t) => format!(
                    "a tangent of {} Pa/m at d = {} m, rise {} Pa",
                    fmt_num(t.tangent),
                    fmt_num(t.d),
                    fmt_num(t.rise)
                ),
            };
            return Err(LawError::format(
                join(&r.path, "positive_tangent"),
                format!(
                    "{} recorded, but the curve has {}: the record must match the curve",
                    found(stored),
                    found(set.positive_tangent)
                ),
            ));
        }
        if let Some(v) = b.opt("measured_error") {
            let o = as_obj(v, format!("branches[{k}].measured_error"))?;
            o.keys(&["approach", "retract"])?;
            set.measured = Some(BranchError {
                approach: error_value(&o, "approach")?,
                retract: error_value(&o, "retract")?,
            });
        }
        branches.push(set);
    }
    let law = ContactLaw::assemble(
        virgin,
        branches,
        floor,
        Meta {
            length_scale,
            measured,
            tabulation,
            partial_reload,
            scene,
        },
    )?;
    let stored = match top.opt("positive_retract_tangent") {
        None => None,
        Some(v) => {
            let o = as_obj(v, "positive_retract_tangent".into())?;
            o.keys(&[
                "branches",
                "d_min_range",
                "worst",
                "largest_relative_rise",
                "advice",
            ])?;
            o.string("advice")?;
            Some(o.uint("branches")?)
        }
    };
    let have = law.positive_retract.map(|p| p.branches as u64);
    if stored != have {
        return Err(LawError::format(
            "positive_retract_tangent",
            format!(
                "{} branches recorded, but {} retract branches rise before their pull-out: the \
                 summary must match the branches",
                stored.map_or("no".into(), |n| n.to_string()),
                have.unwrap_or(0)
            ),
        ));
    }
    Ok(law)
}

// ------------------------------------------------------------------------------------
// Writing

/// An ordered JSON tree for the writer (the key order of the file is fixed).
enum J {
    Obj(Vec<(&'static str, J)>),
    Arr(Vec<J>),
    Num(f64),
    Int(u64),
    Str(String),
    Bool(bool),
    Raw(Value),
}

fn num_text(v: f64) -> String {
    // serde_json prints the shortest representation that reads back to the same f64; the
    // curves are validated finite, and a non-finite value (an infinite measured error) is
    // written as the string "inf", "-inf" or "nan", never as a finite stand-in
    match serde_json::Number::from_f64(v) {
        Some(n) => n.to_string(),
        None => Value::String(non_finite_word(v).unwrap_or("nan").to_string()).to_string(),
    }
}

fn is_scalar(j: &J) -> bool {
    matches!(j, J::Num(_) | J::Int(_) | J::Str(_) | J::Bool(_))
}

fn write_j(out: &mut String, j: &J, indent: usize) {
    let pad = |n: usize| " ".repeat(n);
    match j {
        J::Num(v) => out.push_str(&num_text(*v)),
        J::Int(v) => out.push_str(&v.to_string()),
        J::Bool(b) => out.push_str(if *b { "true" } else { "false" }),
        J::Str(s) => out.push_str(&Value::String(s.clone()).to_string()),
        J::Raw(v) => write_value(out, v, indent),
        J::Obj(items) => {
            if items.is_empty() {
                out.push_str("{}");
                return;
            }
            out.push_str("{\n");
            for (i, (k, v)) in items.iter().enumerate() {
                out.push_str(&pad(indent + 2));
                out.push_str(&Value::String((*k).to_string()).to_string());
                out.push_str(": ");
                write_j(out, v, indent + 2);
                out.push_str(if i + 1 < items.len() { ",\n" } else { "\n" });
            }
            out.push_str(&pad(indent));
            out.push('}');
        }
        J::Arr(items) => {
            if items.iter().all(is_scalar) {
                // scalars inline, wrapped at about 100 columns
                out.push('[');
                let mut col = indent + 1;
                for (i, v) in items.iter().enumerate() {
                    let mut s = String::new();
                    write_j(&mut s, v, 0);
                    if i > 0 {
                        if col + s.len() + 2 > 100 {
                            out.push_str(",\n");
                            out.push_str(&pad(indent + 1));
                            col = indent + 1;
                        } else {
                            out.push_str(", ");
                            col += 2;
                        }
                    }
                    col += s.len();
                    out.push_str(&s);
                }
                out.push(']');
                return;
            }
            out.push_str("[\n");
            for (i, v) in items.iter().enumerate() {
                out.push_str(&pad(indent + 2));
                write_j(out, v, indent + 2);
                out.push_str(if i + 1 < items.len() { ",\n" } else { "\n" });
            }
            out.push_str(&pad(indent));
            out.push(']');
        }
    }
}

fn write_value(out: &mut String, v: &Value, indent: usize) {
    // a user object (the scene): serde_json's own layout, indented to its place
    let text = serde_json::to_string_pretty(v).unwrap_or_else(|_| "{}".into());
    out.push_str(&text.replace('\n', &format!("\n{}", " ".repeat(indent))));
}

fn point_j(p: Point) -> J {
    J::Obj(vec![("d", J::Num(p.d)), ("pressure", J::Num(p.pressure))])
}

fn nums(v: &[f64]) -> J {
    J::Arr(v.iter().map(|&x| J::Num(x)).collect())
}

fn stats_items(s: &ErrorStats, extra: Option<f64>) -> Vec<(&'static str, J)> {
    let mut worst = vec![("d", J::Num(s.worst_d)), ("d_min", J::Num(s.worst_d_min))];
    if let Some(t) = extra {
        worst.push(("d_turn", J::Num(t)));
    }
    vec![
        ("max", J::Num(s.max)),
        ("p99", J::Num(s.p99)),
        ("samples", J::Int(s.samples as u64)),
        ("worst", J::Obj(worst)),
    ]
}

fn curve_j(c: &Curve, with_most_tensile: bool, positive: Option<PositiveTangent>) -> J {
    let mut items = vec![("reach", J::Num(c.reach()))];
    if with_most_tensile {
        items.push(("most_tensile", point_j(c.most_tensile())));
    }
    if let Some(t) = positive {
        items.push((
            "positive_tangent",
            J::Obj(vec![
                ("d", J::Num(t.d)),
                ("tangent", J::Num(t.tangent)),
                ("rise", J::Num(t.rise)),
                ("relative_rise", J::Num(t.relative_rise)),
            ]),
        ));
    }
    items.push(("d", nums(c.d())));
    items.push(("pressure", nums(c.pressure())));
    J::Obj(items)
}

impl ContactLaw {
    /// The law as `law.json` text (keys in a fixed order, number arrays inline).
    pub fn to_json_string(&self) -> String {
        let mut interp = vec![
            (
                "in_d",
                J::Obj(vec![
                    ("rule", J::Str(RULE_IN_D.into())),
                    ("description", J::Str(DESC_IN_D.into())),
                ]),
            ),
            (
                "in_d_min",
                J::Obj(vec![
                    ("rule", J::Str(RULE_IN_D_MIN.into())),
                    ("description", J::Str(DESC_IN_D_MIN.into())),
                ]),
            ),
            (
                "pressure_floor",
                J::Obj(vec![
                    ("value", J::Num(self.floor)),
                    ("description", J::Str(PRESSURE_FLOOR.into())),
                ]),
            ),
        ];
        if let Some(m) = &self.meta.measured {
            interp.push((
                "measured_error",
                J::Obj(vec![
                    ("metric", J::Str(METRIC.into())),
                    ("method", J::Str(METHOD.into())),
                    ("seed", J::Int(m.seed)),
                    ("virgin", J::Obj(stats_items(&m.virgin, None))),
                    ("approach", J::Obj(stats_items(&m.approach, None))),
                    ("retract", J::Obj(stats_items(&m.retract, None))),
                ]),
            ));
        }
        let mut top = vec![
            ("format", J::Str(FORMAT_NAME.into())),
            ("version", J::Int(FORMAT_VERSION)),
            (
                "units",
                J::Obj(vec![
                    ("d", J::Str("m".into())),
                    ("d_min", J::Str("m".into())),
                    ("pressure", J::Str("Pa".into())),
                    ("tangent", J::Str("Pa/m".into())),
                ]),
            ),
            ("sign_convention", J::Str(SIGN_CONVENTION.into())),
            ("reference_plane", J::Str(REFERENCE_PLANE.into())),
            ("interpolation", J::Obj(interp)),
            (
                "regions",
                J::Obj(vec![
                    ("measured", J::Str(REGION_MEASURED.into())),
                    ("beyond_reach", J::Str(REGION_BEYOND_REACH.into())),
                    ("above_table", J::Str(REGION_ABOVE_TABLE.into())),
                    ("below_table", J::Str(REGION_BELOW_TABLE.into())),
                ]),
            ),
        ];
        if let Some(p) = &self.positive_retract {
            let w = p.worst;
            top.push((
                "positive_retract_tangent",
                J::Obj(vec![
                    ("branches", J::Int(p.branches as u64)),
                    ("d_min_range", nums(&p.d_min_range)),
                    (
                        "worst",
                        J::Obj(vec![
                            ("d_min", J::Num(p.worst_d_min)),
                            ("d", J::Num(w.d)),
                            ("tangent", J::Num(w.tangent)),
                            ("rise", J::Num(w.rise)),
                            ("relative_rise", J::Num(w.relative_rise)),
                        ]),
                    ),
                    ("largest_relative_rise", J::Num(p.largest_relative_rise)),
                    ("advice", J::Str(POSITIVE_ADVICE.into())),
                ]),
            ));
        }
        if let Some(s) = self.meta.length_scale {
            top.push(("length_scale", J::Num(s)));
        }
        if let Some(t) = &self.meta.tabulation {
            top.push((
                "tabulation",
                J::Obj(vec![
                    ("tolerance", J::Num(t.tolerance)),
                    ("points_per_branch", J::Int(t.points_per_branch as u64)),
                    ("d_min_rule", J::Str(t.d_min_rule.clone())),
                    ("source_evaluations", J::Int(t.source_evaluations as u64)),
                    ("converged", J::Bool(t.converged)),
                ]),
            ));
        }
        if let Some(r) = &self.meta.partial_reload {
            let mut items = vec![
                ("metric", J::Str(METRIC.into())),
                ("method", J::Str(RELOAD_METHOD.into())),
            ];
            items.extend(stats_items(&r.stats, Some(r.worst_d_turn)));
            top.push(("partial_reload", J::Obj(items)));
        }
        top.push(("scene", J::Raw(self.meta.scene.clone())));
        top.push(("d_min_grid", nums(&self.grid)));
        top.push(("virgin", curve_j(&self.virgin, true, None)));
        top.push((
            "branches",
            J::Arr(
                self.branches
                    .iter()
                    .map(|b| {
                        let mut items = vec![
                            ("d_min", J::Num(b.d_min)),
                            ("pull_out", point_j(b.pull_out())),
                        ];
                        if let Some(m) = b.measured {
                            items.push((
                                "measured_error",
                                J::Obj(vec![
                                    ("approach", J::Num(m.approach)),
                                    ("retract", J::Num(m.retract)),
                                ]),
                            ));
                        }
                        items.push(("approach", curve_j(&b.approach, true, None)));
                        items.push(("retract", curve_j(&b.retract, false, b.positive_tangent)));
                        J::Obj(items)
                    })
                    .collect(),
            ),
        ));
        let mut out = String::new();
        write_j(&mut out, &J::Obj(top), 0);
        out.push('\n');
        out
    }

    /// Writes `law.json`.
    pub fn write_json(&self, path: impl AsRef<FsPath>) -> Result<(), LawError> {
        let path = path.as_ref();
        std::fs::write(path, self.to_json_string()).map_err(|source| LawError::Io {
            path: path.display().to_string(),
            source,
        })
    }

    /// Writes `law.csv`: the long form of the tabulated nodes, columns
    /// `d_min_m,path,d_m,pressure_pa,tangent_pa_per_m`. `path` is `virgin`, `approach` or
    /// `retract`; virgin rows leave `d_min_m` empty (the envelope has no history). The
    /// pressure is the tabulated value, the tangent the slope of that curve's interpolant
    /// at the node (the left slope at the reach).
    pub fn write_csv<W: Write>(&self, mut w: W) -> std::io::Result<()> {
        writeln!(w, "d_min_m,path,d_m,pressure_pa,tangent_pa_per_m")?;
        for (i, (&d, &p)) in self
            .virgin
            .d()
            .iter()
            .zip(self.virgin.pressure())
            .enumerate()
        {
            let t = self
                .virgin
                .interp()
                .value_and_slope(self.virgin.interp().nodes()[i])
                .1;
            writeln!(w, ",virgin,{d:e},{p:e},{t:e}")?;
        }
        for b in &self.branches {
            for c in [&b.approach, &b.retract] {
                let name = if std::ptr::eq(c, &b.approach) {
                    "approach"
                } else {
                    "retract"
                };
                for (i, (&d, &p)) in c.d().iter().zip(c.pressure()).enumerate() {
                    let t = c.interp().value_and_slope(c.interp().nodes()[i]).1;
                    writeln!(w, "{:e},{name},{d:e},{p:e},{t:e}", b.d_min)?;
                }
            }
        }
        Ok(())
    }

    /// Writes `law.csv` to a file (see [`ContactLaw::write_csv`]).
    pub fn write_csv_file(&self, path: impl AsRef<FsPath>) -> Result<(), LawError> {
        let path = path.as_ref();
        let io = |source| LawError::Io {
            path: path.display().to_string(),
            source,
        };
        let file = std::fs::File::create(path).map_err(io)?;
        let mut buf = std::io::BufWriter::new(file);
        self.write_csv(&mut buf).map_err(io)?;
        buf.flush().map_err(io)
    }
}
