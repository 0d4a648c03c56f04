// Foam technique `none`: no foam. Implements the foam interface (foam_coverage) that
// water.wgsl imports as `technique/foam`. CPU mirror: ocean-cpu/src/shaders/foam/none.rs.

fn foam_coverage(in: VertexOut, p: SurfacePoint) -> f32 {
    return 0.0;
}
