//! Physics tests of the Fresnel term (seed 000, eq. 2), its Schlick approximation and the
//! tables built from it. Every comparator here has a negative control: the same check run on a
//! deliberately wrong input, asserted to fail.
//!
//! Run with `cargo test --release --test fresnel -- --nocapture` to see the measured figures.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_6, SQRT_2};

use ocean_core::fresnel::{
    brewster_angle, critical_angle, fresnel_dielectric_polarized, fresnel_dielectric_sp,
    fresnel_exact, fresnel_schlick,
};
use ocean_core::tables::{
    FresnelTable1D, FresnelTexture, MAX_TABLE_SIZE, TextureMapping, texture_error,
};

/// Water seen from air (η = 1.333), and from inside water (1/1.333).
const WATER: f64 = 1.333;
const WATER_INSIDE: f64 = 1.0 / 1.333;

/// docs/design.md's tolerance for eq. 2 against the s/p form, evaluated in f32.
const F32_TOL: f64 = 1e-6;

/// Polar angles in degrees, ascending: 0° to 90° in steps of 0.001°, with approaches to 90°
/// closer than that grid gets inserted before 90° itself.
fn thetas_deg() -> Vec<f64> {
    let mut v: Vec<f64> = (0..90_000).map(|k| f64::from(k) * 1e-3).collect();
    v.extend([89.9995, 89.9999, 89.99999, 89.999_999, 90.0 - 1e-9, 90.0]);
    v
}

/// cos θ for θ in degrees, exactly 0 at 90° (cos(π/2) in floating point is 6e-17, not 0).
fn cos_deg(theta_deg: f64) -> f64 {
    if theta_deg == 90.0 { 0.0 } else { theta_deg.to_radians().cos() }
}

// ---------------------------------------------------------------------------------------------
// eq. 2 against the independent s/p formulation
// ---------------------------------------------------------------------------------------------

/// The largest |eq. 2 − s/p| in f64 over the θ grid, and the θ where it occurs; eq. 2 is
/// evaluated with `eta_eq2` (equal to `eta` except in negative controls). The window of
/// ±`skip_deg` around the critical angle is left out (see `critical_angle_window`).
fn eq2_vs_sp_f64(eta: f64, eta_eq2: f64, skip_deg: f64) -> (f64, f64) {
    let crit = critical_angle(eta).map(f64::to_degrees);
    let mut worst = (0.0, 0.0);
    for th in thetas_deg() {
        if crit.is_some_and(|tc| (th - tc).abs() < skip_deg) {
            continue;
        }
        let c = cos_deg(th);
        let d = (fresnel_exact(c, eta_eq2) - fresnel_dielectric_sp(c, eta)).abs();
        if d > worst.0 {
            worst = (d, th);
        }
    }
    worst
}

#[test]
fn eq2_matches_sp_in_f64() {
    // Well conditioned: both forms are ~20 f64 operations on quantities of order 1, so they
    // agree to a few tens of ε = 2.2e-16. Measured: ≤ 1.2e-15.
    for eta in [WATER, 1.5, 2.5] {
        let (d, th) = eq2_vs_sp_f64(eta, eta, 0.0);
        eprintln!("eq.2 vs s/p, f64, eta {eta}: max abs {d:.2e} at {th}°");
        assert!(d <= 1e-14, "eta {eta}: {d:e} at {th}°");
        // Negative control: η off by 1e-12 relative must be seen.
        let (d_bad, _) = eq2_vs_sp_f64(eta, eta * (1.0 + 1e-12), 0.0);
        assert!(d_bad > 1e-14, "the f64 comparator did not see eta perturbed by 1e-12: {d_bad:e}");
    }
    // Inside water: the same outside ±0.1° of the critical angle (measured 2e-15). Closer, g
    // = η cos θₜ → 0 and both forms' O(ε) round-off in g² becomes O(ε/g) in F (2.5e-14 at
    // 0.012° from it); there `near_critical_angle_is_backward_stable` applies instead.
    let (d, th) = eq2_vs_sp_f64(WATER_INSIDE, WATER_INSIDE, 0.1);
    eprintln!(
        "eq.2 vs s/p, f64, eta 1/1.333 (outside ±0.1° of critical): max abs {d:.2e} at {th}°"
    );
    assert!(d <= 1e-14, "eta 1/1.333: {d:e} at {th}°");

    // η = 1: no interface. eq. 2 gives exactly 0 everywhere (documented, including c = 0 where
    // the formula is 0/0). The s/p form gives only round-off for c > 0: cos²θₜ = 1 − (1 − c²)
    // is off by δ ≤ 2ε, so r ≈ δ/(4c²) and R ≤ ε²/(4c⁴) (tested with 4× slack); at c = 0 it
    // takes its TIR branch (sin²θₜ = 1): the one documented disagreement.
    for th in thetas_deg() {
        let c = cos_deg(th);
        assert_eq!(fresnel_exact(c, 1.0), 0.0, "eta 1 at {th}°");
        if c > 0.0 {
            let bound = (f64::EPSILON / (c * c)).powi(2);
            assert!(fresnel_dielectric_sp(c, 1.0) <= bound, "s/p, eta 1 at {th}°");
        }
    }
    assert_eq!(fresnel_dielectric_sp(0.0, 1.0), 1.0);
}

#[test]
fn eta_near_one_f64_relative_accuracy() {
    // η = 1.00001: F is ~2.5e-11 at normal incidence, so only relative error means anything.
    // The s/p reference itself cancels in η cos θᵢ − cos θₜ and is good to ~ε/(η − 1) = 2e-11
    // relative; the stable eq. 2 is good to a few ε. Measured: 2.9e-11, the reference's own
    // error. Bound: 1e-9, far below the 1e-6 asked of the renderer.
    let eta = 1.00001;
    let rel = max_rel_vs_sp(eta, |c| fresnel_exact(c, eta));
    eprintln!("eq.2 vs s/p, f64, eta 1.00001: max rel {rel:.2e}");
    assert!(rel <= 1e-9, "{rel:e}");
    // Negative control: the relative comparator sees η off by 1e-9 (F ∝ (η − 1)² near normal
    // incidence, so that is a 2e-4 relative change).
    let rel_bad = max_rel_vs_sp(eta, |c| fresnel_exact(c, eta + 1e-9));
    assert!(rel_bad > 1e-9, "{rel_bad:e}");
}

fn max_rel_vs_sp(eta: f64, f: impl Fn(f64) -> f64) -> f64 {
    let mut worst = 0.0_f64;
    for th in thetas_deg() {
        let c = cos_deg(th);
        let r = fresnel_dielectric_sp(c, eta);
        worst = worst.max(((f(c) - r) / r).abs());
    }
    worst
}

/// Why the stable form exists: eq. 2 exactly as printed, g − c formed directly.
fn fresnel_eq2_printed_f32(c: f32, eta: f32) -> f32 {
    let g = (eta * eta + c * c - 1.0).sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

#[test]
fn eta_near_one_f32_stable_form_keeps_its_digits() {
    // In f32, 1.00001 is 1.0000100136 (84 ulp above 1); the reference is evaluated at the same
    // f32 inputs, widened exactly to f64, so only the arithmetic is compared.
    let eta32 = 1.00001_f32;
    let eta = f64::from(eta32);
    let rel = |f: &dyn Fn(f32) -> f32| {
        let mut worst = 0.0_f64;
        for k in 0..=899 {
            let c32 = cos_deg(f64::from(k) * 0.1) as f32;
            let r = fresnel_dielectric_sp(f64::from(c32), eta);
            worst = worst.max(((f64::from(f(c32)) - r) / r).abs());
        }
        worst
    };
    let stable = rel(&|c| fresnel_exact(c, eta32));
    let printed = rel(&|c| fresnel_eq2_printed_f32(c, eta32));
    eprintln!(
        "eta 1.00001 in f32, 0°..89.9°: stable max rel {stable:.2e}, printed form {printed:.2e}"
    );
    // Stable: a few f32 ulp (ε = 6e-8 per operation, ~10 operations); measured 5.1e-7.
    assert!(stable <= 2e-6, "stable form: {stable:e}");
    // Printed: (η² − 1) keeps ~7 of 24 bits and g − c cancels; measured 1.4e-2. This is also
    // the negative control of the comparator above.
    assert!(printed > 1e-3, "the printed form was expected to lose digits: {printed:e}");
}

/// Whether `value` (computed from the f32 cosine `c32`) is the reference F of c32 within `tol`,
/// or of a cosine within one f32 ulp of c32 (a backward error of one ulp of the input).
fn agrees_within_one_ulp_of_input(value: f64, c32: f32, eta: f64, tol: f64) -> bool {
    let refs = [c32.next_down(), c32, c32.next_up()]
        .map(|c| fresnel_dielectric_sp(f64::from(c.clamp(0.0, 1.0)), eta));
    let lo = refs.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = refs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    value >= lo - tol && value <= hi + tol
}

/// Checks eq. 2 evaluated in f32 against the f64 s/p reference at the same (f32) inputs:
/// |difference| ≤ `tol` everywhere outside ±0.2° of the critical angle; inside that window
/// (only for η < 1), agreement with the reference at the input or a neighbouring f32 cosine.
/// Returns the largest plain |difference| and its θ, or the first failure.
fn eq2_f32_vs_sp(eta: f64, eta_eq2: f32, tol: f64) -> Result<(f64, f64), String> {
    let eta32 = eta as f32;
    let eta_ref = f64::from(eta32);
    let crit = critical_angle(eta_ref).map(f64::to_degrees);
    let mut worst = (0.0, 0.0);
    for th in thetas_deg() {
        let c32 = cos_deg(th) as f32;
        let value = f64::from(fresnel_exact(c32, eta_eq2));
        let d = (value - fresnel_dielectric_sp(f64::from(c32), eta_ref)).abs();
        if d > worst.0 {
            worst = (d, th);
        }
        let near_critical = crit.is_some_and(|tc| (th - tc).abs() < 0.2);
        let ok =
            d <= tol || (near_critical && agrees_within_one_ulp_of_input(value, c32, eta_ref, tol));
        if !ok {
            return Err(format!("eta {eta}: |{value} - ref| = {d:e} at {th}°"));
        }
    }
    Ok(worst)
}

#[test]
fn eq2_matches_sp_in_f32() {
    for eta in [1.00001, WATER, 1.5, 2.5, WATER_INSIDE] {
        let (d, th) = eq2_f32_vs_sp(eta, eta as f32, F32_TOL).unwrap_or_else(|e| panic!("{e}"));
        eprintln!("eq.2 in f32 vs s/p, eta {eta}: max abs {d:.2e} at {th}°");
        // Negative control: η one part in 1e5 off moves F by > 1e-6 (dF₀/dη ≈ 0.1 for water).
        let bad = eq2_f32_vs_sp(eta, (eta * (1.0 + 1e-5)) as f32, F32_TOL);
        assert!(bad.is_err(), "the f32 comparator did not see eta perturbed by 1e-5: {bad:?}");
    }
    // η = 1 in f32: exactly 0, like f64.
    for k in 0..=900 {
        assert_eq!(fresnel_exact(cos_deg(f64::from(k) * 0.1) as f32, 1.0_f32), 0.0);
    }
}

#[test]
fn near_critical_angle_is_backward_stable() {
    // At the critical angle F = 1 − O(sqrt(θc − θ)), so dF/dc is unbounded and an absolute
    // tolerance cannot hold for an f32 input: measured, the plain f32 error is 1.3e-6 just
    // outside ±0.1° and reaches 6.5e-4 at the critical angle itself. What holds is that the
    // f32 result is the exact F of a cosine within one ulp of the input.
    let eta32 = WATER_INSIDE as f32;
    let eta = f64::from(eta32);
    let crit_deg = critical_angle(eta).map(f64::to_degrees).unwrap_or(f64::NAN);
    let mut plain = 0.0_f64;
    let mut failures = 0;
    let mut failures_bad_eta = 0;
    for k in 0..=200_000 {
        let th = crit_deg - 0.2 + 0.4 * f64::from(k) / 200_000.0;
        let c32 = cos_deg(th) as f32;
        let value = f64::from(fresnel_exact(c32, eta32));
        plain = plain.max((value - fresnel_dielectric_sp(f64::from(c32), eta)).abs());
        if !agrees_within_one_ulp_of_input(value, c32, eta, F32_TOL) {
            failures += 1;
        }
        // Negative control: η off by 1e-5 relative moves the critical angle by ~8e-4°, which
        // no single ulp of the cosine (~3e-6°) covers.
        let wrong = f64::from(fresnel_exact(c32, (eta * (1.0 + 1e-5)) as f32));
        if !agrees_within_one_ulp_of_input(wrong, c32, eta, F32_TOL) {
            failures_bad_eta += 1;
        }
    }
    eprintln!("within ±0.2° of the critical angle, f32: plain max abs {plain:.2e}");
    assert_eq!(failures, 0);
    assert!(failures_bad_eta > 0, "the backward comparator did not see a perturbed eta");

    // The same in f64, with the exact η = 1/1.333, to 1e-14. Here the reference is in the same
    // precision as eq. 2: each form perturbs g² = c² − (1 − η²) by a few ε, i.e. c by one or
    // two ulp, so the result must be the reference at a cosine within 4 ulp of c.
    let eta = WATER_INSIDE;
    let crit_deg = critical_angle(eta).map(f64::to_degrees).unwrap_or(f64::NAN);
    let agrees = |value: f64, c: f64, eta_ref: f64| {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut down, mut up) = (c, c);
        for _ in 0..=4 {
            for c in [down, up] {
                let r = fresnel_dielectric_sp(c, eta_ref);
                (lo, hi) = (lo.min(r), hi.max(r));
            }
            (down, up) = (down.next_down(), up.next_up());
        }
        value >= lo - 1e-14 && value <= hi + 1e-14
    };
    let mut plain = 0.0_f64;
    let mut bad_eta_seen = false;
    for k in 0..=200_000 {
        let c = cos_deg(crit_deg - 0.2 + 0.4 * f64::from(k) / 200_000.0);
        let value = fresnel_exact(c, eta);
        plain = plain.max((value - fresnel_dielectric_sp(c, eta)).abs());
        assert!(agrees(value, c, eta), "f64 at c = {c}: {value}");
        bad_eta_seen |= !agrees(fresnel_exact(c, eta * (1.0 + 1e-12)), c, eta);
    }
    eprintln!("within ±0.2° of the critical angle, f64: plain max abs {plain:.2e}");
    assert!(bad_eta_seen, "the f64 backward comparator did not see a perturbed eta");
}

// ---------------------------------------------------------------------------------------------
// Published values: Jerlov (1976), Marine Optics, Table XVI
// ---------------------------------------------------------------------------------------------

struct JerlovRow {
    theta_deg: f64,
    rho_parallel: f64,
    rho_perpendicular: f64,
    rho: f64,
}

fn jerlov_table() -> Vec<JerlovRow> {
    let path =
        concat!(env!("CARGO_MANIFEST_DIR"), "/reference/tables/jerlov_water_reflectance.csv");
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("the reference table {path} is missing: {e}"));
    let mut lines = text.lines().filter(|l| !l.trim().is_empty() && !l.starts_with('#'));
    assert_eq!(
        lines.next(),
        Some("theta_deg,rho_parallel_pct,rho_perpendicular_pct,rho_pct"),
        "unexpected header in {path}"
    );
    let rows: Vec<JerlovRow> = lines
        .map(|l| {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse().unwrap_or_else(|e| panic!("{path}: {l:?}: {e}")))
                .collect();
            assert_eq!(v.len(), 4, "{path}: {l:?}");
            JerlovRow { theta_deg: v[0], rho_parallel: v[1], rho_perpendicular: v[2], rho: v[3] }
        })
        .collect();
    assert_eq!(rows.len(), 19, "{path} should hold 0°..90° in 5° steps");
    rows
}

/// The largest |100·F − ρ| over Jerlov's rows, for the unpolarised column, and for the two
/// polarised columns against (R_∥, R_⊥) = (`p`, `s`) of the model.
fn jerlov_deviation(eta: f64, swap_polarisations: bool) -> (f64, f64) {
    let mut rho_dev = 0.0_f64;
    let mut pol_dev = 0.0_f64;
    for row in jerlov_table() {
        let c = cos_deg(row.theta_deg);
        let f = 100.0 * fresnel_exact(c, eta);
        let pol = fresnel_dielectric_polarized(c, eta);
        let (p, s) = if swap_polarisations { (pol.r_s, pol.r_p) } else { (pol.r_p, pol.r_s) };
        rho_dev = rho_dev.max((f - row.rho).abs());
        pol_dev = pol_dev
            .max((100.0 * p - row.rho_parallel).abs())
            .max((100.0 * s - row.rho_perpendicular).abs());
    }
    (rho_dev, pol_dev)
}

#[test]
fn jerlov_flat_sea_reflectance() {
    // Jerlov computed the table for n = 4/3 (stated in the text; Brewster's angle 53°).
    let eta = 4.0 / 3.0;
    for row in jerlov_table() {
        let c = cos_deg(row.theta_deg);
        let pol = fresnel_dielectric_polarized(c, eta);
        eprintln!(
            "Jerlov {:>4}°: rho {:6.1} model {:8.3} | par {:6.1} model {:8.3} | perp {:6.1} model {:8.3}",
            row.theta_deg,
            row.rho,
            100.0 * fresnel_exact(c, eta),
            row.rho_parallel,
            100.0 * pol.r_p,
            row.rho_perpendicular,
            100.0 * pol.r_s
        );
    }
    let (rho_dev, pol_dev) = jerlov_deviation(eta, false);
    eprintln!("Jerlov vs n = 4/3: rho max dev {rho_dev:.3} points, components {pol_dev:.3}");
    // ρ is printed to 0.1 (±0.05) and is the mean of the components as printed, themselves
    // rounded to 0.1 (±0.05): ±0.1 in all. Measured: 0.097 (80°); 60°, 80° and 85° are outside
    // the ±0.05 of ρ's own rounding (0.075, 0.097, 0.061).
    assert!(rho_dev <= 0.1, "{rho_dev}");
    // The components deviate by up to 0.18 (55°, 75°, 80°: see the CSV's notes), beyond their
    // rounding; 0.2 is the table's own accuracy, and the check still tells s from p.
    assert!(pol_dev <= 0.2, "{pol_dev}");
    // Negative controls: swapping s and p is off by > 1 point from 20° on; η = 1.34 (a common
    // sea-water value) is off by 0.26 in ρ.
    assert!(jerlov_deviation(eta, true).1 > 1.0);
    assert!(jerlov_deviation(1.34, false).0 > 0.1);

    // F(0°) = ((η − 1)/(η + 1))² = 0.0204 for η = 1.333 (0.020373).
    let f0 = fresnel_exact(1.0, WATER);
    assert!((f0 - 0.0204).abs() < 5e-5, "{f0}");
    assert!((fresnel_exact(1.0_f64, 1.34) - 0.0204).abs() > 5e-5);
}

// ---------------------------------------------------------------------------------------------
// Brewster's angle, total internal reflection, extremes
// ---------------------------------------------------------------------------------------------

#[test]
fn brewster_angle_zeroes_p_reflectance() {
    for eta in [WATER, 1.5, 2.5, WATER_INSIDE] {
        let theta_b = brewster_angle(eta);
        let c = theta_b.cos();
        let pol = fresnel_dielectric_polarized(c, eta);
        // r_∥ ∝ η cos θ_B − cos θₜ = 0 up to round-off (~1e-16), so R_p ~ 1e-32.
        assert!(pol.r_p <= 1e-28, "eta {eta}: R_p(θ_B) = {:e}", pol.r_p);
        // eq. 2's second factor vanishes too: F = ½ R_s.
        let f = fresnel_exact(c, eta);
        assert!((f - 0.5 * pol.r_s).abs() <= 1e-15, "eta {eta}: F {f} vs R_s/2 {}", 0.5 * pol.r_s);
        // Negative control: half a degree away R_p is clearly not 0, so the zero is at θ_B.
        for off in [-0.5_f64, 0.5] {
            let r_p = fresnel_dielectric_polarized((theta_b + off.to_radians()).cos(), eta).r_p;
            assert!(r_p > 1e-6, "eta {eta}: R_p at θ_B{off:+}° = {r_p:e}");
        }
        // The angles on the two sides of an interface are complementary.
        assert!((brewster_angle(eta) + brewster_angle(1.0 / eta) - FRAC_PI_2).abs() < 1e-15);
    }
    // From inside water, Brewster's angle (36.9°) comes before the critical angle (48.6°).
    assert!(critical_angle(WATER_INSIDE).is_some_and(|tc| brewster_angle(WATER_INSIDE) < tc));
}

/// 1 − F(θc − δ) for δ = 1e-4, 1e-6, 1e-8 rad below the critical angle.
fn approach_to_critical(f: impl Fn(f64) -> f64, theta_c: f64) -> [f64; 3] {
    [1e-4, 1e-6, 1e-8].map(|delta| 1.0 - f((theta_c - delta).cos()))
}

/// Whether the approach is continuous with the sqrt law of the critical angle: each step of
/// 100 in δ shrinks 1 − F by 10.
fn is_sqrt_approach(gaps: [f64; 3]) -> bool {
    gaps.windows(2).all(|w| (8.0..=12.0).contains(&(w[0] / w[1])))
}

#[test]
fn total_internal_reflection() {
    let eta = WATER_INSIDE;
    let theta_c = critical_angle(eta).unwrap_or(f64::NAN);
    assert!((theta_c - (1.0 / 1.333_f64).asin()).abs() < 1e-15);
    // Beyond the critical angle: exactly 1, in f64 and f32.
    for k in 1..=10_000 {
        let th = theta_c + (FRAC_PI_2 - theta_c) * f64::from(k) / 10_000.0;
        assert_eq!(fresnel_exact(th.cos(), eta), 1.0, "f64 at {}°", th.to_degrees());
        assert_eq!(fresnel_schlick(th.cos(), eta), 1.0, "Schlick at {}°", th.to_degrees());
    }
    let eta32 = eta as f32;
    let theta_c32 = f64::from(eta32).asin();
    for k in 1..=10_000 {
        // Start 1e-5 rad beyond, clear of the ulps of an f32 cosine (~6e-8 rad there).
        let th = theta_c32 + 1e-5 + (FRAC_PI_2 - theta_c32 - 1e-5) * f64::from(k) / 10_000.0;
        assert_eq!(fresnel_exact(th.cos() as f32, eta32), 1.0, "f32 at {}°", th.to_degrees());
    }
    // Just below: < 1.
    assert!(fresnel_exact((theta_c - 1e-9).cos(), eta) < 1.0);
    // Continuity at the critical angle, at the sqrt rate.
    let gaps = approach_to_critical(|c| fresnel_exact(c, eta), theta_c);
    eprintln!("1 - F at 1e-4, 1e-6, 1e-8 rad below the critical angle: {gaps:?}");
    assert!(gaps[2] < 1e-3 && gaps[2] > 0.0, "{gaps:?}");
    assert!(is_sqrt_approach(gaps), "{gaps:?}");
    // Negative control: a reflectance that jumps at the critical angle fails the check.
    let jump = approach_to_critical(|c| 0.95 * fresnel_exact(c, eta), theta_c);
    assert!(!is_sqrt_approach(jump), "{jump:?}");
}

#[test]
fn extreme_inputs_give_documented_finite_values() {
    let etas = [1.00001, WATER, 1.5, 2.5, WATER_INSIDE, 0.5];
    for eta in etas {
        let f0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
        // Grazing: exactly 1 (η ≠ 1).
        assert_eq!(fresnel_exact(0.0, eta), 1.0, "eta {eta}");
        assert_eq!(fresnel_exact(-0.0, eta), 1.0, "eta {eta}");
        assert_eq!(fresnel_exact(0.0_f32, eta as f32), 1.0, "eta {eta}");
        // Normal incidence: F₀.
        assert!((fresnel_exact(1.0, eta) - f0).abs() <= 1e-17, "eta {eta}");
        // |c| slightly above 1 (unnormalised dot products) is clamped: same value as at ±1.
        assert_eq!(fresnel_exact(1.0 + 1e-7, eta), fresnel_exact(1.0, eta));
        assert_eq!(fresnel_exact(-1.0 - 1e-7, eta), fresnel_exact(-1.0, eta));
        assert_eq!(fresnel_exact(1.000_000_1_f32, eta as f32), fresnel_exact(1.0, eta as f32));
        assert!((fresnel_exact(-1.0, eta) - f0).abs() <= 1e-16, "eta {eta}");
        // c < 0 is the same interface seen from the other side.
        for c in [0.1, 0.5, 0.9] {
            assert_eq!(fresnel_exact(-c, eta), fresnel_exact(c, 1.0 / eta));
        }
    }
    // η = 1: no interface, exactly 0 at every c, grazing included.
    for c in [-1.0, -0.5, -0.0, 0.0, 1e-300, 0.5, 1.0] {
        assert_eq!(fresnel_exact(c, 1.0), 0.0);
        assert_eq!(fresnel_schlick(c, 1.0), 0.0);
    }
    // η = 1 + 1e-5: tiny, positive, rising to 1 at grazing.
    let f_normal = fresnel_exact(1.0_f64, 1.00001);
    assert!((f_normal - 2.499_975e-11).abs() < 1e-16, "{f_normal:e}");
    // At c = 1e-4, g = sqrt(η² − 1 + c²) = 4.47e-3 and F ≈ ((g − c)/(g + c))² = 0.91.
    let f_grazing = fresnel_exact(1e-4, 1.00001);
    assert!(f_grazing > 0.9 && (f_grazing - fresnel_dielectric_sp(1e-4, 1.00001)).abs() < 1e-10);
    // Every finite (and infinite) input that is not NaN gives a value in [0, 1].
    let cs = [-f64::MAX, -1.5, -1.0, -0.999, -1e-300, -0.0, 0.0, 1e-300, 0.3, 0.999, 1.0, 1.5];
    let etas_all = [
        -1.0,
        0.0,
        1e-300,
        1e-8,
        0.5,
        WATER_INSIDE,
        1.0 - 1e-12,
        1.0,
        1.0 + 1e-12,
        1.00001,
        WATER,
        2.0,
        2.0 + 1e-12,
        1e8,
        1e300,
        f64::MAX,
        f64::INFINITY,
    ];
    for &c in &cs {
        for &eta in &etas_all {
            for f in [fresnel_exact(c, eta), fresnel_schlick(c, eta)] {
                assert!((0.0..=1.0).contains(&f), "F({c}, {eta}) = {f}");
            }
            let f32v = fresnel_exact(c as f32, eta as f32);
            assert!((0.0..=1.0).contains(&f32v), "f32 F({c}, {eta}) = {f32v}");
        }
    }
    // Non-physical η ≤ 0 and η = ∞: 1 (documented limits). NaN propagates.
    assert_eq!(fresnel_exact(0.5, 0.0), 1.0);
    assert_eq!(fresnel_exact(0.5, -2.0), 1.0);
    assert_eq!(fresnel_exact(0.5, f64::INFINITY), 1.0);
    assert!(fresnel_exact(f64::NAN, WATER).is_nan());
    assert!(fresnel_exact(0.5, f64::NAN).is_nan());
    // Monotone in θ on the physical side (non-decreasing as c falls), for every η tested.
    for eta in etas {
        let values: Vec<f64> =
            thetas_deg().into_iter().map(|th| fresnel_exact(cos_deg(th), eta)).collect();
        assert!(values.windows(2).all(|w| w[1] >= w[0] - 1e-15), "eta {eta} not monotone");
    }
}

// ---------------------------------------------------------------------------------------------
// Schlick's approximation
// ---------------------------------------------------------------------------------------------

/// The largest |Schlick − exact| over θ in 0.001° steps, and where.
fn schlick_worst(eta: f64, eta_schlick: f64) -> (f64, f64) {
    let mut worst = (0.0, 0.0);
    for th in thetas_deg() {
        let c = cos_deg(th);
        let d = (fresnel_schlick(c, eta_schlick) - fresnel_exact(c, eta)).abs();
        if d > worst.0 {
            worst = (d, th);
        }
    }
    worst
}

#[test]
fn schlick_error_is_bounded() {
    // Schlick's formula is exact at normal incidence (F₀) and at grazing (1), and overshoots
    // in between, most where the exact F turns up steeply near grazing: (1 − c)⁵ rises earlier
    // than the exact curve for these low indices. Measured worst absolute errors:
    //   η = 1.333: 0.0592 at 83.8°; η = 1.5: 0.0357 at 85.0°; η = 1/1.333 (with cos θₜ):
    //   0.0592 at 48.2°, just inside the critical angle.
    // The bounds are these figures plus ~1 % margin; they are bounds on a measured quantity,
    // not a claim from the literature.
    let cases = [(WATER, 0.060), (1.5, 0.036), (WATER_INSIDE, 0.060)];
    for (eta, bound) in cases {
        let (d, th) = schlick_worst(eta, eta);
        eprintln!("Schlick vs eq.2, eta {eta:.4}: worst abs {d:.4} at {th:.3}°");
        assert!(d <= bound, "eta {eta}: {d} at {th}°");
        // The bound is tight: the error really is that large (not a loose figure).
        assert!(d >= 0.97 * bound, "eta {eta}: bound {bound} is loose for {d}");
        // Exact at both ends.
        assert!((fresnel_schlick(1.0, eta) - fresnel_exact(1.0, eta)).abs() < 1e-16);
        assert_eq!(fresnel_schlick(0.0, eta), 1.0);
    }
    // Negative control: Schlick with the wrong index (1.5 for water) is outside the bound.
    assert!(schlick_worst(WATER, 1.5).0 > 0.060);
}

// ---------------------------------------------------------------------------------------------
// The 1D table
// ---------------------------------------------------------------------------------------------

/// max |F''(c)| on [0, 1] by central differences (step 1e-5: truncation ~1e-10, round-off
/// ~4ε/1e-10 = 1e-5 on values of order 10).
fn max_second_derivative_in_c(eta: f64) -> f64 {
    let d = 1e-5;
    (1..100_000)
        .map(|k| {
            let c = f64::from(k) * 1e-5;
            let (a, b) = ((c - d).max(0.0), (c + d).min(1.0));
            let h = 0.5 * (b - a);
            ((fresnel_exact(b, eta) - 2.0 * fresnel_exact(0.5 * (a + b), eta)
                + fresnel_exact(a, eta))
                / (h * h))
                .abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn table_1d_error() -> ocean_core::Result<()> {
    let f2 = max_second_derivative_in_c(WATER);
    for n in [64, 256] {
        let table = FresnelTable1D::new(n, WATER)?;
        let edge = 0.5 / n as f64;
        let (mut inner, mut outer) = (0.0_f64, 0.0_f64);
        for k in 0..=100_000 {
            let c = f64::from(k) * 1e-5;
            let e = (f64::from(table.lookup(c as f32)) - fresnel_exact(c, WATER)).abs();
            if c < edge { outer = outer.max(e) } else { inner = inner.max(e) }
        }
        // Between texel centres: linear interpolation error ≤ h²/8 max|F''| (h = 1/N), plus
        // f32 storage and arithmetic (≤ 3e-7).
        let bound = f2 / (8.0 * (n * n) as f64) + 3e-7;
        // Below the first centre the sampler clamps: F(0.5/N) stands in for F(0) = 1.
        let clamp = 1.0 - fresnel_exact(edge, WATER);
        eprintln!(
            "1D table N {n}: max {inner:.3e} between centres (bound {bound:.3e}), {outer:.3e} below c = 0.5/N (clamp model {clamp:.3e})"
        );
        assert!(inner <= bound, "N {n}: {inner:e} > {bound:e}");
        assert!((outer - clamp).abs() <= 1e-6, "N {n}: {outer:e} vs {clamp:e}");
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// The 2D Fresnel texture (seed 000 §5.1, §5.3; docs/design.md's `ocean fresnel --table` layout)
// ---------------------------------------------------------------------------------------------

/// docs/design.md's contract for texel (i, j), written out independently of the library.
fn contract_vector(i: usize, j: usize, n: usize) -> [f64; 3] {
    let s = (i as f64 + 0.5) / n as f64;
    let t = (j as f64 + 0.5) / n as f64;
    let x = 2.0 * s - 1.0;
    let y = 2.0 * t - 1.0;
    let r = (x * x + y * y).sqrt();
    if r > 1.0 { [x / r, y / r, 0.0] } else { [x, y, (1.0 - x * x - y * y).max(0.0).sqrt()] }
}

/// Every texel: (x, y, z) is the contract's vector to f32 rounding (1.2e-7), unit length to
/// f32 rounding (2e-7), and A is fresnel_exact of the stored z, exactly (as f32).
fn check_texels(tex: &FresnelTexture) -> Result<(), String> {
    let n = tex.size();
    for j in 0..n {
        for i in 0..n {
            let [x, y, z, a] = tex.texels()[j * n + i];
            let want = contract_vector(i, j, n);
            for (got, want) in [x, y, z].iter().zip(want) {
                if (f64::from(*got) - want).abs() > 1.2e-7 {
                    return Err(format!("texel ({i}, {j}): vector {:?} vs {want:?}", [x, y, z]));
                }
            }
            let len = [x, y, z].iter().map(|&v| f64::from(v).powi(2)).sum::<f64>().sqrt();
            if (len - 1.0).abs() > 2e-7 {
                return Err(format!("texel ({i}, {j}): |v| = {len}"));
            }
            let f = fresnel_exact(f64::from(z), tex.eta()) as f32;
            if a != f {
                return Err(format!("texel ({i}, {j}): A = {a} but F(z = {z}) = {f}"));
            }
        }
    }
    Ok(())
}

#[test]
fn texture_texels_follow_the_contract() -> ocean_core::Result<()> {
    for n in [1, 2, 3, 16, 17, 256] {
        let mut tex = FresnelTexture::new(n, WATER, TextureMapping::Hemisphere)?;
        assert_eq!(tex.texels().len(), n * n);
        assert_eq!(tex.mapping(), TextureMapping::Hemisphere);
        check_texels(&tex).unwrap_or_else(|e| panic!("N {n}: {e}"));
        // Outside the unit disc (the corners): the rim, grazing, F = 1.
        if n >= 4 {
            let [x, y, z, a] = tex.texel(0, 0);
            assert_eq!((z, a), (0.0, 1.0));
            assert!((x + std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-7 && x == y);
        }
        // Negative controls: A one ulp off, or x moved by 1e-6, in one texel.
        let k = (n / 2) * n + n / 3;
        tex.texels_mut()[k][3] = tex.texels()[k][3].next_up();
        assert!(check_texels(&tex).is_err(), "N {n}: corrupted A not seen");
        tex.texels_mut()[k][3] = tex.texels()[k][3].next_down();
        tex.texels_mut()[k][0] += 1e-6;
        assert!(check_texels(&tex).is_err(), "N {n}: corrupted x not seen");
    }
    // N = 1: one texel at the centre, the normal view.
    let tex = FresnelTexture::new(1, WATER, TextureMapping::Hemisphere)?;
    assert_eq!(tex.texel(0, 0), [0.0, 0.0, 1.0, fresnel_exact(1.0, WATER) as f32]);
    Ok(())
}

/// max over r ≤ ρ of max(|f_rr|, |f_r / r|) for f(x, y) = F(sqrt(1 − x² − y²)): since
/// f_xx = f_rr cos²φ + (f_r/r) sin²φ (and f_yy alike), this bounds |f_xx| and |f_yy| on the
/// disc of radius ρ. Central differences with step 1e-5. Infinite if the disc reaches the rim.
fn max_curvature_on_disc(rho: f64, eta: f64) -> f64 {
    let d = 1e-5;
    let f = |r: f64| fresnel_exact((1.0 - r * r).sqrt(), eta);
    let steps = 20_000;
    let mut m = 0.0_f64;
    for k in 1..=steps {
        let r = rho * f64::from(k) / f64::from(steps);
        if r + d >= 1.0 {
            return f64::INFINITY;
        }
        let f_rr = (f(r + d) - 2.0 * f(r) + f(r - d)) / (d * d);
        let f_r = (f(r + d) - f(r - d)) / (2.0 * d);
        m = m.max(f_rr.abs()).max((f_r / r).abs());
    }
    m
}

/// The largest error the hemisphere mapping can have at grazing views along the x axis, for
/// even N (odd N has a texel row on the axis and a slightly different edge cosine): there
/// the lookup coordinate s → 1 lies beyond the last texel centre (x = 1 − 1/N), so the sampler
/// clamps to the edge texels (1 − 1/N, ±1/N), whose cosine is z_edge = sqrt(2/N − 2/N²) —
/// not to anything near the rim, where F → 1. Returns F(c_view) − F(z_edge).
fn rim_clamp_error(n: usize, eta: f64, cos_view: f64) -> f64 {
    let inv = 1.0 / n as f64;
    let z_edge = (2.0 * inv - 2.0 * inv * inv).sqrt();
    fresnel_exact(cos_view, eta) - fresnel_exact(z_edge, eta)
}

#[test]
fn texture_error_against_table_size() -> ocean_core::Result<()> {
    const SAMPLES: usize = 1024;
    // The last row of the error grid, 45°/SAMPLES from the horizon.
    let cos_last = ((SAMPLES as f64 - 0.5) * FRAC_PI_2 / SAMPLES as f64).cos();
    let mut previous: Option<(f64, f64)> = None;
    eprintln!(
        "2D Fresnel texture, eta {WATER}, hemisphere mapping, bilinear vs exact ({SAMPLES}x{} directions):",
        4 * SAMPLES
    );
    eprintln!(
        "    N | max abs (all) | at theta | RMS (solid angle) | max θ<30° | max θ<60° | max θ<75° | max θ<80° | first 1° band > 2e-3"
    );
    for n in [16, 32, 64, 128, 256, 512] {
        let e = texture_error(n, WATER, TextureMapping::Hemisphere, SAMPLES)?;
        eprintln!(
            "{n:>5} | {:>13.3e} | {:>7.3}° | {:>17.3e} | {:>9.2e} | {:>9.2e} | {:>9.2e} | {:>9.2e} | {:?}",
            e.max_abs,
            e.worst_theta_deg,
            e.rms,
            e.max_abs_below(30.0),
            e.max_abs_below(60.0),
            e.max_abs_below(75.0),
            e.max_abs_below_80(),
            e.first_degree_exceeding(2e-3)
        );
        // The whole-hemisphere maximum is the rim clamp at grazing views along the axes,
        // to f32 rounding of the texel.
        let rim = rim_clamp_error(n, WATER, cos_last);
        assert!((e.max_abs - rim).abs() <= 1e-6, "N {n}: max {} vs rim model {rim}", e.max_abs);
        // Away from the rim F is smooth in (x, y) and bilinear interpolation obeys
        // |error| ≤ (h²/8)(max|f_xx| + max|f_yy|), h = 2/N, over the cells that the views with
        // θ < θmax fall in (they reach √2·h beyond sin θmax); plus 3e-7 for f32.
        let h = 2.0 / n as f64;
        for theta_max in [30.0_f64, 60.0, 75.0] {
            let rho = theta_max.to_radians().sin() + SQRT_2 * h;
            let bound = h * h / 8.0 * 2.0 * max_curvature_on_disc(rho, WATER) + 3e-7;
            let got = e.max_abs_below(theta_max);
            assert!(got <= bound, "N {n}, θ < {theta_max}°: {got:e} > bound {bound:e}");
        }
        // Second order: the error below 60° falls by 4 per doubling of N once h resolves F
        // (measured ratios 4.3, 4.07, 4.02, 4.0 from N = 32 on).
        if let Some((prev_below_60, prev_rms)) = previous {
            let ratio = prev_below_60 / e.max_abs_below(60.0);
            if n >= 64 {
                assert!((3.5..=4.5).contains(&ratio), "N {n}: ratio {ratio}");
            }
            assert!(e.rms < prev_rms, "N {n}: RMS did not fall");
        }
        previous = Some((e.max_abs_below(60.0), e.rms));

        if n == 256 {
            // docs/design.md's "256²: ≤ 2e-3" holds for view directions up to 76° from the normal
            // (measured 1.35e-3 below 75°, 1.8e-3 in 75°–76°, 2.4e-3 in 76°–77°) and not over
            // the whole hemisphere: the rim clamp gives 0.415 at grazing. Both are recorded.
            assert!(e.max_abs_below(76.0) <= 2e-3, "{:e}", e.max_abs_below(76.0));
            assert!(e.max_abs > 2e-3);
            // Negative control: one texel corrupted by 0.01 near the normal is seen by the same
            // measurement and breaks the 2e-3 check.
            let mut tex = FresnelTexture::new(n, WATER, TextureMapping::Hemisphere)?;
            let k = (n / 2 + 10) * n + n / 2;
            tex.texels_mut()[k][3] += 0.01;
            let bad = tex.measure_error(SAMPLES)?;
            assert!(bad.max_abs_below(76.0) > 2e-3, "corrupted texel not seen");
        }
    }
    // No table the GPU can hold meets 2e-3 over the whole hemisphere with this mapping: even at
    // the largest size, the rim clamp at the horizon is 1 − F(sqrt(2/N − 2/N²)).
    let at_max = rim_clamp_error(MAX_TABLE_SIZE, WATER, 0.0);
    eprintln!("rim clamp error at N = {MAX_TABLE_SIZE}: {at_max:.3e}");
    assert!(at_max > 2e-3);
    Ok(())
}

#[test]
fn paper_half_range_clamps_grazing_views() -> ocean_core::Result<()> {
    const SAMPLES: usize = 512;
    for n in [32, 64, 256] {
        let paper = FresnelTexture::new(n, WATER, TextureMapping::PaperHalfRange)?;
        let hemi = FresnelTexture::new(n, WATER, TextureMapping::Hemisphere)?;
        assert_eq!(paper.mapping(), TextureMapping::PaperHalfRange);
        // The stored vectors are the paper's V = (s − ½, t − ½, sqrt(1 − …)), unit length.
        for (k, texel) in paper.texels().iter().enumerate() {
            let (i, j) = (k % n, k / n);
            let x = (i as f64 + 0.5) / n as f64 - 0.5;
            let y = (j as f64 + 0.5) / n as f64 - 0.5;
            let z = (1.0 - x * x - y * y).sqrt();
            for (got, want) in texel[..3].iter().zip([x, y, z]) {
                assert!((f64::from(*got) - want).abs() <= 1.2e-7);
            }
            assert_eq!(texel[3], fresnel_exact(f64::from(texel[2]), WATER) as f32);
        }
        let ep = paper.measure_error(SAMPLES)?;
        let eh = hemi.measure_error(SAMPLES)?;
        eprintln!(
            "N {n}: paper half-range: below 25° {:.2e}, band 45° {:.2e}, band 60° {:.2e}, band 89° {:.2e}, first band > 2e-3: {:?}; hemisphere: below 25° {:.2e}, band 45° {:.2e}, band 60° {:.2e}, band 89° {:.2e}",
            ep.max_abs_below(25.0),
            ep.max_abs_by_degree[45],
            ep.max_abs_by_degree[60],
            ep.max_abs_by_degree[89],
            ep.first_degree_exceeding(2e-3),
            eh.max_abs_below(25.0),
            eh.max_abs_by_degree[45],
            eh.max_abs_by_degree[60],
            eh.max_abs_by_degree[89]
        );
        // Beyond ~30° (axes) to 45° (diagonals) the paper's table clamps to its edge, so the
        // error is the whole rise of F from there on, whatever N: > 0.04 at 60°, > 0.9 at the
        // horizon.
        assert!(ep.max_abs_by_degree[60] > 0.04);
        assert!(ep.max_abs_by_degree[89] > 0.9);
        if n <= 64 {
            // Within its range the half-range texels are twice as dense: ~4× smaller error
            // (at N = 256 both are near f32 rounding, so the ratio is not tested there).
            assert!(ep.max_abs_below(25.0) < eh.max_abs_below(25.0) / 3.0);
        } else {
            // The hemisphere mapping at 256² holds 2e-3 up to 76° (see
            // texture_error_against_table_size); the paper's mapping is ≥ 3.5× worse than that
            // limit in every band from 45° on.
            for band in 45..76 {
                assert!(eh.max_abs_by_degree[band] <= 2e-3, "band {band}°");
                assert!(ep.max_abs_by_degree[band] > 7e-3, "band {band}°");
            }
        }
        // A grazing view looks up s = x + ½ ≈ 1.5: clamped to the edge column, the Fresnel
        // value of a view about 30° from the normal.
        let (s, t) = paper.lookup_coords([1.0, 0.0, 0.0]);
        assert!((s - 1.5).abs() < 1e-7 && (t - 0.5).abs() < 1e-7);
        let clamped = f64::from(paper.lookup_fresnel([1.0, 0.0, 0.0]));
        let f30 = fresnel_exact(30.0_f64.to_radians().cos(), WATER);
        assert!((clamped - f30).abs() < 1e-3, "{clamped} vs F(30°) = {f30}");
    }
    Ok(())
}

#[test]
fn lookup_of_unit_view_vectors_matches_exact() -> ocean_core::Result<()> {
    // §5.1 looks the (bumped) view vector up directly, with no normal; for a unit vector the
    // result is F(z) to the interpolation error (≤ 5.1e-4 up to 70° at 256², measured in
    // texture_error_against_table_size). Views at 0°..70°, 12 azimuths, N = 256.
    let tex = FresnelTexture::new(256, WATER, TextureMapping::Hemisphere)?;
    for th in (0..=70).map(|d| f64::from(d).to_radians()) {
        for phi in (0..12).map(|k| f64::from(k) * FRAC_PI_6 + 0.1) {
            let v = [th.sin() * phi.cos(), th.sin() * phi.sin(), th.cos()];
            let got = f64::from(tex.lookup_fresnel(v));
            let want = fresnel_exact(th.cos(), WATER);
            assert!((got - want).abs() < 1e-3, "θ {}°: {got} vs {want}", th.to_degrees());
            // The RGB channels give back the view vector (for §5.3's specular term).
            let (s, t) = tex.lookup_coords(v);
            let rgb = tex.sample_bilinear(s, t);
            for (a, b) in rgb[..3].iter().zip(v) {
                assert!(
                    (f64::from(*a) - b).abs() < 2e-3,
                    "θ {}°: {rgb:?} vs {v:?}",
                    th.to_degrees()
                );
            }
        }
    }
    Ok(())
}

/// The grazing mapping's texel (i, j), written out from its definition independently of the
/// library: u = 2i/(N − 1) − 1, v = 2j/(N − 1) − 1; the elliptical grid mapping
/// d = (u·sqrt(1 − v²/2), v·sqrt(1 − u²/2)); ρ = |d| = sqrt(1 − z), so z = 1 − ρ² and the
/// horizontal part is d/ρ·sin θ with sin θ = sqrt(1 − z²).
fn grazing_vector(i: usize, j: usize, n: usize) -> [f64; 3] {
    let u = 2.0 * i as f64 / (n as f64 - 1.0) - 1.0;
    let v = 2.0 * j as f64 / (n as f64 - 1.0) - 1.0;
    let d = [u * (1.0 - v * v / 2.0).sqrt(), v * (1.0 - u * u / 2.0).sqrt()];
    let rho = d[0].hypot(d[1]).min(1.0);
    let z = 1.0 - rho * rho;
    if rho == 0.0 {
        return [0.0, 0.0, 1.0];
    }
    let sin_theta = (1.0 - z * z).sqrt();
    [d[0] / rho * sin_theta, d[1] / rho * sin_theta, z]
}

#[test]
fn grazing_mapping_puts_the_rim_on_texel_centres() -> ocean_core::Result<()> {
    for n in [2, 3, 16, 17, 256] {
        let tex = FresnelTexture::new(n, WATER, TextureMapping::Grazing)?;
        for j in 0..n {
            for i in 0..n {
                let [x, y, z, a] = tex.texel(i, j);
                let want = grazing_vector(i, j, n);
                for (got, want) in [x, y, z].iter().zip(want) {
                    assert!((f64::from(*got) - want).abs() <= 2.4e-7, "N {n} ({i}, {j}): {want:?}");
                }
                assert_eq!(a, fresnel_exact(f64::from(z), WATER) as f32);
                // The edge texels are the rim itself: grazing, F = 1.
                if i == 0 || j == 0 || i == n - 1 || j == n - 1 {
                    assert_eq!((z, a), (0.0, 1.0), "N {n} ({i}, {j})");
                }
            }
        }
    }
    // The mapping needs two texels a side to have a rim at all.
    assert!(FresnelTexture::new(1, WATER, TextureMapping::Grazing).is_err());
    Ok(())
}

#[test]
fn grazing_mapping_meets_2e3_over_the_whole_hemisphere() -> ocean_core::Result<()> {
    const SAMPLES: usize = 1024;
    eprintln!("2D Fresnel texture, eta {WATER}, grazing mapping, bilinear vs exact:");
    eprintln!("    N | max abs (all) | at theta | RMS (solid angle)");
    let mut previous: Option<f64> = None;
    for n in [16, 32, 64, 128, 256, 512] {
        let e = texture_error(n, WATER, TextureMapping::Grazing, SAMPLES)?;
        eprintln!("{n:>5} | {:>13.3e} | {:>7.3}° | {:>17.3e}", e.max_abs, e.worst_theta_deg, e.rms);
        // The mapping is smooth inside the square and the rim is sampled exactly, so the error
        // over the whole hemisphere is second order: it falls by 4 per doubling of N once the
        // cells resolve F at grazing (measured ratios 3.6, 3.8, 4.0, 4.0 from N = 64 on).
        if let Some(prev) = previous {
            let ratio = prev / e.max_abs;
            if n >= 128 {
                assert!((3.5..=4.5).contains(&ratio), "N {n}: ratio {ratio}");
            }
        }
        previous = Some(e.max_abs);
        if n == 256 {
            // docs/design.md's 2e-3 at 256², now over the whole hemisphere (measured 1.33e-3), where
            // the contract's mapping is off by 0.41 at the horizon.
            assert!(e.max_abs <= 2e-3, "{:e}", e.max_abs);
            let hemisphere = texture_error(n, WATER, TextureMapping::Hemisphere, SAMPLES)?;
            assert!(hemisphere.max_abs > 0.4, "{:e}", hemisphere.max_abs);
            // Negative control: one texel next to the rim corrupted by 0.01 breaks the check.
            let mut tex = FresnelTexture::new(n, WATER, TextureMapping::Grazing)?;
            let k = (n / 2) * n + 1;
            tex.texels_mut()[k][3] -= 0.01;
            assert!(tex.measure_error(SAMPLES)?.max_abs > 2e-3, "corrupted texel not seen");
        }
    }
    Ok(())
}

/// The renderer's own f32 path: the table the `fresnel_table` stage writes (CPU mirror of the
/// WGSL) looked up at the water shader's `fresnel_st`, against eq. 2, over the hemisphere.
#[test]
fn the_water_shaders_grazing_lookup_meets_2e3() {
    use ocean_core::frame::FresnelTableUniforms;
    use ocean_cpu::sampler::texture_sample;
    use ocean_cpu::shaders::{fresnel_table, water};
    let n = 256u32;
    let table = fresnel_table::dispatch(&FresnelTableUniforms::new(
        WATER as f32,
        n,
        TextureMapping::Grazing,
    ));
    // The f32 table against the f64 one: the vector to f32 rounding, F within a few ulp.
    let reference = FresnelTexture::new(n as usize, WATER, TextureMapping::Grazing).unwrap();
    for (got, want) in table.texels.iter().zip(reference.texels()) {
        for c in 0..4 {
            assert!((got[c] - want[c]).abs() <= 5e-7, "{got:?} vs {want:?}");
        }
    }
    let scale = TextureMapping::grazing_scale(n);
    let lookup = |table: &ocean_cpu::sampler::Texture2D, v: [f64; 3]| {
        // The shader's view vector is world (x, y up, z); the local frame has z up.
        let view = [v[0] as f32, v[2] as f32, v[1] as f32];
        let st = water::fresnel_st(water::bumped_view(view.into(), [0.0, 1.0, 0.0].into()), scale);
        texture_sample(table, &water::CLAMP_LINEAR, st.into())[3]
    };
    let worst = |table: &ocean_cpu::sampler::Texture2D| {
        let mut worst = (0.0f64, 0.0f64);
        let rows = 720;
        for k in 0..rows {
            let theta = (k as f64 + 0.5) * FRAC_PI_2 / rows as f64;
            for l in 0..4 * rows {
                let phi = (l as f64 + 0.5) * std::f64::consts::TAU / (4 * rows) as f64;
                let v = [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()];
                let e = (f64::from(lookup(table, v)) - fresnel_exact(v[2], WATER)).abs();
                if e > worst.0 {
                    worst = (e, theta.to_degrees());
                }
            }
        }
        worst
    };
    let (e, at) = worst(&table);
    eprintln!("water shader's grazing lookup at {n}²: max |F − eq. 2| = {e:.3e} at θ = {at:.2}°");
    assert!(e <= 2e-3, "{e:e} at {at}°");
    // Negative control: the contract's hemisphere table looked up with the grazing
    // coordinates is far off.
    let wrong = fresnel_table::dispatch(&FresnelTableUniforms::new(
        WATER as f32,
        n,
        TextureMapping::Hemisphere,
    ));
    assert!(worst(&wrong).0 > 2e-3);
}
