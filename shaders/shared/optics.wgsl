// Water optics shared by the stages that shade water or what lies under it (`water`,
// `objects`): arithmetic-only e^x and the water-volume colour (the constant of shading `hu` or
// seed 001's eq. 8). Reads the importing stage's
// `frame` (FrameUniforms). CPU mirror: ocean-cpu/src/shaders/shared/optics.rs.

// #import shared/fresnel.wgsl

// exp_arith's arguments are clamped to [EXP_MIN, 0] (e^−80 ≈ 2e-35: zero for its uses).
const EXP_MIN: f32 = -80.0;

// e^x for x ≤ 0 by + − × only, so both back ends round alike (exp() is the implementation's
// approximation; lavapipe's differs from the CPU's by ulps, and the sun's lobe magnified
// that past the float tolerance): 2^n · e^y, n = ⌊x·log2 e + ½⌋ (ldexp: exact), |y| ≤ ½ ln 2,
// e^y by its Taylor polynomial to y⁷ (relative error < 6e-9 plus rounding).
fn exp_arith(x: f32) -> f32 {
    let z = clamp(x, EXP_MIN, 0.0) * 1.442695;
    let n = floor(z + 0.5);
    let y = (z - n) * 0.6931472;
    let p = 1.0 + y * (1.0 + y * (0.5 + y * (0.16666667 + y * (0.041666668 + y * (0.008333334 + y * (0.0013888889 + y * 0.0001984127))))));
    return p * ldexp(1.0, i32(n));
}

// ln 0.30, ln 0.73, ln 0.63: eq. 8's colour (0.30, 0.73, 0.63)^(k_d·y) is e^(k_d·y·ln c).
const EQ8_LN_R: f32 = -1.2039728;
const EQ8_LN_G: f32 = -0.31471074;
const EQ8_LN_B: f32 = -0.46203546;

// The radiance a white Lambertian surface facing up returns under the sun and the sky: the
// downwelling light at the surface, E_sun cos θ_sun/π plus the sky's ambient.
fn downwelling() -> vec3<f32> {
    let cos_sun = max(frame.sun.direction.y, 0.0) * frame.sun.lit;
    return frame.sun.radiance * (cos_sun * 0.31830988618) + frame.ambient.sky;
}

// The colour of the water volume at depth `depth` (m): shading `hu`'s constant C_deep_water,
// or seed 001's eq. 8 under the downwelling light, which is white at y = 0 (the light
// reaching a white floor there) and goes to black as red, then blue and green are absorbed.
fn water_volume_colour(depth: f32) -> vec3<f32> {
    if (frame.water.volume_model == 0.0) {
        return frame.water.color;
    }
    let k = frame.water.kd_per_m * max(depth, 0.0);
    return downwelling() * vec3<f32>(exp_arith(k * EQ8_LN_R), exp_arith(k * EQ8_LN_G), exp_arith(k * EQ8_LN_B));
}
