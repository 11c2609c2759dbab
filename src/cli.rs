//! The `stiction` command line. Exit status: 0 success, 2 bad input, 1 numerical failure.

use crate::output::{self, Format};
use crate::run::{self, RunError};
use crate::scene::{self, Accuracy, AsperityScene, SurfaceScene, SwitchScene};
use clap::{Parser, Subcommand, ValueEnum};
use contact_core::Path as LawPath;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

#[derive(Parser, Debug)]
#[command(
    name = "stiction",
    version,
    about = "Adhesive contact of elasto-plastic rough surfaces and in-use stiction of a MEMS micro-switch",
    long_about = "Adhesive contact of elasto-plastic rough surfaces and in-use stiction of a MEMS micro-switch.\n\n\
                  Without a subcommand, runs the paper's micro-switch scene (Fig 4) and writes out/.\n\
                  All scene values and outputs are SI (m, N, Pa, J/m^2) unless a column says otherwise."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PathArg {
    Approach,
    Retract,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SceneKind {
    Asperity,
    Surface,
    Switch,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Maugis-Dugdale curve with the Kim extension, nondimensional (paper eq 7).
    Md {
        /// Transition parameter lambda.
        #[arg(long, allow_hyphen_values = true)]
        lambda: f64,
        /// Points on the curve.
        #[arg(long, default_value_t = 200)]
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
        #[arg(long, value_enum, default_value_t = Format::Table)]
        format: Format,
        /// Write an SVG plot of the curves.
        #[arg(long)]
        plot: Option<PathBuf>,
    },
    /// The rough surface: virgin loading and, with --unload-from, unloading.
    Surface {
        #[arg(long)]
        scene: Option<PathBuf>,
        /// Load to this separation d (m) and unload from it.
        #[arg(long, allow_hyphen_values = true)]
        unload_from: Option<f64>,
        #[arg(long, value_enum)]
        accuracy: Option<Accuracy>,
        #[arg(long, value_enum, default_value_t = Format::Table)]
        format: Format,
        #[arg(long)]
        plot: Option<PathBuf>,
    },
    /// The micro-switch cycle by cycle: d_e, pull-out pressure, accommodation, stiction.
    Switch {
        #[arg(long)]
        scene: Option<PathBuf>,
        /// Number of cycles (replaces the scene's).
        #[arg(long, conflicts_with = "until_accommodated")]
        cycles: Option<usize>,
        /// Run until accommodation is detected (at most the scene's cycles, or 1000).
        #[arg(long)]
        until_accommodated: bool,
        #[arg(long, value_enum)]
        accuracy: Option<Accuracy>,
        #[arg(long, value_enum, default_value_t = Format::Table)]
        format: Format,
        /// Write switch.json, cycles.csv, curves.csv and switch.svg here.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Print an embedded scene as TOML, to start a scene of your own from.
    Scene {
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
            let _ = e.print();
            return code;
        }
    };
    match execute(cli.command) {
        Ok(text) => {
            print!("{text}");
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

fn write_file(path: &Path, text: &str) -> Result<(), RunError> {
    std::fs::write(path, text)
        .map_err(|e| RunError::Input(format!("cannot write {}: {e}", path.display())))
}

fn plot_err(path: &Path, e: String) -> RunError {
    RunError::Input(format!("cannot write plot {}: {e}", path.display()))
}

/// Runs one command and returns what it prints.
pub fn execute(command: Option<Command>) -> Result<String, RunError> {
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
        } => {
            if let Some(delta) = delta {
                let p = match (path, from) {
                    (PathArg::Approach, None) => LawPath::Approach,
                    (PathArg::Approach, Some(_)) => {
                        return Err(RunError::Input(
                            "--from applies to --path retract only".into(),
                        ))
                    }
                    (PathArg::Retract, Some(f)) => LawPath::Retract { from: f },
                    (PathArg::Retract, None) => {
                        return Err(RunError::Input("--path retract needs --from".into()))
                    }
                };
                let r = run::md_point(lambda, delta, p)?;
                return Ok(match format {
                    Format::Json => output::json(&r),
                    Format::Csv => format!(
                        "lambda,delta,path,force\n{},{},{},{}\n",
                        r.lambda, r.delta, r.path, r.force
                    ),
                    Format::Table => format!(
                        "lambda = {}, Delta = {}, path = {}: Fbar = {}\n",
                        r.lambda, r.delta, r.path, r.force
                    ),
                });
            }
            let r = run::md(lambda, points, delta_end)?;
            Ok(match format {
                Format::Json => output::json(&r),
                Format::Csv => output::md_csv(&r),
                Format::Table => output::md_table(&r),
            })
        }
        Command::Asperity {
            scene: file,
            delta_max,
            format,
            plot,
        } => {
            let (name, mut s): (String, AsperityScene) =
                scene::load(file.as_deref(), scene::DEFAULT_ASPERITY)?;
            if !delta_max.is_empty() {
                s.delta_max = delta_max;
            }
            s.validate(&name)?;
            let r = run::asperity(&s).map_err(|e| e.in_scene(&name))?;
            if let Some(p) = &plot {
                output::asperity_plot(&r, p).map_err(|e| plot_err(p, e))?;
            }
            Ok(match format {
                Format::Json => output::json(&r),
                Format::Csv => output::asperity_csv(&r),
                Format::Table => output::asperity_table(&r),
            })
        }
        Command::Surface {
            scene: file,
            unload_from,
            accuracy,
            format,
            plot,
        } => {
            let (name, mut s): (String, SurfaceScene) =
                scene::load(file.as_deref(), scene::DEFAULT_SURFACE)?;
            if unload_from.is_some() {
                s.unload_from = unload_from;
            }
            if let Some(a) = accuracy {
                s.accuracy = a;
            }
            s.validate(&name)?;
            let r = run::surface(&s).map_err(|e| e.in_scene(&name))?;
            if let Some(p) = &plot {
                output::surface_plot(&r, p).map_err(|e| plot_err(p, e))?;
            }
            Ok(match format {
                Format::Json => output::json(&r),
                Format::Csv => output::surface_csv(&r),
                Format::Table => output::surface_table(&r),
            })
        }
        Command::Switch {
            scene: file,
            cycles,
            until_accommodated,
            accuracy,
            format,
            out,
        } => {
            let (name, mut s): (String, SwitchScene) =
                scene::load(file.as_deref(), scene::DEFAULT_SWITCH)?;
            if let Some(n) = cycles {
                s.cycles = n;
            }
            if until_accommodated {
                s.until_accommodated = true;
                if file.is_none() {
                    s.cycles = 1000;
                }
            }
            if let Some(a) = accuracy {
                s.accuracy = a;
            }
            s.validate(&name)?;
            let r = run::switch(&s).map_err(|e| e.in_scene(&name))?;
            let mut text = match format {
                Format::Json => output::json(&r),
                Format::Csv => output::switch_cycles_csv(&r),
                Format::Table => output::switch_table(&r),
            };
            if let Some(dir) = out {
                std::fs::create_dir_all(&dir).map_err(|e| {
                    RunError::Input(format!("cannot create {}: {e}", dir.display()))
                })?;
                write_file(&dir.join("switch.json"), &output::json(&r))?;
                write_file(&dir.join("cycles.csv"), &output::switch_cycles_csv(&r))?;
                write_file(&dir.join("curves.csv"), &output::switch_curves_csv(&r))?;
                let svg = dir.join("switch.svg");
                let mut written = vec!["switch.json", "cycles.csv", "curves.csv"];
                if !r.loading.is_empty() {
                    output::switch_plot(&r, &svg).map_err(|e| plot_err(&svg, e))?;
                    written.push("switch.svg");
                }
                if format == Format::Table {
                    let list: Vec<String> = written
                        .iter()
                        .map(|f| dir.join(f).display().to_string())
                        .collect();
                    text.push_str(&format!("\nwrote {}\n", list.join(", ")));
                    if r.loading.is_empty() {
                        text.push_str("(no plot: the scene asks for no curves, points = 0)\n");
                    }
                }
            }
            Ok(text)
        }
        Command::Scene { print } => Ok(match print {
            SceneKind::Asperity => scene::DEFAULT_ASPERITY,
            SceneKind::Surface => scene::DEFAULT_SURFACE,
            SceneKind::Switch => scene::DEFAULT_SWITCH,
        }
        .to_string()),
    }
}
