//! Inputs and outputs the command line refuses by name instead of blocking, writing a file
//! of a surprising name or failing in silence: a scene that is not a regular file, a JSON
//! scene with a key given twice, `-` as an output path, help that cannot be written, an
//! output folder that cannot be made (named as given, not by its hidden staging folder).

mod common;

use common::{stiction, temp_dir};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Runs the binary with `args`, killing it (and failing) if it runs longer than `limit`:
/// a test of "never blocks" must not block itself.
fn run_within(args: &[&str], limit: Duration) -> std::process::Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(args)
        .current_dir(std::env::temp_dir())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run stiction");
    let started = Instant::now();
    loop {
        if child.try_wait().expect("wait").is_some() {
            return child.wait_with_output().expect("output");
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("stiction {args:?} still runs after {limit:?}: it blocks");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A FIFO given as a scene with no writer is refused at once naming the path (it used to
/// wait for a writer for ever); so are a folder and a character device, unread.
#[test]
fn a_scene_that_is_not_a_regular_file_is_refused_unread_naming_it() {
    let dir = temp_dir("scene-fifo");
    let fifo = dir.join("scene.toml");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    let out = run_within(
        &["switch", "--scene", fifo.to_str().unwrap()],
        Duration::from_secs(30),
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains(fifo.to_str().unwrap()) && err.contains("FIFO"),
        "{err}"
    );
    for (path, what) in [
        (dir.to_str().unwrap(), "folder"),
        ("/dev/null", "character device"),
    ] {
        if !Path::new(path).exists() {
            continue;
        }
        let out = run_within(&["asperity", "--scene", path], Duration::from_secs(30));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{path}: {err}");
        assert!(err.contains(path) && err.contains(what), "{err}");
    }
    // the same for a finite-element file of `calibrate`
    let out = run_within(
        &["calibrate", "--fe", fifo.to_str().unwrap()],
        Duration::from_secs(30),
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("FIFO"), "{err}");
}

/// A JSON scene that gives a key twice is refused naming the key (TOML refuses it too),
/// instead of keeping the last value without a word.
#[test]
fn a_json_scene_with_a_key_given_twice_is_refused_naming_it() {
    let dir = temp_dir("scene-duplicate");
    let p = dir.join("twice.json");
    std::fs::write(
        &p,
        r#"{"kind": "asperity", "delta_max": [1e-8], "contact": {"radius": 4e-6, "radius": 5e-6}}"#,
    )
    .unwrap();
    let out = stiction(&["asperity", "--scene", p.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("twice.json") && err.contains("duplicate key `contact.radius`"),
        "{err}"
    );
}

/// `-` is not taken as a file name for `--plot` or `--out`: refused with a message, and no
/// file named `-` appears.
#[test]
fn a_dash_as_an_output_path_is_refused_and_writes_no_file_named_dash() {
    let dir = temp_dir("dash");
    for args in [
        &["asperity", "--plot", "-"][..],
        &["switch", "--out", "-"][..],
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_stiction"))
            .args(args)
            .current_dir(&dir)
            .output()
            .expect("run stiction");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(args[1]) && err.contains("standard output"),
            "{err}"
        );
        assert!(!dir.join("-").exists(), "{args:?} wrote a file named -");
    }
}

/// Help that cannot be written (standard output on a full device) exits 2 with a message
/// on standard error, not 1 (a numerical failure) in silence.
#[test]
fn help_into_a_full_device_exits_2_with_a_message() {
    if !Path::new("/dev/full").exists() {
        return;
    }
    for args in [
        &["--help"][..],
        &["switch", "--help"][..],
        &["--version"][..],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_stiction"))
            .args(args)
            .stdout(full)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("standard output"), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// An `--out` folder that cannot be made is named as the user gave it, never as the hidden
/// staging folder beside it. (Permission bits do not stop root, so the folder is asked for
/// in /proc, where no one can make one.)
#[test]
fn an_out_folder_that_cannot_be_made_is_named_as_given() {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let dir = temp_dir("out-unwritable");
    let map = dir.join("rough.txt");
    let rows: Vec<String> = (0..8)
        .map(|j| {
            (0..8)
                .map(|i| {
                    format!(
                        "{}",
                        ((i * 7 + j * 13) % 5) as f64 - 2.0 + 0.1 * (i * j % 3) as f64
                    )
                })
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    std::fs::write(
        &map,
        format!(
            "# spacing = 10 nm\n# height_unit = nm\n{}\n",
            rows.join("\n")
        ),
    )
    .unwrap();
    let target = format!("/proc/stiction-tests-out-{}", std::process::id());
    let out = stiction(&[
        "topography",
        map.to_str().unwrap(),
        "--out",
        target.as_str(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(&format!("cannot write {target}:")), "{err}");
    assert!(!err.contains(".new-"), "the staging folder is named: {err}");
}
