// Sky technique `overcast`: the CIE standard overcast sky (Moon & Spencer 1942; CIE S 011/E:2003
// sky type 1), L(theta) = L_z (1 + 2 cos theta) / 3, grey, with the clear sky's zenith
// luminance as L_z and no sun disc (the cloud deck hides it). An even, known light for testing
// the water's shading: its horizontal illuminance is 7 pi L_z / 9. It implements the sky
// interface (sky_radiance, sun_disc; SkyUniforms) that `sky.wgsl` and the water's shading import
// as `technique/sky`. CPU mirror: ocean-cpu/src/shaders/sky/overcast.rs.

// #import shared/preetham.wgsl

// Sky radiance in unit direction dir: linear sRGB (grey: R = G = B = the luminance, since
// sRGB's white is D65's), scene units; views at and below the horizon see the horizon's value.
fn sky_radiance(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    let cos_theta = max(dir.y, sky.cos_theta_min);
    let luminance = sky.zenith.x * (1.0 + 2.0 * cos_theta) / 3.0;
    return vec3<f32>(luminance * sky.sky_scale);
}

// No sun disc under the cloud deck.
fn sun_disc(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(0.0);
}
