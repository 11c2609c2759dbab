//! The `stiction` binary: the command line of [`stiction::cli`].
fn main() {
    std::process::exit(stiction::cli::main_with_args(std::env::args_os()));
}
