//! `stiction-model`: the stiction model as a library, one path of data for every front end
//! (the command line, `cargo xtask`, the benches, the Python package):
//!
//! ```text
//! scene (TOML, JSON, a tree)  --spec::*Spec::new (key registry, law registry)-->  spec
//!   --*Model::build-->  model (pair, laws, surface built once)  --run-->  typed result
//! ```
//!
//! * [`scene::Scene`]: a scene as written, editable key by key;
//! * [`keys`]: every scene key's unit, domain, default and meaning, the one source of
//!   truth for validation, defaults, echoes and the docs;
//! * [`laws::LawRegistry`]: adhesion and plasticity laws by name, built-in and a user's own;
//! * [`spec`]: validated scenes, checked once;
//! * [`asperity`], [`surface`], [`switch`], [`law`], [`design`], [`probability`], [`md`],
//!   [`calibration`]:
//!   the models and their runs, each returning a `Serialize` result;
//! * [`guards`]: the physics checks and the model's [`guards::Validity`] on every result.
//!
//! No command line, no printing, no files written: results are data.
//!
//! The paper's switch in a few lines:
//!
//! ```
//! use stiction_model::{keys::Kind, laws::LawRegistry, scene::Scene, spec::SwitchSpec};
//! use stiction_model::{switch::SwitchModel, Silent};
//! let mut scene = Scene::paper(Kind::Switch); // Table 1, Table 2, E_I = 0.5 J/m^2
//! scene.set_text("accuracy", "fast")?;
//! let spec = SwitchSpec::new(&scene, &LawRegistry::builtin())?;
//! let result = SwitchModel::build(&spec)?.run(&Silent)?;
//! // Fig 4: the pull-out grows from 1.81 MPa (cycle 1) to 2.45 MPa (accommodated)
//! assert!((result.cycles[0].pull_out_pressure / 1.811e6 - 1.0).abs() < 1e-3);
//! assert!((result.largest_pull_out / 2.446e6 - 1.0).abs() < 1e-3);
//! assert!(result.stiction && result.validity.holds);
//! # Ok::<(), stiction_model::ModelError>(())
//! ```

// The README's example is compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

pub mod accuracy;
pub mod asperity;
pub mod calibration;
mod cancel;
pub mod design;
mod error;
pub mod guards;
pub mod keys;
pub mod law;
pub mod laws;
pub mod md;
pub mod model_form;
pub mod ohmic;
pub mod probability;
pub mod scene;
pub mod scenegen;
pub mod spec;
pub mod surface;
pub mod switch;
pub mod topography;

pub use accuracy::{Accuracy, Targets};
pub use cancel::Cancellable;
pub use error::{ModelError, SceneError};

pub use asperity_plastic;
pub use contact_core;
pub use contact_law;
pub use design_sweep;
pub use gw_surface;
pub use maugis_kim;
pub use switch_1d;
pub use switch_dynamics;

/// Where a long run reports how far it is, and how its caller stops it. Front ends show
/// the count (a progress bar, a Python callback); the library only counts, and polls
/// [`Progress::cancelled`] often enough (every design point, every sample, every cycle,
/// every surface evaluation of a switch run, every step of a law's tabulation, every
/// evaluation of a threshold search) that a stop takes effect within a fraction of a
/// second. A run stopped so returns [`ModelError::Cancelled`], never a partial result.
/// Calls may come from several threads.
pub trait Progress: Sync {
    /// A run (or the next stage of a run) of `total` steps of `what` starts.
    fn start(&self, total: u64, what: &str) {
        let _ = (total, what);
    }
    /// `done` steps are done (never decreasing within a stage).
    fn set(&self, done: u64) {
        let _ = done;
    }
    /// The stage ended (all its steps done, or the rest of them not needed: a switch run
    /// that stops at accommodation).
    fn finish(&self) {}
    /// Whether the caller asks the run to stop (false by default: a run never stops). Polled
    /// from the computing threads, often: it must be cheap (an atomic load).
    fn cancelled(&self) -> bool {
        false
    }
}

/// No progress shown.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Progress for Silent {}

/// The cancellation of `progress` without its counting: what the inner runs of a longer
/// one report to (the design points of a map, the combinations of a model-form check),
/// so that they stop with it while the outer run keeps the count.
#[derive(Clone, Copy)]
pub struct CancelOnly<'a>(pub &'a dyn Progress);

impl Progress for CancelOnly<'_> {
    fn cancelled(&self) -> bool {
        self.0.cancelled()
    }
}

/// `Err(ModelError::Cancelled)` if `progress` asks the run to stop.
pub fn check_cancelled(progress: &dyn Progress) -> Result<(), ModelError> {
    if progress.cancelled() {
        Err(ModelError::Cancelled)
    } else {
        Ok(())
    }
}
