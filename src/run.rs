//! The computations behind each subcommand; results are plain serialisable data.

use crate::model::{self, BuildError};
use crate::scene::{Accuracy, AsperityScene, SceneError, SurfaceScene, SwitchScene};
use contact_core::{AsperityHistory, AsperityModel, Path, SurfaceLaw};
use maugis_kim::{MdCurve, MdPoint};
use serde::Serialize;
use switch_1d::{ImpactFilm, PressurePoint, Switch};

/// Why a run failed: bad input (exit status 2) or a numerical failure (exit status 1).
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error("invalid input: {0}")]
    Input(String),
    #[error("numerical failure: {0}")]
    Numeric(String),
}

impl RunError {
    /// The same error, prefixed with the scene it came from.
    pub fn in_scene(self, file: &str) -> Self {
        match self {
            RunError::Input(m) => RunError::Input(format!("{file}: {m}")),
            RunError::Numeric(m) => RunError::Numeric(format!("{file}: {m}")),
            e => e,
        }
    }

    /// Exit status: 2 for bad input, 1 for a numerical failure.
    pub fn exit_code(&self) -> i32 {
        match self {
            RunError::Scene(_) | RunError::Input(_) => 2,
            RunError::Numeric(_) => 1,
        }
    }
}

impl From<BuildError> for RunError {
    fn from(e: BuildError) -> Self {
        RunError::Input(e.0)
    }
}

fn numeric(e: impl std::fmt::Display) -> RunError {
    RunError::Numeric(e.to_string())
}

// ---------------------------------------------------------------- md

/// `stiction md`: the nondimensional Maugis-Kim curve.
#[derive(Debug, Clone, Serialize)]
pub struct MdReport {
    pub lambda: f64,
    pub jump_in_delta: f64,
    pub turning_delta: f64,
    pub turning_force: f64,
    pub pull_off_load_control: f64,
    pub pull_off_displacement_control: f64,
    pub curve: Vec<MdPoint>,
}

/// `stiction md --delta D`: one point.
#[derive(Debug, Clone, Serialize)]
pub struct MdPointReport {
    pub lambda: f64,
    pub delta: f64,
    pub path: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub from: Option<f64>,
    pub force: f64,
}

fn md_curve(lambda: f64) -> Result<MdCurve, RunError> {
    if !(lambda.is_finite() && (1e-6..=1e6).contains(&lambda)) {
        return Err(RunError::Input(format!(
            "invalid --lambda {lambda}: must be finite and in [1e-6, 1e6]"
        )));
    }
    MdCurve::new(lambda).map_err(|e| RunError::Input(e.to_string()))
}

pub fn md(lambda: f64, points: usize, delta_end: f64) -> Result<MdReport, RunError> {
    let c = md_curve(lambda)?;
    if !(4..=100_000).contains(&points) {
        return Err(RunError::Input(format!(
            "invalid --points {points}: must be in [4, 100000]"
        )));
    }
    if !(delta_end.is_finite() && delta_end > c.junction().delta && delta_end <= 1e6) {
        return Err(RunError::Input(format!(
            "invalid --delta-end {delta_end}: must be finite, above the junction Delta_j = {} and at most 1e6",
            c.junction().delta
        )));
    }
    let t = c.turning_point().map_err(numeric)?;
    Ok(MdReport {
        lambda,
        jump_in_delta: c.jump_in_delta(),
        turning_delta: t.delta,
        turning_force: t.force,
        pull_off_load_control: c.pull_off_load_control().map_err(numeric)?.force,
        pull_off_displacement_control: t.force,
        curve: c.curve(points, delta_end).map_err(numeric)?,
    })
}

pub fn md_point(lambda: f64, delta: f64, path: Path) -> Result<MdPointReport, RunError> {
    let c = md_curve(lambda)?;
    if !(delta.is_finite() && delta.abs() <= 1e6) {
        return Err(RunError::Input(format!(
            "invalid --delta {delta}: must be finite, |Delta| <= 1e6"
        )));
    }
    let (name, from) = match path {
        Path::Approach => ("approach", None),
        Path::Retract { from } => {
            if !(from.is_finite() && from.abs() <= 1e6) {
                return Err(RunError::Input(format!(
                    "invalid --from {from}: must be finite, |Delta| <= 1e6"
                )));
            }
            ("retract", Some(from))
        }
    };
    Ok(MdPointReport {
        lambda,
        delta,
        path: name.into(),
        from,
        force: c.force(delta, path).map_err(numeric)?,
    })
}

// ---------------------------------------------------------------- asperity

/// A point of a single-asperity curve: interference (m), force (N).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ForcePoint {
    pub delta: f64,
    pub force: f64,
}

/// One loading/unloading case of `stiction asperity`.
#[derive(Debug, Clone, Serialize)]
pub struct AsperityCase {
    pub delta_max: f64,
    pub delta_res: f64,
    pub r_res: f64,
    /// R_eff on loading at delta_max (eq 12 with x = 1).
    pub r_eff_loading: f64,
    /// Most tensile force on the unloading path (N).
    pub pull_off_force: f64,
    /// The same for the elastic asperity (no yield).
    pub elastic_pull_off_force: f64,
    /// delta_max beyond the fits' range (delta_max/delta_CP > 110).
    pub extrapolated: bool,
    pub loading: Vec<ForcePoint>,
    pub unloading: Vec<ForcePoint>,
}

/// `stiction asperity`.
#[derive(Debug, Clone, Serialize)]
pub struct AsperityReport {
    pub delta_cp: f64,
    pub lambda: f64,
    pub radius: f64,
    pub cases: Vec<AsperityCase>,
}

/// Most tensile force on the retraction from `delta_max`, scanned on `n` points
/// between delta_max and the jump-out and refined by golden section.
fn pull_off<M: AsperityModel>(
    m: &M,
    delta_max: f64,
    n: usize,
) -> Result<(f64, Vec<ForcePoint>), RunError> {
    let hist = AsperityHistory { delta_max };
    let j = m.jumps(hist).map_err(numeric)?;
    let lo = j.jump_out - 0.02 * (delta_max - j.jump_out);
    let path = Path::Retract { from: delta_max };
    let mut curve = Vec::with_capacity(n);
    for i in 0..n {
        let delta = delta_max - (delta_max - lo) * i as f64 / (n - 1) as f64;
        curve.push(ForcePoint {
            delta,
            force: m.force(delta, hist, path).map_err(numeric)?,
        });
    }
    // the search never scans coarser than 64 samples, whatever curve was asked for
    let samples: Vec<(f64, f64)> = if n >= 64 {
        curve.iter().map(|p| (p.delta, p.force)).collect()
    } else {
        (0..64)
            .map(|i| {
                let delta = delta_max - (delta_max - lo) * i as f64 / 63.0;
                m.force(delta, hist, path).map(|f| (delta, f))
            })
            .collect::<Result<_, _>>()
            .map_err(numeric)?
    };
    let (_, best) = contact_core::numeric::refine_sampled_min(
        &samples,
        |x| m.force(x, hist, path),
        1e-12 * delta_max,
    )
    .map_err(numeric)?;
    Ok((best, curve))
}

pub fn asperity(scene: &AsperityScene) -> Result<AsperityReport, RunError> {
    let plastic = model::asperity(&scene.contact, false)?;
    let elastic = model::asperity(&scene.contact, true)?;
    let pair = model::pair(&scene.contact)?;
    let lambda = maugis_kim::Scales::lambda(
        pair.k(),
        scene.contact.work_of_adhesion,
        scene.contact.z0,
        scene.contact.radius,
    );
    let n = scene.points;
    let mut cases = Vec::new();
    for &dmax in &scene.delta_max {
        let virgin = AsperityHistory::VIRGIN;
        let j0 = plastic.jumps(virgin).map_err(numeric)?;
        let start = j0.jump_in - 0.02 * (dmax - j0.jump_in);
        let mut loading = Vec::with_capacity(n);
        for i in 0..n {
            let delta = start + (dmax - start) * i as f64 / (n - 1) as f64;
            loading.push(ForcePoint {
                delta,
                force: plastic
                    .force(delta, virgin, Path::Approach)
                    .map_err(numeric)?,
            });
        }
        let (pull, unloading) = pull_off(&plastic, dmax, n)?;
        let (epull, _) = pull_off(&elastic, dmax, n)?;
        let st = plastic.plastic_state(AsperityHistory { delta_max: dmax });
        let (r_load, _, _) = plastic.effective(dmax, dmax);
        cases.push(AsperityCase {
            delta_max: dmax,
            delta_res: st.delta_res,
            r_res: st.r_res,
            r_eff_loading: r_load,
            pull_off_force: pull,
            elastic_pull_off_force: epull,
            extrapolated: st.extrapolated,
            loading,
            unloading,
        });
    }
    Ok(AsperityReport {
        delta_cp: plastic.yield_interference(),
        lambda,
        radius: scene.contact.radius,
        cases,
    })
}

// ---------------------------------------------------------------- surface

/// `stiction surface`.
#[derive(Debug, Clone, Serialize)]
pub struct SurfaceReport {
    pub sigma_s: f64,
    pub accuracy: Accuracy,
    pub loading: Vec<PressurePoint>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unload_from: Option<f64>,
    pub unloading: Vec<PressurePoint>,
    /// Magnitude of the most tensile unloading pressure (Pa); null without unloading.
    pub pull_out_pressure: Option<f64>,
    pub pull_out_separation: Option<f64>,
    /// Fraction of asperities loaded beyond the fits' range (delta_max/delta_CP > 110).
    pub extrapolated_fraction: f64,
}

pub fn surface(scene: &SurfaceScene) -> Result<SurfaceReport, RunError> {
    let gw = model::surface(&scene.contact, &scene.surface, scene.accuracy, false)?;
    let virgin = gw.virgin();
    let top = gw.reach(&virgin).map_err(numeric)?;
    let start = scene.d_start.or(scene.unload_from).unwrap_or(0.0);
    let n = scene.points;
    let mut loading = Vec::with_capacity(n);
    for i in 0..n {
        let d = start + (top - start) * i as f64 / (n - 1) as f64;
        loading.push(PressurePoint {
            d,
            pressure: gw.pressure(d, &virgin, Path::Approach).map_err(numeric)?,
        });
    }
    // the deepest separation the surface has seen: the loading curve's start, or the
    // unloading point if deeper
    let deepest = scene.unload_from.map_or(start, |u| u.min(start));
    let extrapolated_fraction =
        gw.fraction_beyond(&gw.load(&virgin, deepest), asperity_plastic::FIT_RANGE_MAX);
    let (unloading, pull, at) = match scene.unload_from {
        Some(d) => {
            let hist = gw.load(&virgin, d);
            let u = switch_1d::unload(&gw, &hist, d, n).map_err(numeric)?;
            (
                u.curve,
                Some(u.pull_out_pressure),
                Some(u.pull_out_separation),
            )
        }
        None => (Vec::new(), None, None),
    };
    Ok(SurfaceReport {
        sigma_s: scene.surface.sigma_s,
        accuracy: scene.accuracy,
        loading,
        unload_from: scene.unload_from,
        unloading,
        pull_out_pressure: pull,
        pull_out_separation: at,
        extrapolated_fraction,
    })
}

// ---------------------------------------------------------------- switch

/// One cycle of `stiction switch`.
#[derive(Debug, Clone, Serialize)]
pub struct CycleReport {
    pub cycle: usize,
    pub d_e: f64,
    pub pull_out_pressure: f64,
    pub pull_out_separation: f64,
    /// Pull-out pressure above the restoring pressure K_s d0.
    pub sticks: bool,
    pub unloading: Vec<PressurePoint>,
}

/// The elastic comparison.
#[derive(Debug, Clone, Serialize)]
pub struct ElasticReport {
    pub d_e: f64,
    pub pull_out_pressure: f64,
    pub pull_out_separation: f64,
    pub unloading: Vec<PressurePoint>,
}

/// `stiction switch`.
#[derive(Debug, Clone, Serialize)]
pub struct SwitchReport {
    pub k_s: f64,
    pub v_pull_in: f64,
    pub voltage: f64,
    pub impact_energy: f64,
    pub restoring_pressure: f64,
    pub accuracy: Accuracy,
    pub accommodation_tolerance: f64,
    pub loading: Vec<PressurePoint>,
    pub cycles: Vec<CycleReport>,
    pub elastic: Option<ElasticReport>,
    pub accommodated_after: Option<usize>,
    pub stiction: bool,
    /// Fraction of asperities loaded beyond the fits' range (delta_max/delta_CP > 110)
    /// after the last cycle.
    pub extrapolated_fraction: f64,
}

pub fn switch(scene: &SwitchScene) -> Result<SwitchReport, RunError> {
    let g = &scene.switch;
    let sw = Switch::new(g.d0, g.t_d, g.epsilon_r, g.epsilon_0)
        .map_err(|e| RunError::Input(e.to_string()))?;
    let (k_s, voltage, e_i) = match (g.impact_energy, g.k_s) {
        (Some(e), _) => {
            let k = sw
                .stiffness_for_impact_energy(e)
                .map_err(|e| RunError::Input(e.to_string()))?;
            (k, sw.pull_in_voltage(k), e)
        }
        (None, Some(k)) => {
            let u = g.voltage.unwrap_or_else(|| sw.pull_in_voltage(k));
            let e = sw.impact_energy(k, u);
            if e <= 0.0 {
                return Err(RunError::Input(format!(
                    "switch: k_s = {k:e} Pa/m at U = {u} V gives impact energy {e:e} J/m^2: the electrode does not reach contact with energy to spare"
                )));
            }
            (k, u, e)
        }
        (None, None) => return Err(RunError::Input("switch: give impact_energy or k_s".into())),
    };
    let film = ImpactFilm {
        thickness: g.film_thickness,
        youngs_modulus: scene.contact.youngs_modulus,
    };
    let restoring = sw.restoring_pressure(k_s);
    let gw = model::surface(&scene.contact, &scene.surface, scene.accuracy, false)?;
    let options = switch_1d::CycleOptions {
        cycles: scene.cycles,
        until_accommodated: scene.until_accommodated,
        accommodation_tolerance: scene.accommodation_tolerance,
        unloading_points: scene.points,
        loading_points: scene.points,
        energy_rule: model::energy_rule(scene.accuracy),
    };
    let run = switch_1d::run_cycles(&gw, gw.virgin(), e_i, film, options).map_err(numeric)?;
    let extrapolated_fraction = run.cycles.last().map_or(0.0, |c| {
        gw.fraction_beyond(&c.history, asperity_plastic::FIT_RANGE_MAX)
    });
    let elastic = if scene.elastic_comparison {
        let el = model::surface(&scene.contact, &scene.surface, scene.accuracy, true)?;
        let hist = el.virgin();
        let d_e = switch_1d::end_of_impact_with(
            &el,
            &hist,
            e_i,
            film,
            model::energy_rule(scene.accuracy),
        )
        .map_err(numeric)?;
        let u = switch_1d::unload(&el, &el.load(&hist, d_e), d_e, scene.points).map_err(numeric)?;
        Some(ElasticReport {
            d_e,
            pull_out_pressure: u.pull_out_pressure,
            pull_out_separation: u.pull_out_separation,
            unloading: u.curve,
        })
    } else {
        None
    };
    let cycles: Vec<CycleReport> = run
        .cycles
        .into_iter()
        .map(|c| CycleReport {
            cycle: c.cycle,
            d_e: c.d_e,
            pull_out_pressure: c.unloading.pull_out_pressure,
            pull_out_separation: c.unloading.pull_out_separation,
            sticks: c.unloading.pull_out_pressure > restoring,
            unloading: c.unloading.curve,
        })
        .collect();
    let stiction = cycles.iter().any(|c| c.sticks);
    Ok(SwitchReport {
        k_s,
        v_pull_in: sw.pull_in_voltage(k_s),
        voltage,
        impact_energy: e_i,
        restoring_pressure: restoring,
        accuracy: scene.accuracy,
        accommodation_tolerance: scene.accommodation_tolerance,
        loading: run.loading,
        cycles,
        elastic,
        accommodated_after: run.accommodated_after,
        stiction,
        extrapolated_fraction,
    })
}
