// Foam technique `accumulated`: the foam field that stage `foam` (shaders/foam.wgsl) grows
// where J < threshold and decays over time, one fixed step per frame (ocean-core foam),
// sampled bilinearly at the undisplaced point (repeat addressing: under waves `fft` the field
// is the displacement map's periodic grid, under `gerstner` a torus of world-fixed lattice
// points around the camera, faded out towards the window's edge), through the foam texture.
// Implements the foam interface (foam_coverage) that water.wgsl imports as `technique/foam`.
// CPU mirror: ocean-cpu/src/shaders/foam/accumulated.rs.

fn foam_coverage(in: VertexOut, p: SurfacePoint) -> f32 {
    let f = frame.foam;
    let uv = (in.pos + f.field_origin) * f.inv_field_size + f.field_half_texel;
    var t = clamp(textureSampleLevel(foam_field, wrap_linear, uv, 0.0).x, 0.0, 1.0);
    if (f.window_outer > 0.0) {
        let d = sqrt(in.rel.x * in.rel.x + in.rel.z * in.rel.z);
        t = t * clamp((f.window_outer - d) * f.inv_window_band, 0.0, 1.0);
    }
    return foam_mix(t, foam_texture_at(in.pos));
}
