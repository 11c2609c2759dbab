//! The `stiction` command line: clap definitions and a short dispatch. Exit status: 0
//! success, 2 bad input, 1 numerical failure.

use crate::accuracy::Accuracy;
use crate::commands::{self, asperity::AsperityCommand, md, surface::SurfaceCommand, switch::SwitchCommand};
use crate::error::Error;
use crate::render::{self, Format};
use crate::scene::fields::Kind;
use clap::{Parser, Subcommand, ValueEnum};
use std::ffi::OsString;
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "stiction",
    version,
    about = "Adhesive contact of elasto-plastic rough surfaces and in-use stiction of a MEMS micro-switch",
    long_about = "Adhesive contact of elasto-plastic rough surfaces and in-use stiction of a MEMS micro-switch.\n\n\
                  Without a subcommand, runs the paper's micro-switch scene (Fig 4) and writes out/.\n\
                  All scene values and outputs are SI (m, N, Pa, J/m^2) unless a column says otherwise."
)]
/// The command line.
pub struct Cli {
    /// The subcommand (the paper's switch scene if none).
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// A path option of `md --delta`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PathArg {
    /// Coming from far away.
    Approach,
    /// Retracting after `--from`.
    Retract,
}

/// The scene kinds of `scene --print`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SceneKind {
    /// `stiction asperity`.
    Asperity,
    /// `stiction surface`.
    Surface,
    /// `stiction switch`, `design`, `law`.
    Switch,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Maugis-Dugdale curve with the Kim extension, nondimensional (paper eq 7).
    Md {
        /// Transition parameter lambda.
        #[arg(long, allow_hyphen_values = true)]
        lambda: f64,
        /// Points on the curve.
        #[arg(long, default_value_t = 200, allow_hyphen_values = true)]
        points: usize,
        /// Largest interference Delta of the curve.
        #[arg(long, default_value_t = 5.0, allow_hyphen_values = true)]
        delta_end: f64,
        /// Print the force at this one interference Delta instead of the curve.
        #[arg(long, allow_hyphen_values = true)]
        delta: Option<f64>,
        /// Path for --delta.
        #[arg(long, value_enum, default_value_t = PathArg::Approach, requires = "delta")]
        path: PathArg,
        /// Largest interference of the excursion for --path retract.
        #[arg(long, allow_hyphen_values = true)]
        from: Option<f64>,
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Json)]
        format: Format,
    },
    /// One elasto-plastic adhesive asperity loaded and unloaded (paper Fig 2).
    Asperity {
        /// Scene file (TOML); the paper's Fig 2 scene if absent.
        #[arg(long)]
        scene: Option<PathBuf>,
        /// Maximum interference (m); repeat for several cases. Replaces the scene's list.
        #[arg(long = "delta-max", allow_hyphen_values = true)]
        delta_max: Vec<f64>,
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Table)]
        format: Format,
        /// Write an SVG plot of the curves.
        #[arg(long)]
        plot: Option<PathBuf>,
    },
    /// The rough surface: virgin loading and, with --unload-from, unloading and reloading.
    Surface {
        /// Scene file (TOML); the paper's surface if absent.
        #[arg(long)]
        scene: Option<PathBuf>,
        /// Load to this separation d (m) and unload from it.
        #[arg(long, allow_hyphen_values = true)]
        unload_from: Option<f64>,
        /// Accuracy mode (replaces the scene's).
        #[arg(long, value_enum)]
        accuracy: Option<Accuracy>,
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Table)]
        format: Format,
        /// Write an SVG plot of the curves.
        #[arg(long)]
        plot: Option<PathBuf>,
    },
    /// The micro-switch cycle by cycle: d_e, pull-out pressure, accommodation, stiction.
    Switch {
        /// Scene file (TOML); the paper's switch if absent.
        #[arg(long)]
        scene: Option<PathBuf>,
        /// Number of cycles (replaces the scene's), 1..1000.
        #[arg(long, conflicts_with = "until_accommodated", allow_hyphen_values = true)]
        cycles: Option<usize>,
        /// Run until accommodation is detected (at most the scene's cycles, or 1000).
        #[arg(long)]
        until_accommodated: bool,
        /// Accuracy mode (replaces the scene's).
        #[arg(long, value_enum)]
        accuracy: Option<Accuracy>,
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Table)]
        format: Format,
        /// Write switch.json, cycles.csv, curves.csv and switch.svg to this folder
        /// (replaced as a whole; it may hold only those files).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Print an embedded scene as TOML, with every accepted key, to start a scene from.
    Scene {
        /// Which scene.
        #[arg(long, value_enum)]
        print: SceneKind,
    },
}

/// Runs the CLI on `args` and returns the exit status.
pub fn main_with_args<I: IntoIterator<Item = OsString>>(args: I) -> i32 {
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            if e.print().is_err() {
                return code;
            }
            return code;
        }
    };
    match execute(cli.command).and_then(|text| render::emit(&text)) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

/// Runs one command and returns what it prints on standard output.
pub fn execute(command: Option<Command>) -> Result<String, Error> {
    let command = command.unwrap_or(Command::Switch {
        scene: None,
        cycles: None,
        until_accommodated: false,
        accuracy: None,
        format: Format::Table,
        out: Some(PathBuf::from("out")),
    });
    match command {
        Command::Md {
            lambda,
            points,
            delta_end,
            delta,
            path,
            from,
            format,
        } => match delta {
            Some(delta) => {
                let p = match (path, from) {
                    (PathArg::Approach, None) => contact_core::Path::Approach,
                    (PathArg::Approach, Some(_)) => {
                        return Err(Error::usage("--from", "applies to --path retract only"))
                    }
                    (PathArg::Retract, Some(f)) => contact_core::Path::Retract { from: f },
                    (PathArg::Retract, None) => {
                        return Err(Error::usage("--path retract", "needs --from"))
                    }
                };
                Ok(commands::show(&md::point(lambda, delta, p)?, format))
            }
            None => Ok(commands::show(&md::curve(lambda, points, delta_end)?, format)),
        },
        Command::Asperity {
            scene,
            delta_max,
            format,
            plot,
        } => commands::pipeline(&AsperityCommand {
            scene,
            delta_max,
            format,
            plot,
        }),
        Command::Surface {
            scene,
            unload_from,
            accuracy,
            format,
            plot,
        } => commands::pipeline(&SurfaceCommand {
            scene,
            unload_from,
            accuracy,
            format,
            plot,
        }),
        Command::Switch {
            scene,
            cycles,
            until_accommodated,
            accuracy,
            format,
            out,
        } => commands::pipeline(&SwitchCommand {
            scene,
            cycles,
            until_accommodated,
            accuracy,
            format,
            out,
        }),
        Command::Scene { print } => Ok(commands::print::scene_text(match print {
            SceneKind::Asperity => Kind::Asperity,
            SceneKind::Surface => Kind::Surface,
            SceneKind::Switch => Kind::Switch,
        })
        .to_string()),
    }
}
