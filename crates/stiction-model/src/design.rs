//! Stiction-free design: a **design point** is a switch scene run until accommodated (at
//! most the scene's `cycles`), reduced to the pull-out ratio phi x largest pull-out /
//! K_s d0 (> 1 sticks), and the engine of the crate `design-sweep` turns design points into
//! the critical value of one scene field ([`threshold`]) and 1-D or 2-D maps over one or
//! two fields ([`map`], shardable): numeric fields (`FIELD=FROM:TO:lin|log:N`) and fields
//! whose value is a word, a law name or a choice (`FIELD=WORD,WORD,...`, e.g.
//! `contact.plasticity_law=etsion_kadin,kogut_etsion`). User guide: `docs/design.md`.
//!
//! Every design point starts from the scene as written (before validation, so that
//! defaults derived from other keys, such as `switch.film_youngs_modulus`, follow a varied
//! key), with `until_accommodated = true`, `points = 0`, `elastic_comparison = false` and
//! the accuracy mode given (else the scene's); the varied fields are set on the scene and
//! the result is validated like a scene file.

use crate::accuracy::Accuracy;
use crate::error::ModelError;
use crate::guards::{Validity, Warning};
use crate::keys::{self, num, Domain, Key, Kind};
use crate::laws::LawRegistry;
use crate::scene::Scene;
use crate::spec::{Drive, SwitchSpec};
use crate::switch::{SharedTables, SwitchModel, SwitchResult};
use crate::{check_cancelled, CancelOnly, Progress, Silent};
pub use design_sweep::{
    Axis, DesignPoint, Grid, Labels, Level, Map, MapRequest, PointError, Quantity, Requirement,
    Shard, Threshold, ThresholdOptions,
};
use std::collections::BTreeMap;
use std::sync::Mutex;

/// The name design points carry in messages (they have no file of their own).
pub const POINT: &str = "design point";

/// Runs design points of one scene: the field values are set on the scene, which is
/// validated and run until accommodated. Shareable between threads; it keeps a tally of
/// the physics guards the points raise.
pub struct Evaluator<'a> {
    base: Scene,
    registry: &'a LawRegistry,
    guards: Mutex<BTreeMap<&'static str, GuardTally>>,
    /// Reload-work tables by contact (the resolved contact section and the mode).
    tables: Mutex<BTreeMap<String, SharedTables>>,
    /// What stops the points (never, by default).
    stop: &'a dyn Progress,
}

/// Contacts whose reload-work tables an evaluator keeps; past this many it starts afresh
/// (a sweep over material values makes every point's contact new).
const KEPT_TABLES: usize = 64;

#[derive(Debug, Clone)]
struct GuardTally {
    points: usize,
    example: String,
    breaks_validity: bool,
}

/// The settings of a design point, applied to a scene before validation: run until
/// accommodated (capped by the scene's `cycles`), no curves, no elastic comparison, and
/// `accuracy` if given.
pub fn design_scene(scene: &Scene, accuracy: Option<Accuracy>) -> Result<Scene, ModelError> {
    // a design varies a switch: another kind of scene is said to be one, not reported by
    // the first key a switch does not take
    match scene.kind() {
        Ok(Kind::Switch) | Err(_) => {}
        Ok(other) => {
            return Err(ModelError::Option {
                name: "scene".into(),
                message: format!(
                    "{}: a {} scene; a design runs a switch scene (its [switch] section, with its drive)",
                    scene.file(),
                    other
                ),
            })
        }
    }
    let mut s = scene.clone();
    s.set("until_accommodated", toml::Value::Boolean(true))?;
    s.set("points", toml::Value::Integer(0))?;
    s.set("elastic_comparison", toml::Value::Boolean(false))?;
    if let Some(a) = accuracy {
        s.set("accuracy", toml::Value::String(a.as_str().into()))?;
    }
    // the contact state of the last cycle only (the map columns and requirements read it),
    // none when the scene says none
    if s.get("contact_state").and_then(|v| v.as_str()) != Some("none") {
        s.set("contact_state", toml::Value::String("last_cycle".into()))?;
    }
    Ok(s)
}

/// Parses `--require` and checks that the scene computes its quantity: a contact
/// resistance needs the films' conduction (`contact.resistivity`, `contact.mean_free_path`)
/// and `switch.electrode_area`; both quantities need `contact_state` other than `none`.
/// Errors name the argument `require`.
pub fn requirement(text: &str, base: &SwitchSpec) -> Result<Requirement, ModelError> {
    let r = Requirement::parse(text).map_err(|e| ModelError::Option {
        name: "require".into(),
        message: match e {
            design_sweep::DesignError::Requirement(m) => m,
            e => e.to_string(),
        },
    })?;
    if base.contact_states == crate::spec::ContactStates::None {
        return Err(ModelError::argument(
            "require",
            text,
            "a scene that computes the contact state: it sets contact_state = \"none\" (remove it, or set \"last_cycle\")",
        ));
    }
    if r.quantity == Quantity::ContactResistance {
        let mut missing = Vec::new();
        if base.contact.conduction.is_none() {
            missing.push("contact.resistivity and contact.mean_free_path in [contact]");
        }
        if base.switch.electrode_area.is_none() {
            missing.push("switch.electrode_area in [switch]");
        }
        if !missing.is_empty() {
            return Err(ModelError::argument(
                "require",
                text,
                format!(
                    "a scene with the films' conduction and the electrode area for a contact resistance: give {}",
                    missing.join(" and ")
                ),
            ));
        }
    }
    Ok(r)
}

impl<'a> Evaluator<'a> {
    /// An evaluator for `base`: a switch scene as written, with the design settings applied
    /// ([`design_scene`]), whose laws come from `registry`.
    pub fn new(base: Scene, registry: &'a LawRegistry) -> Self {
        Self {
            base,
            registry,
            guards: Mutex::new(BTreeMap::new()),
            tables: Mutex::new(BTreeMap::new()),
            stop: &Silent,
        }
    }

    /// The same evaluator, its points stopped by `progress` ([`Progress::cancelled`]): once
    /// it asks, a running point stops at its next surface evaluation and every point
    /// fails at once ([`PointError::Failed`]); the caller then reports the whole run as
    /// [`ModelError::Cancelled`].
    pub fn stopped_by(mut self, progress: &'a dyn Progress) -> Self {
        self.stop = progress;
        self
    }

    /// The reload-work tables of `spec`'s contact, shared by every point with an equal
    /// contact section and mode (within one registry a law's name, parameters and context
    /// determine it).
    fn tables_of(&self, spec: &SwitchSpec) -> SharedTables {
        let key = format!("{:?} {}", spec.contact, spec.common.accuracy);
        let mut tables = self.tables.lock().unwrap_or_else(|e| e.into_inner());
        if tables.len() >= KEPT_TABLES && !tables.contains_key(&key) {
            tables.clear();
        }
        tables.entry(key).or_default().clone()
    }

    /// The base scene.
    pub fn base(&self) -> &Scene {
        &self.base
    }

    /// The spec of one point: `values` (`section.key`, value in the key's SI unit) set on
    /// the base scene, validated. A value outside a key's domain, or a rule between keys it
    /// breaks, is [`PointError::OutOfDomain`] with the scene's message.
    pub fn spec(&self, values: &[(&str, f64)]) -> Result<SwitchSpec, PointError> {
        self.spec_at(&numbers(values))
    }

    /// [`Evaluator::spec`] of a point whose fields may be words (a law name, a choice),
    /// set on the scene as a scene file writes them (`plasticity_law = "kogut_etsion"`).
    pub fn spec_at(&self, values: &[(&str, Level<'_>)]) -> Result<SwitchSpec, PointError> {
        let mut s = self.base.clone();
        let out = |e: ModelError| PointError::OutOfDomain(e.without_file());
        for &(key, v) in values {
            match v {
                Level::Number(x) => s.set_number(key, x),
                Level::Word(w) => s.set(key, toml::Value::String(w.to_owned())),
            }
            .map_err(|e| out(e.into()))?;
        }
        SwitchSpec::new(&s, self.registry).map_err(out)
    }

    /// The full switch result of one point.
    pub fn result(&self, values: &[(&str, f64)]) -> Result<SwitchResult, PointError> {
        self.result_at(&numbers(values))
    }

    /// [`Evaluator::result`] of a point whose fields may be words.
    pub fn result_at(&self, values: &[(&str, Level<'_>)]) -> Result<SwitchResult, PointError> {
        let stopped = || PointError::Failed(ModelError::Cancelled.to_string());
        if self.stop.cancelled() {
            return Err(stopped());
        }
        let spec = self.spec_at(values)?;
        let model = SwitchModel::build(&spec)
            .map_err(|e| PointError::OutOfDomain(e.without_file()))?
            .with_tables(self.tables_of(&spec));
        model.run(&CancelOnly(self.stop)).map_err(|e| {
            if matches!(e, ModelError::Cancelled) {
                return stopped();
            }
            let m = e.without_file();
            let no_end_of_impact = matches!(
                e.cause(),
                ModelError::Switch(switch_1d::SwitchError::EnergyNotAbsorbed { .. })
            );
            use contact_core::{Categorized, Category};
            if e.category() == Category::Input || no_end_of_impact {
                PointError::OutOfDomain(m)
            } else {
                PointError::Failed(m)
            }
        })
    }

    /// One design point. Errors of the run that are bad input (such as a derived impact
    /// energy out of its range), and a scene for which the model has no end of impact
    /// (the surface cannot absorb the impact energy, mostly where adhesion pulls harder
    /// than the asperities push back), are `OutOfDomain`; the others `Failed`.
    pub fn point(&self, values: &[(&str, f64)]) -> Result<DesignPoint, PointError> {
        self.point_at(&numbers(values))
    }

    /// [`Evaluator::point`] of a point whose fields may be words: what a map runs.
    pub fn point_at(&self, values: &[(&str, Level<'_>)]) -> Result<DesignPoint, PointError> {
        let r = self.result_at(values)?;
        self.record_at(values, &r.warnings);
        Ok(design_point(&r))
    }

    /// Adds the guards one point raised (`values`: its fields and values) to the tally
    /// that [`Evaluator::warnings`] reports, as [`Evaluator::point`] does for the points it
    /// runs. For a front end that runs the points elsewhere ([`Evaluator::result`] and
    /// [`design_point`] on the workers of a cluster) and collects their warnings here.
    pub fn record(&self, values: &[(&str, f64)], warnings: &[Warning]) {
        self.record_at(&numbers(values), warnings)
    }

    /// [`Evaluator::record`] of a point whose fields may be words.
    pub fn record_at(&self, values: &[(&str, Level<'_>)], warnings: &[Warning]) {
        if warnings.is_empty() {
            return;
        }
        let at = values
            .iter()
            .map(|(k, v)| match v {
                Level::Number(x) => format!("{k} = {}", num(*x)),
                Level::Word(w) => format!("{k} = {w}"),
            })
            .collect::<Vec<_>>()
            .join(", ");
        if let Ok(mut g) = self.guards.lock() {
            // each code once per point: a count never exceeds the points
            let mut seen: Vec<&'static str> = Vec::new();
            for w in warnings {
                if seen.contains(&w.code) {
                    continue;
                }
                seen.push(w.code);
                g.entry(w.code)
                    .and_modify(|t| {
                        t.points += 1;
                        t.breaks_validity |= w.breaks_validity;
                    })
                    .or_insert_with(|| GuardTally {
                        points: 1,
                        example: format!("at {at}: {}", w.message),
                        breaks_validity: w.breaks_validity,
                    });
            }
        }
    }

    /// The guards raised so far, one warning per kind with the number of points that
    /// raised it out of `evaluated` and one example.
    pub fn warnings(&self, evaluated: usize) -> Vec<Warning> {
        let g = match self.guards.lock() {
            Ok(g) => g,
            Err(p) => p.into_inner(),
        };
        g.iter()
            .map(|(code, t)| Warning {
                code,
                message: format!(
                    "{} of {evaluated} design points raised it; e.g. {}",
                    t.points, t.example
                ),
                breaks_validity: t.breaks_validity,
            })
            .collect()
    }
}

/// Numeric field values as levels.
fn numbers<'a>(values: &[(&'a str, f64)]) -> Vec<(&'a str, Level<'a>)> {
    values.iter().map(|&(k, v)| (k, Level::Number(v))).collect()
}

/// A switch result reduced to a design point: a switch that does not close has ratio 0.
pub fn design_point(r: &SwitchResult) -> DesignPoint {
    if !r.closes {
        return DesignPoint::does_not_close(r.restoring_pressure);
    }
    // the closed switch under the hold voltage after the last cycle
    let hold = r.cycles.last().and_then(|c| c.hold.as_ref());
    DesignPoint {
        pull_out_ratio: r.pull_out_ratio,
        largest_pull_out_pa: r.largest_pull_out,
        restoring_pressure_pa: r.restoring_pressure,
        cycles_to_accommodation: r.accommodated_after,
        first_sticking_cycle: r.first_sticking_cycle,
        sticks: r.stiction,
        closes: true,
        validity_holds: r.validity.holds,
        accommodation_cause: match r.accommodation_cause {
            Some("non_deepening") => Some(design_sweep::AccommodationCause::NonDeepening),
            Some(_) => Some(design_sweep::AccommodationCause::Saturated),
            None => None,
        },
        contact_resistance: hold.and_then(|h| h.contact_resistance),
        real_contact_fraction: hold.map(|h| h.real_contact_fraction),
    }
}

// ------------------------------------------------------------------ fields

/// Whether a registry key is a field `design` may vary: a numeric key of a switch scene
/// written `section.key`.
fn variable(f: &Key) -> bool {
    f.domain.is_numeric() && f.key.contains('.') && f.in_kind(Kind::Switch)
}

/// The fields `design` may vary, in registry order.
pub fn variable_fields() -> impl Iterator<Item = &'static Key> {
    keys::KEYS.iter().filter(|f| variable(f))
}

/// Whether a registry key is a field a map may vary over words: a law name or a choice of
/// a switch scene written `section.key`.
fn categorical(f: &Key) -> bool {
    matches!(f.domain, Domain::Law | Domain::Choice(_))
        && f.key.contains('.')
        && f.in_kind(Kind::Switch)
}

/// The fields a map may vary over words (`FIELD=WORD,WORD,...`), in registry order: the
/// law names (`contact.adhesion_law`, `contact.plasticity_law`) and the choices
/// (`contact.yield_modulus`, `contact.reload`, `contact.counter`) of a switch scene.
pub fn categorical_fields() -> impl Iterator<Item = &'static Key> {
    keys::KEYS.iter().filter(|f| categorical(f))
}

/// The words a categorical field accepts, and what they are in words: the names of the
/// registry's laws of its kind, or the key's choices.
fn accepted_words<'r>(f: &Key, registry: &'r LawRegistry) -> (String, Vec<&'r str>) {
    match (f.domain, f.key) {
        (Domain::Choice(words), k) => (format!("a choice of {k}"), words.to_vec()),
        (_, k @ "contact.adhesion_law") => (
            format!("a registered adhesion law ({k})"),
            registry.adhesion_names(),
        ),
        (_, k @ "contact.plasticity_law") => (
            format!("a registered plasticity law ({k})"),
            registry.plasticity_names(),
        ),
        (_, k) => (format!("a word {k} takes"), Vec::new()),
    }
}

/// Checks a categorical axis (`FIELD=WORD,WORD,...`; `option` the text as given): the
/// field takes words (a law name or a choice of a switch scene), and each word is one the
/// scene key accepts (a law of `registry` of the key's kind, or one of the key's choices),
/// before any point runs. Errors name the option and the word.
pub fn check_words(
    axis: &Axis,
    option: &str,
    registry: &LawRegistry,
) -> Result<&'static Key, ModelError> {
    let field = axis.field.as_str();
    let fail = |reason: String| {
        Err(ModelError::Design(design_sweep::DesignError::Axis {
            option: option.to_owned(),
            reason,
        }))
    };
    let Some(f) = keys::key(field).filter(|f| categorical(f)) else {
        let list = categorical_fields()
            .map(|f| f.key)
            .collect::<Vec<_>>()
            .join(", ");
        let why = match keys::key(field) {
            Some(f) if variable(f) => {
                return fail(format!(
                    "{field} takes numbers, not words: vary it as {field}=FROM:TO:lin|log:N"
                ))
            }
            Some(f) if !f.key.contains('.') => format!(
                "`{field}` is a top-level setting of the scene, not a design field (set it in the scene file)"
            ),
            Some(_) => format!("`{field}` does not take a word a map can vary"),
            None => format!("unknown field `{field}`"),
        };
        return fail(format!(
            "{why}; the fields a map varies over words are: {list}"
        ));
    };
    let (what, accepted) = accepted_words(f, registry);
    for w in &axis.words {
        if !accepted.contains(&w.as_str()) {
            return fail(format!(
                "`{w}` is not {what}: one of {}",
                accepted.join(", ")
            ));
        }
    }
    Ok(f)
}

/// Checks that `field` may be varied on `base` (a validated switch spec): a known numeric
/// key of a switch scene, and not in conflict with the scene's drive or counter-surface.
/// The error (argument `vary`) says what to give.
pub fn check_field(field: &str, base: &SwitchSpec) -> Result<&'static Key, ModelError> {
    check_field_as(field, base, "vary")
}

/// [`check_field`] for a field given by the argument `argument` (`vary`, `scatter`).
pub fn check_field_as(
    field: &str,
    base: &SwitchSpec,
    argument: &str,
) -> Result<&'static Key, ModelError> {
    let list = || {
        variable_fields()
            .map(|f| f.key)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let fail = |message: String| {
        Err(ModelError::Option {
            name: argument.into(),
            message,
        })
    };
    let Some(f) = keys::key(field).filter(|f| variable(f)) else {
        let why = match keys::key(field) {
            Some(f) if !f.key.contains('.') => format!(
                "`{field}` is a top-level setting of the scene, not a design field (set it in the scene file)"
            ),
            Some(f) if categorical(f) => format!(
                "`{field}` is not a numeric key of a switch scene (it takes words: a map varies it as {field}=WORD,WORD,...)"
            ),
            Some(_) => format!("`{field}` is not a numeric key of a switch scene"),
            None => format!("unknown field `{field}`"),
        };
        return fail(format!(
            "{why}; the fields that can be varied are: {}",
            list()
        ));
    };
    let spring = matches!(base.switch.drive, Drive::Spring { .. });
    let per_length = base.switch.spring_constant.is_some();
    match field {
        "switch.k_s" if per_length => {
            return fail(
                "switch.k_s conflicts with the scene's drive: it gives switch.spring_constant over switch.electrode_area; vary switch.spring_constant (or give k_s instead)"
                    .into(),
            )
        }
        "switch.spring_constant" if !per_length => {
            return fail(
                "switch.spring_constant conflicts with the scene's drive: give `spring_constant = <N/m>` with `electrode_area = <m^2>` instead of k_s or impact_energy in [switch] to vary it, or vary switch.k_s"
                    .into(),
            )
        }
        "switch.k_s" | "switch.voltage" if !spring => {
            return fail(format!(
                "{field} conflicts with the scene's drive: it gives switch.impact_energy, from which K_s is derived (at U = V_PI); give `k_s = <Pa/m>` instead of `impact_energy` in [switch] to vary {field}{}",
                if field == "switch.k_s" {
                    ", or vary switch.impact_energy"
                } else {
                    " (voltage is then the step voltage, default V_PI)"
                }
            ))
        }
        "switch.impact_energy" if spring => {
            return fail(
                "switch.impact_energy conflicts with the scene's drive: it gives switch.k_s, from which E_I is derived (with the voltage); vary switch.k_s or switch.voltage, or give `impact_energy = <J/m^2>` instead of `k_s` (and no `voltage`) in [switch]"
                    .into(),
            )
        }
        "contact.counter_youngs_modulus"
        | "contact.counter_poisson_ratio"
        | "contact.counter_yield_stress"
            if !matches!(base.contact.counter, crate::spec::Counter::Material { .. }) =>
        {
            return fail(format!(
                "{field} applies only to a counter-surface of another material: give `counter = \"material\"` with counter_youngs_modulus and counter_poisson_ratio in [contact], or vary contact.youngs_modulus"
            ))
        }
        _ => {}
    }
    Ok(f)
}

/// The SI unit of a field, if it has one (not for pure numbers).
pub fn unit(field: &str) -> Option<&'static str> {
    keys::key(field)
        .map(|f| f.unit)
        .filter(|u| !u.is_empty() && *u != "-")
}

/// Plot and table labels of fields: their SI units.
pub fn field_labels<'k>(keys: impl Iterator<Item = &'k str>) -> Labels {
    keys.fold(Labels::new(), |l, k| match unit(k) {
        Some(u) => l.with_unit(k, u),
        None => l,
    })
}

/// Plot title and SI units of the varied fields. It depends only on the map (the scene
/// echo's title and the grid), so a merged map is drawn exactly like an unsharded one.
pub fn map_labels(map: &Map) -> Labels {
    let mut l = field_labels(map.grid().axes().iter().map(|a| a.field.as_str()));
    if let Some(t) = map.scene().get("title").and_then(|t| t.as_str()) {
        l = l.with_title(format!(
            "{t}: pull-out ratio after accommodation ({})",
            map.accuracy()
        ));
    }
    l
}

/// The relative tolerance of the root on the critical value: a tenth of the mode's
/// relative error of the ratio (no point refining below what the ratio can tell), within
/// [1e-9, 1e-3].
pub fn root_tolerance(accuracy: Accuracy) -> f64 {
    (0.1 * accuracy.targets().pull_out_tolerance).clamp(1e-9, 1e-3)
}

/// The base of a design question: the scene with the design settings, validated once
/// (so that a scene error is reported against the scene file).
pub(crate) fn base_spec(
    scene: &Scene,
    registry: &LawRegistry,
    accuracy: Option<Accuracy>,
) -> Result<(Scene, SwitchSpec), ModelError> {
    let s = design_scene(scene, accuracy)?;
    let spec = SwitchSpec::new(&s, registry)?;
    Ok((s, spec))
}

/// The answer of a threshold search: the crate's [`Threshold`], the accuracy mode, the
/// field's unit and the guards the points raised.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ThresholdResult {
    /// The search.
    #[serde(flatten)]
    pub threshold: Threshold,
    /// The accuracy mode of the design points.
    pub accuracy: &'static str,
    /// The laws and modelling choices of the base scene (a point varies only the field).
    pub laws: crate::switch::Laws,
    /// The resolved base scene (defaults filled in).
    pub scene: serde_json::Value,
    /// The SI unit of the parameter, its critical value and uncertainty.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit: Option<&'static str>,
    /// Units for tables.
    #[serde(skip)]
    pub labels: Labels,
    /// Guards the design points raised.
    #[serde(skip)]
    pub warnings: Vec<Warning>,
    /// Whether the model holds at every evaluated point (`reasons`: the checks that fail
    /// somewhere; each scan point says where in `validity_holds`).
    pub validity: Validity,
    /// The model-form check (`model_form = "check"`): the critical value under every
    /// combination of the credible published forms.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_form: Option<crate::model_form::ThresholdModelForm>,
}

/// The critical value of `field` in [`from`, `to`] at which the pull-out ratio after
/// accommodation crosses 1 (errors name the arguments `vary`, `from`, `to`).
pub fn threshold(
    scene: &Scene,
    registry: &LawRegistry,
    field: &str,
    from: f64,
    to: f64,
    accuracy: Option<Accuracy>,
) -> Result<ThresholdResult, ModelError> {
    threshold_with(scene, registry, field, from, to, accuracy, None, &Silent)
}

/// Evaluations a threshold search is expected to add to its scan: the refinement of one
/// crossing (the progress count's total; a search that needs more holds at total - 1
/// until it ends).
const REFINEMENT_ESTIMATE: usize = 8;

/// [`threshold`] with a second requirement `require` (`contact_resistance<1`, see
/// [`requirement`]): its crossings along the field and the window where the switch is
/// both free of stiction and meets it ([`design_sweep::threshold_with`]). The design
/// points it evaluates are reported to `progress` (the total: the scan and a typical
/// refinement), which can stop the search ([`ModelError::Cancelled`]).
#[allow(clippy::too_many_arguments)]
pub fn threshold_with(
    scene: &Scene,
    registry: &LawRegistry,
    field: &str,
    from: f64,
    to: f64,
    accuracy: Option<Accuracy>,
    require: Option<&str>,
    progress: &dyn Progress,
) -> Result<ThresholdResult, ModelError> {
    check_cancelled(progress)?;
    let (base, spec) = base_spec(scene, registry, accuracy)?;
    let require_text = require;
    let require = require.map(|t| requirement(t, &spec)).transpose()?;
    let f = check_field(field, &spec)?;
    for (name, v) in [("from", from), ("to", to)] {
        if !f.domain.contains(v) {
            return Err(ModelError::argument(
                name,
                num(v),
                format!("inside the domain of {}: {}", f.key, f.domain.describe()),
            ));
        }
    }
    let accuracy = spec.common.accuracy;
    let options = ThresholdOptions {
        tolerance: root_tolerance(accuracy),
        ratio_rel_error: accuracy.targets().pull_out_tolerance,
        scan_points: None,
    };
    let ev = Evaluator::new(base, registry).stopped_by(progress);
    let total = (options.scan_points_over(from, to) + REFINEMENT_ESTIMATE) as u64;
    progress.start(total, "design points");
    let evaluated = std::sync::atomic::AtomicU64::new(0);
    let t = design_sweep::threshold_with(
        f.key,
        from,
        to,
        |x| {
            let r = ev.point(&[(f.key, x)]);
            let n = evaluated.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress.set(n.min(total - 1));
            r
        },
        &options,
        require.as_ref(),
    );
    // a stopped search is no answer, whatever its points made of it
    check_cancelled(progress)?;
    let t = t?;
    progress.set(total);
    progress.finish();
    let warnings = ev.warnings(t.evaluations);
    let model_form = spec.model_form.check.then(|| {
        use crate::model_form::{check_accuracy, each_form, ThresholdFormRun, ThresholdModelForm};
        let mode = check_accuracy(accuracy);
        let (_, ran, excluded) = each_form(&spec, registry, scene, progress, |s| {
            threshold_with(
                s,
                registry,
                field,
                from,
                to,
                Some(mode),
                require_text,
                &CancelOnly(progress),
            )
        });
        let run_of = |r: &ThresholdResult| ThresholdFormRun {
            laws: r.laws.clone(),
            critical_value: r.threshold.critical_value,
            validity_holds: r.validity.holds,
        };
        let mut runs = vec![ThresholdFormRun {
            laws: crate::switch::Laws::of(&spec.contact),
            critical_value: t.critical_value,
            validity_holds: Validity::of(&warnings).holds,
        }];
        runs.extend(ran.iter().map(|(_, r)| run_of(r)));
        ThresholdModelForm::of(mode, runs, excluded)
    });
    Ok(ThresholdResult {
        validity: Validity::of(&warnings),
        labels: field_labels(std::iter::once(f.key)),
        // "-" for a dimensionless field (an absent unit read as "unknown" in Python)
        unit: unit(f.key).or(Some("-")),
        accuracy: accuracy.as_str(),
        laws: crate::switch::Laws::of(&spec.contact),
        scene: spec.common.echo(),
        threshold: t,
        warnings,
        model_form,
    })
}

/// A computed map (whole or one shard) with the guards its points raised.
#[derive(Debug, Clone)]
pub struct MapResult {
    /// The map.
    pub map: Map,
    /// Units and title.
    pub labels: Labels,
    /// Guards the design points raised.
    pub warnings: Vec<Warning>,
    /// Whether the model holds at every point (each point says so in `validity_holds`).
    pub validity: Validity,
    /// The model-form check (`model_form = "check"`): at each point, the share of the
    /// combinations of the credible published forms under which the switch sticks.
    pub model_form: Option<crate::model_form::MapModelForm>,
}

/// The request of a map: the scene with the design settings, the grid of `vary` (each
/// `FIELD=FROM:TO:lin|log:N`, or `FIELD=WORD,WORD,...` for a law name or a choice, see
/// [`check_words`]), the part of it `shard` names (`K/N`); checked before any point runs
/// (errors name the arguments `vary`, `shard`).
pub fn map_request(
    scene: &Scene,
    registry: &LawRegistry,
    vary: &[String],
    shard: Option<&str>,
    accuracy: Option<Accuracy>,
) -> Result<(Scene, MapRequest), ModelError> {
    map_request_with(scene, registry, vary, shard, accuracy, None).map(|(s, r, _)| (s, r))
}

/// [`map_request`] with a second requirement `require` (checked against the scene, see
/// [`requirement`]), returned parsed for [`Map::with_requirement`].
pub fn map_request_with(
    scene: &Scene,
    registry: &LawRegistry,
    vary: &[String],
    shard: Option<&str>,
    accuracy: Option<Accuracy>,
    require: Option<&str>,
) -> Result<(Scene, MapRequest, Option<Requirement>), ModelError> {
    let (base, spec) = base_spec(scene, registry, accuracy)?;
    let require = require.map(|t| requirement(t, &spec)).transpose()?;
    let grid = Grid::parse(vary)?;
    for (a, option) in grid.axes().iter().zip(vary) {
        if a.is_categorical() {
            check_words(a, option, registry)?;
        } else {
            check_field(&a.field, &spec)?;
        }
    }
    let shard = shard.map(Shard::parse).transpose()?;
    Ok((
        base,
        MapRequest {
            scene: spec.common.echo(),
            grid,
            accuracy: spec.common.accuracy.as_str().into(),
            shard,
        },
        require,
    ))
}

/// A map of the pull-out ratio over the grid of `vary` (points in parallel, each reported
/// to `progress`).
pub fn map(
    scene: &Scene,
    registry: &LawRegistry,
    vary: &[String],
    shard: Option<&str>,
    accuracy: Option<Accuracy>,
    progress: &dyn Progress,
) -> Result<MapResult, ModelError> {
    map_with(scene, registry, vary, shard, accuracy, None, progress)
}

/// [`map`] with a second requirement `require` (`contact_resistance<1`): the map marks
/// the points free of stiction that meet it (the design window).
pub fn map_with(
    scene: &Scene,
    registry: &LawRegistry,
    vary: &[String],
    shard: Option<&str>,
    accuracy: Option<Accuracy>,
    require: Option<&str>,
    progress: &dyn Progress,
) -> Result<MapResult, ModelError> {
    let (base, request, require) =
        map_request_with(scene, registry, vary, shard, accuracy, require)?;
    check_cancelled(progress)?;
    let ev = Evaluator::new(base, registry).stopped_by(progress);
    let total = match request.shard {
        Some(s) => s.indices(request.grid.len()).count(),
        None => request.grid.len(),
    };
    progress.start(total as u64, "design points");
    let done = Mutex::new(0u64);
    let map = design_sweep::run_map(
        request,
        |values| ev.point_at(values),
        |n, _| {
            if let Ok(mut d) = done.lock() {
                // workers report out of order: the count only moves forward
                *d = (*d).max(n as u64);
                progress.set(*d);
            }
        },
    );
    // a stopped map is no map: its points after the stop failed for that reason alone
    check_cancelled(progress)?;
    progress.finish();
    let map = map.with_requirement(require);
    let warnings = ev.warnings(map.points().len());
    let (_, spec) = base_spec(scene, registry, accuracy)?;
    let model_form = spec.model_form.check.then(|| {
        use crate::model_form::{check_accuracy, each_form, MapModelForm};
        let mode = check_accuracy(spec.common.accuracy);
        let (_, ran, excluded) = each_form(&spec, registry, scene, progress, |s| {
            map_with(
                s,
                registry,
                vary,
                shard,
                Some(mode),
                None,
                &CancelOnly(progress),
            )
        });
        let mut maps: Vec<(crate::switch::Laws, &Map)> =
            vec![(crate::switch::Laws::of(&spec.contact), &map)];
        maps.extend(ran.iter().map(|(form, r)| (form.laws(), &r.map)));
        MapModelForm::of(mode, &maps, excluded)
    });
    check_cancelled(progress)?;
    Ok(MapResult {
        validity: Validity::of(&warnings),
        labels: map_labels(&map),
        map,
        warnings,
        model_form,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::guards::code;

    #[test]
    fn recorded_warnings_are_tallied_once_per_point() {
        let registry = LawRegistry::builtin();
        let ev = Evaluator::new(Scene::paper(Kind::Switch), &registry);
        let w = Warning::invalid(code::BEYOND_FIT_RANGE, "most of the load".into());
        // a code raised twice by one point counts once
        ev.record(&[("surface.sigma_s", 2e-9)], &[w.clone(), w.clone()]);
        ev.record(&[("surface.sigma_s", 4e-9)], &[w]);
        ev.record(&[("surface.sigma_s", 8e-9)], &[]);
        let tally = ev.warnings(3);
        assert_eq!(tally.len(), 1);
        assert_eq!(tally[0].code, code::BEYOND_FIT_RANGE);
        assert!(tally[0].breaks_validity);
        assert_eq!(
            tally[0].message,
            format!(
                "2 of 3 design points raised it; e.g. at surface.sigma_s = {}: most of the load",
                num(2e-9)
            )
        );
    }
}
