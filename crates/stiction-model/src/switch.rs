//! The micro-switch cycle by cycle (the paper's Fig 4): the model of a switch scene, built
//! once, and its run.
//!
//! ```
//! use stiction_model::{keys::Kind, laws::LawRegistry, scene::Scene, switch::SwitchModel};
//! use stiction_model::{spec::SwitchSpec, Silent};
//! // the paper's switch in the fast mode, pull-out only
//! let mut scene = Scene::paper(Kind::Switch);
//! scene.set_text("accuracy", "fast")?;
//! scene.set_text("points", "0")?;
//! let spec = SwitchSpec::new(&scene, &LawRegistry::builtin())?;
//! let result = SwitchModel::build(&spec)?.run(&Silent)?;
//! assert!(result.stiction);
//! assert!((result.cycles[0].pull_out_pressure / 1.811e6 - 1.0).abs() < 1e-3);
//! # Ok::<(), stiction_model::ModelError>(())
//! ```

use crate::accuracy::{Accuracy, Targets};
use crate::error::{ModelError, SceneError};
use crate::guards::{self, Validity, Warning};
use crate::keys::{self, num};
use crate::spec::{ContactStates, Drive, RoughSurface, SwitchSpec};
use crate::Progress;
use contact_core::{Path, SurfaceLaw};
use gw_surface::{GreenwoodWilliamson, GwHistory, Roughness};
use serde::Serialize;
use switch_1d::{
    AccommodationCause, CycleOptions, CycleRun, Impact, ImpactFilm, PressurePoint, Switch,
    SwitchGeometry,
};
use switch_dynamics::{DynamicsOptions, SqueezeFilm};

/// Which of K_s, U and E_I the scene gave and which were derived.
#[derive(Debug, Clone, Serialize)]
pub struct DriveReport {
    /// `impact_energy` (K_s derived at U = V_PI) or `spring` (E_I derived from K_s, U).
    pub mode: &'static str,
    /// Keys given by the scene.
    pub given: Vec<&'static str>,
    /// Quantities derived from them.
    pub derived: Vec<&'static str>,
}

/// The electrostatics of a scene, resolved from its drive.
#[derive(Debug, Clone, Serialize)]
pub struct Electrostatics {
    /// Spring stiffness per unit area K_s (Pa/m).
    pub k_s: f64,
    /// Static pull-in voltage V_PI (V).
    pub v_pull_in: f64,
    /// Dynamic pull-in voltage (V): the lowest step voltage that closes the switch.
    pub dynamic_pull_in_voltage: f64,
    /// The step voltage U (V).
    pub voltage: f64,
    /// Impact energy per electrode area E_I (J/m^2; 0 when the switch does not close).
    pub impact_energy: f64,
    /// Restoring pressure of the spring at contact, K_s d0 (Pa).
    pub restoring_pressure: f64,
    /// Whether the electrode reaches contact.
    pub closes: bool,
    /// Which were given and which derived.
    pub drive: DriveReport,
}

/// Resolves the drive of a switch spec: K_s, U, E_I, the pull-in voltages and whether the
/// switch closes. A derived impact energy is range-checked like a given one.
pub fn electrostatics(spec: &SwitchSpec) -> Result<(Switch, Electrostatics), ModelError> {
    let g = &spec.switch;
    let sw = Switch::new(SwitchGeometry {
        d0: g.d0,
        t_d: g.t_d,
        epsilon_r: g.epsilon_r,
        epsilon_0: g.epsilon_0,
    })?
    .with_dimple_height(g.dimple_height)?;
    let resolved = match g.drive {
        Drive::ImpactEnergy(e) => {
            let k = sw.stiffness_for_impact_energy(e)?;
            Electrostatics {
                k_s: k,
                v_pull_in: sw.pull_in_voltage(k),
                dynamic_pull_in_voltage: sw.dynamic_pull_in_voltage(k),
                voltage: sw.pull_in_voltage(k),
                impact_energy: e,
                restoring_pressure: sw.restoring_pressure(k),
                closes: true,
                drive: DriveReport {
                    mode: "impact_energy",
                    given: vec!["impact_energy"],
                    derived: vec!["k_s", "voltage (= V_PI)"],
                },
            }
        }
        Drive::Spring { k_s: k, voltage } => {
            let u = voltage.unwrap_or_else(|| sw.pull_in_voltage(k));
            let closes = sw.closes(k, u);
            let e = if closes { sw.impact_energy(k, u) } else { 0.0 };
            let domain = keys::key("switch.impact_energy").map(|f| f.domain);
            if closes && !domain.is_some_and(|d| d.contains(e)) {
                return Err(SceneError::Field {
                    file: spec.common.scene.file().to_string(),
                    key: "switch.impact_energy".into(),
                    value: format!(
                        "{} (derived from k_s = {} Pa/m and voltage = {} V)",
                        num(e),
                        num(k),
                        num(u)
                    ),
                    line: String::new(),
                    allowed: domain.map(|d| d.describe()).unwrap_or_default(),
                }
                .into());
            }
            let (mut given, mut derived) = if g.spring_constant.is_some() {
                (
                    vec!["spring_constant", "electrode_area"],
                    vec!["k_s", "impact_energy"],
                )
            } else {
                (vec!["k_s"], vec!["impact_energy"])
            };
            if voltage.is_some() {
                given.push("voltage");
            } else {
                derived.push("voltage (= V_PI)");
            }
            Electrostatics {
                k_s: k,
                v_pull_in: sw.pull_in_voltage(k),
                dynamic_pull_in_voltage: sw.dynamic_pull_in_voltage(k),
                voltage: u,
                impact_energy: e,
                restoring_pressure: sw.restoring_pressure(k),
                closes,
                drive: DriveReport {
                    mode: "spring",
                    given,
                    derived,
                },
            }
        }
    };
    // the contacting fraction absorbs E_I/phi per contact area: range-checked like E_I
    let phi = g.contact_area_fraction;
    let per_contact = resolved.impact_energy / phi;
    let domain = keys::key("switch.impact_energy").map(|f| f.domain);
    if resolved.closes && !domain.is_some_and(|d| d.contains(per_contact)) {
        return Err(SceneError::Field {
            file: spec.common.scene.file().to_string(),
            key: "switch.contact_area_fraction".into(),
            value: format!(
                "{} (the impact energy per contact area E_I/phi = {} J/m^2)",
                num(phi),
                num(per_contact)
            ),
            line: spec
                .common
                .scene
                .line_of("switch.contact_area_fraction")
                .map_or(String::new(), |l| format!(" (line {l})")),
            allowed: format!(
                "such that E_I/phi lies in the domain of switch.impact_energy: {}",
                domain.map(|d| d.describe()).unwrap_or_default()
            ),
        }
        .into());
    }
    Ok((sw, resolved))
}

/// One cycle.
#[derive(Debug, Clone, Serialize)]
pub struct CycleResult {
    /// 1-based.
    pub cycle: usize,
    /// End-of-impact separation (m).
    pub d_e: f64,
    /// Its error estimate (m).
    pub d_e_error: f64,
    /// This impact went deeper than every earlier one.
    pub deepened: bool,
    /// How far d_e stopped above the deepest separation of the earlier cycles (m).
    pub shallower_by: f64,
    /// Approach pressure at d_e (Pa, per contact area).
    pub contact_pressure: f64,
    /// Pull-out pressure (Pa, per contact area, >= 0).
    pub pull_out_pressure: f64,
    /// Its error estimate (Pa).
    pub pull_out_error: f64,
    /// Where (m).
    pub pull_out_separation: f64,
    /// phi pull-out / (K_s d0).
    pub pull_out_ratio: f64,
    /// Ratio above 1: the spring cannot open the switch.
    pub sticks: bool,
    /// Unloading curve (empty with points = 0).
    pub unloading: Vec<PressurePoint>,
    /// The adhesive well sampled on its own, with the pull-out point (empty with
    /// points = 0).
    pub well: Vec<PressurePoint>,
    /// Where the closed switch rests under the hold voltage after this impact, and its
    /// contact there (null when it opens or the state was not computed: `hold_status`).
    pub hold: Option<ContactState>,
    /// `rests` (on the unloading branch), `deeper_than_impact` (the hold presses further
    /// than the impact did), `opens` (the spring outweighs the hold and the contact's
    /// pull-out: no rest), `not_computed` (`contact_state`) or `not_computable` (the rest
    /// could not be found, e.g. a hold the surface cannot bear: warning
    /// `side_quantity_not_computed`).
    pub hold_status: &'static str,
    /// The contact at the end of impact, d_e (null when not computed).
    pub end_of_impact: Option<ContactState>,
    /// In time (`[dynamics]`): where the contact phase of the first impact began.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub impact: Option<switch_dynamics::ImpactState>,
    /// In time: the number of bounces of the closure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bounces: Option<usize>,
    /// In time: each bounce's re-impact and its deepest separation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bounce_impacts: Option<Vec<switch_dynamics::Bounce>>,
    /// In time: where the closure's energy went.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_ledger: Option<switch_dynamics::EnergyLedger>,
    /// In time: the time from the voltage step to the capture (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub capture_time: Option<f64>,
    /// In time: the release with the voltage off (from rest at the pull-out's separation).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub release: Option<switch_dynamics::Release>,
}

/// The switch in time (theory 13).
#[derive(Debug, Clone, Serialize)]
pub struct DynamicsReport {
    /// c'' at x = dimple_height (Pa s/m per electrode area; 0 in vacuum).
    pub squeeze_film_coefficient_at_contact: f64,
    /// The squeeze film's geometry factor beta(W/L) (0 in vacuum).
    pub squeeze_film_geometry_factor: f64,
    /// m'' (kg/m^2).
    pub areal_mass: f64,
    /// The natural frequency sqrt(K_s/m'')/(2 pi) (Hz).
    pub natural_frequency: f64,
    /// The gas pressure (Pa; 0: vacuum).
    pub gas_pressure: f64,
    /// The integration's relative tolerance: the accuracy mode's, or a tenth of it (or a
    /// hundredth, ...) where the cycles' error estimates needed it to meet the mode's
    /// targets, down to [`MIN_DYNAMICS_TOLERANCE`].
    pub tolerance: f64,
    /// The first closure's motion: time, displacement, velocity, contact pressure.
    pub trace: Vec<switch_dynamics::TracePoint>,
}

impl CycleResult {
    /// Whether a contact resistance was computed for this cycle (hold or end of impact).
    pub fn has_resistance(&self) -> bool {
        self.hold
            .iter()
            .chain(self.end_of_impact.iter())
            .any(|s| s.contact_resistance.is_some())
    }
}

/// The contact of the closed switch at one state of a cycle (the rest under the hold
/// voltage, or the end of impact): the real contact area, the spots and the contact
/// resistance, from the history-aware integrals of the surface
/// ([`gw_surface::GreenwoodWilliamson::contact_spots`]; theory 6.5).
#[derive(Debug, Clone, Serialize)]
pub struct ContactState {
    /// Separation of the mean plane of asperity heights from the counter-surface (m).
    pub separation: f64,
    /// Contact pressure there (Pa per contact area, compressive > 0).
    pub contact_pressure: f64,
    /// Real contact area over the contact area, A_r/(phi A) (-).
    pub real_contact_fraction: f64,
    /// Contacting asperities per unit contact area (1/m^2).
    pub spot_density: f64,
    /// Their mean contact radius (m; 0 without spots).
    pub mean_spot_radius: f64,
    /// Spots on the contact area phi x `electrode_area` (absent without `electrode_area`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spots: Option<f64>,
    /// Contact resistance (ohm): the constriction resistances of the spots in parallel
    /// over the contact area phi x `electrode_area`, each spot Wexler's interpolation of
    /// Holm and Sharvin; null without `contact.resistivity`, without `electrode_area` or
    /// without spots.
    pub contact_resistance: Option<f64>,
    /// Greenwood's interaction term of the spots scattered over the contact area as one
    /// circle of radius alpha, 16 rho / (3 pi^2 alpha) (ohm; absent when the resistance is).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interaction_resistance: Option<f64>,
    /// `contact_resistance` plus `interaction_resistance` (ohm): Greenwood's resistance of
    /// the spots of one apparent contact (absent when the resistance is).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_resistance_with_interaction: Option<f64>,
    /// Knudsen number of the mean spot, lambda / a (-; above 1 the spots conduct
    /// ballistically; absent without conduction).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub knudsen_number: Option<f64>,
    /// The largest relative error estimate of the contact integrals (-).
    pub relative_error: f64,
}

/// The elastic comparison: the same surface with asperities that never yield, one cycle.
#[derive(Debug, Clone, Serialize)]
pub struct ElasticResult {
    /// End-of-impact separation (m).
    pub d_e: f64,
    /// Pull-out pressure (Pa).
    pub pull_out_pressure: f64,
    /// Where (m).
    pub pull_out_separation: f64,
    /// phi pull-out / (K_s d0).
    pub pull_out_ratio: f64,
    /// Ratio above 1.
    pub sticks: bool,
    /// Unloading curve.
    pub unloading: Vec<PressurePoint>,
}

/// Error estimates of the reported quantities.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct SwitchErrors {
    /// The largest d_e error estimate over the cycles (m).
    pub d_e: f64,
    /// The largest pull-out error estimate (Pa), the stopping rule's included.
    pub pull_out: f64,
    /// The part of it from stopping at accommodation: how much the largest pull-out could
    /// still grow in the cycles not run (Pa).
    pub accommodation: f64,
    /// The error of the pull-out ratio these make (-).
    pub pull_out_ratio: f64,
}

/// The laws and modelling choices of a run, echoed in every output.
#[derive(Debug, Clone, Serialize)]
pub struct Laws {
    /// Adhesion law.
    pub adhesion: String,
    /// Plasticity law.
    pub plasticity: String,
    /// Reading of eq 1.
    pub yield_modulus: &'static str,
    /// Reload rule.
    pub reload: &'static str,
}

impl Laws {
    /// The laws of a contact.
    pub fn of(c: &crate::spec::ContactSpec) -> Self {
        Self {
            adhesion: c.adhesion.name.clone(),
            plasticity: c.plasticity.name.clone(),
            yield_modulus: c.yield_modulus.as_str(),
            reload: c.reload.as_str(),
        }
    }
}

/// A switch run.
#[derive(Debug, Clone, Serialize)]
pub struct SwitchResult {
    /// Plot and table title.
    pub title: String,
    /// The laws and modelling choices.
    pub laws: Laws,
    /// Accuracy mode and targets.
    pub accuracy: Targets,
    /// Error estimates.
    pub error_estimate: SwitchErrors,
    /// Spring stiffness per unit area (Pa/m).
    pub k_s: f64,
    /// Static pull-in voltage (V).
    pub v_pull_in: f64,
    /// Dynamic pull-in voltage (V).
    pub dynamic_pull_in_voltage: f64,
    /// Step voltage (V).
    pub voltage: f64,
    /// Impact energy per electrode area (J/m^2).
    pub impact_energy: f64,
    /// K_s d0 (Pa).
    pub restoring_pressure: f64,
    /// Fraction of the electrode in contact.
    pub contact_area_fraction: f64,
    /// The voltage holding the switch shut after each impact (V; 0 with `hold_force`).
    pub hold_voltage: f64,
    /// The force holding it shut on its contacts (N), when the scene gives it instead.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hold_force: Option<f64>,
    /// The pressure the hold puts on the contact: (eps0 eps_r^2 U_hold^2 / (2 t_d^2) -
    /// K_s d0) / phi (Pa per contact area; negative when the spring outweighs it).
    pub hold_pressure: f64,
    /// When the contact states were computed: `every_cycle`, `last_cycle` or `none`.
    pub contact_state: &'static str,
    /// Whether the electrode reaches contact.
    pub closes: bool,
    /// What the scene gave and what was derived.
    pub drive: DriveReport,
    /// Relative change that counts as accommodated.
    pub accommodation_tolerance: f64,
    /// Virgin loading curve of cycle 1 (empty with points = 0).
    pub loading: Vec<PressurePoint>,
    /// The cycles (none when the switch does not close).
    pub cycles: Vec<CycleResult>,
    /// The elastic comparison.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub elastic: Option<ElasticResult>,
    /// The cycle after which nothing changes within the tolerance.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accommodated_after: Option<usize>,
    /// Why (`saturated`: the impacts still deepen by less than the tolerance;
    /// `non_deepening`: an impact stopped short of an earlier one, so nothing changes
    /// any more); null when not accommodated (a public contract: the one null of a switch
    /// result).
    pub accommodation_cause: Option<&'static str>,
    /// The largest pull-out of all cycles (Pa).
    pub largest_pull_out: f64,
    /// phi largest pull-out / (K_s d0): above 1 the switch sticks.
    pub pull_out_ratio: f64,
    /// The first cycle that sticks.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_sticking_cycle: Option<usize>,
    /// Some cycle sticks.
    pub stiction: bool,
    /// Whether the model holds for this run, and which checks say it does not.
    pub validity: Validity,
    /// Fraction of asperities (by count) loaded beyond the plasticity fits' range after the
    /// last cycle.
    pub extrapolated_fraction: f64,
    /// Guards raised.
    pub warnings: Vec<Warning>,
    /// The resolved scene.
    pub scene: serde_json::Value,
    /// The model-form check, when the scene asks for it (`model_form = "check"`):
    /// whether another published model form changes the verdict.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_form: Option<crate::model_form::ModelFormReport>,
    /// The switch in time (a `[dynamics]` section): the squeeze film at contact, the mass,
    /// and the first closure's motion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dynamics: Option<DynamicsReport>,
}

/// A switch scene's model, built once: the electrostatics, the rough surface of the
/// scene's laws (and of elastic asperities for the comparison), the impact.
pub struct SwitchModel<'a> {
    spec: &'a SwitchSpec,
    sw: Switch,
    es: Electrostatics,
    floor: f64,
    /// Reload-work tables shared with other models of the same contact (plastic, elastic).
    tables: Option<SharedTables>,
}

/// The reload-work tables of a contact's two asperities (its own, and the elastic one of
/// the comparison), for models of equal contacts to share ([`SwitchModel::with_tables`]).
#[derive(Debug, Clone, Default)]
pub struct SharedTables {
    plastic: std::sync::Arc<gw_surface::ReloadTables>,
    elastic: std::sync::Arc<gw_surface::ReloadTables>,
}

impl<'a> SwitchModel<'a> {
    /// The model of `spec`.
    pub fn build(spec: &'a SwitchSpec) -> Result<Self, ModelError> {
        let (sw, es) = electrostatics(spec)?;
        let phi = spec.switch.contact_area_fraction;
        // a pressure error below 1e-9 K_s d0 (per electrode area) does not matter
        let floor = spec.common.accuracy.targets().pull_out_floor_of_restoring
            * es.restoring_pressure
            / phi;
        Ok(Self {
            spec,
            sw,
            es,
            floor,
            tables: None,
        })
    }

    /// The same model drawing on `tables` for the reload work of its asperities (eq 17
    /// after the first impact). Share them only between models whose contact sections
    /// are equal (the tables depend on the asperities alone, not on the roughness, the
    /// switch or the drive); a design map shares them across its points.
    pub fn with_tables(mut self, tables: SharedTables) -> Self {
        self.tables = Some(tables);
        self
    }

    /// The resolved electrostatics.
    pub fn electrostatics(&self) -> &Electrostatics {
        &self.es
    }

    /// The rough surface the cycles run on (`elastic`: with asperities that never yield).
    pub fn surface(&self, elastic: bool) -> Result<RoughSurface, ModelError> {
        let gw = surface_of(self.spec, self.spec.common.accuracy, self.floor, elastic)?;
        Ok(match &self.tables {
            Some(t) if elastic => gw.with_reload_tables(t.elastic.clone()),
            Some(t) => gw.with_reload_tables(t.plastic.clone()),
            None => gw,
        })
    }

    /// The plate of a `[dynamics]` scene: the switch, its spring and voltage, the mass and
    /// the gas film (None for a quasi-static scene).
    pub fn plate(&self) -> Result<Option<switch_dynamics::Plate>, ModelError> {
        let Some(d) = self.spec.dynamics else {
            return Ok(None);
        };
        let squeeze = d
            .gas
            .map(|g| SqueezeFilm::new(g.width, g.length, g.viscosity, g.mean_free_path, g.pressure))
            .transpose()?;
        let plate = switch_dynamics::Plate {
            switch: self.sw,
            k_s: self.es.k_s,
            voltage: self.es.voltage,
            areal_mass: d.areal_mass_for(self.es.k_s),
            contact_area_fraction: self.spec.switch.contact_area_fraction,
            squeeze,
        };
        Ok(Some(plate.validated()?))
    }

    fn impact(&self) -> Impact {
        let s = self.spec;
        Impact {
            energy: self.es.impact_energy,
            film: ImpactFilm {
                thickness: s.switch.film_thickness,
                youngs_modulus: s.switch.film_youngs_modulus,
            },
            contact_area_fraction: s.switch.contact_area_fraction,
            restoring_pressure: self.es.restoring_pressure,
        }
    }

    fn options(&self) -> CycleOptions {
        let s = self.spec;
        CycleOptions {
            cycles: s.cycles,
            until_accommodated: s.until_accommodated,
            accommodation_tolerance: s.accommodation_tolerance,
            unloading_points: s.common.points,
            loading_points: s.common.points,
            precision: s.common.accuracy.precision(),
        }
    }

    /// Runs the cycles (and the elastic comparison, at the same time), reporting cycles
    /// to `progress`; [`ModelError::Cancelled`] when `progress` stops it (polled at every
    /// surface evaluation).
    pub fn run(&self, progress: &dyn Progress) -> Result<SwitchResult, ModelError> {
        let file = self.spec.common.scene.file().to_string();
        crate::check_cancelled(progress)?;
        self.run_inner(progress)
            .and_then(|r| crate::check_cancelled(progress).map(|()| r))
            .map_err(|e| e.or_cancelled(progress).in_scene(&file))
    }

    fn run_inner(&self, progress: &dyn Progress) -> Result<SwitchResult, ModelError> {
        let s = self.spec;
        let mut result = self.empty_result();
        if !self.es.closes {
            return Ok(result);
        }
        let gw = self.surface(false)?;
        // the cycles see the surface through the caller's stop (the same values)
        let stoppable = crate::Cancellable::new(&gw, progress);
        let impact = self.impact();
        let options = self.options();
        let plate = self.plate()?;
        let mut records: Vec<switch_dynamics::DynamicCycle> = Vec::new();
        let mut tolerance = DynamicsOptions::for_target(options.precision.d_e).tolerance;
        let (targets, floor) = (result.accuracy, pull_out_floor(&result));
        let mut last_excess = f64::INFINITY;
        // the elastic comparison is independent of the cycles: both at once
        let (run, elastic) = contact_core::par::join(
            || {
                let run = match (&plate, s.dynamics) {
                    // in time, the contact phases are integrated to the mode's tolerance;
                    // where the cycles' error estimates still exceed the mode's targets
                    // (errors carried from history to history add up over the cycles),
                    // the run is repeated at a tenth of the tolerance, down to 1e-12
                    // (theory 13.4)
                    (Some(plate), Some(d)) => loop {
                        progress.start(s.cycles as u64, "cycles");
                        let (run, rec) = match switch_dynamics::run_cycles(
                            &stoppable,
                            gw.virgin(),
                            plate,
                            options,
                            DynamicsOptions {
                                max_bounces: d.max_bounces,
                                trace: s.common.points > 0,
                                tolerance,
                            },
                            &mut |k| progress.set(k as u64),
                        ) {
                            Ok(r) => r,
                            Err(e) => break Err(ModelError::from(e)),
                        };
                        let excess = estimate_excess(targets, s.roughness.sigma_s, floor, &run);
                        // done: within the targets, at the floor, or no longer helped (the
                        // surface's own quadrature error then rules, which the tolerance
                        // does not reach; the run's warning says so)
                        let done = excess <= 1.0
                            || tolerance <= MIN_DYNAMICS_TOLERANCE
                            || excess > 0.5 * last_excess;
                        last_excess = excess;
                        if done {
                            records = rec;
                            break Ok(run);
                        }
                        tolerance = (0.1 * tolerance).max(MIN_DYNAMICS_TOLERANCE);
                    },
                    _ => {
                        progress.start(s.cycles as u64, "cycles");
                        switch_1d::run_cycles(&stoppable, gw.virgin(), impact, options, &mut |cy| {
                            progress.set(cy.cycle as u64)
                        })
                        .map_err(ModelError::from)
                    }
                };
                progress.finish();
                run
            },
            || {
                s.elastic_comparison
                    .then(|| self.elastic_comparison(impact, options, progress))
                    .transpose()
            },
        );
        // a stopped run is no result: nothing computed beside it is kept either
        crate::check_cancelled(progress)?;
        let run = match run {
            // under the gas the plate can stop short of a contact the vacuum drive reaches
            Err(ModelError::Dynamics(switch_dynamics::DynamicsError::DoesNotClose {
                time,
                gap,
            })) => {
                result.closes = false;
                result.warnings.push(Warning::note(
                    guards::code::DOES_NOT_CLOSE,
                    format!(
                        "in time, the electrode stopped {} after the voltage step, {} short of the contact: the squeeze film and the spring stop it although U exceeds the dynamic pull-in voltage of the vacuum",
                        guards::si(time, "s", 4),
                        guards::si(gap, "m", 4)
                    ),
                ));
                return Ok(result);
            }
            run => run?,
        };
        // the cycles and the verdict stand on their own: a quantity computed beside them
        // that fails (the elastic comparison, a guard's check, a contact state) is absent,
        // with a warning saying which and why, instead of losing the run
        let mut not_computed = Vec::new();
        result.elastic = elastic.unwrap_or_else(|e| {
            not_computed.push(side_quantity_failed("the elastic comparison", &e));
            None
        });
        result.warnings = physics_guards(s, &gw, &run, &mut not_computed);
        let last = run.cycles.last().expect("at least one cycle");
        result.extrapolated_fraction = guards::fit_range_max(&s.contact)
            .map_or(0.0, |hi| gw.fraction_beyond(&last.history, hi));
        let states = self.contact_states(&gw, &run, &mut not_computed);
        record(&mut result, run, impact);
        for (cy, (hold, status, end)) in result.cycles.iter_mut().zip(states) {
            cy.hold = hold;
            cy.hold_status = status;
            cy.end_of_impact = end;
        }
        if let (Some(plate), Some(_)) = (&plate, s.dynamics) {
            let mut trace = Vec::new();
            for (cy, rec) in result.cycles.iter_mut().zip(records) {
                cy.impact = Some(rec.impact);
                cy.bounces = Some(rec.bounces.len());
                cy.bounce_impacts = Some(rec.bounces);
                cy.energy_ledger = Some(rec.energy_ledger);
                cy.capture_time = Some(rec.capture_time);
                cy.release = Some(rec.release);
                if trace.is_empty() {
                    trace = rec.trace;
                }
            }
            result.dynamics = Some(DynamicsReport {
                squeeze_film_coefficient_at_contact: plate.squeeze_coefficient_at_contact(),
                squeeze_film_geometry_factor: plate.squeeze.map_or(0.0, |f| f.geometry_factor()),
                areal_mass: plate.areal_mass,
                natural_frequency: 1.0 / (2.0 * std::f64::consts::PI * plate.natural_time()),
                gas_pressure: s.dynamics.and_then(|d| d.gas).map_or(0.0, |g| g.pressure),
                tolerance,
                trace,
            });
        }
        result.warnings.extend(contact_warnings(&result));
        result.warnings.extend(guards::estimates_within_targets(
            result.accuracy,
            s.roughness.sigma_s,
            pull_out_floor(&result),
            result
                .cycles
                .iter()
                .map(|c| (c.cycle, c.d_e_error, c.pull_out_pressure, c.pull_out_error)),
        ));
        result.warnings.extend(not_computed);
        // the scene's own notes (a key that overrides its height map's value)
        result.warnings.extend(s.common.notes.iter().cloned());
        result.validity = Validity::of(&result.warnings);
        Ok(result)
    }

    /// The voltage holding the switch shut (V): `switch.hold_voltage`, by default the
    /// actuation voltage.
    pub fn hold_voltage(&self) -> f64 {
        if self.spec.switch.hold_force.is_some() {
            return 0.0;
        }
        self.spec.switch.hold_voltage.unwrap_or(self.es.voltage)
    }

    /// The hold's pressure on the contact (Pa per contact area): the closed electrostatic
    /// pressure of the hold voltage minus the spring's K_s d0, over phi (theory 6.5); or,
    /// given `switch.hold_force`, that force over phi x electrode_area.
    pub fn hold_pressure(&self) -> f64 {
        let g = &self.spec.switch;
        if let (Some(f), Some(a)) = (g.hold_force, g.electrode_area) {
            return f / (g.contact_area_fraction * a);
        }
        let electrostatic = self.sw.closed_electrostatic_pressure(self.hold_voltage());
        (electrostatic - self.es.restoring_pressure) / g.contact_area_fraction
    }

    /// The contact at a separation `d` with `history` on `path`.
    pub fn contact_state(
        &self,
        gw: &RoughSurface,
        history: &GwHistory,
        d: f64,
        path: Path,
    ) -> Result<ContactState, ModelError> {
        let s = self.spec;
        let conduction = s.contact.conduction;
        let g = conduction.map(|c| move |a: f64| c.spot_conductance(a));
        let spots = gw.contact_spots(
            d,
            history,
            path,
            g.as_ref().map(|g| g as &(dyn Fn(f64) -> f64 + Sync)),
        )?;
        let pressure = gw.pressure(d, history, path)?;
        let area = s
            .switch
            .electrode_area
            .map(|a| a * s.switch.contact_area_fraction);
        let resistance = match (conduction, area, spots.conductance_per_area) {
            (Some(_), Some(area), Some(g)) if g > 0.0 => Some(1.0 / (g * area)),
            _ => None,
        };
        let interaction = match (conduction, area, resistance) {
            (Some(c), Some(a), Some(_)) => Some(c.interaction_resistance(a)),
            _ => None,
        };
        Ok(ContactState {
            separation: d,
            contact_pressure: pressure,
            real_contact_fraction: spots.real_contact_fraction,
            spot_density: spots.spot_density,
            mean_spot_radius: spots.mean_spot_radius,
            spots: area.map(|a| spots.spot_density * a),
            contact_resistance: resistance,
            interaction_resistance: interaction,
            contact_resistance_with_interaction: resistance.zip(interaction).map(|(r, i)| r + i),
            knudsen_number: match conduction {
                Some(c) if spots.mean_spot_radius > 0.0 => {
                    Some(c.mean_free_path / spots.mean_spot_radius)
                }
                _ => None,
            },
            relative_error: spots.relative_error,
        })
    }

    /// The hold and end-of-impact states of the cycles `contact_state` asks for. A state
    /// that cannot be computed (a hold the surface cannot bear, a failed integral) is
    /// absent (`hold_status` `not_computable` for the hold), with a warning pushed to
    /// `not_computed`: the cycles do not depend on it.
    #[allow(clippy::type_complexity)]
    fn contact_states(
        &self,
        gw: &RoughSurface,
        run: &CycleRun<GwHistory>,
        not_computed: &mut Vec<Warning>,
    ) -> Vec<(Option<ContactState>, &'static str, Option<ContactState>)> {
        let n = run.cycles.len();
        let wanted: Vec<usize> = match self.spec.contact_states {
            ContactStates::EveryCycle => (0..n).collect(),
            ContactStates::LastCycle => vec![n - 1],
            ContactStates::None => Vec::new(),
        };
        let hold = self.hold_pressure();
        let precision = self.spec.common.accuracy.precision();
        // A cycle whose impact stopped short of an earlier one repeats the cycle before it
        // to the bit (same history, d_e and pull-out: `run_cycles` reuses it), so its
        // contact states are the earlier cycle's: each distinct cycle is solved once.
        let same = |a: &switch_1d::Cycle<GwHistory>, b: &switch_1d::Cycle<GwHistory>| {
            a.d_e().to_bits() == b.d_e().to_bits()
                && a.unloading.pull_out_separation.to_bits()
                    == b.unloading.pull_out_separation.to_bits()
                && a.history == b.history
        };
        let source: Vec<usize> = wanted
            .iter()
            .map(|&i| {
                let cy = &run.cycles[i];
                wanted
                    .iter()
                    .copied()
                    .take_while(|&j| j < i)
                    .find(|&j| same(&run.cycles[j], cy))
                    .unwrap_or(i)
            })
            .collect();
        let unique: Vec<usize> = wanted
            .iter()
            .zip(&source)
            .filter(|(i, s)| i == s)
            .map(|(&i, _)| i)
            .collect();
        // each cycle's states and what failed of them (what, why), never an error
        let computed = contact_core::par::map(&unique, |&i| {
            let cy = &run.cycles[i];
            let d_e = cy.d_e();
            let retract = Path::Retract { from: d_e };
            let mut failed: Vec<(&'static str, ModelError)> = Vec::new();
            let end = self
                .contact_state(gw, &cy.history, d_e, retract)
                .map_err(|e| failed.push(("the contact state at the end of impact", e)))
                .ok();
            let rest = switch_1d::rest(
                gw,
                &cy.history,
                d_e,
                cy.unloading.pull_out_separation,
                hold,
                precision,
            )
            .map_err(|e| failed.push(("the rest under the hold", ModelError::from(e))))
            .ok();
            let (at, status) = match rest {
                None => (None, "not_computable"),
                Some(rest) => {
                    let at = match rest {
                        switch_1d::Rest::At(d) => Some((d, retract)),
                        switch_1d::Rest::Deeper(d) => Some((d, Path::Approach)),
                        _ => None,
                    };
                    let state = at.and_then(|(d, path)| {
                        self.contact_state(gw, &cy.history, d, path)
                            .map_err(|e| failed.push(("the contact state under the hold", e)))
                            .ok()
                    });
                    (state, rest.as_str())
                }
            };
            Ok::<_, ModelError>((i, at, status, end, failed))
        })
        .unwrap_or_default();
        let mut out: Vec<_> = (0..n).map(|_| (None, "not_computed", None)).collect();
        for (i, at, status, end, failed) in computed {
            out[i] = (at, status, end);
            for (what, e) in failed {
                let what = format!("{what} of cycle {}", run.cycles[i].cycle);
                not_computed.push(side_quantity_failed(&what, &e));
            }
        }
        for (&i, &from) in wanted.iter().zip(&source) {
            if from != i {
                out[i] = out[from].clone();
            }
        }
        out
    }

    /// The result of a scene before any cycle: the laws, the drive, the targets.
    fn empty_result(&self) -> SwitchResult {
        let s = self.spec;
        let es = &self.es;
        SwitchResult {
            title: s.common.title.clone(),
            laws: Laws::of(&s.contact),
            accuracy: s.common.accuracy.targets(),
            error_estimate: SwitchErrors {
                d_e: 0.0,
                pull_out: 0.0,
                accommodation: 0.0,
                pull_out_ratio: 0.0,
            },
            k_s: es.k_s,
            v_pull_in: es.v_pull_in,
            dynamic_pull_in_voltage: es.dynamic_pull_in_voltage,
            voltage: es.voltage,
            impact_energy: es.impact_energy,
            restoring_pressure: es.restoring_pressure,
            contact_area_fraction: s.switch.contact_area_fraction,
            hold_voltage: self.hold_voltage(),
            hold_force: s.switch.hold_force,
            hold_pressure: self.hold_pressure(),
            contact_state: s.contact_states.as_str(),
            closes: es.closes,
            drive: es.drive.clone(),
            accommodation_tolerance: s.accommodation_tolerance,
            loading: Vec::new(),
            cycles: Vec::new(),
            elastic: None,
            accommodated_after: None,
            accommodation_cause: None,
            largest_pull_out: 0.0,
            pull_out_ratio: 0.0,
            first_sticking_cycle: None,
            stiction: false,
            validity: Validity {
                holds: true,
                reasons: Vec::new(),
            },
            extrapolated_fraction: 0.0,
            warnings: Vec::new(),
            scene: s.common.echo(),
            model_form: None,
            dynamics: None,
        }
    }

    /// The same surface with asperities that never yield, one cycle through `run_cycles`.
    fn elastic_comparison(
        &self,
        impact: Impact,
        options: CycleOptions,
        progress: &dyn Progress,
    ) -> Result<ElasticResult, ModelError> {
        let el = self.surface(true)?;
        let one = CycleOptions {
            cycles: 1,
            loading_points: 0,
            ..options
        };
        let stoppable = crate::Cancellable::new(&el, progress);
        let e = switch_1d::run_cycles(&stoppable, el.virgin(), impact, one, &mut |_| {})?;
        let cy = &e.cycles[0];
        Ok(ElasticResult {
            d_e: cy.d_e(),
            pull_out_pressure: cy.unloading.pull_out_pressure,
            pull_out_separation: cy.unloading.pull_out_separation,
            pull_out_ratio: cy.pull_out_ratio,
            sticks: cy.sticks,
            unloading: cy.unloading.curve.clone(),
        })
    }
}

/// The rough surface of a spec's contact and roughness at an accuracy mode (`abs_floor`:
/// a pressure error in Pa that does not matter, 0 for none).
pub fn surface_of(
    spec: &SwitchSpec,
    accuracy: Accuracy,
    abs_floor: f64,
    elastic: bool,
) -> Result<RoughSurface, ModelError> {
    rough_surface(&spec.contact, spec.roughness, accuracy, abs_floor, elastic)
}

/// The rough surface of a contact and a roughness.
pub fn rough_surface(
    contact: &crate::spec::ContactSpec,
    roughness: crate::spec::RoughnessSpec,
    accuracy: Accuracy,
    abs_floor: f64,
    elastic: bool,
) -> Result<RoughSurface, ModelError> {
    // the adhesion law's cheaper form where the mode's quadrature cannot see its error
    let adhesion = contact
        .adhesion
        .law
        .within(accuracy.force_tolerance())
        .unwrap_or_else(|| contact.adhesion.law.clone());
    let asperity = if elastic {
        contact.elastic_asperity_with(adhesion)
    } else {
        contact.asperity_with(adhesion)
    };
    Ok(GreenwoodWilliamson::new(
        asperity,
        Roughness {
            sigma_s: roughness.sigma_s,
            asperity_density: roughness.asperity_density,
        },
        accuracy.quadrature(abs_floor),
    )?)
}

/// The warning of a quantity beside the cycles that could not be computed (`what`: "the
/// elastic comparison", "the rest under the hold of cycle 3", ...): it is absent from the
/// result, the cycles and the verdict stand.
fn side_quantity_failed(what: &str, e: &ModelError) -> Warning {
    Warning::note(
        guards::code::NOT_COMPUTED,
        format!(
            "{what} could not be computed ({e}): it is absent from the result; the cycles, the pull-out and the verdict do not depend on it"
        ),
    )
}

/// The guards of a run: the load beyond the fits at the deepest end of impact (with the
/// history before that cycle), adhesion that yields a virgin asperity, pressures above the
/// hardness or the interface's strength, impacts that did not deepen. A check that cannot
/// be evaluated is not made, with a warning pushed to `not_computed`.
fn physics_guards(
    s: &SwitchSpec,
    gw: &RoughSurface,
    run: &CycleRun<GwHistory>,
    not_computed: &mut Vec<Warning>,
) -> Vec<Warning> {
    let c = &s.contact;
    let mut warnings = Vec::new();
    let deepest = run
        .cycles
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.d_e().total_cmp(&b.1.d_e()))
        .map(|(i, _)| i)
        .unwrap_or(0);
    let before = if deepest == 0 {
        gw.virgin()
    } else {
        run.cycles[deepest - 1].history.clone()
    };
    let at = run.cycles[deepest].d_e();
    if let Some(hi) = guards::fit_range_max(c) {
        match gw.load_share_beyond(at, &before, Path::Approach, hi) {
            Ok(share) => warnings.extend(guards::surface_beyond_fit(c, share, at)),
            Err(e) => not_computed.push(side_quantity_failed(
                "the load share beyond the plasticity fits (the beyond_fit_range check)",
                &ModelError::from(e),
            )),
        }
    }
    match guards::adhesion_yields(c) {
        Ok(w) => warnings.extend(w),
        Err(e) => not_computed.push(side_quantity_failed(
            "the check whether adhesion yields an asperity (adhesion_yields_asperity)",
            &e,
        )),
    }
    let compressive = run
        .cycles
        .iter()
        .map(|cy| cy.end.pressure)
        .fold(0.0, f64::max);
    warnings.extend(guards::pressures(c, compressive, run.largest_pull_out));
    warnings.extend(non_deepening(s, run));
    warnings
}

/// `non_deepening_impact`: a cycle whose end of impact stopped above the deepest
/// separation of the earlier cycles, by more than the accommodation tolerance of sigma_s
/// and its error estimates.
fn non_deepening(s: &SwitchSpec, run: &CycleRun<GwHistory>) -> Option<Warning> {
    let sigma = s.roughness.sigma_s;
    let worst = run
        .cycles
        .iter()
        .filter(|cy| cy.shallower_by > s.accommodation_tolerance * sigma + 2.0 * cy.end.error)
        .max_by(|a, b| a.shallower_by.total_cmp(&b.shallower_by))?;
    let count = run
        .cycles
        .iter()
        .filter(|cy| cy.shallower_by > s.accommodation_tolerance * sigma + 2.0 * cy.end.error)
        .count();
    let yielded = s.contact.plasticity.name != "elastic";
    let cause = match (s.contact.reload, yielded) {
        (asperity_plastic::Reload::AsPrinted, true) => format!(
            "the reload of the flattened asperities is stiffer than their virgin loading (eq 12 as printed overshoots beyond about 16 delta_CP, docs/theory.md 2.5; the {} fits near yield, 2.6), so the impact is absorbed before it reaches the earlier depth; contact.reload = \"bounded\" removes that cause",
            s.contact.plasticity.name
        ),
        _ => "the reload curve absorbs the impact above the earlier depth".to_string(),
    };
    Some(Warning::note(
        guards::code::NON_DEEPENING,
        format!(
            "{count} cycle(s) stopped shallower than an earlier impact (worst: cycle {}, d_e {} above the deepest separation so far, {:.3} sigma_s): {cause}. Such a cycle leaves the history unchanged and every later cycle repeats it; accommodation declared then comes from the non-deepening impact, not from a settled surface",
            worst.cycle,
            guards::si(worst.shallower_by, "m", 3),
            worst.shallower_by / sigma
        ),
    ))
}

/// The tightest tolerance a run in time repeats its contact phases at to bring its error
/// estimates within the mode's targets (the explicit steps' own floor).
pub const MIN_DYNAMICS_TOLERANCE: f64 = 1e-12;

/// The largest ratio of a cycle's error estimate to the mode's target (d_e to
/// `sigma_s` x its tolerance, the pull-out to its tolerance x max(|p|, `floor`)): above 1
/// the run misses its targets.
fn estimate_excess<H>(
    targets: crate::accuracy::Targets,
    sigma_s: f64,
    floor: f64,
    run: &CycleRun<H>,
) -> f64 {
    run.cycles
        .iter()
        .map(|c| {
            let pull = c.unloading.pull_out_pressure.abs().max(floor);
            (c.end.error / (targets.d_e_tolerance_sigma * sigma_s))
                .max(c.unloading.pull_out_error / (targets.pull_out_tolerance * pull))
        })
        .fold(0.0, f64::max)
}

/// The pull-out's floor of the targets (Pa per contact area): 1e-9 of the restoring
/// pressure over phi, below which a pull-out counts as none.
fn pull_out_floor(result: &SwitchResult) -> f64 {
    1e-9 * result.restoring_pressure / result.contact_area_fraction
}

/// The cycles, the verdict and the error estimates of a run, into the result.
fn record(result: &mut SwitchResult, run: CycleRun<GwHistory>, impact: Impact) {
    let pull_err = run
        .cycles
        .iter()
        .map(|cy| cy.unloading.pull_out_error)
        .fold(0.0, f64::max);
    let total = pull_err + run.stopping_error;
    result.error_estimate = SwitchErrors {
        d_e: run.cycles.iter().map(|cy| cy.end.error).fold(0.0, f64::max),
        pull_out: total,
        accommodation: run.stopping_error,
        pull_out_ratio: impact.pull_out_ratio(total),
    };
    result.cycles = run
        .cycles
        .iter()
        .map(|cy| CycleResult {
            cycle: cy.cycle,
            d_e: cy.d_e(),
            d_e_error: cy.end.error,
            deepened: cy.deepened,
            shallower_by: cy.shallower_by,
            contact_pressure: cy.end.pressure,
            pull_out_pressure: cy.unloading.pull_out_pressure,
            pull_out_error: cy.unloading.pull_out_error,
            pull_out_separation: cy.unloading.pull_out_separation,
            pull_out_ratio: cy.pull_out_ratio,
            sticks: cy.sticks,
            unloading: cy.unloading.curve.clone(),
            well: cy.unloading.well.clone(),
            hold: None,
            hold_status: "not_computed",
            end_of_impact: None,
            impact: None,
            bounces: None,
            bounce_impacts: None,
            energy_ledger: None,
            capture_time: None,
            release: None,
        })
        .collect();
    result.loading = run.loading;
    result.accommodated_after = run.accommodated_after;
    result.accommodation_cause = run.accommodation_cause.map(AccommodationCause::as_str);
    result.largest_pull_out = run.largest_pull_out;
    result.pull_out_ratio = run.pull_out_ratio;
    result.first_sticking_cycle = run.first_sticking_cycle;
    result.stiction = run.stiction;
}

/// The largest real contact fraction up to which the spots of independent asperities
/// (Greenwood-Williamson) are read as separate spots without a note (theory 6.5).
pub const SPARSE_CONTACT_FRACTION: f64 = 0.2;

/// The guards of the contact states: `hold_deeper_than_impact` (a hold that presses the
/// contact further than its impact did; the cycles do not carry that extra loading into
/// the next impact) and `dense_contact_spots` (a real contact fraction above
/// [`SPARSE_CONTACT_FRACTION`]: the asperities' spots would merge, which GW's independent
/// asperities ignore; above 1 the area is impossible and the result leaves the model).
fn contact_warnings(result: &SwitchResult) -> Vec<Warning> {
    let mut out = Vec::new();
    let deeper: Vec<usize> = result
        .cycles
        .iter()
        .filter(|c| c.hold_status == "deeper_than_impact")
        .map(|c| c.cycle)
        .collect();
    if let Some(&first) = deeper.first() {
        out.push(Warning::note(
            guards::code::HOLD_DEEPER_THAN_IMPACT,
            format!(
                "the hold pressure {} per contact area exceeds the contact pressure at the end of impact in {} cycle(s) (first: cycle {first}): the hold presses the surface deeper than the impact did, and the cycles do not carry that extra loading into the next impact (the paper's model loads only by impacts); lower the hold or read the hold state of those cycles as a lower bound of the flattening",
                guards::si(result.hold_pressure, "Pa", 4),
                deeper.len()
            ),
        ));
    }
    let densest = result
        .cycles
        .iter()
        .flat_map(|c| {
            [
                ("under the hold", c.cycle, c.hold.as_ref()),
                ("at the end of impact", c.cycle, c.end_of_impact.as_ref()),
            ]
        })
        .filter_map(|(at, cy, st)| st.map(|st| (at, cy, st.real_contact_fraction)))
        .max_by(|a, b| a.2.total_cmp(&b.2));
    if let Some((at, cycle, f)) = densest.filter(|d| d.2 > SPARSE_CONTACT_FRACTION) {
        let message = format!(
            "the real contact area reaches {:.3} of the contact area ({at}, cycle {cycle}): Greenwood-Williamson asperities are independent, so their spots are counted as separate although at this density they merge{}; the area, spot count and resistance are estimates there",
            f,
            if f > 1.0 { " (above 1: an impossible area)" } else { "" }
        );
        out.push(if f > 1.0 {
            Warning::invalid(guards::code::DENSE_CONTACT_SPOTS, message)
        } else {
            Warning::note(guards::code::DENSE_CONTACT_SPOTS, message)
        });
    }
    out
}
