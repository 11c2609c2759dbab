//! The CSV files of the design questions (`map.csv`, `samples.csv`), written with the
//! `csv` crate (quoting a word or a detail that holds a comma); the curves' CSV of the
//! other results is plain text in each result's module ([`crate::render::csv_num`]).

use crate::ReportError;
use stiction_model::design_sweep::{Map, Probability, CSV_COLUMNS, SAMPLE_COLUMNS};

fn opt(v: Option<usize>) -> String {
    v.map(|c| c.to_string()).unwrap_or_default()
}

/// `map.csv`: a header (the varied fields, then [`CSV_COLUMNS`]) and one row per point.
/// Numbers in Rust's shortest round-trip form (`{:e}`), the word of a categorical axis
/// as it is; absent values are empty cells.
pub fn map_csv(map: &Map) -> Result<String, ReportError> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let csv_err = |e: csv::Error| ReportError::Csv(e.to_string());
    let header: Vec<&str> = map
        .grid()
        .axes()
        .iter()
        .map(|a| a.field.as_str())
        .chain(CSV_COLUMNS)
        .collect();
    w.write_record(&header).map_err(csv_err)?;
    for p in map.points() {
        let mut row: Vec<String> = map
            .grid()
            .levels(p.index)
            .iter()
            .map(ToString::to_string)
            .collect();
        match &p.design {
            Some(d) => {
                row.push(format!("{:e}", d.pull_out_ratio));
                row.push(format!("{:e}", d.largest_pull_out_pa));
                row.push(format!("{:e}", d.restoring_pressure_pa));
                row.push(opt(d.cycles_to_accommodation));
                row.push(opt(d.first_sticking_cycle));
                row.push(d.sticks.to_string());
                row.push(d.closes.to_string());
                row.push(d.validity_holds.to_string());
                row.push(
                    d.accommodation_cause
                        .map_or(String::new(), |c| c.as_str().to_owned()),
                );
                row.push(
                    d.contact_resistance
                        .map_or(String::new(), |v| format!("{v:e}")),
                );
                row.push(
                    d.real_contact_fraction
                        .map_or(String::new(), |v| format!("{v:e}")),
                );
            }
            None => row.extend(std::iter::repeat_n(String::new(), 11)),
        }
        row.push(p.status.word().to_owned());
        w.write_record(&row).map_err(csv_err)?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| ReportError::Csv(e.to_string()))?;
    String::from_utf8(bytes).map_err(|e| ReportError::Csv(e.to_string()))
}

/// `samples.csv`: `index`, a column per scattered field (named as the field), then
/// [`SAMPLE_COLUMNS`]; one row per sample. Numbers in shortest round-trip form; absent
/// values are empty cells.
pub fn samples_csv(run: &Probability) -> Result<String, ReportError> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let csv_err = |e: csv::Error| ReportError::Csv(e.to_string());
    let header: Vec<&str> = std::iter::once("index")
        .chain(run.plan().scatter.iter().map(|s| s.field.as_str()))
        .chain(SAMPLE_COLUMNS)
        .collect();
    w.write_record(&header).map_err(csv_err)?;
    let opt = |v: Option<usize>| v.map(|c| c.to_string()).unwrap_or_default();
    for p in run.points() {
        let mut row: Vec<String> = vec![p.index.to_string()];
        row.extend(p.values.iter().map(|v| format!("{v:e}")));
        row.push(p.status.word().to_owned());
        row.push(
            p.counted_counting(run.plan().count_outside_validity)
                .to_string(),
        );
        match &p.design {
            Some(d) => {
                row.push(format!("{:e}", d.pull_out_ratio));
                row.push(opt(d.first_sticking_cycle));
                row.push(opt(d.cycles_to_accommodation));
                row.push(d.sticks.to_string());
                row.push(d.closes.to_string());
                row.push(d.validity_holds.to_string());
                row.push(format!("{:e}", d.largest_pull_out_pa));
                row.push(format!("{:e}", d.restoring_pressure_pa));
                row.push(
                    d.accommodation_cause
                        .map_or(String::new(), |c| c.as_str().to_owned()),
                );
            }
            None => row.extend(std::iter::repeat_n(String::new(), 9)),
        }
        row.push(p.status.detail().unwrap_or_default().to_owned());
        w.write_record(&row).map_err(csv_err)?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| ReportError::Csv(e.to_string()))?;
    String::from_utf8(bytes).map_err(|e| ReportError::Csv(e.to_string()))
}
