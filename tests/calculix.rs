//! Issue 46 item 5: the exported pressure-overclosure table inside CalculiX. A law of the
//! paper's switch is tabulated, exported with `stiction law export --format calculix` (um,
//! MPa) and included in a small deck: one elastic C3D8 block pressed, displacement
//! controlled, onto one fixed C3D8 base through node-to-surface contact with
//! `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR`. At every increment the overclosure
//! CalculiX reports (`*CONTACT PRINT` CDIS) and both the contact pressure it reports (CSTR,
//! every slave node) and the force it transmits (the reaction at the block's top over the
//! block's area) must agree with the law's virgin loading at d = d_ref - h within the
//! export's tolerance, 1e-3 in the law's own error metric |p - p_law| / (|p_law| +
//! |p_pull_out| + floor) (crates/contact-law/src/export.rs); and the pressure must be the
//! rows read linearly at the printed overclosure, to the rounding of the `.dat`'s 7 digits
//! (CalculiX resamples a table of more than 200 rows: docs/contact-law.md section 6.4).
//!
//! Needs `ccx` (Debian's `calculix-ccx`, 2.20; another binary through `CCX`): skipped with
//! a message when it cannot be run, unless `STICTION_REQUIRE_CCX` is set, as `.ci/calculix`
//! does, which makes a missing `ccx` a failure.

mod common;
use common::{json, stiction, temp_dir};
use contact_law::{ContactLaw, EXPORT_TOLERANCE};
use std::collections::BTreeMap;
use std::process::Command;

/// Histories 7.6 to 9.2 nm around the paper switch's end of impact, as in tests/law.rs:
/// the virgin loading exported does not depend on them, and a short grid is quick.
const GRID: &str = "7.6e-9:9.2e-9:13";

/// The block's Young's modulus (MPa, ruthenium's 410 GPa) and Poisson's ratio: under the
/// table's last pressure, 283 MPa, it shortens by about 0.5 nm, so that the overclosure
/// CalculiX finds is not the displacement applied.
const BLOCK: (f64, f64) = (410e3, 0.3);

/// Increments below the rise of the law (to a quarter of the table's last overclosure) and
/// through it (to 0.995 of the last overclosure: the block's shortening keeps every
/// increment inside the table, where CalculiX holds the last pressure beyond it).
const INCREMENTS: (usize, usize) = (2, 50);

/// The deck (um, MPa, uN): a 1 x 1 x 1 um block (nodes 11-18) on a 2 x 2 x 1 um base
/// (nodes 1-8, fixed), touching at z = 0 (overclosure 0 is d = d_ref); the block held
/// laterally (uniaxial strain: a uniform pressure), its top moved down by `first` in
/// `INCREMENTS.0` increments, then by `last` in `INCREMENTS.1`. Numbers are written in at
/// most 20 characters: CalculiX refuses a longer field of a card (`*ERROR reading
/// *BOUNDARY`), and still ends with "Job finished" and exit status 0.
fn deck(first: f64, last: f64) -> String {
    let (e, nu) = BLOCK;
    let (n1, n2) = INCREMENTS;
    format!(
        "** stiction: the exported contact law in a block pressed onto a base (um, MPa)
*NODE
1, -0.5, -0.5, -1
2, 1.5, -0.5, -1
3, 1.5, 1.5, -1
4, -0.5, 1.5, -1
5, -0.5, -0.5, 0
6, 1.5, -0.5, 0
7, 1.5, 1.5, 0
8, -0.5, 1.5, 0
11, 0, 0, 0
12, 1, 0, 0
13, 1, 1, 0
14, 0, 1, 0
15, 0, 0, 1
16, 1, 0, 1
17, 1, 1, 1
18, 0, 1, 1
*ELEMENT, TYPE=C3D8, ELSET=BASE
1, 1, 2, 3, 4, 5, 6, 7, 8
*ELEMENT, TYPE=C3D8, ELSET=BLOCK
2, 11, 12, 13, 14, 15, 16, 17, 18
*NSET, NSET=NBASE
1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=NBLOCK
11, 12, 13, 14, 15, 16, 17, 18
*NSET, NSET=NTOP
15, 16, 17, 18
*MATERIAL, NAME=FILM
*ELASTIC
{e}, {nu}
*SOLID SECTION, ELSET=BASE, MATERIAL=FILM
*SOLID SECTION, ELSET=BLOCK, MATERIAL=FILM
*SURFACE, NAME=SLAVE, TYPE=ELEMENT
2, S1
*SURFACE, NAME=MASTER, TYPE=ELEMENT
1, S2
*SURFACE INTERACTION, NAME=LAW
*INCLUDE, INPUT=contact.inp
*CONTACT PAIR, INTERACTION=LAW, TYPE=NODE TO SURFACE
SLAVE, MASTER
*BOUNDARY
NBASE, 1, 3
NBLOCK, 1, 2
*STEP, INC=1000
*STATIC, DIRECT
{s1}, 1.0
*BOUNDARY
NTOP, 3, 3, {first:.9e}
*NODE PRINT, NSET=NTOP, TOTALS=ONLY
RF
*CONTACT PRINT
CDIS, CSTR
*END STEP
*STEP, INC=1000
*STATIC, DIRECT
{s2}, 1.0
*BOUNDARY
NTOP, 3, 3, {last:.9e}
*END STEP
",
        s1 = 1.0 / n1 as f64,
        s2 = 1.0 / n2 as f64,
        first = -first,
        last = -last,
    )
}

/// One converged increment: the force on the block's top (uN, z), and per slave node the
/// normal relative displacement (um, negative in penetration) and the pressure (MPa).
#[derive(Default, Debug)]
struct Increment {
    force_z: Option<f64>,
    normal: Vec<f64>,
    pressure: Vec<f64>,
}

fn num(s: &str) -> f64 {
    s.parse()
        .unwrap_or_else(|_| panic!("not a number in the .dat: {s}"))
}

/// The `.dat` file's blocks, by their time (the line after a header is blank, the values
/// follow up to the next blank line).
fn read_dat(text: &str) -> BTreeMap<String, Increment> {
    let mut incs: BTreeMap<String, Increment> = BTreeMap::new();
    let lines: Vec<&str> = text.lines().collect();
    for (i, line) in lines.iter().enumerate() {
        let Some((head, time)) = line.split_once(" and time ") else {
            continue;
        };
        let values = lines[i + 1..]
            .iter()
            .skip_while(|l| l.trim().is_empty())
            .take_while(|l| !l.trim().is_empty())
            .map(|l| l.split_whitespace().collect::<Vec<_>>());
        let inc = incs.entry(time.trim().to_string()).or_default();
        if head.contains("total force") {
            let v: Vec<Vec<&str>> = values.collect();
            assert_eq!(v.len(), 1, "{head}");
            inc.force_z = Some(num(v[0][2]));
        } else if head.contains("relative contact displacement") {
            inc.normal.extend(values.map(|v| num(v[1])));
        } else if head.contains("contact stress") {
            inc.pressure.extend(values.map(|v| num(v[1])));
        }
    }
    incs
}

#[test]
fn calculix_reproduces_the_virgin_loading_from_the_exported_table() {
    let ccx = std::env::var("CCX").unwrap_or_else(|_| "ccx".into());
    let required = std::env::var_os("STICTION_REQUIRE_CCX").is_some();
    // `ccx -v` prints its version and exits with 201
    let version = Command::new(&ccx)
        .arg("-v")
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .filter(|v| v.contains("Version"));
    let Some(version) = version else {
        assert!(
            !required,
            "STICTION_REQUIRE_CCX is set but CalculiX `{ccx}` cannot be run"
        );
        eprintln!(
            "SKIPPED: no CalculiX `{ccx}` (install calculix-ccx, or set CCX; STICTION_REQUIRE_CCX=1 makes this a failure)"
        );
        return;
    };
    eprintln!("{version}");

    // the law and its table, through the command line
    let dir = temp_dir("calculix");
    let law_dir = dir.join("law");
    json(&stiction(&[
        "law",
        "--out",
        law_dir.to_str().unwrap(),
        "--d-min",
        GRID,
        "--format",
        "json",
    ]));
    let law_path = law_dir.join("law.json");
    let run = stiction(&[
        "law",
        "export",
        "--law",
        law_path.to_str().unwrap(),
        "--format",
        "calculix",
        "--out",
        dir.join("contact.inp").to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let block = std::fs::read_to_string(dir.join("contact.inp")).unwrap();
    assert!(block.lines().any(|l| l == "** units: um, MPa"));
    let d_ref: f64 = block
        .lines()
        .find_map(|l| l.strip_prefix("** d_ref = ")?.strip_suffix(" m"))
        .expect("a d_ref line")
        .parse()
        .unwrap();
    // the rows as CalculiX reads them: (overclosure um, pressure MPa)
    let rows: Vec<(f64, f64)> = block
        .lines()
        .skip_while(|l| !l.starts_with("*SURFACE BEHAVIOR"))
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(", ").map(num).collect();
            (v[1], v[0])
        })
        .collect();
    let h_last = rows.last().unwrap().0;
    // linear interpolation of the rows at h, and the steeper slope of the intervals beside
    let linear = |h: f64| -> (f64, f64) {
        let k = rows.partition_point(|r| r.0 <= h).clamp(1, rows.len() - 1);
        let ((a, pa), (b, pb)) = (rows[k - 1], rows[k]);
        let slope = |i: usize| (rows[i].1 - rows[i - 1].1) / (rows[i].0 - rows[i - 1].0);
        let steepest = (k.max(2) - 1..=(k + 1).min(rows.len() - 1))
            .map(|i| slope(i).abs())
            .fold(0.0, f64::max);
        (pa + (h - a) / (b - a) * (pb - pa), steepest)
    };

    // the deck, run
    std::fs::write(dir.join("block.inp"), deck(0.25 * h_last, 0.995 * h_last)).unwrap();
    let out = Command::new(&ccx)
        .arg("block")
        .current_dir(&dir)
        .env("OMP_NUM_THREADS", "1")
        .output()
        .expect("run ccx");
    let log = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && log.contains("Job finished") && !log.contains("*ERROR"),
        "ccx failed ({}):\n{log}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let incs = read_dat(&std::fs::read_to_string(dir.join("block.dat")).unwrap());
    assert_eq!(
        incs.len(),
        INCREMENTS.0 + INCREMENTS.1,
        "increments in block.dat"
    );

    // every increment against the law, in its metric
    let law = ContactLaw::from_path(&law_path).unwrap();
    let tension = law.virgin().most_tensile().pressure.min(0.0);
    let floor = law.pressure_floor();
    // the virgin loading at overclosure h (um), compressive (as the table: 0 above d_ref),
    // not below the deepest separation tabulated by the rounding of the last row's h (the
    // increments stay short of it: asserted below)
    let deepest = law.virgin().d()[0];
    let p_law = |h_um: f64| -> f64 {
        let d = (d_ref - h_um * 1e-6).max(deepest);
        law.virgin_pressure(d).unwrap().0.max(0.0)
    };
    let metric = |p_mpa: f64, exact: f64| {
        (p_mpa * 1e6 - exact).abs() / (exact.abs() + tension.abs() + floor)
    };
    let area = 1.0; // um^2
    let (mut worst_cstr, mut worst_force, mut h_max, mut p_max): (f64, f64, f64, f64) =
        (0.0, 0.0, 0.0, 0.0);
    let mut worst_reading: f64 = 0.0;
    for (time, inc) in &incs {
        assert_eq!(inc.normal.len(), 4, "slave nodes at time {time}");
        assert_eq!(inc.pressure.len(), 4, "slave nodes at time {time}");
        let force_z = inc.force_z.expect("the total force");
        // uniform: one overclosure for the four slave nodes (to the print's 7 digits)
        let h = -inc.normal[0];
        for (&n, &p) in inc.normal.iter().zip(&inc.pressure) {
            assert!(
                (-n - h).abs() <= 1e-6 * h.abs(),
                "time {time}: {n} against {h}"
            );
            // CalculiX reads the rows linearly, as they were placed for (no resampling):
            // the .dat prints 7 digits, so a pressure and an overclosure are rounded by at
            // most 5e-7 of themselves, and the linear reading at the printed overclosure
            // differs from the printed pressure by at most 5e-7 (|p| + |dp/dh| h)
            let (lin, slope) = linear(-n);
            let rounding = 5e-7 * (p.abs() + slope * -n);
            worst_reading = worst_reading.max((p - lin).abs() / rounding);
            assert!(
                (p - lin).abs() <= rounding,
                "time {time}: overclosure {} um, CalculiX {p} MPa, the rows read linearly {lin} MPa",
                -n
            );
            // the law: the export's tolerance (the rows hold the law within it by linear
            // interpolation; CalculiX adds only the rounding above)
            let e = metric(p, p_law(-n));
            worst_cstr = worst_cstr.max(e);
            assert!(
                e <= EXPORT_TOLERANCE,
                "time {time}: overclosure {} um, CalculiX {p} MPa, law {} MPa: error {e:.3e}",
                -n,
                p_law(-n) * 1e-6
            );
        }
        // the force the contact transmits, in equilibrium with the block's top
        let exact = p_law(h);
        let e = metric(-force_z / area, exact);
        worst_force = worst_force.max(e);
        assert!(
            e <= EXPORT_TOLERANCE,
            "time {time}: overclosure {h} um, force {force_z} uN on {area} um^2, law {} MPa: error {e:.3e}",
            exact * 1e-6
        );
        h_max = h_max.max(h);
        p_max = p_max.max(exact);
    }
    // the increments went through the law's rise, to near the table's end
    let p_last = p_law(h_last);
    assert!(
        h_max > 0.98 * h_last && h_max <= h_last && p_max > 0.5 * p_last,
        "deepest overclosure {h_max} um of {h_last} um, {p_max} Pa of {p_last} Pa"
    );
    eprintln!(
        "CalculiX on {} rows, {} increments to {h_max:.6} um ({:.4} MPa): largest error {worst_cstr:.3e} (contact pressure), {worst_force:.3e} (force) of {EXPORT_TOLERANCE:e}; the rows read linearly to {worst_reading:.2} of the print's rounding",
        rows.len(),
        incs.len(),
        p_max * 1e-6
    );
}
