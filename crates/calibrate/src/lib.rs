//! Inverse identification of the effective-radius constants of the paper's eq 13 from
//! finite-element force-interference curves of one asperity.
//!
//! The paper: "c1 and c2 are functions that have to be determined by inverse analysis from
//! finite-element results". With
//! c1(omega) = a1 + a2 exp(-a3 omega), c2(omega) = b1/(1 + (omega/b2)^2) - b3,
//! omega = delta_max/delta_CP, this crate fits [a1, a2, a3] and [b1, b2, b3] for another
//! film material:
//!
//! * [`FeData`]: the curves, read from CSV (`delta_max_m, delta_m, force_n, branch`),
//!   errors naming line and column;
//! * [`Calibrator`]: the forward model, the workspace's own
//!   `ElastoPlasticAsperity<EtsionKadin, A>` for the scene's material, adhesion law and
//!   reading of eq 1; [`Calibrator::fit`] runs Levenberg-Marquardt with faer's SVD;
//! * [`FitReport`]: constants, standard errors, correlation, rank and the constants the
//!   data do not determine, per-curve misfit, and the scene fragment.
//!
//! The method and its assumptions are in `docs/calibration.md`.
//!
//! ```
//! use asperity_plastic::{EffectiveRadiusFit, EtsionKadin, YieldModulus};
//! use calibrate::{Calibrator, FitOptions, SynthSpec};
//! use contact_core::{paper, Material, Pair};
//! use maugis_kim::{DugdaleParams, MaugisKim};
//!
//! let pair = Pair::new(Material::new(paper::RU)?, None, paper::RADIUS)?;
//! let cal = Calibrator::new(
//!     EtsionKadin::new(&pair, YieldModulus::AsPrinted)?,
//!     MaugisKim::new(DugdaleParams::for_pair(&pair, paper::WORK_OF_ADHESION, paper::Z0))?,
//! );
//! // "finite-element" curves made by the model with other constants, at 5 to 40 delta_CP
//! let truth = EffectiveRadiusFit::new([0.3, 0.5, 0.12], [8.0, 12.0, 4.0])?;
//! let spec = SynthSpec {
//!     delta_max: [5.0, 10.0, 20.0, 40.0].map(|w| w * cal.delta_cp()).to_vec(),
//!     loading_points: 20,
//!     unloading_points: 20,
//!     noise: 0.0,
//!     seed: 1,
//! };
//! let data = cal.synthesize(truth, &spec)?;
//! // fit all six constants, starting from the paper's eq 13
//! let report = cal.fit(&data, &FitOptions { start: Some(EffectiveRadiusFit::PAPER), ..FitOptions::default() })?;
//! assert!(report.converged && report.rank == 6 && report.not_determined.is_empty());
//! assert!((report.c1[2] - 0.12).abs() < 1e-9 && (report.c2[1] - 12.0).abs() < 1e-7);
//! assert!(report.scene_fragment.contains("c2 = [8.0, 12.0, 4.0]"));
//! // with loading curves alone, c2 has no effect at all: reported, not invented
//! let loading = cal.synthesize(truth, &SynthSpec { unloading_points: 0, ..spec })?;
//! let report = cal.fit(&loading, &FitOptions::default())?;
//! assert_eq!(report.not_determined.len(), 3);
//! assert!(report.standard_errors.c2.is_empty());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod branch;
mod constants;
mod data;
mod error;
mod fit;
mod model;
mod report;
mod synthetic;

pub use constants::{Constant, Selection};
pub use data::{Branch, Curve, CurvePoint, FeData, COLUMNS, DELTA_MAX_TOLERANCE};
pub use error::{CalibError, DataProblem};
pub use fit::{FitOptions, B2_MIN, FORCE_SCALE_LIMIT, NULL_WEIGHT};
pub use model::{Calibrator, OverlayCurve, FD_STEP};
pub use report::{
    scene_fragment, Correlation, CurveReport, Direction, DirectionComponent, FitReport,
    StandardErrors, StopReason,
};
pub use synthetic::{Gaussian, SynthSpec};
