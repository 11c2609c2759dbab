//! `stiction`: adhesive contact of elasto-plastic rough surfaces and the in-use stiction
//! of a MEMS micro-switch (the model of `docs/theory.md`).
//!
//! This facade re-exports the workspace crates and holds the scene files, the model
//! assembly and the command-line front end. Each crate can also be used on its own:
//! [`contact_core`] (traits, materials, numerics), [`maugis_kim`] (adhesion laws),
//! [`asperity_plastic`] (plasticity laws and the elasto-plastic asperity),
//! [`gw_surface`] (rough surface), [`switch_1d`] (the switch and its cycles).

pub use asperity_plastic;
pub use contact_core;
pub use gw_surface;
pub use maugis_kim;
pub use switch_1d;

pub mod cli;
pub mod model;
pub mod output;
pub mod run;
pub mod scene;
