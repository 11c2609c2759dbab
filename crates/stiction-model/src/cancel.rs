//! A surface that stops when its caller asks: every fallible evaluation first polls
//! [`Progress::cancelled`], and so does `SurfaceLaw::check_cancelled` (which the plate's
//! integration polls at every step), so that a switch run (whose cycles can take seconds
//! each) stops within one surface evaluation or one integration step.

use crate::Progress;
use contact_core::{
    AboveDeepest, CoreError, Estimate, LawError, LengthScales, Path, SurfaceLaw, VirginWork,
};

/// `surface` seen through a cancellation check: the same values to the bit (every method
/// forwards, the optional ones included), and `CoreError::Cancelled` (category
/// `Interrupted`) from any fallible method once `progress` asks the run to stop.
pub struct Cancellable<'a, S> {
    surface: &'a S,
    progress: &'a dyn Progress,
}

impl<'a, S: SurfaceLaw> Cancellable<'a, S> {
    /// `surface`, stopped by `progress`.
    pub fn new(surface: &'a S, progress: &'a dyn Progress) -> Self {
        Self { surface, progress }
    }

    fn check(&self) -> Result<(), LawError> {
        if self.progress.cancelled() {
            Err(CoreError::Cancelled.into())
        } else {
            Ok(())
        }
    }
}

impl<S: SurfaceLaw> SurfaceLaw for Cancellable<'_, S> {
    type History = S::History;

    fn virgin(&self) -> Self::History {
        self.surface.virgin()
    }

    fn pressure(&self, d: f64, history: &Self::History, path: Path) -> Result<f64, LawError> {
        self.check()?;
        self.surface.pressure(d, history, path)
    }

    fn pressure_estimate(
        &self,
        d: f64,
        history: &Self::History,
        path: Path,
    ) -> Result<Estimate, LawError> {
        self.check()?;
        self.surface.pressure_estimate(d, history, path)
    }

    fn pressure_scan(&self, d: f64, history: &Self::History, path: Path) -> Result<f64, LawError> {
        self.check()?;
        self.surface.pressure_scan(d, history, path)
    }

    fn pressure_rough(
        &self,
        d: f64,
        history: &Self::History,
        path: Path,
    ) -> Result<Option<Estimate>, LawError> {
        self.check()?;
        self.surface.pressure_rough(d, history, path)
    }

    fn load(&self, history: &Self::History, d: f64) -> Self::History {
        self.surface.load(history, d)
    }

    fn reach(&self, history: &Self::History, path: Path) -> Result<f64, LawError> {
        self.check()?;
        self.surface.reach(history, path)
    }

    fn length_scales(&self, history: &Self::History) -> Result<LengthScales, LawError> {
        self.check()?;
        self.surface.length_scales(history)
    }

    fn kinks(&self, history: &Self::History) -> Vec<f64> {
        self.surface.kinks(history)
    }

    fn above_deepest(
        &self,
        history: &Self::History,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<Option<AboveDeepest>, LawError> {
        self.check()?;
        self.surface.above_deepest(history, abs, rel_of_abs)
    }

    fn virgin_work(
        &self,
        history: &Self::History,
        lo: f64,
        hi: f64,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<Option<VirginWork>, LawError> {
        self.check()?;
        self.surface.virgin_work(history, lo, hi, abs, rel_of_abs)
    }

    fn tension_bound(
        &self,
        d: f64,
        history: &Self::History,
        path: Path,
    ) -> Result<Option<f64>, LawError> {
        self.check()?;
        self.surface.tension_bound(d, history, path)
    }

    fn check_cancelled(&self) -> Result<(), LawError> {
        self.check()?;
        self.surface.check_cancelled()
    }
}
