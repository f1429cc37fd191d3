//! Band tables: every technique's measured value with the band a test holds
//! it to, checked so that each band admits its own technique only.
//!
//! A band that also contains another technique's value cannot tell the two
//! apart: that technique could be swapped in, or this one degrade into it,
//! and the test would still pass. Like the goldens' pair test
//! (`tests/goldens.rs`), every band is therefore held against every other
//! row, both against its value recorded on lavapipe and against its value
//! computed in the same run.

/// A row of a band table: technique, its value measured on lavapipe (the
/// comment beside the table says with which command), and the band `[lo, hi]`
/// the test holds its value to.
pub type Row = (&'static str, f64, (f64, f64));

/// `x` to 4 significant digits: the bands' values span 10⁻⁶ to 10⁻¹.
pub fn sig(x: f64) -> String {
    let digits = if x == 0.0 {
        4
    } else {
        (3 - x.abs().log10().floor() as i32).max(0) as usize
    };
    format!("{x:.digits$}")
}

fn contains((lo, hi): (f64, f64), x: f64) -> bool {
    (lo..=hi).contains(&x)
}

/// Everything wrong with `rows` given this run's values `got` (in row
/// order), one line each, prefixed with `table`:
/// - a value outside its own band (the technique changed);
/// - a band around a value measured elsewhere than inside it (a typo);
/// - a band that contains another row's measured value, or another row's
///   value in this run (the band admits another technique), or overlaps
///   another row's band (a value would not name its technique).
///
/// Empty when every band holds and is exclusive. Prints every row.
pub fn band_failures(table: &str, rows: &[Row], got: &[f64]) -> Vec<String> {
    assert_eq!(rows.len(), got.len(), "{table}: one value per row");
    let mut failures = Vec::new();
    for (i, ((name, measured, band), value)) in rows.iter().zip(got).enumerate() {
        println!(
            "{table}: {name} {} (measured {}, band [{}, {}])",
            sig(*value),
            sig(*measured),
            band.0,
            band.1
        );
        if !contains(*band, *value) {
            failures.push(format!(
                "{table}: {name} {} outside its band [{}, {}] (measured {})",
                sig(*value),
                band.0,
                band.1,
                sig(*measured)
            ));
        }
        if !contains(*band, *measured) {
            failures.push(format!(
                "{table}: {name}'s band [{}, {}] does not contain its measured {}",
                band.0,
                band.1,
                sig(*measured)
            ));
        }
        for (j, ((other, other_measured, other_band), other_value)) in
            rows.iter().zip(got).enumerate()
        {
            if i == j {
                continue;
            }
            // Disjoint bands: a value inside one names its technique.
            if j > i && band.0 <= other_band.1 && other_band.0 <= band.1 {
                failures.push(format!(
                    "{table}: {name}'s band [{}, {}] overlaps {other}'s [{}, {}]",
                    band.0, band.1, other_band.0, other_band.1
                ));
            }
            for (what, x) in [("measured", other_measured), ("this run", other_value)] {
                if contains(*band, *x) {
                    failures.push(format!(
                        "{table}: {name}'s band [{}, {}] admits {other} ({what} {})",
                        band.0,
                        band.1,
                        sig(*x)
                    ));
                }
            }
        }
    }
    failures
}
