//! Random valid scenes for the frame-graph property tests (CPU: `tests/frame_graph.rs`, GPU:
//! `tests/gpu_frame_graph.rs`).

use ocean_core::plan::OutputKind;
use ocean_core::scene::{Scene, SceneSource};

pub use ocean_core::fuzz::Rng;

fn uniform(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.unit()
}

fn pick<T: Copy>(rng: &mut Rng, xs: &[T]) -> T {
    xs[rng.below(xs.len())]
}

/// A random valid scene at a tiny size: random `[quality]`, wave grids, camera height (above
/// and under the water), sun, objects above and below, wind on or off, PNG or EXR.
pub fn random_scene(rng: &mut Rng) -> (Scene, OutputKind) {
    let res = pick(rng, &[16u32, 32, 64]);
    let text = format!(
        "[ocean]\nwind_speed = {wind}\nresolution = {res}\nbump_resolution = {bres}\n\
         patch_size_m = {patch}\n\
         [quality]\nfresnel_table_size = {fres}\nreflection_map_scale = {scale}\n\
         lod_split_threshold = {lod}\n\
         [camera]\nwidth = {w}\nheight = {h}\nposition = [0.0, {y}, 30.0]\n\
         look_at = [0.0, {ly}, 0.0]\n{sun}{objects}",
        wind = pick(rng, &[0.0, 4.0, 12.0]),
        bres = pick(rng, &[16u32, 32]),
        patch = pick(rng, &[64.0, 128.0, 256.0]),
        fres = pick(rng, &[2u32, 17, 64, 128, 256]),
        scale = uniform(rng, 0.05, 1.0),
        lod = pick(rng, &[0.02, 0.05, 0.2]),
        w = pick(rng, &[16u32, 33, 48]),
        h = pick(rng, &[9u32, 18, 27]),
        y = pick(rng, &[6.0, 40.0, -5.0]),
        ly = pick(rng, &[0.0, 2.0, -3.0]),
        sun = if rng.next_u64().is_multiple_of(2) {
            "[sun]\ndirection = [0.3, 0.5, -1.0]\n"
        } else {
            ""
        },
        objects = match rng.next_u64() % 3 {
            0 => "",
            1 => "[[objects]]\nkind = \"sphere\"\ncenter = [0.0, 3.0, 0.0]\nradius = 2.0\n",
            _ =>
                "[[objects]]\nkind = \"box\"\ncenter = [1.0, -2.0, 5.0]\nsize = [2.0, 2.0, 2.0]\n\
                  [[objects]]\nkind = \"sphere\"\ncenter = [-4.0, 2.0, 0.0]\nradius = 1.0\n",
        },
    );
    let s = Scene::from_toml(&text, SceneSource::Text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    (s, if rng.next_u64().is_multiple_of(3) { OutputKind::Hdr } else { OutputKind::Ldr })
}
