//! What the water stage over [`Real`](crate::envelope::Real) reads: its textures by name, its inputs and its
//! varyings. Below every part of [`super`], so the parts import it and not each other.

use ocean_core::frame::FrameUniforms;
use ocean_core::plan::{Foam, Shading};

/// A texture the stage reads, as [`Inputs::sample`] names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tex {
    /// Binding 1, repeat.
    Displacement,
    /// Binding 2 (a chain under far fields `mip` and `variance`), repeat.
    DisplacementSlopes,
    /// Binding 3 (likewise), repeat.
    Bump,
    /// Binding 4, clamp.
    FresnelAbove,
    /// Binding 5, clamp.
    FresnelBelow,
    /// Binding 6, clamp.
    ReflectionMap,
    /// Binding 7, clamp.
    RefractionMap,
    /// Binding 11, clamp.
    FresnelFilter,
    /// `floor_map` (binding 12), clamp.
    FloorMap,
    /// Binding 13 (foam `accumulated`'s field), repeat.
    FoamField,
}

/// What the stage reads, over a [`Real`](crate::envelope::Real).
pub struct Inputs<'a, R> {
    /// The frame's uniforms.
    pub frame: &'a FrameUniforms,
    /// The shading technique.
    pub shading: Shading,
    /// The foam technique.
    pub foam: Foam,
    /// `textureSampleLevel(texture, sampler, uv, lod)` with the texture's sampler.
    pub sample: &'a (dyn Fn(Tex, [R; 2], R) -> [R; 4] + Sync),
    /// For a slope chain's sample, the least t₂ − t₀² and t₃ − t₁² (E\[s²\] − E\[s\]² per
    /// axis) any conformant filter gives there (−∞ where nothing is known beyond `sample`:
    /// always, for a scalar), `crate::envelope::filter::spread_floor`.
    pub spread_floor: &'a (dyn Fn(Tex, [R; 2], R) -> [f64; 2] + Sync),
    /// The sky technique's `sky_radiance(sky, dir)`.
    pub sky: &'a (dyn Fn([R; 3]) -> [R; 3] + Sync),
    /// The shadow map's size.
    pub shadow_dims: [u32; 2],
    /// The shadow map's texel (x, y).
    pub occluder: &'a (dyn Fn(u32, u32) -> R + Sync),
}

/// The varyings of `VertexOut` in declaration order: rel (3), uv_d (2), uv_b (2), weight,
/// pos (2).
pub type Varyings<R> = [R; 10];

/// The least positive f32 (a subnormal): what a positive value is at least.
pub(super) const LEAST_POSITIVE: f64 = 1.401_298_464_324_817e-45;
