// Foam technique `heuristic` (seed 002, §Water Surface: "a combination of the normal and
// height of the wave are used to estimate areas of turbulence where foam would generate such
// as on the crests of waves", broken up by a noise texture): high × steep × compressed — the
// point's height above the mean sea plane, the slope of the displaced surface (|∇h|/J) and
// the compression 1 − J, each over its `[foam]` scale and clamped to [0, 1] (ocean-core
// foam::heuristic_turbulence), through the foam texture.
// Implements the foam interface (foam_coverage) that water.wgsl imports as `technique/foam`.
// CPU mirror: ocean-cpu/src/shaders/foam/heuristic.rs.

fn foam_coverage(in: VertexOut, p: SurfacePoint) -> f32 {
    let h = in.rel.y + frame.view.eye_height;
    let s = sqrt(p.slopes.x * p.slopes.x + p.slopes.y * p.slopes.y);
    let t = heuristic_turbulence(h, s, surface_jacobian(in));
    return foam_mix(t, foam_texture_at(in.pos));
}
