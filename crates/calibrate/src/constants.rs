//! The six constants of eq 13 and the selection of those to fit.

use crate::error::CalibError;
use asperity_plastic::EffectiveRadiusFit;
use serde::Serialize;
use std::fmt;
use std::str::FromStr;

/// One constant of eq 13: c1(omega) = a1 + a2 exp(-a3 omega),
/// c2(omega) = b1/(1 + (omega/b2)^2) - b3 (`a1` is `EffectiveRadiusFit::c1[0]`, ...).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Constant {
    /// a1 = `c1[0]`, the large-omega limit of c1.
    A1,
    /// a2 = `c1[1]`.
    A2,
    /// a3 = `c1[2]`, the decay rate of c1 in omega.
    A3,
    /// b1 = `c2[0]`.
    B1,
    /// b2 = `c2[1]`, the omega scale of c2.
    B2,
    /// b3 = `c2[2]`.
    B3,
}

impl Constant {
    /// All six, in the order a1, a2, a3, b1, b2, b3.
    pub const ALL: [Constant; 6] = [
        Constant::A1,
        Constant::A2,
        Constant::A3,
        Constant::B1,
        Constant::B2,
        Constant::B3,
    ];

    /// Position in [a1, a2, a3, b1, b2, b3].
    pub fn index(self) -> usize {
        self as usize
    }

    /// `a1` ... `b3`.
    pub fn name(self) -> &'static str {
        ["a1", "a2", "a3", "b1", "b2", "b3"][self.index()]
    }

    /// Its value in `fit`.
    pub fn get(self, fit: &EffectiveRadiusFit) -> f64 {
        to_array(fit)[self.index()]
    }
}

impl fmt::Display for Constant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// [a1, a2, a3, b1, b2, b3] of a fit.
pub(crate) fn to_array(fit: &EffectiveRadiusFit) -> [f64; 6] {
    [
        fit.c1[0], fit.c1[1], fit.c1[2], fit.c2[0], fit.c2[1], fit.c2[2],
    ]
}

/// The validated fit of [a1, a2, a3, b1, b2, b3].
pub(crate) fn from_array(
    t: &[f64; 6],
) -> Result<EffectiveRadiusFit, asperity_plastic::PlasticError> {
    EffectiveRadiusFit::new([t[0], t[1], t[2]], [t[3], t[4], t[5]])
}

/// The constants to fit (the others are held at their starting values).
///
/// Parsed from a comma-separated list of `c1` (a1, a2, a3), `c2` (b1, b2, b3), `all`, or
/// single names `a1` ... `b3`:
///
/// ```
/// use calibrate::{Constant, Selection};
/// let s: Selection = "c1,b3".parse()?;
/// assert_eq!(s.constants(), [Constant::A1, Constant::A2, Constant::A3, Constant::B3]);
/// assert!("c3".parse::<Selection>().is_err());
/// # Ok::<(), calibrate::CalibError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Selection([bool; 6]);

impl Selection {
    /// a1, a2, a3.
    pub const C1: Self = Self([true, true, true, false, false, false]);
    /// b1, b2, b3.
    pub const C2: Self = Self([false, false, false, true, true, true]);
    /// All six.
    pub const ALL: Self = Self([true; 6]);

    /// The selection of exactly `constants` (may be empty).
    pub fn of(constants: &[Constant]) -> Self {
        let mut s = [false; 6];
        for c in constants {
            s[c.index()] = true;
        }
        Self(s)
    }

    /// Whether `c` is selected.
    pub fn contains(&self, c: Constant) -> bool {
        self.0[c.index()]
    }

    /// The selected constants in the order a1 ... b3.
    pub fn constants(&self) -> Vec<Constant> {
        Constant::ALL
            .into_iter()
            .filter(|c| self.contains(*c))
            .collect()
    }

    /// How many are selected.
    pub fn len(&self) -> usize {
        self.0.iter().filter(|b| **b).count()
    }

    /// True when none is selected.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl Default for Selection {
    /// All six constants.
    fn default() -> Self {
        Self::ALL
    }
}

impl FromStr for Selection {
    type Err = CalibError;

    fn from_str(text: &str) -> Result<Self, CalibError> {
        let bad = |reason: String| CalibError::Selection {
            text: text.to_string(),
            reason,
        };
        let mut s = [false; 6];
        for token in text.split(',').map(str::trim) {
            match token {
                "c1" => s[..3].fill(true),
                "c2" => s[3..].fill(true),
                "all" => s.fill(true),
                "" => return Err(bad("empty name".into())),
                name => match Constant::ALL.iter().find(|c| c.name() == name) {
                    Some(c) => s[c.index()] = true,
                    None => {
                        return Err(bad(format!(
                            "unknown constant {name:?} (use c1, c2, all, or a1, a2, a3, b1, b2, b3)"
                        )))
                    }
                },
            }
        }
        Ok(Self(s))
    }
}

impl fmt::Display for Selection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = self.constants().iter().map(|c| c.name()).collect();
        f.write_str(&names.join(","))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn selections_parse_and_print() {
        assert_eq!("c1,c2".parse::<Selection>().unwrap(), Selection::ALL);
        assert_eq!(" c2 ".parse::<Selection>().unwrap(), Selection::C2);
        assert_eq!("a1,a2,a3".parse::<Selection>().unwrap(), Selection::C1);
        assert_eq!("a1, b3".parse::<Selection>().unwrap().to_string(), "a1,b3");
        for bad in ["", "c1,", "A1", "c3", "a4"] {
            assert!(bad.parse::<Selection>().is_err(), "{bad:?}");
        }
        let fit = EffectiveRadiusFit::PAPER;
        assert_eq!(Constant::A3.get(&fit), 0.092);
        assert_eq!(Constant::B2.get(&fit), 10.0);
        assert_eq!(from_array(&to_array(&fit)).unwrap(), fit);
    }
}
