//! CPU mirror of `shaders/foam/jacobian.wgsl`: foam where J < threshold.

use crate::shaders::shared::foam::{foam_mix, foam_texture_at, jacobian_turbulence};
use crate::shaders::water::{Bindings, SurfacePoint, VertexOut, surface_jacobian};

/// `foam_coverage(in, p)`.
pub fn foam_coverage(input: &VertexOut, _p: &SurfacePoint, b: &Bindings<'_>) -> f32 {
    let t = jacobian_turbulence(surface_jacobian(input, b), b.frame);
    foam_mix(t, foam_texture_at(input.pos, b.frame), b.frame)
}
