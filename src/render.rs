//! How reports leave the program: formats, numbers with units that fit, warnings, and
//! standard output that survives a closed pipe (files: [`crate::output`]).

use crate::error::Error;
pub use crate::output::{write_file, OutputSet};
use serde::Serialize;
use std::io::Write;

/// Output format of a subcommand.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Pretty-printed JSON.
    Json,
    /// Comma-separated values, one header row.
    Csv,
    /// A table for people.
    Table,
}

/// A physics guard raised by a run: the model is used where it leaves its ground.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// Stable identifier (`adhesion_yields_asperity`, `beyond_fit_range`,
    /// `pressure_above_hardness`, ...).
    pub code: &'static str,
    /// What happened and what it means, with numbers.
    pub message: String,
}

/// A report that can be rendered in every format.
pub trait Render: Serialize {
    /// The table for people.
    fn table(&self) -> String;
    /// The CSV form.
    fn csv(&self) -> String;
    /// The guards raised.
    fn warnings(&self) -> &[Warning] {
        &[]
    }
    /// The report in `format`.
    fn render(&self, format: Format) -> String {
        match format {
            Format::Json => json(self),
            Format::Csv => self.csv(),
            Format::Table => self.table(),
        }
    }
}

/// Pretty JSON with a final newline. Reports hold no NaN or infinity (absent values are
/// omitted), so serialisation cannot fail.
pub fn json<T: Serialize + ?Sized>(v: &T) -> String {
    serde_json::to_string_pretty(v).expect("reports hold finite numbers and string keys") + "\n"
}

/// A float as JSON: the number when finite, else its name (`"inf"`, `"-inf"`, `"NaN"`),
/// never `null` (serde `serialize_with`; an infinite yield stress means "never yields").
pub fn number_or_name<S: serde::Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if v.is_finite() {
        s.serialize_f64(*v)
    } else {
        s.serialize_str(&crate::scene::num(*v))
    }
}

/// [`number_or_name`] for an optional float (absent ones are skipped by the field).
pub fn some_number_or_name<S: serde::Serializer>(v: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
    match v {
        Some(v) => number_or_name(v, s),
        None => s.serialize_none(),
    }
}

/// Skips a float that is not finite (serde `skip_serializing_if`).
pub fn not_finite(v: &f64) -> bool {
    !v.is_finite()
}

/// `value` in `unit` with the SI prefix that keeps 1 to 3 digits before the point and
/// `digits` significant digits (never "0.000000" for a non-zero value).
pub fn si(value: f64, unit: &str, digits: usize) -> String {
    if value == 0.0 {
        return format!("0 {unit}");
    }
    if !value.is_finite() {
        return format!("{value} {unit}");
    }
    const PREFIXES: [(f64, &str); 9] = [
        (1e12, "T"),
        (1e9, "G"),
        (1e6, "M"),
        (1e3, "k"),
        (1.0, ""),
        (1e-3, "m"),
        (1e-6, "u"),
        (1e-9, "n"),
        (1e-12, "p"),
    ];
    let a = value.abs();
    if !(1e-12..1e15).contains(&a) {
        return format!("{value:.*e} {unit}", digits.saturating_sub(1));
    }
    let (scale, prefix) = PREFIXES
        .iter()
        .copied()
        .find(|(s, _)| a >= *s)
        .unwrap_or((1e-12, "p"));
    let x = value / scale;
    if x.abs() >= 1e3 || x.abs() < 1e-3 {
        return format!("{value:.*e} {unit}", digits.saturating_sub(1));
    }
    let int_digits = (x.abs().log10().floor() as i64 + 1).max(1) as usize;
    let decimals = digits.saturating_sub(int_digits);
    format!("{x:.decimals$} {prefix}{unit}")
}

/// A pressure in Pa, kPa, MPa or GPa, 4 significant digits.
pub fn pressure(p: f64) -> String {
    si(p, "Pa", 4)
}

/// Writes `text` to standard output. A closed pipe (the reader went away, as `| head`
/// does) ends the program quietly with status 0; any other failure is an error.
pub fn emit(text: &str) -> Result<(), Error> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => std::process::exit(0),
        Err(source) => Err(Error::Write {
            path: "standard output".into(),
            source,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_take_the_prefix_that_fits_and_never_print_zero_for_a_value() {
        assert_eq!(pressure(16_880.37), "16.88 kPa");
        assert_eq!(pressure(2.446e6), "2.446 MPa");
        assert_eq!(pressure(6.0e-5), "60.00 uPa");
        assert_eq!(pressure(0.0), "0 Pa");
        assert_eq!(si(-1.81e6, "Pa", 3), "-1.81 MPa");
        assert_eq!(si(7.78e-9, "m", 3), "7.78 nm");
        assert_eq!(si(1e-20, "Pa", 3), "1.00e-20 Pa");
        assert_eq!(si(1.2e-15, "m", 2), "1.2e-15 m");
        for v in [1e-14, 3e-7, 0.4, 12.0, 7e5, 4e11, 2e16] {
            assert!(!pressure(v).starts_with("0.000"), "{v}: {}", pressure(v));
        }
    }
}
