//! The `variance` far field's physics (ocean-core `far_field`), against independent
//! evaluations: the filtered Fresnel term against a direct 2D average of eq. 2 over the slope
//! distribution, the table against both, and the filtered Phong lobe against a direct average
//! of the lobe. Run with `--nocapture` for the figures.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use ocean_core::far_field::{
    FILTER_RADII, FILTER_SIGMAS, FresnelFilterTable, RADIUS_MAX, SIGMA_MAX, filter_texel_point,
    fresnel_filtered, fresnel_of_radius, phong_filtered_exponent,
};
use ocean_core::fresnel::fresnel_exact;

const WATER: f64 = 1.333;

/// E[F(|p + δ|)], δ ~ N(0, σ² I), by the midpoint rule on a Cartesian grid over ±6σ with
/// `m` × `m` cells, weights the normalised Gaussian density (independent of the library's
/// Rice-density quadrature: no Bessel function, no substitution at the rim).
fn direct_average(r: f64, sigma: f64, m: usize) -> f64 {
    let h = 12.0 * sigma / m as f64;
    let (mut sum_w, mut sum_wf) = (0.0, 0.0);
    for a in 0..m {
        let dx = -6.0 * sigma + (a as f64 + 0.5) * h;
        for b in 0..m {
            let dy = -6.0 * sigma + (b as f64 + 0.5) * h;
            let w = (-(dx * dx + dy * dy) / (2.0 * sigma * sigma)).exp();
            let rho = (r + dx).hypot(dy);
            let f = fresnel_exact((1.0 - rho * rho).max(0.0).sqrt(), WATER);
            sum_w += w;
            sum_wf += w * f;
        }
    }
    sum_wf / sum_w
}

#[test]
fn filtered_fresnel_matches_a_direct_average_of_eq2() {
    let mut worst = 0.0f64;
    for sigma in [0.01, 0.05, 0.15, 0.4] {
        for r in [0.0, 0.5, 0.8, 0.95, 1.0, 1.05, 1.3] {
            let direct = direct_average(r, sigma, 800);
            let got = fresnel_filtered(r, sigma, WATER);
            let e = (got - direct).abs();
            eprintln!(
                "σ {sigma:<5} r {r:<5} F {:.5} F̄ {got:.6} direct {direct:.6} |Δ| {e:.2e}",
                fresnel_of_radius(r, WATER)
            );
            worst = worst.max(e);
            // The midpoint rule's error at the rim's sqrt singularity is O(h^1.5) with
            // h = 12σ/800 (≤ 3e-5 here), the Rice quadrature's far smaller: 1e-4 holds both.
            assert!(e < 1e-4, "σ {sigma} r {r}: {got} vs {direct}");
        }
    }
    eprintln!("worst |F̄ − direct| = {worst:.2e}");
    // Negative control: the average at a 20 % wider blur is seen as wrong.
    let off = (fresnel_filtered(0.9, 0.12, WATER) - direct_average(0.9, 0.1, 800)).abs();
    assert!(off > 1e-3, "{off}");
}

/// The table's bilinear lookup at (r, σ), as the water shader will read it: r on texel
/// centres i·R/(N_r − 1), t = sqrt(σ/Σ) on centres j/(N_σ − 1).
fn table_lookup(t: &FresnelFilterTable, r: f64, sigma: f64) -> f64 {
    let u = r / RADIUS_MAX * f64::from(FILTER_RADII - 1);
    let v = (sigma / SIGMA_MAX).sqrt() * f64::from(FILTER_SIGMAS - 1);
    let (i0, j0) = (u.floor() as usize, v.floor() as usize);
    let (i1, j1) =
        ((i0 + 1).min(FILTER_RADII as usize - 1), (j0 + 1).min(FILTER_SIGMAS as usize - 1));
    let (a, b) = (u - i0 as f64, v - j0 as f64);
    let at = |i: usize, j: usize| f64::from(t.texels[j * FILTER_RADII as usize + i][1]);
    let lo = at(i0, j0) + a * (at(i1, j0) - at(i0, j0));
    let hi = at(i0, j1) + a * (at(i1, j1) - at(i0, j1));
    lo + b * (hi - lo)
}

#[test]
fn filtered_table_interpolates_the_filtered_fresnel() {
    let start = std::time::Instant::now();
    let table = FresnelFilterTable::new(WATER);
    eprintln!(
        "filtered Fresnel table {FILTER_RADII}×{FILTER_SIGMAS} built in {:.0} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
    // Row 0 is σ = 0: ΔF exactly 0 and F̄ = F.
    for i in 0..FILTER_RADII {
        let [d, f, _, _] = table.texels[i as usize];
        assert_eq!(d, 0.0);
        assert_eq!(f, fresnel_of_radius(filter_texel_point(i, 0).0, WATER) as f32);
    }
    // Between texels: the bilinear lookup against the quadrature at off-grid points.
    let mut worst = (0.0f64, 0.0, 0.0);
    for sigma in [0.02, 0.07, 0.2, 0.45] {
        for k in 0..200 {
            let r = (k as f64 + 0.37) * 1.6 / 200.0;
            let e = (table_lookup(&table, r, sigma) - fresnel_filtered(r, sigma, WATER)).abs();
            if e > worst.0 {
                worst = (e, r, sigma);
            }
        }
    }
    eprintln!("worst |table − F̄| = {:.2e} at r {:.3}, σ {}", worst.0, worst.1, worst.2);
    // Bilinear error, (h²/8)·|F̄''| per axis: largest where a narrow blur meets the rim.
    assert!(worst.0 < 2e-3, "{worst:?}");
}

#[test]
fn filtered_phong_matches_a_direct_average_of_the_lobe() {
    // E over α ~ N(ᾱ, σ² I) of exp(−s|α|²/2), by the midpoint rule, against the closed form
    // exp(−s'|ᾱ|²/2)/(1 + sσ²).
    for (s, var, mean) in [(400.0f64, 1e-3f64, 0.02f64), (400.0, 1e-2, 0.1), (50.0, 4e-3, 0.0)] {
        let sigma = var.sqrt();
        let m = 600;
        let h = 12.0 * sigma / m as f64;
        let (mut sw, mut swf) = (0.0, 0.0);
        for a in 0..m {
            let x = mean - 6.0 * sigma + (a as f64 + 0.5) * h;
            for b in 0..m {
                let y = -6.0 * sigma + (b as f64 + 0.5) * h;
                let w = (-((x - mean).powi(2) + y * y) / (2.0 * var)).exp();
                sw += w;
                swf += w * (-s * (x * x + y * y) / 2.0).exp();
            }
        }
        let direct = swf / sw;
        let (s2, scale) = phong_filtered_exponent(s, var);
        let closed = scale * (-s2 * mean * mean / 2.0).exp();
        assert!(
            (direct - closed).abs() < 1e-6 * closed.max(1e-3),
            "s {s} σ² {var}: {direct} vs {closed}"
        );
    }
}
