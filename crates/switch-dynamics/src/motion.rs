//! The plate's equation of motion, its flight, impacts, bounces and capture.

use crate::ode::{self, End, Threshold};
use crate::table::PressureTable;
use crate::{DynamicsError, SqueezeFilm};
use contact_core::{LawError, Path, SurfaceLaw};
use switch_1d::Switch;

/// The movable electrode as a rigid plate per unit area:
///
/// ```text
///   m'' y'' = eps0 U^2 / (2 (x + t_d/eps_r)^2) - K_s y - c''(x) y' - phi p(d),
///   x = d0 - y,   d = x - h
/// ```
///
/// y (m) the displacement from the open position toward the substrate, x the air gap, h
/// the dimple height (`Switch::dimple_height`), d the contact's separation, p the surface
/// law's pressure on the contact (per contact area, phi of the electrode), c'' the
/// squeeze-film coefficient (none in vacuum).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plate {
    /// The switch's geometry (d0, t_d, eps_r, eps0, the dimple height).
    pub switch: Switch,
    /// Spring constant per unit electrode area K_s (Pa/m).
    pub k_s: f64,
    /// Actuation voltage U (V), applied as a step at t = 0 with the plate at rest.
    pub voltage: f64,
    /// Mass per unit electrode area m'' (kg/m^2).
    pub areal_mass: f64,
    /// Fraction phi of the electrode that touches (dimples, bumps), in (0, 1].
    pub contact_area_fraction: f64,
    /// The gas film under the plate; None in vacuum.
    pub squeeze: Option<SqueezeFilm>,
}

impl Plate {
    /// Checks the plate's numbers.
    pub fn validated(self) -> Result<Self, DynamicsError> {
        for (field, v) in [
            ("k_s", self.k_s),
            ("areal_mass", self.areal_mass),
            ("voltage", self.voltage),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(DynamicsError::Invalid {
                    field,
                    value: v,
                    allowed: "finite and > 0",
                });
            }
        }
        let phi = self.contact_area_fraction;
        if !(phi.is_finite() && phi > 0.0 && phi <= 1.0) {
            return Err(DynamicsError::Invalid {
                field: "contact_area_fraction",
                value: phi,
                allowed: "in (0, 1]",
            });
        }
        if self.squeeze.is_some() && self.switch.dimple_height() <= 0.0 {
            return Err(DynamicsError::Invalid {
                field: "dimple_height",
                value: self.switch.dimple_height(),
                allowed: "> 0 under a gas film: a flat plate landing on the dielectric squeezes the gas out through a gap that closes as x^-3 (x^-1.84 with rarefaction), so under this model it never closes in finite time",
            });
        }
        Ok(self)
    }

    /// The travel s = d0 - h (m): the displacement at which the contact touches (d = 0).
    pub fn travel(&self) -> f64 {
        self.switch.travel()
    }

    /// The electrostatic pressure (Pa per electrode area) at air gap `x` (m).
    pub fn electrostatic(&self, x: f64) -> f64 {
        let g = self.switch.geometry();
        let gap = x + g.t_d / g.epsilon_r;
        0.5 * g.epsilon_0 * self.voltage * self.voltage / (gap * gap)
    }

    /// Whether the plate at air gap `x`, moving at `v`, is at rest to `within` (m): the
    /// distance it can still travel, (|F| + c''(x) |v|)/kappa + |v| sqrt(m''/kappa) (the
    /// creep the static force F and the film's drag leave, and where its kinetic energy
    /// would carry it against the restoring stiffness kappa), is below it. Never at rest
    /// where kappa <= 0 (no stable equilibrium).
    pub(crate) fn at_rest(&self, x: f64, v: f64, force: f64, kappa: f64, within: f64) -> bool {
        if !(kappa > 0.0) {
            return false;
        }
        let creep = (force.abs() + self.damping(x) * v.abs()) / kappa;
        let coast = v.abs() * (self.areal_mass / kappa).sqrt();
        creep + coast <= within
    }

    /// d(p_es)/dx (Pa/m, negative): the electrostatic pressure's slope in the air gap.
    pub(crate) fn electrostatic_slope(&self, x: f64) -> f64 {
        let g = self.switch.geometry();
        let gap = x + g.t_d / g.epsilon_r;
        -g.epsilon_0 * self.voltage * self.voltage / (gap * gap * gap)
    }

    /// The electrostatic work per electrode area (J/m^2) from the open position to air gap `x`.
    pub fn electrostatic_work(&self, x: f64) -> f64 {
        let g = self.switch.geometry();
        let e = g.t_d / g.epsilon_r;
        0.5 * g.epsilon_0 * self.voltage * self.voltage * (1.0 / (x + e) - 1.0 / (g.d0 + e))
    }

    /// The squeeze-film coefficient c'' (Pa s/m per electrode area) at air gap `x` (m); 0 in
    /// vacuum.
    pub fn damping(&self, x: f64) -> f64 {
        self.squeeze.map_or(0.0, |f| f.coefficient(x))
    }

    /// c'' at contact, x = h (Pa s/m per electrode area); 0 in vacuum.
    pub fn squeeze_coefficient_at_contact(&self) -> f64 {
        self.damping(self.switch.dimple_height())
    }

    /// The natural time 1/omega_0 = sqrt(m''/K_s) (s).
    pub fn natural_time(&self) -> f64 {
        (self.areal_mass / self.k_s).sqrt()
    }

    /// The net force per electrode area out of contact (Pa) at displacement `y` and velocity `v`.
    fn free_force(&self, y: f64, v: f64) -> f64 {
        let x = self.switch.d0() - y;
        self.electrostatic(x) - self.k_s * y - self.damping(x) * v
    }
}

/// How closely the motion is integrated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicsOptions {
    /// Relative (and absolute, on the scaled state) tolerance of the integration.
    pub tolerance: f64,
    /// Bounces allowed before the run is refused.
    pub max_bounces: usize,
    /// Keep every accepted step of the motion (for the displacement and pressure plots).
    pub trace: bool,
}

impl DynamicsOptions {
    /// The tolerance for an end of impact to `d_e_fraction` of the roughness scale (an
    /// accuracy mode's target): a hundredth of it, between 1e-12 and 1e-7.
    pub fn for_target(d_e_fraction: f64) -> Self {
        Self {
            tolerance: (1e-2 * d_e_fraction).clamp(1e-12, 1e-7),
            max_bounces: 50,
            trace: false,
        }
    }
}

/// The state where a contact phase begins.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ImpactState {
    /// The contact's separation d there (m): the surface's reach on approach, above which
    /// its pressure is zero to the law's tail bound.
    pub separation: f64,
    /// The plate's speed toward the substrate (m/s).
    pub velocity: f64,
    /// Its kinetic energy m'' v^2 / 2 (J/m^2 per electrode area).
    pub energy: f64,
    /// The time since the voltage step (first impact) or since the last separation (a
    /// bounce's re-impact) (s).
    pub flight_time: f64,
}

/// One impact after a bounce.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Bounce {
    /// The re-impact.
    pub impact: ImpactState,
    /// The deepest separation of that impact (m).
    pub d_e: f64,
    /// Time of the re-impact since the voltage step (s).
    pub time: f64,
}

/// Where the energy of a closure went (J/m^2 per electrode area), from the voltage step to
/// the capture.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct EnergyLedger {
    /// The electrostatic work done on the plate.
    pub work_in: f64,
    /// Stored in the spring, K_s y^2 / 2.
    pub spring: f64,
    /// The plate's kinetic energy at the end.
    pub kinetic: f64,
    /// Dissipated by the squeeze film, the integral of c'' v^2 dt.
    pub gas: f64,
    /// The net work done on the contact, the integral of phi p v dt: dissipated by
    /// plasticity and adhesion hysteresis, plus `stored`.
    pub contact: f64,
    /// Of it, the elastic energy the contact would give back, unloading from the end to
    /// its reach on the retraction path.
    pub stored: f64,
    /// Of it, dissipated: `contact - stored`.
    pub dissipated: f64,
    /// (work_in - spring - kinetic - gas - contact) / work_in: the integration's error.
    pub residual: f64,
}

/// A point of the motion.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct TracePoint {
    /// Time since the voltage step (s).
    pub t: f64,
    /// Displacement y (m).
    pub displacement: f64,
    /// Speed toward the substrate (m/s).
    pub velocity: f64,
    /// The contact's pressure (Pa per contact area; 0 in flight).
    pub contact_pressure: f64,
}

/// A closure of the switch in time: flight, impact, bounces, capture.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Closure<H> {
    /// The first impact.
    pub impact: ImpactState,
    /// The first impact's deepest separation (m).
    pub d_e: f64,
    /// The deepest separation of all impacts (m).
    pub deepest: f64,
    /// The estimated error of `deepest` (m): the integration's tolerance on the roughness
    /// scale, plus the error of the work the contact did on the way in (the pressure
    /// evaluations' own estimates and the table's misses, integrated from the deepest
    /// separation to the reach, and the closure's energy residual) over the pressure there.
    pub deepest_error: f64,
    /// The impacts after bounces.
    pub bounces: Vec<Bounce>,
    /// The surface's history after every impact.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub history: H,
    /// The time of the capture (s): the first turning point in contact after which the plate
    /// no longer separates.
    pub capture_time: f64,
    /// The separation at the capture (m).
    pub capture_separation: f64,
    /// The energy ledger up to the capture.
    pub ledger: EnergyLedger,
    /// The motion, if asked for.
    pub trace: Vec<TracePoint>,
}

const FLIGHT_LIMIT: f64 = 1e3; // natural times

/// The scales of a contact phase: the travel s, m'', phi, the roughness scale sigma, the
/// speed V, the time tau = sigma/V and the energy m'' V^2.
#[derive(Debug, Clone, Copy)]
struct Scales {
    s: f64,
    m: f64,
    phi: f64,
    sigma: f64,
    vel: f64,
    tau: f64,
    ec: f64,
}

/// The contact phase's right-hand side on the state [d/sigma, v/V, gas, contact work]
/// (energies over m'' V^2) with the tabulated pressure of the phase's path.
fn contact_rhs<'a, S: SurfaceLaw>(
    table: &'a PressureTable<'a, S>,
    plate: &'a Plate,
    k: Scales,
) -> impl Fn(f64, &[f64], &mut [f64]) -> Result<(), DynamicsError> + 'a {
    move |_t: f64, z: &[f64], dz: &mut [f64]| {
        let d = z[0] * k.sigma;
        let vv = z[1] * k.vel;
        let yy = k.s - d;
        let x = plate.switch.d0() - yy;
        let p = table.pressure(d)?;
        let force = plate.free_force(yy, vv) - k.phi * p;
        dz[0] = -z[1];
        dz[1] = force * k.tau / (k.m * k.vel);
        dz[2] = plate.damping(x) * vv * vv * k.tau / k.ec;
        dz[3] = k.phi * p * vv * k.tau / k.ec;
        Ok(())
    }
}

/// Whether the plate in a contact phase (scaled state `z`, pressure from `table`) is at
/// rest to the integration's tolerance on the roughness scale: the static force
/// p_es - K_s y - phi p against the stiffness K_s - |dp_es/dx| + phi |dp/dd|.
fn settled_in_contact<S: SurfaceLaw>(
    table: &PressureTable<S>,
    plate: &Plate,
    k: Scales,
    z: &[f64],
    tol: f64,
) -> bool {
    let d = z[0] * k.sigma;
    let vv = z[1] * k.vel;
    let yy = k.s - d;
    let x = plate.switch.d0() - yy;
    let step = 1e-3 * k.sigma;
    let (Ok(p), Ok(p_above)) = (table.pressure(d), table.pressure(d + step)) else {
        return false;
    };
    let force = plate.electrostatic(x) - plate.k_s * yy - k.phi * p;
    let kappa = plate.k_s + plate.electrostatic_slope(x) + k.phi * ((p_above - p) / step).abs();
    plate.at_rest(x, vv, force, kappa, tol * k.sigma)
}

/// Closes the switch from rest at the open position: the flight under the voltage step, the
/// first impact on `surface` with `history`, each bounce (separation on the retraction,
/// flight, re-impact on the reloading path with the history every earlier impact left), up
/// to the capture. Each phase is integrated with diffsol's tsit45 in its own scales (flight:
/// the travel and the natural time; contact: the roughness scale and the impact speed) and
/// ends at an event: the contact's reach on approach, the turning point at the deepest
/// separation (the history is loaded there), the reach on the retraction (a bounce) or a
/// turning point in contact (the capture).
pub fn close<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    plate: &Plate,
    options: &DynamicsOptions,
) -> Result<Closure<S::History>, DynamicsError> {
    close_with(surface, history, plate, options, &mut None)
}

/// [`close`] with the approach table of an earlier closure: the last impact of a closure
/// leaves the history the next closure's first impact approaches (a bounce's re-impact
/// approaches the same history), so the table of the surface's pressure on that approach
/// carries over from cycle to cycle while the history is unchanged.
pub(crate) fn close_with<'a, S: SurfaceLaw>(
    surface: &'a S,
    history: &S::History,
    plate: &Plate,
    options: &DynamicsOptions,
    approach_table: &mut Option<PressureTable<'a, S>>,
) -> Result<Closure<S::History>, DynamicsError> {
    let plate = plate.validated()?;
    let s = plate.travel();
    let m = plate.areal_mass;
    let phi = plate.contact_area_fraction;
    let t0 = plate.natural_time();
    let e0 = plate.k_s * s * s;
    let tol = options.tolerance;
    // a phase's time limit: a thousand natural times, or damping times c''(h)/K_s where the
    // gas film overdamps the plate
    let limit_t0 = FLIGHT_LIMIT * (plate.squeeze_coefficient_at_contact() * t0 / m).max(1.0);
    let mut hist = history.clone();
    let mut trace = Vec::new();
    let mut time = 0.0;
    // state in SI between phases: displacement, velocity, gas and contact energies
    let (mut y, mut v, mut gas, mut contact) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    // each impact: its state, deepest separation, time, and that separation's error (m)
    let mut impacts: Vec<(ImpactState, f64, f64, f64)> = Vec::new();
    // the contact pressure, tabulated in panels of two roughness scales to the
    // integration's tolerance of the larger of the panel's pressure and the electrostatic
    // pressure at contact (per contact area); the approach table serves every re-impact on
    // the same history
    let floor = plate.electrostatic(plate.switch.dimple_height()) / phi;
    let mut flight_start = 0.0;
    loop {
        // -- flight: scaled q = y/s, w = v t0/s, energies / (K_s s^2)
        let reach = surface.reach(&hist, Path::Approach)?;
        let q_contact = (s - reach) / s;
        let rhs = |_t: f64, z: &[f64], dz: &mut [f64]| -> Result<(), DynamicsError> {
            let (yy, vv) = (z[0] * s, z[1] * s / t0);
            let x = plate.switch.d0() - yy;
            dz[0] = z[1];
            dz[1] = plate.free_force(yy, vv) / (plate.k_s * s);
            dz[2] = plate.damping(x) * vv * vv * t0 / e0;
            dz[3] = 0.0;
            Ok(())
        };
        let z0 = [y / s, v * t0 / s, gas / e0, contact / e0];
        let mut thresholds = vec![Threshold {
            component: 0,
            level: q_contact,
            rising: true,
        }];
        if impacts.is_empty() {
            // from rest: a plate that turns back before touching does not close
            thresholds.push(Threshold {
                component: 1,
                level: 0.0,
                rising: false,
            });
        }
        let mut on_step = |st: &ode::Step| {
            if options.trace {
                trace.push(TracePoint {
                    t: time + st.0 * t0,
                    displacement: st.1[0] * s,
                    velocity: st.1[1] * s / t0,
                    contact_pressure: 0.0,
                })
            }
        };
        // an overdamped plate creeping into an equilibrium short of the contact has come to
        // rest there (the film would take it there in infinite time)
        let settled = |z: &[f64]| {
            let (yy, vv) = (z[0] * s, z[1] * s / t0);
            let x = plate.switch.d0() - yy;
            let force = plate.electrostatic(x) - plate.k_s * yy;
            let kappa = plate.k_s + plate.electrostatic_slope(x);
            plate.at_rest(x, vv, force, kappa, tol * s)
        };
        let poll = || surface.check_cancelled();
        let end = ode::run(
            "flight",
            rhs,
            &thresholds,
            &z0,
            limit_t0,
            tol,
            &mut on_step,
            &settled,
            &poll,
        )?;
        let (t, z) = match end {
            End::Crossed { t, y, which: 0 } => (t, y),
            End::Crossed { t, y: z, .. } | End::Settled { t, y: z } => {
                return Err(DynamicsError::DoesNotClose {
                    time: time + t * t0,
                    gap: (q_contact - z[0]) * s,
                })
            }
            // below the static pull-in voltage an overdamped plate creeps to its equilibrium
            // short of the contact without ever turning back: it does not close
            End::Timeout { t, y: z }
                if impacts.is_empty()
                    && plate.voltage < plate.switch.pull_in_voltage(plate.k_s) =>
            {
                return Err(DynamicsError::DoesNotClose {
                    time: time + t * t0,
                    gap: (q_contact - z[0]) * s,
                })
            }
            End::Timeout { .. } => {
                return Err(DynamicsError::Timeout {
                    phase: "flight",
                    limit: limit_t0 * t0,
                    what: "the contact was not reached",
                })
            }
        };
        time += t * t0;
        y = z[0] * s;
        v = z[1] * s / t0;
        gas = z[2] * e0;
        contact = z[3] * e0;
        let (y_at_impact, gas_at_impact) = (y, gas);
        // the integration's energy residual since the voltage step, at the impact
        let residual_at_impact = plate.electrostatic_work(plate.switch.d0() - y)
            - 0.5 * plate.k_s * y * y
            - 0.5 * m * v * v
            - gas
            - contact;
        let impact = ImpactState {
            separation: reach,
            velocity: v,
            energy: 0.5 * m * v * v,
            flight_time: time - flight_start,
        };
        // -- contact, approach path: u = d/sigma, w = v/V, energies / (m V^2)
        let sigma = surface.length_scales(&hist)?.roughness;
        let vel = v.abs().max(sigma / t0);
        let tau = sigma / vel;
        let ec = m * vel * vel;
        let scales = Scales {
            s,
            m,
            phi,
            sigma,
            vel,
            tau,
            ec,
        };
        let width = 2.0 * sigma;
        if !approach_table
            .as_ref()
            .is_some_and(|t| t.is_for(&hist, Path::Approach, width, tol, floor))
        {
            let origin = surface
                .kinks(&hist)
                .into_iter()
                .filter(|k| k.is_finite())
                .fold(f64::INFINITY, f64::min);
            *approach_table = Some(PressureTable::new(
                surface,
                hist.clone(),
                Path::Approach,
                if origin.is_finite() { origin } else { 0.0 },
                reach,
                width,
                tol,
                floor,
            ));
        }
        let approach = approach_table.as_ref().expect("set above");
        let zc = [(s - y) / sigma, v / vel, gas / ec, contact / ec];
        let mut trace_error: Option<LawError> = None;
        let phase_start = std::cell::Cell::new(time);
        let mut on_contact = |st: &ode::Step, table: &PressureTable<S>| {
            if options.trace && trace_error.is_none() {
                let d = st.1[0] * sigma;
                match table.pressure(d) {
                    Ok(p) => trace.push(TracePoint {
                        t: phase_start.get() + st.0 * tau,
                        displacement: s - d,
                        velocity: st.1[1] * vel,
                        contact_pressure: p,
                    }),
                    Err(e) => trace_error = Some(e),
                }
            }
        };
        let limit = limit_t0 * t0 / tau;
        let end = ode::run(
            "contact (approach)",
            contact_rhs(approach, &plate, scales),
            &[Threshold {
                component: 1,
                level: 0.0,
                rising: false,
            }],
            &zc,
            limit,
            tol,
            &mut |st| on_contact(st, approach),
            &|z: &[f64]| settled_in_contact(approach, &plate, scales, z, tol),
            &|| surface.check_cancelled(),
        )?;
        // a plate that crept into its equilibrium in the contact is captured there
        let mut at_rest = false;
        let (t, z) = match end {
            End::Crossed { t, y, .. } => (t, y),
            End::Settled { t, y } => {
                at_rest = true;
                (t, y)
            }
            End::Timeout { .. } => {
                return Err(DynamicsError::Timeout {
                    phase: "contact (approach)",
                    limit: limit_t0 * t0,
                    what: "the plate did not stop in the contact",
                })
            }
        };
        time += t * tau;
        phase_start.set(time);
        let d_min = z[0] * sigma;
        // the error of d_min. The turning point closes the energy balance of the contact
        // phase, f(d) = E_0 + [W(y) - W(y_0)] - K_s [y^2 - y_0^2]/2 - gas - phi int_d^reach p
        // = 0 (E_0, y_0 at the impact, gas the film's work in this phase), evaluated with
        // the table's exact work at the integrated d_min: what it misses is the
        // integration's energy error in this phase. With the table's work error (its
        // evaluations' estimates and misses) and the residual the impact arrived with
        // (every earlier flight, impact and bounce), that energy error dE moves the turning
        // point by the root of kappa x^2/2 + F x = dE: F the net force there (phi p - p_es
        // + K_s y), kappa the contact's stiffness phi |dp/dd| (F alone where the balance
        // decides, a quadratic well where the plate creeps to rest at F = 0 under a gas
        // film). Plus the integration's tolerance on the roughness scale.
        let p_min = approach.pressure(d_min)?;
        let step = 1e-3 * sigma;
        let kappa = phi * ((approach.pressure(d_min + step)? - p_min) / step).abs();
        let y_turn = s - d_min;
        let v_turn = z[1] * vel;
        let balance = impact.energy + plate.electrostatic_work(plate.switch.d0() - y_turn)
            - plate.electrostatic_work(plate.switch.d0() - y_at_impact)
            - 0.5 * plate.k_s * (y_turn * y_turn - y_at_impact * y_at_impact)
            - 0.5 * m * v_turn * v_turn
            - (z[2] * ec - gas_at_impact)
            - phi * approach.work(d_min, reach)?;
        let energy_error =
            balance.abs() + residual_at_impact.abs() + phi * approach.error_integral(d_min, reach);
        let force = (phi * p_min - plate.electrostatic(plate.switch.d0() - y_turn)
            + plate.k_s * y_turn)
            .abs();
        let shift = if kappa > 0.0 {
            2.0 * energy_error / (force + (force * force + 2.0 * kappa * energy_error).sqrt())
        } else {
            energy_error / force.max(f64::MIN_POSITIVE)
        };
        // a plate that crept to rest is where the forces balance, whatever energy the film
        // took: the error of the pressure there (the table's, per contact area, over the
        // restoring stiffness) moves it, and the creep left (below the tolerance)
        let d_min_error = if at_rest {
            let pressure_error = approach.error_integral(d_min, d_min + step) / step;
            let stiffness =
                plate.k_s + plate.electrostatic_slope(plate.switch.d0() - y_turn) + kappa;
            tol * sigma + phi * pressure_error / stiffness.max(f64::MIN_POSITIVE)
        } else {
            tol * sigma + shift
        };
        impacts.push((impact, d_min, time, d_min_error));
        hist = surface.load(&hist, d_min);
        // -- contact, retraction from d_min: separation (a bounce) or capture
        let out = surface.reach(&hist, Path::Retract { from: d_min })?;
        let path = Path::Retract { from: d_min };
        let retract =
            PressureTable::new(surface, hist.clone(), path, d_min, out, width, tol, floor);
        let zr = [z[0], z[1], z[2], z[3]];
        let end = if at_rest {
            End::Crossed {
                t: 0.0,
                y: zr.to_vec(),
                which: 0,
            }
        } else {
            ode::run(
                "contact (retraction)",
                contact_rhs(&retract, &plate, scales),
                &[
                    Threshold {
                        component: 1,
                        level: 0.0,
                        rising: true,
                    },
                    Threshold {
                        component: 0,
                        level: out / sigma,
                        rising: true,
                    },
                ],
                &zr,
                limit,
                tol,
                &mut |st| on_contact(st, &retract),
                &|z: &[f64]| settled_in_contact(&retract, &plate, scales, z, tol),
                &|| surface.check_cancelled(),
            )?
        };
        if let Some(e) = trace_error {
            return Err(e.into());
        }
        let (t, z, which) = match end {
            End::Crossed { t, y, which } => (t, y, which),
            // crept to rest in the contact: captured
            End::Settled { t, y } => (t, y, 0),
            End::Timeout { .. } => {
                return Err(DynamicsError::Timeout {
                    phase: "contact (retraction)",
                    limit: limit_t0 * t0,
                    what: "neither a capture nor a separation",
                })
            }
        };
        time += t * tau;
        let d = z[0] * sigma;
        y = s - d;
        v = z[1] * vel;
        gas = z[2] * ec;
        contact = z[3] * ec;
        if which == 0 {
            // captured: a turning point in contact
            let (first, d_e, ..) = impacts[0];
            let deepest_impact = impacts
                .iter()
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .expect("an impact");
            let (deepest, deepest_error) = (deepest_impact.1, deepest_impact.3);
            let stored = stored_energy(&retract, d, out)? * phi;
            let work_in = plate.electrostatic_work(plate.switch.d0() - y);
            let spring = 0.5 * plate.k_s * y * y;
            let kinetic = 0.5 * m * v * v;
            let ledger = EnergyLedger {
                work_in,
                spring,
                kinetic,
                gas,
                contact,
                stored,
                dissipated: contact - stored,
                residual: (work_in - spring - kinetic - gas - contact) / work_in,
            };
            let bounces = impacts[1..]
                .iter()
                .map(|&(impact, d_e, time, ..)| Bounce { impact, d_e, time })
                .collect();
            return Ok(Closure {
                impact: first,
                d_e,
                deepest,
                deepest_error,
                bounces,
                history: hist,
                capture_time: time,
                capture_separation: d,
                ledger,
                trace,
            });
        }
        if impacts.len() > options.max_bounces {
            return Err(DynamicsError::TooManyBounces {
                limit: options.max_bounces,
            });
        }
        flight_start = time;
    }
}

/// The elastic energy the contact gives back unloading from `d` to `out` on the retraction
/// `table` holds (J/m^2 per contact area): the integral of its pressure, Gauss-Legendre on
/// 32 panels (only the compressive part counts: the tensile well is the adhesion's).
fn stored_energy<S: SurfaceLaw>(
    table: &PressureTable<S>,
    d: f64,
    out: f64,
) -> Result<f64, LawError> {
    if !(out > d) {
        return Ok(0.0);
    }
    let gl = contact_core::numeric::GaussLegendre::new(8);
    let n = 32;
    let h = (out - d) / n as f64;
    let mut total = 0.0;
    for k in 0..n {
        let (a, b) = (d + h * k as f64, d + h * (k + 1) as f64);
        for (x, w) in gl.mapped(a, b) {
            let p = table.pressure(x)?;
            total += w * p.max(0.0);
        }
    }
    Ok(total)
}
