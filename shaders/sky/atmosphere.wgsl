// Sky technique `atmosphere` (seed 002): single scattering by air (Rayleigh) and aerosols (Mie)
// in a spherical, ozone-free standard atmosphere (Bruneton & Neyret 2008's constants;
// ocean_core::atmosphere), read from the frame's sky-view table (shared/sky_lut.wgsl); the sun
// disc is Preetham's disc shape (formed without cancellation) with the sun's radiance through the atmosphere, which the
// frame puts in `sky.sun_radiance`. It implements the sky interface (sky_radiance, sun_disc;
// SkyUniforms) that `sky.wgsl` and the water's shading import as `technique/sky`.
// CPU mirror: ocean-cpu/src/shaders/sky/atmosphere.rs.

// #import shared/preetham.wgsl
// #import shared/sky_lut.wgsl

// Sky radiance without the sun disc in unit direction dir: linear sRGB, scene units.
fn sky_radiance(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    return sky_lut_radiance(dir, sky.sun_direction.xyz);
}

// The sun disc in unit direction dir: Preetham's disc (preetham_sun_disc) with the sun's
// radiance through the atmosphere, which the frame puts in `sky.sun_radiance`.
fn sun_disc(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    return preetham_sun_disc(sky, dir);
}
