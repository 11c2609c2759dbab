//! Outputs never damage what is at their path (issue 21, D1 and D7): a FIFO, a character
//! device or a symbolic link at an output path is written through or refused, never
//! replaced by a regular file; temporary files of interrupted runs do not accumulate.

mod common;

use common::{stiction, temp_dir};
use std::fs;
use std::io::Read;
use std::os::unix::fs::{symlink, FileTypeExt};
use std::path::Path;
use std::process::Command;

fn mkfifo(p: &Path) {
    let ok = Command::new("mkfifo").arg(p).status().expect("mkfifo");
    assert!(ok.success());
}

fn is_fifo(p: &Path) -> bool {
    fs::symlink_metadata(p)
        .map(|m| m.file_type().is_fifo())
        .unwrap_or(false)
}

#[test]
fn a_plot_into_a_fifo_with_a_reader_streams_through_it_and_the_fifo_stays() {
    let dir = temp_dir("fifo-reader");
    let fifo = dir.join("plot.svg");
    mkfifo(&fifo);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || {
            let mut s = String::new();
            fs::File::open(&fifo)
                .expect("open fifo")
                .read_to_string(&mut s)
                .expect("read fifo");
            s
        })
    };
    // the reader must be waiting before the writer looks for one
    std::thread::sleep(std::time::Duration::from_millis(300));
    let out = stiction(&["asperity", "--plot", fifo.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = reader.join().unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(is_fifo(&fifo), "the FIFO was replaced");
}

#[test]
fn a_plot_into_a_fifo_nobody_reads_is_refused_at_once_and_the_fifo_stays() {
    let dir = temp_dir("fifo-alone");
    let fifo = dir.join("plot.svg");
    mkfifo(&fifo);
    let started = std::time::Instant::now();
    let out = stiction(&["asperity", "--plot", fifo.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("FIFO") && err.contains("plot.svg"), "{err}");
    assert!(is_fifo(&fifo), "the FIFO was replaced");
    // refused at once, not after waiting for a reader
    assert!(started.elapsed().as_secs() < 30);
    let leftovers: Vec<_> = fs::read_dir(&dir).unwrap().flatten().collect();
    assert_eq!(leftovers.len(), 1, "temporary files left: {leftovers:?}");
}

#[test]
fn a_plot_into_a_character_device_is_written_in_place() {
    // /dev/null is a character device on every Unix: written to, never replaced
    let before = fs::metadata("/dev/null").unwrap();
    assert!(before.file_type().is_char_device());
    let out = stiction(&["asperity", "--plot", "/dev/null"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let after = fs::symlink_metadata("/dev/null").unwrap();
    assert!(after.file_type().is_char_device());
}

#[test]
fn a_plot_into_dev_stdout_goes_to_standard_output() {
    let out = stiction(&["asperity", "--format", "json", "--plot", "/dev/stdout"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("<svg") && text.contains("</svg>"),
        "no SVG on stdout"
    );
}

#[test]
fn a_symlinked_plot_is_followed_to_its_target_and_the_link_stays() {
    let dir = temp_dir("plot-link");
    let target = dir.join("target.svg");
    fs::write(&target, "old").unwrap();
    let link = dir.join("link.svg");
    symlink("target.svg", &link).unwrap();
    let out = stiction(&["asperity", "--plot", link.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(fs::read_to_string(&target).unwrap().starts_with("<svg"));
}

#[test]
fn a_dangling_symlinked_plot_creates_its_target() {
    let dir = temp_dir("plot-dangling");
    let link = dir.join("link.svg");
    symlink("made.svg", &link).unwrap();
    let out = stiction(&["asperity", "--plot", link.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(fs::read_to_string(dir.join("made.svg"))
        .unwrap()
        .starts_with("<svg"));
}

#[test]
fn a_symlinked_out_folder_is_followed_and_the_link_stays() {
    let dir = temp_dir("out-link");
    let real = dir.join("real");
    fs::create_dir(&real).unwrap();
    let link = dir.join("results");
    symlink("real", &link).unwrap();
    let out = stiction(&[
        "switch",
        "--cycles",
        "1",
        "--accuracy",
        "fast",
        "--out",
        link.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(real.join("switch.json").is_file());
    assert!(link.join("cycles.csv").is_file());
}

#[test]
fn an_out_path_that_is_a_file_or_a_device_is_refused_before_computing() {
    let dir = temp_dir("out-file");
    let file = dir.join("taken");
    fs::write(&file, "keep").unwrap();
    for path in [file.to_str().unwrap(), "/dev/null"] {
        let out = stiction(&["switch", "--cycles", "1", "--out", path]);
        assert_eq!(out.status.code(), Some(2), "{path}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(path) && err.contains("not a folder"), "{err}");
    }
    assert_eq!(fs::read_to_string(&file).unwrap(), "keep");
    assert!(fs::metadata("/dev/null")
        .unwrap()
        .file_type()
        .is_char_device());
}

#[test]
fn temporary_folders_of_dead_processes_are_swept_by_the_next_run() {
    let dir = temp_dir("sweep");
    // pid 2^22 + 1 is above Linux's pid_max: no such process can exist
    let stale = dir.join(".out.new-4194305-123");
    fs::create_dir(&stale).unwrap();
    fs::write(stale.join("switch.json"), "partial").unwrap();
    let stale_file = dir.join(".plot.svg.new-4194305-9");
    fs::write(&stale_file, "partial").unwrap();
    // a temporary of a running process (this test) is left alone
    let live = dir.join(format!(".out.new-{}-1", std::process::id()));
    fs::create_dir(&live).unwrap();
    let out = stiction(&[
        "switch",
        "--cycles",
        "1",
        "--accuracy",
        "fast",
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!stale.exists(), "stale staging folder left");
    assert!(live.exists(), "a live process's folder was removed");
    let out = stiction(&["asperity", "--plot", dir.join("plot.svg").to_str().unwrap()]);
    assert!(out.status.success());
    assert!(!stale_file.exists(), "stale temporary file left");
}
