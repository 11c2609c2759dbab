//! Stiction-free design of a switch: maps of the pull-out ratio over one or two scene
//! fields, and the critical value of one field where the ratio crosses 1.
//!
//! The crate knows nothing of the contact model. It works on an evaluator closure that
//! runs a full switch scene for given field values and reduces it to a [`DesignPoint`]
//! (pull-out ratio = largest pull-out pressure / restoring pressure K_s d0; > 1 sticks).
//!
//! * [`Grid`] from `FIELD=FROM:TO:lin|log:N` options, or categorical `FIELD=WORD,WORD,...`
//!   (law names, choices; [`Axis::parse`]); 1-D or 2-D, point `i` ordered with the first
//!   axis varying slowest. The evaluator receives each axis's [`Level`]: a number or a word.
//! * [`run_map`] evaluates the grid, or one [`Shard`] `K/N` of it, in parallel (rayon),
//!   in index order: the same [`Map`] whatever the thread count. Failing points get a
//!   [`Status`] and the map goes on.
//! * [`Map::to_json`]: the map as data (`map.json`), read back by [`Map::from_json`];
//!   [`merge`] joins shards into the map of an unsharded run, point for point. The crate
//!   draws nothing and writes no file: tables, CSV and plots of a map are the
//!   presentation crate's (`stiction-report`).
//! * [`threshold`]: scan, then Brent-Dekker refinement of every crossing of ratio = 1,
//!   with its uncertainty.
//! * [`run_probability`]: Monte Carlo over distributions of fields ([`Scatter`], `FIELD=DIST`,
//!   optionally [`Correlation`]s), each sample's values from `(seed, index)` alone; the
//!   probability of stiction by cycle, after accommodation and of "does not close" with
//!   Clopper-Pearson intervals ([`stats`]), rank correlations, shards and
//!   [`merge_probability`]; [`exact_single_field`] gives the exact answer of one monotone
//!   field from its threshold and CDF.
//!
//! ```
//! use design_sweep::{run_map, threshold, DesignPoint, Grid, Level, MapRequest,
//!                    ThresholdOptions, FreeSide};
//!
//! // a stand-in for a switch run: ratio = (3e3 / k)^2, sticks below k = 3e3
//! let point = |k: f64| -> Result<DesignPoint, String> {
//!     let ratio = (3e3 / k).powi(2);
//!     Ok(DesignPoint { pull_out_ratio: ratio, largest_pull_out_pa: ratio * k,
//!                      restoring_pressure_pa: k, cycles_to_accommodation: Some(4),
//!                      first_sticking_cycle: (ratio > 1.0).then_some(1),
//!                      sticks: ratio > 1.0, closes: true, validity_holds: true,
//!                      accommodation_cause: None, contact_resistance: None,
//!                      real_contact_fraction: None })
//! };
//! let grid = Grid::parse(&["switch.k_s=1e2:1e5:log:7"])?;
//! let request = MapRequest { scene: serde_json::json!({"name": "demo"}), grid,
//!                            accuracy: "fast".into(), shard: None };
//! let map = run_map(request, |v: &[(&str, Level)]| point(v[0].1.number().unwrap()),
//!                   |_done, _total| {});
//! assert_eq!(map.points().len(), 7);
//! assert!(map.to_json().contains("\"switch.k_s\""));
//!
//! let t = threshold("switch.k_s", 1e2, 1e5, point, &ThresholdOptions::default())?;
//! assert!((t.critical_value.unwrap() / 3e3 - 1.0).abs() < 1e-6);
//! assert_eq!(t.free_side, FreeSide::Above);
//! # Ok::<(), design_sweep::DesignError>(())
//! ```

mod boundary;
mod dist;
mod error;
mod grid;
mod map;
mod point;
mod probability;
mod requirement;
mod shard;
pub mod stats;
mod threshold;

use std::collections::BTreeMap;

pub use boundary::{contour_plotted, BoundaryPoint, WordBoundary};
pub use dist::{Correlation, Dist, DistSpec, Sampler, Scatter, DISTRIBUTIONS};
pub use error::DesignError;
pub use grid::{Axis, Grid, Level, Spacing, MAX_AXIS_POINTS, MAX_GRID_POINTS};
pub use map::{
    merge, run_map, Map, MapPoint, MapRequest, MapSummary, CSV_COLUMNS, MAP_FORMAT, MAP_VERSION,
    MAX_MAP_BYTES,
};
pub use point::{AccommodationCause, DesignPoint, PointError, Status};
pub use probability::{
    exact_range, exact_single_field, merge_probability, run_probability, Counts, CycleProbability,
    Estimate, Exact, ExactBoundary, Outcome, Probability, ProbabilityPlan, ProbabilityView,
    RankCorrelation, SamplePoint, Stopping, Summary, EXACT_TAIL, MAX_SAMPLES, PROBABILITY_FORMAT,
    PROBABILITY_VERSION, SAMPLE_COLUMNS, STOP_CHECK_EVERY,
};
pub use requirement::{Bound, Quantity, Requirement};
pub use shard::Shard;
pub use threshold::{
    ratio_rel_error, threshold, threshold_with, Crossing, CrossingKind, FreeSide,
    RequirementCrossing, RequirementReport, ScanPoint, Threshold, ThresholdOptions,
};

/// Plot title and the unit of each field (`switch.k_s` -> `Pa/m`), for plots and tables.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Labels {
    /// Plot title; `None` makes one from the field names and the accuracy mode.
    pub title: Option<String>,
    /// Unit per field.
    pub units: BTreeMap<String, String>,
}

impl Labels {
    /// No title, no units.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the unit of `field`.
    pub fn with_unit(mut self, field: impl Into<String>, unit: impl Into<String>) -> Self {
        self.units.insert(field.into(), unit.into());
        self
    }

    /// Sets the plot title.
    pub fn with_title(mut self, title: impl Into<String>) -> Self {
        self.title = Some(title.into());
        self
    }

    /// The unit of `field`, if known.
    pub fn unit(&self, field: &str) -> Option<&str> {
        self.units.get(field).map(String::as_str)
    }

    /// `field [unit]`, or `field` without a unit.
    pub fn axis_label(&self, field: &str) -> String {
        match self.unit(field) {
            Some(u) => format!("{field} [{u}]"),
            None => field.to_owned(),
        }
    }
}
