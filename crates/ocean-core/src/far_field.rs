//! Stage `far_field` (docs/design.md, "Filtering and ground truth"): what becomes of the wave
//! detail a pixel cannot resolve, after Bruneton, Neyret & Holzschuch 2010.
//!
//! - `none`: the wave maps' level 0, bilinear (a far pixel picks one slope: it sparkles).
//! - `mip`: the slope maps carry mip chains (each level the 2×2 box of the one below), and the
//!   water pass samples them trilinearly at the LOD of the pixel's footprint on the sea.
//! - `variance`: as `mip`, and the slopes the footprint averaged away are not dropped: each
//!   level also holds the mean squared slopes, so E\[s²\] − E\[s\]² is the variance of the
//!   unresolved slopes under the pixel (LEAN mapping's moments), and the shading takes the
//!   expectation of the Fresnel term and of the sun's highlight over a Gaussian slope
//!   distribution of that variance ([`FresnelFilterTable`], [`SunLobe`]).
//!
//! **The footprint** (the water shader's `footprint`): a pixel subtends δ = 2·tan(fov_y/2)/height
//! radians at the image centre; at distance d it is d·δ across, and a plane seen at cos θ_v
//! from its normal stretches it to d·δ/cos θ_v along the view's horizontal direction. The
//! pixel takes 2^k taps along that long axis, k = ⌈log2(long/short)⌉ ≤ log2
//! [`MAX_ANISOTROPY`], spaced long/2^k apart, each a trilinear sample at the LOD of
//! max(short, long/2^k) in the map's texels, and averages them (anisotropic filtering; with
//! k = 0 the isotropic choice of the longer side, which over-filters the shorter one and
//! stretched the unresolved variance over 16× the area at grazing views). The LOD is explicit
//! (`textureSampleLevel`), not the GPU's derivative-based one, so both back ends select
//! levels from the same f32 arithmetic, with no 2×2 quads, and a footprint does not jump at
//! the edges of the far patch's long triangles (see docs/far-field.md).
//!
//! **Visible facets** (far field `variance`): the displacement map's slopes are geometry, and
//! at a grazing view the eye sees the wave faces turned towards it and not their backs. A
//! facet of slope s along h (the horizontal direction towards the eye) shows in proportion to
//! its area projected towards the eye, ∝ max(0, v_y − v_h s) per unit of sea; the shader
//! replaces the Gaussian of the displacement slopes the taps span lengthwise (mean and
//! variance of their slopes along h) by that of the visible facets — a truncated-normal
//! moment, in closed form — which tilts the mean normal towards the eye. The bump map's
//! slopes only bend the normal, as in the 64-sample frame: no facet of theirs hides another,
//! and they are not reweighted.

use std::sync::{Arc, Mutex, OnceLock};

use rayon::prelude::*;

use crate::fresnel::fresnel_exact;

pub use crate::stage::FarField;

/// `FarFieldBlock::mode` of far field `none` (WGSL `FAR_NONE`, shared/frame.wgsl).
pub const FAR_NONE: f32 = 0.0;
/// `FarFieldBlock::mode` of far field `mip` (WGSL `FAR_MIP`).
pub const FAR_MIP: f32 = 1.0;
/// `FarFieldBlock::mode` of far field `variance` (WGSL `FAR_VARIANCE`).
pub const FAR_VARIANCE: f32 = 2.0;

impl FarField {
    /// The value of `FarFieldBlock::mode` that selects it in the water shader.
    pub fn code(self) -> f32 {
        match self {
            Self::None => FAR_NONE,
            Self::Mip => FAR_MIP,
            Self::Variance => FAR_VARIANCE,
        }
    }
}

/// Number of levels of a full mip chain of a `width` × `height` map: ⌊log2 max(w, h)⌋ + 1.
pub fn mip_level_count(width: u32, height: u32) -> u32 {
    32 - width.max(height).max(1).leading_zeros()
}

/// Size of level `k`: max(1, w >> k) × max(1, h >> k) (Vulkan's rule).
pub fn mip_level_size(width: u32, height: u32, k: u32) -> [u32; 2] {
    [(width >> k).max(1), (height >> k).max(1)]
}

/// First row of level `k` in a chain's packed atlas (`w` wide, the levels stacked from row 0,
/// each from column 0): the sum of the heights below it. Both back ends pack a chain so, and
/// the cross-check compares the atlases.
pub fn mip_level_row(height: u32, k: u32) -> u32 {
    (0..k).map(|i| (height >> i).max(1)).sum()
}

/// The most taps a pixel takes along its footprint's long axis (a power of two; the common
/// GPU limit of 16). Beyond a 16:1 footprint the taps' LOD rises to the long side / 16.
pub const MAX_ANISOTROPY: u32 = 16;

/// The largest slope standard deviation the filtered Fresnel table holds; a larger σ reads
/// the table's last row (clamp-to-edge). Cox & Munk's sea at 20 m/s has σ ≈ 0.32.
pub const SIGMA_MAX: f64 = 0.5;

/// The largest radius |(x_v − du, z_v − dv)| of the bumped view vector the table holds: a
/// unit view minus a unit normal's horizontal part is under 2 long.
pub const RADIUS_MAX: f64 = 2.0;

/// Texels of the filtered Fresnel table along r ∈ [0, [`RADIUS_MAX`]]: 2/511 = 0.0039 apart,
/// four to the narrowest blur the σ axis holds beside 0.
pub const FILTER_RADII: u32 = 512;

/// Texels of the table along the σ axis, t = sqrt(σ/[`SIGMA_MAX`]) ∈ [0, 1].
pub const FILTER_SIGMAS: u32 = 32;

/// Φ(x), the standard normal distribution function in f64, from the complementary error
/// function's Chebyshev fit (Press et al., Numerical Recipes §6.2, `erfcc`: relative error
/// below 1.2e-7 everywhere).
pub fn normal_cdf_f64(x: f64) -> f64 {
    let z = (x * std::f64::consts::FRAC_1_SQRT_2).abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let erfc = t
        * (-z * z - 1.265_512_23
            + t * (1.000_023_68
                + t * (0.374_091_96
                    + t * (0.096_784_18
                        + t * (-0.186_288_06
                            + t * (0.278_868_07
                                + t * (-1.135_203_98
                                    + t * (1.488_515_87
                                        + t * (-0.822_152_23 + t * 0.170_872_77)))))))))
            .exp();
    if x >= 0.0 { 1.0 - 0.5 * erfc } else { 0.5 * erfc }
}

/// The sun's Phong lobe cos^s θ in the coordinates the water shader reads it in: u, the
/// horizontal part of the bumped view vector (the Fresnel table's axes; u = v_h − n_h moves
/// one for one with the slope, to first order). The lobe peaks at u = r_h, the mirrored sun's
/// horizontal part, |r_h| = cos α for a sun α above the horizon. Across the sun's azimuth it
/// is exp(−s u_t²/2). Along it (radially) u_r = cos(elevation): the elevations below α are
/// squeezed into cos α < u_r < 1, those above spread out, and beyond the rim u_r > 1 the
/// table's clamp holds the lobe at its rim value exp(−s α²/2). For slope blur each radial
/// side becomes a half Gaussian with the lobe's peak (1 at u_r = cos α) and the lobe's
/// integral over that side, ∫ exp(−s δ²/2) sin(α + δ) dδ with sin(α + δ) ≈ sin α + δ cos α
/// (the side below α cut at the rim); the expectation of a Gaussian piece or a step over a
/// Gaussian slope distribution is a closed form (the water shader's `sun_lobe_filtered`).
/// Isotropic blur of cos^s in angle (Toksvig 2005), used before, misses the squeeze and held
/// a low sun's glitter at the horizon, 17 % too bright against the supersampled frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunLobe {
    /// cos α: where the lobe peaks along u_r.
    pub centre: f64,
    /// The variance of the half Gaussian for u_r < cos α (elevations above the sun's).
    pub above: f64,
    /// The variance of the half Gaussian for cos α < u_r < 1 (elevations below it).
    pub below: f64,
    /// The tangential Gaussian's variance, 1/s.
    pub tangential: f64,
    /// The lobe's value beyond the table's rim, exp(−s α²/2).
    pub rim: f64,
}

/// [`SunLobe`] for a sun whose direction has vertical component `sin_elevation` (clamped to
/// [0, 1]: a sun below the horizon does not light the water) and Phong exponent `s` ≥ 1.
pub fn sun_lobe(sin_elevation: f64, s: f64) -> SunLobe {
    let sin_a = sin_elevation.clamp(0.0, 1.0);
    let alpha = sin_a.asin();
    let cos_a = (1.0 - sin_a * sin_a).sqrt();
    let (pi, tau) = (std::f64::consts::PI, std::f64::consts::TAU);
    let rim = (-0.5 * s * alpha * alpha).exp();
    // ∫ over δ ≥ 0, and over −α ≤ δ ≤ 0, of exp(−s δ²/2)(sin α + δ cos α) dδ.
    let above_mass = 0.5 * sin_a * (tau / s).sqrt() + cos_a / s;
    let below_mass = sin_a * (tau / s).sqrt() * (normal_cdf_f64(alpha * s.sqrt()) - 0.5)
        - cos_a * (1.0 - rim) / s;
    // A half Gaussian of peak 1 holds √(2πa)/2; the one below is cut at the rim, 1 − cos α
    // away, and holds √(2πa)(Φ((1 − cos α)/√a) − ½), which grows with a towards 1 − cos α.
    let gap = 1.0 - cos_a;
    let below = if gap <= 0.0 || below_mass <= 0.0 {
        0.0
    } else {
        let mass = |a: f64| (tau * a).sqrt() * (normal_cdf_f64(gap / a.sqrt()) - 0.5);
        let (mut lo, mut hi) = (1e-20f64.ln(), 4.0f64.ln());
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mass(mid.exp()) < below_mass { lo = mid } else { hi = mid }
        }
        (0.5 * (lo + hi)).exp()
    };
    SunLobe {
        centre: cos_a,
        above: 2.0 * above_mass * above_mass / pi,
        below,
        tangential: 1.0 / s,
        rim,
    }
}

/// I₀(x)·e^(−x), the exponentially scaled modified Bessel function of order 0, for x ≥ 0
/// (Abramowitz & Stegun 9.8.1 and 9.8.2; relative error below 2e-7).
pub fn bessel_i0e(x: f64) -> f64 {
    if x < 3.75 {
        let t = (x / 3.75).powi(2);
        let i0 = 1.0
            + t * (3.5156229
                + t * (3.0899424
                    + t * (1.2067492 + t * (0.2659732 + t * (0.0360768 + t * 0.0045813)))));
        i0 * (-x).exp()
    } else {
        let t = 3.75 / x;
        let p = 0.39894228
            + t * (0.01328592
                + t * (0.00225319
                    + t * (-0.00157565
                        + t * (0.00916281
                            + t * (-0.02057706
                                + t * (0.02635537 + t * (-0.01647633 + t * 0.00392377)))))));
        p / x.sqrt()
    }
}

/// F of the bumped view vector at radius r of the lookup plane: eq. 2 at cos θ =
/// sqrt(1 − r²), and the rim's F = 1 beyond it (as the 2D table's lookup clamps it).
pub fn fresnel_of_radius(r: f64, eta: f64) -> f64 {
    fresnel_exact((1.0 - r * r).max(0.0).sqrt(), eta)
}

/// Composite Simpson's rule of `f` over [a, b] with `n` (even) intervals.
fn simpson(a: f64, b: f64, n: usize, f: impl Fn(f64) -> f64) -> f64 {
    if b <= a {
        return 0.0;
    }
    let h = (b - a) / n as f64;
    let mut sum = f(a) + f(b);
    for i in 1..n {
        sum += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// The expectation of F over the bumped view vector's lookup point p + δ, δ ~ N(0, σ² I) in
/// the plane, at |p| = r: since F depends on |p| only, this is the 1D integral of F(ρ) against
/// the Rice density p(ρ | r, σ) = (ρ/σ²) exp(−(ρ − r)²/(2σ²)) I₀e(rρ/σ²) over ρ within 8σ of
/// r (normalised by the same quadrature of p, so the truncation and the rule's error in the
/// mass cancel). Inside the rim the substitution ρ = 1 − s² makes F(ρ) = F(sqrt(1 − ρ²))
/// smooth in s (its derivative is unbounded at ρ = 1); beyond it F = 1.
pub fn fresnel_filtered(r: f64, sigma: f64, eta: f64) -> f64 {
    if sigma <= 0.0 {
        return fresnel_of_radius(r, eta);
    }
    let s2 = sigma * sigma;
    let density = |rho: f64| {
        if rho <= 0.0 {
            return 0.0;
        }
        rho / s2 * (-(rho - r) * (rho - r) / (2.0 * s2)).exp() * bessel_i0e(r * rho / s2)
    };
    let (lo, hi) = ((r - 8.0 * sigma).max(0.0), r + 8.0 * sigma);
    const N: usize = 256;
    let (mut mass, mut weighted) = (0.0, 0.0);
    if lo < 1.0 {
        // ρ = 1 − s², dρ = 2s ds, s from sqrt(1 − min(hi, 1)) to sqrt(1 − lo).
        let (s_lo, s_hi) = ((1.0 - hi.min(1.0)).sqrt(), (1.0 - lo).sqrt());
        let inner = |s: f64, with_f: bool| {
            let rho = 1.0 - s * s;
            let w = density(rho) * 2.0 * s;
            if with_f { w * fresnel_of_radius(rho, eta) } else { w }
        };
        mass += simpson(s_lo, s_hi, N, |s| inner(s, false));
        weighted += simpson(s_lo, s_hi, N, |s| inner(s, true));
    }
    if hi > 1.0 {
        let outer = simpson(lo.max(1.0), hi, N, density);
        mass += outer;
        weighted += outer;
    }
    if mass > 0.0 { weighted / mass } else { fresnel_of_radius(r, eta) }
}

/// The radius and σ of texel (i, j) of the filtered Fresnel table: r = i·R/(N_r − 1),
/// σ = (j/(N_σ − 1))²·Σ, so row 0 is σ = 0 and the rows crowd towards small σ, where F̄
/// changes fastest at the rim (∝ sqrt σ there, ∝ σ² elsewhere).
pub fn filter_texel_point(i: u32, j: u32) -> (f64, f64) {
    let r = f64::from(i) * RADIUS_MAX / f64::from(FILTER_RADII - 1);
    let t = f64::from(j) / f64::from(FILTER_SIGMAS - 1);
    (r, t * t * SIGMA_MAX)
}

/// The filtered Fresnel table of the `variance` technique: [`FILTER_RADII`] ×
/// [`FILTER_SIGMAS`] texels, texel (i, j) = (F̄, 0, 0, 0) at [`filter_texel_point`] (F̄ by
/// [`fresnel_filtered`]; row 0, σ = 0, is F = [`fresnel_of_radius`]). The water shader reads
/// it bilinearly at (r, σ) for a pixel with unresolved slopes (σ > 0), in place of the 2D
/// texture's F (a pixel whose slope variance is 0 does not read it and shades exactly as
/// `mip`). It holds F̄, not F̄ − F: F rises from 0.68 to 1 within one of its texels of the rim,
/// where a bilinear F̄ − F was off by up to 0.16; F̄ is smooth there for σ > 0.
#[derive(Clone, Debug, PartialEq)]
pub struct FresnelFilterTable {
    /// η of the table.
    pub eta: f64,
    /// Row-major texels, row j = σ index.
    pub texels: Vec<[f32; 4]>,
}

impl FresnelFilterTable {
    /// Builds the table for `eta` (f64 quadrature, rows in parallel; about 0.1 s).
    pub fn new(eta: f64) -> Self {
        let texels = (0..FILTER_SIGMAS)
            .into_par_iter()
            .flat_map_iter(|j| {
                (0..FILTER_RADII).map(move |i| {
                    let (r, sigma) = filter_texel_point(i, j);
                    let f = if j == 0 {
                        fresnel_of_radius(r, eta)
                    } else {
                        fresnel_filtered(r, sigma, eta)
                    };
                    [f as f32, 0.0, 0.0, 0.0]
                })
            })
            .collect();
        Self { eta, texels }
    }

    /// The table for `eta`, built once per process and η (the CPU frame, the GPU upload and
    /// the report share it).
    pub fn cached(eta: f64) -> Arc<Self> {
        static CACHE: OnceLock<Mutex<Vec<Arc<FresnelFilterTable>>>> = OnceLock::new();
        let cache = CACHE.get_or_init(|| Mutex::new(Vec::new()));
        let mut tables = cache.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(t) = tables.iter().find(|t| t.eta.to_bits() == eta.to_bits()) {
            return Arc::clone(t);
        }
        let t = Arc::new(Self::new(eta));
        tables.push(Arc::clone(&t));
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bessel_i0e_matches_its_power_series() {
        // I₀(x) = Σ (x/2)^{2k}/(k!)², summed in f64 to convergence, times e^−x.
        let series = |x: f64| {
            let (mut term, mut sum, mut k) = (1.0f64, 1.0f64, 1.0f64);
            while term > 1e-18 * sum {
                term *= (x / 2.0) * (x / 2.0) / (k * k);
                sum += term;
                k += 1.0;
            }
            sum * (-x).exp()
        };
        for x in [0.0, 0.5, 1.0, 3.0, 3.75, 5.0, 10.0, 30.0] {
            let (got, want) = (bessel_i0e(x), series(x));
            assert!((got - want).abs() < 2e-7 * want, "x {x}: {got} vs {want}");
        }
        // Negative control: the unscaled I₀ is far from it.
        assert!((bessel_i0e(5.0) - series(5.0) * 5f64.exp()).abs() > 1.0);
    }

    #[test]
    fn filtered_fresnel_tends_to_the_unfiltered_and_stays_in_range() {
        let eta = 1.333;
        for r in [0.0, 0.3, 0.9, 0.99, 1.0, 1.2] {
            let f = fresnel_of_radius(r, eta);
            // Far from the rim a tiny blur changes F by ½σ²∇²F: 1e-6 for σ = 1e-3.
            if (r - 1.0f64).abs() > 0.05 {
                assert!((fresnel_filtered(r, 1e-3, eta) - f).abs() < 1e-5, "r {r}");
            }
            for sigma in [0.01, 0.1, 0.5] {
                let g = fresnel_filtered(r, sigma, eta);
                assert!((0.0..=1.0).contains(&g), "r {r} σ {sigma}: {g}");
            }
        }
        // The mean over a wide blur at the centre exceeds F at the centre (F grows outwards).
        assert!(fresnel_filtered(0.0, 0.3, eta) > fresnel_of_radius(0.0, eta));
    }
}
