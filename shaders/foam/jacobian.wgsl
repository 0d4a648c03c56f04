// Foam technique `jacobian`: foam where the horizontal displacement's Jacobian J is below
// `[foam] threshold`, rising to full over `[foam] softness` (ocean-core
// foam::jacobian_turbulence), through the foam texture. J is the displacement map's (its
// texels carry it in w) or, under waves `gerstner`, the waves' analytic one.
// Implements the foam interface (foam_coverage) that water.wgsl imports as `technique/foam`.
// CPU mirror: ocean-cpu/src/shaders/foam/jacobian.rs.

fn foam_coverage(in: VertexOut, p: SurfacePoint) -> f32 {
    let t = jacobian_turbulence(surface_jacobian(in));
    return foam_mix(t, foam_texture_at(in.pos));
}
