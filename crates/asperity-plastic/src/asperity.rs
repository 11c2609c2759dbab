use contact_core::numeric::{geomspace, grid_min, linspace, Tolerance};
use contact_core::{
    AdhesionLaw, AsperityHistory, AsperityModel, Jumps, LawError, Path, PlasticState, PlasticityLaw,
};

/// One asperity: a plasticity law `P` and an adhesion law `A` composed as in the paper's
/// section 2.2. The adhesion law sees the deformed asperity as an elastic sphere of radius
/// R_eff(delta) (eq 12) at the effective interference delta - delta_res; lambda follows
/// from R_eff inside the adhesion law. Plastic deformation is uncoupled from adhesion.
///
/// The elastic comparison is the same type with [`crate::Elastic`].
///
/// ```
/// use asperity_plastic::{ElastoPlasticAsperity, EtsionKadin, YieldModulus};
/// use contact_core::{paper, AsperityModel, AsperityHistory, Material, Pair, Path};
/// use maugis_kim::{DugdaleParams, MaugisKim};
/// let pair = Pair::new(Material::new(paper::RU)?, None, paper::RADIUS)?;
/// let asperity = ElastoPlasticAsperity::new(
///     EtsionKadin::new(&pair, YieldModulus::AsPrinted)?,
///     MaugisKim::new(DugdaleParams::for_pair(&pair, paper::WORK_OF_ADHESION, paper::Z0))?,
/// );
/// // loaded to 17 nm (paper Fig 2) and retracted: the flattened tip pulls harder
/// let pull = asperity.pull_off(17e-9)?;
/// assert!(pull.force < -50e-6 && pull.delta < 17e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElastoPlasticAsperity<P, A> {
    /// The plasticity law.
    pub plasticity: P,
    /// The adhesion law.
    pub adhesion: A,
    /// How an asperity below its deepest interference reloads and unloads.
    pub reload: Reload,
}

/// How a yielded asperity's force below its deepest interference is read (the reload and
/// unload of an elastic-plastic contact, `docs/theory.md` section 2.5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[non_exhaustive]
pub enum Reload {
    /// The adhesion law on the effective sphere of the plasticity law, as the paper prints
    /// it: with eq 12 an asperity pressed beyond about 16 delta_CP reloads (and unloads)
    /// stiffer than it loaded.
    #[default]
    AsPrinted,
    /// The same, but a compressive force below the deepest interference never exceeds
    /// the virgin loading force at that interference, F(delta) <= F_L(delta) where
    /// F_L(delta) > 0: an elastic unload-reload curve of a dissipative material lies below
    /// its loading curve. Removes the eq-12 overshoot and the near-yield artefact
    /// (theory 2.5, 2.6); leaves the adhesive (tensile) part untouched.
    Bounded,
}

impl Reload {
    /// The scene spelling: `as_printed` or `bounded`.
    pub fn as_str(self) -> &'static str {
        match self {
            Reload::AsPrinted => "as_printed",
            Reload::Bounded => "bounded",
        }
    }
}

/// The elastic sphere the adhesion law sees at one interference.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct EffectiveSphere {
    /// R_eff (m), eq 12.
    pub radius: f64,
    /// delta - delta_res (m).
    pub interference: f64,
    /// The plastic state behind it.
    pub state: PlasticState,
}

/// The most tensile force on a retraction, and where it occurs.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct PullOff {
    /// Interference (m).
    pub delta: f64,
    /// Force (N, negative when adhesive).
    pub force: f64,
}

/// Relative bracket tolerance of the pull-off refinement: the force at a smooth minimum
/// is then exact to rounding (quadratic in the location error).
pub const PULL_OFF_TOLERANCE: Tolerance = Tolerance::relative(1e-10);

impl<P: PlasticityLaw, A: AdhesionLaw> ElastoPlasticAsperity<P, A> {
    /// Compose a plasticity law and an adhesion law (reload as printed).
    pub fn new(plasticity: P, adhesion: A) -> Self {
        Self {
            plasticity,
            adhesion,
            reload: Reload::AsPrinted,
        }
    }

    /// The same asperity with another reload rule.
    pub fn with_reload(self, reload: Reload) -> Self {
        Self { reload, ..self }
    }

    /// The force on the virgin loading curve at `delta` (m): the asperity loaded to
    /// `delta` from its virgin state, on approach (eqs 4-5, 12 at x = 1).
    pub fn loading_force(&self, delta: f64) -> Result<f64, LawError> {
        let e = self.effective(delta, delta.max(0.0));
        self.adhesion
            .force(e.radius, e.interference, Path::Approach)
    }

    /// The sphere the adhesion law sees at `delta` after the history `delta_max`.
    pub fn effective(&self, delta: f64, delta_max: f64) -> EffectiveSphere {
        let state = self.plasticity.state(delta_max);
        EffectiveSphere {
            radius: self.plasticity.effective_radius(&state, delta),
            interference: delta - state.delta_res,
            state,
        }
    }

    /// Pull-off after loading to `delta_max` (m): the most tensile force on the retraction
    /// from `delta_max` down to the jump-out. The search samples the retraction on a grid
    /// that follows the asperity's own length scales (geometric from both ends, from a
    /// millionth of the range, so a well near the jump-out or just below `delta_max`
    /// cannot fall between samples, plus 64 even steps), then refines the best local
    /// minima ([`contact_core::numeric::grid_min`]).
    pub fn pull_off(&self, delta_max: f64) -> Result<PullOff, LawError> {
        let hist = AsperityHistory { delta_max };
        let j = self.jumps(hist)?;
        let path = Path::Retract { from: delta_max };
        let (lo, hi) = (j.jump_out, delta_max);
        if !(hi > lo) {
            return Ok(PullOff {
                delta: hi,
                force: self.force(hi, hist, path)?,
            });
        }
        let range = hi - lo;
        // never exactly at the jump-out, where the force is zero just below
        let lo_in = lo + 1e-12 * range;
        let mut grid: Vec<f64> = linspace(lo_in, hi, 65).collect();
        grid.extend(geomspace(1e-6 * range, 0.5 * range, 40).map(|x| lo_in + x));
        grid.extend(geomspace(1e-6 * range, 0.5 * range, 40).map(|x| hi - x));
        grid.sort_by(f64::total_cmp);
        grid.dedup();
        let m = grid_min(
            "asperity pull-off",
            |x| self.force(x, hist, path),
            &grid,
            PULL_OFF_TOLERANCE,
        )?;
        Ok(PullOff {
            delta: m.x,
            force: m.value,
        })
    }
}

impl<P: PlasticityLaw, A: AdhesionLaw> ElastoPlasticAsperity<P, A> {
    /// The effective sphere the adhesion law sees at `delta` with `history` on `path`, the
    /// delta_max it was made by and the path on it: loading beyond the history yields again
    /// (delta_max = delta); retracting, the excursion's extreme counts as history, and the
    /// excursion starts at its extreme less the residual interference.
    fn sphere(
        &self,
        delta: f64,
        history: AsperityHistory,
        path: Path,
    ) -> (EffectiveSphere, f64, Path) {
        let delta_max = match path {
            Path::Approach => history.delta_max.max(delta),
            Path::Retract { from } => history.delta_max.max(from),
        };
        let e = self.effective(delta, delta_max);
        let path = match path {
            Path::Approach => Path::Approach,
            Path::Retract { from } => Path::Retract {
                from: from - e.state.delta_res,
            },
        };
        if self.plasticity.couples_adhesion() {
            return (e, delta_max, self.coupled_path(delta, history, path, &e));
        }
        (e, delta_max, path)
    }

    /// The path the adhesion law sees under a law whose plastic state the adhesive contact
    /// drives (theory 2.8). Such a law can leave the residual height above the interference
    /// that made it (delta_res > delta_max: adhesion pulled the flattened tip into contact),
    /// so the effective interference of a contact can be negative. An asperity that is in
    /// adhesive contact (loaded beyond its virgin jump-in, and either loading now or
    /// retracting from that loading) is on the adhesion law's contact branch: the path says
    /// so by an excursion that reached at least the effective sphere's jump-in. A
    /// re-approach below the history jumps in on the deformed sphere, as with any law.
    fn coupled_path(
        &self,
        delta: f64,
        history: AsperityHistory,
        path: Path,
        e: &EffectiveSphere,
    ) -> Path {
        let virgin_jump_in = match self.adhesion.jump_in(self.plasticity.radius()) {
            Ok(j) => j,
            Err(_) => return path,
        };
        let touching = |reach: f64| {
            let jump_in = self.adhesion.jump_in(e.radius).unwrap_or(f64::INFINITY);
            Path::Retract {
                from: reach.max(crate::coupled::contact_reach(jump_in)),
            }
        };
        match path {
            Path::Approach if delta >= history.delta_max && delta > virgin_jump_in => {
                touching(e.interference)
            }
            Path::Retract { from }
                if history.delta_max.max(from + e.state.delta_res) > virgin_jump_in =>
            {
                touching(from)
            }
            p => p,
        }
    }
}

impl<P: PlasticityLaw, A: AdhesionLaw> AsperityModel for ElastoPlasticAsperity<P, A> {
    fn force(&self, delta: f64, history: AsperityHistory, path: Path) -> Result<f64, LawError> {
        let (e, delta_max, sphere_path) = self.sphere(delta, history, path);
        let f = self.adhesion.force(e.radius, e.interference, sphere_path)?;
        if self.reload == Reload::Bounded && f > 0.0 && delta < delta_max {
            let virgin = self.loading_force(delta)?;
            if virgin > 0.0 && f > virgin {
                return Ok(virgin);
            }
        }
        Ok(f)
    }

    /// The adhesion law's contact radius on the effective sphere, R_eff at delta - delta_res
    /// (the same sphere the force comes from; under the bounded reload the force is capped
    /// but the geometry is the effective sphere's).
    fn contact_radius(
        &self,
        delta: f64,
        history: AsperityHistory,
        path: Path,
    ) -> Result<f64, LawError> {
        let (e, _, sphere_path) = self.sphere(delta, history, path);
        self.adhesion
            .contact_radius(e.radius, e.interference, sphere_path)
    }

    fn delta_cp(&self) -> f64 {
        self.plasticity.delta_cp()
    }

    /// The adhesion law's bound on the largest effective sphere the state presents
    /// ([`PlasticityLaw::radius_bound`]); the bounded reload only caps compression.
    fn max_tension(&self, history: AsperityHistory) -> Option<f64> {
        let state = self.plasticity.state(history.delta_max);
        self.adhesion
            .max_tension(self.plasticity.radius_bound(&state)?)
    }

    fn radius(&self) -> f64 {
        self.plasticity.radius()
    }

    fn plastic_state(&self, history: AsperityHistory) -> PlasticState {
        self.plasticity.state(history.delta_max)
    }

    /// delta_CP, then the plasticity law's declared breaks.
    fn plastic_breaks(&self) -> Vec<f64> {
        let dcp = self.plasticity.delta_cp();
        if !dcp.is_finite() {
            return Vec::new();
        }
        if self.plasticity.couples_adhesion() {
            // the state jumps or bends at the law's own breaks (the jump-in, the geometric
            // yield onset), below delta_CP
            let mut b: Vec<f64> = self
                .plasticity
                .breaks()
                .into_iter()
                .filter(|x| x.is_finite())
                .collect();
            b.sort_by(f64::total_cmp);
            b.dedup();
            return b;
        }
        let mut b = vec![dcp];
        b.extend(
            self.plasticity
                .breaks()
                .into_iter()
                .filter(|x| x.is_finite() && *x > dcp),
        );
        b
    }

    fn fit_range(&self) -> Option<(f64, f64)> {
        self.plasticity.fit_range()
    }

    fn fit_interference(&self, omega: f64) -> f64 {
        self.plasticity.fit_interference(omega)
    }

    fn yielding_body(&self) -> Option<contact_core::YieldingBody> {
        self.plasticity.yielding_body()
    }

    /// Jumps happen out of contact (delta <= delta_res), where R_eff = R_res.
    fn jumps(&self, history: AsperityHistory) -> Result<Jumps, LawError> {
        let st = self.plasticity.state(history.delta_max);
        let j = self.adhesion.jumps(st.r_res)?;
        Ok(Jumps {
            jump_in: j.jump_in + st.delta_res,
            jump_out: j.jump_out + st.delta_res,
        })
    }

    fn jump_in(&self, history: AsperityHistory) -> Result<f64, LawError> {
        let st = self.plasticity.state(history.delta_max);
        Ok(self.adhesion.jump_in(st.r_res)? + st.delta_res)
    }

    /// delta_res where R_eff switches from R_res to eq 12, then the adhesion law's kinks
    /// shifted by delta_res; under the bounded reload also the plastic breaks below
    /// delta_max, where the cap (the virgin loading force) bends or jumps. Each kind keeps
    /// its position at every height: a law that can yield lists delta_res first, `None`
    /// before yield (nothing bends there then).
    fn kinks(&self, history: AsperityHistory) -> Result<Vec<Option<f64>>, LawError> {
        let st = self.plasticity.state(history.delta_max);
        let mut k = Vec::with_capacity(4);
        if self.plasticity.delta_cp().is_finite() {
            k.push((st.delta_res > 0.0).then_some(st.delta_res));
        }
        k.extend(self.plasticity.kinks(&st));
        k.extend(
            self.adhesion
                .kinks(st.r_res)?
                .into_iter()
                .map(|x| x.map(|x| x + st.delta_res)),
        );
        if self.reload == Reload::Bounded {
            k.extend(
                self.plastic_breaks()
                    .into_iter()
                    .map(|b| cap_kink(b, st.delta_max)),
            );
        }
        Ok(k)
    }

    /// One entry of [`Self::kinks`] without building the list: delta_res needs only the
    /// plastic state (the breakpoint search evaluates each kind about 14 times per
    /// pressure), and the adhesion law is asked only for its own kinds.
    fn kink(&self, i: usize, history: AsperityHistory) -> Result<Option<f64>, LawError> {
        let st = self.plasticity.state(history.delta_max);
        let mut i = i;
        if self.plasticity.delta_cp().is_finite() {
            if i == 0 {
                return Ok((st.delta_res > 0.0).then_some(st.delta_res));
            }
            i -= 1;
        }
        let plastic = self.plasticity.kinks(&st);
        if let Some(k) = plastic.get(i) {
            return Ok(*k);
        }
        i -= plastic.len();
        let adhesion = self.adhesion.kinks(st.r_res)?;
        if let Some(k) = adhesion.get(i) {
            return Ok(k.map(|x| x + st.delta_res));
        }
        if self.reload != Reload::Bounded {
            return Ok(None);
        }
        i -= adhesion.len();
        Ok(self
            .plastic_breaks()
            .get(i)
            .and_then(|&b| cap_kink(b, st.delta_max)))
    }
}

/// Under the bounded reload, the interference `b` (m) of a plastic break where the cap of
/// a reload below `delta_max` bends or jumps: the virgin loading force it caps with does
/// (delta_CP, and a piecewise law's regime boundaries, such as Kogut-Etsion's jump at
/// omega = 6). Absent where the reload does not reach it.
fn cap_kink(b: f64, delta_max: f64) -> Option<f64> {
    (b < delta_max).then_some(b)
}
