//! The accuracy modes: targets on the reported quantities, and the numerical settings
//! that meet them (measured over random scenes of the documented domains by
//! `cargo xtask accuracy` and `tests/accuracy_modes.rs`; figures in docs/performance.md).

use serde::{Deserialize, Serialize};

/// A speed/accuracy trade, named by its targets (see [`Targets`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum Accuracy {
    /// d_e within 1e-9 sigma_s, pull-out within 1e-8 (relative).
    #[default]
    Accurate,
    /// d_e within 1e-6 sigma_s, pull-out within 1e-6.
    Balanced,
    /// d_e within 1e-4 sigma_s, pull-out within 1e-4.
    Fast,
    /// Tighter than accurate (1e-11 sigma_s, 1e-10): the yardstick the other modes are
    /// measured against.
    Reference,
}

/// What a mode promises on the reported quantities, against a tighter computation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Targets {
    /// The mode.
    pub mode: Accuracy,
    /// d_e to this fraction of sigma_s.
    pub d_e_tolerance_sigma: f64,
    /// The pull-out pressure to this fraction of itself ...
    pub pull_out_tolerance: f64,
    /// ... or to this fraction of the restoring pressure K_s d0, whichever is larger.
    pub pull_out_floor_of_restoring: f64,
}

impl Accuracy {
    /// Every mode, fastest last.
    pub const ALL: [Accuracy; 4] = [
        Accuracy::Reference,
        Accuracy::Accurate,
        Accuracy::Balanced,
        Accuracy::Fast,
    ];

    /// The mode a scene names (`accurate`, `balanced`, `fast`, `reference`).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|a| a.as_str() == name)
    }

    /// The scene spelling.
    pub fn as_str(self) -> &'static str {
        match self {
            Accuracy::Accurate => "accurate",
            Accuracy::Balanced => "balanced",
            Accuracy::Fast => "fast",
            Accuracy::Reference => "reference",
        }
    }

    /// The mode's targets.
    pub fn targets(self) -> Targets {
        let (d_e, pull) = match self {
            Accuracy::Reference => (1e-11, 1e-10),
            Accuracy::Accurate => (1e-9, 1e-8),
            Accuracy::Balanced => (1e-6, 1e-6),
            Accuracy::Fast => (1e-4, 1e-4),
        };
        Targets {
            mode: self,
            d_e_tolerance_sigma: d_e,
            pull_out_tolerance: pull,
            pull_out_floor_of_restoring: 1e-9,
        }
    }

    /// Internal margin: the settings aim this much tighter than the targets, because the
    /// targets bound the *measured* error over the documented domains.
    const MARGIN: f64 = 0.1;

    /// The height quadrature of the rough surface (`abs_floor`: a pressure error in Pa
    /// that does not matter to the caller, 0 for none).
    pub fn quadrature(self, abs_floor: f64) -> gw_surface::Quadrature {
        let t = self.targets();
        gw_surface::Quadrature {
            // pressures to a tenth of the tighter of the two targets
            rel_tol: (Self::MARGIN * t.pull_out_tolerance.min(t.d_e_tolerance_sigma)).max(1e-13),
            abs_tol: Self::MARGIN * abs_floor,
            nodes: 6,
        }
    }

    /// The error an asperity's force may carry (relative to max(|F|, pi w R)) without
    /// showing in the height quadrature: a tenth of the quadrature's floor, which is a
    /// thousandth of its relative tolerance of the forces summed. Fast mode: 1e-9, where
    /// the tabulated Maugis-Kim force (`maugis_kim::INTERPOLATION_ERROR`) qualifies;
    /// balanced 1e-11 and tighter modes solve every force.
    pub fn force_tolerance(self) -> f64 {
        1e-4 * self.quadrature(0.0).rel_tol
    }

    /// The targets of the switch computations (d_e, pull-out); the pressure floor that
    /// does not matter to a switch goes to the surface's quadrature ([`Self::quadrature`]).
    pub fn precision(self) -> switch_1d::Precision {
        let t = self.targets();
        switch_1d::Precision {
            d_e: Self::MARGIN * t.d_e_tolerance_sigma,
            pull_out: Self::MARGIN * t.pull_out_tolerance,
        }
    }
}

impl std::fmt::Display for Accuracy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::Accuracy;
    use contact_core::{AdhesionLaw, Path};
    use maugis_kim::{DugdaleParams, MaugisKim, INTERPOLATION_ERROR};

    /// Fast mode's force tolerance admits the tabulated Maugis-Kim force and no tighter
    /// mode's does; the law offers its table exactly when asked within its bound, and the
    /// offered law agrees with the solve to that bound (SI, a sphere of the paper's size
    /// over interferences from adhesive to deep).
    #[test]
    fn only_fast_mode_reads_the_tabulated_maugis_kim_force() {
        assert!(Accuracy::Fast.force_tolerance() >= INTERPOLATION_ERROR);
        for m in [Accuracy::Balanced, Accuracy::Accurate, Accuracy::Reference] {
            assert!(m.force_tolerance() < INTERPOLATION_ERROR, "{m}");
        }
        let w = 1.0;
        let law = MaugisKim::new(DugdaleParams {
            k: 2.7e11,
            work_of_adhesion: w,
            z0: 0.169e-9,
        })
        .unwrap();
        assert!(law.within(Accuracy::Balanced.force_tolerance()).is_none());
        let table = law
            .within(Accuracy::Fast.force_tolerance())
            .expect("fast mode gets the table");
        let r = 1e-6;
        let scale = std::f64::consts::PI * w * r;
        let mut read = 0;
        for k in 0..400 {
            let delta = -0.3e-9 + 8e-9 * k as f64 / 399.0;
            for path in [Path::Approach, Path::Retract { from: 8e-9 }] {
                let exact = law.force(r, delta, path).unwrap();
                let got = table.force(r, delta, path).unwrap();
                let err = (got - exact).abs() / exact.abs().max(scale);
                assert!(err <= INTERPOLATION_ERROR, "delta {delta:e}: {err:e}");
                read += usize::from(got != exact);
            }
        }
        // most of these points are read from the table, not solved
        assert!(read > 400, "{read} of 800 points differ from the solve");
    }
}
