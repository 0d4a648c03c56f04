//! Numerical stability on stiff and extreme inputs (issue 5): every case of
//! `ocean_cpu::stability` (the table `ocean report` prints) is finite and within its stated
//! bound against the f64 reference. The bounds and where they come from are in that module's
//! documentation; a negative control shows the comparison can fail.

use ocean_core::fresnel::{fresnel_exact, fresnel_schlick};
use ocean_verify::stability::{Case, cases, fresnel_check};

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

#[test]
fn the_fresnel_bound_rejects_an_approximation() {
    // Negative control of the Fresnel rows: eq. 2 meets the backward-stability bound where
    // Schlick's approximation (3e-2 off at grazing angles) does not.
    for c in [1e-3f32, 0.1, 0.5] {
        let (e, b, _) = fresnel_check(fresnel_exact, c, 1.333);
        assert!(e <= b, "eq. 2 at c = {c}: {e} > {b}");
        let (e, b, _) = fresnel_check(fresnel_schlick, c, 1.333);
        assert!(e > b, "Schlick at c = {c}: {e} ≤ {b}");
    }
}
