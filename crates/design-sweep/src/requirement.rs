//! A second requirement on a design beside freedom from stiction, such as a contact
//! resistance below a limit: `--require contact_resistance<1`.

use crate::point::DesignPoint;
use crate::DesignError;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The quantities of a design point a requirement can bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Quantity {
    /// Contact resistance of the closed switch under the hold voltage, after the last cycle
    /// (ohm).
    ContactResistance,
    /// Real contact area over the contact area under the hold voltage, after the last
    /// cycle (-).
    RealContactFraction,
}

impl Quantity {
    /// Every quantity, in the order the error messages list them.
    pub const ALL: [Quantity; 2] = [Quantity::ContactResistance, Quantity::RealContactFraction];

    /// The name a requirement and the map columns use.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::ContactResistance => "contact_resistance",
            Quantity::RealContactFraction => "real_contact_fraction",
        }
    }

    /// The SI unit ("" for a ratio).
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::ContactResistance => "ohm",
            Quantity::RealContactFraction => "",
        }
    }

    /// The value of a design point, if it has one.
    pub fn of(self, d: &DesignPoint) -> Option<f64> {
        match self {
            Quantity::ContactResistance => d.contact_resistance,
            Quantity::RealContactFraction => d.real_contact_fraction,
        }
    }
}

/// Which side of the limit is required.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// The quantity below the limit (`<` or `<=`).
    Below,
    /// The quantity above the limit (`>` or `>=`).
    Above,
}

/// A requirement `QUANTITY<LIMIT` or `QUANTITY>LIMIT` (`<=` and `>=` read the same: on a
/// continuous quantity the boundary itself has no weight), the limit in the quantity's SI
/// unit and > 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Requirement {
    /// What is bounded.
    pub quantity: Quantity,
    /// Which side.
    pub bound: Bound,
    /// The limit (SI, > 0).
    pub limit: f64,
}

impl Requirement {
    /// Parses `contact_resistance<1`, `real_contact_fraction>=0.01`, spaces allowed.
    /// Errors name the text and say what is accepted.
    pub fn parse(text: &str) -> Result<Self, DesignError> {
        let names = Quantity::ALL
            .iter()
            .map(|q| {
                format!(
                    "{} ({})",
                    q.name(),
                    if q.unit().is_empty() { "-" } else { q.unit() }
                )
            })
            .collect::<Vec<_>>()
            .join(", ");
        let bad = |why: String| {
            DesignError::Requirement(format!(
                "`{text}`: {why}; write QUANTITY<LIMIT or QUANTITY>LIMIT with QUANTITY one of {names} and LIMIT > 0 in its SI unit, e.g. contact_resistance<1"
            ))
        };
        let (at, bound, width) = match (text.find('<'), text.find('>')) {
            (Some(i), None) => (i, Bound::Below, 1),
            (None, Some(i)) => (i, Bound::Above, 1),
            _ => return Err(bad("one comparison < or > expected".into())),
        };
        let width = if text[at + width..].starts_with('=') {
            width + 1
        } else {
            width
        };
        let name = text[..at].trim();
        let quantity = Quantity::ALL
            .into_iter()
            .find(|q| q.name() == name)
            .ok_or_else(|| bad(format!("unknown quantity `{name}`")))?;
        let value = text[at + width..].trim();
        let limit: f64 = value
            .parse()
            .map_err(|_| bad(format!("the limit `{value}` is not a number")))?;
        if !(limit.is_finite() && limit > 0.0) {
            return Err(bad(format!("the limit {value} must be finite and > 0")));
        }
        if quantity == Quantity::RealContactFraction && limit > 1.0 {
            return Err(bad(format!(
                "the limit {value} of a fraction of the contact area must be at most 1"
            )));
        }
        Ok(Self {
            quantity,
            bound,
            limit,
        })
    }

    /// ln(q / limit), signed so that it is < 0 where the requirement is met (`None` when
    /// the point has no value of the quantity, or a value of 0 or below).
    pub fn margin(&self, d: &DesignPoint) -> Option<f64> {
        let q = self.quantity.of(d)?;
        if !(q > 0.0) {
            return None;
        }
        let m = (q / self.limit).ln();
        Some(match self.bound {
            Bound::Below => m,
            Bound::Above => -m,
        })
    }

    /// Whether a point meets it (`None` without its quantity: a switch that does not close
    /// or opens under the hold voltage has no contact resistance).
    pub fn met(&self, d: &DesignPoint) -> Option<bool> {
        self.margin(d).map(|m| m < 0.0)
    }

    /// A point in the design window: free of stiction and meeting the requirement.
    pub fn in_window(&self, d: &DesignPoint) -> bool {
        d.free() && self.met(d) == Some(true)
    }
}

impl std::fmt::Display for Requirement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let op = match self.bound {
            Bound::Below => "<",
            Bound::Above => ">",
        };
        write!(f, "{}{op}{:e}", self.quantity.name(), self.limit)
    }
}

impl Serialize for Requirement {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for Requirement {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        Requirement::parse(&text).map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(r: Option<f64>, ratio: f64) -> DesignPoint {
        DesignPoint {
            pull_out_ratio: ratio,
            largest_pull_out_pa: ratio * 10.0,
            restoring_pressure_pa: 10.0,
            cycles_to_accommodation: Some(3),
            first_sticking_cycle: (ratio > 1.0).then_some(1),
            sticks: ratio > 1.0,
            closes: true,
            validity_holds: true,
            accommodation_cause: None,
            contact_resistance: r,
            real_contact_fraction: None,
        }
    }

    #[test]
    fn parses_and_reads_back() {
        let r = Requirement::parse("contact_resistance < 0.5").unwrap();
        assert_eq!(r.quantity, Quantity::ContactResistance);
        assert_eq!(r.bound, Bound::Below);
        assert_eq!(r.limit, 0.5);
        assert_eq!(Requirement::parse(&r.to_string()).unwrap(), r);
        let r = Requirement::parse("real_contact_fraction>=1e-3").unwrap();
        assert_eq!((r.bound, r.limit), (Bound::Above, 1e-3));
    }

    #[test]
    fn bad_requirements_say_why() {
        for (text, why) in [
            ("contact_resistance=1", "one comparison"),
            ("resistance<1", "unknown quantity `resistance`"),
            ("contact_resistance<one", "not a number"),
            ("contact_resistance<-1", "finite and > 0"),
            ("real_contact_fraction<2", "at most 1"),
            ("a<1>2", "one comparison"),
        ] {
            let e = Requirement::parse(text).unwrap_err().to_string();
            assert!(e.contains(why) && e.contains(text), "{text}: {e}");
        }
    }

    #[test]
    fn the_window_needs_both() {
        let r = Requirement::parse("contact_resistance<1").unwrap();
        assert!(r.in_window(&point(Some(0.5), 0.5)));
        assert!(!r.in_window(&point(Some(2.0), 0.5)), "too resistive");
        assert!(!r.in_window(&point(Some(0.5), 2.0)), "sticks");
        assert!(!r.in_window(&point(None, 0.5)), "no resistance");
        assert_eq!(r.met(&point(None, 0.5)), None);
        assert!((r.margin(&point(Some(2.0), 0.5)).unwrap() - 2f64.ln()).abs() < 1e-15);
    }
}
