// Preetham, Shirley & Smits (1999), "A practical analytic model for daylight": sky radiance in
// a direction, and the sun disc. Physics, equations and the choices at the model's edges:
// ocean_core::sky (f64 reference). Rust struct: ocean_core::sky::SkyUniforms.
// CPU mirror: ocean-cpu/src/shaders/shared/preetham.rs. The sky techniques `preetham` (this
// sky alone) and `preetham_clouds` (with seed 001's cloud layer) are built on it.
//
// Channels are ordered (Y, x, y): luminance Y in kcd/m2, CIE chromaticities x and y.

struct SkyUniforms {
    // Perez coefficients A..E of (Y, x, y); w unused.
    perez_a: vec4<f32>,
    perez_b: vec4<f32>,
    perez_c: vec4<f32>,
    perez_d: vec4<f32>,
    perez_e: vec4<f32>,
    // Zenith values (Y_z, x_z, y_z).
    zenith: vec4<f32>,
    // F(0, theta_s) of (Y, x, y): the normalisation of eq. 4.
    perez_zenith: vec4<f32>,
    // Unit direction towards the sun.
    sun_direction: vec4<f32>,
    // Radiance of the sun disc, linear sRGB, scene units.
    sun_radiance: vec4<f32>,
    // Scene units per kcd/m2, the twilight fade included.
    sky_scale: f32,
    // Lower clamp of cos(theta) (views at and below the horizon).
    cos_theta_min: f32,
    // sin of the inner and outer radius of the sun disc's rim.
    sun_sin_inner: f32,
    sun_sin_outer: f32,
    // Sky technique `preetham_clouds`' layer (ocean-core sky::clouds): the eye's (x, z) on the
    // noise lattice (reduced modulo its period), the layer's height above the eye in lattice
    // cells, and the opacity's threshold (ocean-core clouds::cloud_threshold).
    cloud_origin: vec4<f32>,
    // The lit cloud's radiance (rgb), and the alpha towards the horizon (w).
    cloud_color: vec4<f32>,
}

// Smallest chromaticity y in xyY -> XYZ (ocean_core::sky::MIN_CHROMATICITY_Y).
const MIN_CHROMATICITY_Y: f32 = 0.0001;

// Perez et al. (1993) distribution, Preetham et al. eq. 3, for (Y, x, y) at once:
// F(theta, gamma) = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma).
fn perez(sky: SkyUniforms, cos_theta: f32, gamma: f32, cos_gamma: f32) -> vec3<f32> {
    let a = sky.perez_a.xyz;
    let b = sky.perez_b.xyz;
    let c = sky.perez_c.xyz;
    let d = sky.perez_d.xyz;
    let e = sky.perez_e.xyz;
    return (1.0 + a * exp(b / cos_theta)) * (1.0 + c * exp(d * gamma) + e * cos_gamma * cos_gamma);
}

// CIE XYZ -> linear sRGB, IEC 61966-2-1 (ocean_core::sky::XYZ_TO_LINEAR_SRGB).
fn xyz_to_linear_srgb(xyz: vec3<f32>) -> vec3<f32> {
    let r = 3.2406 * xyz.x - 1.5372 * xyz.y - 0.4986 * xyz.z;
    let g = -0.9689 * xyz.x + 1.8758 * xyz.y + 0.0415 * xyz.z;
    let b = 0.0557 * xyz.x - 0.2040 * xyz.y + 1.0570 * xyz.z;
    return vec3<f32>(r, g, b);
}

// Sky radiance without the sun disc in unit direction dir: linear sRGB, scene units.
// Y(theta, gamma) = Y_z F(theta, gamma) / F(0, theta_s), likewise x and y (eq. 4), with
// cos(theta) clamped below; gamma = 2 atan2(|dir x sun|, 1 + dir . sun), the half-angle
// form: accurate near the sun, and its second argument stays away from 0 but opposite the
// sun, where WGSL's atan2 is bounded (4096 ULP needs |x| >= 2^-126; atan2(sin, cos) had no
// bound on the whole great circle 90 degrees from the sun).
fn preetham_radiance(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    let sun = sky.sun_direction.xyz;
    let cos_theta = max(dir.y, sky.cos_theta_min);
    let cos_gamma = dot(dir, sun);
    let sin_gamma = length(cross(dir, sun));
    let gamma = 2.0 * atan2(sin_gamma, 1.0 + cos_gamma);
    let f = perez(sky, cos_theta, gamma, cos_gamma);
    let yxy = sky.zenith.xyz * f / sky.perez_zenith.xyz;
    let big_y = yxy.x;
    let x = yxy.y;
    let y = max(yxy.z, MIN_CHROMATICITY_Y);
    let xyz = vec3<f32>(x / y * big_y, big_y, (1.0 - x - y) / y * big_y);
    let rgb = xyz_to_linear_srgb(xyz);
    return max(rgb, vec3<f32>(0.0)) * sky.sky_scale;
}

// The sun disc in unit direction dir: sun_radiance times a weight that is 1 inside the disc,
// falls linearly in sin(gamma) across the rim, and is 0 outside and below the horizon.
// sin(gamma) = |(d − s) × s| (= |d × s|): next to the sun the components of d × s cancel,
// d − s is formed exactly there (Sterbenz), and the rim then agrees between the back ends.
fn preetham_sun_disc(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    let sun = sky.sun_direction.xyz;
    let cos_gamma = dot(dir, sun);
    let sin_gamma = length(cross(dir - sun, sun));
    let ramp = clamp((sky.sun_sin_outer - sin_gamma) / (sky.sun_sin_outer - sky.sun_sin_inner), 0.0, 1.0);
    let weight = select(0.0, ramp, cos_gamma > 0.0 && dir.y >= 0.0);
    return sky.sun_radiance.xyz * weight;
}
