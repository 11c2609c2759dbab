//! The C ABI seen from C: a C program (`tests/c/driver.c`) is compiled with the system C
//! compiler against `include/stiction_contact_law.h` and this crate's static library, run
//! on a law tabulated here from the analytic toy law, and every number it prints is
//! compared with the Rust evaluator bit for bit.
//!
//! The static library is the one cargo builds for this crate's own tests (the `lib` target
//! is compiled with all its crate types, `staticlib` included, into the directory of the
//! test executable); no nested cargo call.

use contact_law::tabulate::{tabulate, Tabulation};
use contact_law::toy::ToyLaw;
use contact_law::{ContactLaw, Path, Region, State};
use contact_law_capi::*;
use std::io::Write;
use std::path::{Path as FsPath, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;

const LIB: &str = "libcontact_law_capi.a";

/// The static library built with this test: next to the test executable (target/<profile>/
/// deps), or one level up; the newest if several.
fn static_lib() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    let deps = exe.parent().expect("test executable directory");
    let mut found: Vec<PathBuf> = Vec::new();
    for dir in [deps, deps.parent().unwrap_or(deps)] {
        if let Ok(entries) = std::fs::read_dir(dir) {
            for e in entries.flatten() {
                let name = e.file_name().to_string_lossy().into_owned();
                if name == LIB || (name.starts_with("libcontact_law_capi-") && name.ends_with(".a"))
                {
                    found.push(e.path());
                }
            }
        }
    }
    found.sort_by_key(|p| std::fs::metadata(p).and_then(|m| m.modified()).ok());
    found.pop().unwrap_or_else(|| {
        panic!(
            "{LIB} not found in {} or its parent: cargo should have built the staticlib of \
             contact-law-capi for its tests",
            deps.display()
        )
    })
}

/// A folder of this test process's own: test runners that start a process per test would
/// otherwise write the same law file and driver at once.
fn tmp() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("contact-law-capi")
        .join(std::process::id().to_string())
}

/// The law file (tabulated once per test process) and the law read back from it.
fn law_file() -> &'static (PathBuf, ContactLaw) {
    static LAW: OnceLock<(PathBuf, ContactLaw)> = OnceLock::new();
    LAW.get_or_init(|| {
        let dir = tmp();
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("law.json");
        let law = tabulate(&ToyLaw::default(), &Tabulation::adaptive(1.5e-9, 15e-9)).unwrap();
        law.write_json(&file).unwrap();
        let back = ContactLaw::from_path(&file).unwrap();
        (file, back)
    })
}

/// The driver, compiled once per test process (tests run in parallel threads).
fn compile_driver() -> PathBuf {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(compile).clone()
}

fn compile() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let out = tmp().join("driver");
    std::fs::create_dir_all(tmp()).unwrap();
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let lib = static_lib();
    let output = Command::new(&cc)
        .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-I"])
        .arg(manifest.join("include"))
        .arg(manifest.join("tests/c/driver.c"))
        .arg(&lib)
        .args(["-lpthread", "-ldl", "-lm", "-lrt", "-lgcc_s", "-lc", "-o"])
        .arg(&out)
        .output()
        .unwrap_or_else(|e| panic!("cannot run the C compiler `{cc}`: {e}"));
    assert!(
        output.status.success(),
        "compiling driver.c against {} failed:\n{}",
        lib.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    out
}

fn run_driver(exe: &FsPath, law: &FsPath, commands: &str) -> Vec<String> {
    let mut child = Command::new(exe)
        .arg(law)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(commands.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "driver failed: {}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect()
}

/// A C `%.17g` number read back exactly.
fn num(s: &str) -> f64 {
    s.parse().unwrap_or_else(|_| panic!("not a number: {s:?}"))
}

fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits()
}

struct Lcg(u64);
impl Lcg {
    fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

enum Cmd {
    Eval(f64),
    Stateless(f64, f64, i32),
    Exact,
    Reset,
}

fn commands() -> Vec<Cmd> {
    use Cmd::*;
    // a scripted history: approach from far, deepen, retract, partial reload, retract
    // again, deepen further, out-of-range and invalid queries
    let mut c = vec![
        Eval(2e-8),
        Eval(9e-9),
        Eval(6e-9),
        Eval(3e-9),
        Exact,
        Eval(3.05e-9),
        Eval(3.3e-9),
        Eval(4e-9),
        Exact,
        Eval(3.6e-9),
        Eval(3.2e-9),
        Exact,
        Eval(3.5e-9),
        Exact,
        Eval(2.5e-9),
        Eval(1e-9),
        Eval(f64::NAN),
        Eval(f64::INFINITY),
        Eval(2.6e-9),
        Eval(3e-8),
        Exact,
        Reset,
        Eval(5e-9),
        Stateless(3e-9, f64::INFINITY, 0),
        Stateless(3.2e-9, 3e-9, 1),
        Stateless(3.2e-9, 3e-9, 0),
        Stateless(2.9e-9, 3e-9, 1),
        Stateless(1e-9, 3e-9, 1),
        Stateless(3e-9, 1e-9, 0),
        Stateless(f64::NAN, 3e-9, 0),
        Stateless(3.3e-9, 3.0000001e-9, 1),
        Stateless(1.6e-8, 1.55e-8, 1),
        Stateless(2e-8, 1.9e-8, 0),
        Reset,
    ];
    // a random walk in and out of contact, with resets
    let mut rng = Lcg(7);
    let mut d = 2e-8;
    for i in 0..600 {
        let step = (rng.uniform() - 0.55) * 1.2e-9;
        d = (d + step).clamp(1.4e-9, 2.2e-8);
        c.push(Eval(d));
        if i % 97 == 96 {
            c.push(Exact);
            c.push(Reset);
        }
    }
    for _ in 0..300 {
        let d_min = 1.45e-9 + 14e-9 * rng.uniform();
        let d = d_min + (rng.uniform() - 0.1) * 9e-9;
        c.push(Stateless(d, d_min, (rng.uniform() < 0.5) as i32));
    }
    c
}

fn text(cmds: &[Cmd]) -> String {
    let mut s = String::new();
    for c in cmds {
        match c {
            Cmd::Eval(d) => s += &format!("e {d:e}\n"),
            Cmd::Stateless(d, m, p) => s += &format!("s {d:e} {m:e} {p}\n"),
            Cmd::Exact => s += "x\n",
            Cmd::Reset => s += "r\n",
        }
    }
    s
}

#[test]
fn a_c_program_agrees_with_the_rust_evaluator_bit_for_bit() {
    let (file, law) = law_file();
    let exe = compile_driver();
    let cmds = commands();
    let lines = run_driver(&exe, file, &text(&cmds));
    let mut it = lines.iter();
    let mut next = |tag: &str| -> Vec<String> {
        let l = it.next().unwrap_or_else(|| panic!("missing line {tag}"));
        let f: Vec<String> = l.split_whitespace().map(str::to_string).collect();
        assert_eq!(f[0], tag, "line {l:?}");
        f[1..].to_vec()
    };

    // struct layout and constants, as the C compiler sees them
    let layout: Vec<usize> = next("layout").iter().map(|v| v.parse().unwrap()).collect();
    assert_eq!(
        layout,
        [
            std::mem::size_of::<SclState>(),
            std::mem::offset_of!(SclState, d_min),
            std::mem::offset_of!(SclState, last_d),
            std::mem::offset_of!(SclState, d_turn),
            std::mem::offset_of!(SclState, path),
            std::mem::offset_of!(SclState, flags),
        ]
    );
    let consts: Vec<i32> = next("consts").iter().map(|v| v.parse().unwrap()).collect();
    assert_eq!(
        consts,
        [
            SCL_OK,
            SCL_ERR_NULL,
            SCL_ERR_IO,
            SCL_ERR_FORMAT,
            SCL_ERR_OUT_OF_RANGE,
            SCL_ERR_INVALID,
            SCL_ERR_INTERNAL,
            SCL_BEYOND_REACH,
            SCL_ABOVE_TABLE,
            SCL_PATH_APPROACH,
            SCL_PATH_RETRACT,
            SCL_STATE_TOUCHED,
            SCL_STATE_TURNED,
            SCL_ABI_VERSION,
            SCL_ABI_VERSION,
        ]
    );
    // the statuses with a value: the success and the two regions outside the measured one
    assert_eq!(next("has_value"), ["1", "1", "1", "0", "0"]);
    assert_eq!(SCL_ABI_VERSION, 2);

    // error paths: codes, untouched outputs, messages
    let code = |v: i32| v.to_string();
    assert_eq!(
        next("load_null"),
        [code(SCL_ERR_NULL), "1".into(), "1".into()]
    );
    assert_eq!(next("load_null_out"), [code(SCL_ERR_NULL)]);
    assert_eq!(
        next("load_missing"),
        [code(SCL_ERR_IO), "1".into(), "1".into()]
    );
    assert_eq!(next("copy"), ["1", "1", "1"]);
    assert_eq!(next("copy_null"), ["1"]);
    assert_eq!(next("load"), [code(SCL_OK)]);
    assert_eq!(next("eval_null"), vec![code(SCL_ERR_NULL); 4]);
    assert_eq!(next("stateless_null"), vec![code(SCL_ERR_NULL); 2]);
    let range = next("range");
    let (lo, hi) = law.d_min_range();
    assert_eq!(range[0], code(SCL_OK));
    assert!(same(num(&range[1]), lo) && same(num(&range[2]), hi));
    assert_eq!(range[3], code(SCL_ERR_NULL));
    assert_eq!(next("exact_null"), [code(SCL_ERR_NULL)]);
    assert_eq!(next("bad_state"), [code(SCL_ERR_INVALID)]);
    assert_eq!(next("bad_path"), [code(SCL_ERR_INVALID)]);

    // the commands, against the Rust evaluator
    let mut state = State::VIRGIN;
    let (mut ok, mut failed) = (0, 0);
    let mut regions: Vec<Region> = Vec::new();
    for (i, c) in cmds.iter().enumerate() {
        match c {
            Cmd::Eval(d) => {
                let f = next("e");
                let before = state;
                match law.step(*d, &mut state) {
                    Ok(e) => {
                        let (p, t) = (e.pressure, e.tangent);
                        ok += 1;
                        regions.push(e.region);
                        assert_eq!(f[0], code(region_status(e.region)), "command {i}: e {d:e}");
                        assert!(
                            same(num(&f[1]), p) && same(num(&f[2]), t),
                            "command {i}: e {d:e}: C {f:?}, Rust {p:e} {t:e}"
                        );
                        let cs = SclState::from_state(&state);
                        assert!(
                            same(num(&f[3]), cs.d_min)
                                && same(num(&f[4]), cs.last_d)
                                && same(num(&f[5]), cs.d_turn),
                            "command {i}: state {f:?} vs {cs:?}"
                        );
                        assert_eq!(
                            (f[6].parse::<i32>().unwrap(), f[7].parse::<i32>().unwrap()),
                            (cs.path, cs.flags)
                        );
                    }
                    Err(e) => {
                        failed += 1;
                        assert_eq!(state, before);
                        assert_eq!(f[0], code(status_code(&e)), "command {i}: e {d:e}: {e}");
                        // the C state is unchanged too
                        let cs = SclState::from_state(&state);
                        assert!(same(num(&f[3]), cs.d_min) && same(num(&f[4]), cs.last_d));
                    }
                }
            }
            Cmd::Stateless(d, m, p) => {
                let f = next("s");
                let path = if *p == 0 {
                    Path::Approach
                } else {
                    Path::Retract
                };
                match law.evaluate(*d, *m, path) {
                    Ok(e) => {
                        ok += 1;
                        regions.push(e.region);
                        assert_eq!(f[0], code(region_status(e.region)), "command {i}");
                        assert!(
                            same(num(&f[1]), e.pressure)
                                && same(num(&f[2]), e.tangent)
                                && same(num(&f[3]), e.d_min),
                            "command {i}: s {d:e} {m:e} {p}: C {f:?}, Rust {e:?}"
                        );
                    }
                    Err(e) => {
                        failed += 1;
                        assert_eq!(f[0], code(status_code(&e)), "command {i}: {e}");
                    }
                }
            }
            Cmd::Exact => {
                let f = next("x");
                let region = if state.is_virgin() {
                    Region::Measured
                } else {
                    law.history_region(state.d_min)
                };
                assert_ne!(region, Region::BelowTable, "command {i}");
                assert_eq!(
                    f,
                    [
                        code(region_status(region)),
                        (law.is_history_exact(&state) as i32).to_string()
                    ],
                    "command {i}"
                );
            }
            Cmd::Reset => {
                next("r");
                state = State::VIRGIN;
            }
        }
    }
    assert!(it.next().is_none(), "extra output from the driver");
    // the script exercised both outcomes, and mostly successes
    assert!(ok > 700 && failed >= 6, "ok {ok}, failed {failed}");
    // and every region with a value, each with its own status
    for r in [Region::Measured, Region::BeyondReach, Region::AboveTable] {
        assert!(regions.contains(&r), "no evaluation in {r:?}");
    }
}

#[test]
fn the_c_program_reports_a_corrupted_law_file_by_its_json_path() {
    let (file, _) = law_file();
    let exe = compile_driver();
    let text = std::fs::read_to_string(file).unwrap();
    let bad = tmp().join("bad-version.json");
    std::fs::write(&bad, text.replacen("\"version\": 2", "\"version\": 3", 1)).unwrap();
    let mut child = Command::new(&exe)
        .arg(&bad)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdin.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains(&format!("load {SCL_ERR_FORMAT}")),
        "{stdout}"
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("version") && stderr.contains('3'),
        "{stderr}"
    );
}

#[test]
fn the_c_program_refuses_a_law_file_with_a_duplicated_key() {
    let (file, _) = law_file();
    let exe = compile_driver();
    let text = std::fs::read_to_string(file).unwrap();
    let bad = tmp().join("duplicated-version.json");
    let dup = text.replacen("\"version\": 2,", "\"version\": 2,\n  \"version\": 3,", 1);
    assert_ne!(dup, text);
    std::fs::write(&bad, dup).unwrap();
    let out = Command::new(&exe)
        .arg(&bad)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains(&format!("load {SCL_ERR_FORMAT}")),
        "{stdout}"
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("version") && stderr.contains("duplicated key"),
        "{stderr}"
    );
}

/// Function names declared in the header and exported by the library are the same set.
#[test]
fn the_header_declares_exactly_the_exported_functions() {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let header = std::fs::read_to_string(manifest.join("include/stiction_contact_law.h")).unwrap();
    let source = std::fs::read_to_string(manifest.join("src/lib.rs")).unwrap();
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect()
    };
    let mut declared: Vec<String> = Vec::new();
    for line in header.lines().map(str::trim) {
        if line.starts_with('/') || line.starts_with('*') || line.starts_with('#') {
            continue;
        }
        for (i, _) in line.match_indices("scl_") {
            let name = ident(&line[i..]);
            if line[i + name.len()..].starts_with('(') {
                declared.push(name);
            }
        }
    }
    let mut exported: Vec<String> = Vec::new();
    let mut lines = source.lines().peekable();
    while let Some(l) = lines.next() {
        if l.trim() == "#[no_mangle]" {
            let sig = lines.next().unwrap_or_default();
            let at = sig.find("fn ").expect("a function after #[no_mangle]");
            exported.push(ident(&sig[at + 3..]));
        }
    }
    declared.sort();
    exported.sort();
    assert!(!exported.is_empty());
    assert_eq!(declared, exported);
}

/// The header is also valid C++ (extern "C" block), when a C++ compiler is installed.
#[test]
fn the_header_compiles_as_cpp() {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let cxx = std::env::var("CXX").unwrap_or_else(|_| "c++".into());
    let src = tmp().join("header.cpp");
    std::fs::create_dir_all(tmp()).unwrap();
    std::fs::write(
        &src,
        "#include \"stiction_contact_law.h\"\nint main() { scl_state s; scl_state_init(&s); return s.flags; }\n",
    )
    .unwrap();
    let out = match Command::new(&cxx)
        .args([
            "-std=c++11",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-fsyntax-only",
            "-I",
        ])
        .arg(manifest.join("include"))
        .arg(&src)
        .output()
    {
        Ok(o) => o,
        Err(_) => {
            eprintln!("no C++ compiler `{cxx}`: skipped");
            return;
        }
    };
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Every evaluation outside the measured region has a status of its own, with its value
/// written (above the table, beyond the reach), or an error without one (below the table);
/// the history query flags a shallower history than the table.
#[test]
fn the_c_abi_flags_every_point_outside_the_measured_region() {
    let (file, law) = law_file();
    let path = std::ffi::CString::new(file.to_str().unwrap()).unwrap();
    let mut h = std::ptr::null_mut();
    assert_eq!(unsafe { scl_law_load(path.as_ptr(), &mut h) }, SCL_OK);
    let (lo, hi) = law.d_min_range();
    let top = law.virgin().reach();
    let stateless = |d: f64, d_min: f64, p: i32| {
        let (mut pr, mut t, mut dm) = (f64::NAN, f64::NAN, f64::NAN);
        let rc = unsafe { scl_law_eval_stateless(h, d, d_min, p, &mut pr, &mut t, &mut dm) };
        (rc, pr, t, dm)
    };
    // inside: OK
    let mid = 0.5 * (lo + hi);
    let (rc, p, ..) = stateless(mid + 1e-10, mid, SCL_PATH_RETRACT);
    assert_eq!(rc, SCL_OK);
    assert!(p.is_finite());
    // a history shallower than the table, within reach: a value, flagged
    let above = hi + 0.3 * (top - hi);
    let (rc, p, t, dm) = stateless(above + 1e-11, above, SCL_PATH_RETRACT);
    assert_eq!(rc, SCL_ABOVE_TABLE, "{}", last_error());
    assert!(p.is_finite() && t.is_finite() && dm == above);
    // beyond the reach of the branch: exactly zero, flagged
    let reach = law.reach(mid, Path::Retract).unwrap();
    let (rc, p, t, _) = stateless(reach + 1e-9, mid, SCL_PATH_RETRACT);
    assert_eq!((rc, p, t), (SCL_BEYOND_REACH, 0.0, 0.0));
    // deeper than the table: an error, nothing written
    let (rc, p, ..) = stateless(lo, 0.5 * lo, SCL_PATH_APPROACH);
    assert_eq!(rc, SCL_ERR_OUT_OF_RANGE);
    assert!(p.is_nan());
    assert!(last_error().contains("below_table"), "{}", last_error());

    // stateful: a touch that stops above the table, then its retraction
    let mut st = SclState::default();
    let (mut p, mut t) = (0.0, 0.0);
    let mut codes = Vec::new();
    let mut exact = -1;
    for d in [1.2 * top, above, above + 0.01 * (top - above)] {
        codes.push(unsafe { scl_law_eval(h, d, &mut st, &mut p, &mut t) });
    }
    assert_eq!(codes, [SCL_BEYOND_REACH, SCL_OK, SCL_ABOVE_TABLE]);
    // the history is one number and exact, but not in the table: flagged, not OK
    assert_eq!(
        unsafe { scl_law_history_exact(h, &st, &mut exact) },
        SCL_ABOVE_TABLE
    );
    assert_eq!(exact, 1);
    // a state deeper than the table (written by hand): an error
    let deep = SclState {
        d_min: 0.5 * lo,
        last_d: 0.5 * lo,
        flags: SCL_STATE_TOUCHED,
        ..SclState::default()
    };
    exact = -1;
    assert_eq!(
        unsafe { scl_law_history_exact(h, &deep, &mut exact) },
        SCL_ERR_OUT_OF_RANGE
    );
    assert_eq!(exact, -1);
    // a virgin state: OK
    assert_eq!(
        unsafe { scl_law_history_exact(h, &SclState::default(), &mut exact) },
        SCL_OK
    );
    unsafe { scl_law_free(h) };
}

fn last_error() -> String {
    unsafe { std::ffi::CStr::from_ptr(scl_last_error()) }
        .to_string_lossy()
        .into_owned()
}

/// The Fortran FE client (`tests/fortran/uinter.f90`, a UINTER-like routine through
/// `bind(C)`: gap in, pressure and tangent out, the state in the caller's real array),
/// compiled with gfortran when it is installed (required when STICTION_REQUIRE_FORTRAN is
/// set, as `.ci/fortran` does), and compared with the Rust evaluator bit for bit over Newton
/// iterations (not committed) and converged increments (committed).
#[test]
fn a_fortran_uinter_agrees_with_the_rust_evaluator_bit_for_bit() {
    let fc = std::env::var("FC").unwrap_or_else(|_| "gfortran".into());
    let required = std::env::var_os("STICTION_REQUIRE_FORTRAN").is_some();
    if Command::new(&fc).arg("--version").output().is_err() {
        assert!(
            !required,
            "STICTION_REQUIRE_FORTRAN is set but the Fortran compiler `{fc}` cannot be run"
        );
        eprintln!("no Fortran compiler `{fc}`: skipped (set FC, or install gfortran)");
        return;
    }
    let (file, law) = law_file();
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let dir = tmp().join("fortran");
    std::fs::create_dir_all(&dir).unwrap();
    let exe = dir.join("uinter");
    let out = Command::new(&fc)
        .args(["-std=f2008", "-Wall", "-Werror", "-J"])
        .arg(&dir)
        .arg(manifest.join("tests/fortran/uinter.f90"))
        .arg(static_lib())
        .args(["-lpthread", "-ldl", "-lm", "-o"])
        .arg(&exe)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "compiling uinter.f90 failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // increments of a loading history with two Newton iterations each (the first ones
    // overshoot and are not committed), in and out of contact, beyond the table's
    // shallowest history and back, with resets
    let mut rng = Lcg(11);
    let mut script = String::new();
    let mut g = 2e-8;
    for i in 0..500 {
        let step = (rng.uniform() - 0.55) * 1.2e-9;
        g = (g + step).clamp(1.6e-9, 2.4e-8);
        script += &format!("i {:e}\n", g + 0.3e-9 * (rng.uniform() - 0.5));
        script += &format!("g {g:e}\n");
        if i % 83 == 82 {
            script += "r\n";
        }
    }
    let lines = run_driver(&exe, file, &script);
    assert_eq!(lines[0], format!("abi {SCL_ABI_VERSION}"));
    let mut state = State::VIRGIN;
    let mut seen = Vec::new();
    let mut errors = 0;
    let mut k = 1;
    for cmd in script.lines() {
        let line = &lines[k];
        k += 1;
        if cmd == "r" {
            assert_eq!(line, "r");
            state = State::VIRGIN;
            continue;
        }
        let f: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(f[0], &cmd[..1], "{line}");
        let gap: f64 = cmd[2..].parse().unwrap();
        let mut trial = state;
        let v: Vec<f64> = f[2..].iter().map(|s| num(s)).collect();
        // an error leaves the caller's state and gives no value
        let (rc, p, t) = match law.step(gap, &mut trial) {
            Ok(e) => {
                seen.push(e.region);
                (region_status(e.region), e.pressure, e.tangent)
            }
            Err(e) => {
                errors += 1;
                (status_code(&e), 0.0, 0.0)
            }
        };
        assert_eq!(f[1], rc.to_string(), "{cmd}: {line}");
        let cs = SclState::from_state(&trial);
        let want = [
            p,
            t,
            cs.d_min,
            cs.last_d,
            cs.d_turn,
            f64::from(cs.path),
            f64::from(cs.flags),
        ];
        for (a, b) in v.iter().zip(want) {
            assert!(same(*a, b), "{cmd}: Fortran {line}, Rust {want:?}");
        }
        if cmd.starts_with('g') {
            state = trial;
        }
    }
    assert_eq!(k, lines.len(), "extra output from the Fortran client");
    for r in [Region::Measured, Region::BeyondReach] {
        assert!(seen.contains(&r), "no evaluation in {r:?}");
    }
    // some iterations went deeper than the table: refused, the state kept
    assert!(errors > 0 && errors < 50, "{errors} errors");
}

/// The header states what the law does outside the measured region and what an FE user
/// should do with a positive retract tangent (issue 24, item 3).
#[test]
fn the_header_states_the_regions_and_the_positive_retract_tangent() {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let header = std::fs::read_to_string(manifest.join("include/stiction_contact_law.h")).unwrap();
    // the comments as running text: line breaks and their leading " * " are spaces
    let header = header
        .lines()
        .map(|l| l.trim().trim_start_matches("* ").trim_start_matches('*'))
        .collect::<Vec<_>>()
        .join(" ");
    for needle in [
        "SCL_BEYOND_REACH = 7",
        "SCL_ABOVE_TABLE = 8",
        "SCL_HAS_VALUE",
        "positive_retract_tangent",
        "negative unloading stiffness",
        "min(tangent, 0)",
        "reload = \"bounded\"",
        "#define SCL_ABI_VERSION 2",
    ] {
        assert!(
            header.contains(needle),
            "the header does not say {needle:?}"
        );
    }
}
