//! The BRDF of shading technique `ggx` (seed 002; Walter et al. 2007, Heitz 2014): Cook–Torrance
//! with the GGX (Trowbridge–Reitz) distribution of microfacet normals, Smith's masking and the
//! exact Fresnel of eq. 2 (Schlick's only as the explicit option), in f64 — the model the shader
//! will mirror, and the oracle of its tests.
//!
//! With n the macro normal, v the view, l the light, h = (v + l)/|v + l|, α the roughness
//! parameter (the scene's `roughness` r maps to α = r², Burley's remapping, so that r is
//! perceptually linear):
//!
//! ```text
//! f(l, v) = F(h·v) · G(l, v) · D(h) / (4 (n·l)(n·v))
//! D(m)    = α² / (π ((n·m)²(α² − 1) + 1)²)                         ∫ D(m)(n·m) dm = 1
//! Λ(v)    = (−1 + √(1 + α² tan²θ_v)) / 2                           Smith's, exact for GGX
//! G1(v)   = 1 / (1 + Λ(v))          G(l, v) = 1 / (1 + Λ(l) + Λ(v))  (height-correlated)
//! ```
//!
//! The seed's geometry term is Schlick's fit to G1, n·v / (n·v (1 − k) + k), with k = α/2 (Karis
//! 2013), used as G1(l)·G1(v): [`schlick_ggx_g1`], an approximation kept beside the exact one so
//! that its error can be measured.

use std::f64::consts::PI;

use glam::DVec3;

use serde::{Deserialize, Serialize};

use crate::fresnel::{fresnel_exact, fresnel_schlick};

/// The Fresnel term of shading `ggx`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GgxFresnel {
    /// Eq. 2 of seed 000.
    #[default]
    Exact,
    /// Schlick's approximation, F0 = ((η − 1)/(η + 1))².
    Schlick,
}

/// The least α: below it D is a spike no f64 quadrature or f32 shader resolves (a mirror).
pub const MIN_ALPHA: f64 = 1e-3;

/// α from the scene's roughness r ∈ [0, 1]: r², clamped below at [`MIN_ALPHA`].
pub fn alpha_from_roughness(r: f64) -> f64 {
    (r * r).max(MIN_ALPHA)
}

/// D(m) for the cosine `cos_m` = n·m of the microfacet normal (0 for n·m ≤ 0).
pub fn ggx_d(cos_m: f64, alpha: f64) -> f64 {
    if cos_m <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let t = cos_m * cos_m * (a2 - 1.0) + 1.0;
    a2 / (PI * t * t)
}

/// Smith's Λ for GGX at the direction whose cosine with n is `cos_v` (0 at normal incidence;
/// ∞ at grazing, where G → 0).
pub fn smith_lambda(cos_v: f64, alpha: f64) -> f64 {
    if cos_v <= 0.0 {
        return f64::INFINITY;
    }
    let cos2 = (cos_v * cos_v).min(1.0);
    let tan2 = (1.0 - cos2) / cos2;
    0.5 * ((1.0 + alpha * alpha * tan2).sqrt() - 1.0)
}

/// Smith's G1 (the share of the microfacets facing `v` that are not masked).
pub fn smith_g1(cos_v: f64, alpha: f64) -> f64 {
    1.0 / (1.0 + smith_lambda(cos_v, alpha))
}

/// The height-correlated masking–shadowing G(l, v).
pub fn smith_g2(cos_l: f64, cos_v: f64, alpha: f64) -> f64 {
    1.0 / (1.0 + smith_lambda(cos_l, alpha) + smith_lambda(cos_v, alpha))
}

/// Schlick's fit to G1 with k = α/2 (the seed's geometry term).
pub fn schlick_ggx_g1(cos_v: f64, alpha: f64) -> f64 {
    let k = 0.5 * alpha;
    let c = cos_v.max(0.0);
    c / (c * (1.0 - k) + k)
}

/// Which Fresnel term the BRDF uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FresnelTerm {
    /// Eq. 2 of seed 000, exact.
    Exact,
    /// Schlick's approximation (explicit option).
    Schlick,
    /// F = 1 (the white-furnace tests).
    One,
}

/// Which geometry term.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeometryTerm {
    /// Smith's height-correlated G(l, v), exact for GGX.
    SmithCorrelated,
    /// Schlick-GGX G1(l)·G1(v), k = α/2 (the seed's).
    SchlickGgx,
}

/// f(l, v) for unit vectors `n`, `v`, `l` (0 where either lies below the surface), with the
/// water's index `eta`.
pub fn cook_torrance(
    n: [f64; 3],
    v: [f64; 3],
    l: [f64; 3],
    alpha: f64,
    eta: f64,
    fresnel: FresnelTerm,
    geometry: GeometryTerm,
) -> f64 {
    let (n, v, l) = (DVec3::from(n), DVec3::from(v), DVec3::from(l));
    let (nv, nl) = (n.dot(v), n.dot(l));
    if nv <= 0.0 || nl <= 0.0 {
        return 0.0;
    }
    let Some(h) = (v + l).try_normalize() else { return 0.0 };
    let hv = h.dot(v).clamp(0.0, 1.0);
    let f = match fresnel {
        FresnelTerm::Exact => fresnel_exact(hv, eta),
        FresnelTerm::Schlick => fresnel_schlick(hv, eta),
        FresnelTerm::One => 1.0,
    };
    let g = match geometry {
        GeometryTerm::SmithCorrelated => smith_g2(nl, nv, alpha),
        GeometryTerm::SchlickGgx => schlick_ggx_g1(nl, alpha) * schlick_ggx_g1(nv, alpha),
    };
    f * g * ggx_d(n.dot(h), alpha) / (4.0 * nl * nv)
}
