//! Numerical stability on stiff and extreme inputs (issue 5): every case of
//! `ocean_cpu::stability` (the table `ocean report` prints) is finite and within its stated
//! bound against the f64 reference. The bounds and where they come from are in that module's
//! documentation; a negative control shows the comparison can fail.

use ocean_cpu::stability::{Case, cases};

#[test]
fn every_extreme_case_is_finite_and_within_its_bound() {
    let all = cases().expect("the cases run");
    println!(
        "{:<10} {:<55} {:>6} {:>10} {:>10}  metric / note",
        "group", "case", "finite", "error", "bound"
    );
    for c in &all {
        println!(
            "{:<10} {:<55} {:>6} {:>10.2e} {:>10.2e}  {} / {}",
            c.group, c.name, c.finite, c.error, c.bound, c.metric, c.note
        );
    }
    for group in ["fresnel", "spectrum", "time", "folding", "camera", "sun", "raster"] {
        assert!(all.iter().any(|c| c.group == group), "no {group} case");
    }
    let failing: Vec<&Case> = all.iter().filter(|c| !c.passes()).collect();
    assert!(failing.is_empty(), "{failing:#?}");
}

#[test]
fn a_case_beyond_its_bound_or_not_finite_fails() {
    let ok = Case {
        group: "fresnel",
        name: "control".into(),
        finite: true,
        error: 1e-7,
        bound: 1e-7,
        metric: "",
        note: String::new(),
    };
    assert!(ok.passes());
    assert!(!Case { error: 1.000001e-7, ..ok.clone() }.passes());
    assert!(!Case { finite: false, ..ok.clone() }.passes());
    assert!(!Case { error: f64::NAN, ..ok }.passes());
}
