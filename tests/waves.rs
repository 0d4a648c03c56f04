//! Wave synthesis against its definitions: the FFT against the direct sums of eq. 1, Parseval,
//! the dispersion relation read back from the maps, looping, the height query, the
//! displacement / bump bands, the frame cycle, extreme inputs and determinism.
//!
//! "rel" below is always: max |map − reference| over the points compared, divided by the max
//! |value| of that field over the whole map (the absolute error when the field is 0).
//! Every comparator is run once against a deliberately wrong input and must reject it.
//! `cargo test --release --test waves -- --nocapture` prints the measured figures.

use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

use num_complex::Complex;
use ocean_core::GRAVITY as G;
use ocean_core::dispersion::Dispersion;
use ocean_core::rng::{SplitMix64, mode_gaussians};
use ocean_core::waves::{
    FrameCycle, MapFloat, ModeParams, OceanParams, OceanSurface, SurfaceQuery, Synthesizer,
    WaveMaps, WaveModes, eval_direct,
};
use rustfft::FftPlannerScalar;

// ---------------------------------------------------------------------------------------------
// Test spectrum and oracles, written independently of the library's evaluation code.

/// A Phillips-like spectrum F(kx, kz), m⁴: A e^{−1/(kL)²}/k⁴ · directional · e^{−k²l²}, with
/// L = U²/g, the wind towards 0.3 rad, and one-sided spreading (cos² downwind, 0.1 cos²
/// upwind) so that F(k) ≠ F(−k) and the two halves of h̃ differ.
fn phillips(wind_speed: f64, amplitude: f64) -> impl Fn(f64, f64) -> f64 + Copy {
    let l_wind = wind_speed * wind_speed / G;
    let l_small = l_wind / 1000.0;
    let (wx, wz) = (0.3f64.cos(), 0.3f64.sin());
    move |kx, kz| {
        let k2 = kx * kx + kz * kz;
        if k2 == 0.0 {
            return 0.0;
        }
        let cos_wind = (kx * wx + kz * wz) / k2.sqrt();
        let spreading =
            if cos_wind >= 0.0 { cos_wind * cos_wind } else { 0.1 * cos_wind * cos_wind };
        amplitude * (-1.0 / (k2 * l_wind * l_wind)).exp() / (k2 * k2)
            * spreading
            * (-k2 * l_small * l_small).exp()
    }
}

const WIND: f64 = 10.0;
const AMPLITUDE: f64 = 0.01;

fn build(n: usize, l: f64, seed: u64, dispersion: Dispersion) -> WaveModes {
    WaveModes::new(&ModeParams::new(l, n, seed), dispersion, phillips(WIND, AMPLITUDE))
        .expect("valid modes")
}

/// The fields (h, Dx, Dz, hx, hz, J) by the plain sums of eq. 1, one sine and cosine per mode
/// and point; `sign` = −1 evaluates the wrong convention exp(−ik·x).
struct Oracle {
    /// (kx, kz, |k|, h̃)
    terms: Vec<(f64, f64, f64, Complex<f64>)>,
    lambda: f64,
    sign: f64,
}

impl Oracle {
    fn new(modes: &WaveModes, t: f64, lambda: f64, sign: f64) -> Self {
        let h0: HashMap<(i64, i64), Complex<f64>> =
            modes.modes().map(|m| ((m.n, m.m), m.h0)).collect();
        let terms = modes
            .modes()
            .filter(|m| m.active)
            .map(|m| {
                let e = Complex::cis(modes.dispersion().phase(m.k, t));
                let minus = h0[&(-m.n, -m.m)];
                (m.kx, m.kz, m.k, m.h0 * e + minus.conj() * e.conj())
            })
            .collect();
        Self { terms, lambda, sign }
    }

    fn fields(&self, x: f64, z: f64) -> [f64; 6] {
        let mut s = [0.0; 8]; // h, Dx, Dz, hx, hz, Dxx, Dzz, Dxz (before χ)
        for &(kx, kz, k, ht) in &self.terms {
            let c = ht * Complex::cis(self.sign * (kx * x + kz * z));
            let i_c = Complex::new(-c.im, c.re); // i·c
            s[0] += c.re;
            // D = χ Σ i k/|k| h̃ e^{ik·x} (χ = choppiness > 0 moves samples towards the
            // crests, as a Gerstner wave does); ∂Dx/∂x = χ Σ (i kx/k)(i kx) h̃ e^{ik·x}.
            s[1] += (i_c * (kx / k)).re;
            s[2] += (i_c * (kz / k)).re;
            s[3] += (i_c * kx).re;
            s[4] += (i_c * kz).re;
            s[5] -= (c * (kx * kx / k)).re;
            s[6] -= (c * (kz * kz / k)).re;
            s[7] -= (c * (kx * kz / k)).re;
        }
        let l = self.lambda;
        let j = (1.0 + l * s[5]) * (1.0 + l * s[6]) - (l * s[7]) * (l * s[7]);
        [s[0], l * s[1], l * s[2], s[3], s[4], j]
    }

    fn variance(&self) -> f64 {
        self.terms.iter().map(|t| t.3.norm_sqr()).sum()
    }
}

fn sample_points(n: usize, count: usize, seed: u64) -> Vec<(usize, usize)> {
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|_| ((rng.next_u64() % n as u64) as usize, (rng.next_u64() % n as u64) as usize))
        .collect()
}

fn field_max<T: MapFloat>(field: &[T]) -> f64 {
    field.iter().map(|v| v.cast_to_f64().abs()).fold(0.0, f64::max)
}

/// rel error of each of the six fields (see the file's header) at `points`.
fn rel_errors<T: MapFloat>(
    maps: &WaveMaps<T>,
    points: &[(usize, usize)],
    expected: &[[f64; 6]],
) -> [f64; 6] {
    let fields = maps.fields();
    let mut out = [0.0; 6];
    for (f, (_, field)) in fields.iter().enumerate() {
        let max_abs = field_max(field);
        let err = points
            .iter()
            .zip(expected)
            .map(|(&(i, j), e)| (field[maps.index(i, j)].cast_to_f64() - e[f]).abs())
            .fold(0.0, f64::max);
        out[f] = if max_abs > 0.0 { err / max_abs } else { err };
    }
    out
}

fn worst(errs: &[f64; 6]) -> f64 {
    errs.iter().copied().fold(0.0, f64::max)
}

fn grid_expected(oracle: &Oracle, points: &[(usize, usize)], n: usize, l: f64) -> Vec<[f64; 6]> {
    points
        .iter()
        .map(|&(i, j)| oracle.fields(i as f64 * l / n as f64, j as f64 * l / n as f64))
        .collect()
}

/// The 2D forward DFT divided by N²: the h̃ whose unnormalised inverse is `field`.
fn forward_fft2(field: &[f64], n: usize) -> Vec<Complex<f64>> {
    let fft = FftPlannerScalar::new().plan_fft_forward(n);
    let mut data: Vec<Complex<f64>> = field.iter().map(|&v| Complex::new(v, 0.0)).collect();
    fft.process(&mut data); // rows (x)
    let mut column = vec![Complex::new(0.0, 0.0); n];
    for i in 0..n {
        for j in 0..n {
            column[j] = data[j * n + i];
        }
        fft.process(&mut column);
        for j in 0..n {
            data[j * n + i] = column[j] / (n * n) as f64;
        }
    }
    data
}

fn bits<T: MapFloat>(maps: &WaveMaps<T>) -> Vec<u64> {
    maps.fields().iter().flat_map(|(_, f)| f.iter().map(|v| v.cast_to_f64().to_bits())).collect()
}

// ---------------------------------------------------------------------------------------------
// The generator.

#[test]
fn gaussians_have_unit_moments_and_are_independent() {
    // 10⁶ samples: 500 000 modes × (ξ_r, ξ_i).
    let (mut xr, mut xi, mut xr_next, mut xr_seed) = (vec![], vec![], vec![], vec![]);
    for n in -500..500 {
        for m in 0..500 {
            let (a, b) = mode_gaussians(11, n, m);
            xr.push(a);
            xi.push(b);
            xr_next.push(mode_gaussians(11, n + 1, m).0);
            xr_seed.push(mode_gaussians(12, n, m).0);
        }
    }
    let all: Vec<f64> = xr.iter().chain(&xi).copied().collect();
    let count = all.len() as f64;
    let mean = all.iter().sum::<f64>() / count;
    let var = all.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / count;
    // Standard errors: mean 1/√n, variance √(2/n) (Gaussian fourth moment 3).
    let (se_mean, se_var) = (1.0 / count.sqrt(), (2.0 / count).sqrt());
    println!(
        "gaussians: n = {count}, mean = {mean:.2e} ({:.1} SE), var − 1 = {:.2e} ({:.1} SE)",
        mean / se_mean,
        var - 1.0,
        (var - 1.0) / se_var
    );
    assert!(mean.abs() < 5.0 * se_mean);
    assert!((var - 1.0).abs() < 5.0 * se_var);
    // Negative control: 1 % too wide a distribution is rejected by the same bound.
    assert!((1.01f64.powi(2) * var - 1.0).abs() > 5.0 * se_var);

    let corr =
        |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>() / a.len() as f64;
    let se_corr = 1.0 / (xr.len() as f64).sqrt();
    for (name, other) in
        [("ξ_i, same mode", &xi), ("ξ_r, mode (n+1, m)", &xr_next), ("ξ_r, seed + 1", &xr_seed)]
    {
        let rho = corr(&xr, other);
        println!("corr(ξ_r, {name}) = {rho:.2e} ({:.1} SE)", rho / se_corr);
        assert!(rho.abs() < 5.0 * se_corr, "{name}: {rho}");
    }
    // Negative control: a pair with correlation 0.01 is rejected.
    let mixed: Vec<f64> =
        xr.iter().zip(&xi).map(|(a, b)| 0.01 * a + (1.0 - 1e-4f64).sqrt() * b).collect();
    assert!(corr(&xr, &mixed).abs() > 5.0 * se_corr);
}

#[test]
fn larger_grid_keeps_the_low_modes() {
    let d = Dispersion::deep(G);
    let small = build(16, 100.0, 5, d);
    let large = build(64, 100.0, 5, d);
    let by_index: HashMap<(i64, i64), Complex<f64>> =
        large.modes().map(|m| ((m.n, m.m), m.h0)).collect();
    let mut compared = 0;
    for m in small.modes().filter(|m| m.active) {
        assert_eq!(m.h0, by_index[&(m.n, m.m)]);
        compared += 1;
    }
    assert_eq!(compared, 15 * 15 - 1);
    // And a different seed changes them.
    let other = build(16, 100.0, 6, d);
    assert!(small.modes().zip(other.modes()).any(|(a, b)| a.h0 != b.h0));
}

// ---------------------------------------------------------------------------------------------
// FFT synthesis against the direct sum.

#[test]
fn fft_synthesis_matches_the_direct_sum() {
    let l = 100.0;
    let (mut worst64, mut worst32) = ([0.0f64; 6], [0.0f64; 6]);
    for &n in &[16usize, 45, 48, 64, 128] {
        let modes = build(n, l, 7, Dispersion::deep(G));
        let mut s64 = Synthesizer::<f64>::new(n).expect("synthesizer");
        let mut s32 = Synthesizer::<f32>::new(n).expect("synthesizer");
        let points = sample_points(n, 64, n as u64);
        for &(t, lambda) in &[(0.0, 0.0), (3.7, 0.9), (1.0e4, -1.3)] {
            let expected = grid_expected(&Oracle::new(&modes, t, lambda, 1.0), &points, n, l);
            let e64 =
                rel_errors(&s64.synthesize(&modes, t, lambda).expect("maps"), &points, &expected);
            let e32 =
                rel_errors(&s32.synthesize(&modes, t, lambda).expect("maps"), &points, &expected);
            for f in 0..6 {
                worst64[f] = worst64[f].max(e64[f]);
                worst32[f] = worst32[f].max(e32[f]);
            }
            assert!(worst(&e64) <= 1e-12, "f64 N={n} t={t} λ={lambda}: {e64:?}");
            assert!(worst(&e32) <= 1e-5, "f32 N={n} t={t} λ={lambda}: {e32:?}");
        }
    }
    let names = WaveMaps::<f64>::FIELD_NAMES;
    for f in 0..6 {
        println!(
            "FFT vs direct, max rel error {:>8}: f64 {:.2e}, f32 {:.2e}",
            names[f], worst64[f], worst32[f]
        );
    }
}

#[test]
fn fft_vs_direct_comparator_rejects_wrong_maps() {
    let (n, l, t, lambda) = (48, 100.0, 3.7, 0.9);
    let modes = build(n, l, 7, Dispersion::deep(G));
    let points = sample_points(n, 64, 1);
    let expected = grid_expected(&Oracle::new(&modes, t, lambda, 1.0), &points, n, l);
    let biggest = (0..n * n)
        .max_by(|&a, &b| modes.h0()[a].norm().total_cmp(&modes.h0()[b].norm()))
        .expect("bins");

    // One mode's amplitude off by 1e-6 (f64) / 1e-3 (f32).
    let mut perturbed = modes.clone();
    perturbed.h0_mut()[biggest] *= 1.0 + 1e-6;
    let e = rel_errors(
        &Synthesizer::<f64>::new(n).expect("s").synthesize(&perturbed, t, lambda).expect("m"),
        &points,
        &expected,
    );
    println!("perturbed mode (1e-6), f64: rel {:.2e}", worst(&e));
    assert!(worst(&e) > 1e-12);
    let mut perturbed = modes.clone();
    perturbed.h0_mut()[biggest] *= 1.0 + 1e-3;
    let e = rel_errors(
        &Synthesizer::<f32>::new(n).expect("s").synthesize(&perturbed, t, lambda).expect("m"),
        &points,
        &expected,
    );
    assert!(worst(&e) > 1e-5);

    // The sign convention flipped: exp(−ik·x).
    let flipped = grid_expected(&Oracle::new(&modes, t, lambda, -1.0), &points, n, l);
    let e = rel_errors(
        &Synthesizer::<f64>::new(n).expect("s").synthesize(&modes, t, lambda).expect("m"),
        &points,
        &flipped,
    );
    println!("flipped sign convention: rel {:.2e}", worst(&e));
    assert!(worst(&e) > 1e-2);
}

#[test]
fn eval_direct_is_the_direct_sum_off_the_grid() {
    let (n, l, t, lambda) = (32, 80.0, 12.5, 0.7);
    let modes = build(n, l, 3, Dispersion::new(G, 8.0, 0.0).expect("dispersion"));
    let oracle = Oracle::new(&modes, t, lambda, 1.0);
    let mut worst_err = 0.0f64;
    for &(x, z) in &[(0.3, 7.7), (-13.1, 101.9), (79.99, 0.01), (1234.5, -987.6)] {
        let s = eval_direct(&modes, t, lambda, x, z).expect("sample");
        let got = [s.height, s.disp_x, s.disp_z, s.slope_x, s.slope_z, s.jacobian];
        let want = oracle.fields(x, z);
        for f in 0..6 {
            worst_err = worst_err.max((got[f] - want[f]).abs() / want[f].abs().max(1.0));
        }
    }
    println!("eval_direct vs plain sum, off grid: {worst_err:.2e}");
    assert!(worst_err < 1e-11);
}

// ---------------------------------------------------------------------------------------------
// Parseval and the variance of the spectrum.

#[test]
fn parseval_holds_exactly() {
    let (n, l, t) = (64, 100.0, 2.5);
    let modes = build(n, l, 9, Dispersion::deep(G));
    let maps = Synthesizer::<f64>::new(n).expect("s").synthesize(&modes, t, 0.0).expect("m");
    let mean_h2 = maps.height.iter().map(|h| h * h).sum::<f64>() / (n * n) as f64;
    let sum_ht2 = Oracle::new(&modes, t, 0.0, 1.0).variance();
    let rel = (mean_h2 - sum_ht2).abs() / sum_ht2;
    println!("Parseval: mean h² = {mean_h2:.6e}, Σ|h̃|² = {sum_ht2:.6e}, rel {rel:.2e}");
    assert!(rel < 1e-12);
    // Negative control: one mode 1e-6 larger changes Σ|h̃|² by more than the bound.
    let mut perturbed = modes.clone();
    let biggest = (0..n * n)
        .max_by(|&a, &b| modes.h0()[a].norm().total_cmp(&modes.h0()[b].norm()))
        .expect("bins");
    perturbed.h0_mut()[biggest] *= 1.0 + 1e-6;
    let other = Oracle::new(&perturbed, t, 0.0, 1.0).variance();
    assert!((mean_h2 - other).abs() / other > 1e-12);
}

#[test]
fn variance_over_seeds_is_the_integral_of_the_spectrum() {
    let (n, l, seeds) = (32, 100.0, 400);
    let f = phillips(WIND, AMPLITUDE);
    let reference = build(n, l, 0, Dispersion::deep(G));
    let dk2 = (TAU / l).powi(2);
    // Expected Σ F Δk² over the active modes, and per mode σ² = E|h̃|² = (F(k) + F(−k)) Δk²/2.
    let mut expected = 0.0;
    let mut sum_sigma4 = 0.0;
    for m in reference.modes().filter(|m| m.active) {
        expected += f(m.kx, m.kz) * dk2;
        let sigma2 = (f(m.kx, m.kz) + f(-m.kx, -m.kz)) * dk2 / 2.0;
        sum_sigma4 += sigma2 * sigma2;
    }
    // V = Σ_k |h̃_k|² = 2 Σ_{half plane} |h̃_k|²; each |h̃_k|² is σ_k²·Exp(1), independent across
    // the half plane, so Var V = 4 Σ_half σ⁴ = 2 Σ_all σ⁴.
    let se = (2.0 * sum_sigma4 / seeds as f64).sqrt();
    let mut synth = Synthesizer::<f64>::new(n).expect("s");
    let mut total = 0.0;
    for seed in 0..seeds {
        let modes = build(n, l, seed, Dispersion::deep(G));
        let maps = synth.synthesize(&modes, 1.0, 0.0).expect("m");
        total += maps.height.iter().map(|h| h * h).sum::<f64>() / (n * n) as f64;
    }
    let mean = total / seeds as f64;
    println!(
        "variance over {seeds} seeds: {mean:.5e} vs Σ F Δk² = {expected:.5e} \
         ({:+.2} SE, SE = {:.1e} rel, Hs = {:.2} m); library says {:.5e}",
        (mean - expected) / se,
        se / expected,
        4.0 * expected.sqrt(),
        reference.expected_variance()
    );
    assert!((mean - expected).abs() < 5.0 * se);
    assert!((reference.expected_variance() - expected).abs() < 1e-12 * expected);
    // Negative control: Tessendorf's normalisation (twice the variance) is rejected.
    assert!((mean - 2.0 * expected).abs() > 5.0 * se);
}

// ---------------------------------------------------------------------------------------------
// Dispersion read back from the maps.

#[test]
fn dispersion_is_read_back_from_the_maps() {
    let (n, l, t, dt) = (64, 100.0, 10.0, 0.5);
    let mut synth = Synthesizer::<f64>::new(n).expect("s");
    for (name, depth) in [("deep", f64::INFINITY), ("depth 5 m", 5.0)] {
        let modes = build(n, l, 21, Dispersion::new(G, depth, 0.0).expect("dispersion"));
        let mut spectrum =
            |time: f64| forward_fft2(&synth.synthesize(&modes, time, 0.0).expect("m").height, n);
        let (minus, now, plus) = (spectrum(t - dt), spectrum(t), spectrum(t + dt));
        let scale = now.iter().map(|c| c.norm()).fold(0.0, f64::max);
        // h̃(t ± dt) = a e^{iω(t±dt)} + b e^{−iω(t±dt)}, so per bin
        // h̃(t+dt) + h̃(t−dt) = 2 cos(ω dt) h̃(t).
        let residual = |omega: &dyn Fn(f64) -> f64| {
            (0..n * n)
                .map(|bin| {
                    let c = 2.0 * (omega(modes.wavenumbers()[bin]) * dt).cos();
                    (plus[bin] + minus[bin] - now[bin] * c).norm() / scale
                })
                .fold(0.0, f64::max)
        };
        let omega_true = |k: f64| {
            if depth.is_finite() { (G * k * (k * depth).tanh()).sqrt() } else { (G * k).sqrt() }
        };
        let err = residual(&omega_true);
        println!(
            "dispersion read back ({name}): worst |H(t+dt) + H(t−dt) − 2cos(ω dt)H(t)| / max|H| = {err:.2e}"
        );
        assert!(err < 1e-12, "{name}: {err}");
        // Negative control: the wrong relation (deep for 5 m; 1 % off for deep) is rejected.
        let wrong: Box<dyn Fn(f64) -> f64> = if depth.is_finite() {
            Box::new(|k: f64| (G * k).sqrt())
        } else {
            Box::new(|k: f64| 1.01 * (G * k).sqrt())
        };
        let wrong_err = residual(&wrong);
        println!("  with the wrong ω: {wrong_err:.2e}");
        assert!(wrong_err > 1e-4);
    }
}

// ---------------------------------------------------------------------------------------------
// Looping.

#[test]
fn looping_repeats_exactly() {
    let (n, l, period) = (32, 100.0, 20.0);
    let looping = Dispersion::new(G, f64::INFINITY, period).expect("dispersion");
    let modes = build(n, l, 4, looping);
    let mut synth = Synthesizer::<f64>::new(n).expect("s");
    // t + T is exact in f64 for these t, so the reduced times and the maps are identical.
    for &t in &[0.0, 3.25, 1.0e6, 1.0e6 + 0.1, 1.0e9 + 0.25] {
        let a = synth.synthesize(&modes, t, -0.8).expect("m");
        let b = synth.synthesize(&modes, t + period, -0.8).expect("m");
        assert!(a.fields().iter().flat_map(|(_, f)| f.iter()).all(|v| v.is_finite()));
        assert_eq!(bits(&a), bits(&b), "t = {t}");
    }
    // t = 10⁹ + 0.1 and t + T: both rounded in f64 (ulp 1.2e-7 s); the maps then agree to
    // Σ 2|h0| ω_max Δt.
    let t = 1.0e9 + 0.1;
    let (a, b) = (
        synth.synthesize(&modes, t, 0.0).expect("m"),
        synth.synthesize(&modes, t + period, 0.0).expect("m"),
    );
    let diff = a.height.iter().zip(&b.height).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    let omega_max = modes.omegas().iter().copied().fold(0.0, f64::max);
    let bound =
        modes.h0().iter().map(|h| 2.0 * h.norm()).sum::<f64>() * omega_max * 2.0 * f64::EPSILON * t
            + 1e-13;
    println!("looping at t = 1e9 + 0.1: max |h(t+T) − h(t)| = {diff:.2e} m (bound {bound:.1e})");
    assert!(diff <= bound);
    // Negative control: without looping h(t + T) ≠ h(t).
    let free = build(n, l, 4, Dispersion::deep(G));
    let (a, b) = (
        synth.synthesize(&free, 3.25, 0.0).expect("m"),
        synth.synthesize(&free, 3.25 + period, 0.0).expect("m"),
    );
    let diff = a.height.iter().zip(&b.height).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    assert!(diff > 1e-3 * field_max(&a.height));
}

// ---------------------------------------------------------------------------------------------
// Height query.

#[test]
fn query_equals_the_maps_at_grid_points() {
    let (n, l, t) = (32, 100.0, 4.0);
    let modes = build(n, l, 13, Dispersion::deep(G));
    let mut synth = Synthesizer::<f64>::new(n).expect("s");
    for lambda in [0.0, 0.7] {
        let maps = synth.synthesize(&modes, t, lambda).expect("m");
        let query = SurfaceQuery::new(&modes, t, lambda).expect("q");
        let points: Vec<(usize, usize)> =
            (0..n).flat_map(|j| (0..n).map(move |i| (i, j))).collect();
        let expected: Vec<[f64; 6]> = points
            .iter()
            .map(|&(i, j)| {
                let s = query.sample(i as f64 * l / n as f64, j as f64 * l / n as f64);
                [s.height, s.disp_x, s.disp_z, s.slope_x, s.slope_z, s.jacobian]
            })
            .collect();
        let e = rel_errors(&maps, &points, &expected);
        println!("query.sample vs maps at all grid points (λ = {lambda}): rel {:.2e}", worst(&e));
        assert!(worst(&e) < 1e-12);

        // The displaced surface: height_at above the displaced position of sample (i, j) is
        // the map's height there.
        let mut worst_h = 0.0f64;
        for &(i, j) in points.iter().step_by(7) {
            let idx = maps.index(i, j);
            let x = i as f64 * l / n as f64 + maps.disp_x[idx];
            let z = j as f64 * l / n as f64 + maps.disp_z[idx];
            worst_h = worst_h.max((query.height_at(x, z) - maps.height[idx]).abs());
        }
        let rel = worst_h / field_max(&maps.height);
        println!("  height_at over displaced grid points: rel {rel:.2e}");
        assert!(rel < 1e-9);
    }
}

#[test]
fn query_is_the_band_limited_interpolant() {
    // The same waves on a grid twice as fine: the density is cut to the coarse band, and the
    // modes are keyed by (n, m), so the fine grid holds exactly the coarse grid's waves.
    let (n, l, t, lambda) = (32, 100.0, 6.0, 0.6);
    let coarse = build(n, l, 17, Dispersion::deep(G));
    let f = phillips(WIND, AMPLITUDE);
    let half = (n / 2) as f64;
    let cut = move |kx: f64, kz: f64| {
        let index = |k: f64| (k * l / TAU).round().abs();
        if index(kx) < half && index(kz) < half { f(kx, kz) } else { 0.0 }
    };
    let fine =
        WaveModes::new(&ModeParams::new(l, 2 * n, 17), Dispersion::deep(G), cut).expect("fine");
    let fine_maps =
        Synthesizer::<f64>::new(2 * n).expect("s").synthesize(&fine, t, lambda).expect("m");
    let query = SurfaceQuery::new(&coarse, t, lambda).expect("q");
    let coarse_maps =
        Synthesizer::<f64>::new(n).expect("s").synthesize(&coarse, t, lambda).expect("m");
    // Points half-way between the coarse grid points.
    let points: Vec<(usize, usize)> =
        (0..n).flat_map(|j| (0..n).map(move |i| (2 * i + 1, 2 * j + 1))).collect();
    let expected: Vec<[f64; 6]> = points
        .iter()
        .map(|&(i, j)| {
            let s = query.sample(i as f64 * l / (2 * n) as f64, j as f64 * l / (2 * n) as f64);
            [s.height, s.disp_x, s.disp_z, s.slope_x, s.slope_z, s.jacobian]
        })
        .collect();
    let e = rel_errors(&fine_maps, &points, &expected);
    println!("query between grid points vs the 2N synthesis: rel {:.2e}", worst(&e));
    assert!(worst(&e) < 1e-12);
    // Negative control: bilinear interpolation of the coarse map is not band-limited.
    let bilinear: Vec<[f64; 6]> = points
        .iter()
        .map(|&(i, j)| {
            let (i0, j0) = ((i - 1) / 2, (j - 1) / 2);
            let (i1, j1) = ((i0 + 1) % n, (j0 + 1) % n);
            let h = &coarse_maps.height;
            let avg = 0.25 * (h[j0 * n + i0] + h[j0 * n + i1] + h[j1 * n + i0] + h[j1 * n + i1]);
            [avg, 0.0, 0.0, 0.0, 0.0, 0.0]
        })
        .collect();
    let e = rel_errors(&fine_maps, &points, &bilinear);
    assert!(e[0] > 1e-3);
}

#[test]
fn height_at_inverts_the_displacement() {
    let (n, l, t, lambda) = (32, 100.0, 8.0, 0.8);
    let modes = build(n, l, 23, Dispersion::deep(G));
    let maps = Synthesizer::<f64>::new(n).expect("s").synthesize(&modes, t, lambda).expect("m");
    let min_j = maps.jacobian.iter().copied().fold(f64::INFINITY, f64::min);
    println!("inversion test: λ = {lambda}, min J on the grid = {min_j:.3}");
    assert!(min_j > 0.1, "the test wants a surface that does not fold");
    let query = SurfaceQuery::new(&modes, t, lambda).expect("q");
    let mut rng = SplitMix64::new(5);
    let (mut worst_residual, mut worst_naive, mut max_iterations) = (0.0f64, 0.0f64, 0);
    for _ in 0..200 {
        let x = (rng.next_open_closed() * 3.0 - 1.0) * l;
        let z = (rng.next_open_closed() * 3.0 - 1.0) * l;
        let inv = query.invert(x, z);
        assert!(inv.converged);
        max_iterations = max_iterations.max(inv.iterations);
        // The residual recomputed from scratch.
        let s = query.sample(inv.x0, inv.z0);
        let residual = (inv.x0 + s.disp_x - x).hypot(inv.z0 + s.disp_z - z);
        worst_residual = worst_residual.max(residual);
        assert_eq!(query.height_at(x, z), inv.sample.height);
        let naive = query.sample(x, z);
        worst_naive = worst_naive.max((x + naive.disp_x - x).hypot(z + naive.disp_z - z));
    }
    println!(
        "height_at: worst |x0 + D(x0) − x| = {worst_residual:.2e} m, ≤ {max_iterations} \
         iterations (uninverted: {worst_naive:.2e} m)"
    );
    assert!(worst_residual < 1e-9);
    // Negative control: x0 = x (no inversion) fails the same check.
    assert!(worst_naive > 1e-9);
    // λ = 0: nothing to invert.
    let flat_query = SurfaceQuery::new(&modes, t, 0.0).expect("q");
    assert_eq!(flat_query.height_at(12.3, 45.6), flat_query.sample(12.3, 45.6).height);
}

#[test]
fn normal_at_is_the_gradient_of_height_at() {
    let (n, l, t, lambda) = (32, 100.0, 8.0, 0.8);
    let modes = build(n, l, 23, Dispersion::deep(G));
    let query = SurfaceQuery::new(&modes, t, lambda).expect("q");
    let delta = 1e-4;
    let mut rng = SplitMix64::new(8);
    let (mut worst_err, mut worst_naive) = (0.0f64, 0.0f64);
    for _ in 0..50 {
        let (x, z) = (rng.next_open_closed() * l, rng.next_open_closed() * l);
        let hx = (query.height_at(x + delta, z) - query.height_at(x - delta, z)) / (2.0 * delta);
        let hz = (query.height_at(x, z + delta) - query.height_at(x, z - delta)) / (2.0 * delta);
        let norm = (hx * hx + 1.0 + hz * hz).sqrt();
        let fd = [-hx / norm, 1.0 / norm, -hz / norm];
        let got = query.normal_at(x, z);
        let err = (0..3).map(|c| (got[c] - fd[c]).abs()).fold(0.0, f64::max);
        worst_err = worst_err.max(err);
        // The slopes at the parameter point, ignoring the Jacobian: wrong for λ ≠ 0.
        let s = query.invert(x, z).sample;
        let nn = (s.slope_x * s.slope_x + 1.0 + s.slope_z * s.slope_z).sqrt();
        let naive = [-s.slope_x / nn, 1.0 / nn, -s.slope_z / nn];
        worst_naive = worst_naive.max((0..3).map(|c| (naive[c] - fd[c]).abs()).fold(0.0, f64::max));
    }
    println!(
        "normal_at vs central differences of height_at: {worst_err:.2e} (uncorrected slopes: {worst_naive:.2e})"
    );
    assert!(worst_err < 1e-5);
    assert!(worst_naive > 1e-5);
}

// ---------------------------------------------------------------------------------------------
// Displacement and bump maps.

/// A smooth spectrum (a ring around k = 1 rad/m), so that both lattices integrate it well.
fn ring(kx: f64, kz: f64) -> f64 {
    let k = (kx * kx + kz * kz).sqrt();
    1e-3 * (-((k - 1.0) / 1.5).powi(2)).exp()
}

/// Builds the two maps and checks that their bands are disjoint, cover the union square and
/// that the held modes' cells tile it (the weighted cell areas add up to its area).
fn check_bands(l: f64, n_d: usize, r: usize, n_b: usize) -> OceanSurface {
    let params = OceanParams {
        patch_size_m: l,
        displacement_resolution: n_d,
        bump_ratio: r,
        bump_resolution: n_b,
        seed: 31,
        dispersion: Dispersion::deep(G),
    };
    let ocean = OceanSurface::new(&params, ring).expect("ocean");
    let l_b = l / r as f64;
    let (k_nyq_d, k_nyq_b) = (PI * n_d as f64 / l, PI * n_b as f64 / l_b);
    let index = |k: f64| (k * l / TAU).round() as i64; // on the displacement lattice
    let mut held = HashMap::new();
    for m in ocean.displacement.modes().filter(|m| m.active) {
        assert!(m.kx.abs().max(m.kz.abs()) < k_nyq_d * (1.0 - 1e-12));
        assert!(held.insert((index(m.kx), index(m.kz)), "displacement").is_none());
    }
    for m in ocean.bump.modes().filter(|m| m.active) {
        let k_cheb = m.kx.abs().max(m.kz.abs());
        assert!(k_cheb >= k_nyq_d * (1.0 - 1e-12), "bump mode inside the displacement band");
        assert!(k_cheb < k_nyq_b * (1.0 - 1e-12), "bump mode at or above its Nyquist");
        assert!(held.insert((index(m.kx), index(m.kz)), "bump").is_none(), "a wave counted twice");
    }
    // Covering: every lattice point of either map, below its own Nyquist and inside the union
    // square, is held by exactly one map.
    let half = |n: usize| (n as i64 - 1) / 2; // the largest |index| below Nyquist
    for i in -half(n_d)..=half(n_d) {
        for j in -half(n_d)..=half(n_d) {
            let want = if (i, j) == (0, 0) { None } else { Some("displacement") };
            assert_eq!(held.get(&(i, j)).copied(), want);
        }
    }
    let r_i = r as i64;
    for i in -half(n_b)..=half(n_b) {
        for j in -half(n_b)..=half(n_b) {
            if 2 * r_i * i.abs().max(j.abs()) >= n_d as i64 {
                assert_eq!(held.get(&(r_i * i, r_i * j)).copied(), Some("bump"));
            }
        }
    }
    // Tiling: the frame between the two maps' outer cell edges has the held cells' area.
    let (dk_d, dk_b) = (TAU / l, TAU / l_b);
    let edge_d = (half(n_d) as f64 + 0.5) * dk_d;
    let edge_b = (half(n_b) as f64 + 0.5) * dk_b;
    let frame_area: f64 = ocean.bump.modes().map(|m| m.cell_weight).sum::<f64>() * dk_b * dk_b;
    let want_area = (2.0 * edge_b).powi(2) - (2.0 * edge_d).powi(2);
    assert!(
        (frame_area - want_area).abs() < 1e-12 * want_area,
        "N_d {n_d}, r {r}, N_b {n_b}: cells {frame_area}, frame {want_area}"
    );
    // Negative control: unit weights do not tile it (except where the lattices align, r = 1).
    let unit_area = ocean.bump.modes().filter(|m| m.active).count() as f64 * dk_b * dk_b;
    assert!(r == 1 || (unit_area - want_area).abs() > 1e-3 * want_area);
    ocean
}

#[test]
fn bump_and_displacement_bands_are_disjoint_and_cover() {
    // Overlapping edge cells (r even), a gap (r = 3: the innermost bump ring is at 18 > 16.5),
    // an odd N_d, the innermost ring at c₀ = r, and r = 1.
    for (n_d, r, n_b) in [(32, 4, 32), (32, 3, 24), (33, 2, 40), (6, 4, 8), (16, 1, 40)] {
        check_bands(100.0, n_d, r, n_b);
    }
    let (l, n_d, r, n_b) = (100.0, 32, 4, 32);
    let ocean = check_bands(l, n_d, r, n_b);
    let (dk_d, dk_b) = (TAU / l, TAU * r as f64 / l);
    let edge_d = (((n_d - 1) / 2) as f64 + 0.5) * dk_d;
    let edge_b = (((n_b - 1) / 2) as f64 + 0.5) * dk_b;
    // Energy: the two Riemann sums against ∫∫ F over the union square, midpoint rule on a grid
    // 16× finer than the displacement lattice.
    let step = dk_d / 16.0;
    let cells = (2.0 * edge_b / step).round() as i64;
    let (mut inner, mut outer) = (0.0, 0.0);
    for a in 0..cells {
        for b in 0..cells {
            let (kx, kz) = (-edge_b + (a as f64 + 0.5) * step, -edge_b + (b as f64 + 0.5) * step);
            let v = ring(kx, kz) * step * step;
            if kx.abs().max(kz.abs()) < edge_d { inner += v } else { outer += v }
        }
    }
    let (var_d, var_b) = (ocean.displacement.expected_variance(), ocean.bump.expected_variance());
    let total_err = (var_d + var_b - inner - outer).abs() / (inner + outer);
    // Without the edge weights (every bump cell a full Δk_b² square):
    let unweighted: f64 =
        ocean.bump.modes().filter(|m| m.active).map(|m| ring(m.kx, m.kz) * dk_b * dk_b).sum();
    let unweighted_err = (var_d + unweighted - inner - outer).abs() / (inner + outer);
    println!(
        "bands: displacement Σ F Δk² = {var_d:.5e} (∫ inner {inner:.5e}), bump {var_b:.5e} (∫ frame {outer:.5e}); \
         total rel error {total_err:.2e} (unweighted edge cells: {unweighted_err:.2e})"
    );
    // The remaining error is quadrature: the midpoint rule on the coarse bump lattice,
    // Δk_b²/24·|F''|/F ≈ 0.25²/24 · 2/1.5² ≈ 0.2 % at the ring's crest and more in its flanks,
    // and the first-order error of the stretched edge cells (their mode is not at their
    // centroid); measured 0.46 %. The bound is 1 %, twice that.
    assert!(total_err < 1e-2);
    // Negative control: the unweighted accounting overcounts the band edge (measured 3.8 %).
    assert!(unweighted_err > 1e-2);

    // A wave vector gets the same random numbers in either map: the bump's h0 is the h0 of a
    // displacement grid fine enough to hold it, scaled by Δk_b/Δk_d = r.
    let big =
        WaveModes::new(&ModeParams::new(l, r * n_b, 31), Dispersion::deep(G), ring).expect("big");
    let by_index: HashMap<(i64, i64), Complex<f64>> =
        big.modes().map(|m| ((m.n, m.m), m.h0)).collect();
    for m in ocean.bump.modes().filter(|m| m.active) {
        let want = by_index[&(r as i64 * m.n, r as i64 * m.m)] * (r as f64 * m.cell_weight.sqrt());
        assert!((m.h0 - want).norm() <= 1e-14 * want.norm());
    }
}

// ---------------------------------------------------------------------------------------------
// Frame cycle.

#[test]
fn frame_cycle_samples_above_the_temporal_nyquist_limit() {
    let (n, l, period) = (32, 100.0, 20.0);
    let modes = build(n, l, 2, Dispersion::new(G, 30.0, period).expect("dispersion"));
    let mut synth = Synthesizer::<f32>::new(n).expect("s");
    let cycle = FrameCycle::new(&modes, &mut synth, -0.5).expect("cycle");
    let count = cycle.frame_count();
    let omega_max =
        (0..n * n).filter(|&b| modes.is_live(b)).map(|b| modes.omegas()[b]).fold(0.0, f64::max);
    let limit = omega_max * period / std::f64::consts::PI;
    println!("frame cycle: ω_max = {omega_max:.3} rad/s, ω_max T/π = {limit:.3}, frames = {count}");
    assert!(
        count as f64 > limit + 0.5 && (count - 1) as f64 <= limit + 1e-9,
        "smallest F > ω_max T/π"
    );
    for &t in &[0.3, 7.77, 19.2, 1.0e6 + 4.1] {
        assert_eq!(cycle.frame_index(t), cycle.frame_index(t + period));
        assert!(std::ptr::eq(cycle.frame_at(t), cycle.frame_at(t + period)));
        assert!(std::ptr::eq(cycle.frame_at(t), cycle.frame_at(t - 3.0 * period)));
    }
    for i in [0, 1, count / 2, count - 1] {
        let t = cycle.frame_time(i);
        assert_eq!(cycle.frame_index(t), i);
        assert_eq!(bits(cycle.frame_at(t)), bits(&synth.synthesize(&modes, t, -0.5).expect("m")));
    }
    // Nearest frame: just before t_1 + half a frame still picks frame 1.
    let dt = period / count as f64;
    assert_eq!(cycle.frame_index(dt * 1.49), 1);
    assert_eq!(cycle.frame_index(dt * 1.51), 2);
    assert_eq!(cycle.frame_index(period - 0.1 * dt), 0);

    // Not looping: an error. Too many frames: an error, before any allocation.
    assert!(FrameCycle::<f32>::frame_count_for(&build(n, l, 2, Dispersion::deep(G))).is_err());
    let long = build(256, l, 2, Dispersion::new(G, f64::INFINITY, 1.0e4).expect("dispersion"));
    let mut big_synth = Synthesizer::<f32>::new(256).expect("s");
    assert!(FrameCycle::new(&long, &mut big_synth, 0.0).is_err());
}

// ---------------------------------------------------------------------------------------------
// Extremes, invalid input, determinism.

#[test]
fn zero_spectrum_gives_flat_maps() {
    let modes = WaveModes::new(&ModeParams::new(50.0, 16, 1), Dispersion::deep(G), |_, _| 0.0)
        .expect("modes");
    let maps = Synthesizer::<f32>::new(16).expect("s").synthesize(&modes, 5.0, 1.5).expect("m");
    assert!(
        maps.height
            .iter()
            .chain(&maps.disp_x)
            .chain(&maps.disp_z)
            .chain(&maps.slope_x)
            .chain(&maps.slope_z)
            .all(|&v| v == 0.0)
    );
    assert!(maps.jacobian.iter().all(|&j| j == 1.0));
    let query = SurfaceQuery::new(&modes, 5.0, 1.5).expect("q");
    assert_eq!(query.mode_count(), 0);
    assert_eq!(query.height_at(3.0, 4.0), 0.0);
    assert_eq!(query.normal_at(3.0, 4.0), [0.0, 1.0, 0.0]);
    let looping = WaveModes::new(
        &ModeParams::new(50.0, 16, 1),
        Dispersion::new(G, 10.0, 8.0).expect("d"),
        |_, _| 0.0,
    )
    .expect("m");
    assert_eq!(FrameCycle::<f32>::frame_count_for(&looping).expect("count"), 1);
}

#[test]
fn two_by_two_grid_is_flat() {
    let modes = build(2, 10.0, 1, Dispersion::deep(G));
    assert!(modes.modes().all(|m| !m.active && m.h0 == Complex::new(0.0, 0.0)));
    let maps = Synthesizer::<f64>::new(2).expect("s").synthesize(&modes, 1.0, 1.0).expect("m");
    assert!(maps.height.iter().all(|&h| h == 0.0) && maps.jacobian.iter().all(|&j| j == 1.0));
    // Odd N = 3 holds n, m ∈ {−1, 0, 1}: 8 waves, no Nyquist.
    assert_eq!(build(3, 10.0, 1, Dispersion::deep(G)).modes().filter(|m| m.active).count(), 8);
}

#[test]
fn huge_time_and_folding_choppiness_stay_finite() {
    let (n, l) = (32, 100.0);
    let modes = build(n, l, 19, Dispersion::deep(G));
    let mut synth = Synthesizer::<f64>::new(n).expect("s");
    let maps = synth.synthesize(&modes, 1.0e9, 0.5).expect("m");
    assert!(maps.fields().iter().all(|(_, f)| f.iter().all(|v| v.is_finite())));
    // The phase is exact to f64 at 1e9 s: the direct sum agrees with the FFT there too.
    let points = sample_points(n, 16, 3);
    let expected = grid_expected(&Oracle::new(&modes, 1.0e9, 0.5, 1.0), &points, n, l);
    assert!(worst(&rel_errors(&maps, &points, &expected)) < 1e-12);

    let lambda = 4.0;
    let maps = synth.synthesize(&modes, 2.0, lambda).expect("m");
    let (argmin, min_j) = maps
        .jacobian
        .iter()
        .copied()
        .enumerate()
        .fold((0, f64::INFINITY), |a, (i, j)| if j < a.1 { (i, j) } else { a });
    println!("λ = {lambda}: min J = {min_j:.3}");
    assert!(min_j < 0.0, "the test wants a folded surface");
    assert!(maps.fields().iter().all(|(_, f)| f.iter().all(|v| v.is_finite())));
    let query = SurfaceQuery::new(&modes, 2.0, lambda).expect("q");
    let (i, j) = (argmin % n, argmin / n);
    let (x, z) = (
        i as f64 * l / n as f64 + maps.disp_x[argmin],
        j as f64 * l / n as f64 + maps.disp_z[argmin],
    );
    let mut rng = SplitMix64::new(77);
    for (dx, dz) in std::iter::once((0.0, 0.0)).chain(
        (0..50).map(|_| (rng.next_open_closed() * 4.0 - 2.0, rng.next_open_closed() * 4.0 - 2.0)),
    ) {
        let inv = query.invert(x + dx, z + dz);
        let normal = query.normal_at(x + dx, z + dz);
        assert!(
            inv.x0.is_finite()
                && inv.z0.is_finite()
                && inv.residual_m.is_finite()
                && inv.sample.height.is_finite()
        );
        assert!((normal.iter().map(|c| c * c).sum::<f64>() - 1.0).abs() < 1e-12);
    }
}

#[test]
fn resolution_2048_works() {
    let (n, l, t, lambda) = (2048, 1000.0, 7.0, 0.5);
    let modes = build(n, l, 1, Dispersion::deep(G));
    let maps = Synthesizer::<f32>::new(n).expect("s").synthesize(&modes, t, lambda).expect("m");
    assert!(maps.fields().iter().all(|(_, f)| f.iter().all(|v| v.is_finite())));
    let query = SurfaceQuery::new(&modes, t, lambda).expect("q");
    let points = sample_points(n, 3, 4);
    let expected: Vec<[f64; 6]> = points
        .iter()
        .map(|&(i, j)| {
            let s = query.sample(i as f64 * l / n as f64, j as f64 * l / n as f64);
            [s.height, s.disp_x, s.disp_z, s.slope_x, s.slope_z, s.jacobian]
        })
        .collect();
    let e = rel_errors(&maps, &points, &expected);
    println!(
        "N = 2048, f32: rel error vs direct sum at 3 points {:.2e}; maps {} MB",
        worst(&e),
        maps.byte_size() >> 20
    );
    assert!(worst(&e) < 1e-5);
}

#[test]
fn invalid_parameters_are_errors() {
    let d = Dispersion::deep(G);
    let f = phillips(WIND, AMPLITUDE);
    for n in [0, 1] {
        assert!(WaveModes::new(&ModeParams::new(100.0, n, 1), d, f).is_err());
        assert!(Synthesizer::<f32>::new(n).is_err());
    }
    for l in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(WaveModes::new(&ModeParams::new(l, 16, 1), d, f).is_err());
    }
    assert!(WaveModes::new(&ModeParams::new(100.0, 16, 1), d, |_, _| -1.0).is_err());
    assert!(WaveModes::new(&ModeParams::new(100.0, 16, 1), d, |_, _| f64::NAN).is_err());
    let modes = build(16, 100.0, 1, d);
    let mut synth = Synthesizer::<f64>::new(16).expect("s");
    assert!(synth.synthesize(&modes, 0.0, f64::NAN).is_err());
    assert!(synth.synthesize(&modes, f64::NAN, 0.0).is_err());
    assert!(synth.synthesize(&modes, f64::INFINITY, 0.0).is_err());
    assert!(Synthesizer::<f64>::new(32).expect("s").synthesize(&modes, 0.0, 0.0).is_err());
    assert!(SurfaceQuery::new(&modes, 0.0, f64::NAN).is_err());
    assert!(eval_direct(&modes, f64::NAN, 0.0, 1.0, 1.0).is_err());
    let ocean = |ratio, n_b| {
        OceanSurface::new(
            &OceanParams {
                patch_size_m: 100.0,
                displacement_resolution: 32,
                bump_ratio: ratio,
                bump_resolution: n_b,
                seed: 1,
                dispersion: d,
            },
            f,
        )
    };
    assert!(ocean(0, 32).is_err());
    assert!(ocean(1, 32).is_err()); // the same band twice: nothing left for the bump map
    assert!(ocean(4, 8).is_err()); // Nyquist 4·8/2 = 16 = the displacement's: empty
    assert!(ocean(4, 10).is_ok());
    match WaveModes::new(&ModeParams::new(100.0, 1, 1), d, f) {
        Err(ocean_core::Error::InvalidParameter { name, .. }) => assert_eq!(name, "resolution"),
        other => panic!("expected InvalidParameter, got {other:?}"),
    }
}

#[test]
fn synthesis_is_deterministic() {
    let (n, l) = (48, 100.0);
    let a = build(n, l, 99, Dispersion::new(G, 12.0, 0.0).expect("d"));
    let b = build(n, l, 99, Dispersion::new(G, 12.0, 0.0).expect("d"));
    assert!(
        a.h0()
            .iter()
            .zip(b.h0())
            .all(|(x, y)| x.re.to_bits() == y.re.to_bits() && x.im.to_bits() == y.im.to_bits())
    );
    let mut reused = Synthesizer::<f32>::new(n).expect("s");
    let first = reused.synthesize(&a, 12.3, -1.1).expect("m");
    let _ = reused.synthesize(&a, 99.0, 0.4).expect("m"); // dirty the scratch
    let again = reused.synthesize(&b, 12.3, -1.1).expect("m");
    let fresh = Synthesizer::<f32>::new(n).expect("s").synthesize(&a, 12.3, -1.1).expect("m");
    assert_eq!(bits(&first), bits(&again));
    assert_eq!(bits(&first), bits(&fresh));
    // And into caller-owned maps of the wrong shape.
    let mut out = WaveMaps::<f32>::new(3, 1.0);
    reused.synthesize_into(&a, 12.3, -1.1, &mut out).expect("m");
    assert_eq!(bits(&first), bits(&out));
}

/// Pearson correlation of two equally long fields.
fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let va: f64 = a.iter().map(|x| (x - ma) * (x - ma)).sum();
    let vb: f64 = b.iter().map(|y| (y - mb) * (y - mb)).sum();
    cov / (va * vb).sqrt()
}

#[test]
fn positive_choppiness_sharpens_crests() {
    // Samples bunch up (J < 1) where the surface is high, as in a Gerstner wave: for one mode
    // h = A cos kx, J = 1 − χ A k cos kx, so J and h are perfectly anti-correlated; for a
    // random sea the correlation stays clearly negative. The old sign (Tessendorf's λ = +χ)
    // gives the opposite and is the negative control.
    let (n, l) = (64, 100.0);
    let modes = build(n, l, 5, Dispersion::deep(G));
    let mut synth = Synthesizer::<f64>::new(n).expect("s");
    let sharp = synth.synthesize(&modes, 4.0, 1.0).expect("m");
    let c = correlation(&sharp.height, &sharp.jacobian);
    println!("corr(h, J) at choppiness +1: {c:.3}");
    assert!(c < -0.3, "positive choppiness must put the bunching on the crests: {c}");
    let inverted = synth.synthesize(&modes, 4.0, -1.0).expect("m");
    let c = correlation(&inverted.height, &inverted.jacobian);
    assert!(c > 0.3, "negative control: the opposite sign sharpens troughs: {c}");
}
