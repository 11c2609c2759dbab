//! The model-form check (issue 42; docs/theory.md section 12): would another published
//! model form change the verdict?
//!
//! Four modelling choices of the contact can move a verdict: the plasticity law, the
//! reading of eq 1, the reload rule and the adhesion law. A check repeats the run under
//! every combination of their credible alternatives (the scene's own setting always among
//! them) and reports whether the verdict is the same under all ([`ModelFormReport`]). The
//! defaults ([`Forms::of`]):
//! - plasticity: the scene's law and every registered law that yields
//!   ([`crate::laws::PlasticityEntry::credible`]; a user's law is one unless it says not);
//! - eq 1: `as_printed` and `composite`;
//! - reload: `as_printed` and `bounded`;
//! - adhesion: the scene's law and `maugis_kim` (the Dugdale law holds at every Tabor
//!   parameter); `jkr` where the virgin asperity's lambda (eq 6) is at least 5 and `dmt`
//!   where it is at most 0.1, the limits of Johnson & Greenwood's adhesion map (J. Colloid
//!   Interface Sci. 192 (1997) 326); the others are listed in `excluded` with the reason.
//!
//! A scene pins a choice with a list key (`model_form_plasticity = ["etsion_kadin"]`).

use crate::error::ModelError;
use crate::keys::{RELOADS, YIELD_MODULI};
use crate::laws::LawRegistry;
use crate::scene::Scene;
use crate::spec::{ContactSpec, SwitchSpec};
use crate::switch::{Laws, SwitchModel, SwitchResult};
use crate::{Accuracy, CancelOnly, Progress};
use serde::Serialize;

/// A modelling choice a check varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Choice {
    /// `contact.plasticity_law`.
    Plasticity,
    /// `contact.yield_modulus` (the reading of eq 1).
    YieldModulus,
    /// `contact.reload`.
    Reload,
    /// `contact.adhesion_law`.
    Adhesion,
}

impl Choice {
    /// Every choice, in report order.
    pub const ALL: [Choice; 4] = [
        Choice::Plasticity,
        Choice::YieldModulus,
        Choice::Reload,
        Choice::Adhesion,
    ];

    /// The name reports use (`plasticity`, `yield_modulus`, `reload`, `adhesion`).
    pub fn as_str(self) -> &'static str {
        match self {
            Choice::Plasticity => "plasticity",
            Choice::YieldModulus => "yield_modulus",
            Choice::Reload => "reload",
            Choice::Adhesion => "adhesion",
        }
    }

    /// The scene key the choice sets.
    pub fn scene_key(self) -> &'static str {
        match self {
            Choice::Plasticity => "contact.plasticity_law",
            Choice::YieldModulus => "contact.yield_modulus",
            Choice::Reload => "contact.reload",
            Choice::Adhesion => "contact.adhesion_law",
        }
    }

    /// The scene key that pins it (`model_form_plasticity`, ...).
    pub fn pin_key(self) -> &'static str {
        match self {
            Choice::Plasticity => "model_form_plasticity",
            Choice::YieldModulus => "model_form_yield_modulus",
            Choice::Reload => "model_form_reload",
            Choice::Adhesion => "model_form_adhesion",
        }
    }

    /// The choice's value in words for a verdict line ("composite eq 1").
    fn words(self, value: &str) -> String {
        match self {
            Choice::Plasticity => value.to_string(),
            Choice::YieldModulus => format!("{value} eq 1"),
            Choice::Reload => format!("{value} reload"),
            Choice::Adhesion => value.to_string(),
        }
    }
}

/// The model-form settings of a switch scene (`model_form` and the pins).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ModelFormSpec {
    /// `model_form = "check"`.
    pub(crate) check: bool,
    /// The pinned choices and their values (validated words).
    pub(crate) pins: Vec<(Choice, Vec<String>)>,
}

impl ModelFormSpec {
    /// `model_form = "check"`.
    #[must_use]
    pub fn check(&self) -> bool {
        self.check
    }

    /// The pinned choices and their values (validated words).
    #[must_use]
    pub fn pins(&self) -> &[(Choice, Vec<String>)] {
        &self.pins
    }

    /// The values a choice is pinned to, if it is.
    pub fn pinned(&self, choice: Choice) -> Option<&[String]> {
        self.pins
            .iter()
            .find(|(c, _)| *c == choice)
            .map(|(_, v)| v.as_slice())
    }
}

/// One combination of the four choices.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct Form {
    /// Plasticity law.
    pub plasticity: String,
    /// Reading of eq 1.
    pub yield_modulus: String,
    /// Reload rule.
    pub reload: String,
    /// Adhesion law.
    pub adhesion: String,
}

impl Form {
    /// The form of a contact.
    pub fn of(c: &ContactSpec) -> Self {
        Self {
            plasticity: c.plasticity.name.clone(),
            yield_modulus: c.yield_modulus.as_str().into(),
            reload: c.reload.as_str().into(),
            adhesion: c.adhesion.name.clone(),
        }
    }

    /// The form as the laws line of a result.
    pub fn laws(&self) -> Laws {
        let word = |words: &[&'static str], w: &str| -> &'static str {
            words.iter().copied().find(|x| *x == w).unwrap_or("unknown")
        };
        Laws {
            adhesion: self.adhesion.clone(),
            plasticity: self.plasticity.clone(),
            yield_modulus: word(YIELD_MODULI, &self.yield_modulus),
            reload: word(RELOADS, &self.reload),
        }
    }

    /// The value of one choice.
    pub fn get(&self, choice: Choice) -> &str {
        match choice {
            Choice::Plasticity => &self.plasticity,
            Choice::YieldModulus => &self.yield_modulus,
            Choice::Reload => &self.reload,
            Choice::Adhesion => &self.adhesion,
        }
    }

    fn with(&self, choice: Choice, value: &str) -> Self {
        let mut f = self.clone();
        let slot = match choice {
            Choice::Plasticity => &mut f.plasticity,
            Choice::YieldModulus => &mut f.yield_modulus,
            Choice::Reload => &mut f.reload,
            Choice::Adhesion => &mut f.adhesion,
        };
        *slot = value.to_string();
        f
    }

    /// The choices in which it differs from `other`.
    pub fn differences(&self, other: &Form) -> Vec<Choice> {
        Choice::ALL
            .into_iter()
            .filter(|&c| self.get(c) != other.get(c))
            .collect()
    }

    /// `base` with the four choices set and `model_form = "single"`: the scene a design
    /// question (threshold, map, probability) asks again under this form.
    pub fn apply(&self, base: &Scene) -> Result<Scene, ModelError> {
        let mut s = base.clone();
        let word = |w: &str| toml::Value::String(w.to_string());
        for c in Choice::ALL {
            s.set(c.scene_key(), word(self.get(c)))?;
        }
        s.set("model_form", word("single"))?;
        Ok(s)
    }

    /// The scene of this form for a switch check: [`Form::apply`], and what a check's runs
    /// need (no curves, no elastic comparison, no contact state, the check's accuracy
    /// mode).
    pub fn scene(&self, base: &Scene, accuracy: Accuracy) -> Result<Scene, ModelError> {
        let mut s = self.apply(base)?;
        let word = |w: &str| toml::Value::String(w.to_string());
        s.set("points", toml::Value::Integer(0))?;
        s.set("elastic_comparison", toml::Value::Boolean(false))?;
        s.set("contact_state", word("none"))?;
        s.set("accuracy", word(accuracy.as_str()))?;
        Ok(s)
    }
}

/// The form of a resolved scene (a result's echo, as JSON: `contact.plasticity_law`, ...),
/// if it names all four choices.
pub fn form_of_echo(echo: &serde_json::Value) -> Option<Form> {
    let c = echo.get("contact")?;
    let word = |k: &str| c.get(k).and_then(|v| v.as_str()).map(str::to_string);
    Some(Form {
        plasticity: word("plasticity_law")?,
        yield_modulus: word("yield_modulus")?,
        reload: word("reload")?,
        adhesion: word("adhesion_law")?,
    })
}

/// A value a check leaves out, and why.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct Excluded {
    /// The choice (`adhesion`, ...), or `combination` for a whole combination that could
    /// not run.
    pub choice: String,
    /// The value or the combination in words.
    pub value: String,
    /// Why.
    pub reason: String,
}

/// The combinations a check runs, and what it leaves out.
#[derive(Debug, Clone, PartialEq)]
pub struct Forms {
    /// The scene's own form.
    pub own: Form,
    /// Every combination, the scene's own first.
    pub forms: Vec<Form>,
    /// Values left out, with the reason.
    pub excluded: Vec<Excluded>,
}

/// The Tabor parameter at or above which JKR is a credible form (Johnson & Greenwood
/// 1997's adhesion map).
pub const JKR_LAMBDA: f64 = 5.0;
/// The Tabor parameter at or below which DMT is a credible form.
pub const DMT_LAMBDA: f64 = 0.1;

impl Forms {
    /// The combinations of a switch spec (module docs).
    pub fn of(spec: &SwitchSpec, registry: &LawRegistry) -> Self {
        let own = Form::of(&spec.contact);
        let mut excluded = Vec::new();
        // a law for the regime where the uncoupled laws' assumption fails is tried there
        let adhesion_yields = matches!(crate::guards::adhesion_yields(&spec.contact), Ok(Some(_)));
        let lambda = spec.contact.lambda();
        let values = |choice: Choice, excluded: &mut Vec<Excluded>| -> Vec<String> {
            let mut v: Vec<String> = vec![own.get(choice).to_string()];
            fn add(v: &mut Vec<String>, w: &str) {
                if !v.iter().any(|x| x == w) {
                    v.push(w.to_string());
                }
            }
            if let Some(pinned) = spec.model_form.pinned(choice) {
                pinned.iter().for_each(|w| add(&mut v, w));
                return v;
            }
            match choice {
                Choice::Plasticity => {
                    for e in registry.plasticity_laws().iter().filter(|e| e.credible()) {
                        if e.only_where_adhesion_yields() && !adhesion_yields {
                            if !v.iter().any(|x| x == e.name()) {
                                excluded.push(Excluded {
                                    choice: choice.as_str().into(),
                                    value: e.name().into(),
                                    reason: "adhesion does not yield a virgin asperity here (no adhesion_yields_asperity), so the uncoupled laws' assumption holds: pin it with model_form_plasticity to include it".into(),
                                });
                            }
                            continue;
                        }
                        add(&mut v, e.name());
                    }
                }
                Choice::YieldModulus => YIELD_MODULI.iter().for_each(|w| add(&mut v, w)),
                Choice::Reload => RELOADS.iter().for_each(|w| add(&mut v, w)),
                Choice::Adhesion => {
                    add(&mut v, "maugis_kim");
                    for e in registry.adhesion_laws() {
                        let name = e.name();
                        if v.iter().any(|x| x == name) {
                            continue;
                        }
                        let reason = match name {
                            "jkr" if lambda >= JKR_LAMBDA => {
                                add(&mut v, name);
                                continue;
                            }
                            "dmt" if lambda <= DMT_LAMBDA => {
                                add(&mut v, name);
                                continue;
                            }
                            "jkr" => format!(
                                "the Tabor parameter lambda = {} of the virgin asperity (eq 6) is below {JKR_LAMBDA}, where JKR holds (Johnson & Greenwood 1997)",
                                ratio_words(lambda)
                            ),
                            "dmt" => format!(
                                "the Tabor parameter lambda = {} of the virgin asperity (eq 6) is above {DMT_LAMBDA}, where DMT holds (Johnson & Greenwood 1997)",
                                ratio_words(lambda)
                            ),
                            "hertz" => "no adhesion: not a form of an adhering contact".into(),
                            _ => "a law of one's own: pin it with model_form_adhesion to include it".into(),
                        };
                        excluded.push(Excluded {
                            choice: choice.as_str().into(),
                            value: name.into(),
                            reason,
                        });
                    }
                }
            }
            if choice == Choice::Plasticity {
                for e in registry.plasticity_laws().iter().filter(|e| !e.credible()) {
                    if !v.iter().any(|x| x == e.name()) {
                        excluded.push(Excluded {
                            choice: choice.as_str().into(),
                            value: e.name().into(),
                            reason: "never yields: not a plasticity form of a metal film".into(),
                        });
                    }
                }
            }
            v
        };
        let sets: Vec<(Choice, Vec<String>)> = Choice::ALL
            .into_iter()
            .map(|c| (c, values(c, &mut excluded)))
            .collect();
        let mut forms = vec![own.clone()];
        for p in &sets[0].1 {
            for y in &sets[1].1 {
                for r in &sets[2].1 {
                    for a in &sets[3].1 {
                        let f = own
                            .with(Choice::Plasticity, p)
                            .with(Choice::YieldModulus, y)
                            .with(Choice::Reload, r)
                            .with(Choice::Adhesion, a);
                        if f != own {
                            forms.push(f);
                        }
                    }
                }
            }
        }
        Self {
            own,
            forms,
            excluded,
        }
    }
}

/// One combination's run.
#[derive(Debug, Clone, Serialize)]
pub struct ModelFormRun {
    /// Its laws and choices.
    pub laws: Laws,
    /// The largest pull-out ratio over its cycles.
    pub pull_out_ratio: f64,
    /// Whether it sticks (ratio > 1).
    pub stiction: bool,
    /// Whether the model holds for it (no guard puts it outside its validity).
    pub validity_holds: bool,
    /// Whether the ratio lies farther from 1 than its error estimate (else the verdict is
    /// within the numerics of the check's mode).
    pub decided: bool,
    /// Whether the switch closes under this form.
    pub closes: bool,
}

impl ModelFormRun {
    fn of(r: &SwitchResult) -> Self {
        Self {
            laws: r.laws.clone(),
            pull_out_ratio: r.pull_out_ratio,
            stiction: r.stiction,
            validity_holds: r.validity.holds,
            decided: (r.pull_out_ratio - 1.0).abs() > r.error_estimate.pull_out_ratio,
            closes: r.closes,
        }
    }
}

/// What a check found for a switch.
#[derive(Debug, Clone, Serialize)]
pub struct ModelFormReport {
    /// The mode the combinations ran in (the scene's, or `balanced` for an accurate or
    /// reference scene: its ratio error, 1e-6, decides every verdict not within it of 1).
    pub accuracy: &'static str,
    /// Every combination gives the scene's verdict.
    pub robust: bool,
    /// The choices for which changing that choice alone from the scene's own setting
    /// flips the verdict (`[]` when none does).
    pub flips: Vec<&'static str>,
    /// [lowest, highest] pull-out ratio over the combinations: the margin a designer has.
    pub ratio_range: [f64; 2],
    /// One entry per combination, the scene's own first.
    pub runs: Vec<ModelFormRun>,
    /// Values and combinations left out, with the reason.
    pub excluded: Vec<Excluded>,
    /// The verdict in words ("sticks under all 8 combinations; smallest ratio 1.07 with
    /// composite eq 1").
    pub summary: String,
}

/// The mode a check's combinations run in for a scene of mode `own`.
pub fn check_accuracy(own: Accuracy) -> Accuracy {
    match own {
        Accuracy::Accurate | Accuracy::Reference => Accuracy::Balanced,
        other => other,
    }
}

/// Runs a switch scene as it asks: its own run, and beside it the model-form check when
/// `model_form = "check"` (the combinations in parallel, `progress` counting them).
pub fn run_switch(
    spec: &SwitchSpec,
    registry: &LawRegistry,
    progress: &dyn Progress,
) -> Result<SwitchResult, ModelError> {
    let mut result = SwitchModel::build(spec)?.run(progress)?;
    if spec.model_form.check {
        result.model_form = Some(check_switch(spec, registry, &result, progress)?);
    }
    Ok(result)
}

/// The model-form check of a switch whose own run gave `own` (reused as the scene's own
/// combination when the check runs in the scene's mode).
pub fn check_switch(
    spec: &SwitchSpec,
    registry: &LawRegistry,
    own: &SwitchResult,
    progress: &dyn Progress,
) -> Result<ModelFormReport, ModelError> {
    let forms = Forms::of(spec, registry);
    let accuracy = check_accuracy(spec.common.accuracy);
    let reuse = accuracy == spec.common.accuracy;
    let base = &spec.common.scene;
    progress.start(forms.forms.len() as u64, "model forms");
    let done = std::sync::atomic::AtomicU64::new(0);
    let outcomes = contact_core::par::map(&forms.forms, |form| {
        let out = if reuse && *form == forms.own {
            Ok(ModelFormRun::of(own))
        } else {
            run_form(form, base, registry, accuracy, progress)
        };
        progress.set(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
        Ok::<_, ModelError>(out)
    })?;
    // a stopped check is no check (its combinations failed for that reason alone)
    crate::check_cancelled(progress)?;
    progress.finish();
    let mut excluded = forms.excluded.clone();
    let mut runs = Vec::new();
    let mut kept = Vec::new();
    for (form, outcome) in forms.forms.iter().zip(outcomes) {
        match outcome {
            Ok(r) => {
                runs.push(r);
                kept.push(form.clone());
            }
            Err(e) if *form == forms.own => return Err(e),
            Err(e) => excluded.push(Excluded {
                choice: "combination".into(),
                value: describe(form),
                reason: e.without_file(),
            }),
        }
    }
    Ok(report(accuracy, &forms.own, &kept, runs, excluded))
}

/// One combination's run (its scene validated like any scene: a form that a scene key
/// refuses is an error naming it).
fn run_form(
    form: &Form,
    base: &Scene,
    registry: &LawRegistry,
    accuracy: Accuracy,
    progress: &dyn Progress,
) -> Result<ModelFormRun, ModelError> {
    let scene = form.scene(base, accuracy)?;
    let spec = SwitchSpec::new(&scene, registry)?;
    let r = SwitchModel::build(&spec)?.run(&CancelOnly(progress))?;
    Ok(ModelFormRun::of(&r))
}

/// A combination in words ("kogut_etsion, composite eq 1, bounded reload, maugis_kim").
pub fn describe(form: &Form) -> String {
    Choice::ALL
        .into_iter()
        .map(|c| c.words(form.get(c)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The report of the combinations `forms` (the scene's own first) and their runs.
pub fn report(
    accuracy: Accuracy,
    own: &Form,
    forms: &[Form],
    runs: Vec<ModelFormRun>,
    excluded: Vec<Excluded>,
) -> ModelFormReport {
    let verdict = runs.first().map(|r| r.stiction).unwrap_or(false);
    let robust = runs.iter().all(|r| r.stiction == verdict);
    let mut flips: Vec<&'static str> = Vec::new();
    for (form, r) in forms.iter().zip(&runs) {
        if let [c] = form.differences(own)[..] {
            if r.stiction != verdict && !flips.contains(&c.as_str()) {
                flips.push(c.as_str());
            }
        }
    }
    flips.sort_by_key(|f| Choice::ALL.iter().position(|c| c.as_str() == *f));
    let (i_low, low) = runs
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.pull_out_ratio.total_cmp(&b.1.pull_out_ratio))
        .expect("the scene's own run");
    let highest = runs
        .iter()
        .map(|r| r.pull_out_ratio)
        .fold(low.pull_out_ratio, f64::max);
    let ratio_range = [low.pull_out_ratio, highest];
    // what differs from the scene's own form, in words
    let differing = |i: usize| {
        let d = forms[i].differences(own);
        if d.is_empty() {
            "the scene's own choices".to_string()
        } else {
            d.iter()
                .map(|&c| c.words(forms[i].get(c)))
                .collect::<Vec<_>>()
                .join(", ")
        }
    };
    let n = runs.len();
    let summary = if robust {
        format!(
            "{} under all {n} combinations; smallest ratio {} with {}",
            if verdict { "sticks" } else { "free" },
            ratio_words(low.pull_out_ratio),
            differing(i_low)
        )
    } else {
        let other: Vec<usize> = (0..n).filter(|&i| runs[i].stiction != verdict).collect();
        // the combination that flips with the fewest changes, then the farthest ratio
        let &i = other
            .iter()
            .min_by(|&&a, &&b| {
                forms[a]
                    .differences(own)
                    .len()
                    .cmp(&forms[b].differences(own).len())
            })
            .expect("a combination that flips");
        format!(
            "NOT robust: {} under {} of {n} combinations; e.g. {} with {}, ratio {}",
            if verdict { "free" } else { "sticks" },
            other.len(),
            if verdict { "free" } else { "sticks" },
            differing(i),
            ratio_words(runs[i].pull_out_ratio)
        )
    };
    ModelFormReport {
        accuracy: accuracy.as_str(),
        robust,
        flips,
        ratio_range,
        runs,
        excluded,
        summary,
    }
}

/// A ratio for a verdict line, to three significant digits (1.07, 0.0151, 158).
fn ratio_words(r: f64) -> String {
    if r == 0.0 || !r.is_finite() {
        return format!("{r}");
    }
    if (1e-3..1e6).contains(&r.abs()) {
        let digits = (2 - r.abs().log10().floor() as i32).max(0) as usize;
        format!("{r:.digits$}")
    } else {
        format!("{r:.2e}")
    }
}

/// Runs `question` under every combination but the scene's own (in order, each one's
/// points in parallel inside it), with the combination's scene; a combination that the
/// scene keys refuse or that fails is left out with the reason. The scene's own form first
/// in the forms returned, then those that ran. `progress` sees a stage of its own, one
/// step a combination (the question's runs should report to it only their stop, as
/// [`crate::CancelOnly`]).
pub fn each_form<T>(
    spec: &SwitchSpec,
    registry: &LawRegistry,
    scene: &Scene,
    progress: &dyn crate::Progress,
    mut question: impl FnMut(&Scene) -> Result<T, ModelError>,
) -> (Forms, Vec<(Form, T)>, Vec<Excluded>) {
    let forms = Forms::of(spec, registry);
    let mut excluded = forms.excluded.clone();
    let mut ran = Vec::new();
    progress.start(
        forms.forms.len().saturating_sub(1) as u64,
        "model-form combinations",
    );
    for (k, form) in forms.forms.iter().skip(1).enumerate() {
        match form.apply(scene).and_then(|s| question(&s)) {
            Ok(t) => ran.push((form.clone(), t)),
            Err(e) => excluded.push(Excluded {
                choice: "combination".into(),
                value: describe(form),
                reason: e.without_file(),
            }),
        }
        progress.set(k as u64 + 1);
    }
    progress.finish();
    (forms, ran, excluded)
}

/// For a front end that runs a design question's combinations elsewhere (a cluster): when
/// the scene asks for a check, the mode the other combinations run in, each one's form and
/// scene ([`Form::apply`] on `scene`), and what is left out; None when it does not ask.
/// `accuracy`: the question's mode option (else the scene's).
#[allow(clippy::type_complexity)]
pub fn design_forms(
    scene: &Scene,
    registry: &LawRegistry,
    accuracy: Option<Accuracy>,
) -> Result<Option<(Accuracy, Vec<(Form, Scene)>, Vec<Excluded>)>, ModelError> {
    let (_, spec) = crate::design::base_spec(scene, registry, accuracy)?;
    if !spec.model_form.check {
        return Ok(None);
    }
    let forms = Forms::of(&spec, registry);
    let mut excluded = forms.excluded.clone();
    let mut out = Vec::new();
    for form in forms.forms.into_iter().skip(1) {
        match form.apply(scene) {
            Ok(s) => out.push((form, s)),
            Err(e) => excluded.push(Excluded {
                choice: "combination".into(),
                value: describe(&form),
                reason: e.without_file(),
            }),
        }
    }
    Ok(Some((check_accuracy(spec.common.accuracy), out, excluded)))
}

/// One combination's answer to a threshold question.
#[derive(Debug, Clone, Serialize)]
pub struct ThresholdFormRun {
    /// Its laws and choices.
    pub laws: Laws,
    /// The critical value (the field's SI unit; null where the ratio does not cross 1 in
    /// the range).
    pub critical_value: Option<f64>,
    /// Whether the model holds at every point it evaluated.
    pub validity_holds: bool,
}

/// The model-form check of a threshold: the critical value under each combination.
#[derive(Debug, Clone, Serialize)]
pub struct ThresholdModelForm {
    /// The mode the other combinations ran in.
    pub accuracy: &'static str,
    /// Every combination finds a critical value, or none does.
    pub robust: bool,
    /// [lowest, highest] critical value over the combinations that find one (null when
    /// none does).
    pub critical_range: Option<[f64; 2]>,
    /// One entry per combination, the scene's own first.
    pub runs: Vec<ThresholdFormRun>,
    /// Values and combinations left out, with the reason.
    pub excluded: Vec<Excluded>,
    /// The answer in words.
    pub summary: String,
}

impl ThresholdModelForm {
    /// The report of the runs (the scene's own first).
    pub fn of(accuracy: Accuracy, runs: Vec<ThresholdFormRun>, excluded: Vec<Excluded>) -> Self {
        let found: Vec<f64> = runs.iter().filter_map(|r| r.critical_value).collect();
        let robust = found.is_empty() || found.len() == runs.len();
        let critical_range = (!found.is_empty()).then(|| {
            let lo = found.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = found.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            [lo, hi]
        });
        let n = runs.len();
        let summary = match critical_range {
            None => format!("no combination of {n} finds a critical value in the range"),
            Some([lo, hi]) if robust => format!(
                "every one of {n} combinations finds a critical value, from {lo:.4e} to {hi:.4e} (a factor {})",
                ratio_words(if lo != 0.0 { hi / lo } else { f64::INFINITY })
            ),
            Some([lo, hi]) => format!(
                "NOT robust: {} of {n} combinations find a critical value (from {lo:.4e} to {hi:.4e}), the others none in the range",
                found.len(),
            ),
        };
        Self {
            accuracy: accuracy.as_str(),
            robust,
            critical_range,
            runs,
            excluded,
            summary,
        }
    }
}

/// One Clopper-Pearson interval and its estimate.
#[derive(Debug, Clone, Serialize)]
pub struct ProbabilityFormRun {
    /// Its laws and choices.
    pub laws: Laws,
    /// P(stiction) over the samples that count (null where none does).
    pub stiction_probability: Option<f64>,
    /// Its Clopper-Pearson interval.
    pub interval: [f64; 2],
    /// The counted samples that stick (so that shards merge: `design merge`).
    pub sticking: usize,
    /// The counted samples (the denominator).
    pub counted: usize,
}

/// The model-form check of a failure probability.
#[derive(Debug, Clone, Serialize)]
pub struct ProbabilityModelForm {
    /// The mode the other combinations ran in.
    pub accuracy: &'static str,
    /// The intervals' confidence.
    pub confidence: f64,
    /// [lowest, highest] P(stiction) over the combinations.
    pub stiction_probability_range: [f64; 2],
    /// One entry per combination, the scene's own first.
    pub runs: Vec<ProbabilityFormRun>,
    /// Values and combinations left out, with the reason.
    pub excluded: Vec<Excluded>,
    /// The answer in words.
    pub summary: String,
}

/// The range of P(stiction) over the combinations, in words ("P(stiction) from 0.400 to 1.00
/// over 8 combinations"): the summary of a check, and of the merge of its shards.
pub fn probability_summary(range: [f64; 2], combinations: usize) -> String {
    format!(
        "P(stiction) from {} to {} over {combinations} combinations",
        ratio_words(range[0]),
        ratio_words(range[1])
    )
}

impl ProbabilityModelForm {
    /// The report of the runs (the scene's own first), their intervals at `confidence`.
    pub fn of(
        accuracy: Accuracy,
        confidence: f64,
        runs: Vec<ProbabilityFormRun>,
        excluded: Vec<Excluded>,
    ) -> Self {
        let ps: Vec<f64> = runs.iter().filter_map(|r| r.stiction_probability).collect();
        let lo = ps.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ps.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let range = if ps.is_empty() { [0.0, 1.0] } else { [lo, hi] };
        let summary = probability_summary(range, runs.len());
        Self {
            accuracy: accuracy.as_str(),
            confidence,
            stiction_probability_range: range,
            runs,
            excluded,
            summary,
        }
    }
}

impl MapModelForm {
    /// The check of the maps of the combinations (the scene's own first, each with its
    /// laws; every map of the same grid and shard).
    pub fn of(
        accuracy: Accuracy,
        maps: &[(Laws, &crate::design::Map)],
        excluded: Vec<Excluded>,
    ) -> Self {
        let n = maps.first().map_or(0, |(_, m)| m.points().len());
        let mut share = vec![None; n];
        let mut robust_points = 0;
        for (i, slot) in share.iter_mut().enumerate() {
            // a switch sticks at a point where its ratio exceeds 1 (one that does not
            // close has ratio 0); failed points have no answer
            let verdicts: Vec<bool> = maps
                .iter()
                .filter_map(|(_, m)| m.points().get(i).and_then(|p| p.ratio()))
                .map(|ratio| ratio > 1.0)
                .collect();
            if verdicts.is_empty() {
                continue;
            }
            let sticking = verdicts.iter().filter(|&&v| v).count();
            *slot = Some(sticking as f64 / verdicts.len() as f64);
            if sticking == 0 || sticking == verdicts.len() {
                robust_points += 1;
            }
        }
        Self {
            accuracy: accuracy.as_str(),
            combinations: maps.iter().map(|(l, _)| l.clone()).collect(),
            share_sticking: share,
            robust_points,
            excluded,
        }
    }
}

/// The model-form check of a map: at each point, the share of the combinations under
/// which the switch sticks.
#[derive(Debug, Clone, Serialize)]
pub struct MapModelForm {
    /// The mode the other combinations ran in.
    pub accuracy: &'static str,
    /// The combinations, the scene's own first.
    pub combinations: Vec<Laws>,
    /// Per map point (in the map's order): the share of the combinations that answered
    /// there under which it sticks (null where none answered).
    pub share_sticking: Vec<Option<f64>>,
    /// Points whose verdict every combination shares.
    pub robust_points: usize,
    /// Values and combinations left out, with the reason.
    pub excluded: Vec<Excluded>,
}
