//! Foam `heuristic` (seed 002: foam "on the crests of waves") measured in the rendered
//! picture: the pixels the foam covers are found by rendering the frame twice, with and
//! without foam (`[foam] coverage = 0` leaves the water's colour untouched bit for bit), and
//! each one's surface point is found independently of the renderer, by marching the pixel's
//! camera ray against ocean-core's f64 height query of the same sea. At least
//! [`MIN_ON_CREST`] of the foam pixels must lie where the surface is above its mean height
//! and compressed (J < 1), on the built-in `welch` scene, `welch_stormy_sunset` and `foam_gerstner` (its foam
//! switched to `heuristic`; `welch_calm_day` shows too little foam to measure); the foam
//! must show (at least [`MIN_FOAM_PIXELS`] pixels) and must not be a sheet (at most
//! [`MAX_FOAM_SHARE`] of the water). Negative controls, on a sample of the water whose
//! surface points are marched the same way: as many pixels as the foam covers, but taken
//! evenly over the water, fail the crest share (so the crest measure tells crests from
//! anywhere); and the formula this replaced, evaluated at the sampled surface points, fails
//! the share (so the measure tells a sheet from crest foam — the crest share alone cannot: a
//! Gerstner swell's upper half is compressed, J < 1, so the old sheet was "on a crest" too).

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use glam::DVec3;
use ocean_core::camera::{Camera, pixel_centre_ndc};
use ocean_core::plan::{FramePlan, OutputKind, Stage, System};
use ocean_core::scene::{Scene, SceneSource};
use ocean_core::waves::WaveSurface;

/// Least share of the foam pixels on a crest (the figure).
const MIN_ON_CREST: f64 = 0.9;
/// Least number of foam pixels: a scene that shows no foam proves nothing.
const MIN_FOAM_PIXELS: usize = 20;
/// Most share of the pixels below the horizon the foam covers within 400 m: crest foam is
/// sparse. The formula this replaced, (h/crest_height)·(s/crest_slope) − 1, covered 22.0 %
/// of the built-in welch scene, 36.1 % of `welch_stormy_sunset` and 12.5 % of `foam_gerstner`
/// (measured by this test on 994c579: it fails there) — with 100 %, 99.5 % and 100 % of it
/// above the mean plane with J < 1, so the share is what tells a sheet on a swell's upper
/// flank from crest foam.
const MAX_FOAM_SHARE: f64 = 0.1;
/// A pixel is foam where the foam raises its radiance by more than this share (the foam's
/// albedo is about 0.8, so this is a coverage of a few percent).
const FOAM_RISE: f64 = 0.05;
/// Frame size: the measure needs no more, and the CPU renders it in well under a second.
const SIZE: (u32, u32) = (480, 270);

/// A reference scene, its foam technique set to `heuristic`.
fn reference(name: &str) -> Scene {
    let path = format!("{}/reference/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("foam = \"jacobian\"", "foam = \"heuristic\"");
    Scene::from_toml(&text, SceneSource::Text).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn hdr(scene: &Scene) -> Vec<[f32; 4]> {
    let r = ocean_cpu::render_scene(scene, OutputKind::Hdr, &mut |_| {}).unwrap();
    r.buffers.hdr.color.clone()
}

/// Where a pixel's ray meets the displaced surface: (height above the mean plane, J, the
/// heuristic's slope |∇h|/max(J, 0.1)) at the surface point, or `None` where the ray meets no
/// water within `far` m.
fn surface_at(
    surface: &WaveSurface,
    eye: DVec3,
    d: DVec3,
    bound: f64,
    far: f64,
) -> Option<(f64, f64, f64)> {
    if d.y >= 0.0 {
        return None;
    }
    // From where the ray enters the slab |y| ≤ bound, in steps that grow with the distance
    // (a crest several steps wide is not stepped over), then bisection.
    let above = |t: f64| {
        let p = eye + d * t;
        p.y - surface.height_at(p.x, p.z)
    };
    let mut t0 = ((eye.y - bound) / -d.y).max(0.0);
    if above(t0) <= 0.0 {
        return None; // the eye is under the surface
    }
    loop {
        let t1 = t0 + (0.05 + 0.004 * t0);
        if t1 > far {
            return None;
        }
        if above(t1) <= 0.0 {
            let (mut lo, mut hi) = (t0, t1);
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                if above(mid) > 0.0 { lo = mid } else { hi = mid }
            }
            let p = eye + d * hi;
            let s = surface.invert(p.x, p.z).sample;
            let slope = s.slope_x.hypot(s.slope_z) / s.jacobian.max(0.1);
            return Some((s.height, s.jacobian, slope));
        }
        t0 = t1;
    }
}

/// Every [`CONTROL_STRIDE`]-th pixel below the horizon is marched for the negative controls
/// (every foam pixel is): the march is the test's cost.
const CONTROL_STRIDE: usize = 7;

/// The pixels below the horizon, and the marched ones.
struct Water {
    below_horizon: usize,
    /// Pixels of the every-[`CONTROL_STRIDE`]-th sample (marched, whether or not they hit
    /// water within 400 m).
    sampled: usize,
    marched: Vec<WaterPixel>,
}

/// A pixel of the water: whether the foam covers it, and the surface there.
struct WaterPixel {
    foam: bool,
    /// Whether the pixel is one of the every-[`CONTROL_STRIDE`]-th sample.
    sampled: bool,
    height: f64,
    jacobian: f64,
    /// The old formula's turbulence, (max(h, 0)/crest_height)·(slope/crest_slope) − 1, here.
    old_turbulence: f64,
}

/// The water of `scene` at [`SIZE`].
fn water_pixels(mut scene: Scene) -> Water {
    (scene.camera.width, scene.camera.height) = SIZE;
    let with = hdr(&scene);
    let mut bare = scene.clone();
    bare.foam.coverage = 0.0;
    let without = hdr(&bare);
    let plan = FramePlan::new(&scene, OutputKind::Hdr);
    let t = scene.ocean.time_s;
    let surface = ocean_core::frame::surface_query(&scene, &plan, t).unwrap();
    let bound = match &surface {
        WaveSurface::Gerstner(sea) => sea.bounds().0,
        _ => panic!("the measure marches Gerstner seas (the direct FFT sum is too slow)"),
    };
    let camera = Camera::from_scene(&scene.camera).unwrap();
    let far = 400.0;
    let mut water = Water { below_horizon: 0, sampled: 0, marched: Vec::new() };
    let (crest_h, crest_s) = (scene.foam.crest_height_m, scene.foam.crest_slope);
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let i = (y * SIZE.0 + x) as usize;
            let (nx, ny) = pixel_centre_ndc(x, y, SIZE.0, SIZE.1);
            let d = camera.ray_direction(nx, ny);
            if d.y >= 0.0 {
                continue;
            }
            water.below_horizon += 1;
            let sum = |c: [f32; 4]| f64::from(c[0]) + f64::from(c[1]) + f64::from(c[2]);
            let foam = sum(with[i]) > sum(without[i]) * (1.0 + FOAM_RISE) + 1e-6;
            let sampled = water.below_horizon.is_multiple_of(CONTROL_STRIDE);
            water.sampled += usize::from(sampled);
            if !foam && !sampled {
                continue;
            }
            if let Some((height, jacobian, slope)) = surface_at(&surface, camera.eye, d, bound, far)
            {
                let old_turbulence = (height.max(0.0) / crest_h) * (slope / crest_s) - 1.0;
                water.marched.push(WaterPixel { foam, sampled, height, jacobian, old_turbulence });
            }
        }
    }
    water
}

/// The share of `pixels` on a crest (above the mean plane and compressed).
fn on_crest(pixels: &[&WaterPixel]) -> f64 {
    let crest = pixels.iter().filter(|p| p.height > 0.0 && p.jacobian < 1.0).count();
    crest as f64 / pixels.len().max(1) as f64
}

/// The measure: Err with the figures when the foam is not on the crests. `share` is the foam's
/// share of the pixels below the horizon (of the sample's, for a control on the sample).
fn check(name: &str, share: f64, foam: &[&WaterPixel]) -> Result<String, String> {
    let crest = on_crest(foam);
    let line = format!(
        "{name}: foam on {} pixels ({:.2} % of those below the horizon) within 400 m, {:.1} % \
         of them on a crest",
        foam.len(),
        100.0 * share,
        100.0 * crest
    );
    if foam.len() < MIN_FOAM_PIXELS || share > MAX_FOAM_SHARE || crest < MIN_ON_CREST {
        Err(line)
    } else {
        Ok(line)
    }
}

#[test]
fn heuristic_foam_lies_on_the_crests() {
    let scenes = [
        ("built-in welch", Scene::builtin().with_system(System::Welch).unwrap()),
        // The choppy Gerstner sea that foam `jacobian` whitens, under `heuristic` (its
        // `softness`, set for `jacobian`'s threshold, back at the default).
        ("foam_gerstner (heuristic)", {
            let mut s = reference("foam_gerstner");
            s.foam.softness = ocean_core::scene::Foam::default().softness;
            s
        }),
        ("welch_stormy_sunset", reference("welch_stormy_sunset")),
    ];
    let mut failures = Vec::new();
    for (name, scene) in scenes {
        let plan = FramePlan::new(&scene, OutputKind::Hdr);
        assert_eq!(plan.techniques.of(Stage::Foam).name, "heuristic", "{name}");
        let water = water_pixels(scene);
        let foam: Vec<_> = water.marched.iter().filter(|p| p.foam).collect();
        let share = foam.len() as f64 / water.below_horizon.max(1) as f64;
        match check(name, share, &foam) {
            Ok(line) => println!("{line}"),
            Err(line) => failures.push(line),
        }
        // Negative controls on the sample. As much "foam" spread evenly over the water (every
        // k-th sampled pixel): it must fail on the crest share.
        let sample: Vec<_> = water.marched.iter().filter(|p| p.sampled).collect();
        let k = (sample.len() / foam.len().max(MIN_FOAM_PIXELS)).max(1);
        let even: Vec<_> = sample.iter().copied().step_by(k).collect();
        let even_share = even.len() as f64 / water.sampled.max(1) as f64;
        let spread = check("  control, spread evenly", even_share, &even);
        println!("{}", spread.as_ref().unwrap_or_else(|e| e));
        assert!(on_crest(&even) < MIN_ON_CREST, "{name}: foam anywhere passed: {spread:?}");
        // The old formula at the sampled points (the noise at its mean: foam where t > 0.3).
        let old: Vec<_> = sample.iter().copied().filter(|p| p.old_turbulence > 0.3).collect();
        let old_share = old.len() as f64 / water.sampled.max(1) as f64;
        let old_check = check("  control, the old formula", old_share, &old);
        println!("{}", old_check.as_ref().unwrap_or_else(|e| e));
        assert!(old_check.is_err(), "{name}: the old formula passed: {old_check:?}");
    }
    assert!(failures.is_empty(), "foam off the crests:\n{}", failures.join("\n"));
}
