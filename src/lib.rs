//! `stiction`: the command line of the stiction model (adhesive contact of elasto-plastic
//! rough surfaces and the in-use stiction of a MEMS micro-switch, `docs/theory.md`).
//!
//! The model is the library `stiction-model` (re-exported as [`model`]): every command
//! reads a scene, hands it to the library and renders the typed result as a table, JSON,
//! CSV or SVG ([`render::Render`]). This crate holds only what a command line needs:
//! options ([`cli`]), rendering and plots, files written safely ([`output`]), progress bars.

pub use stiction_model as model;
pub use stiction_model::{asperity_plastic, contact_core, gw_surface, maugis_kim, switch_1d};

pub mod cli;
pub mod commands;
pub mod error;
pub mod output;
pub mod plot;
pub mod progress;
pub mod render;

pub use error::Error;
