//! The subcommands. Each is scene -> validated model -> run -> report -> render: the
//! [`Command`] trait says where the scene comes from, what the command line overrides and
//! what is computed; [`pipeline`] does the rest, the same way for every command.

pub mod asperity;
pub mod calibrate;
pub mod design;
pub mod law;
pub mod md;
pub mod print;
pub mod surface;
pub mod switch;

use crate::error::Error;
use crate::render::{self, Format, OutputSet, Render};
use crate::scene::{self, Loaded, Scene};
use std::path::Path;

/// A subcommand that works on a scene.
pub trait Command {
    /// Its scene kind.
    type Scene: Scene;
    /// Its report.
    type Report: Render;
    /// The scene file (None: the embedded paper scene).
    fn scene_path(&self) -> Option<&Path>;
    /// Command-line overrides, applied before validation.
    fn apply(&self, scene: &mut Self::Scene) -> Result<(), Error> {
        let _ = scene;
        Ok(())
    }
    /// The scene keys this invocation's options replaced, with the option that set each
    /// (`("cycles", "--cycles")`): a value out of its domain is then reported against the
    /// option the user typed, not against the scene file.
    fn overrides(&self) -> Vec<(&'static str, &'static str)> {
        Vec::new()
    }
    /// The computation.
    fn run(&self, scene: &Loaded<Self::Scene>) -> Result<Self::Report, Error>;
    /// Files to write besides standard output (an `--out` folder, a `--plot`).
    fn outputs(&self, report: &Self::Report) -> Result<Option<OutputSet>, Error> {
        let _ = report;
        Ok(None)
    }
    /// The format of standard output.
    fn format(&self) -> Format;
}

/// Runs a command: load, override, validate, run, warn, write files, render.
pub fn pipeline<C: Command>(cmd: &C) -> Result<String, Error> {
    let mut loaded = scene::load::<C::Scene>(cmd.scene_path())?;
    cmd.apply(&mut loaded.scene)?;
    loaded
        .scene
        .validate(&loaded.file)
        .map_err(|e| blame_option(e, &cmd.overrides()))?;
    let report = cmd.run(&loaded).map_err(|e| e.in_scene(&loaded.file))?;
    for w in report.warnings() {
        eprintln!("warning[{}]: {}", w.code, w.message);
    }
    let mut text = report.render(cmd.format());
    if let Some(set) = cmd.outputs(&report)? {
        let written = set.commit()?;
        if cmd.format() == Format::Table {
            let list: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
            text.push_str(&format!("\nwrote {}\n", list.join(", ")));
        }
    }
    Ok(text)
}

/// A scene error on a key an option replaced, as an error of that option.
fn blame_option(e: scene::SceneError, overrides: &[(&str, &str)]) -> Error {
    if let scene::SceneError::Field {
        key,
        value,
        allowed,
        ..
    } = &e
    {
        // `delta_max[0]` was set by `--delta-max` as much as `delta_max` itself
        let base = key.split('[').next().unwrap_or(key);
        if let Some((_, option)) = overrides.iter().find(|(k, _)| *k == base) {
            return Error::usage(option, format!("{value}: must be {allowed}"));
        }
    }
    e.into()
}

/// Renders a report computed without a scene.
pub fn show<R: Render>(report: &R, format: Format) -> String {
    for w in report.warnings() {
        eprintln!("warning[{}]: {}", w.code, w.message);
    }
    report.render(format)
}

/// An SVG plot for a `--plot` option, written atomically.
pub fn write_plot(path: &Path, svg: Result<String, String>) -> Result<(), Error> {
    let svg = svg.map_err(|message| Error::Plot {
        path: path.display().to_string(),
        message,
    })?;
    render::write_file(path, svg.as_bytes())
}
