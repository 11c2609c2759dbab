//! `stiction`: adhesive contact of elasto-plastic rough surfaces and the in-use stiction
//! of a MEMS micro-switch (the model of `docs/theory.md`).
//!
//! This facade re-exports the workspace crates and holds the scenes, the model assembly
//! and the command-line front end: each command runs scene -> validated model -> run ->
//! report -> render ([`commands::Command`], [`render::Render`]).

pub use asperity_plastic;
pub use contact_core;
pub use gw_surface;
pub use maugis_kim;
pub use switch_1d;

pub mod accuracy;
pub mod cli;
pub mod commands;
pub mod error;
pub mod guards;
pub mod model;
pub mod output;
pub mod plot;
pub mod progress;
pub mod render;
pub mod scene;
pub mod scenegen;

pub use error::Error;
