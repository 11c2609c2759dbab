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
use contact_law::{ContactLaw, Path, State};
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
            SCL_PATH_APPROACH,
            SCL_PATH_RETRACT,
            SCL_STATE_TOUCHED,
            SCL_STATE_TURNED,
            SCL_ABI_VERSION,
            SCL_ABI_VERSION,
        ]
    );

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
    for (i, c) in cmds.iter().enumerate() {
        match c {
            Cmd::Eval(d) => {
                let f = next("e");
                let before = state;
                match law.pressure(*d, &mut state) {
                    Ok((p, t)) => {
                        ok += 1;
                        assert_eq!(f[0], code(SCL_OK), "command {i}: e {d:e}");
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
                        assert_eq!(f[0], code(SCL_OK), "command {i}");
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
                assert_eq!(
                    f,
                    [
                        code(SCL_OK),
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
}

#[test]
fn the_c_program_reports_a_corrupted_law_file_by_its_json_path() {
    let (file, _) = law_file();
    let exe = compile_driver();
    let text = std::fs::read_to_string(file).unwrap();
    let bad = tmp().join("bad-version.json");
    std::fs::write(&bad, text.replacen("\"version\": 1", "\"version\": 2", 1)).unwrap();
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
        stderr.contains("version") && stderr.contains('2'),
        "{stderr}"
    );
}

#[test]
fn the_c_program_refuses_a_law_file_with_a_duplicated_key() {
    let (file, _) = law_file();
    let exe = compile_driver();
    let text = std::fs::read_to_string(file).unwrap();
    let bad = tmp().join("duplicated-version.json");
    let dup = text.replacen("\"version\": 1,", "\"version\": 1,\n  \"version\": 2,", 1);
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
