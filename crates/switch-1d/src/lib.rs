//! The one-dimensional micro-switch of the paper's section 3 (Table 2): parallel plates in
//! vacuum, a movable electrode on a spring of stiffness K_s per unit area, a substrate
//! electrode under a dielectric (thickness t_d, relative permittivity eps_r), and Ru films
//! of thickness t_s where the two meet.
//!
//! * [`Switch`]: static pull-in voltage, impact energy from (K_s, U), the K_s that gives
//!   a chosen impact energy at U = V_PI.
//! * [`end_of_impact`]: the separation d_e of eq 17.
//! * [`run_cycles`]: loading/unloading cycles on any [`contact_core::SurfaceLaw`], pull-out
//!   pressure per cycle and accommodation; [`Switch::restoring_pressure`] is what the
//!   pull-out pressure is compared with for the stiction verdict.

mod cycles;
mod error;
mod switch;

pub use cycles::{
    end_of_impact, end_of_impact_with, run_cycles, unload, Cycle, CycleOptions, CycleRun,
    EnergyRule, ImpactFilm, PressurePoint, Unloading,
};
pub use error::SwitchError;
pub use switch::{Switch, EPSILON_0};
