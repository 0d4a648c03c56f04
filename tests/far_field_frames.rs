//! Far fields `none`, `mip` and `variance` against the supersampled ground truth (issue 12):
//! per band of the sea, the mean |Δ log(1 + L)| of the 1-sample frame against the 64-sample
//! frame of `none` (the same model, point-sampled 64 times per pixel), the horizon band's mean
//! brightness, and the flicker between two frames 1/30 s apart, at 320×180 (the size the issue
//! measured the sparkle at). Run with `--nocapture` for the table.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use ocean_core::camera::Camera;
use ocean_core::plan::{FarField, OutputKind};
use ocean_core::scene::Scene;
use ocean_core::supersample::{
    BAND_NAMES, band_error, band_luminance, box_filter, grid_side, sea_bands,
};

const W: u32 = 320;
const H: u32 = 180;

/// The scene's HDR frame at W × H, `spp` samples per pixel, far field `far`, time + `dt`.
fn frame(scene: &Scene, far: FarField, spp: u32, dt: f64) -> Vec<[f32; 4]> {
    let k = grid_side(spp).unwrap();
    let mut s = scene.clone();
    (s.camera.width, s.camera.height) = (W * k, H * k);
    s.ocean.time_s += dt;
    s.techniques.far_field = Some(far);
    let r = ocean_cpu::render_scene(&s, OutputKind::Hdr, &mut |_| {}).unwrap();
    box_filter(&r.buffers.hdr.color, W, H, k)
}

/// The rows of the three bands of sea (ocean-core's `sea_bands`).
fn bands(scene: &Scene) -> [Vec<u32>; 3] {
    let mut s = scene.clone();
    (s.camera.width, s.camera.height) = (W, H);
    sea_bands(&Camera::from_scene(&s.camera).unwrap(), H)
}

/// The scenes: the four the issue names (whose table docs/far-field.md quotes), then three more
/// reference scenes; every check below runs on all seven.
fn scenes() -> Vec<(&'static str, Scene)> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("reference/scenes");
    let load = |name: &str| Scene::load(&root.join(format!("{name}.toml"))).unwrap();
    let mut high = load("default");
    high.camera.position[1] = 40.0;
    vec![
        ("default", load("default")),
        ("40 m up", high),
        ("grazing sun", load("grazing_sun")),
        ("storm", load("storm")),
        ("calm", load("calm")),
        ("phillips", load("phillips")),
        ("shallow_reef", load("shallow_reef")),
    ]
}

/// docs/design.md's limit per band against the 64-sample frame.
const BAND_LIMIT: f64 = 0.06;

/// The limit on the horizon band's mean brightness against the 64-sample frame's.
const HORIZON_BRIGHTNESS: f64 = 0.10;

/// The checks (and the table the note quotes), in every band of every scene: `variance` is
/// within docs/design.md's 0.06 of the 64-sample frame, its horizon band's mean brightness within
/// 10 %, and it and `mip` flicker at most 1.5× as much as the 64-sample frames between two
/// frames 1/30 s apart. Negative control: `none` flickers more, and is over 0.06 in the
/// horizon and middle bands (the near band's pixels resolve its waves at this size).
#[test]
fn far_fields_against_the_64_sample_frame() {
    let dt = 1.0 / 30.0;
    let mut failures = Vec::new();
    eprintln!(
        "scene | technique | band | mean |Δ log(1+L)| vs 64 spp | brightness ratio | flicker (64 spp flicker)"
    );
    for (name, scene) in scenes() {
        let truth = frame(&scene, FarField::None, 64, 0.0);
        let truth_next = frame(&scene, FarField::None, 64, dt);
        let bands = bands(&scene);
        let mut none_error = [0.0f64; 3];

        for far in [FarField::None, FarField::Mip, FarField::Variance] {
            let a = frame(&scene, far, 1, 0.0);
            let b = frame(&scene, far, 1, dt);
            for (k, (band, rows)) in BAND_NAMES.iter().zip(&bands).enumerate() {
                if rows.is_empty() {
                    continue;
                }
                let e = band_error(&a, &truth, W, rows);
                let ratio = band_luminance(&a, W, rows) / band_luminance(&truth, W, rows);
                let flicker = band_error(&a, &b, W, rows);
                let truth_flicker = band_error(&truth, &truth_next, W, rows);
                let over = if e > BAND_LIMIT { " (over docs/design.md's limit)" } else { "" };
                eprintln!(
                    "{name} | {far} | {band} | {e:.4}{over} | {ratio:.3} | {flicker:.4} ({truth_flicker:.4})"
                );
                let steady = flicker <= 1.5 * truth_flicker;
                match far {
                    FarField::None => {
                        none_error[k] = e;
                        if steady {
                            failures.push(format!("{name} {band}: `none` does not flicker"));
                        }
                        // The near band is resolved at this size (within 0.06 in two scenes).
                        if k < 2 && e <= BAND_LIMIT {
                            failures.push(format!("{name} {band}: `none` within {e}"));
                        }
                    }
                    _ => {
                        if !steady {
                            failures.push(format!("{name} {band}: `{far}` flickers {flicker}"));
                        }
                        if far == FarField::Variance && e >= none_error[k] {
                            failures.push(format!("{name} {band}: `variance` {e} vs none"));
                        }
                        if far == FarField::Variance && e > BAND_LIMIT {
                            failures.push(format!("{name} {band}: `variance` off by {e}"));
                        }
                        if far == FarField::Variance
                            && k == 0
                            && (ratio - 1.0).abs() > HORIZON_BRIGHTNESS
                        {
                            failures.push(format!("{name} horizon: `variance` brightness {ratio}"));
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
