//! The `sky` stage: the f64 Preetham model against the paper (Preetham, Shirley & Smits 1999,
//! Appendix A.2) typed here independently, the model's own predictions (normalisation, azimuthal
//! symmetry, circumsolar and horizon brightening), its edges (sun at and below the horizon,
//! views straight down, turbidity limits), and the CPU shader (f32) against the f64 model on
//! rendered frames. Each comparator has a negative control.

use std::f64::consts::{FRAC_PI_2, PI};

use ocean_core::camera_uniforms::CameraUniforms;
use ocean_core::sky::{
    self, COS_THETA_MIN, NIGHT_FLOOR, PreethamSky, SUN_ANGULAR_RADIUS, SkyParams, TURBIDITY_MAX,
    TURBIDITY_MIN, TWILIGHT_DEPTH,
};
use ocean_cpu::raster::RenderTarget;
use ocean_cpu::shaders::sky::cs_main;

/// The `sky` pass with technique `preetham`.
fn render_sky(
    target: &mut ocean_cpu::raster::RenderTarget,
    camera: &ocean_core::camera_uniforms::CameraUniforms,
    sky: &ocean_core::sky::SkyUniforms,
) {
    let t = ocean_cpu::shaders::sky::technique(ocean_core::plan::Sky::Preetham);
    let lut: ocean_core::atmosphere::SkyLut = bytemuck::Zeroable::zeroed();
    ocean_cpu::shaders::sky::render_sky(target, camera, sky, &lut, &t);
}

const TURBIDITIES: [f64; 6] = [TURBIDITY_MIN, 2.0, 3.0, 6.0, 10.0, TURBIDITY_MAX];

/// Unit vector at elevation `el` (from the horizon) and azimuth `az` (from +x towards +z).
fn dir(el: f64, az: f64) -> [f64; 3] {
    [el.cos() * az.cos(), el.sin(), el.cos() * az.sin()]
}

fn deg(d: f64) -> f64 {
    d.to_radians()
}

fn sky_at(sun_el: f64, sun_az: f64, t: f64) -> PreethamSky {
    let params = SkyParams::new(dir(sun_el, sun_az), t, [1.0, 0.9, 0.75], 20.0);
    PreethamSky::new(params.expect("valid sky parameters"))
}

/// Preetham et al. (1999), Appendix A.2, typed from the paper: the distribution coefficients as
/// functions of T, rows Y, x, y; columns A, B, C, D, E.
fn paper_coefficients(t: f64) -> [[f64; 5]; 3] {
    [
        [
            0.1787 * t - 1.4630,
            -0.3554 * t + 0.4275,
            -0.0227 * t + 5.3251,
            0.1206 * t - 2.5771,
            -0.0670 * t + 0.3703,
        ],
        [
            -0.0193 * t - 0.2592,
            -0.0665 * t + 0.0008,
            -0.0004 * t + 0.2125,
            -0.0641 * t - 0.8989,
            -0.0033 * t + 0.0452,
        ],
        [
            -0.0167 * t - 0.2608,
            -0.0950 * t + 0.0092,
            -0.0079 * t + 0.2102,
            -0.0441 * t - 1.6537,
            -0.0109 * t + 0.0529,
        ],
    ]
}

/// Appendix A.2, typed from the paper: x_z and y_z as polynomials, expanded.
fn paper_zenith_chromaticity(ts: f64, t: f64) -> [f64; 2] {
    let (t2, s2, s3) = (t * t, ts * ts, ts * ts * ts);
    let x = t2 * (0.00166 * s3 - 0.00375 * s2 + 0.00209 * ts)
        + t * (-0.02903 * s3 + 0.06377 * s2 - 0.03202 * ts + 0.00394)
        + (0.11693 * s3 - 0.21196 * s2 + 0.06052 * ts + 0.25886);
    let y = t2 * (0.00275 * s3 - 0.00610 * s2 + 0.00317 * ts)
        + t * (-0.04214 * s3 + 0.08970 * s2 - 0.04153 * ts + 0.00516)
        + (0.15346 * s3 - 0.26756 * s2 + 0.06670 * ts + 0.26688);
    [x, y]
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()) + 1e-300
}

#[test]
fn coefficients_match_the_papers_table() {
    for t in [1.7, 2.0, 2.5, 4.0, 7.5, 10.0, 20.0] {
        let ours = sky::perez_coefficients(t);
        let paper = paper_coefficients(t);
        for c in 0..3 {
            for k in 0..5 {
                assert!(close(ours[c][k], paper[c][k], 1e-14), "T={t} channel {c} coeff {k}");
            }
        }
    }
    // Negative control: one digit off in one entry (C_Y's intercept 5.3251 -> 5.3215) is seen.
    let mut wrong = paper_coefficients(3.0);
    wrong[0][2] += 5.3215 - 5.3251;
    assert!(!close(sky::perez_coefficients(3.0)[0][2], wrong[0][2], 1e-6));
}

#[test]
fn zenith_values_match_the_paper() {
    // Y_z = (4.0453 T − 4.9710) tan χ − 0.2155 T + 2.4192, χ = (4/9 − T/120)(π − 2θ_s), typed
    // again; and four values worked out by hand (kcd/m²) against transcription errors in both.
    for t in [2.0, 3.0, 6.0, 10.0] {
        for ts_deg in [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 89.0, 90.0] {
            let ts = deg(ts_deg);
            let chi = (4.0 / 9.0 - t / 120.0) * (PI - 2.0 * ts);
            let want = (4.0453 * t - 4.9710) * chi.tan() - 0.2155 * t + 2.4192;
            assert!(close(sky::zenith_luminance(ts, t), want, 1e-13), "Y_z T={t} θs={ts_deg}");
            let [x, y] = sky::zenith_chromaticity(ts, t);
            let [px, py] = paper_zenith_chromaticity(ts, t);
            assert!(close(x, px, 1e-13) && close(y, py, 1e-13), "x_z, y_z T={t} θs={ts_deg}");
        }
    }
    for (t, ts_deg, want) in
        [(2.0, 0.0, 15.5007), (2.0, 30.0, 5.88674), (2.0, 60.0, 3.48733), (2.5, 30.0, 8.19297)]
    {
        let got = sky::zenith_luminance(deg(ts_deg), t);
        assert!((got - want).abs() < 1e-4, "Y_z(T={t}, θs={ts_deg}°) = {got}, hand: {want}");
    }
    // θ_s = 0: only the constant column survives. x_z = 0.00394 T + 0.25886.
    let [x, y] = sky::zenith_chromaticity(0.0, 2.0);
    assert!((x - 0.26674).abs() < 1e-12 && (y - 0.27720).abs() < 1e-12, "{x} {y}");
}

#[test]
fn zenith_radiance_is_the_zenith_value() {
    // Eq. 4 is normalised so that Y(θ = 0, γ = θ_s) = Y_z, and likewise x and y.
    for t in TURBIDITIES {
        for el in [90.0, 60.0, 30.0, 5.0, 0.0] {
            let s = sky_at(deg(el), deg(40.0), t);
            let yxy = s.yxy([0.0, 1.0, 0.0]);
            for (c, (got, want)) in yxy.iter().zip(s.zenith).enumerate() {
                assert!(close(*got, want, 1e-12), "T={t} el={el} channel {c}");
            }
        }
    }
}

#[test]
fn sky_is_symmetric_about_the_suns_vertical_plane() {
    for t in [2.0, 6.0] {
        let sun_az = deg(30.0);
        let s = sky_at(deg(25.0), sun_az, t);
        for el in [-30.0, 0.0, 10.0, 45.0, 80.0] {
            for off in [1.0, 20.0, 90.0, 135.0, 179.0] {
                let a = s.radiance(dir(deg(el), sun_az + deg(off)));
                let b = s.radiance(dir(deg(el), sun_az - deg(off)));
                for c in 0..3 {
                    assert!(close(a[c], b[c], 1e-12), "T={t} el={el} off={off}: {a:?} {b:?}");
                }
            }
        }
        // Negative control: a different offset on the two sides is seen.
        let a = s.radiance(dir(deg(45.0), sun_az + deg(20.0)));
        let b = s.radiance(dir(deg(45.0), sun_az - deg(21.0)));
        assert!(!close(a[0], b[0], 1e-6));
    }
}

#[test]
fn luminance_rises_towards_the_sun_and_towards_the_horizon() {
    for t in [2.0, 3.0, 6.0, 10.0] {
        let s = sky_at(deg(30.0), 0.0, t);
        // Circumsolar brightening: at the sun's elevation, Y falls as the azimuth leaves the sun
        // (γ grows from 0.5° to 60°).
        let ring: Vec<f64> =
            (0..=120).map(|i| s.yxy(dir(deg(30.0), deg(0.5 + i as f64 * 0.5)))[0]).collect();
        assert!(ring.windows(2).all(|w| w[1] < w[0]), "T={t}: not decreasing away from the sun");
        // Negative control: the sky opposite the sun, 60° up, is darker than near the sun.
        assert!(s.yxy(dir(deg(60.0), PI))[0] < ring[0]);
        // Horizon: at fixed γ the Perez θ-factor 1 + A e^{B / cos θ} (B < 0) grows towards the
        // horizon when A_Y < 0, i.e. T < 1.4630 / 0.1787 ≈ 8.19 (the paper's table), and falls
        // for hazier skies. (Non-strict steps: e^{B / cos θ} underflows near the horizon.)
        let [k_y, ..] = sky::perez_coefficients(t);
        let brightens = t < 1.4630 / 0.1787;
        for gamma in [0.2, 1.0, 2.0, 3.0] {
            let f: Vec<f64> =
                (0..=89).map(|d| sky::perez(&k_y, deg(d as f64).cos(), gamma)).collect();
            let (first, last) = (f[0], f[89]);
            if brightens {
                assert!(f.windows(2).all(|w| w[1] >= w[0]) && last > first, "T={t} γ={gamma}");
            } else {
                assert!(f.windows(2).all(|w| w[1] <= w[0]) && last < first, "T={t} γ={gamma}");
            }
        }
        // In the sky itself: with the sun on the horizon, the zenith and the horizon 90° from
        // the sun in azimuth are both 90° from the sun (same γ), so only the θ-factor differs.
        let sunset = sky_at(0.0, 0.0, t);
        let (horizon, zenith) = (sunset.yxy(dir(0.0, FRAC_PI_2))[0], sunset.zenith[0]);
        assert_eq!(horizon > zenith, brightens, "T={t}: horizon {horizon}, zenith {zenith}");
    }
}

#[test]
fn colour_is_a_daylight_blue_at_the_zenith() {
    // A clear noon sky: zenith chromaticity bluer than D65 (x, y < 0.3127, 0.3290) and its
    // linear sRGB has blue > green > red.
    let s = sky_at(deg(60.0), 0.0, 2.5);
    let [_, x, y] = s.yxy([0.0, 1.0, 0.0]);
    assert!(x < 0.3127 && y < 0.3290, "zenith xy = ({x}, {y})");
    let rgb = s.sky_radiance([0.0, 1.0, 0.0]);
    assert!(rgb[2] > rgb[1] && rgb[1] > rgb[0] && rgb[0] > 0.0, "{rgb:?}");
}

/// Directions on a sphere (elevation −90°..90°, azimuth 0..360°) plus the special ones.
fn sphere_directions(sun: [f64; 3]) -> Vec<[f64; 3]> {
    let mut dirs = vec![[0.0, 1.0, 0.0], [0.0, -1.0, 0.0], sun, sun.map(|c| -c), [1.0, 0.0, 0.0]];
    for i in 0..=36 {
        for j in 0..24 {
            dirs.push(dir(deg(-90.0 + 5.0 * i as f64), deg(15.0 * j as f64)));
        }
    }
    dirs
}

#[test]
fn finite_and_non_negative_everywhere() {
    let sun_elevations = [90.0, 45.0, 1.0, 1e-9, 0.0, -1e-9, -1.0, -3.0, -6.0, -10.0, -45.0, -90.0];
    for t in TURBIDITIES {
        for el in sun_elevations {
            let s = sky_at(deg(el), deg(10.0), t);
            let u = s.uniforms();
            let camera = identity_camera();
            for d in sphere_directions(s.params.sun_direction) {
                let r = s.radiance(d);
                assert!(
                    r.iter().all(|c| c.is_finite() && *c >= 0.0),
                    "T={t} el={el} d={d:?}: {r:?}"
                );
                // The f32 shader too, through its sky function (not a pixel).
                let d32 = d.map(|c| c as f32);
                let g: [f32; 3] =
                    ocean_cpu::shaders::sky::preetham::sky_radiance(&u, d32.into()).into();
                let h: [f32; 3] =
                    ocean_cpu::shaders::sky::preetham::sun_disc(&u, d32.into()).into();
                assert!(
                    g.iter().chain(&h).all(|c| c.is_finite() && *c >= 0.0),
                    "f32 T={t} el={el}"
                );
            }
            let t = ocean_cpu::shaders::sky::technique(ocean_core::plan::Sky::Preetham);
            let lut: ocean_core::atmosphere::SkyLut = bytemuck::Zeroable::zeroed();
            let px = cs_main([0, 0], &camera, &u, &lut, &t);
            assert!(px.iter().all(|c| c.is_finite()));
        }
    }
}

#[test]
fn sky_is_continuous_as_the_sun_sets_and_across_the_view_horizon() {
    let probe = [dir(deg(20.0), deg(60.0)), dir(deg(0.0), deg(180.0)), [0.0, 1.0, 0.0]];
    for t in [2.0, 10.0] {
        // Sun crossing the horizon: values just above and just below agree.
        let above = sky_at(1e-7, 0.0, t);
        let below = sky_at(-1e-7, 0.0, t);
        for d in probe {
            let (a, b) = (above.sky_radiance(d), below.sky_radiance(d));
            for c in 0..3 {
                assert!(close(a[c], b[c], 1e-5), "T={t} {d:?}: {a:?} vs {b:?}");
            }
        }
        // View direction crossing the horizon.
        let s = sky_at(deg(20.0), 0.0, t);
        for az in [30.0, 120.0, 180.0] {
            let a = s.sky_radiance(dir(1e-7, deg(az)));
            let b = s.sky_radiance(dir(-1e-7, deg(az)));
            for c in 0..3 {
                assert!(close(a[c], b[c], 1e-5), "T={t} az={az}: {a:?} vs {b:?}");
            }
        }
    }
}

#[test]
fn twilight_fade_goes_from_day_to_the_night_floor() {
    assert_eq!(sky::twilight_fade(0.0), 1.0);
    assert_eq!(sky::twilight_fade(deg(30.0)), 1.0);
    assert_eq!(sky::twilight_fade(-TWILIGHT_DEPTH), NIGHT_FLOOR);
    assert_eq!(sky::twilight_fade(-FRAC_PI_2), NIGHT_FLOOR);
    let f: Vec<f64> =
        (0..=600).map(|i| sky::twilight_fade(-TWILIGHT_DEPTH * i as f64 / 600.0)).collect();
    assert!(f.windows(2).all(|w| w[1] <= w[0]), "fade must not rise as the sun sinks");
    // The sky dims monotonically as the sun sinks through twilight, to about the floor times
    // the sunset sky (γ is measured from the true sun, so the ratio is not exactly the floor).
    for (d, far_from_sun) in [
        (dir(deg(40.0), deg(100.0)), true),
        (dir(deg(2.0), 0.0), false),
        (dir(deg(10.0), PI), true),
        ([0.0, 1.0, 0.0], true),
    ] {
        let y: Vec<f64> = (0..=60)
            .map(|i| {
                sky_at(deg(-0.1 * i as f64), 0.0, 3.0).yxy(d)[0]
                    * sky::twilight_fade(deg(-0.1 * i as f64))
            })
            .collect();
        assert!(y.windows(2).all(|w| w[1] < w[0]), "{d:?}: not dimming");
        if !far_from_sun {
            continue; // the circumsolar glow sinks with the sun: much more than the fade
        }
        let night = sky_at(deg(-30.0), 0.0, 3.0).sky_radiance(d);
        let sunset = sky_at(0.0, 0.0, 3.0).sky_radiance(d);
        for c in 0..3 {
            let ratio = night[c] / sunset[c];
            assert!(ratio > 0.3 * NIGHT_FLOOR && ratio < 3.0 * NIGHT_FLOOR, "{d:?}: {ratio}");
        }
    }
}

#[test]
fn sun_disc_has_the_suns_angular_radius() {
    let s = sky_at(deg(35.0), deg(70.0), 3.0);
    let sun = s.params.sun_direction;
    // Tilt the sun direction by angle a towards the zenith side.
    let at = |a: f64| dir(deg(35.0) + a, deg(70.0));
    assert_eq!(s.sun_disc_weight(sun), 1.0);
    assert_eq!(s.sun_disc_weight(at(0.9 * SUN_ANGULAR_RADIUS)), 1.0);
    assert!((s.sun_disc_weight(at(SUN_ANGULAR_RADIUS)) - 0.5).abs() < 1e-3);
    assert_eq!(s.sun_disc_weight(at(1.1 * SUN_ANGULAR_RADIUS)), 0.0);
    assert_eq!(s.sun_disc_weight(sun.map(|c| -c)), 0.0, "the anti-solar point has sin γ = 0 too");
    let r = s.radiance(sun);
    let sky_only = s.sky_radiance(sun);
    for c in 0..3 {
        assert!(close(r[c] - sky_only[c], s.params.sun_radiance[c], 1e-12));
    }
    assert_eq!(s.params.sun_radiance, [20.0, 18.0, 15.0], "intensity × colour");
    // Below the horizon the Earth hides the disc: a sun 0.1° below shows nothing, one on the
    // horizon shows its upper half.
    let low = sky_at(deg(-0.1), 0.0, 3.0);
    assert_eq!(low.sun_disc_weight(low.params.sun_direction), 0.0);
    let setting = sky_at(0.0, 0.0, 3.0);
    assert_eq!(setting.sun_disc_weight(dir(0.5 * SUN_ANGULAR_RADIUS, 0.0)), 1.0);
    assert_eq!(setting.sun_disc_weight(dir(-0.5 * SUN_ANGULAR_RADIUS, 0.0)), 0.0);
}

#[test]
fn parameters_are_validated() {
    let d = [0.0, 1.0, 0.0];
    for t in [TURBIDITY_MIN, 2.0, 10.0, TURBIDITY_MAX] {
        assert!(SkyParams::new(d, t, [1.0; 3], 1.0).is_ok(), "T={t}");
    }
    for t in [1.69, 20.01, 0.0, -3.0, f64::NAN, f64::INFINITY] {
        let err = SkyParams::new(d, t, [1.0; 3], 1.0).unwrap_err().to_string();
        assert!(err.contains("turbidity"), "{err}");
    }
    for bad in [[0.0; 3], [f64::NAN, 1.0, 0.0], [f64::INFINITY, 0.0, 0.0]] {
        assert!(SkyParams::new(bad, 3.0, [1.0; 3], 1.0).is_err(), "{bad:?}");
    }
    assert!(SkyParams::new(d, 3.0, [1.0, -0.1, 1.0], 1.0).is_err());
    assert!(SkyParams::new(d, 3.0, [1.0; 3], f64::NAN).is_err());
    let p = SkyParams::new([0.0, 2.0, 0.0], 3.0, [1.0; 3], 1.0).unwrap();
    assert_eq!(p.sun_direction, [0.0, 1.0, 0.0], "normalised");
    assert!(p.with_sky_scale(-1.0).is_err() && p.with_sky_scale(f64::NAN).is_err());
    assert_eq!(p.with_sky_scale(0.2).unwrap().sky_scale, 0.2);
}

#[test]
fn uniforms_carry_the_model() {
    let s = sky_at(deg(-3.0), deg(10.0), 4.0);
    let u = s.uniforms();
    let k = sky::perez_coefficients(4.0);
    assert_eq!(u.perez_a, [k[0][0] as f32, k[1][0] as f32, k[2][0] as f32, 0.0]);
    assert_eq!(u.perez_e, [k[0][4] as f32, k[1][4] as f32, k[2][4] as f32, 0.0]);
    assert_eq!(u.zenith[0], sky::zenith_luminance(FRAC_PI_2, 4.0) as f32, "θ_s clamped to 90°");
    assert_eq!(u.sky_scale, (sky::DEFAULT_SKY_SCALE * sky::twilight_fade(deg(-3.0))) as f32);
    assert_eq!(u.cos_theta_min, COS_THETA_MIN as f32);
    assert!(u.sun_sin_inner < u.sun_sin_outer);
}

// ---------------------------------------------------------------------------------------------
// Rendered frames: the CPU shader (f32, through the rasterizer) against the f64 model.

/// A camera at the origin looking along `forward` with vertical field of view `fov_y`: the f64
/// basis (right, up, forward) and the reversed-Z infinite perspective × view matrix,
/// column-major.
struct TestCamera {
    right: [f64; 3],
    up: [f64; 3],
    forward: [f64; 3],
    tan_half_fov: f64,
    aspect: f64,
    view_proj: [[f64; 4]; 4],
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

impl TestCamera {
    fn new(forward: [f64; 3], fov_y: f64, width: u32, height: u32) -> Self {
        let f = normalize(forward);
        let r = normalize(cross(f, [0.0, 1.0, 0.0]));
        let u = cross(r, f);
        let tan_half_fov = (0.5 * fov_y).tan();
        let aspect = f64::from(width) / f64::from(height);
        let (sx, sy, near) = (1.0 / (aspect * tan_half_fov), 1.0 / tan_half_fov, 0.1);
        // Rows of view: r, u, −f. Clip = (sx·x_v, sy·y_v, near, −z_v).
        let rows = [r.map(|c| sx * c), u.map(|c| sy * c), [0.0; 3], f];
        let mut m = [[0.0; 4]; 4];
        for (row, v) in rows.iter().enumerate() {
            for col in 0..3 {
                m[col][row] = v[col];
            }
        }
        m[3][2] = near;
        Self { right: r, up: u, forward: f, tan_half_fov, aspect, view_proj: m }
    }

    fn uniforms(&self, width: u32, height: u32, eye: [f64; 3]) -> CameraUniforms {
        CameraUniforms::new(self.view_proj, eye, width, height).expect("invertible camera")
    }

    /// The f64 ray through pixel centre (x + ½, y + ½), from the basis (not the matrix).
    fn ray(&self, x: u32, y: u32, width: u32, height: u32) -> [f64; 3] {
        let ndc_x = 2.0 * (f64::from(x) + 0.5) / f64::from(width) - 1.0;
        let ndc_y = 1.0 - 2.0 * (f64::from(y) + 0.5) / f64::from(height);
        let (a, b) = (ndc_x * self.aspect * self.tan_half_fov, ndc_y * self.tan_half_fov);
        normalize(std::array::from_fn(|i| self.forward[i] + a * self.right[i] + b * self.up[i]))
    }
}

fn identity_camera() -> CameraUniforms {
    TestCamera::new([0.0, 0.2, -1.0], deg(60.0), 4, 4).uniforms(4, 4, [0.0; 3])
}

/// Per-pixel tolerance of the f32 shader against the f64 model, channel `c` of a pixel whose
/// f64 ray is `ray` and reference value `reference`.
fn tolerance(model: &PreethamSky, ray: [f64; 3], reference: [f64; 3], c: usize) -> f64 {
    let scale = reference.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let [sin_inner, sin_outer] = rim_sines();
    let sin_gamma = length(cross(ray, model.params.sun_direction));
    let near_rim = sin_gamma > sin_inner - RIM_MARGIN && sin_gamma < sin_outer + RIM_MARGIN;
    let rim = if near_rim { model.params.sun_radiance[c] * RIM_WEIGHT_ERROR } else { 0.0 };
    REL_TOL * scale + ABS_TOL + rim
}

/// f32 evaluation, relative to the pixel's largest channel: exp, atan2, the inverse matrix cast
/// to f32 and the ray's normalisation each contribute a few ULP (2⁻²⁴ ≈ 6·10⁻⁸), and the XYZ →
/// sRGB rows cancel (a channel much smaller than the others, e.g. blue at sunset, has the error
/// of the largest). 2·10⁻⁵ is ≈ 300 ULP; the measured maximum is printed by the test.
const REL_TOL: f64 = 2e-5;
/// Absolute floor for values near 0: 10⁻⁷ scene units.
const ABS_TOL: f64 = 1e-7;
/// In the disc's rim the weight moves by 1 over Δ sin γ = sin(1.05 r) − sin(0.95 r) ≈ 4.65·10⁻⁴;
/// the f32 ray's sin γ is good to ≈ 2·10⁻⁷, so the weight to ≈ 4.3·10⁻⁴: allow 10⁻³ of the
/// sun's radiance for pixels whose f64 ray is within [`RIM_MARGIN`] of the rim.
const RIM_WEIGHT_ERROR: f64 = 1e-3;
/// How far (in sin γ) outside the rim the rim allowance applies: 100 times the f32 ray error.
const RIM_MARGIN: f64 = 2e-5;

fn rim_sines() -> [f64; 2] {
    let half = 0.5 * sky::SUN_RIM_FRACTION * SUN_ANGULAR_RADIUS;
    [(SUN_ANGULAR_RADIUS - half).sin(), (SUN_ANGULAR_RADIUS + half).sin()]
}

fn length(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

struct Comparison {
    /// Largest |f32 − f64| / (largest channel) outside the disc.
    worst_rel: f64,
    /// Channels out of tolerance.
    failures: usize,
    /// Pixels whose centre falls in the disc's rim.
    rim_pixels: usize,
}

fn compare(target: &RenderTarget, cam: &TestCamera, model: &PreethamSky) -> Comparison {
    let (w, h) = (target.width, target.height);
    let mut cmp = Comparison { worst_rel: 0.0, failures: 0, rim_pixels: 0 };
    for y in 0..h {
        for x in 0..w {
            let got = target.pixel(x, y);
            let ray = cam.ray(x, y, w, h);
            let want = model.radiance(ray);
            let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert_eq!(got[3], 1.0);
            let weight = model.sun_disc_weight(ray);
            if weight > 0.0 && weight < 1.0 {
                cmp.rim_pixels += 1;
            }
            for c in 0..3 {
                let err = (f64::from(got[c]) - want[c]).abs();
                if err > tolerance(model, ray, want, c) {
                    cmp.failures += 1;
                }
                if weight == 0.0 && scale > 0.0 {
                    cmp.worst_rel = cmp.worst_rel.max(err / scale);
                }
            }
        }
    }
    cmp
}

#[test]
fn cpu_shader_matches_the_f64_model_per_pixel() {
    let (w, h) = (160, 96);
    // (camera forward, sun elevation, sun azimuth, turbidity): looking at the sun (disc in view),
    // at a low sun across the horizon, straight up, steeply down, and a twilight sky.
    // The first camera has a 4° field of view: the disc (0.53° across) spans ~20 pixels.
    let cases = [
        ([1.0, 0.36, 0.0], 20.0, 0.0, 2.5),
        ([0.0, 0.05, -1.0], 4.0, -80.0, 6.0),
        ([0.001, 1.0, 0.0], 60.0, 30.0, 2.0),
        ([0.3, -1.0, 0.2], 45.0, 90.0, 10.0),
        ([1.0, 0.1, 0.0], -3.0, 0.0, 3.0),
    ];
    let mut rim_pixels = 0;
    for (i, (forward, el, az, t)) in cases.into_iter().enumerate() {
        let fov = if i == 0 { 4.0 } else { 60.0 };
        let cam = TestCamera::new(forward, deg(fov), w, h);
        let model = sky_at(deg(el), deg(az), t);
        let mut target = RenderTarget::new(w, h);
        target.clear_color([f32::NAN; 4]);
        render_sky(&mut target, &cam.uniforms(w, h, [0.0; 3]), &model.uniforms());
        let cmp = compare(&target, &cam, &model);
        println!(
            "forward {forward:?} sun ({el}°, {az}°) T={t}: worst sky rel err {:.2e}, {} rim pixels",
            cmp.worst_rel, cmp.rim_pixels
        );
        assert_eq!(
            cmp.failures, 0,
            "forward {forward:?}: {} channels out of tolerance",
            cmp.failures
        );
        rim_pixels += cmp.rim_pixels;
    }
    assert!(rim_pixels > 10, "the rim allowance was not exercised");
}

#[test]
fn the_disc_is_in_the_frame_where_the_sun_is() {
    // 4° field of view on 160 × 96: 0.042° per pixel, the disc ≈ 13 pixels across. Pixels whose
    // centre is inside the inner rim hold sky + the sun's radiance.
    let (w, h) = (160, 96);
    let cam = TestCamera::new([1.0, 0.36, 0.0], deg(4.0), w, h);
    let model = sky_at(deg(20.0), 0.0, 2.5);
    let mut target = RenderTarget::new(w, h);
    render_sky(&mut target, &cam.uniforms(w, h, [0.0; 3]), &model.uniforms());
    let lit = target.color.iter().filter(|p| p[0] > 20.0).count();
    let pixel = deg(4.0) / f64::from(h);
    let expected = PI * (0.95 * SUN_ANGULAR_RADIUS / pixel).powi(2);
    println!("disc: {lit} fully lit pixels, π(0.95 r / pixel)² = {expected:.1}");
    assert!(
        (lit as f64 - expected).abs() < 0.15 * expected,
        "{lit} lit pixels, {expected:.1} expected"
    );
}

#[test]
fn comparator_rejects_a_wrong_pixel_and_a_wrong_sky() {
    let (w, h) = (64, 40);
    let cam = TestCamera::new([0.0, 0.3, -1.0], deg(60.0), w, h);
    let model = sky_at(deg(30.0), deg(-60.0), 3.0);
    let mut target = RenderTarget::new(w, h);
    render_sky(&mut target, &cam.uniforms(w, h, [0.0; 3]), &model.uniforms());
    assert_eq!(compare(&target, &cam, &model).failures, 0);
    // One channel of one pixel moved by twice its tolerance.
    let mut one = target.clone();
    let (x, y) = (17, 9);
    let want = model.radiance(cam.ray(x, y, w, h));
    let i = (y * w + x) as usize;
    one.color[i][1] = (want[1] + 2.0 * tolerance(&model, cam.ray(x, y, w, h), want, 1)) as f32;
    assert_eq!(compare(&one, &cam, &model).failures, 1);
    // A 1 % different turbidity fails nearly everywhere (3 channels per pixel).
    let other = sky_at(deg(30.0), deg(-60.0), 3.03);
    assert!(compare(&target, &cam, &other).failures > 2 * (w * h) as usize);
}

#[test]
fn the_pass_writes_every_pixel_and_no_depth() {
    // One invocation per pixel: every pixel written (the target starts as NaN), at its centre
    // (pixel (x, y) is cs_main at id (x, y)), and the depth left alone.
    for (w, h) in [(1, 1), (7, 5), (33, 64)] {
        let cam = TestCamera::new([0.0, 0.0, -1.0], deg(50.0), w, h);
        let mut target = RenderTarget::new(w, h);
        target.clear_color([f32::NAN; 4]);
        render_sky(&mut target, &cam.uniforms(w, h, [0.0; 3]), &sky_at(0.5, 0.0, 3.0).uniforms());
        assert!(target.color.iter().all(|p| p.iter().all(|c| c.is_finite())), "{w}x{h}");
        assert!(target.depth.iter().all(|&d| d == 1.0), "the sky writes no depth");
        let t = ocean_cpu::shaders::sky::technique(ocean_core::plan::Sky::Preetham);
        let lut: ocean_core::atmosphere::SkyLut = bytemuck::Zeroable::zeroed();
        let (camera, u) = (cam.uniforms(w, h, [0.0; 3]), sky_at(0.5, 0.0, 3.0).uniforms());
        let last = cs_main([w - 1, h - 1], &camera, &u, &lut, &t);
        assert_eq!(target.color.last().unwrap().map(f32::to_bits), last.map(f32::to_bits));
        // Negative control: the pixel before it is another ray.
        if w > 1 {
            let other = cs_main([w - 2, h - 1], &camera, &u, &lut, &t);
            assert_ne!(other.map(f32::to_bits), last.map(f32::to_bits), "{w}x{h}");
        }
    }
}

#[test]
fn frame_is_deterministic_and_ignores_the_eye_position() {
    let (w, h) = (96, 64);
    let cam = TestCamera::new([0.4, 0.2, -1.0], deg(70.0), w, h);
    let u = sky_at(deg(15.0), deg(-70.0), 4.0).uniforms();
    let render = |threads: usize, eye: [f64; 3]| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let mut target = RenderTarget::new(w, h);
        pool.install(|| render_sky(&mut target, &cam.uniforms(w, h, eye), &u));
        target.color
    };
    let a = render(1, [0.0; 3]);
    let same = |x: &[[f32; 4]], y: &[[f32; 4]]| {
        x.iter().flatten().zip(y.iter().flatten()).all(|(p, q)| p.to_bits() == q.to_bits())
    };
    assert!(same(&a, &render(4, [0.0; 3])), "thread count changed the frame");
    // Camera-relative: an eye 10⁶ m away renders the same sky.
    assert!(same(&a, &render(2, [1e6, 30.0, -2e6])), "the eye position changed the sky");
}
