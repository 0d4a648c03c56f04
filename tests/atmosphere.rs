//! The single-scattering atmosphere of sky technique `atmosphere` (`ocean_core::atmosphere`):
//! normalised phase functions, the vertical optical depth of an exponential atmosphere in
//! closed form, the shader's step counts against a brute-force integration at several sun
//! elevations, the colours Rayleigh scattering must give, and finite values at and below the
//! horizon.

use std::f64::consts::PI;

use ocean_core::atmosphere::{
    EARTH_RADIUS_M, MIE_BETA, MIE_EXTINCTION_RATIO, MIE_G, MIE_HEIGHT_M, RAYLEIGH_BETA,
    RAYLEIGH_HEIGHT_M, SKY_STEPS, SUN_STEPS, TOP_RADIUS_M, mie_phase, rayleigh_phase, sky_radiance,
    sun_transmittance,
};

const E_SUN: [f64; 3] = [1.0; 3];

fn dir(elevation_deg: f64, azimuth_deg: f64) -> [f64; 3] {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    [e.cos() * a.cos(), e.sin(), e.cos() * a.sin()]
}

#[test]
fn the_phase_functions_are_normalised() {
    let n = 200_000;
    let integral = |p: &dyn Fn(f64) -> f64| -> f64 {
        (0..n)
            .map(|i| 2.0 * PI * p(-1.0 + (i as f64 + 0.5) * 2.0 / n as f64) * 2.0 / n as f64)
            .sum()
    };
    let r = integral(&rayleigh_phase);
    let m = integral(&|mu| mie_phase(mu, MIE_G));
    println!("∫ P dω: Rayleigh {r:.8}, Mie (g = {MIE_G}) {m:.8}");
    assert!((r - 1.0).abs() < 1e-8 && (m - 1.0).abs() < 1e-6, "{r} {m}");
    // Mie scatters forwards.
    assert!(mie_phase(1.0, MIE_G) > 100.0 * mie_phase(-1.0, MIE_G));
}

#[test]
fn the_vertical_optical_depth_is_the_exponential_atmospheres() {
    // Straight up from sea level: τ = β H (1 − e^{−Z/H}) per constituent, Z the top's height.
    let z = TOP_RADIUS_M - EARTH_RADIUS_M;
    let t = sun_transmittance([0.0, EARTH_RADIUS_M, 0.0], [0.0, 1.0, 0.0], 20_000);
    let mie = MIE_BETA * MIE_EXTINCTION_RATIO * MIE_HEIGHT_M * (1.0 - (-z / MIE_HEIGHT_M).exp());
    for c in 0..3 {
        let rayleigh =
            RAYLEIGH_BETA[c] * RAYLEIGH_HEIGHT_M * (1.0 - (-z / RAYLEIGH_HEIGHT_M).exp());
        let want = (-(rayleigh + mie)).exp();
        println!("channel {c}: T = {:.9}, closed form {want:.9}", t[c]);
        assert!((t[c] - want).abs() < 1e-7, "{} vs {want}", t[c]);
    }
    // The planet blocks the sun below the horizon.
    assert_eq!(sun_transmittance([0.0, EARTH_RADIUS_M + 10.0, 0.0], dir(-5.0, 0.0), 64), [0.0; 3]);
}

#[test]
fn the_shaders_step_counts_stay_near_a_brute_force_integration() {
    let mut worst: f64 = 0.0;
    let mut coarse_worst: f64 = 0.0;
    for sun_elevation in [90.0, 45.0, 10.0, 2.0] {
        let sun = dir(sun_elevation, 0.0);
        for elevation in [90.0, 60.0, 30.0, 10.0, 3.0, 0.5] {
            for azimuth in [0.0, 60.0, 120.0, 180.0] {
                let v = dir(elevation, azimuth);
                let truth = sky_radiance(0.0, v, sun, E_SUN, 4000, 400);
                let fast = sky_radiance(0.0, v, sun, E_SUN, SKY_STEPS, SUN_STEPS);
                let coarse = sky_radiance(0.0, v, sun, E_SUN, 4, 2);
                for c in 0..3 {
                    let rel = |x: f64| (x - truth[c]).abs() / truth[c];
                    worst = worst.max(rel(fast[c]));
                    coarse_worst = coarse_worst.max(rel(coarse[c]));
                }
            }
        }
    }
    println!(
        "{SKY_STEPS} × {SUN_STEPS} steps against 4000 × 400: worst relative error {worst:.4} \
         (4 × 2 steps: {coarse_worst:.3})"
    );
    assert!(worst < 0.03, "{worst}");
    assert!(coarse_worst > 3.0 * worst, "the negative control must be worse: {coarse_worst}");
}

#[test]
fn rayleigh_makes_the_noon_sky_blue_and_the_sunset_red() {
    let noon = sky_radiance(0.0, dir(90.0, 0.0), dir(80.0, 0.0), E_SUN, 400, 100);
    println!("zenith at noon: {:.3e} {:.3e} {:.3e}", noon[0], noon[1], noon[2]);
    assert!(noon[2] > noon[1] && noon[1] > noon[0], "{noon:?}");
    // Towards a setting sun, near the horizon, red gains on blue.
    let dusk = sky_radiance(0.0, dir(2.0, 0.0), dir(1.0, 0.0), E_SUN, 400, 100);
    let day = sky_radiance(0.0, dir(2.0, 0.0), dir(60.0, 0.0), E_SUN, 400, 100);
    println!(
        "horizon towards the sun: r/b {:.3} at dusk, {:.3} by day",
        dusk[0] / dusk[2],
        day[0] / day[2]
    );
    assert!(dusk[0] / dusk[2] > 2.0 * day[0] / day[2]);
}

#[test]
fn the_sky_is_finite_at_and_below_the_horizon_and_at_night() {
    for altitude in [0.0, 2.0, 10_000.0, 100_000.0, -5.0] {
        for sun_elevation in [90.0, 0.0, -0.5, -20.0] {
            for elevation in [90.0, 0.0, -0.01, -30.0, -90.0] {
                let l = sky_radiance(
                    altitude,
                    dir(elevation, 30.0),
                    dir(sun_elevation, 0.0),
                    E_SUN,
                    SKY_STEPS,
                    SUN_STEPS,
                );
                assert!(
                    l.iter().all(|x| x.is_finite() && *x >= 0.0),
                    "{altitude} {sun_elevation} {elevation}: {l:?}"
                );
            }
        }
    }
    // No sun above the horizon anywhere on the planet's lit side: a dim, not a bright, sky.
    let night = sky_radiance(0.0, dir(45.0, 0.0), dir(-20.0, 0.0), E_SUN, SKY_STEPS, SUN_STEPS);
    let day = sky_radiance(0.0, dir(45.0, 0.0), dir(45.0, 0.0), E_SUN, SKY_STEPS, SUN_STEPS);
    assert!(night[2] < 1e-3 * day[2], "{night:?} {day:?}");
}

/// The sky-view table's coordinates invert its directions, at every texel centre and for a
/// sun high, low and at the zenith (where the azimuth is undefined and u = 0 is used).
#[test]
fn the_tables_coordinates_invert_its_directions() {
    use ocean_core::atmosphere::{lut_coordinates, lut_direction};
    let (mut worst, mut worst_u): (f64, f64) = (0.0, 0.0);
    for sun in [dir(30.0, 20.0), dir(3.0, -110.0), dir(89.999, 0.0)] {
        for j in 0..32 {
            for i in 0..32 {
                let (u, v) = (f64::from(i) / 31.0, f64::from(j) / 31.0);
                let d = lut_direction(u, v, sun);
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                assert!((len - 1.0).abs() < 1e-12, "unit: {len}");
                let [u2, v2] = lut_coordinates(d, sun);
                // At the poles (and under a vertical sun) there is no azimuth: only v counts.
                let pole = j == 0 || j == 31 || sun[1] > 0.9999;
                worst_u = worst_u.max(if pole { 0.0 } else { (u2 - u).abs() });
                worst = worst.max((v2 - v).abs());
            }
        }
    }
    println!("table coordinates round trip: worst v {worst:.1e}, u {worst_u:.1e}");
    assert!(worst < 1e-9, "{worst}");
    assert!(worst_u < 1e-7, "{worst_u}");
    // A vertical sun or view has no azimuth: u = 0, and v covers the poles.
    assert_eq!(lut_coordinates([0.0, 1.0, 0.0], dir(30.0, 0.0)), [0.0, 1.0]);
    assert_eq!(lut_coordinates([0.0, -1.0, 0.0], dir(30.0, 0.0)), [0.0, 0.0]);
    assert_eq!(lut_coordinates(dir(10.0, 40.0), [0.0, 1.0, 0.0])[0], 0.0);
}

/// The table (f64 bilinear lookup, `SkyLut::radiance`) against the model itself: equal at the
/// texel centres (to f32 rounding), and between them within the interpolation error measured
/// here over 4000 random upward directions (relative to each direction's brightest channel),
/// for a high and a low sun; the shaders' f32 lookup
/// (the CPU mirror of shared/sky_lut.wgsl) equals the f64 one to f32 rounding. A table made for
/// another sun is the negative control.
#[test]
fn the_sky_view_table_reproduces_the_model() {
    use ocean_core::atmosphere::{SkyLut, lut_direction};
    use ocean_core::rng::SplitMix64;
    use ocean_cpu::shaders::shared::sky_lut::sky_lut_radiance;
    use ocean_cpu::shaders::wgsl::vec3;
    let e = [1.0, 1.0, 1.0];
    let mut rng = SplitMix64::new(3);
    for (sun, bound) in [(dir(40.0, 30.0), 0.05), (dir(4.0, -60.0), 0.05)] {
        let lut = SkyLut::new(10.0, sun, e);
        let model = |d: [f64; 3]| sky_radiance(10.0, d, sun, e, SKY_STEPS, SUN_STEPS);
        let mut at_centres: f64 = 0.0;
        for (j, i) in [(0, 0), (5, 7), (16, 0), (17, 31), (31, 12), (24, 3)] {
            let d = lut_direction(f64::from(i) / 31.0, f64::from(j) / 31.0, sun);
            let (want, got) = (model(d), lut.radiance(d, sun));
            for c in 0..3 {
                at_centres = at_centres.max((got[c] - want[c]).abs() / want[c].max(1e-12));
            }
        }
        let (mut between, mut mirror, mut other): (f64, f64, f64) = (0.0, 0.0, 0.0);
        let other_lut = SkyLut::new(10.0, dir(sun[1].asin().to_degrees() + 10.0, 150.0), e);
        for _ in 0..4000 {
            let d = dir(89.0 * rng.next_open_closed(), 360.0 * rng.next_open_closed());
            let (want, got) = (model(d), lut.radiance(d, sun));
            let f = |a: [f64; 3]| vec3(a[0] as f32, a[1] as f32, a[2] as f32);
            let shader = sky_lut_radiance(&lut, f(d), f(sun));
            let wrong = other_lut.radiance(d, sun);
            let shader = [shader.x, shader.y, shader.z];
            // Relative to the direction's brightest channel: at a low sun the blue of the
            // horizon is a sixth of its red, and a pixel's error is seen against its whole.
            let scale = want.iter().copied().fold(1e-6, f64::max);
            for c in 0..3 {
                between = between.max((got[c] - want[c]).abs() / scale);
                mirror = mirror.max((f64::from(shader[c]) - got[c]).abs() / got[c].max(1e-6));
                other = other.max((wrong[c] - want[c]).abs() / scale);
            }
        }
        println!(
            "sun {sun:.3?}: table at centres {at_centres:.1e}, between {between:.3}, \
             f32 lookup vs f64 {mirror:.1e}, another sun's table {other:.2}"
        );
        assert!(at_centres < 1e-6, "{at_centres}");
        assert!(between < bound, "{between} ≥ {bound}");
        assert!(mirror < 2e-5, "{mirror}");
        assert!(other > bound, "the negative control must fail the bound: {other}");
    }
}

/// The kept sky table (made once per altitude, sun and irradiance) is the table made anew,
/// bit for bit, and another sun gets another table (not the kept one).
#[test]
fn the_kept_sky_table_is_the_fresh_one() {
    use ocean_core::atmosphere::SkyLut;
    let sun = [0.3, 0.5, -0.812_403_840_463_596];
    let top = [1.7, 1.8, 1.9];
    let first = SkyLut::kept(2.0, sun, top);
    let again = SkyLut::kept(2.0, sun, top);
    assert!(*first == *SkyLut::new(2.0, sun, top) && *again == *first);
    let lower = [0.3, 0.2, -0.932_737_905_308_881_5];
    let other = SkyLut::kept(2.0, lower, top);
    assert!(*other == *SkyLut::new(2.0, lower, top) && *other != *first);
}

/// A frame's light under sky `atmosphere` — the sun at the eye and the sky's ambient term,
/// kept per eye height and sun since they cost a quarter of a millisecond each frame — is the
/// one computed anew, bit for bit, for two suns asked in turn; and the two differ, so a stale
/// answer would be seen.
#[test]
fn the_kept_atmosphere_light_is_the_fresh_one() {
    use ocean_core::atmosphere::{SkyLut, sun_at_eye, top_irradiance};
    use ocean_core::graph::{FrameInputs, FrameState};
    use ocean_core::plan::{FramePlan, OutputKind};
    use ocean_core::scene::Scene;
    use ocean_core::technique::System;
    let base = Scene::builtin_for(System::Welch).with_system(System::Welch).expect("welch");
    let scene = |elevation: f64| {
        let mut s = base.clone();
        s.sun.as_mut().expect("a sun").direction = dir(elevation, 40.0);
        s
    };
    let (high, low) = (scene(50.0), scene(12.0));
    let light = |s: &Scene| {
        let plan = FramePlan::new(s, OutputKind::Ldr);
        assert!(plan.techniques.sky().sky_view_table(), "welch's sky is the atmosphere");
        let f = FrameInputs::new(s, &plan, &FrameState::new(0.0)).expect("frame");
        (f.uniforms.ambient.sky, f.uniforms.sun.radiance, f.camera.eye.y)
    };
    let fresh = |s: &Scene, altitude: f64| {
        let sun = s.sun.as_ref().expect("a sun");
        let d = glam::DVec3::from(sun.direction).normalize().to_array();
        let top = top_irradiance(std::array::from_fn(|c| sun.color[c] * sun.intensity));
        let at_eye = sun_at_eye(altitude.max(0.0), d, top).map(|e| e as f32);
        (SkyLut::new(altitude.max(0.0), d, top).ambient(d), at_eye)
    };
    let mut seen = Vec::new();
    for s in [&high, &low, &high, &low] {
        let (ambient, sun, altitude) = light(s);
        let (want_ambient, want_sun) = fresh(s, altitude);
        assert_eq!(ambient, want_ambient);
        assert_eq!(sun, want_sun);
        seen.push(ambient);
    }
    assert_ne!(seen[0], seen[1], "two suns, one ambient term");
}
