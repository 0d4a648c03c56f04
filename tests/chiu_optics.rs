//! Shading `chiu` (seed 001 §3.5): its Fresnel is eq. 2 itself, and the water colour of eq. 8
//! is in the picture pixel by pixel.
//!
//! The picture test renders a mirror-calm sea over a sloping floor whose drawn square lies
//! behind the camera (so the refraction map is empty and every water pixel shows eq. 8's
//! colour through eq. 2), under a uniform sky S and a sun behind the camera (eq. 5's lobe is
//! then exactly 0 on the water). Each water pixel must be
//!   C = F·S + (1 − F)·L_down·(0.30, 0.73, 0.63)^(k_d·y),
//! with F eq. 2 at the pixel's view angle, y the floor's depth under the point the pixel's ray
//! meets, both computed here in f64 from the scene (ocean-core's `fresnel_exact` and
//! `Terrain::height`), and L_down the frame's downwelling light.

use glam::DVec3;
use ocean_core::camera::Camera;
use ocean_core::fresnel::fresnel_exact;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::{Scene, SceneSource};
use ocean_cpu::frame::{FrameBuffers, render};
use ocean_cpu::raster::RenderTarget;
use ocean_cpu::shaders::shared::optics;

#[test]
fn the_shaders_fresnel_is_eq2() {
    // The f32 mirror of shared/fresnel.wgsl against ocean-core's f64 eq. 2. Backward stability
    // is the criterion: the f32 result must be eq. 2 at arguments within 4 ulp of the given
    // ones, to 8 ulp (near the critical angle eq. 2 is so steep that a forward bound would
    // have to be huge there, and elsewhere it would be loose).
    let eps = f64::from(f32::EPSILON) / 2.0;
    let misses = |perturb: f64| {
        let (mut misses, mut worst) = (0, 0.0f64);
        for eta in [1.333f32, 1.0 / 1.333, 1.0001, 0.9999, 1.5, 2.5, 1.0, 0.5] {
            for i in 0..=4000 {
                let c = i as f32 / 4000.0;
                let got = f64::from(optics::fresnel_exact(c, eta));
                assert!(got.is_finite() && (0.0..=1.0).contains(&got), "η {eta} c {c}: {got}");
                let (c, e) = (f64::from(c), f64::from(eta) + perturb);
                let (mut lo, mut hi) = (f64::MAX, f64::MIN);
                for dc in [-4.0, 0.0, 4.0] {
                    for de in [-4.0, 0.0, 4.0] {
                        let f =
                            fresnel_exact((c * (1.0 + dc * eps)).min(1.0), e * (1.0 + de * eps));
                        (lo, hi) = (lo.min(f), hi.max(f));
                    }
                }
                let want = fresnel_exact(c, e);
                worst = worst.max((got - want).abs() / want.max(1e-3));
                if got < lo * (1.0 - 8.0 * eps) || got > hi * (1.0 + 8.0 * eps) {
                    misses += 1;
                }
            }
        }
        (misses, worst)
    };
    let (m, w) = misses(0.0);
    println!("shared/fresnel.wgsl fresnel_exact vs eq. 2 (f64): {m} misses, worst forward {w:.2e}");
    assert_eq!(m, 0);
    // Negative control: η off by 1e-3 is caught.
    let (m, _) = misses(1e-3);
    assert!(m > 20_000, "{m}");
}

/// The scene: mirror-calm sea, floor rising towards +z, its square (1 m) behind the camera.
fn calm_over_slope() -> Scene {
    let text = "[techniques]\nshading = \"chiu\"\nsurface = \"projected_grid\"\nfar_field = \"none\"\n\
        [ocean]\nwind_speed = 0.0\n\
        [camera]\nposition = [0.0, 8.0, 0.0]\nlook_at = [0.0, 0.0, -40.0]\nfov_y_deg = 60.0\n\
        width = 160\nheight = 90\n\
        [sun]\ndirection = [0.0, 0.3, 1.0]\nintensity = 3.0\n\
        [terrain]\ndepth_m = -5.0\ncenter = [0.0, 200.0]\nslope = 0.05\n\
        slope_direction_deg = 90.0\nextent_m = 1.0\n\
        [chiu]\nkd_per_m = 0.3\n";
    Scene::from_toml(text, SceneSource::Text).expect("valid scene")
}

const SKY: f32 = 0.8;

fn render_chiu(scene: &Scene) -> FrameBuffers {
    let plan = FramePlan::new(scene, OutputKind::Hdr);
    assert!(!plan.runs(ocean_core::plan::Pass::RefractionMap), "the floor must be out of view");
    let sky = |_: [f32; 3]| [SKY; 3];
    let mesh = |c: &Camera| {
        plan.water_mesh(scene, c).map(Into::into).map_err(ocean_cpu::frame::Error::Core)
    };
    render(scene, &plan, &sky, &|_: &mut RenderTarget| {}, &mesh, &mut |_| {}).expect("render")
}

/// Pixels checked, and those outside the expected range (see the module doc) when the
/// expected colour uses eq. 8 with `kd` and the floor's depth plus `extra_depth`.
fn eq8_misses(scene: &Scene, frame: &FrameBuffers, kd: f64, extra_depth: f64) -> (usize, usize) {
    let camera = Camera::from_scene(&scene.camera).expect("camera");
    let terrain = scene.terrain.as_ref().expect("terrain");
    let u = &frame.uniforms;
    let sun = DVec3::from_array(u.sun.direction.map(f64::from));
    let down = DVec3::from_array(u.sun.radiance.map(f64::from))
        * (sun.y.max(0.0) / std::f64::consts::PI)
        + DVec3::from_array(u.ambient.sky.map(f64::from));
    let expected = |ndc_x: f64, ndc_y: f64| {
        let d = camera.ray_direction(ndc_x, ndc_y);
        let p = camera.eye + d * (-camera.eye.y / d.y);
        let f = fresnel_exact(-d.y, scene.water.ior);
        let y = (-terrain.height(p.x, p.z)).max(0.0) + extra_depth;
        let t = DVec3::new(0.30f64.powf(kd * y), 0.73f64.powf(kd * y), 0.63f64.powf(kd * y));
        DVec3::splat(f * f64::from(SKY)) + down * t * (1.0 - f)
    };
    let (w, h) = (camera.width, camera.height);
    let (mut checked, mut misses) = (0, 0);
    for py in 0..h {
        for px in 0..w {
            let (ndc_x, ndc_y) = ocean_core::camera::pixel_centre_ndc(px, py, w, h);
            if camera.ray_direction(ndc_x, ndc_y).y > -0.05 {
                continue;
            }
            // The rasterizer snaps vertices to 1/256 pixel: the point shaded at a pixel centre
            // is that of a ray up to √2/512 pixel away (twice that as a margin); the expected
            // colour is the range over those rays, plus f32 rounding.
            let e = 2.0 * 2f64.sqrt() / 512.0;
            let (ex, ey) = (2.0 * e / w as f64, 2.0 * e / h as f64);
            let (mut lo, mut hi) = (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN));
            for ox in [-ex, 0.0, ex] {
                for oy in [-ey, 0.0, ey] {
                    let c = expected(ndc_x + ox, ndc_y + oy);
                    (lo, hi) = (lo.min(c), hi.max(c));
                }
            }
            let got = frame.hdr.pixel(px, py);
            let got = DVec3::new(f64::from(got[0]), f64::from(got[1]), f64::from(got[2]));
            let slack = hi.abs() * 2e-5 + DVec3::splat(1e-7);
            checked += 1;
            if got.cmplt(lo - slack).any() || got.cmpgt(hi + slack).any() {
                misses += 1;
            }
        }
    }
    (checked, misses)
}

#[test]
fn eq8_water_colour_is_in_the_picture_per_pixel() {
    let scene = calm_over_slope();
    let frame = render_chiu(&scene);
    let (checked, misses) = eq8_misses(&scene, &frame, 0.3, 0.0);
    println!("eq. 8 over a sloping floor: {checked} water pixels, {misses} off the formula");
    assert!(checked > 5000, "the view must show the sea: {checked}");
    assert_eq!(misses, 0);
    // Negative controls: 0.2 m more depth, or k_d 5 % off, moves most pixels off.
    let (_, deeper) = eq8_misses(&scene, &frame, 0.3, 0.2);
    let (_, kd_off) = eq8_misses(&scene, &frame, 0.315, 0.0);
    println!("  negative controls: {deeper} (y + 0.2 m), {kd_off} (k_d × 1.05) pixels off");
    assert!(deeper > checked / 2 && kd_off > checked / 2, "{deeper} {kd_off}");
}

/// The sea's height at world (x, z): the displacement map's height channel, bilinear between
/// its samples at (i, j)·L/N (f64, from the map's texels).
fn wave_height(map: &ocean_cpu::sampler::Texture2D, patch: f64, x: f64, z: f64) -> f64 {
    let n = f64::from(map.width);
    let (u, v) = (x / patch * n, z / patch * n);
    let (i, j) = (u.floor(), v.floor());
    let (fu, fv) = (u - i, v - j);
    let at = |di: f64, dj: f64| {
        let w = map.width as i64;
        let (a, b) = (((i + di) as i64).rem_euclid(w), ((j + dj) as i64).rem_euclid(w));
        f64::from(map.texel(a as u32, b as u32)[1])
    };
    let top = at(0.0, 0.0) * (1.0 - fu) + at(1.0, 0.0) * fu;
    let bottom = at(0.0, 1.0) * (1.0 - fu) + at(1.0, 1.0) * fu;
    top * (1.0 - fv) + bottom * fv
}

/// A sphere of radius 2 centred on the sea plane in 10 m/s waves, its reflection map read
/// back: (pixels where the mirrored ray meets the sphere, covered pixels whose sphere point is
/// below the wave by more than 2 cm, uncovered ones above it by more than 2 cm).
fn clipped_reflection(shading: &str) -> (usize, usize, usize) {
    let text = format!(
        "[techniques]\nshading = \"{shading}\"\nsurface = \"projected_grid\"\nfar_field = \"none\"\n\
         [ocean]\nwind_speed = 10.0\npatch_size_m = 64.0\nresolution = 128\nbump_resolution = 128\n\
         time_s = 3.0\n\
         [camera]\nposition = [0.0, 1.5, 9.0]\nlook_at = [0.0, -0.5, 0.0]\nfov_y_deg = 50.0\n\
         width = 160\nheight = 90\n\
         [sun]\ndirection = [0.3, 0.6, -1.0]\n\
         [[objects]]\nkind = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 2.0\n"
    );
    let scene = Scene::from_toml(&text, SceneSource::Text).expect("scene");
    let plan = FramePlan::new(&scene, OutputKind::Hdr);
    let fb = ocean_cpu::render::render_scene_with_plan(&scene, plan, &mut |_| {})
        .expect("render")
        .buffers;
    let camera = Camera::from_scene(&scene.camera).expect("camera");
    let map = &fb.reflection_map;
    let (w, h) = (map.width, map.height);
    let (r, c) = (2.0f64, DVec3::ZERO);
    let eps = 0.02;
    let (mut hits, mut under, mut missing) = (0, 0, 0);
    for py in 0..h {
        for px in 0..w {
            let ndc = ocean_core::camera::pixel_centre_ndc(px, py, w, h);
            let d = camera.ray_direction(ndc.0, ndc.1);
            // The map draws the sphere mirrored in y = 0: meet the mirrored sphere.
            let mc = DVec3::new(c.x, -c.y, c.z);
            let oc = camera.eye - mc;
            let b = oc.dot(d);
            let disc = b * b - (oc.length_squared() - r * r);
            if disc < 0.0 {
                continue;
            }
            // Near the silhouette the tessellated sphere and the true one part: skip the rim.
            if disc < 0.05 * r * r {
                continue;
            }
            hits += 1;
            // The front and the back of the sphere along the ray (with the front clipped away,
            // the back shows): each point's height over the wave under it.
            let over = [-1.0, 1.0].map(|s| {
                let m = camera.eye + d * (-b + s * disc.sqrt());
                let sea = wave_height(&fb.displacement, scene.ocean.patch_size_m, m.x, m.z);
                -m.y - sea
            });
            let covered = map.texel(px, py)[3] > 0.0;
            under += usize::from(covered && over.iter().all(|&o| o < -eps));
            missing += usize::from(!covered && over.iter().any(|&o| o > eps));
        }
    }
    (hits, under, missing)
}

#[test]
fn the_reflection_map_clips_a_sphere_at_the_wave_height() {
    let (hits, under, missing) = clipped_reflection("chiu");
    println!(
        "sphere in waves, shading chiu: {hits} pixels on it in the reflection map, {under} \
         shown under the wave, {missing} above it left out"
    );
    assert!(hits > 500, "{hits}");
    assert_eq!((under, missing), (0, 0));
    // Negative control: clipped at y = 0 (shading hu), the map shows the sphere under crests
    // and leaves it out above troughs.
    let (_, under, missing) = clipped_reflection("hu");
    println!(
        "  clipped at y = 0 (shading hu): {under} under the wave, {missing} above it left out"
    );
    assert!(under + missing > 50, "{under} {missing}");
}
