//! CPU mirror of `shaders/foam/none.wgsl`: no foam.

use crate::shaders::water::{Bindings, SurfacePoint, VertexOut};

/// `foam_coverage(in, p)`.
pub fn foam_coverage(_input: &VertexOut, _p: &SurfacePoint, _b: &Bindings<'_>) -> f32 {
    0.0
}
