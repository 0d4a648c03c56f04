//! Physics tests of `ocean_core::spectrum`: closed forms, published fits, normalisation,
//! consistency between the three views of a spectrum (S(ω), S_k(k), F(k)), limits, extremes.
//!
//! Every integral on the test side uses adaptive Simpson (independent of the Gauss–Legendre
//! quadrature inside the module), and every comparator has a negative control: a perturbation
//! just past the tolerance, or the nearest wrong physics, that the same comparator rejects.
//! Run with `--nocapture` to see the measured figures.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use ocean_core::spectrum::{
    JONSWAP_GAMMA_DEFAULT, MAX_FETCH_M, MAX_WIND_SPEED, PHILLIPS_AMPLITUDE_DEFAULT,
    PHILLIPS_SMALL_WAVE_DEFAULT_M, PM_ALPHA, PM_BETA, SpectrumKind, SpectrumParams, U19_5_PER_U10,
    WaveSpectrum, kitaigorodskii_depth_factor,
};
use ocean_core::{Error, GRAVITY};

const G: f64 = GRAVITY;
const KINDS: [SpectrumKind; 4] = [
    SpectrumKind::Phillips,
    SpectrumKind::PiersonMoskowitz,
    SpectrumKind::Jonswap,
    SpectrumKind::Tma,
];

fn make(kind: SpectrumKind, edit: impl FnOnce(&mut SpectrumParams)) -> WaveSpectrum {
    let mut p = SpectrumParams { kind, ..SpectrumParams::default() };
    edit(&mut p);
    WaveSpectrum::new(p).expect("valid parameters")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Deep-water peak wavenumber of a spectrum, rad/m.
fn k_peak(s: &WaveSpectrum) -> f64 {
    let w = s.peak_omega().expect("not flat");
    w * w / G
}

/// ω(k) = sqrt(g k tanh(k h)), written here independently of `Dispersion`.
fn omega_of_k(k: f64, h: f64) -> f64 {
    let t = if h.is_infinite() { 1.0 } else { (k * h).tanh() };
    (G * k * t).sqrt()
}

// --- Adaptive Simpson (test-side quadrature) ---------------------------------------------

#[allow(clippy::too_many_arguments)]
fn simpson_step(
    f: &dyn Fn(f64) -> f64,
    a: f64,
    b: f64,
    fa: f64,
    fm: f64,
    fb: f64,
    whole: f64,
    eps: f64,
    depth: u32,
) -> f64 {
    let m = 0.5 * (a + b);
    let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
    let (flm, frm) = (f(lm), f(rm));
    let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    let delta = left + right - whole;
    // Stop at the tolerance, or where the estimate is already at round-off (which no
    // refinement can improve), or at the depth limit.
    let round_off = 64.0 * f64::EPSILON * (left.abs() + right.abs());
    if depth == 0 || delta.abs() <= (15.0 * eps).max(round_off) {
        left + right + delta / 15.0
    } else {
        simpson_step(f, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1)
            + simpson_step(f, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1)
    }
}

/// ∫_a^b f with relative accuracy ~`rel_tol`: 256 pieces (so no feature is missed), each
/// refined by adaptive Simpson with Richardson's correction.
fn integrate(f: &dyn Fn(f64) -> f64, a: f64, b: f64, rel_tol: f64) -> f64 {
    const PIECES: usize = 256;
    let h = (b - a) / PIECES as f64;
    let xs: Vec<f64> = (0..=PIECES).map(|i| a + i as f64 * h).collect();
    let fx: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
    let fm: Vec<f64> = (0..PIECES).map(|i| f(0.5 * (xs[i] + xs[i + 1]))).collect();
    let wholes: Vec<f64> =
        (0..PIECES).map(|i| h / 6.0 * (fx[i] + 4.0 * fm[i] + fx[i + 1])).collect();
    let scale: f64 = wholes.iter().map(|w| w.abs()).sum::<f64>().max(f64::MIN_POSITIVE);
    let eps = rel_tol * scale / PIECES as f64;
    (0..PIECES)
        .map(|i| simpson_step(f, xs[i], xs[i + 1], fx[i], fm[i], fx[i + 1], wholes[i], eps, 30))
        .sum()
}

/// ∫_a^b f(k) dk over u = ln k.
fn integrate_ln(f: &dyn Fn(f64) -> f64, a: f64, b: f64, rel_tol: f64) -> f64 {
    integrate(
        &|u: f64| {
            let k = u.exp();
            f(k) * k
        },
        a.ln(),
        b.ln(),
        rel_tol,
    )
}

/// 2D composite Simpson over the square [−w, w]² with n (even) intervals per axis.
fn simpson_square(f: &dyn Fn(f64, f64) -> f64, w: f64, n: usize) -> f64 {
    let h = 2.0 * w / n as f64;
    let weight = |i: usize| {
        if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        }
    };
    let mut total = 0.0;
    for j in 0..=n {
        let kz = -w + j as f64 * h;
        let mut row = 0.0;
        for i in 0..=n {
            row += weight(i) * f(-w + i as f64 * h, kz);
        }
        total += weight(j) * row;
    }
    total * h * h / 9.0
}

// --- Pierson–Moskowitz -----------------------------------------------------------------

#[test]
fn pm_significant_wave_height_matches_closed_form() {
    // m₀ = ∫ α g² ω⁻⁵ exp(−β(ω₀/ω)⁴) dω; x = (ω₀/ω)⁴ turns it into α g²/(4 ω₀⁴) ∫ e^(−βx) dx
    // = α g²/(4 β ω₀⁴), so Hs = 4 sqrt(m₀) = 2 sqrt(α/β) U₁₉.₅²/g.
    let coefficient_u19 = 2.0 * (PM_ALPHA / PM_BETA).sqrt();
    let coefficient_u10 = coefficient_u19 * U19_5_PER_U10 * U19_5_PER_U10;
    println!("PM: Hs = {coefficient_u19:.6} U19.5²/g = {coefficient_u10:.6} U10²/g");
    for u10 in [1.0, 5.0, 10.0, 20.0, 60.0] {
        let s = make(SpectrumKind::PiersonMoskowitz, |p| p.wind_speed = u10);
        let closed = coefficient_u10 * u10 * u10 / G;
        let hs = s.significant_wave_height();
        // Independent route: the test's own integral of S(ω) over ln ω.
        let w_p = s.peak_omega().expect("wind");
        let m0 = integrate_ln(&|w| s.frequency_spectrum(w), w_p / 20.0, w_p * 1e6, 1e-12);
        let hs_omega = 4.0 * m0.sqrt();
        println!(
            "  U10 = {u10:4} m/s: Hs closed {closed:.9} m, from S_k {hs:.9} m (rel {:.1e}), \
             from S(ω) {hs_omega:.9} m (rel {:.1e})",
            rel(hs, closed),
            rel(hs_omega, closed)
        );
        assert!(rel(hs, closed) < 1e-6);
        assert!(rel(hs_omega, closed) < 1e-6);
        // Negative control: β off by 2·10⁻⁶ moves the closed form by 10⁻⁶, past the limit.
        let beta_off = PM_BETA * (1.0 + 2.1e-6);
        let closed_off = 2.0 * (PM_ALPHA / beta_off).sqrt() * (U19_5_PER_U10 * u10).powi(2) / G;
        assert!(rel(hs, closed_off) > 1e-6);
    }
    // docs/design.md: Hs ≈ 0.22 U₁₀²/g. The published figure has two digits: ±0.005.
    assert!((coefficient_u10 - 0.22).abs() <= 0.005, "{coefficient_u10}");
    // Negative control: forgetting U₁₉.₅ = 1.026 U₁₀ (0.2092) is outside that rounding.
    assert!((coefficient_u19 - 0.22).abs() > 0.005, "{coefficient_u19}");
}

#[test]
fn pm_peak_frequency_matches_closed_form() {
    // dS/dω = 0 ⇔ −5/ω + 4β ω₀⁴/ω⁵ = 0 ⇔ ω_p = (4β/5)^¼ ω₀.
    let factor = (0.8 * PM_BETA).powf(0.25);
    println!("PM: ω_p = {factor:.6} g/U19.5");
    assert!((factor - 0.877).abs() < 5e-4);
    for u10 in [3.0, 10.0, 40.0] {
        let s = make(SpectrumKind::PiersonMoskowitz, |p| p.wind_speed = u10);
        let closed = factor * G / (U19_5_PER_U10 * u10);
        let w_p = s.peak_omega().expect("wind");
        assert!(rel(w_p, closed) < 1e-14);
        // Golden-section search for the maximum of S(ω), independent of peak_omega.
        let (mut a, mut b) = (0.5 * closed, 2.0 * closed);
        let phi = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..200 {
            let c = b - phi * (b - a);
            let d = a + phi * (b - a);
            if s.frequency_spectrum(c) > s.frequency_spectrum(d) {
                b = d;
            } else {
                a = c;
            }
        }
        let argmax = 0.5 * (a + b);
        println!("  U10 = {u10}: ω_p closed {closed:.9}, argmax of S {argmax:.9}");
        // The maximum is flat to second order: S(ω_p(1+δ)) − S(ω_p) ~ δ², so f64 locates it to
        // sqrt(ε) ≈ 1.5·10⁻⁸ relative; 10⁻⁷ leaves margin.
        assert!(rel(argmax, closed) < 1e-7);
        // Negative control: one part in 10³ off the peak is measurably lower.
        let top = s.frequency_spectrum(closed);
        assert!(s.frequency_spectrum(closed * 1.001) < top);
        assert!(s.frequency_spectrum(closed * 0.999) < top);
    }
}

// --- JONSWAP ---------------------------------------------------------------------------

#[test]
fn jonswap_with_gamma_one_has_the_pm_shape() {
    let (u10, fetch) = (10.0, 50e3);
    let alpha_j = 0.076 * (u10 * u10 / (fetch * G)).powf(0.22);
    let j1 = make(SpectrumKind::Jonswap, |p| {
        p.wind_speed = u10;
        p.fetch_m = fetch;
        p.peak_enhancement = 1.0;
    });
    let w_p = j1.peak_omega().expect("wind");
    assert!(rel(w_p, 22.0 * (G * G / (u10 * fetch)).cbrt()) < 1e-14);
    // The PM sea with the same peak: (4β/5)^¼ g/(1.026 U) = ω_p.
    let u_pm = (0.8 * PM_BETA).powf(0.25) * G / (U19_5_PER_U10 * w_p);
    let pm = make(SpectrumKind::PiersonMoskowitz, |p| p.wind_speed = u_pm);
    assert!(rel(pm.peak_omega().expect("wind"), w_p) < 1e-14);
    let ratio = |s: &WaveSpectrum, w: f64| s.frequency_spectrum(w) / pm.frequency_spectrum(w);
    let expected = alpha_j / PM_ALPHA;
    let mut worst: f64 = 0.0;
    for i in 0..=100 {
        let w = w_p * (0.6 + 0.1 * f64::from(i));
        worst = worst.max(rel(ratio(&j1, w), expected));
    }
    println!("JONSWAP γ=1 / PM with the same peak: constant α_J/α_PM to {worst:.1e}");
    assert!(worst < 1e-12);
    // Negative control: γ = 3.3 is not the PM shape; the ratio varies by more than 10 %.
    let j33 = make(SpectrumKind::Jonswap, |p| {
        p.wind_speed = u10;
        p.fetch_m = fetch;
    });
    assert!(rel(ratio(&j33, w_p), expected) > 0.1);
}

#[test]
fn jonswap_hs_against_the_fetch_limited_growth_law() {
    // Hasselmann et al. (1973) fitted the energy separately: g² m₀/U₁₀⁴ = 1.6·10⁻⁷ x̃, x̃ = gF/U₁₀²,
    // i.e. Hs = 1.6·10⁻³ U₁₀ sqrt(F/g) (as in CERC 1984, Shore Protection Manual, ch. 3).
    // The α and ω_p fits combine to m₀ ∝ α ω_p⁻⁴ ∝ x̃^(−0.22 + 4/3) = x̃^1.113, not x̃^1: the
    // three fits agree with each other only near x̃ ≈ 70, and within 10 % for x̃ ≈ 10…370
    // (measured below). The 10 % limit is the brief's; it is asserted on that range only,
    // and the drift beyond it is printed, not hidden.
    let growth_law = |u10: f64, fetch: f64| 1.6e-3 * u10 * (fetch / G).sqrt();
    let hs = |u10: f64, fetch: f64, gamma: f64| {
        make(SpectrumKind::Jonswap, |p| {
            p.wind_speed = u10;
            p.fetch_m = fetch;
            p.peak_enhancement = gamma;
        })
        .significant_wave_height()
    };
    for u10 in [5.0, 10.0, 20.0] {
        for x_tilde in [20.0, 50.0, 100.0, 200.0, 300.0] {
            let fetch = x_tilde * u10 * u10 / G;
            let (ours, law) = (hs(u10, fetch, JONSWAP_GAMMA_DEFAULT), growth_law(u10, fetch));
            println!(
                "  U10 {u10:4}, x̃ {x_tilde:5}, F {fetch:9.1} m: Hs {ours:.4} m, \
                 growth law {law:.4} m, ratio {:.4}",
                ours / law
            );
            assert!(rel(ours, law) < 0.1);
            // Negative control: γ = 1 (no peak enhancement, 1.525× less energy) falls outside.
            assert!(rel(hs(u10, fetch, 1.0), law) > 0.1);
        }
    }
    // Beyond that range, reported (not asserted): the x̃^0.057 drift of the ratio.
    for x_tilde in [1e3, 1e4, 2e4] {
        let fetch = x_tilde * 100.0 / G;
        println!(
            "  x̃ {x_tilde:7}: Hs / growth law = {:.3}",
            hs(10.0, fetch, JONSWAP_GAMMA_DEFAULT) / growth_law(10.0, fetch)
        );
    }
    // The exponent itself: Hs ∝ sqrt(α/ω_p⁴) ∝ F^((−0.22 + 4/3)/2) = F^0.55667 exactly.
    let slope = (hs(10.0, 2e5, 3.3) / hs(10.0, 1e5, 3.3)).ln() / 2f64.ln();
    let expected = 0.5 * (4.0 / 3.0 - 0.22);
    println!("  d ln Hs / d ln F = {slope:.8} (expected {expected:.8})");
    assert!((slope - expected).abs() < 1e-8);
    // Negative control: the growth law's own slope, 1/2, is far outside that.
    assert!((0.5 - expected).abs() > 1e-3);
}

// --- Spreading -------------------------------------------------------------------------

/// Donelan et al. (1985) / Banner (1990) β(r), written here from the papers' formulas.
fn beta_reference(r: f64) -> f64 {
    if 0.56 < r && r < 0.95 {
        2.61 * r.powf(1.3)
    } else if (0.95..1.6).contains(&r) {
        2.28 * r.powf(-0.65)
    } else {
        10f64.powf(-0.4 + 0.8393 * (-0.567 * (r * r).ln()).exp())
    }
}

const RATIOS: [f64; 16] =
    [0.3, 0.4, 0.5, 0.56, 0.5601, 0.7, 0.9, 0.95, 1.0, 1.3, 1.5999, 1.6, 2.0, 5.0, 20.0, 100.0];

#[test]
fn spreading_matches_donelan_banner() {
    let s = make(SpectrumKind::PiersonMoskowitz, |_| {});
    let w_p = s.peak_omega().expect("wind");
    for &r in &RATIOS {
        let k = (r * w_p).powi(2) / G;
        // r as the module sees it after k → ω (a few ulp off r; matters at the break points).
        let beta = beta_reference(omega_of_k(k, f64::INFINITY) / w_p);
        for &theta in &[0.0, 0.1, -0.5, 1.0, 3.0, PI] {
            let reference = beta / (2.0 * (beta * PI).tanh()) / (beta * theta).cosh().powi(2);
            let d = s.spreading(k, theta);
            assert!(
                (d - reference).abs() <= 1e-12 * reference,
                "r={r} θ={theta}: {d} vs {reference}"
            );
        }
    }
    // Negative control: the neighbouring branch's β (2.28 r^−0.65 at r = 0.9) is told apart.
    let k = (0.9 * w_p).powi(2) / G;
    let beta = 2.28 * 0.9f64.powf(-0.65);
    let wrong = beta / (2.0 * (beta * PI).tanh()) / (beta * 0.1).cosh().powi(2);
    assert!((s.spreading(k, 0.1) - wrong).abs() > 1e-12 * wrong);
    // Phillips: cos²θ/π.
    let ph = make(SpectrumKind::Phillips, |_| {});
    for &theta in &[0.0, 0.3, FRAC_PI_2 - 0.01, 2.0, PI] {
        let reference = theta.cos().powi(2) / PI;
        assert!((ph.spreading(1.0, theta) - reference).abs() < 1e-16);
    }
}

#[test]
fn spreading_is_normalised_non_negative_and_periodic() {
    let spectra = [
        make(SpectrumKind::PiersonMoskowitz, |_| {}),
        make(SpectrumKind::Jonswap, |_| {}),
        make(SpectrumKind::Tma, |p| p.depth_m = 5.0),
        make(SpectrumKind::Phillips, |_| {}),
    ];
    let mut worst: f64 = 0.0;
    for s in &spectra {
        let w_p = s.peak_omega().expect("wind");
        let mut ks: Vec<f64> = RATIOS.iter().map(|r| (r * w_p).powi(2) / G).collect();
        ks.extend([0.0, 1e-12, 1e-3, 1e6]);
        for &k in &ks {
            let d = |t: f64| s.spreading(k, t);
            // D peaks at θ = 0 (smooth there) and has its kink at ±π: split at 0.
            let total = integrate(&d, -PI, 0.0, 1e-14) + integrate(&d, 0.0, PI, 1e-14);
            worst = worst.max((total - 1.0).abs());
            assert!((total - 1.0).abs() < 1e-10, "{:?} k={k}: {total}", s.params().kind);
            // Shifting θ by whole turns rounds it by ~|θ| ε ≈ 10⁻¹⁴ rad; D' ≤ β D(0) with β ≤ 1000
            // moves D by ≤ 10⁻¹¹ D(0): compare against 10⁻⁹ D(0).
            let tol = 1e-9 * d(0.0);
            for i in 0..=720 {
                let theta = -2.0 * TAU + f64::from(i) * (4.0 * TAU / 720.0);
                let v = d(theta);
                assert!(v >= 0.0 && v.is_finite());
                for turns in [-3.0, 1.0, 7.0] {
                    let shifted = d(theta + turns * TAU);
                    assert!((shifted - v).abs() <= tol, "θ={theta}: {shifted} vs {v}");
                }
                assert!((d(-theta) - v).abs() <= tol, "even in θ");
            }
        }
    }
    println!("spreading: worst |∫D dθ − 1| = {worst:.1e}");
    // Negative control for the periodicity check: a shift of 10⁻⁶ rad off a whole turn is seen.
    let s = make(SpectrumKind::Jonswap, |_| {});
    let k = k_peak(&s);
    let (v, shifted) = (s.spreading(k, 0.4), s.spreading(k, 0.4 + TAU + 1e-6));
    assert!((shifted - v).abs() > 1e-9 * s.spreading(k, 0.0));
    // Negative control: without the 1/tanh(βπ) normalisation the integral is tanh(βπ), which
    // the same quadrature tells from 1 at β = 2.44 (r = 0.95⁻): 1 − tanh(7.7) = 4.5·10⁻⁷.
    let beta = beta_reference(0.9499);
    let unnormalised = |t: f64| beta / 2.0 / (beta * t).cosh().powi(2);
    let total =
        integrate(&unnormalised, -PI, 0.0, 1e-14) + integrate(&unnormalised, 0.0, PI, 1e-14);
    assert!((total - 1.0).abs() > 1e-10, "{total}");
}

// --- Consistency of the three views ----------------------------------------------------

#[test]
fn density_integrated_over_direction_is_the_omnidirectional_spectrum() {
    let mut worst: f64 = 0.0;
    for kind in KINDS {
        for (depth, wind_direction) in [(f64::INFINITY, 0.0), (5.0, 0.7), (f64::INFINITY, -2.5)] {
            let s = make(kind, |p| {
                p.depth_m = depth;
                p.wind_direction = wind_direction;
            });
            let k_p = k_peak(&s);
            for factor in [0.5, 0.9, 1.0, 1.5, 3.0, 10.0] {
                let k = factor * k_p;
                // θ relative to the wind, φ = θ + wind direction absolute.
                let ring = |theta: f64| {
                    let phi = theta + wind_direction;
                    s.density(k * phi.cos(), k * phi.sin()) * k
                };
                let total = integrate(&ring, -PI, 0.0, 1e-14) + integrate(&ring, 0.0, PI, 1e-14);
                let s_k = s.omnidirectional(k);
                worst = worst.max(rel(total, s_k));
                assert!(rel(total, s_k) < 1e-10, "{kind:?} h={depth} k={k}: {total} vs {s_k}");
                // Negative control: without the polar Jacobian k it is off by the factor k.
                assert!(rel(total / k, s_k) > 1e-10 || (k - 1.0).abs() < 1e-6);
            }
        }
    }
    println!("∫ F k dθ vs S_k: worst relative difference {worst:.1e}");
}

#[test]
fn omnidirectional_is_frequency_spectrum_times_group_velocity() {
    let mut worst: f64 = 0.0;
    for kind in KINDS {
        for depth in [f64::INFINITY, 5.0] {
            let s = make(kind, |p| p.depth_m = depth);
            let k_p = k_peak(&s);
            let edges = [0.3, 0.7, 0.9, 1.0, 1.1, 1.5, 3.0, 30.0].map(|f| f * k_p);
            for pair in edges.windows(2) {
                let (k1, k2) = (pair[0], pair[1]);
                // Cumulative route: ∫ S_k dk over [k1, k2] = ∫ S dω over [ω(k1), ω(k2)].
                let by_k = integrate(&|k| s.omnidirectional(k), k1, k2, 1e-13);
                let (w1, w2) = (omega_of_k(k1, depth), omega_of_k(k2, depth));
                let by_omega = integrate(&|w| s.frequency_spectrum(w), w1, w2, 1e-13);
                worst = worst.max(rel(by_k, by_omega));
                assert!(rel(by_k, by_omega) < 1e-9, "{kind:?} h={depth} [{k1}, {k2}]");
                if depth.is_finite() {
                    // Negative control: mapping k to ω with deep-water dispersion in 5 m of water.
                    let (d1, d2) = (omega_of_k(k1, f64::INFINITY), omega_of_k(k2, f64::INFINITY));
                    let wrong = integrate(&|w| s.frequency_spectrum(w), d1, d2, 1e-13);
                    assert!(rel(by_k, wrong) > 1e-6, "{kind:?} [{k1}, {k2}]");
                }
            }
            // Pointwise, with a central difference for dω/dk.
            for factor in [0.8, 1.0, 2.0] {
                let k = factor * k_p;
                let dk = 1e-5 * k;
                let c_g = (omega_of_k(k + dk, depth) - omega_of_k(k - dk, depth)) / (2.0 * dk);
                let expected = s.frequency_spectrum(omega_of_k(k, depth)) * c_g;
                assert!(rel(s.omnidirectional(k), expected) < 1e-8, "{kind:?} h={depth} k={k}");
            }
        }
    }
    println!("∫ S_k dk vs ∫ S dω over matching bands: worst relative difference {worst:.1e}");
}

// --- TMA -------------------------------------------------------------------------------

#[test]
fn tma_tends_to_jonswap_in_deep_water_and_loses_energy_in_shallow_water() {
    let jonswap = make(SpectrumKind::Jonswap, |_| {});
    let tma_deep = make(SpectrumKind::Tma, |p| p.depth_m = 1e4);
    let w_p = jonswap.peak_omega().expect("wind");
    let k_p = k_peak(&jonswap);
    for i in 0..=200 {
        let w = w_p * 0.3 * 1.03f64.powi(i);
        let (a, b) = (tma_deep.frequency_spectrum(w), jonswap.frequency_spectrum(w));
        assert!((a - b).abs() <= 1e-10 * b, "ω={w}: {a} vs {b}");
        let k = k_p * 0.1 * 1.05f64.powi(i);
        let (a, b) = (tma_deep.omnidirectional(k), jonswap.omnidirectional(k));
        assert!((a - b).abs() <= 1e-10 * b, "k={k}: {a} vs {b}");
    }
    let hs_j = jonswap.significant_wave_height();
    let hs_deep = tma_deep.significant_wave_height();
    assert!(rel(hs_deep, hs_j) < 1e-10);

    // In 5 m the depth factor removes energy. JONSWAP in 5 m (no Φ) keeps exactly the same m₀:
    // ∫ S_k dk = ∫ S dω whatever the dispersion.
    let tma_5 = make(SpectrumKind::Tma, |p| p.depth_m = 5.0);
    let jonswap_5 = make(SpectrumKind::Jonswap, |p| p.depth_m = 5.0);
    let (hs_t5, hs_j5) = (tma_5.significant_wave_height(), jonswap_5.significant_wave_height());
    println!(
        "Hs: JONSWAP deep {hs_j:.6} m, TMA 1e4 m {hs_deep:.6} m, JONSWAP 5 m {hs_j5:.6} m, \
         TMA 5 m {hs_t5:.6} m"
    );
    assert!(rel(hs_j5, hs_j) < 1e-9);
    // The expected reduction, integrated here from JONSWAP's S(ω) × Φ(ω sqrt(h/g)).
    let m0_expected = integrate_ln(
        &|w| jonswap.frequency_spectrum(w) * kitaigorodskii_depth_factor(w * (5.0 / G).sqrt()),
        w_p / 20.0,
        w_p * 1e5,
        1e-12,
    );
    let hs_expected = 4.0 * m0_expected.sqrt();
    println!("  TMA 5 m expected from S_J Φ: {hs_expected:.6} m");
    assert!(rel(hs_t5, hs_expected) < 1e-8);
    // Negative control: the 5 m TMA sea is clearly lower than JONSWAP (> 10 % in Hs here).
    assert!(hs_t5 < 0.9 * hs_j);
}

// --- Phillips --------------------------------------------------------------------------

/// docs/design.md's Phillips spectrum, written out independently.
fn phillips_design(a: f64, wind: f64, dir: f64, l: f64, kx: f64, kz: f64) -> f64 {
    let k2 = kx * kx + kz * kz;
    let big_l = wind * wind / G;
    let k_dot_w = (kx * dir.cos() + kz * dir.sin()) / k2.sqrt();
    a * (-1.0 / (k2 * big_l * big_l)).exp() / (k2 * k2) * k_dot_w * k_dot_w * (-k2 * l * l).exp()
}

#[test]
fn phillips_density_is_the_design_formula() {
    let mut worst: f64 = 0.0;
    for (wind, dir, a, l) in [
        (10.0, 0.0, PHILLIPS_AMPLITUDE_DEFAULT, PHILLIPS_SMALL_WAVE_DEFAULT_M),
        (25.0, 1.1, 3e-4, 0.5),
        (3.0, -2.0, 1.0, 0.0),
    ] {
        let s = make(SpectrumKind::Phillips, |p| {
            p.wind_speed = wind;
            p.wind_direction = dir;
            p.phillips_amplitude = a;
            p.phillips_small_wave_m = l;
        });
        let k_p = k_peak(&s);
        for i in 0..40 {
            for j in 0..40 {
                let kx = (f64::from(i) - 19.5) * 0.2 * k_p;
                let kz = (f64::from(j) - 19.7) * 0.23 * k_p;
                let expected = phillips_design(a, wind, dir, l, kx, kz);
                let got = s.density(kx, kz);
                if expected > 0.0 {
                    worst = worst.max(rel(got, expected));
                }
                assert!((got - expected).abs() <= 1e-13 * expected, "({kx}, {kz})");
                // And it is S_k D / k with D = cos²θ/π.
                let k = kx.hypot(kz);
                let theta = kz.atan2(kx) - dir;
                let via_views = s.omnidirectional(k) * s.spreading(k, theta) / k;
                assert!((via_views - expected).abs() <= 1e-12 * expected);
            }
        }
        // Negative control: |k̂·ŵ| instead of its square differs by far more than 1e-13.
        let (kx, kz) = (0.7 * k_p, 0.5 * k_p);
        let cos = (kx * dir.cos() + kz * dir.sin()) / kx.hypot(kz);
        let wrong = phillips_design(a, wind, dir, l, kx, kz) / cos.abs();
        assert!(rel(s.density(kx, kz), wrong) > 1e-13);
        // No NaN at or near k = 0; the limit is 0.
        for k in [0.0, 1e-300, 1e-160, 1e-80, 1e-12] {
            assert_eq!(s.density(k, 0.0), 0.0, "k={k}");
            assert_eq!(s.density(0.0, -k), 0.0, "k={k}");
            assert_eq!(s.omnidirectional(k), 0.0, "k={k}");
        }
    }
    println!("Phillips density vs docs/design.md formula: worst relative difference {worst:.1e}");
}

#[test]
fn phillips_variance_matches_closed_form() {
    // l = 0: m₀ = A π ∫ exp(−1/(kL)²)/k³ dk; u = 1/k² gives A π/2 ∫ e^(−u L²) du = A π L²/2.
    for wind in [5.0, 10.0, 30.0] {
        let s = make(SpectrumKind::Phillips, |p| {
            p.wind_speed = wind;
            p.phillips_small_wave_m = 0.0;
        });
        let big_l = wind * wind / G;
        let closed = PHILLIPS_AMPLITUDE_DEFAULT * PI * big_l * big_l / 2.0;
        let m0 = s.variance();
        println!("Phillips V={wind}: m₀ {m0:.9e} m², closed A π L²/2 {closed:.9e} m²");
        assert!(rel(m0, closed) < 1e-9);
        // Negative control: the default small-wave length (2.7 mm) removes 1.5·10⁻⁵ (V = 5)
        // to 1.8·10⁻⁸ (V = 30 m/s) of m₀ (measured), which this limit sees.
        let suppressed = make(SpectrumKind::Phillips, |p| p.wind_speed = wind).variance();
        println!("  with l = 2.7 mm: m₀ lower by {:.1e}", 1.0 - suppressed / closed);
        assert!(rel(suppressed, closed) > 1e-9);
    }
}

#[test]
fn phillips_default_amplitude_matches_the_pm_tail() {
    // A = α/(2π): both tails are α/(2k³).
    assert!(rel(PHILLIPS_AMPLITUDE_DEFAULT, 1.2892e-3) < 1e-4);
    let ph = make(SpectrumKind::Phillips, |p| p.phillips_small_wave_m = 0.0);
    let pm = make(SpectrumKind::PiersonMoskowitz, |_| {});
    let k = 1e4 * k_peak(&pm);
    let ratio = ph.omnidirectional(k) / pm.omnidirectional(k);
    let saturation = PM_ALPHA / (2.0 * k * k * k);
    println!(
        "tails at k = {k:.1} rad/m: Phillips/PM = {ratio:.9}, PM/(α/2k³) = {:.9}",
        pm.omnidirectional(k) / saturation
    );
    // Both cut-offs are 1 − O((k_p/k)²) = 1 − 10⁻⁸ here.
    assert!((ratio - 1.0).abs() < 1e-6);
    assert!(rel(pm.omnidirectional(k), saturation) < 1e-6);
    // Negative control: an amplitude 10⁻⁵ off is seen.
    let ph_off = make(SpectrumKind::Phillips, |p| {
        p.phillips_small_wave_m = 0.0;
        p.phillips_amplitude = PHILLIPS_AMPLITUDE_DEFAULT * (1.0 + 1e-5);
    });
    assert!((ph_off.omnidirectional(k) / pm.omnidirectional(k) - 1.0).abs() > 1e-6 * 5.0);
    // Small-wave default: the capillary length sqrt(σ/(ρ g)) of sea water.
    let capillary = (0.073 / (1025.0 * G)).sqrt();
    assert!(rel(PHILLIPS_SMALL_WAVE_DEFAULT_M, capillary) < 0.01, "{capillary}");
}

// --- Variance over the grid's square band ----------------------------------------------

#[test]
fn variance_over_square_matches_a_cartesian_integral() {
    // Phillips: F is smooth on the plane, so 2D Simpson converges fast (h⁴).
    // JONSWAP: the spreading's β jumps on the circles r = 0.56, 0.95, 1.6, where Cartesian
    // Simpson is only O(h); the measured difference sets its limit (printed).
    let cases = [
        (SpectrumKind::Phillips, 0.4, 1e-8),
        (SpectrumKind::PiersonMoskowitz, 0.4, 1e-4),
        (SpectrumKind::Jonswap, 0.4, 1e-4),
        (SpectrumKind::Jonswap, 0.0, 1e-4),
    ];
    for (kind, dir, tol) in cases {
        let s = make(kind, |p| p.wind_direction = dir);
        let k_p = k_peak(&s);
        for factor in [0.8, 1.3, 3.0] {
            let w = factor * k_p;
            let ours = s.variance_over_square(w, 0.0);
            let cartesian = simpson_square(&|kx, kz| s.density(kx, kz), w, 1600);
            let disc = integrate(&|k| s.omnidirectional(k), 1e-3 * k_p, w, 1e-13);
            println!(
                "{kind:?} dir {dir} W = {factor} k_p: square {ours:.9e}, Cartesian {cartesian:.9e} \
                 (rel {:.1e}), inscribed disc {disc:.9e}",
                rel(ours, cartesian)
            );
            assert!(rel(ours, cartesian) < tol);
            // Negative control: the inscribed disc (no corners) is told apart.
            assert!(rel(disc, cartesian) > tol);
        }
    }
}

#[test]
fn variance_over_a_large_square_is_the_whole_variance() {
    for kind in KINDS {
        let s = make(kind, |p| p.wind_direction = 0.3);
        let k_p = k_peak(&s);
        let m0 = s.variance();
        let whole = s.variance_over_square(1e4 * k_p, 0.0);
        // What lies beyond 10⁴ k_p: the k⁻³ tail, ~ (k_p/W)² of m₀.
        assert!(rel(whole, m0) < 1e-7, "{kind:?}: {whole} vs {m0}");
        assert_eq!(s.variance_over_square(f64::INFINITY, 0.0), m0);
        // Leaving out a disc of radius e removes ∫₀^e S_k dk, integrated here independently.
        let e = 0.9 * k_p;
        let inner = integrate(&|k| s.omnidirectional(k), 1e-3 * k_p, e, 1e-13);
        let without = s.variance_over_square(1e4 * k_p, e);
        println!("{kind:?}: m₀ {m0:.9e}, square 1e4 k_p {whole:.9e}, minus disc {without:.9e}");
        assert!(rel(without, whole - inner) < 1e-9);
        // Negative control: without removing it the two differ (inner is ≥ 1 % of m₀ here).
        assert!(rel(without, whole) > 1e-9);
        // An excluded disc larger than the square's corners leaves nothing.
        assert_eq!(s.variance_over_square(k_p, 1.5 * k_p), 0.0);
    }
}

// --- Extremes and invalid input --------------------------------------------------------

#[test]
fn extreme_parameters_give_finite_non_negative_values() {
    let mut cases: Vec<(String, WaveSpectrum)> = Vec::new();
    for kind in KINDS {
        cases.push((format!("{kind:?} wind 0"), make(kind, |p| p.wind_speed = 0.0)));
        cases.push((format!("{kind:?} wind 60"), make(kind, |p| p.wind_speed = 60.0)));
        cases.push((format!("{kind:?} wind max"), make(kind, |p| p.wind_speed = MAX_WIND_SPEED)));
        cases.push((format!("{kind:?} wind 0.01"), make(kind, |p| p.wind_speed = 0.01)));
        cases.push((format!("{kind:?} depth 0.01"), make(kind, |p| p.depth_m = 0.01)));
        cases.push((format!("{kind:?} fetch 10 m"), make(kind, |p| p.fetch_m = 10.0)));
        cases.push((
            format!("{kind:?} fetch max, wind max"),
            make(kind, |p| {
                p.fetch_m = MAX_FETCH_M;
                p.wind_speed = MAX_WIND_SPEED;
            }),
        ));
        cases.push((format!("{kind:?} γ 1"), make(kind, |p| p.peak_enhancement = 1.0)));
        cases.push((
            format!("{kind:?} γ 10, 0.01 m deep"),
            make(kind, |p| {
                p.peak_enhancement = 10.0;
                p.depth_m = 0.01;
            }),
        ));
    }
    let ks = [0.0, 1e-300, 1e-12, 1e-6, 0.01, 1.0, 100.0, 1e6, 1e300, f64::INFINITY];
    for (name, s) in &cases {
        for &k in &ks {
            for &(a, b) in &[(k, 0.0), (0.0, k), (-k, 0.6 * k), (0.6 * k, -0.8 * k)] {
                let f = s.density(a, b);
                assert!(f.is_finite() && f >= 0.0, "{name}: F({a}, {b}) = {f}");
            }
            let sk = s.omnidirectional(k);
            assert!(sk.is_finite() && sk >= 0.0, "{name}: S_k({k}) = {sk}");
            let sw = s.frequency_spectrum(k);
            assert!(sw.is_finite() && sw >= 0.0, "{name}: S({k}) = {sw}");
            for &theta in &[0.0, 1.0, PI, -PI, 100.0] {
                let d = s.spreading(k, theta);
                assert!(d.is_finite() && d >= 0.0, "{name}: D({k}, {theta}) = {d}");
            }
        }
        let hs = s.significant_wave_height();
        assert!(hs.is_finite() && hs >= 0.0, "{name}: Hs = {hs}");
        for w in [1e-12, 1.0, 1e6, f64::INFINITY] {
            let v = s.variance_over_square(w, 0.0);
            assert!(v.is_finite() && v >= 0.0, "{name}: V({w}) = {v}");
            assert!(v <= s.variance() * (1.0 + 1e-9), "{name}: V({w}) = {v} > m₀");
        }
        println!("{name:40}: Hs = {hs:.6e} m, ω_p = {:?}", s.peak_omega());
    }
    // Wind 0 is a flat sea: every density is 0, there is no peak.
    for kind in KINDS {
        let s = make(kind, |p| p.wind_speed = 0.0);
        assert!(s.is_flat() && s.peak_omega().is_none());
        assert_eq!(s.significant_wave_height(), 0.0);
        for &k in &ks {
            assert_eq!(s.density(k, 0.3 * k), 0.0);
            assert_eq!(s.omnidirectional(k), 0.0);
        }
        // Negative control: a light wind is not flat.
        assert!(make(kind, |p| p.wind_speed = 1.0).significant_wave_height() > 0.0);
    }
}

#[test]
fn invalid_parameters_are_errors_that_name_the_parameter() {
    type Edit = fn(&mut SpectrumParams);
    let bad: [(SpectrumKind, &str, Edit); 18] = [
        (SpectrumKind::Jonswap, "wind_speed", |p| p.wind_speed = f64::NAN),
        (SpectrumKind::Jonswap, "wind_speed", |p| p.wind_speed = -1.0),
        (SpectrumKind::Jonswap, "wind_speed", |p| p.wind_speed = f64::INFINITY),
        (SpectrumKind::Jonswap, "wind_speed", |p| p.wind_speed = MAX_WIND_SPEED * 1.01),
        (SpectrumKind::Jonswap, "wind_direction", |p| p.wind_direction = f64::NAN),
        (SpectrumKind::Jonswap, "fetch_m", |p| p.fetch_m = -5.0),
        (SpectrumKind::Jonswap, "fetch_m", |p| p.fetch_m = 0.0),
        (SpectrumKind::Tma, "fetch_m", |p| p.fetch_m = f64::NAN),
        (SpectrumKind::Tma, "fetch_m", |p| p.fetch_m = f64::INFINITY),
        (SpectrumKind::Jonswap, "depth_m", |p| p.depth_m = 0.0),
        (SpectrumKind::PiersonMoskowitz, "depth_m", |p| p.depth_m = -3.0),
        (SpectrumKind::Phillips, "depth_m", |p| p.depth_m = f64::NAN),
        (SpectrumKind::Jonswap, "peak_enhancement", |p| p.peak_enhancement = 0.99),
        (SpectrumKind::Tma, "peak_enhancement", |p| p.peak_enhancement = f64::NAN),
        (SpectrumKind::Phillips, "phillips_amplitude", |p| p.phillips_amplitude = -1e-3),
        (SpectrumKind::Phillips, "phillips_small_wave_m", |p| p.phillips_small_wave_m = -0.1),
        (SpectrumKind::Phillips, "gravity", |p| p.gravity = 0.0),
        (SpectrumKind::PiersonMoskowitz, "gravity", |p| p.gravity = f64::NAN),
    ];
    for (kind, expected_name, edit) in bad {
        let mut p = SpectrumParams { kind, ..SpectrumParams::default() };
        edit(&mut p);
        match WaveSpectrum::new(p) {
            Err(Error::InvalidParameter { name, reason, .. }) => {
                assert_eq!(name, expected_name);
                assert!(!reason.is_empty());
            }
            Ok(_) => panic!("{kind:?}: {expected_name} should be rejected"),
            Err(other) => panic!("{kind:?}: wrong error {other}"),
        }
    }
    // Negative controls: the defaults, and parameters a kind does not use, are accepted.
    for kind in KINDS {
        assert!(WaveSpectrum::new(SpectrumParams { kind, ..SpectrumParams::default() }).is_ok());
    }
    let pm_without_fetch = SpectrumParams {
        kind: SpectrumKind::PiersonMoskowitz,
        fetch_m: 0.0,
        peak_enhancement: 0.0,
        ..SpectrumParams::default()
    };
    assert!(WaveSpectrum::new(pm_without_fetch).is_ok());
    let deep = SpectrumParams { depth_m: f64::INFINITY, ..SpectrumParams::default() };
    assert!(WaveSpectrum::new(deep).is_ok());
    let message = WaveSpectrum::new(SpectrumParams { fetch_m: -5.0, ..SpectrumParams::default() })
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    println!("example error: {message}");
    assert!(message.contains("fetch_m") && message.contains("-5"));
}

#[test]
fn default_parameters_are_a_jonswap_sea() {
    let p = SpectrumParams::default();
    assert_eq!(p.kind, SpectrumKind::Jonswap);
    assert_eq!((p.wind_speed, p.fetch_m, p.peak_enhancement), (10.0, 100e3, 3.3));
    assert!(p.depth_m.is_infinite() && p.gravity == G);
    let s = WaveSpectrum::new(p).expect("defaults are valid");
    let hs = s.significant_wave_height();
    let period = TAU / s.peak_omega().expect("wind");
    println!("default sea: Hs {hs:.4} m, peak period {period:.3} s");
    // Measured 2.139 m and 6.23 s (U10 = 10 m/s, F = 100 km); a looser bracket guards the
    // order of magnitude against unit slips (km vs m).
    assert!((2.0..2.3).contains(&hs) && (6.0..6.5).contains(&period));
}
