//! A sweep of every option of every subcommand with hostile values (issue 21, item 4):
//! the options are read from each subcommand's own `--help`, so a new option is swept the
//! day it is added. Each value must give a clean answer: exit 0 (accepted), 1 (numerical),
//! 2 (bad input, with a message on standard error) or 3 (strict validity), never a panic,
//! never a signal, and within a time bound (a hostile value never starts a long run: path
//! options get values that cannot be written or read, so nothing is computed for long).

mod common;

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Every subcommand path of the binary.
const COMMANDS: &[&[&str]] = &[
    &["md"],
    &["asperity"],
    &["surface"],
    &["switch"],
    &["calibrate"],
    &["law"],
    &["law", "eval"],
    &["scene"],
    &["design", "threshold"],
    &["design", "map"],
    &["design", "probability"],
    &["design", "merge"],
    &["topography"],
];

/// Values for an option that takes a number, a word or a key.
const HOSTILE: &[&str] = &["nan", "-1", "", "1e400", "-inf", "K=V=W", "0/0"];

/// Values for an option that names a file or folder: none can be read or written.
const HOSTILE_PATHS: &[&str] = &["", "/nonexistent-stiction-dir/x", "/dev/full/x"];

/// The options of `cmd` that take a value, with the value's name, from its `--help`.
fn options(cmd: &[&str]) -> Vec<(String, String)> {
    let mut args: Vec<&str> = cmd.to_vec();
    args.push("--help");
    let out = common::stiction(&args);
    assert!(out.status.success(), "{cmd:?} --help fails");
    let text = String::from_utf8(out.stdout).unwrap();
    let mut found = Vec::new();
    for line in text.lines() {
        let t = line.trim_start();
        let t = t
            .strip_prefix("-")
            .filter(|r| r.len() > 3 && &r[1..3] == ", ")
            .map_or(t, |r| &r[3..]);
        let Some(rest) = t.strip_prefix("--") else {
            continue;
        };
        let mut parts = rest.splitn(2, ' ');
        let name = parts.next().unwrap_or_default();
        let value = parts.next().unwrap_or_default().trim();
        if value.starts_with('<') {
            let end = value.rfind('>').map_or(value.len(), |i| i + 1);
            found.push((format!("--{name}"), value[..end].to_string()));
        }
    }
    found
}

fn is_path(value_name: &str) -> bool {
    ["FILE", "OUT", "DIR", "LAW", "PLOT", "PATH>"]
        .iter()
        .any(|k| value_name.contains(k))
        && value_name != "<PATH>"
}

/// Runs with a time bound; returns (exit code, stderr).
fn run_bounded(args: &[String], bound: Duration) -> (Option<i32>, String) {
    let dir = common::temp_dir("options");
    let mut child = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(args)
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run stiction");
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            let mut err = String::new();
            use std::io::Read;
            child
                .stderr
                .take()
                .unwrap()
                .read_to_string(&mut err)
                .unwrap();
            return (status.code(), err);
        }
        if start.elapsed() > bound {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{args:?} ran longer than {bound:?} on a hostile value");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn every_option_of_every_subcommand_refuses_hostile_values_cleanly() {
    let mut swept = 0;
    for cmd in COMMANDS {
        let opts = options(cmd);
        assert!(
            !opts.is_empty() || cmd == &["md"],
            "{cmd:?}: no options read"
        );
        for (opt, value_name) in &opts {
            let values = if is_path(value_name) {
                HOSTILE_PATHS
            } else {
                HOSTILE
            };
            for v in values {
                let mut args: Vec<String> = cmd.iter().map(|s| s.to_string()).collect();
                args.push(format!("{opt}={v}"));
                let (code, err) = run_bounded(&args, Duration::from_secs(120));
                assert!(
                    !err.contains("panicked") && !err.contains("RUST_BACKTRACE"),
                    "{args:?} panicked: {err}"
                );
                match code {
                    Some(0) | Some(1) | Some(3) => {}
                    Some(2) => {
                        assert!(!err.trim().is_empty(), "{args:?}: exit 2 without a message")
                    }
                    other => panic!("{args:?}: exit {other:?}: {err}"),
                }
                swept += 1;
            }
        }
    }
    assert!(swept > 150, "only {swept} cases swept");
}
