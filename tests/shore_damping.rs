//! `[terrain] wave_damping` (issue 15): waves `fft` and `gerstner` damped where the floor's
//! depth h is below r·λ, w = clamp(h/(r·λ), 0, 1) (r = 0.5: Crest's half a wavelength), so any
//! system can have a coast. The height query against the formula evaluated here, the shaders'
//! weight (the CPU mirror of `shared/floor.wgsl`, which the GPU cross-check holds to lavapipe)
//! against the same formula, and the sea kept off the sand.

use ocean_core::camera::Camera;
use ocean_core::frame::{FrameUniforms, ObjectPoses, damped_wavelengths, surface_query};
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::{Scene, SceneSource};
use ocean_core::waves::WaveSurface;
use ocean_cpu::sampler::Texture2D;
use ocean_cpu::shaders::shared::floor::shore_weight;

/// The island of reference/scenes/coastal_island.toml under `system` with `damping`.
fn island(system: &str, damping: f64) -> Scene {
    let text = format!(
        "system = \"{system}\"\n[ocean]\ntime_s = 3.0\nwind_speed = 4.0\n\
         [gerstner]\nmedian_amplitude_m = 0.6\nmedian_wavelength_m = 24.0\n\
         [camera]\nposition = [-45.0, 9.0, 125.0]\nlook_at = [0.0, 0.0, 45.0]\nwidth = 64\nheight = 36\n\
         [terrain]\nkind = \"island\"\ndepth_m = 10.0\nextent_m = 420.0\n\
         island_radius_m = 60.0\nisland_height_m = 12.0\nshore_slope = 0.08\nwave_damping = {damping}\n"
    );
    Scene::from_toml(&text, SceneSource::Text).expect("scene")
}

fn query(s: &Scene) -> WaveSurface {
    surface_query(s, &FramePlan::new(s, OutputKind::Hdr), s.ocean.time_s).expect("query")
}

#[test]
fn the_height_query_keeps_clamp_h_over_r_lambda_of_the_waves() {
    for system in ["hu", "welch"] {
        // r = 0.25: the FFT sea's peak (33 m here) kept whole beyond 8 m of water, inside the
        // island's 10 m floor.
        let r = 0.25;
        let s = island(system, r);
        let plan = FramePlan::new(&s, OutputKind::Hdr);
        let lambda = damped_wavelengths(&s, &plan).expect("fft/gerstner")[0];
        let t = s.terrain.as_ref().expect("terrain");
        let WaveSurface::Damped { inner, .. } = query(&s) else {
            panic!("{system}: a damped sea");
        };
        let (mut shallow, mut deep) = (0, 0);
        for i in 0..400 {
            let rad = 40.0 + i as f64 * 0.4;
            let a = i as f64 * 0.37;
            let (x, z) = (rad * a.cos(), rad * a.sin());
            let h = (-t.height(x, z)).max(0.0);
            let w = (h / (r * lambda)).clamp(0.0, 1.0);
            let (d, u) = (query(&s).sample(x, z), inner.sample(x, z));
            for (got, full) in [(d.height, u.height), (d.disp_x, u.disp_x), (d.slope_z, u.slope_z)]
            {
                assert!((got - w * full).abs() < 1e-12, "{system} ({x}, {z}): {got} vs {w}·{full}");
            }
            if w < 1.0 { shallow += 1 } else { deep += 1 }
        }
        assert!(shallow > 50 && deep > 50, "{system}: {shallow} {deep}");
    }
}

#[test]
fn the_shaders_weight_is_the_formula() {
    let s = island("welch", 0.5);
    let plan = FramePlan::new(&s, OutputKind::Hdr);
    let cam = Camera::from_scene(&s.camera).expect("camera");
    let u = FrameUniforms::new(&s, &cam, &plan, [0.0, 0.0], &ObjectPoses::resting(&s));
    let (w, h, texels) = ocean_core::terrain::relief_texels(s.terrain.as_ref());
    let floor = Texture2D::new(w, h, texels);
    let lambda = damped_wavelengths(&s, &plan).expect("gerstner")[0];
    assert_eq!(lambda, 24.0);
    assert_eq!(u.terrain.top[2], (1.0 / (0.5 * 24.0)) as f32);
    let t = s.terrain.as_ref().expect("terrain");
    let eye = s.camera.position;
    let mut worst: f64 = 0.0;
    for i in 0..500 {
        let r = 45.0 + i as f64 * 0.1;
        let a = i as f64 * 0.61;
        let (x, z) = (r * a.cos(), r * a.sin());
        let got =
            shore_weight((x - eye[0]) as f32, (z - eye[2]) as f32, u.terrain.top[2], &u, &floor);
        let want = ((-t.height(x, z)).max(0.0) / 12.0).clamp(0.0, 1.0);
        worst = worst.max((f64::from(got) - want).abs());
    }
    // The relief's bilinear texels (0.41 m) against the profile, and f32.
    assert!(worst < 2e-3, "shader weight vs formula: {worst}");
    // Negative control and the default: no damping, the weight is exactly 1 and the block 0.
    let s0 = island("welch", 0.0);
    let u0 = FrameUniforms::new(
        &s0,
        &cam,
        &FramePlan::new(&s0, OutputKind::Hdr),
        [0.0; 2],
        &ObjectPoses::resting(&s0),
    );
    assert_eq!([u0.terrain.top[2], u0.terrain.top[3]], [0.0, 0.0]);
    assert_eq!(shore_weight(10.0, 10.0, 0.0, &u0, &floor), 1.0);
    assert!(!matches!(query(&s0), WaveSurface::Damped { .. }));
}

#[test]
fn damped_waves_stay_off_the_dry_sand() {
    // Over the island's beach, 0–0.5 m above the sea: the undamped Gerstner sea rises above
    // the sand; damped by Crest's rule it lies under it (the waves vanish where h = 0).
    let highest_over_sand = |damping: f64| {
        let s = island("welch", damping);
        let t = s.terrain.as_ref().expect("terrain").clone();
        let q = query(&s);
        let mut worst = f64::NEG_INFINITY;
        for i in 0..720 {
            let a = i as f64 * std::f64::consts::TAU / 720.0;
            for r in [55.0, 57.0, 58.5, 59.5] {
                let (x, z) = (r * a.cos(), r * a.sin());
                let sand = t.height(x, z);
                worst = worst.max(q.height_at(x, z) - sand);
            }
        }
        worst
    };
    let damped = highest_over_sand(0.5);
    let undamped = highest_over_sand(0.0);
    assert!(damped < 0.0, "damped: the sea stands {damped} m over the sand");
    assert!(undamped > 0.1, "negative control: the undamped sea reaches {undamped} m over it");
}
