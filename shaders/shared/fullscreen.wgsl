// One triangle that covers the viewport, for full-screen passes (sky, tonemap).
// CPU mirror: ocean-cpu/src/shaders/shared/fullscreen.rs.

// Clip position of vertex 0, 1, 2: (-1, -1), (3, -1), (-1, 3), counter-clockwise in NDC
// (y up), z = 0 (the far plane with reversed Z), w = 1. The viewport square [-1, 1]^2 lies
// inside it.
fn fullscreen_position(vertex_index: u32) -> vec4<f32> {
    let x = f32((vertex_index << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(vertex_index & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}
