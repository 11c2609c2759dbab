//! Cycle-runner invariants on the paper's two Ru surfaces (Table 1) under Table 2.

use asperity_plastic::{Elastic, ElastoPlasticAsperity, EtsionKadin, YieldModulus};
use contact_core::{paper, AdhesionLaw, Material, Pair, Path, PlasticityLaw, SurfaceLaw};
use gw_surface::{GreenwoodWilliamson, GwHistory, Quadrature, Roughness};
use maugis_kim::{DugdaleParams, Hertz, Jkr, JkrParams, MaugisKim};
use switch_1d::{
    end_of_impact, eq17_residual, run_cycles, unload, CycleOptions, Impact, ImpactFilm, Precision,
};

const SIGMA: f64 = paper::SIGMA_S;

fn pair() -> Pair {
    let m = Material::new(paper::RU).unwrap();
    Pair::new(m, Some(m), paper::RADIUS).unwrap()
}

fn rough(sigma_s: f64) -> Roughness {
    Roughness {
        sigma_s,
        asperity_density: paper::ASPERITY_DENSITY,
    }
}

fn surface<P: PlasticityLaw, A: AdhesionLaw>(
    p: P,
    a: A,
    sigma_s: f64,
) -> GreenwoodWilliamson<ElastoPlasticAsperity<P, A>> {
    let q = Quadrature {
        rel_tol: 1e-11,
        ..Quadrature::default()
    };
    GreenwoodWilliamson::new(ElastoPlasticAsperity::new(p, a), rough(sigma_s), q).unwrap()
}

fn mk() -> MaugisKim {
    MaugisKim::new(DugdaleParams::for_pair(
        &pair(),
        paper::WORK_OF_ADHESION,
        paper::Z0,
    ))
    .unwrap()
}

fn plastic(
    modulus: YieldModulus,
) -> GreenwoodWilliamson<ElastoPlasticAsperity<EtsionKadin, MaugisKim>> {
    surface(EtsionKadin::new(&pair(), modulus).unwrap(), mk(), SIGMA)
}

const FILM: ImpactFilm = ImpactFilm {
    thickness: paper::FILM_THICKNESS,
    youngs_modulus: paper::RU.youngs_modulus,
};

fn impact(energy: f64) -> Impact {
    Impact {
        energy,
        film: FILM,
        contact_area_fraction: 1.0,
        restoring_pressure: 16_880.0,
    }
}

fn quick(cycles: usize) -> CycleOptions {
    CycleOptions {
        cycles,
        unloading_points: 0,
        loading_points: 0,
        ..Default::default()
    }
}

#[test]
fn end_of_impact_satisfies_the_energy_balance_of_eq_17_where_the_pressure_is_compressive() {
    for modulus in [YieldModulus::AsPrinted, YieldModulus::Composite] {
        let gw = plastic(modulus);
        for (hist, e_i) in [
            (GwHistory::VIRGIN, 0.5),
            (
                GwHistory::Flat {
                    deepest: 1.3 * SIGMA,
                },
                0.5,
            ),
            (GwHistory::VIRGIN, 0.02),
        ] {
            let end = end_of_impact(&gw, &hist, e_i, FILM, Precision::default()).unwrap();
            assert!(
                end.pressure > 0.0,
                "{modulus:?}: the approach pressure at d_e is compressive"
            );
            // an independent quadrature of the balance (eq17_residual) closes at d_e ...
            let g = eq17_residual(&gw, &hist, end.d_e, e_i, FILM).unwrap();
            assert!(
                g.abs() <= 1e-9 * e_i,
                "{modulus:?} E_I {e_i}: residual {g:e}"
            );
            // ... and the error estimate is honest and within the target
            assert!(end.error <= 1e-10 * SIGMA, "{end:?}");
            let g_up = eq17_residual(&gw, &hist, end.d_e + 1e-6 * SIGMA, e_i, FILM).unwrap();
            assert!(g_up < 0.0, "d_e is the first closure on the way in");
        }
    }
}

/// The rule of theory 6.2 on a case where the film term closes the balance inside the
/// tensile well (strong JKR adhesion, a thin stiff film, a smooth surface): the old
/// search stopped there, or failed to absorb the energy at all (repro D5).
#[test]
fn a_closure_in_the_tensile_well_is_not_an_end_of_impact() {
    let p = pair();
    let jkr = Jkr::new(JkrParams {
        k: p.k(),
        work_of_adhesion: 20.0,
    })
    .unwrap();
    let gw = surface(
        EtsionKadin::new(&p, YieldModulus::Composite).unwrap(),
        jkr,
        1e-11,
    );
    let hist = GwHistory::VIRGIN;
    let end = end_of_impact(&gw, &hist, 0.5, FILM, Precision::default()).unwrap();
    assert!(end.pressure > 0.0);
    let g = eq17_residual(&gw, &hist, end.d_e, 0.5, FILM).unwrap();
    assert!(g.abs() <= 1e-8 * 0.5, "residual {g:e}");
    // above d_e the pressure was tensile somewhere, so a film-closed balance was possible
    let mut tensile = false;
    let top = gw.reach(&hist, Path::Approach).unwrap();
    for i in 0..100 {
        let d = end.d_e + (top - end.d_e) * i as f64 / 100.0;
        tensile |= gw.pressure(d, &hist, Path::Approach).unwrap() < 0.0;
    }
    assert!(tensile, "the case must have a tensile approach well");
}

#[test]
fn history_only_deepens_and_pull_out_grows_until_accommodation() {
    let gw = plastic(YieldModulus::AsPrinted);
    let run = run_cycles(&gw, gw.virgin(), impact(0.5), quick(4), &mut |_| {}).unwrap();
    let mut deepest = f64::INFINITY;
    let mut pull = 0.0;
    for c in &run.cycles {
        let d = c.history.deepest().unwrap();
        assert!(
            d <= deepest,
            "cycle {}: deepest {d} above {deepest}",
            c.cycle
        );
        assert!(c.d_e() >= d);
        // contact hardening: each impact flattens more asperities, pull-out does not fall
        assert!(
            c.unloading.pull_out_pressure >= pull * (1.0 - 1e-9),
            "cycle {}",
            c.cycle
        );
        deepest = d;
        pull = c.unloading.pull_out_pressure;
    }
    assert!(
        run.cycles[0].d_e() > run.cycles[1].d_e(),
        "the second impact goes deeper"
    );
    // the verdict lives in the result
    assert_eq!(run.largest_pull_out, pull);
    assert!((run.pull_out_ratio - pull / 16_880.0).abs() < 1e-12 * run.pull_out_ratio);
    assert_eq!(run.stiction, run.pull_out_ratio > 1.0);
    assert_eq!(
        run.first_sticking_cycle,
        run.cycles.iter().find(|c| c.sticks).map(|c| c.cycle)
    );
}

#[test]
fn once_an_impact_stays_above_the_deepest_point_every_later_cycle_repeats_exactly() {
    let gw = plastic(YieldModulus::AsPrinted);
    // a strong first impact, then weaker ones that stay above it
    let strong = run_cycles(&gw, gw.virgin(), impact(1.0), quick(1), &mut |_| {}).unwrap();
    let hist = strong.cycles[0].history.clone();
    let weak = run_cycles(&gw, hist.clone(), impact(0.3), quick(3), &mut |_| {}).unwrap();
    for c in &weak.cycles {
        assert!(c.d_e() > hist.deepest().unwrap());
        assert_eq!(c.history, hist, "history must not change");
        assert_eq!(c.d_e(), weak.cycles[0].d_e());
        assert_eq!(c.unloading, weak.cycles[0].unloading);
    }
    assert_eq!(weak.accommodated_after, Some(1));
}

#[test]
fn elastic_surface_repeats_every_cycle() {
    let gw = surface(Elastic::new(paper::RADIUS).unwrap(), mk(), SIGMA);
    let run = run_cycles(&gw, gw.virgin(), impact(0.5), quick(3), &mut |_| {}).unwrap();
    // the same balance each cycle; later cycles start their search from the previous
    // d_e, so they agree within the error estimates rather than to the bit
    let first = &run.cycles[0];
    for c in &run.cycles[1..] {
        let dd = (c.d_e() - first.d_e()).abs();
        assert!(dd <= c.end.error + first.end.error, "d_e moved {dd:e}");
        let dp = (c.unloading.pull_out_pressure - first.unloading.pull_out_pressure).abs();
        assert!(
            dp <= c.unloading.pull_out_error
                + first.unloading.pull_out_error
                + 1e-12 * first.unloading.pull_out_pressure,
            "pull-out moved {dp:e}"
        );
    }
    assert_eq!(run.accommodated_after, Some(1));
}

#[test]
fn the_pull_out_does_not_depend_on_the_curve_asked_for() {
    let gw = plastic(YieldModulus::AsPrinted);
    let hist = gw.load(&gw.virgin(), 0.3 * SIGMA);
    let base = unload(&gw, &hist, 0.3 * SIGMA, 0, Precision::default()).unwrap();
    for points in [2, 7, 300] {
        let u = unload(&gw, &hist, 0.3 * SIGMA, points, Precision::default()).unwrap();
        assert_eq!(
            u.pull_out_pressure, base.pull_out_pressure,
            "points {points}"
        );
        assert_eq!(u.curve.len(), points);
    }
    // no sample of a dense curve lies below the pull-out found without one
    let dense = unload(&gw, &hist, 0.3 * SIGMA, 2000, Precision::default()).unwrap();
    let lowest = dense.curve.iter().map(|p| p.pressure).fold(0.0, f64::min);
    assert!(
        -lowest <= base.pull_out_pressure * (1.0 + 1e-12),
        "{lowest} vs {}",
        base.pull_out_pressure
    );
}

#[test]
fn contact_on_part_of_the_electrode_absorbs_more_per_area_and_pulls_on_less() {
    let gw = plastic(YieldModulus::AsPrinted);
    let whole = run_cycles(&gw, gw.virgin(), impact(0.5), quick(1), &mut |_| {}).unwrap();
    let part = run_cycles(
        &gw,
        gw.virgin(),
        Impact {
            contact_area_fraction: 0.25,
            ..impact(0.5)
        },
        quick(1),
        &mut |_| {},
    )
    .unwrap();
    // E_I/phi per contact area: the same as a whole electrode hit with 2 J/m^2
    let four = run_cycles(&gw, gw.virgin(), impact(2.0), quick(1), &mut |_| {}).unwrap();
    assert_eq!(part.cycles[0].d_e(), four.cycles[0].d_e());
    assert!(part.cycles[0].d_e() < whole.cycles[0].d_e());
    // adhesion on a quarter of the electrode
    let p = part.cycles[0].unloading.pull_out_pressure;
    assert!((part.pull_out_ratio - 0.25 * p / 16_880.0).abs() <= 1e-12 * part.pull_out_ratio);
}

#[test]
fn an_energy_the_surface_cannot_absorb_is_an_error() {
    let gw = plastic(YieldModulus::AsPrinted);
    let e = end_of_impact(&gw, &GwHistory::VIRGIN, 1e12, FILM, Precision::default()).unwrap_err();
    assert!(
        matches!(e, switch_1d::SwitchError::EnergyNotAbsorbed { .. }),
        "{e}"
    );
    assert!(end_of_impact(&gw, &GwHistory::VIRGIN, -1.0, FILM, Precision::default()).is_err());
    let bad = Impact {
        contact_area_fraction: 0.0,
        ..impact(0.5)
    };
    assert!(run_cycles(&gw, gw.virgin(), bad, quick(1), &mut |_| {}).is_err());
}

#[test]
fn no_end_of_impact_is_found_below_the_deepest_separation_the_surface_covers() {
    let gw = plastic(YieldModulus::AsPrinted);
    // the work down to that depth (the lowest asperity pressed by its own radius), as the
    // error reports it
    let (floor, absorbed) =
        match end_of_impact(&gw, &GwHistory::VIRGIN, 1e12, FILM, Precision::default()) {
            Err(switch_1d::SwitchError::EnergyNotAbsorbed { d, absorbed, .. }) => (d, absorbed),
            other => panic!("{other:?}"),
        };
    assert!(absorbed > 0.0 && floor < -gw.roughness().sigma_s);
    // a little more energy, a film too thin to store any: the balance closes only below
    // that depth, so there
    // is no end of impact, on the tables and with evaluated pressures alone (which found
    // one below it: the 200-scene run's wide scene 48, the reference mode's d_e at -11.7
    // um where the modes stopped at -8.3 um)
    let no_film = ImpactFilm {
        thickness: 1e-30,
        ..FILM
    };
    for tables in [true, false] {
        let mut surface = Recorder::new(&gw, 1.0, 1.0);
        surface.work = tables;
        let e = end_of_impact(
            &surface,
            &GwHistory::VIRGIN,
            1.01 * absorbed,
            no_film,
            Precision::default(),
        );
        match e {
            Err(switch_1d::SwitchError::EnergyNotAbsorbed { d, .. }) => {
                assert_eq!(d, floor, "tables {tables}")
            }
            other => panic!("tables {tables}: {other:?}"),
        }
    }
}

/// A surface that wraps another, logs the approach separations it is asked for, counts
/// the scan pressures, can hide its tension bound, and can report every approach
/// pressure's error `inflate` times larger than its quadrature's (with a floor of 1e-12 of
/// the pressure) and its roughness `sigma_scale` times its own (which scales the d_e target
/// of eq 17, a fraction of the roughness, without changing the pressures).
struct Recorder<'a, S> {
    inner: &'a S,
    inflate: f64,
    sigma_scale: f64,
    asked: std::sync::Mutex<Vec<u64>>,
    /// Forward the inner surface's tension bound (else none).
    bound: bool,
    /// Scan pressures asked for.
    scans: std::sync::atomic::AtomicUsize,
    /// Forward the inner surface's approach work above the deepest point and its virgin
    /// work below (else neither).
    work: bool,
    /// Forward the inner surface's rough pressure (else none).
    rough: bool,
    /// Rough pressures asked for.
    roughs: std::sync::atomic::AtomicUsize,
}

impl<'a, S: SurfaceLaw> Recorder<'a, S> {
    fn new(inner: &'a S, inflate: f64, sigma_scale: f64) -> Self {
        Self {
            inner,
            inflate,
            sigma_scale,
            asked: std::sync::Mutex::new(Vec::new()),
            bound: false,
            scans: Default::default(),
            work: false,
            rough: false,
            roughs: Default::default(),
        }
    }

    /// The plain surface with its tension bound, counting scan and rough pressures, with
    /// its rough pressure or without.
    fn roughly(inner: &'a S, rough: bool) -> Self {
        Self {
            rough,
            ..Self::scans(inner, true)
        }
    }

    /// The plain surface, counting scan pressures, with its tension bound or without.
    fn scans(inner: &'a S, bound: bool) -> Self {
        Self {
            bound,
            ..Self::new(inner, 1.0, 1.0)
        }
    }

    /// The plain surface, recording approach pressures, with its approach work above the
    /// deepest point and its virgin work below, or without.
    fn works(inner: &'a S, work: bool) -> Self {
        Self {
            work,
            ..Self::new(inner, 1.0, 1.0)
        }
    }

    /// Approach pressures asked for.
    fn approaches(&self) -> usize {
        self.asked.lock().unwrap().len()
    }
}

impl<S: SurfaceLaw> SurfaceLaw for Recorder<'_, S> {
    type History = S::History;
    fn virgin(&self) -> S::History {
        self.inner.virgin()
    }
    fn pressure_estimate(
        &self,
        d: f64,
        history: &S::History,
        path: Path,
    ) -> Result<contact_core::Estimate, contact_core::LawError> {
        if path == Path::Approach {
            self.asked.lock().unwrap().push(d.to_bits());
        }
        let e = self.inner.pressure_estimate(d, history, path)?;
        if self.inflate == 1.0 {
            return Ok(e);
        }
        Ok(contact_core::Estimate {
            value: e.value,
            error: self.inflate * e.error.max(1e-12 * e.value.abs()),
        })
    }
    fn load(&self, history: &S::History, d: f64) -> S::History {
        self.inner.load(history, d)
    }
    fn reach(&self, history: &S::History, path: Path) -> Result<f64, contact_core::LawError> {
        self.inner.reach(history, path)
    }
    fn length_scales(
        &self,
        history: &S::History,
    ) -> Result<contact_core::LengthScales, contact_core::LawError> {
        let mut s = self.inner.length_scales(history)?;
        s.roughness *= self.sigma_scale;
        Ok(s)
    }
    fn kinks(&self, history: &S::History) -> Vec<f64> {
        self.inner.kinks(history)
    }
    fn pressure_scan(
        &self,
        d: f64,
        history: &S::History,
        path: Path,
    ) -> Result<f64, contact_core::LawError> {
        self.scans
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        self.inner.pressure_scan(d, history, path)
    }
    fn pressure_rough(
        &self,
        d: f64,
        history: &S::History,
        path: Path,
    ) -> Result<Option<contact_core::Estimate>, contact_core::LawError> {
        if !self.rough {
            return Ok(None);
        }
        self.roughs
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        self.inner.pressure_rough(d, history, path)
    }
    fn tension_bound(
        &self,
        d: f64,
        history: &S::History,
        path: Path,
    ) -> Result<Option<f64>, contact_core::LawError> {
        if self.bound {
            self.inner.tension_bound(d, history, path)
        } else {
            Ok(None)
        }
    }
    fn above_deepest(
        &self,
        history: &S::History,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<Option<contact_core::AboveDeepest>, contact_core::LawError> {
        if self.work {
            self.inner.above_deepest(history, abs, rel_of_abs)
        } else {
            Ok(None)
        }
    }
    fn virgin_work(
        &self,
        history: &S::History,
        lo: f64,
        hi: f64,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<Option<contact_core::VirginWork>, contact_core::LawError> {
        if self.work {
            self.inner.virgin_work(history, lo, hi, abs, rel_of_abs)
        } else {
            Ok(None)
        }
    }
}

/// eq 17's re-solves with a tighter energy integral start on the panels of the solve
/// before, and each approach pressure is evaluated once per end of impact: the re-solves
/// reuse the values (the same d, the same bits) instead of evaluating them again. (A
/// roughness reported 100 times smaller makes the d_e target 100 times tighter, beyond
/// what the first solve's energy tolerance reaches, so the solve is repeated.)
#[test]
fn a_re_solve_of_eq_17_evaluates_no_separation_twice() {
    let gw = plastic(YieldModulus::AsPrinted);
    let p = Recorder::new(&gw, 1.0, 1e-2);
    let fast = Precision {
        d_e: 1e-5,
        ..Precision::default()
    };
    let end = end_of_impact(&p, &p.virgin(), 0.5, FILM, fast).unwrap();
    let plain = end_of_impact(&gw, &gw.virgin(), 0.5, FILM, fast).unwrap();
    // the solve was repeated with a tighter energy integral: a smaller estimate
    assert!(
        end.error < 0.5 * plain.error,
        "{:e} vs {:e}",
        end.error,
        plain.error
    );
    let mut asked = p.asked.into_inner().unwrap();
    let n = asked.len();
    asked.sort_unstable();
    asked.dedup();
    assert_eq!(
        asked.len(),
        n,
        "{} of {n} approach pressures asked twice",
        n - asked.len()
    );
    // and the answer is the one of the plain surface
    assert!((end.d_e - plain.d_e).abs() <= fast.d_e * SIGMA);
}

/// Where the approach pressures' own errors alone exceed the d_e target, a tighter energy
/// integral cannot meet it: eq 17 is not re-solved for it. A surface whose pressure errors
/// are reported 1e8 times larger is asked for no more approach pressures than the plain
/// surface, its estimate stays honest (above the target), and its d_e is the plain one.
/// (Before, the two re-solves chased the pressures' noise with an energy tolerance down to
/// 1e-12 of the first: a plausible MEMS scene took 60 s in accurate mode, against 0.9 s in
/// the tighter reference mode.)
#[test]
fn eq_17_is_not_re_solved_for_an_error_only_the_pressures_can_reduce() {
    let gw = plastic(YieldModulus::AsPrinted);
    let fast = Precision {
        d_e: 1e-5,
        ..Precision::default()
    };
    let plain = Recorder::new(&gw, 1.0, 1.0);
    let reference = end_of_impact(&plain, &plain.virgin(), 0.5, FILM, fast).unwrap();
    let pessimist = Recorder::new(&gw, 1e8, 1.0);
    let end = end_of_impact(&pessimist, &pessimist.virgin(), 0.5, FILM, fast).unwrap();
    assert!(end.error > fast.d_e * SIGMA, "{:e}", end.error);
    let (n_plain, n_pessimist) = (
        plain.asked.into_inner().unwrap().len(),
        pessimist.asked.into_inner().unwrap().len(),
    );
    assert!(
        n_pessimist <= n_plain,
        "{n_pessimist} approach pressures against the plain surface's {n_plain}"
    );
    assert!((end.d_e - reference.d_e).abs() <= fast.d_e * SIGMA);
}

/// The pull-out scan ends where the surface's tension bound rules out anything further
/// out, with fewer scan pressures and the same pull-out to the bit as the whole scan, for
/// adhesive surfaces whose well lies at different depths (both readings of eq 1, a
/// shallow and a deep impact, Maugis-Kim and JKR).
#[test]
fn the_pull_out_scan_stops_early_only_where_the_bound_allows() {
    let jkr = Jkr::new(JkrParams {
        k: pair().k(),
        work_of_adhesion: paper::WORK_OF_ADHESION,
    })
    .unwrap();
    let surfaces: Vec<(&str, Run)> = vec![
        (
            "maugis_kim as printed",
            Box::new(|d| compare(&plastic(YieldModulus::AsPrinted), d)),
        ),
        (
            "maugis_kim composite",
            Box::new(|d| compare(&plastic(YieldModulus::Composite), d)),
        ),
        (
            "jkr",
            Box::new(move |d| {
                compare(
                    &surface(
                        EtsionKadin::new(&pair(), YieldModulus::AsPrinted).unwrap(),
                        jkr,
                        SIGMA,
                    ),
                    d,
                )
            }),
        ),
    ];
    let mut stopped = 0;
    for (name, run) in &surfaces {
        for d_e in [0.3 * SIGMA, -SIGMA] {
            let Compared {
                with,
                without,
                at,
                n_with,
                n_without,
            } = run(d_e);
            assert_eq!(with, without, "{name} at {d_e:e}: the pull-out changed");
            assert!(with > 0.0 && at > d_e, "{name}: no pull-out");
            assert!(n_with <= n_without, "{name}: {n_with} > {n_without}");
            if n_with < n_without {
                stopped += 1;
            }
        }
    }
    // the bound ends most scans early (the point of it)
    assert!(stopped >= 4, "only {stopped} of 6 scans ended early");
}

/// The compressive start of the pull-out scan evaluated roughly: the same unloading to
/// the bit (pull-out, its separation and error estimate) as with scan pressures
/// throughout, with most of the compressive samples rough, for adhesive surfaces whose
/// well lies at different depths (both readings of eq 1, Maugis-Kim and JKR, a shallow and
/// a deep impact) and for a surface without adhesion (Hertz: nothing tensile, so the rough
/// samples are evaluated again before the refinement ranks them).
#[test]
fn the_rough_start_of_the_pull_out_scan_leaves_the_pull_out_as_it_was() {
    let jkr = Jkr::new(JkrParams {
        k: pair().k(),
        work_of_adhesion: paper::WORK_OF_ADHESION,
    })
    .unwrap();
    let ek = || EtsionKadin::new(&pair(), YieldModulus::AsPrinted).unwrap();
    fn both<S: SurfaceLaw<History = GwHistory>>(gw: &S, d_e: f64, adhesive: bool, name: &str) {
        let hist = gw.load(&gw.virgin(), d_e);
        let run = |rough| {
            let s = Recorder::roughly(gw, rough);
            let u = unload(&s, &hist, d_e, 0, Precision::default()).unwrap();
            (u, s.scans.into_inner(), s.roughs.into_inner())
        };
        let ((with, scans_with, roughs), (without, scans_without, none)) = (run(true), run(false));
        assert_eq!(with, without, "{name} at {d_e:e}");
        assert_eq!(none, 0);
        if adhesive {
            assert!(with.pull_out_pressure > 0.0, "{name}: no pull-out");
            // most compressive samples are rough ones, which replace scan pressures (a
            // batch's rough samples from its first unsure one on are evaluated again)
            assert!(
                scans_with + 10 <= scans_without && scans_with + roughs >= scans_without,
                "{name} at {d_e:e}: {scans_with} scan and {roughs} rough pressures against {scans_without}"
            );
        } else {
            assert_eq!(with.pull_out_pressure, 0.0, "{name}");
        }
    }
    for d_e in [0.3 * SIGMA, -SIGMA] {
        both(
            &plastic(YieldModulus::AsPrinted),
            d_e,
            true,
            "maugis_kim as printed",
        );
        both(
            &plastic(YieldModulus::Composite),
            d_e,
            true,
            "maugis_kim composite",
        );
        both(&surface(ek(), jkr, SIGMA), d_e, true, "jkr");
        both(
            &surface(ek(), Hertz::new(pair().k()).unwrap(), SIGMA),
            d_e,
            false,
            "hertz",
        );
    }
}

/// Unloading with and without the tension bound: the two pull-outs, the separation of the
/// first and the scan pressures each asked for.
struct Compared {
    with: f64,
    without: f64,
    at: f64,
    n_with: usize,
    n_without: usize,
}

/// One surface's comparison at an impact depth.
type Run = Box<dyn Fn(f64) -> Compared>;

/// [`Compared`] for an unloading from `d_e` after loading the virgin surface to it.
fn compare<S: SurfaceLaw<History = GwHistory>>(gw: &S, d_e: f64) -> Compared {
    let hist = gw.load(&gw.virgin(), d_e);
    let run = |bound| {
        let s = Recorder::scans(gw, bound);
        let u = unload(&s, &hist, d_e, 0, Precision::default()).unwrap();
        (u, s.scans.into_inner())
    };
    let ((with, n_with), (without, n_without)) = (run(true), run(false));
    Compared {
        with: with.pull_out_pressure,
        without: without.pull_out_pressure,
        at: with.pull_out_separation,
        n_with,
        n_without,
    }
}

/// A made-up retraction curve with two adhesive wells, the deeper one further out:
/// p(d) = P (2 e^(-d/l) - g(d; 2 nm) - 2 g(d; 6 nm)), g a Gaussian bump 0.4 nm wide, and
/// its exact tension bound (the largest tension from d outward, sampled densely) when
/// `bound`.
struct TwoWells {
    bound: bool,
    scale: f64,
    /// How much deeper than it is the scan pressure sees the first well (in P).
    lie: f64,
}

impl TwoWells {
    const P: f64 = 1e6;
    fn g(d: f64, c: f64) -> f64 {
        (-((d - c) / 0.4e-9).powi(2)).exp()
    }
    fn p(d: f64) -> f64 {
        Self::P * (2.0 * (-d / 0.3e-9).exp() - Self::g(d, 2e-9) - 2.0 * Self::g(d, 6e-9))
    }
}

impl SurfaceLaw for TwoWells {
    type History = ();
    fn virgin(&self) {}
    fn pressure_estimate(
        &self,
        d: f64,
        _: &(),
        _: Path,
    ) -> Result<contact_core::Estimate, contact_core::LawError> {
        Ok(contact_core::Estimate {
            value: Self::p(d),
            error: 0.0,
        })
    }
    fn pressure_scan(&self, d: f64, _: &(), _: Path) -> Result<f64, contact_core::LawError> {
        Ok(Self::p(d) - self.lie * Self::P * Self::g(d, 2e-9))
    }
    fn load(&self, _: &(), _: f64) {}
    fn reach(&self, _: &(), _: Path) -> Result<f64, contact_core::LawError> {
        Ok(10e-9)
    }
    fn length_scales(&self, _: &()) -> Result<contact_core::LengthScales, contact_core::LawError> {
        Ok(contact_core::LengthScales {
            finest: 0.1e-9,
            roughness: 1e-9,
            deepest: -10e-9,
        })
    }
    fn tension_bound(
        &self,
        d: f64,
        _: &(),
        _: Path,
    ) -> Result<Option<f64>, contact_core::LawError> {
        Ok(self.bound.then(|| {
            self.scale
                * (0..=4000)
                    .map(|i| -Self::p(d + (10e-9 - d) * i as f64 / 4000.0))
                    .fold(0.0, f64::max)
        }))
    }
}

/// Past a first well the scan goes on while the bound says something further out may
/// pull harder, and finds the deeper well; with a bound that is wrong (a hundredth of the
/// true one) it stops after the first well, which shows the stop is what the bound
/// decides.
#[test]
fn the_pull_out_scan_goes_on_while_the_bound_allows_a_deeper_well() {
    let unload_with = |bound, scale| {
        let s = TwoWells {
            bound,
            scale,
            lie: 0.0,
        };
        unload(&s, &(), 0.0, 0, Precision::default()).unwrap()
    };
    let (bounded, plain) = (unload_with(true, 1.0), unload_with(false, 1.0));
    assert_eq!(bounded.pull_out_pressure, plain.pull_out_pressure);
    assert!((bounded.pull_out_separation - 6e-9).abs() < 0.05e-9);
    assert!(bounded.pull_out_pressure > 1.9 * TwoWells::P);
    let wrong = unload_with(true, 1e-2);
    assert!(
        (wrong.pull_out_separation - 2e-9).abs() < 0.05e-9,
        "{wrong:?}"
    );
}

/// A scan pressure that sees the first well ten times deeper than it is stops the scan
/// after it; the refined pull-out (the true, shallow well) does not beat the bound there,
/// so the rest of the grid is sampled and the deeper well further out is found all the
/// same.
#[test]
fn a_scan_misled_into_stopping_early_is_resumed_when_the_refined_pull_out_falls_short() {
    let s = TwoWells {
        bound: true,
        scale: 1.0,
        lie: 10.0,
    };
    let u = unload(&s, &(), 0.0, 0, Precision::default()).unwrap();
    assert!((u.pull_out_separation - 6e-9).abs() < 0.05e-9, "{u:?}");
    assert!(u.pull_out_pressure > 1.9 * TwoWells::P);
}

/// eq 17 on the surface's tables (started at the deepest point of the history with the work
/// above it integrated over the asperities, and below it on the tabulated virgin loading)
/// finds the same end of impact as the search with evaluated pressures from the first
/// touch (within the two error estimates), asking for fewer approach pressures (3 or 4
/// against 135 to 581 where it starts at D): the first four impacts on Maugis-Kim (both
/// readings of eq 1) and JKR surfaces, at two energies and two precisions.
#[test]
fn eq_17_from_the_deepest_point_finds_the_end_of_impact_of_the_search_from_the_top() {
    let jkr = Jkr::new(JkrParams {
        k: pair().k(),
        work_of_adhesion: paper::WORK_OF_ADHESION,
    })
    .unwrap();
    let surfaces = [
        ("maugis_kim as printed", plastic(YieldModulus::AsPrinted)),
        ("maugis_kim composite", plastic(YieldModulus::Composite)),
    ];
    let jkr_surface = surface(
        EtsionKadin::new(&pair(), YieldModulus::AsPrinted).unwrap(),
        jkr,
        SIGMA,
    );
    let fast = Precision {
        d_e: 1e-5,
        ..Precision::default()
    };
    let mut saved = 0;
    let mut cases = 0;
    let mut check = |name: &str, gw: &dyn Fn(bool) -> Vec<(f64, f64, usize)>| {
        let (with, without) = (gw(true), gw(false));
        for (k, (a, b)) in with.iter().zip(&without).enumerate() {
            assert!(
                (a.0 - b.0).abs() <= a.1 + b.1,
                "{name} impact {}: d_e {:e} vs {:e} (estimates {:e}, {:e})",
                k + 1,
                a.0,
                b.0,
                a.1,
                b.1
            );
            cases += 1;
            if a.2 < b.2 {
                saved += 1;
            }
        }
    };
    for precision in [Precision::default(), fast] {
        for energy in [0.5, 2.0] {
            for (name, gw) in &surfaces {
                check(name, &|forward| impacts(gw, forward, energy, precision));
            }
            check("jkr", &|forward| {
                impacts(&jkr_surface, forward, energy, precision)
            });
        }
    }
    // it is taken in most cases (the point of it)
    assert!(saved * 4 >= cases * 3, "{saved} of {cases}");
}

/// Impacts 1 to `n` (all of `energy`): (d_e, its error estimate, approach pressures asked)
/// each.
fn impacts_n<S: SurfaceLaw>(
    gw: &S,
    forward: bool,
    energy: f64,
    precision: Precision,
    n: usize,
) -> Vec<(f64, f64, usize)> {
    let mut hist = gw.virgin();
    (0..n)
        .map(|_| {
            let s = Recorder::works(gw, forward);
            let e = end_of_impact(&s, &hist, energy, FILM, precision).unwrap();
            hist = gw.load(&hist, e.d_e);
            (e.d_e, e.error, s.approaches())
        })
        .collect()
}

/// Impacts 1 to 4 ([`impacts_n`]).
fn impacts<S: SurfaceLaw>(
    gw: &S,
    forward: bool,
    energy: f64,
    precision: Precision,
) -> Vec<(f64, f64, usize)> {
    impacts_n(gw, forward, energy, precision, 4)
}

/// Nearly accommodated impacts (the fifth to the twelfth of the paper's switch): E_I less
/// the approach work above D and the film term at D leaves a few 1e-5 J/m^2 or less, less
/// than the film term's rise under the pressure bound P above D. The balance is still
/// shown open from D (the film term bounded by evaluated pressures within 1e-3 sigma_s of
/// D), the first step below D closes, and the evaluated pressure at D decides that the
/// balance is open there and starts Newton: a few evaluated pressures per impact (before,
/// 21 to 51 on the panels from D up to where the bound with P held and below D, and 450 to
/// 580 from the first touch where the balance at D was open by less than its estimates),
/// and the same end of impact as the search with evaluated pressures from the first touch,
/// within the two estimates (both readings of eq 1, two precisions).
#[test]
fn nearly_accommodated_impacts_are_found_from_the_deepest_point_with_a_few_pressures() {
    let fast = Precision {
        d_e: 1e-5,
        ..Precision::default()
    };
    for modulus in [YieldModulus::AsPrinted, YieldModulus::Composite] {
        let gw = plastic(modulus);
        for precision in [Precision::default(), fast] {
            let with = impacts_n(&gw, true, 0.5, precision, 12);
            let without = impacts_n(&gw, false, 0.5, precision, 12);
            for (k, (a, b)) in with.iter().zip(&without).enumerate() {
                assert!(
                    (a.0 - b.0).abs() <= a.1 + b.1,
                    "{modulus:?} impact {}: d_e {:e} vs {:e} (estimates {:e}, {:e})",
                    k + 1,
                    a.0,
                    b.0,
                    a.1,
                    b.1
                );
            }
            // a handful each; where the balance at D is open by less than its estimates
            // (composite, which accommodates within a few impacts: E_I - W(D) - film(p(D))
            // of 1e-7 to 1e-12 J/m^2 from the sixth impact on) the panels from D to
            // 1e-4 sigma_s above it, about 20 more
            let late: Vec<usize> = with[4..].iter().map(|a| a.2).collect();
            let most = match modulus {
                YieldModulus::AsPrinted => 12,
                _ => 32,
            };
            assert!(
                late.iter().all(|&n| n <= most),
                "{modulus:?} {precision:?}: approach pressures of impacts 5 to 12: {late:?}"
            );
        }
    }
}

/// An impact that stops above the deepest point (a weaker one after a strong one): the
/// balance closes above D, so the search runs from the first touch as before and finds the
/// same d_e to the bit.
#[test]
fn an_impact_that_stops_above_the_deepest_point_is_searched_from_the_top() {
    let gw = plastic(YieldModulus::AsPrinted);
    let strong = end_of_impact(&gw, &gw.virgin(), 2.0, FILM, Precision::default()).unwrap();
    let hist = gw.load(&gw.virgin(), strong.d_e);
    let run = |forward| {
        let s = Recorder::works(&gw, forward);
        end_of_impact(&s, &hist, 0.1, FILM, Precision::default()).unwrap()
    };
    let (with, without) = (run(true), run(false));
    assert!(with.d_e > strong.d_e);
    assert_eq!(with.d_e, without.d_e);
    assert_eq!(with.error, without.error);
}

/// The soft gold-like film of the 2026-11-24 user report (the Pt-Au bridge: E 90 GPa,
/// nu 0.42, S_Y 320 MPa, R 2 um, w 0.08 J/m^2, z0 0.2 nm, sigma_s 22 nm, 3e12 asperities per
/// m^2, composite yield modulus, eq 12 as printed), pressures to 1e-7.
fn gold_film() -> GreenwoodWilliamson<ElastoPlasticAsperity<EtsionKadin, MaugisKim>> {
    let gold = Material::new(contact_core::MaterialProps {
        youngs_modulus: 90e9,
        poisson_ratio: 0.42,
        yield_stress: 320e6,
    })
    .unwrap();
    let pair = Pair::new(gold, Some(gold), 2e-6).unwrap();
    GreenwoodWilliamson::new(
        ElastoPlasticAsperity::new(
            EtsionKadin::new(&pair, YieldModulus::Composite).unwrap(),
            MaugisKim::new(DugdaleParams::for_pair(&pair, 0.08, 0.2e-9)).unwrap(),
        ),
        Roughness {
            sigma_s: 22e-9,
            asperity_density: 3e12,
        },
        Quadrature {
            rel_tol: 1e-7,
            ..Quadrature::default()
        },
    )
    .unwrap()
}

/// The gold film's impact film (0.6 um thick).
const GOLD_FILM: ImpactFilm = ImpactFilm {
    thickness: 0.6e-6,
    youngs_modulus: 90e9,
};

/// A fixed number of cycles runs as a pipeline (eq 17 in turn, each unloading beside the
/// next impacts): the same cycles to the bit as one cycle after the other (the run that
/// stops at accommodation, with a tolerance nothing meets), on the paper's surface (10
/// cycles, both readings of eq 1) and on a soft film whose later impacts stop above the
/// deepest point, so that the history stops changing and cycles repeat (40 cycles, more
/// than one window).
#[test]
fn a_fixed_number_of_cycles_found_ahead_is_the_cycle_by_cycle_run() {
    fn both<S: SurfaceLaw>(gw: &S, impact: Impact, cycles: usize, name: &str) -> usize
    where
        S::History: std::fmt::Debug,
    {
        let options = CycleOptions {
            cycles,
            precision: Precision {
                d_e: 1e-6,
                pull_out: 1e-6,
            },
            ..quick(cycles)
        };
        let ahead = run_cycles(gw, gw.virgin(), impact, options, &mut |_| {}).unwrap();
        let mut seen = 0;
        let one_by_one = run_cycles(
            gw,
            gw.virgin(),
            impact,
            CycleOptions {
                until_accommodated: true,
                accommodation_tolerance: 1e-300,
                ..options
            },
            &mut |_| seen += 1,
        )
        .unwrap();
        // one by one, the run stops only where the history stopped changing (every later
        // cycle repeats the last)
        let n = one_by_one.cycles.len();
        assert_eq!(seen, n);
        assert!(n >= 5, "{name}: {n} cycles one by one");
        assert_eq!(ahead.cycles.len(), cycles, "{name}");
        assert_eq!(ahead.cycles[..n], one_by_one.cycles[..], "{name}");
        let last = &one_by_one.cycles[n - 1];
        for c in &ahead.cycles[n..] {
            assert_eq!(
                (c.end, &c.history, &c.unloading),
                (last.end, &last.history, &last.unloading),
                "{name} cycle {}",
                c.cycle
            );
        }
        // cycles that repeat the one before
        ahead
            .cycles
            .windows(2)
            .filter(|w| w[0].history == w[1].history)
            .count()
    }
    for modulus in [YieldModulus::AsPrinted, YieldModulus::Composite] {
        both(&plastic(modulus), impact(0.5), 10, "paper");
    }
    let soft = Impact {
        energy: 5.85,
        film: GOLD_FILM,
        contact_area_fraction: 1.0,
        restoring_pressure: 16_880.0,
    };
    let repeats = both(&gold_film(), soft, 40, "soft film");
    assert!(repeats > 0, "no cycle repeated");
}

/// A soft gold-like film (the Pt-Au bridge of the 2026-11-24 user report: E 90 GPa,
/// nu 0.42, S_Y 320 MPa, R 2 um, w 0.08 J/m^2, z0 0.2 nm, sigma_s 22 nm, composite
/// yield modulus, eq 12 as printed) impacted again and again: its reload curves end above
/// the virgin curve (the eq-12 artefact, docs/theory.md 2.5), so the approach pressure
/// drops at the deepest point D and later impacts stop just above D. Started at D, eq 17
/// must see that from D's upper side and search from the top: every impact's d_e is the
/// one the search from the top finds (within the two estimates), and some impact stops
/// above D (the case this guards).
#[test]
fn an_impact_absorbed_by_the_reload_artefact_just_above_the_deepest_point_is_found() {
    let gw = gold_film();
    let film = GOLD_FILM;
    let precision = Precision {
        d_e: 1e-6,
        ..Precision::default()
    };
    let mut hist = gw.virgin();
    let mut deepest = f64::INFINITY;
    let mut above = 0;
    for k in 1..=10 {
        let run = |work| {
            let s = Recorder::works(&gw, work);
            end_of_impact(&s, &hist, 5.85, film, precision).unwrap()
        };
        let (with, without) = (run(true), run(false));
        assert!(
            (with.d_e - without.d_e).abs() <= with.error + without.error,
            "impact {k}: d_e {:e} vs {:e} (estimates {:e}, {:e})",
            with.d_e,
            without.d_e,
            with.error,
            without.error
        );
        if without.d_e > deepest {
            above += 1;
        }
        deepest = deepest.min(without.d_e);
        hist = gw.load(&hist, without.d_e);
    }
    assert!(above > 0, "no impact stopped above the deepest point");
}
