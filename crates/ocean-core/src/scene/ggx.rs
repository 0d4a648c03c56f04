//! The `[ggx]` table of shading technique `ggx` (seed 002).

use serde::{Deserialize, Serialize};

pub use crate::ggx::GgxFresnel;

/// The `[ggx]` table: shading technique `ggx` (seed 002's Cook–Torrance BRDF with the GGX
/// distribution; the f64 model is [`crate::ggx`]).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Ggx {
    /// Perceptual roughness r; the distribution's α = r² (Burley 2012). 0.2 is a calm sea's
    /// glossy sheen at the scale the waves do not resolve.
    pub roughness: f64,
    /// The Fresnel term: `exact` (eq. 2 of seed 000) or `schlick` (the seed's approximation,
    /// only on request).
    pub fresnel: GgxFresnel,
    /// The geometry term: `smith` (Smith's height-correlated G, exact for GGX) or
    /// `schlick_ggx` (the seed's Schlick-GGX, k = α/2).
    pub geometry: GgxGeometry,
    /// The seed's double-scrolled detail normal map ([`crate::detail`]): the RMS slope it adds
    /// (both layers); 0 leaves it out.
    pub detail_strength: f64,
    /// The detail map's median wavelength, m.
    pub detail_wavelength_m: f64,
    /// How fast the detail map's first layer drifts with the wind, m/s (the second drifts
    /// against it at 0.6 of that).
    pub detail_speed_m_s: f64,
}

impl Default for Ggx {
    fn default() -> Self {
        Self {
            roughness: 0.2,
            fresnel: GgxFresnel::Exact,
            geometry: GgxGeometry::Smith,
            detail_strength: 0.04,
            detail_wavelength_m: 2.0,
            detail_speed_m_s: 0.4,
        }
    }
}

/// The geometry term of shading `ggx`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GgxGeometry {
    /// Smith's height-correlated G2 = 1/(1 + Λ(l) + Λ(v)).
    #[default]
    Smith,
    /// Schlick-GGX G1(l)·G1(v) with k = α/2 (seed 002).
    SchlickGgx,
}
