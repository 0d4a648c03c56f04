//! The shading techniques' `shade_above` (`shaders/shading/<technique>.wgsl`): the water seen
//! from above, which `water.wgsl` imports as `technique/shading`.

pub mod chiu;
pub mod coastal;
pub mod ggx;
pub mod hu;

use super::water::{Bindings, SurfacePoint, VertexOut};
use super::wgsl::Vec3;
use ocean_core::plan::Shading;

/// A shading technique's `shade_above(in, p)`: the radiance of the water seen from above.
pub type ShadeAbove = fn(&VertexOut, &SurfacePoint, &Bindings<'_>) -> Vec3;

/// The CPU mirror of shading technique `technique`'s `shade_above`.
pub fn shade_above(technique: Shading) -> ShadeAbove {
    match technique {
        Shading::Hu => hu::shade_above,
        Shading::Chiu => chiu::shade_above,
        Shading::Ggx => ggx::shade_above,
        Shading::Coastal => coastal::shade_above,
    }
}
