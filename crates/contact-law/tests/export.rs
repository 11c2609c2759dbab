//! The pressure-overclosure table of the virgin loading (issue 46 item 5): its rows, read
//! by linear interpolation as an FE code reads them, stay within the tolerance of the law
//! in the law's own error metric everywhere between them (checked far more densely than
//! the rows were placed), it starts at (0, 0) where the virgin loading turns compressive,
//! holds at most 200 rows, and its keyword block says what a table cannot carry.

mod common;
use contact_law::{InpDialect, InpUnits, EXPORT_TOLERANCE, MAX_ROWS};

#[test]
fn linear_interpolation_of_the_rows_stays_within_the_tolerance_of_the_law() {
    let law = common::law();
    let t = law.overclosure_table(EXPORT_TOLERANCE, MAX_ROWS).unwrap();
    assert!(
        t.rows.len() <= MAX_ROWS && t.rows.len() > 10,
        "{} rows",
        t.rows.len()
    );
    assert_eq!(t.rows[0], (0.0, 0.0));
    // d_ref: the virgin loading is compressive just below it and not just above
    let p = |d: f64| law.virgin_pressure(d).unwrap().0;
    let span = t.rows.last().unwrap().0;
    assert!(p(t.d_ref - 1e-6 * span) > 0.0 && p(t.d_ref + 1e-6 * span) <= 0.0);
    // increasing overclosure, non-negative pressures
    for w in t.rows.windows(2) {
        assert!(w[1].0 > w[0].0);
        assert!(w[1].1 >= 0.0);
    }
    // between the rows, 200 points each: the law's error metric
    let floor = law.pressure_floor();
    let tension = law.virgin().most_tensile().pressure.abs();
    let mut worst: f64 = 0.0;
    for w in t.rows.windows(2) {
        let ((a, pa), (b, pb)) = (w[0], w[1]);
        for k in 0..=200 {
            let s = k as f64 / 200.0;
            let h = a + s * (b - a);
            let exact = if h <= 0.0 {
                0.0
            } else {
                p(t.d_ref - h).max(0.0)
            };
            let lin = pa + s * (pb - pa);
            worst = worst.max((lin - exact).abs() / (exact.abs() + tension + floor));
        }
    }
    assert!(worst <= EXPORT_TOLERANCE, "worst {worst}");
    // the rows end at the deepest separation the law covers
    assert!((t.d_ref - span - law.virgin().d()[0]).abs() <= 1e-12 * span);
}

#[test]
fn the_keyword_block_names_d_ref_the_units_and_what_a_table_cannot_carry() {
    let t = common::law()
        .overclosure_table(EXPORT_TOLERANCE, MAX_ROWS)
        .unwrap();
    let block = t.inp_block(InpDialect::Calculix, InpUnits::MicrometreMegapascal);
    let lines: Vec<&str> = block.lines().collect();
    assert!(lines.contains(&format!("** d_ref = {:e} m", t.d_ref).as_str()));
    assert!(lines.contains(&"** units: um, MPa"));
    for word in ["unloading", "adhesion", "beyond the deepest row"] {
        assert!(block.contains(word), "{word}");
    }
    let k = lines
        .iter()
        .position(|l| *l == "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR")
        .unwrap();
    assert_eq!(lines[k + 1], "0, 0");
    let data = &lines[k + 1..];
    assert_eq!(data.len(), t.rows.len());
    // pressure first (MPa), then overclosure (um)
    let (h, p) = t.rows[t.rows.len() - 1];
    let last: Vec<f64> = data[data.len() - 1]
        .split(", ")
        .map(|v| v.parse().unwrap())
        .collect();
    assert!((last[0] - p * 1e-6).abs() <= 1e-9 * p * 1e-6);
    assert!((last[1] - h * 1e6).abs() <= 1e-9 * h * 1e6);
    let si = t.inp_block(InpDialect::Abaqus, InpUnits::Si);
    assert!(si.contains("** units: m, Pa") && si.contains("(Abaqus)"));
    // too few rows for the tolerance is an error that says so
    let e = common::law()
        .overclosure_table(1e-6, 20)
        .unwrap_err()
        .to_string();
    assert!(e.contains("rows cannot hold"), "{e}");
    assert!(common::law().overclosure_table(0.0, 200).is_err());
    assert!(common::law().overclosure_table(1e-3, 201).is_err());
}
