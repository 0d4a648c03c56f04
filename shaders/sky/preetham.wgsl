// Sky technique `preetham`: the clear Preetham sky (shared/preetham.wgsl). It implements the
// sky interface (sky_radiance, sun_disc; SkyUniforms) that `sky.wgsl` and the water's shading
// import as `technique/sky`. CPU mirror: ocean-cpu/src/shaders/sky/preetham.rs.

// #import shared/preetham.wgsl

// Sky radiance without the sun disc in unit direction dir: linear sRGB, scene units.
fn sky_radiance(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    return preetham_radiance(sky, dir);
}

// The sun disc in unit direction dir.
fn sun_disc(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    return preetham_sun_disc(sky, dir);
}
