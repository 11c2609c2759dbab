//! The `stiction` command line: clap definitions and a short dispatch. Exit status: 0
//! success, 2 bad input, 1 numerical failure, 3 a result outside the model's validity
//! under `--strict`. Each subcommand's options are its command struct (in `commands/`): a
//! new subcommand is one module and one variant here.
//!
//! A program of one's own, built on this crate, registers its own laws and runs every
//! command with them through [`main_with`] (`examples/user_law.rs`).

use crate::commands::{
    asperity::AsperityCommand, calibrate::CalibrateCommand, design::DesignCommand, law::LawCommand,
    md::MdCommand, print::SceneCommand, surface::SurfaceCommand, switch::SwitchCommand,
    topography::TopographyCommand, Ctx,
};
use crate::error::Error;
use crate::render;
use clap::{Parser, Subcommand};
use std::ffi::OsString;
use stiction_model::laws::LawRegistry;

/// The command line.
#[derive(Parser, Debug)]
#[command(
    name = "stiction",
    version,
    about = "Adhesive contact of elasto-plastic rough surfaces and in-use stiction of a MEMS micro-switch",
    long_about = "Adhesive contact of elasto-plastic rough surfaces and in-use stiction of a MEMS micro-switch.\n\n\
                  Without a subcommand, runs the paper's micro-switch scene (Fig 4) and writes out/.\n\
                  All scene values and outputs are SI (m, N, Pa, J/m^2) unless a column says otherwise.\n\
                  Exit status: 0 success, 2 bad input, 1 numerical failure, 3 outside the model's validity with --strict."
)]
pub struct Cli {
    /// The subcommand (the paper's switch scene if none).
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Maugis-Dugdale curve with the Kim extension, nondimensional (paper eq 7).
    Md(MdCommand),
    /// One elasto-plastic adhesive asperity loaded and unloaded (paper Fig 2).
    Asperity(AsperityCommand),
    /// The rough surface: virgin loading and, with --unload-from, unloading and reloading.
    Surface(SurfaceCommand),
    /// The micro-switch cycle by cycle: d_e, pull-out pressure, accommodation, stiction.
    Switch(SwitchCommand),
    /// Fit the effective-radius constants of eq 13 to finite-element curves of one asperity.
    Calibrate(CalibrateCommand),
    /// The rough surface's contact law p(d; d_min, path) tabulated for an FE code (law.json,
    /// law.csv); `law eval` evaluates a law file.
    Law(LawCommand),
    /// Print an embedded scene as TOML, with every accepted key, to start a scene from.
    Scene(SceneCommand),
    /// Stiction-free design: the critical value of a scene field, maps of the pull-out
    /// ratio, merge of map shards.
    Design(DesignCommand),
    /// Greenwood-Williamson parameters (sigma_s, asperity density, radius) of a measured
    /// height map, by spectral moments and by summits, with a `[surface]` scene fragment.
    Topography(TopographyCommand),
}

/// Runs the CLI on `args` with the built-in laws and returns the exit status.
pub fn main_with_args<I: IntoIterator<Item = OsString>>(args: I) -> i32 {
    main_with(args, &LawRegistry::builtin())
}

/// Runs the CLI on `args` with the laws of `registry` (a user's own laws registered
/// beside the built-in ones) and returns the exit status.
pub fn main_with<I: IntoIterator<Item = OsString>>(args: I, registry: &LawRegistry) -> i32 {
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            // help and version go to stdout (status 0; a closed pipe is no failure, any
            // other write error is reported like a result's: status 2), usage errors to
            // stderr (status 2)
            let printed = e.print();
            if e.use_stderr() {
                return 2;
            }
            return match printed {
                Ok(()) => 0,
                Err(source) if source.kind() == std::io::ErrorKind::BrokenPipe => 0,
                Err(source) => {
                    let e = Error::from(stiction_report::ReportError::Write {
                        path: "standard output".into(),
                        source,
                    });
                    eprintln!("error: {e}");
                    e.exit_code()
                }
            };
        }
    };
    let ctx = Ctx { registry };
    match execute(cli.command, ctx).and_then(|text| render::emit(&text).map_err(Error::from)) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

/// Runs one command and returns what it prints on standard output.
pub fn execute(command: Option<Command>, ctx: Ctx) -> Result<String, Error> {
    match command.unwrap_or(Command::Switch(SwitchCommand::main_job())) {
        Command::Md(c) => c.execute(),
        Command::Asperity(c) => c.execute(ctx),
        Command::Surface(c) => c.execute(ctx),
        Command::Switch(c) => c.execute(ctx),
        Command::Calibrate(c) => c.execute(ctx),
        Command::Law(c) => c.execute(ctx),
        Command::Scene(c) => Ok(c.execute()),
        Command::Design(c) => c.execute(ctx),
        Command::Topography(c) => c.execute(),
    }
}
