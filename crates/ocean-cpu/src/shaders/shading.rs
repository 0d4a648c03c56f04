//! The shading techniques' `shade_above` (`shaders/shading/<technique>.wgsl`): the water seen
//! from above, which `water.wgsl` imports as `technique/shading`.

pub mod chiu;
pub mod coastal;
pub mod ggx;
pub mod hu;

use super::water::{Bindings, SurfacePoint, VertexOut};
use super::wgsl::Vec3;

/// A shading technique's `shade_above(in, p)`: the radiance of the water seen from above.
pub type ShadeAbove = fn(&VertexOut, &SurfacePoint, &Bindings<'_>) -> Vec3;

/// The CPU mirror of shading technique `technique`'s `shade_above`, if it has one.
pub fn shade_above(technique: &str) -> Option<ShadeAbove> {
    match technique {
        "hu" => Some(hu::shade_above),
        "chiu" => Some(chiu::shade_above),
        "ggx" => Some(ggx::shade_above),
        "coastal" => Some(coastal::shade_above),
        _ => None,
    }
}
