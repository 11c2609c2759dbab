//! `stiction`: the command line of the stiction model (adhesive contact of elasto-plastic
//! rough surfaces and the in-use stiction of a MEMS micro-switch, `docs/theory.md`).
//!
//! The model is the library `stiction-model` (re-exported as [`model`]): every command
//! reads a scene, hands it to the library and hands the typed result to the presentation
//! layer `stiction-report` (re-exported as [`report`]: tables, JSON, CSV, SVG, files
//! written safely). This crate holds only what a command line needs: options ([`cli`]),
//! the commands' dispatch, progress bars.

pub use stiction_model as model;
pub use stiction_model::{asperity_plastic, contact_core, gw_surface, maugis_kim, switch_1d};
pub use stiction_report as report;

pub mod cli;
pub mod commands;
pub mod error;
pub mod progress;

pub use stiction_report::{output, plot, render};

pub use error::Error;
