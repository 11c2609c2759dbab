use contact_core::{
    AdhesionLaw, AsperityHistory, AsperityModel, Jumps, LawError, Path, PlasticState, PlasticityLaw,
};

/// One asperity: a plasticity law `P` and an adhesion law `A` composed as in the paper's
/// section 2.2. The adhesion law sees the deformed asperity as an elastic sphere of radius
/// R_eff(delta) (eq 12) at the effective interference delta - delta_res; lambda follows
/// from R_eff inside the adhesion law. Plastic deformation is uncoupled from adhesion.
///
/// The elastic comparison is the same type with [`crate::Elastic`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElastoPlasticAsperity<P, A> {
    pub plasticity: P,
    pub adhesion: A,
}

impl<P: PlasticityLaw, A: AdhesionLaw> ElastoPlasticAsperity<P, A> {
    /// Compose a plasticity law and an adhesion law.
    pub fn new(plasticity: P, adhesion: A) -> Self {
        Self {
            plasticity,
            adhesion,
        }
    }

    /// Radius R_eff (m) and effective interference (m) the adhesion law sees at `delta`
    /// after the history `delta_max`.
    pub fn effective(&self, delta: f64, delta_max: f64) -> (f64, f64, PlasticState) {
        let st = self.plasticity.state(delta_max);
        let r = self.plasticity.effective_radius(&st, delta);
        (r, delta - st.delta_res, st)
    }
}

impl<P: PlasticityLaw, A: AdhesionLaw> AsperityModel for ElastoPlasticAsperity<P, A> {
    fn force(&self, delta: f64, history: AsperityHistory, path: Path) -> Result<f64, LawError> {
        // Loading beyond the history yields again (delta_max = delta); retracting, the
        // excursion's extreme counts as history.
        let delta_max = match path {
            Path::Approach => history.delta_max.max(delta),
            Path::Retract { from } => history.delta_max.max(from),
        };
        let (r, delta_eff, st) = self.effective(delta, delta_max);
        let path = match path {
            Path::Approach => Path::Approach,
            Path::Retract { from } => Path::Retract {
                from: from - st.delta_res,
            },
        };
        self.adhesion.force(r, delta_eff, path)
    }

    fn yield_interference(&self) -> f64 {
        self.plasticity.critical_interference()
    }

    fn plastic_state(&self, history: AsperityHistory) -> PlasticState {
        self.plasticity.state(history.delta_max)
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
    /// shifted by delta_res. Each kind keeps its position at every height: a law that can
    /// yield lists delta_res first, NaN before yield (nothing bends there then).
    fn kinks(&self, history: AsperityHistory) -> Result<Vec<f64>, LawError> {
        let st = self.plasticity.state(history.delta_max);
        let mut k = Vec::new();
        if self.plasticity.critical_interference().is_finite() {
            k.push(if st.delta_res > 0.0 {
                st.delta_res
            } else {
                f64::NAN
            });
        }
        k.extend(
            self.adhesion
                .kinks(st.r_res)?
                .into_iter()
                .map(|x| x + st.delta_res),
        );
        Ok(k)
    }
}
