//! How results leave the program: formats, numbers with units that fit, warnings, the
//! model's validity, and standard output that survives a closed pipe (files:
//! [`crate::output`]).

use crate::ReportError as Error;
use serde::Serialize;
use std::io::Write;
pub use stiction_model::guards::{si, Validity, Warning};

/// Output format of a subcommand.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Format {
    /// Pretty-printed JSON.
    Json,
    /// Comma-separated values, one header row.
    Csv,
    /// A table for people.
    Table,
}

/// A result that can be rendered in every format.
pub trait Render: Serialize {
    /// The table for people.
    fn table(&self) -> String;
    /// The CSV form.
    fn csv(&self) -> String;
    /// The guards raised.
    fn warnings(&self) -> &[Warning] {
        &[]
    }
    /// Whether the model holds for the result (None: the result has no verdict on it).
    fn validity(&self) -> Option<&Validity> {
        None
    }
    /// The result in `format` (`columns`: JSON curves as column arrays).
    fn render(&self, format: Format, columns: bool) -> String {
        match format {
            Format::Json if columns => {
                json(&columnar(serde_json::to_value(self).unwrap_or_default()))
            }
            Format::Json => json(self),
            Format::Csv => self.csv(),
            Format::Table => self.table(),
        }
    }
}

/// Pretty JSON with a final newline. Results hold no NaN or infinity (absent values are
/// omitted, infinite ones named), so serialisation cannot fail.
pub fn json<T: Serialize + ?Sized>(v: &T) -> String {
    serde_json::to_string_pretty(v).expect("results hold finite numbers and string keys") + "\n"
}

/// The JSON tree with every array of points (objects with the same keys, each holding
/// only numbers, booleans or strings) turned into an object of column arrays: what numpy
/// and pandas read directly.
pub fn columnar(v: serde_json::Value) -> serde_json::Value {
    use serde_json::Value as J;
    match v {
        J::Array(items) => {
            let rows: Option<Vec<&serde_json::Map<String, J>>> =
                items.iter().map(|i| i.as_object()).collect();
            let flat = |o: &&serde_json::Map<String, J>| {
                o.values().all(|x| !x.is_array() && !x.is_object())
            };
            match rows {
                Some(rows) if !rows.is_empty() && rows.iter().all(flat) => {
                    let keys: Vec<&String> = rows[0].keys().collect();
                    if rows
                        .iter()
                        .all(|r| r.len() == keys.len() && keys.iter().all(|k| r.contains_key(*k)))
                    {
                        let mut out = serde_json::Map::new();
                        for k in keys {
                            out.insert(
                                k.clone(),
                                J::Array(rows.iter().map(|r| r[k.as_str()].clone()).collect()),
                            );
                        }
                        return J::Object(out);
                    }
                    J::Array(items.into_iter().map(columnar).collect())
                }
                _ => J::Array(items.into_iter().map(columnar).collect()),
            }
        }
        J::Object(o) => J::Object(o.into_iter().map(|(k, x)| (k, columnar(x))).collect()),
        other => other,
    }
}

/// A pressure in Pa, kPa, MPa or GPa, 4 significant digits.
pub fn pressure(p: f64) -> String {
    si(p, "Pa", 4)
}

/// A number in CSV: shortest round-trip digits in scientific notation (every command
/// writes the same format), empty for an absent value.
pub fn csv_num(v: f64) -> String {
    // a negative zero (a force at the jump, rounding) reads as 0 in a table of numbers
    let v = if v == 0.0 { 0.0 } else { v };
    format!("{v:e}")
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

/// Prints the warnings of a result on standard error.
pub fn print_warnings(warnings: &[Warning]) {
    for w in warnings {
        eprintln!("warning[{}]: {}", w.code, w.message);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_numbers_round_trip_and_a_negative_zero_reads_as_zero() {
        assert_eq!(csv_num(-0.0), "0e0");
        assert_eq!(csv_num(0.0), "0e0");
        for v in [-1.5e-9, 7.78e-9, 1e308, -3.0] {
            assert_eq!(csv_num(v).parse::<f64>().unwrap(), v);
        }
    }

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

    #[test]
    fn arrays_of_points_become_columns_and_nothing_else_changes() {
        let v = serde_json::json!({
            "curve": [{"d": 1.0, "p": 2.0}, {"d": 3.0, "p": 4.0}],
            "cycles": [{"cycle": 1, "unloading": [{"d": 1.0, "p": 0.5}]}],
            "names": ["a", "b"],
            "n": 3
        });
        let c = columnar(v);
        assert_eq!(
            c["curve"],
            serde_json::json!({"d": [1.0, 3.0], "p": [2.0, 4.0]})
        );
        assert_eq!(
            c["cycles"][0]["unloading"],
            serde_json::json!({"d": [1.0], "p": [0.5]})
        );
        assert_eq!(c["names"], serde_json::json!(["a", "b"]));
        assert_eq!(c["n"], 3);
    }
}
