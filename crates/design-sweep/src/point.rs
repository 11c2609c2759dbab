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
    /// The model holds at this point (no guard puts it outside its validity).
    #[serde(default = "holds")]
    pub validity_holds: bool,
    /// Why the point counts as accommodated: the history saturating, or an impact that did
    /// not deepen (every later cycle repeats it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accommodation_cause: Option<AccommodationCause>,
    /// Contact resistance of the closed switch under the hold voltage after the last cycle
    /// (ohm), when the scene gives the films' conduction and the electrode area.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_resistance: Option<f64>,
    /// Real contact area over the contact area under the hold voltage after the last cycle
    /// (-), when the contact state was computed and the switch rests shut.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub real_contact_fraction: Option<f64>,
}

fn holds() -> bool {
    true
}

/// Why a design point counts as accommodated (as the switch model reports it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum AccommodationCause {
    /// The impacts still deepen, by less than the tolerance.
    Saturated,
    /// An impact did not go deeper than an earlier one: the history stopped changing.
    NonDeepening,
}

impl AccommodationCause {
    /// The cause as a word (`saturated`, `non_deepening`), as in JSON and CSV.
    pub fn as_str(self) -> &'static str {
        match self {
            AccommodationCause::Saturated => "saturated",
            AccommodationCause::NonDeepening => "non_deepening",
        }
    }
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
            validity_holds: true,
            accommodation_cause: None,
            contact_resistance: None,
            real_contact_fraction: None,
        }
    }

    /// Free of stiction: the switch closes and the ratio stays below 1. A switch that does
    /// not close is never free (it is not a working design).
    pub fn free(&self) -> bool {
        self.closes && self.pull_out_ratio < 1.0
    }

    /// Checks that the values agree with each other, as a switch run makes them:
    ///
    /// * `pull_out_ratio`, `largest_pull_out_pa` and `restoring_pressure_pa` finite and >= 0;
    /// * a closing point has `restoring_pressure_pa` > 0, `sticks` exactly when
    ///   `pull_out_ratio` > 1, `first_sticking_cycle` exactly when it sticks, and a ratio
    ///   above 0 only with a pull-out above 0;
    /// * a point that does not close has ratio 0, pull-out 0, does not stick and has no
    ///   cycle numbers (no cycle ran);
    /// * cycle numbers count from 1.
    ///
    /// The error starts with the key at fault and gives its value.
    pub fn check(&self) -> Result<(), String> {
        let checks = [
            ("pull_out_ratio", self.pull_out_ratio),
            ("largest_pull_out_pa", self.largest_pull_out_pa),
            ("restoring_pressure_pa", self.restoring_pressure_pa),
        ];
        for (name, v) in checks {
            let what = if v.is_nan() {
                "is not a number".to_owned()
            } else if v.is_infinite() {
                format!("= {v} is infinite")
            } else if v < 0.0 {
                format!("= {v:e} is negative")
            } else {
                continue;
            };
            return Err(format!("{name} {what}: must be finite and >= 0"));
        }
        if let Some(r) = self.contact_resistance {
            if !(r.is_finite() && r > 0.0) {
                return Err(format!(
                    "contact_resistance = {r:e}: must be finite and > 0"
                ));
            }
        }
        if let Some(f) = self.real_contact_fraction {
            if !(f.is_finite() && f >= 0.0) {
                return Err(format!(
                    "real_contact_fraction = {f:e}: must be finite and >= 0"
                ));
            }
        }
        for (name, c) in [
            ("cycles_to_accommodation", self.cycles_to_accommodation),
            ("first_sticking_cycle", self.first_sticking_cycle),
        ] {
            if c == Some(0) {
                return Err(format!("{name} = 0: cycles count from 1"));
            }
        }
        let ratio = self.pull_out_ratio;
        if !self.closes {
            let found = if ratio != 0.0 {
                Some(("pull_out_ratio", format!("{ratio:e}")))
            } else if self.largest_pull_out_pa != 0.0 {
                Some((
                    "largest_pull_out_pa",
                    format!("{:e}", self.largest_pull_out_pa),
                ))
            } else if self.sticks {
                Some(("sticks", "true".to_owned()))
            } else if let Some(c) = self.cycles_to_accommodation {
                Some(("cycles_to_accommodation", c.to_string()))
            } else if let Some(c) = self.accommodation_cause {
                Some(("accommodation_cause", format!("{c:?}")))
            } else if !self.validity_holds {
                Some(("validity_holds", "false".to_owned()))
            } else if let Some(r) = self.contact_resistance {
                Some(("contact_resistance", format!("{r:e}")))
            } else if let Some(f) = self.real_contact_fraction {
                Some(("real_contact_fraction", format!("{f:e}")))
            } else {
                self.first_sticking_cycle
                    .map(|c| ("first_sticking_cycle", c.to_string()))
            };
            return match found {
                Some((key, v)) => Err(format!(
                    "{key} = {v} with closes = false: a switch that does not close has ratio 0, \
                     pull-out 0, does not stick and runs no cycle"
                )),
                None => Ok(()),
            };
        }
        if self.restoring_pressure_pa == 0.0 {
            return Err(
                "restoring_pressure_pa = 0e0 with closes = true: a closing switch needs a \
                 restoring pressure > 0 for its ratio"
                    .to_owned(),
            );
        }
        if self.sticks != (ratio > 1.0) {
            return Err(format!(
                "sticks = {} with pull_out_ratio = {ratio:e}: a closing switch sticks exactly \
                 when the ratio exceeds 1",
                self.sticks
            ));
        }
        if self.first_sticking_cycle.is_some() != self.sticks {
            return Err(match self.first_sticking_cycle {
                Some(c) => format!(
                    "first_sticking_cycle = {c} with sticks = false: a cycle that sticks makes \
                     the point stick"
                ),
                None => "first_sticking_cycle absent with sticks = true: a sticking point \
                         names its first sticking cycle"
                    .to_owned(),
            });
        }
        if ratio > 0.0 && self.largest_pull_out_pa == 0.0 {
            return Err(format!(
                "pull_out_ratio = {ratio:e} with largest_pull_out_pa = 0e0: the ratio is \
                 proportional to the pull-out"
            ));
        }
        Ok(())
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

/// Calls `eval` and turns its answer into a status: errors, panics and points that fail
/// [`DesignPoint::check`] (non-finite or negative numbers, contradictory values) become
/// `OutOfDomain`/`Failed`, a switch that does not close `DoesNotClose`. The design point
/// is returned for `Ok` and `DoesNotClose` only.
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
            if let Err(m) = p.check() {
                return (
                    Status::Failed(format!("evaluator returned an inconsistent point: {m}")),
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
