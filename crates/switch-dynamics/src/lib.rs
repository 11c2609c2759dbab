//! The electrostatic micro-switch in time (issue 44, `docs/theory.md` section 13).
//!
//! * [`SqueezeFilm`]: the squeeze-film damping of a W x L plate (Griffin et al. 1966, Blech
//!   1983) with the rarefied gas's effective viscosity (Veijola et al. 1995).
//! * [`Plate`] and [`close`]: the plate's equation of motion per unit electrode area with
//!   the contact's own history-dependent law (any `contact_core::SurfaceLaw`), integrated
//!   phase by phase with diffsol's tsit45 and event location: the flight, the impact, each
//!   bounce and the capture, with the energy ledger.
//! * [`release`]: the opening after the voltage is removed, or the stiction that holds it.

mod cycles;
mod error;
mod motion;
mod ode;
mod release;
mod squeeze;
mod table;

pub use cycles::{run_cycles, DynamicCycle};
pub use error::DynamicsError;
pub use motion::{
    close, Bounce, Closure, DynamicsOptions, EnergyLedger, ImpactState, Plate, TracePoint,
};
pub use release::{release, Release};
pub use squeeze::{geometry_factor, SqueezeFilm, REFERENCE_PRESSURE, VEIJOLA_A, VEIJOLA_B};
