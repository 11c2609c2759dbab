//! `stiction-report`: what a result of the stiction model looks like, for every front end
//! (the command line, `cargo xtask`, the Python package).
//!
//! The model library (`stiction-model`) turns a scene into a typed result; this crate
//! presents it, and nothing here computes physics:
//!
//! * [`render`]: the [`Render`] trait (a table for people, CSV, JSON, JSON in columns),
//!   numbers with units that fit, warnings on standard error, standard output that
//!   survives a closed pipe;
//! * [`csv`]: the CSV files of the design questions (`map.csv`, `samples.csv`);
//! * [`plot`]: every SVG, in one palette;
//! * [`output`]: the safe file writer (atomic; a FIFO, device or descriptor written in
//!   place, never replaced; a symbolic link followed) and [`OutputSet`], a folder of
//!   results written as a whole;
//! * one module per result kind, each implementing [`Render`], [`Plot`] where the result
//!   has a figure and [`Report`] where its command writes an `--out` folder: the files a
//!   front end saves are the files the command line writes, byte for byte.

pub mod asperity;
pub mod calibrate;
pub mod csv;
pub mod design;
pub mod design_table;
mod error;
pub mod law;
pub mod law_eval;
pub mod md;
pub mod output;
pub mod plot;
pub mod probability;
pub mod render;
pub mod surface;
pub mod switch;
pub mod topography;

pub use error::ReportError;
pub use output::OutputSet;
pub use render::{Format, Render};
pub use stiction_model;

use std::path::{Path, PathBuf};

/// A result with a figure: its SVG as a string.
pub trait Plot {
    /// The figure (what `--plot FILE` writes, or the first SVG of an `--out` folder).
    fn svg(&self) -> Result<String, ReportError>;
}

/// A result whose command writes a folder of files (`--out DIR`).
pub trait Report: Render {
    /// Every file such a folder may hold (an earlier run may have written any of them).
    const FILES: &'static [&'static str];

    /// The files of this result, in the order they are written, for the folder `dir`
    /// (named in messages; nothing is written).
    fn files(&self, dir: &Path) -> Result<OutputSet, ReportError>;

    /// Writes the files to `dir`, replacing the folder as a whole (it may hold only
    /// [`Report::FILES`]); returns the paths written.
    fn save(&self, dir: &Path) -> Result<Vec<PathBuf>, ReportError> {
        OutputSet::check(dir, Self::FILES)?;
        self.files(dir)?.commit()
    }
}
