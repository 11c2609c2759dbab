//! A caller stops a long run through its `Progress`: the run returns
//! `ModelError::Cancelled` (category `Interrupted`) promptly, never a partial result.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};
use stiction_model::contact_core::{Categorized, Category};
use stiction_model::keys::Kind;
use stiction_model::law::{self, LawOptions, LawScene};
use stiction_model::laws::LawRegistry;
use stiction_model::probability::{self, ProbabilityRequest};
use stiction_model::scene::Scene;
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::SwitchModel;
use stiction_model::{design, Accuracy, ModelError, Progress, Silent};

/// How soon a stop must be seen. The contract (issue 46) is Ctrl-C within a second; the
/// Python caller wakes every 0.1 s to look, so the library must see a stop within 0.9 s.
/// The bound is the contract, not the typical latency (a few milliseconds): these tests
/// run beside others on a loaded two-core machine, where a tighter wall-clock bound failed
/// for the load, not for the polling.
const WITHIN: Duration = Duration::from_millis(900);

/// Asks to stop after `after` progress reports (0: from the start); counts the polls
/// made after the stop and records the time of the stop.
struct StopAfter {
    after: u64,
    reports: AtomicU64,
    stop: AtomicBool,
    stopped_at: Mutex<Option<Instant>>,
    polls_after: AtomicU64,
}

impl StopAfter {
    fn new(after: u64) -> Self {
        Self {
            after,
            reports: AtomicU64::new(0),
            stop: AtomicBool::new(after == 0),
            stopped_at: Mutex::new((after == 0).then(Instant::now)),
            polls_after: AtomicU64::new(0),
        }
    }

    fn since_stop(&self) -> Duration {
        self.stopped_at
            .lock()
            .unwrap()
            .expect("the run reported progress before it ended")
            .elapsed()
    }
}

impl Progress for StopAfter {
    fn set(&self, _done: u64) {
        if self.reports.fetch_add(1, Ordering::SeqCst) + 1 >= self.after
            && !self.stop.swap(true, Ordering::SeqCst)
        {
            *self.stopped_at.lock().unwrap() = Some(Instant::now());
        }
    }

    fn cancelled(&self) -> bool {
        let s = self.stop.load(Ordering::SeqCst);
        if s {
            self.polls_after.fetch_add(1, Ordering::Relaxed);
        }
        s
    }
}

fn is_cancelled(r: Result<impl std::fmt::Debug, ModelError>) {
    match r {
        Err(ModelError::Cancelled) => {
            let e = ModelError::Cancelled;
            assert_eq!(e.category(), Category::Interrupted);
            assert!(e.to_string().starts_with("interrupted"), "{e}");
        }
        other => panic!("expected Cancelled, got {other:?}"),
    }
}

fn switch(accuracy: &str, cycles: u32) -> SwitchSpec {
    let mut s = Scene::paper(Kind::Switch);
    s.set_text("accuracy", accuracy).unwrap();
    s.set_text("cycles", &cycles.to_string()).unwrap();
    SwitchSpec::new(&s, &LawRegistry::builtin()).unwrap()
}

#[test]
fn a_switch_run_stopped_before_it_starts_is_cancelled_at_once() {
    // 200 accurate cycles take about 1.8 s whole on the command line (twice the bound): a
    // stop seen at once ends it far sooner
    let spec = switch("accurate", 200);
    let stop = StopAfter::new(0);
    let t = Instant::now();
    is_cancelled(SwitchModel::build(&spec).unwrap().run(&stop));
    assert!(t.elapsed() < WITHIN, "{:?}", t.elapsed());
}

#[test]
fn a_switch_run_stopped_after_its_first_cycle_is_cancelled_within_one_surface_evaluation() {
    let spec = switch("accurate", 10);
    let model = SwitchModel::build(&spec).unwrap();
    assert_eq!(model.run(&Silent).unwrap().cycles.len(), 10);
    let stop = StopAfter::new(1);
    is_cancelled(model.run(&stop));
    // the stop is seen at the next surface evaluation: a few milliseconds (a cycle of the
    // accurate mode takes tens of them, and the pipeline reports cycles in windows)
    assert!(stop.since_stop() < WITHIN, "{:?}", stop.since_stop());
    assert!(stop.polls_after.load(Ordering::Relaxed) >= 1);
}

#[test]
fn the_switch_run_polls_the_stop_at_least_every_tenth_of_a_second() {
    // the accurate paper switch: the longest stretch between two polls is what a caller
    // waits at worst for its stop to be seen
    struct Gaps {
        last: Mutex<Instant>,
        longest: Mutex<Duration>,
    }
    impl Progress for Gaps {
        fn cancelled(&self) -> bool {
            let now = Instant::now();
            let mut last = self.last.lock().unwrap();
            let mut longest = self.longest.lock().unwrap();
            *longest = (*longest).max(now - *last);
            *last = now;
            false
        }
    }
    let spec = switch("accurate", 10);
    let model = SwitchModel::build(&spec).unwrap();
    let gaps = Gaps {
        last: Mutex::new(Instant::now()),
        longest: Mutex::new(Duration::ZERO),
    };
    let r = model.run(&gaps).unwrap();
    assert!(r.stiction && r.cycles.len() == 10);
    let longest = *gaps.longest.lock().unwrap();
    assert!(longest < WITHIN, "{longest:?}");
}

#[test]
fn a_design_map_stopped_after_its_first_point_is_cancelled_not_a_map_of_failed_points() {
    let registry = LawRegistry::builtin();
    let scene = Scene::paper(Kind::Switch);
    let vary = vec!["surface.sigma_s=2e-9:1e-7:log:24".to_string()];
    let stop = StopAfter::new(1);
    let t = Instant::now();
    is_cancelled(design::map(
        &scene,
        &registry,
        &vary,
        None,
        Some(Accuracy::Accurate),
        &stop,
    ));
    assert!(stop.since_stop() < WITHIN, "{:?}", stop.since_stop());
    // 24 accurate points take seconds; the stop came after one or two of them
    assert!(t.elapsed() < Duration::from_secs(3), "{:?}", t.elapsed());
}

#[test]
fn a_threshold_search_stopped_after_its_first_point_is_cancelled() {
    let registry = LawRegistry::builtin();
    let scene = Scene::paper(Kind::Switch);
    let stop = StopAfter::new(1);
    is_cancelled(design::threshold_with(
        &scene,
        &registry,
        "surface.sigma_s",
        2e-9,
        1e-7,
        Some(Accuracy::Accurate),
        None,
        &stop,
    ));
    assert!(stop.since_stop() < WITHIN, "{:?}", stop.since_stop());
}

#[test]
fn a_threshold_search_reports_its_points_and_ends_at_its_total() {
    struct Count {
        total: AtomicU64,
        last: AtomicU64,
        monotone: AtomicBool,
    }
    impl Progress for Count {
        fn start(&self, total: u64, _: &str) {
            self.total.store(total, Ordering::SeqCst);
        }
        fn set(&self, done: u64) {
            let before = self.last.swap(done, Ordering::SeqCst);
            if done < before || done > self.total.load(Ordering::SeqCst) {
                self.monotone.store(false, Ordering::SeqCst);
            }
        }
    }
    let count = Count {
        total: AtomicU64::new(0),
        last: AtomicU64::new(0),
        monotone: AtomicBool::new(true),
    };
    let t = design::threshold_with(
        &Scene::paper(Kind::Switch),
        &LawRegistry::builtin(),
        "surface.sigma_s",
        2e-9,
        1e-7,
        Some(Accuracy::Fast),
        None,
        &count,
    )
    .unwrap();
    assert!(t.threshold.critical_value.is_some_and(f64::is_finite));
    assert!(count.monotone.load(Ordering::SeqCst));
    let total = count.total.load(Ordering::SeqCst);
    assert!(total >= 9, "{total}");
    assert_eq!(count.last.load(Ordering::SeqCst), total);
}

#[test]
fn a_probability_run_stopped_after_its_first_sample_is_cancelled() {
    let mut scene = Scene::paper(Kind::Switch);
    scene
        .set_text("contact.yield_modulus", "composite")
        .unwrap();
    let request = ProbabilityRequest {
        scatter: vec!["surface.sigma_s=lognormal(7.78e-9,1.1)".into()],
        samples: 200,
        accuracy: Some(Accuracy::Accurate),
        ..ProbabilityRequest::default()
    };
    let stop = StopAfter::new(1);
    let t = Instant::now();
    is_cancelled(probability::run(
        &scene,
        &LawRegistry::builtin(),
        &request,
        &stop,
    ));
    assert!(stop.since_stop() < WITHIN, "{:?}", stop.since_stop());
    assert!(t.elapsed() < Duration::from_secs(3), "{:?}", t.elapsed());
}

#[test]
fn a_law_tabulation_stopped_after_its_first_report_is_cancelled() {
    let spec = switch("fast", 10);
    let stop = StopAfter::new(1);
    let t = Instant::now();
    is_cancelled(law::tabulate(
        LawScene::Switch(&spec),
        &LawOptions::default(),
        &stop,
    ));
    assert!(stop.since_stop() < WITHIN, "{:?}", stop.since_stop());
    // the whole adaptive tabulation takes about a minute
    assert!(t.elapsed() < Duration::from_secs(10), "{:?}", t.elapsed());
}

#[test]
fn a_switch_in_time_under_a_gas_film_stops_within_an_integration_step() {
    // the plate creeps through an atmosphere's squeeze film, 300 cycles in accurate mode
    // (about 17 s whole): its flight evaluates no surface, the integration polls the stop
    // at every step
    let mut s = Scene::paper(Kind::Switch);
    s.remove("switch.impact_energy");
    for (k, v) in [
        ("cycles", "300"),
        ("accuracy", "\"accurate\""),
        ("switch.k_s", "8.44e9"),
        ("switch.voltage", "60.0"),
        ("switch.dimple_height", "50e-9"),
        ("dynamics.areal_mass", "0.0246"),
        ("dynamics.gas_pressure", "101325.0"),
    ] {
        s.set_text(k, v).unwrap();
    }
    let spec = SwitchSpec::new(&s, &LawRegistry::builtin()).unwrap();
    let model = SwitchModel::build(&spec).unwrap();
    struct StopAt {
        at: Instant,
        seen: Mutex<Option<Instant>>,
    }
    impl Progress for StopAt {
        fn cancelled(&self) -> bool {
            let now = Instant::now();
            if now < self.at {
                return false;
            }
            self.seen.lock().unwrap().get_or_insert(now);
            true
        }
    }
    let stop = StopAt {
        at: Instant::now() + Duration::from_millis(300),
        seen: Mutex::new(None),
    };
    is_cancelled(model.run(&stop));
    let late = Instant::now() - stop.at;
    assert!(late < WITHIN, "stopped {late:?} after the stop");
}
