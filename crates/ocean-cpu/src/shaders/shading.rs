//! The shading techniques' `shade_above` (`shaders/shading/<technique>.wgsl`): the water seen
//! from above, which `water.wgsl` imports as `technique/shading`.

pub mod chiu;
pub mod coastal;
pub mod ggx;
pub mod hu;

pub use super::water::ShadeAbove;
use ocean_core::plan::Shading;

/// The CPU mirror of shading technique `technique`'s `shade_above`.
pub fn shade_above(technique: Shading) -> ShadeAbove {
    match technique {
        Shading::Hu => hu::shade_above,
        Shading::Chiu => chiu::shade_above,
        Shading::Ggx => ggx::shade_above,
        Shading::Coastal => coastal::shade_above,
    }
}
