//! The subcommands: each is a clap struct that reads a scene, hands it to the model library
//! (`stiction-model`: scene -> spec -> model -> run -> result) and renders the result. No
//! physics here: what a command computes is the library's.

pub mod asperity;
pub mod calibrate;
pub mod design;
pub mod law;
pub mod md;
pub mod print;
pub mod probability;
pub mod surface;
pub mod switch;
pub mod topography;

use crate::error::Error;
use crate::output::{self, OutputSet};
use crate::render::{self, Format, Render};
use std::path::{Path, PathBuf};
use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::{ModelError, SceneError};
use stiction_report::ReportError;

/// What every command runs with: the laws scenes may name.
#[derive(Debug, Clone, Copy)]
pub struct Ctx<'a> {
    /// The law registry (the built-in laws, and a user's own in a binary of theirs).
    pub registry: &'a LawRegistry,
}

/// The options of every command that reads a scene.
#[derive(Debug, Clone, Default)]
pub struct SceneArgs {
    /// The scene files (`--scene`, repeatable, merged in order); the paper's scene if none.
    pub scene: SceneFiles,
    /// `--set KEY=VALUE` edits.
    pub set: Vec<String>,
    /// `--strict`.
    pub strict: bool,
}

/// The `--scene` files of a command, in the order given.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SceneFiles(pub Vec<PathBuf>);

impl SceneFiles {
    /// Whether no scene file was given (the paper's scene).
    pub fn is_none(&self) -> bool {
        self.0.is_empty()
    }

    /// Whether a scene file was given.
    pub fn is_some(&self) -> bool {
        !self.0.is_empty()
    }

    /// The first scene file, if any.
    pub fn as_deref(&self) -> Option<&Path> {
        self.0.first().map(PathBuf::as_path)
    }
}

/// The options of [`SceneArgs`] as the command line gives them (clap derives the parser;
/// [`SceneArgs`] holds the files as [`SceneFiles`]).
#[derive(Debug, Clone, Default, clap::Args)]
struct SceneArgsCli {
    /// Scene file (TOML, or JSON if it ends in .json or starts with `{`); the paper's scene
    /// if absent. Repeatable: the files are merged in order, a later file's key replacing
    /// an earlier one's (--scene switch.toml --scene surface.toml takes the switch from the
    /// first and the roughness of the fragment `stiction topography --out` writes).
    #[arg(long, value_name = "FILE")]
    scene: Vec<PathBuf>,
    /// Set a scene key before validation, KEY=VALUE with KEY as `section.key` and VALUE a
    /// TOML value or a bare word (repeatable): --set contact.reload=bounded --set cycles=20.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Exit with status 3 when the model does not hold for the result (the verdict's
    /// "outside the model's validity"); the result is written all the same.
    #[arg(long)]
    strict: bool,
}

impl From<SceneArgsCli> for SceneArgs {
    fn from(c: SceneArgsCli) -> Self {
        SceneArgs {
            scene: SceneFiles(c.scene),
            set: c.set,
            strict: c.strict,
        }
    }
}

impl From<SceneArgs> for SceneArgsCli {
    fn from(a: SceneArgs) -> Self {
        SceneArgsCli {
            scene: a.scene.0,
            set: a.set,
            strict: a.strict,
        }
    }
}

impl clap::FromArgMatches for SceneArgs {
    fn from_arg_matches(m: &clap::ArgMatches) -> Result<Self, clap::Error> {
        SceneArgsCli::from_arg_matches(m).map(Into::into)
    }

    fn update_from_arg_matches(&mut self, m: &clap::ArgMatches) -> Result<(), clap::Error> {
        let mut c = SceneArgsCli::from(std::mem::take(self));
        c.update_from_arg_matches(m)?;
        *self = c.into();
        Ok(())
    }
}

impl clap::Args for SceneArgs {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        SceneArgsCli::augment_args(cmd)
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        SceneArgsCli::augment_args_for_update(cmd)
    }
}

/// A scene loaded for a command, with the command line's edits and who made each.
pub struct Loaded {
    /// The scene, edited.
    pub scene: Scene,
    /// (scene key, option that set it), to blame an option for a value out of its domain.
    pub blame: Vec<(String, String)>,
}

impl SceneArgs {
    /// Reads the scene (or the paper's of `kind`) and applies `--set`, then `edits` (a
    /// command's own options: key, value, option).
    ///
    /// Several `--scene` files merge in order (the later winning key by key). A scene
    /// whose surface comes from a height map (`surface.topography`) prints its notes (a
    /// key of the scene overriding the map's value) with the warnings.
    pub fn load(&self, kind: Kind, edits: &[(&str, toml::Value, &str)]) -> Result<Loaded, Error> {
        let mut scene = Scene::read_merged(&self.scene.0, kind)?;
        let mut blame = Vec::new();
        for s in &self.set {
            let Some((key, value)) = s.split_once('=') else {
                return Err(Error::usage(
                    "--set",
                    format!("`{s}`: expected KEY=VALUE, e.g. contact.reload=bounded"),
                ));
            };
            let key = key.trim();
            scene
                .set_text(key, value.trim())
                .map_err(|e| Error::usage("--set", e.without_file()))?;
            blame.push((key.to_string(), format!("--set {key}")));
        }
        for (key, value, option) in edits {
            // an option that replaces what --set gave would drop the --set value unread
            // (even an invalid one): the two contradict each other unless they agree
            if blame.iter().any(|(k, _)| k == key) && scene.get(key) != Some(value) {
                return Err(Error::usage(
                    option,
                    format!("`{key}` is also set by --set {key}: give one of the two"),
                ));
            }
            scene.set(key, value.clone())?;
            blame.push((key.to_string(), option.to_string()));
        }
        render::print_warnings(&stiction_model::spec::topography_notes(&scene));
        Ok(Loaded { scene, blame })
    }
}

impl Loaded {
    /// Refuses a field that `--set` gave and `option` (`--vary`, `--scatter`) would
    /// replace at every point: the `--set` value would be dropped without a word.
    pub fn refuse_set_of(&self, field: &str, option: &str) -> Result<(), Error> {
        let field = field.trim();
        if self
            .blame
            .iter()
            .any(|(k, by)| k == field && by.starts_with("--set "))
        {
            return Err(Error::usage(
                option,
                format!("`{field}` is also set by --set {field}, which {option} would replace at every point: give one of the two"),
            ));
        }
        Ok(())
    }

    /// A model error on a key an option set, as an error of that option; a library
    /// argument as the option of its name; others as they are.
    pub fn blame(&self, e: ModelError) -> Error {
        if let ModelError::Scene(s) = &e {
            if let Some(key) = s.key() {
                // `delta_max[0]` was set by `--delta-max` as much as `delta_max` itself
                let base = key.split('[').next().unwrap_or(key);
                if let Some((_, option)) = self.blame.iter().rev().find(|(k, _)| k == base) {
                    let message = match s {
                        SceneError::Field { value, allowed, .. } => {
                            format!("{value}: must be {allowed}")
                        }
                        other => other.without_file(),
                    };
                    return Error::usage(option, message);
                }
            }
        }
        argument_error(e)
    }
}

/// The option a library argument came from, for messages (`vary` -> `--vary`), also when
/// the argument's error is reported in a scene.
pub fn argument_error(e: ModelError) -> Error {
    use stiction_model::design_sweep::DesignError;
    let option = |name: &str| format!("--{}", name.replace('_', "-"));
    match e.cause() {
        ModelError::Argument {
            name,
            value,
            allowed,
        } => Error::usage(&option(name), format!("{value}: must be {allowed}")),
        ModelError::Option { name, message } => Error::usage(&option(name), message.clone()),
        ModelError::Design(DesignError::Axis { option, reason }) => {
            Error::usage(&format!("--vary `{option}`"), reason.clone())
        }
        ModelError::Design(DesignError::Shard { option, reason }) => {
            Error::usage(&format!("--shard `{option}`"), reason.clone())
        }
        ModelError::Design(DesignError::Scatter { option, reason }) => {
            Error::usage(&format!("--scatter `{option}`"), reason.clone())
        }
        ModelError::Design(DesignError::Correlation { option, reason }) => {
            Error::usage(&format!("--correlate `{option}`"), reason.clone())
        }
        _ => e.into(),
    }
}

/// What a command writes besides standard output.
#[derive(Default)]
pub struct Outputs {
    /// An `--out` folder.
    pub folder: Option<OutputSet>,
    /// `--plot` files: the path and the SVG (or why it could not be drawn).
    pub plots: Vec<(PathBuf, Result<String, ReportError>)>,
}

/// Checks, before any computation, that the outputs can be written: an `--out` folder
/// holding only `known` files (or absent), a `--plot` path that takes a file. `-` is not
/// taken for standard output (which carries the result itself): it is refused rather than
/// written as a file named `-`.
pub fn preflight(out: Option<&Path>, known: &[&str], plot: Option<&Path>) -> Result<(), Error> {
    if let Some(dir) = out {
        if dir.as_os_str() == "-" {
            return Err(Error::usage(
                "--out",
                "`-`: use a folder name; - (standard output) is not supported for --out",
            ));
        }
        OutputSet::check(dir, known)?;
    }
    if let Some(p) = plot {
        if p.as_os_str() == "-" {
            return Err(Error::usage(
                "--plot",
                "`-`: use a file name; - (standard output) is not supported for --plot",
            ));
        }
        output::check_file(p)?;
    }
    Ok(())
}

/// Prints the warnings, writes the outputs, renders the result in `format` and applies
/// `--strict`.
pub fn finish<R: Render>(
    result: &R,
    format: Format,
    columns: bool,
    strict: bool,
    outputs: Outputs,
) -> Result<String, Error> {
    // a scene's topography notes were printed when it was loaded
    let shown: Vec<_> = result
        .warnings()
        .iter()
        .filter(|w| w.code != stiction_model::topography::TOPOGRAPHY_VALUE_OVERRIDDEN)
        .cloned()
        .collect();
    render::print_warnings(&shown);
    let mut written = Vec::new();
    for (path, svg) in outputs.plots {
        let svg = svg.map_err(|e| match e {
            ReportError::Plot { message, .. } => ReportError::plot(&path, message),
            e => e,
        })?;
        output::write_file(&path, svg.as_bytes())?;
        written.push(path);
    }
    if let Some(set) = outputs.folder {
        written.extend(set.commit()?);
    }
    let mut text = result.render(format, columns);
    if format == Format::Table && !written.is_empty() {
        let list: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        text.push_str(&format!("\nwrote {}\n", list.join(", ")));
    }
    if strict {
        if let Some(v) = result.validity().filter(|v| !v.holds) {
            render::emit(&text)?;
            return Err(Error::Strict(v.words()));
        }
    }
    Ok(text)
}
