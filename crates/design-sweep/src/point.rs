//! One design point, its status, and the guarded call of an evaluator.

use serde::{Deserialize, Serialize};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// One design point: a switch scene run until accommodated, reduced to what a designer needs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DesignPoint {
    /// Largest pull-out pressure over restoring pressure; > 1 sticks; 0 if it does not close.
    pub pull_out_ratio: f64,
    /// Largest pull-out pressure over the cycles (Pa).
    pub largest_pull_out_pa: f64,
    /// Restoring pressure of the spring, K_s d0 (Pa).
    pub restoring_pressure_pa: f64,
    /// Cycle after which the surface had accommodated, if it did.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycles_to_accommodation: Option<usize>,
    /// First cycle whose pull-out pressure exceeded the restoring pressure, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_sticking_cycle: Option<usize>,
    /// The switch stays shut.
    pub sticks: bool,
    /// The electrode reaches contact (dynamic pull-in).
    pub closes: bool,
}

impl DesignPoint {
    /// The point of a switch that does not close: ratio 0, no pull-out, nothing sticks.
    pub fn does_not_close(restoring_pressure_pa: f64) -> Self {
        DesignPoint {
            pull_out_ratio: 0.0,
            largest_pull_out_pa: 0.0,
            restoring_pressure_pa,
            cycles_to_accommodation: None,
            first_sticking_cycle: None,
            sticks: false,
            closes: false,
        }
    }
}

/// Why an evaluator could not give a [`DesignPoint`]; becomes the point's [`Status`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PointError {
    /// The point's values leave a field's domain (bad input for that point).
    OutOfDomain(String),
    /// The run failed numerically.
    Failed(String),
}

impl From<String> for PointError {
    fn from(m: String) -> Self {
        PointError::Failed(m)
    }
}

impl From<&str> for PointError {
    fn from(m: &str) -> Self {
        PointError::Failed(m.to_owned())
    }
}

impl std::fmt::Display for PointError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PointError::OutOfDomain(m) => write!(f, "out of domain: {m}"),
            PointError::Failed(m) => write!(f, "failed: {m}"),
        }
    }
}

/// What became of one point. Points that are not `Ok` do not stop a map or a scan.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Status {
    /// The switch closes; the ratio says whether it sticks.
    Ok,
    /// The switch does not close (no dynamic pull-in): ratio 0.
    DoesNotClose,
    /// The point's values leave a field's domain; the message says which.
    OutOfDomain(String),
    /// The run failed (numerical failure, non-finite result or panic); the message says how.
    Failed(String),
}

impl Status {
    /// Short snake_case word: `ok`, `does_not_close`, `out_of_domain`, `failed`.
    pub fn word(&self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::DoesNotClose => "does_not_close",
            Status::OutOfDomain(_) => "out_of_domain",
            Status::Failed(_) => "failed",
        }
    }

    /// The message of `OutOfDomain` and `Failed`.
    pub fn detail(&self) -> Option<&str> {
        match self {
            Status::OutOfDomain(m) | Status::Failed(m) => Some(m),
            _ => None,
        }
    }

    /// Whether the point has a [`DesignPoint`] (`Ok` or `DoesNotClose`).
    pub fn has_design(&self) -> bool {
        matches!(self, Status::Ok | Status::DoesNotClose)
    }

    pub(crate) fn from_parts(word: &str, detail: Option<String>) -> Option<Status> {
        Some(match word {
            "ok" => Status::Ok,
            "does_not_close" => Status::DoesNotClose,
            "out_of_domain" => Status::OutOfDomain(detail.unwrap_or_default()),
            "failed" => Status::Failed(detail.unwrap_or_default()),
            _ => return None,
        })
    }
}

/// Calls `eval` and turns its answer into a status: errors, panics and non-finite or
/// negative numbers become `OutOfDomain`/`Failed`, a switch that does not close
/// `DoesNotClose`. The design point is returned for `Ok` and `DoesNotClose` only.
pub(crate) fn guarded<E, F>(eval: F) -> (Status, Option<DesignPoint>)
where
    E: Into<PointError>,
    F: FnOnce() -> Result<DesignPoint, E>,
{
    let answer = match catch_unwind(AssertUnwindSafe(eval)) {
        Ok(a) => a,
        Err(payload) => {
            let msg = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            return (Status::Failed(format!("evaluator panicked: {msg}")), None);
        }
    };
    match answer.map_err(Into::into) {
        Err(PointError::OutOfDomain(m)) => (Status::OutOfDomain(m), None),
        Err(PointError::Failed(m)) => (Status::Failed(m), None),
        Ok(p) => {
            let checks = [
                ("pull_out_ratio", p.pull_out_ratio),
                ("largest_pull_out_pa", p.largest_pull_out_pa),
                ("restoring_pressure_pa", p.restoring_pressure_pa),
            ];
            for (name, v) in checks {
                let what = if v.is_nan() {
                    "not a number".to_owned()
                } else if v.is_infinite() {
                    "infinite".to_owned()
                } else if v < 0.0 {
                    format!("negative ({v:e})")
                } else {
                    continue;
                };
                return (
                    Status::Failed(format!(
                        "evaluator returned a {name} that is {what}: must be finite and >= 0"
                    )),
                    None,
                );
            }
            if p.closes {
                (Status::Ok, Some(p))
            } else {
                (Status::DoesNotClose, Some(p))
            }
        }
    }
}

/// Checks a scene key written `section.key` (ASCII letters, digits, `_`, at least one dot).
pub(crate) fn check_field(field: &str) -> Result<(), String> {
    let ok = !field.is_empty()
        && field.contains('.')
        && field
            .split('.')
            .all(|p| !p.is_empty() && p.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'));
    if ok {
        Ok(())
    } else {
        Err(format!(
            "FIELD `{field}` is not a scene key written section.key (e.g. switch.k_s)"
        ))
    }
}
