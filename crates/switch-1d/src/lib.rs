//! The one-dimensional micro-switch of the paper's section 3 (Table 2): parallel plates in
//! vacuum, a movable electrode on a spring of stiffness K_s per unit area, a substrate
//! electrode under a dielectric (thickness t_d, relative permittivity eps_r), and films of
//! thickness t_s where the two meet.
//!
//! * [`Switch`]: static and dynamic pull-in voltages, impact energy from (K_s, U), the K_s
//!   that gives a chosen impact energy at U = V_PI.
//! * [`end_of_impact`]: the separation d_e of eq 17 (first compressive closure of the
//!   energy balance), with its error estimate.
//! * [`unload`]: the pull-out pressure, found on a grid that follows the law's length scales.
//! * [`run_cycles`]: loading/unloading cycles on any [`contact_core::SurfaceLaw`], pull-out
//!   per cycle, accommodation, and the verdict against the spring ([`Impact`]).
//!
//! ```
//! use switch_1d::{Impact, ImpactFilm};
//! // the verdict counts adhesion on the contacting fraction of the electrode only
//! let impact = Impact {
//!     energy: 0.5,
//!     film: ImpactFilm { thickness: 180e-9, youngs_modulus: 410e9 },
//!     contact_area_fraction: 0.25,
//!     restoring_pressure: 16_880.0,
//! };
//! assert!((impact.pull_out_ratio(2.0 * 16_880.0) - 0.5).abs() < 1e-15);
//! ```

// The README's example is compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

mod cycles;
mod error;
mod switch;

pub use cycles::{
    against_before, carry_history_errors, end_of_impact, eq17_residual, pull_out_grid, rest,
    run_cycles, unload, AccommodationCause, Cycle, CycleOptions, CycleRun, EndOfImpact, Impact,
    ImpactFilm, Precision, PressurePoint, Rest, Unloading,
};
pub use error::SwitchError;
pub use switch::{Switch, SwitchGeometry, EPSILON_0};
