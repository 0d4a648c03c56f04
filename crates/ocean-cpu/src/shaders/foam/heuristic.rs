//! CPU mirror of `shaders/foam/heuristic.wgsl`: seed 002's foam on high, steep crests.

use crate::shaders::shared::foam::{foam_mix, foam_texture_at, heuristic_turbulence};
use crate::shaders::water::{Bindings, SurfacePoint, VertexOut, surface_jacobian};
use crate::shaders::wgsl::sqrt;

/// `foam_coverage(in, p)`.
pub fn foam_coverage(input: &VertexOut, p: &SurfacePoint, b: &Bindings<'_>) -> f32 {
    let frame = b.frame;
    let h = input.rel.y + frame.view.eye_height;
    let s = sqrt(p.slopes.x * p.slopes.x + p.slopes.y * p.slopes.y);
    let t = heuristic_turbulence(h, s, surface_jacobian(input, b), frame);
    foam_mix(t, foam_texture_at(input.pos, frame), frame)
}
