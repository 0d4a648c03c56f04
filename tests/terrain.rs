//! The sea floor (`[terrain]`): heightmaps read from 16-bit PNG and EXR files to the stated
//! heights, bad files reported with the key and line, the floor shadowed under the water by
//! the casters above it (through the refracted sun) and by its own relief, each against an
//! independent f64 evaluation here.

use std::path::Path;

use glam::DVec3;
use ocean_core::camera::Camera;
use ocean_core::plan::{OutputKind, Pass};
use ocean_core::scene::{Scene, SceneError, SceneSource};
use ocean_cpu::shaders::shared::floor;
use ocean_cpu::shaders::wgsl::vec3;

/// Writes a 16-bit grayscale PNG of `w × h` samples (row-major, row 0 first).
fn write_png16(path: &Path, w: u32, h: u32, samples: &[u16]) {
    let img = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(w, h, samples.to_vec())
        .expect("sample count");
    img.save(path).expect("write PNG");
}

/// Writes a single-channel (`Y`) f32 EXR.
fn write_exr(path: &Path, w: usize, h: usize, samples: Vec<f32>) {
    use exr::prelude::*;
    let list = vec![AnyChannel::new("Y", FlatSamples::F32(samples))];
    let channels = AnyChannels::sort(list.into());
    let layer = Layer::new((w, h), LayerAttributes::named("h"), Encoding::SMALL_LOSSLESS, channels);
    Image::from_layer(layer).write().to_file(path).expect("write EXR");
}

fn heightmap_scene(file: &Path, extra: &str) -> Result<Scene, SceneError> {
    let text = format!(
        "[terrain]\nkind = \"heightmap\"\nheightmap = {:?}\nheight_range_m = [-2.0, 6.0]\n\
         depth_m = 10.0\ncenter = [5.0, -7.0]\nextent_m = 30.0\n{extra}",
        file.to_str().expect("utf-8 path")
    );
    Scene::from_toml(&text, SceneSource::Text)
}

/// Texel centre (i, j) of a map of side n over the square: x₀ + i·extent/(n − 1).
fn texel_xz(i: u32, j: u32, n: u32) -> (f64, f64) {
    let step = 30.0 / f64::from(n - 1);
    (5.0 - 15.0 + f64::from(i) * step, -7.0 - 15.0 + f64::from(j) * step)
}

#[test]
fn heightmaps_load_to_the_stated_heights_from_png_and_exr() {
    let dir = tempfile::tempdir().expect("tempdir");
    let n = 5u32;
    let samples: Vec<u16> = (0..n * n).map(|k| (k * 2731 % 65536) as u16).collect();
    let png = dir.path().join("relief.png");
    write_png16(&png, n, n, &samples);
    let exr = dir.path().join("relief.exr");
    write_exr(
        &exr,
        n as usize,
        n as usize,
        samples.iter().map(|&s| f32::from(s) / 65535.0).collect(),
    );
    for file in [&png, &exr] {
        let scene = heightmap_scene(file, "").expect("valid heightmap scene");
        let t = scene.terrain.as_ref().expect("terrain");
        assert!(t.relief().is_some(), "{}: relief loaded", file.display());
        // At texel centres: the plane (−10 m) plus −2 + 8·v, v = sample/65535, to f32.
        for j in 0..n {
            for i in 0..n {
                let v = f64::from(samples[(j * n + i) as usize]) / 65535.0;
                let want = -10.0 + f64::from((-2.0 + 8.0 * v) as f32);
                let (x, z) = texel_xz(i, j, n);
                let got = t.height(x, z);
                assert!(
                    (got - want).abs() < 1e-5,
                    "{} ({i}, {j}): {got} vs {want}",
                    file.display()
                );
            }
        }
        // Halfway between texels (1, 2) and (2, 2): their mean; beyond the square: the edge.
        let (a, b) = (
            t.height(texel_xz(1, 2, n).0, texel_xz(1, 2, n).1),
            t.height(texel_xz(2, 2, n).0, texel_xz(2, 2, n).1),
        );
        let mid = texel_xz(1, 2, n);
        let got = t.height(mid.0 + 0.5 * 30.0 / f64::from(n - 1), mid.1);
        assert!((got - 0.5 * (a + b)).abs() < 1e-9, "bilinear: {got} vs {}", 0.5 * (a + b));
        let corner = texel_xz(0, 0, n);
        assert_eq!(t.height(corner.0 - 50.0, corner.1 - 50.0), t.height(corner.0, corner.1));
        // The range the plan and the mesh use.
        let (lo, hi) = t.y_range();
        let vmin = f64::from(*samples.iter().min().unwrap()) / 65535.0;
        let vmax = f64::from(*samples.iter().max().unwrap()) / 65535.0;
        assert!(
            (lo - (-12.0 + 8.0 * vmin)).abs() < 1e-5 && (hi - (-12.0 + 8.0 * vmax)).abs() < 1e-5
        );
        assert_eq!(t.mesh_triangles(), 2 * u64::from((n - 1) * (n - 1)));
    }
}

#[test]
fn bad_heightmaps_are_reported_with_the_key_and_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let eight = dir.path().join("eight.png");
    image::GrayImage::from_raw(2, 2, vec![0, 64, 128, 255])
        .expect("size")
        .save(&eight)
        .expect("png");
    let missing = dir.path().join("missing.png");
    let text_file = dir.path().join("relief.txt");
    std::fs::write(&text_file, "not an image").expect("write");
    let expect = |r: Result<Scene, SceneError>, key: &str, needle: &str| match r {
        Err(SceneError::Invalid { key: Some(k), line, message, .. }) => {
            assert_eq!(k, key, "{message}");
            assert!(line > 0, "the line of `{key}` is named");
            assert!(message.contains(needle), "{message:?} should mention {needle:?}");
        }
        other => panic!("expected an error about {key}, got {other:?}"),
    };
    expect(heightmap_scene(&eight, ""), "terrain.heightmap", "16-bit");
    expect(heightmap_scene(&missing, ""), "terrain.heightmap", "missing.png");
    expect(heightmap_scene(&text_file, ""), "terrain.heightmap", ".exr");
    let no_file = Scene::from_toml("[terrain]\nkind = \"heightmap\"\n", SceneSource::Text);
    expect(no_file, "terrain.kind", "needs `heightmap");
    let plane_with_file =
        Scene::from_toml("[terrain]\nkind = \"plane\"\nheightmap = \"a.png\"\n", SceneSource::Text);
    expect(plane_with_file, "terrain.heightmap", "plane");
    // A relative path is read against the scene file's folder.
    write_png16(&dir.path().join("ok.png"), 2, 2, &[0, 1, 2, 3]);
    let scene_file = dir.path().join("s.toml");
    std::fs::write(&scene_file, "[terrain]\nkind = \"heightmap\"\nheightmap = \"ok.png\"\n")
        .expect("write");
    let s = Scene::load(&scene_file).expect("relative heightmap path");
    assert!(s.terrain.unwrap().relief().is_some());
}

// ---------------------------------------------------------------------------------------------
// Shadows under the water

/// The sun's direction refracted into the water (unit, towards the sun), by Snell in f64.
fn refracted(sun: DVec3, eta: f64) -> DVec3 {
    let (x, z) = (sun.x / eta, sun.z / eta);
    DVec3::new(x, (1.0 - x * x - z * z).sqrt(), z)
}

/// Whether the ray from `p` along `d` meets the box of centre `c` and half-size `h`.
fn hits_box(p: DVec3, d: DVec3, c: DVec3, h: DVec3) -> bool {
    let (mut t0, mut t1) = (0.0f64, f64::MAX);
    for a in 0..3 {
        let (o, v, lo, hi) = (p[a], d[a], c[a] - h[a], c[a] + h[a]);
        if v.abs() < 1e-12 {
            if o < lo || o > hi {
                return false;
            }
            continue;
        }
        let (ta, tb) = ((lo - o) / v, (hi - o) / v);
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    t0 <= t1
}

const ROCK_CENTER: [f64; 3] = [0.0, 3.0, -6.0];
const ROCK_HALF: f64 = 1.5;
const FLOOR_DEPTH_M: f64 = 6.0;

fn under_water_view(with_rock: bool) -> Scene {
    let rock = if with_rock {
        format!("[[objects]]\nkind = \"box\"\ncenter = {ROCK_CENTER:?}\nsize = [3.0, 3.0, 3.0]\n")
    } else {
        String::new()
    };
    let text = format!(
        "[ocean]\nwind_speed = 0.0\n\
         [camera]\nposition = [0.0, -1.0, 10.0]\nlook_at = [0.0, -6.0, -8.0]\nfov_y_deg = 70.0\n\
         width = 160\nheight = 90\n\
         [sun]\ndirection = [0.3, 0.6, -1.0]\nintensity = 3.0\n\
         [terrain]\ndepth_m = {FLOOR_DEPTH_M}\nextent_m = 200.0\n{rock}"
    );
    Scene::from_toml(&text, SceneSource::Text).expect("valid scene")
}

/// Floor pixels of the view compared with the shadow expected here: (checked, shadowed as
/// expected, disagreeing). `sun_under` is the direction the expectation follows under the
/// water (towards the sun); pixels within `margin` m of the shadow's edge are left out.
fn rock_shadow_agreement(sun_under: DVec3, margin: f64) -> (usize, usize, usize) {
    let lit = ocean_cpu::render_scene(&under_water_view(false), OutputKind::Hdr, &mut |_| {})
        .expect("render");
    let scene = under_water_view(true);
    let shadowed = ocean_cpu::render_scene(&scene, OutputKind::Hdr, &mut |_| {}).expect("render");
    assert!(shadowed.plan.runs(Pass::ShadowMap), "the rock above the water casts");
    let camera = Camera::from_scene(&scene.camera).expect("camera");
    let sun = DVec3::new(0.3, 0.6, -1.0).normalize();
    let centre = DVec3::from_array(ROCK_CENTER);
    let in_shadow = |p: DVec3, grow: f64| {
        let surface = p + sun_under * (-p.y / sun_under.y);
        hits_box(surface, sun, centre, DVec3::splat(ROCK_HALF + grow))
    };
    let (w, h) = (camera.width, camera.height);
    let (mut checked, mut dark, mut wrong) = (0, 0, 0);
    for py in 0..h {
        for px in 0..w {
            let ndc = ocean_core::camera::pixel_centre_ndc(px, py, w, h);
            let d = camera.ray_direction(ndc.0, ndc.1);
            if d.y > -0.1 {
                continue;
            }
            let p = camera.eye + d * ((-FLOOR_DEPTH_M - camera.eye.y) / d.y);
            let (outer, inner) = (in_shadow(p, margin), in_shadow(p, -margin));
            if outer != inner {
                continue;
            }
            let (a, b) = (shadowed.buffers.hdr.pixel(px, py)[1], lit.buffers.hdr.pixel(px, py)[1]);
            let got = a < 0.9 * b;
            checked += 1;
            dark += usize::from(got && inner);
            wrong += usize::from(got != inner);
        }
    }
    (checked, dark, wrong)
}

#[test]
fn a_rock_above_the_water_shadows_the_floor_through_the_refracted_sun() {
    let sun = DVec3::new(0.3, 0.6, -1.0).normalize();
    let (checked, dark, wrong) = rock_shadow_agreement(refracted(sun, 1.333), 0.15);
    println!("rock shadow on the floor: {checked} floor pixels, {dark} in shadow, {wrong} off");
    assert!(checked > 5000, "the view must show the floor: {checked}");
    assert!(dark > 200, "the shadow must be in view: {dark}");
    assert_eq!(wrong, 0);
    // Negative control: the shadow expected along the unrefracted sun lies elsewhere.
    let (_, _, straight) = rock_shadow_agreement(sun, 0.15);
    println!("  negative control (sun not refracted): {straight} pixels off");
    assert!(straight > dark / 4, "{straight}");
}

/// A ridge along z through x = 0 on a 64² relief over 64 m, 3 m high, Gaussian across
/// (σ = 0.85 m: steeper than the steepest sun under the water, 41° above the horizon).
fn ridge_scene(dir: &Path) -> Scene {
    let n = 64u32;
    let samples: Vec<u16> = (0..n * n)
        .map(|k| {
            let x = -32.0 + f64::from(k % n) * 64.0 / f64::from(n - 1);
            (65535.0 * (-(x / 1.2).powi(2)).exp()).round() as u16
        })
        .collect();
    let file = dir.join("ridge.png");
    write_png16(&file, n, n, &samples);
    let text = format!(
        "[ocean]\nwind_speed = 0.0\n\
         [camera]\nposition = [0.0, 10.0, 40.0]\nlook_at = [0.0, -5.0, 0.0]\nwidth = 32\nheight = 18\n\
         [sun]\ndirection = [1.0, 0.2, 0.3]\n\
         [terrain]\nkind = \"heightmap\"\nheightmap = {:?}\nheight_range_m = [0.0, 3.0]\n\
         depth_m = 8.0\nextent_m = 64.0\n",
        file.to_str().expect("utf-8")
    );
    Scene::from_toml(&text, SceneSource::Text).expect("valid scene")
}

/// The ridge's oracle frame: the scene (its heightmap in a folder kept while it lives), the
/// rendered frame (its uniforms and relief map) and the eye.
struct Ridge {
    _dir: tempfile::TempDir,
    scene: Scene,
    frame: ocean_cpu::Rendered,
    eye: DVec3,
}

impl Ridge {
    fn new() -> Self {
        let dir = tempfile::tempdir().expect("tempdir");
        let scene = ridge_scene(dir.path());
        let frame = ocean_cpu::render_scene(&scene, OutputKind::Hdr, &mut |_| {}).expect("render");
        let eye = Camera::from_scene(&scene.camera).expect("camera").eye;
        Self { _dir: dir, scene, frame, eye }
    }

    fn terrain(&self) -> &ocean_core::terrain::Terrain {
        self.scene.terrain.as_ref().expect("terrain")
    }
}

#[test]
fn the_relief_shadows_itself_as_an_independent_march_finds() {
    let ridge = Ridge::new();
    let (r, t, eye) = (&ridge.frame, ridge.terrain(), ridge.eye);
    let (u, map) = (&r.buffers.uniforms, &r.buffers.floor_map);
    let sun = DVec3::new(1.0, 0.2, 0.3).normalize();
    let texel = 64.0 / 63.0;
    let top = t.y_range().1;
    // Shadowed when the floor rises above the ray towards the sun (half a texel on, as the
    // shader starts) by more than the bias; `None` within 4 cm of that call.
    let expected = |p: DVec3, dir: DVec3| -> Option<bool> {
        let across = (dir.x * dir.x + dir.z * dir.z).sqrt();
        let mut clearance = f64::MAX;
        let mut s = 0.5 * texel / across;
        while s <= 48.0 * texel / across {
            let q = p + dir * s;
            if q.y > top {
                break;
            }
            clearance =
                clearance.min(q.y + f64::from(floor::RELIEF_SHADOW_BIAS) - t.height(q.x, q.z));
            s += 0.02 * texel / across;
        }
        if clearance.abs() < 0.04 { None } else { Some(clearance < 0.0) }
    };
    let count = |dir: DVec3| {
        let (mut checked, mut dark, mut wrong) = (0, 0, 0);
        for j in 0..40 {
            for i in 0..40 {
                let (x, z) = (-6.0 + f64::from(i) * 0.2013, -20.0 + f64::from(j) * 1.007);
                let p = DVec3::new(x, t.height(x, z), z);
                let Some(want) = expected(p, dir) else { continue };
                let rel = p - eye;
                let got = floor::relief_sun(vec3(rel.x as f32, rel.y as f32, rel.z as f32), u, map)
                    == 0.0;
                checked += 1;
                dark += usize::from(want);
                wrong += usize::from(got != want);
            }
        }
        (checked, dark, wrong)
    };
    let (checked, dark, wrong) = count(refracted(sun, 1.333));
    println!("relief self-shadow: {checked} floor points, {dark} in shadow, {wrong} off");
    assert!(checked > 1200 && dark > 100, "{checked} {dark}");
    assert!(wrong * 200 <= checked, "{wrong} of {checked} disagree");
    // Negative control: the march along the unrefracted sun disagrees widely.
    let (_, _, straight) = count(sun);
    println!("  negative control (sun not refracted): {straight} off");
    assert!(straight > 4 * wrong.max(10), "{straight}");
    // The picture uses it: the plan draws the floor and the frame marks the relief.
    assert!(r.plan.runs(Pass::RefractionMap) && u.terrain.floor[3] == 1.0);
}

#[test]
fn the_relief_march_envelope_holds_every_conformant_march_and_decides_most_points() {
    use floor::ReliefMarch;
    use ocean_cpu::envelope::{Iv, Jitter, JitterRules};
    let ridge = Ridge::new();
    let (r, t, eye) = (&ridge.frame, ridge.terrain(), ridge.eye);
    let (u, map) = (&r.buffers.uniforms, &r.buffers.floor_map);
    // The same GPU marching towards a sun turned about the vertical: the negative control.
    let turn = |deg: f32| {
        let mut turned = *u;
        let [x, y, z, w] = u.terrain.sun_under;
        let (s, c) = deg.to_radians().sin_cos();
        turned.terrain.sun_under = [x * c - z * s, y, x * s + z * c, w];
        turned
    };
    let turned = [turn(10.0)];
    let mut controls = [0usize; 2];
    let (mut points, mut shadowed, mut undecided, mut outside) = (0, 0, 0, 0);
    // The independent test's points, four times as dense across the ridge (along x).
    for j in 0..40u32 {
        for i in 0..160u32 {
            let (x, z) = (-6.0 + f64::from(i) * 0.0503, -20.0 + f64::from(j) * 1.007);
            let rel = (DVec3::new(x, t.height(x, z), z) - eye).as_vec3().to_array();
            let env = Iv::relief_sun(rel.map(Iv::point), u, map);
            let exact = <f32 as ReliefMarch>::relief_sun(rel, u, map);
            assert!(env.contains(exact), "({x}, {z}): the oracle's {exact} outside {env:?}");
            for seed in 0..8 {
                Jitter::reseed(JitterRules { seed, scale: 1.0 }, u64::from(j * 160 + i));
                let g = Jitter::relief_sun(rel.map(Jitter), u, map).0;
                outside += usize::from(!env.contains(g));
            }
            for (k, f) in turned.iter().enumerate() {
                controls[k] +=
                    usize::from(!env.contains(<f32 as ReliefMarch>::relief_sun(rel, f, map)));
            }
            let lifted = [rel[0], rel[1] + 0.1, rel[2]];
            controls[1] +=
                usize::from(!env.contains(<f32 as ReliefMarch>::relief_sun(lifted, u, map)));
            points += 1;
            shadowed += usize::from(env.hi == 0.0);
            undecided += usize::from(env.lo < env.hi);
        }
    }
    println!(
        "relief march envelope: {points} points, {shadowed} certainly shadowed, {undecided} \
         either way; 8 random GPUs: {outside} outside; the sun turned 10°, the point 10 cm up: {controls:?} outside"
    );
    assert_eq!(outside, 0, "a conformant march left the envelope");
    // Carried step by step, the march is decided almost everywhere (the hull of 0 and 1 that
    // stood for it before decided nothing).
    assert!(shadowed > 100 && undecided * 20 <= points, "{shadowed} {undecided} of {points}");
    assert!(controls.iter().all(|&c| c > 0), "a march elsewhere stayed inside: {controls:?}");
}

// ---------------------------------------------------------------------------------------
// `kind = "island"` (issue 15): the profile, the relief made from it, and its validation.

/// The test island, with `extra` (`key = value` lines) replacing or adding keys.
fn island_scene(extra: &str) -> Result<Scene, SceneError> {
    let mut lines: Vec<String> = [
        "kind = \"island\"",
        "depth_m = 10.0",
        "center = [30.0, -20.0]",
        "extent_m = 420.0",
        "island_radius_m = 60.0",
        "island_height_m = 12.0",
        "shore_slope = 0.08",
    ]
    .map(String::from)
    .to_vec();
    for line in extra.lines() {
        let key = line.split('=').next().unwrap_or("").trim();
        lines.retain(|l| l.split('=').next().unwrap_or("").trim() != key);
        lines.push(line.to_owned());
    }
    Scene::from_toml(&format!("[terrain]\n{}\n", lines.join("\n")), SceneSource::Text)
}

/// The profile written here from its documented formula in f64, independently of the crate.
fn profile(r: f64) -> f64 {
    let (h, big_r, s, d) = (12.0, 60.0, 0.08, 10.0);
    if r <= big_r {
        let u: f64 = r / big_r;
        s * (big_r - r) + (h - s * big_r) * (1.0 - u * u).powi(2)
    } else {
        -(s * (r - big_r)).min(d)
    }
}

#[test]
fn the_island_has_its_top_waterline_shore_slope_and_floor() {
    use ocean_core::terrain::{island_height, island_reach};
    let scene = island_scene("").unwrap();
    let t = scene.terrain.as_ref().unwrap();
    // The top, the waterline and the floor beyond the shore's foot (R + d/s = 185 m).
    assert_eq!(island_height(t, 0.0), 12.0);
    assert_eq!(island_height(t, 60.0), 0.0);
    assert_eq!(island_reach(t), 185.0);
    assert_eq!(island_height(t, 185.0), -10.0);
    assert_eq!(island_height(t, 300.0), -10.0);
    // The slope is s on both sides of the waterline: central differences of step e = 1e-4 m
    // centred e from it see the slope there, which the hill's curvature y'' = 8(H − sR)/R²
    // = 0.016 /m moves by 1.6e-6 (0 on the straight shore); round-off adds ~1e-12/e.
    let e = 1e-4;
    for r in [60.0 - e, 60.0 + e] {
        let slope = (island_height(t, r + e) - island_height(t, r - e)) / (2.0 * e);
        assert!((slope + 0.08).abs() < 2e-6, "slope {slope} at {r}");
    }
    // Monotone from the top down to the floor (H ≥ s·R), and equal to the formula here.
    let mut last = f64::INFINITY;
    for i in 0..=4000 {
        let r = f64::from(i) * 0.05;
        let y = island_height(t, r);
        assert!(y <= last, "rises at {r}");
        assert!((y - profile(r)).abs() < 1e-12, "{r}: {y} against {}", profile(r));
        last = y;
    }
}

#[test]
fn the_drawn_relief_is_the_profile_within_the_bilinear_bound() {
    use ocean_core::terrain::{ISLAND_TEXEL_M, island_height};
    let scene = island_scene("").unwrap();
    let t = scene.terrain.as_ref().unwrap();
    let relief = t.relief().expect("made at load");
    let step = 420.0 / f64::from(relief.width - 1);
    assert!(step <= ISLAND_TEXEL_M + 1e-12 || relief.width == 1025, "{step}");
    // Bilinear interpolation of a C¹ function errs by at most step²/8 · (|y_xx| + |y_zz|);
    // the profile's second derivative is at most 4(H − sR)/R² · 3 on the hill (|d²/dr² of
    // (1 − u²)²| ≤ 12/R² at u = 1, 4/R² at the top) and 0 on the shore, except at the shore's
    // foot, where the slope breaks from s to 0 within one texel, and at the top's cone (slope
    // s on every side): there the bound is s·step/2 per axis.
    // Plus the relief's f32 heights (ulp of 22 m, 2e-6 m).
    let curvature = 12.0 * (12.0 - 0.08 * 60.0) / (60.0f64 * 60.0);
    let smooth = step * step / 8.0 * 2.0 * curvature + 4e-6;
    let kink = 0.08 * step / 2.0 * 2.0f64.sqrt() + 4e-6;
    let (mut worst_smooth, mut worst_kink) = (0.0f64, 0.0f64);
    let mut k = 0u64;
    for i in 0..20_000u64 {
        // A fixed quasi-random walk over the drawn square (Weyl sequence).
        k = k.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let (a, b) = ((i as f64 * 0.618_034) % 1.0, (k >> 11) as f64 / (1u64 << 53) as f64);
        let (x, z) = (30.0 + (a - 0.5) * 400.0, -20.0 + (b - 0.5) * 400.0);
        let r = (x - 30.0f64).hypot(z + 20.0);
        let err = (t.height(x, z) - island_height(t, r)).abs();
        if (r - 185.0).abs() < 2.0 * step || r < 2.0 * step {
            worst_kink = worst_kink.max(err);
        } else {
            worst_smooth = worst_smooth.max(err);
        }
    }
    println!(
        "island relief {}²: worst {worst_smooth:.2e} m (bound {smooth:.2e}), at the shore's foot {worst_kink:.2e} (bound {kink:.2e})",
        relief.width
    );
    assert!(worst_smooth <= smooth, "{worst_smooth} > {smooth}");
    assert!(worst_kink <= kink, "{worst_kink} > {kink}");
    // Negative control: a wider island is another floor.
    let wide = island_scene("island_radius_m = 70.0").unwrap();
    let w = wide.terrain.as_ref().unwrap();
    assert!((w.height(30.0 + 65.0, -20.0) - t.height(30.0 + 65.0, -20.0)).abs() > 0.3);
}

#[test]
fn islands_are_validated_with_the_key_and_the_reason() {
    let err = |extra: &str| island_scene(extra).unwrap_err().to_string();
    let e = err("extent_m = 300.0");
    assert!(e.contains("terrain.extent_m") && e.contains("370"), "{e}");
    let e = err("depth_m = -1.0");
    assert!(e.contains("terrain.depth_m"), "{e}");
    let e = err("shore_slope = 0.0");
    assert!(e.contains("terrain.shore_slope"), "{e}");
    let e = err("heightmap = \"x.png\"");
    assert!(e.contains("terrain.heightmap"), "{e}");
    let e = err("island_radius_m = nan");
    assert!(e.contains("terrain.island_radius_m"), "{e}");
    // The plan names the island.
    let scene = island_scene("").unwrap();
    let plan = ocean_core::plan::FramePlan::new(&scene, OutputKind::Ldr);
    let refraction = plan.passes.iter().find(|p| p.name == Pass::RefractionMap).unwrap();
    assert!(refraction.reason.contains("island 120 m across"), "{}", refraction.reason);
}

/// The floor's triangles are made from a world-space grid kept per floor (the coastal frame
/// drew its island's 257² vertices four times a frame); each must equal the vertex evaluated
/// directly from the floor — height, central-difference normal, wet-sand albedo, shifted by the
/// eye — bit for bit, for every eye, and a changed floor must not be served the old grid.
#[test]
fn the_kept_floor_grid_gives_the_directly_evaluated_vertices() {
    use ocean_core::terrain::{terrain_triangles, wet_sand_color};
    let scene = Scene::builtin_for(ocean_core::plan::System::Coastal);
    let mut t = scene.terrain.clone().expect("the coastal scene has an island");
    let direct = |t: &ocean_core::scene::Terrain, eye: DVec3, wet: f64, i: u32, j: u32| {
        let (qx, qz) = t.mesh_quads();
        let (sx, sz) = (t.extent_m / f64::from(qx), t.extent_m / f64::from(qz));
        let x = t.center[0] - 0.5 * t.extent_m + f64::from(i) * sx;
        let z = t.center[1] - 0.5 * t.extent_m + f64::from(j) * sz;
        let (hx, hz) = (0.5 * sx, 0.5 * sz);
        let dx = (t.height(x + hx, z) - t.height(x - hx, z)) / (2.0 * hx);
        let dz = (t.height(x, z + hz) - t.height(x, z - hz)) / (2.0 * hz);
        let n = DVec3::new(-dx, 1.0, -dz).normalize().as_vec3().to_array();
        let y = t.height(x, z);
        let c = wet_sand_color(t.color, y, wet).map(|v| v as f32);
        ((DVec3::new(x, y, z) - eye).as_vec3().to_array(), n, c)
    };
    let check = |t: &ocean_core::scene::Terrain, eye: DVec3, wet: f64| {
        let tris = terrain_triangles(t, eye, wet);
        let qx = t.mesh_quads().0;
        // Triangle 2k of row j starts at vertex (k, j); spot-check a spread of them.
        for (i, j) in [(0, 0), (qx / 2, 7), (qx - 1, qx / 3), (13, qx - 1)] {
            let v = tris[(2 * (j * qx + i)) as usize][0];
            let want = direct(t, eye, wet, i, j);
            assert_eq!((v.position, v.normal, v.color), want, "vertex ({i}, {j}) at eye {eye}");
        }
    };
    check(&t, DVec3::new(0.0, 8.0, 40.0), 1.2);
    check(&t, DVec3::new(-30.0, 2.5, 10.0), 1.2); // the same grid, another eye
    check(&t, DVec3::new(-30.0, 2.5, 10.0), 0.6); // another wet band
    t.color = [0.8, 0.6, 0.3]; // another floor: not the kept grid
    check(&t, DVec3::new(-30.0, 2.5, 10.0), 0.6);
    t.prepare(); // a new relief (same values, new identity)
    check(&t, DVec3::new(5.0, 1.0, -5.0), 0.6);
    // The camera-relative list is kept per floor and eye: the passes of a frame (and a still
    // camera's frames) get the very same list; another eye or another floor gets another.
    let eye = DVec3::new(5.0, 1.0, -5.0);
    // (The kept lists are the process's, shared with the tests running beside this one: a
    // pair of calls may see its entry pushed out between them, rarely; three tries.)
    let a = terrain_triangles(&t, eye, 0.6);
    let kept = (0..3).any(|_| {
        let first = terrain_triangles(&t, eye, 0.6);
        std::sync::Arc::ptr_eq(&first, &terrain_triangles(&t, eye, 0.6))
    });
    assert!(kept, "not kept");
    let moved = terrain_triangles(&t, eye + DVec3::X, 0.6);
    assert!(!std::sync::Arc::ptr_eq(&a, &moved), "another eye got the old list");
    assert_eq!(moved[0][0].position[0], a[0][0].position[0] - 1.0, "not shifted by the eye");
    t.color = [0.5, 0.5, 0.5];
    assert!(!std::sync::Arc::ptr_eq(&a, &terrain_triangles(&t, eye, 0.6)), "another floor");
}
