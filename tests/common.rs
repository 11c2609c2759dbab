//! Helpers shared by the CLI tests.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs the binary with `args` in the temporary folder.
pub fn stiction(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(args)
        .current_dir(std::env::temp_dir())
        .output()
        .expect("run stiction")
}

/// Prefix of the folder each test process writes in: `stiction-tests-<pid>`.
const ROOT_PREFIX: &str = "stiction-tests-";

/// This test process's folder under the system's temporary folder. The first call also
/// removes the folders of earlier test processes that have ended (on systems with a
/// `/proc`), so that repeated `cargo test` runs leave one run's files at most: a test
/// binary has no hook at exit to remove its own.
fn root() -> PathBuf {
    static SWEPT: std::sync::Once = std::sync::Once::new();
    let tmp = std::env::temp_dir();
    SWEPT.call_once(|| {
        let proc_fs = std::path::Path::new("/proc");
        if !proc_fs.join("self").exists() {
            return;
        }
        let Ok(entries) = std::fs::read_dir(&tmp) else {
            return;
        };
        for e in entries.flatten() {
            let name = e.file_name();
            let Some(pid) = name.to_str().and_then(|n| n.strip_prefix(ROOT_PREFIX)) else {
                continue;
            };
            // only `stiction-tests-<digits>` (older layouts appended `-<tag>`: the pid
            // is the digits before the first '-')
            let digits = pid.split('-').next().unwrap_or("");
            if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
                continue;
            }
            if !proc_fs.join(digits).exists() {
                let _ = std::fs::remove_dir_all(e.path());
            }
        }
    });
    tmp.join(format!("{ROOT_PREFIX}{}", std::process::id()))
}

/// A fresh temporary folder for one test.
pub fn temp_dir(tag: &str) -> PathBuf {
    let dir = root().join(tag);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `bytes` to a fresh temporary file and returns its path.
pub fn temp_file(tag: &str, bytes: &[u8]) -> PathBuf {
    let dir = root().join("files");
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(format!("{tag}.toml"));
    std::fs::write(&p, bytes).unwrap();
    p
}

/// Standard output as JSON (the run must succeed).
pub fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

/// True if the JSON tree holds a null anywhere.
pub fn has_null(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Null => true,
        serde_json::Value::Array(a) => a.iter().any(has_null),
        serde_json::Value::Object(o) => o
            .iter()
            .any(|(k, v)| !CONTRACT_NULLS.contains(&k.as_str()) && has_null(v)),
        _ => false,
    }
}

/// Keys whose null is a public contract (the trust issue): "not accommodated", "no
/// closing design is free", "the switch closes everywhere or nowhere".
pub const CONTRACT_NULLS: &[&str] = &[
    "accommodation_cause",
    "critical_value",
    "closure_boundary",
    "hold",
    "end_of_impact",
    "contact_resistance",
];

/// A scene of `kind` printed by the binary, with `edits` (key prefix, new line) applied.
pub fn scene_with(kind: &str, edits: &[(&str, &str)]) -> String {
    let text = String::from_utf8(stiction(&["scene", "--print", kind]).stdout).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for (key, line) in edits {
        let pos = lines
            .iter()
            .position(|l| l.trim_start().starts_with(&format!("{key} =")))
            .unwrap_or_else(|| panic!("no key {key} in the {kind} scene"));
        lines[pos] = line.to_string();
    }
    lines.join("\n") + "\n"
}
