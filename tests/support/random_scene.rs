//! Random valid scenes for the frame-graph property tests (CPU: `tests/frame_graph.rs`, GPU:
//! `tests/gpu_frame_graph.rs`).

use ocean_core::plan::OutputKind;
use ocean_core::scene::{Scene, SceneSource};

/// A small deterministic generator for the property test (SplitMix64).
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[(self.next() % xs.len() as u64) as usize]
    }
}

/// A random valid scene at a tiny size: random `[quality]`, wave grids, camera height (above
/// and under the water), sun, objects above and below, wind on or off, PNG or EXR.
pub fn random_scene(rng: &mut Rng) -> (Scene, OutputKind) {
    let res = rng.pick(&[16u32, 32, 64]);
    let text = format!(
        "[ocean]\nwind_speed = {wind}\nresolution = {res}\nbump_resolution = {bres}\n\
         patch_size_m = {patch}\n\
         [quality]\nfresnel_table_size = {fres}\nreflection_map_scale = {scale}\n\
         lod_split_threshold = {lod}\n\
         [camera]\nwidth = {w}\nheight = {h}\nposition = [0.0, {y}, 30.0]\n\
         look_at = [0.0, {ly}, 0.0]\n{sun}{objects}",
        wind = rng.pick(&[0.0, 4.0, 12.0]),
        bres = rng.pick(&[16u32, 32]),
        patch = rng.pick(&[64.0, 128.0, 256.0]),
        fres = rng.pick(&[2u32, 17, 64, 128, 256]),
        scale = rng.uniform(0.05, 1.0),
        lod = rng.pick(&[0.02, 0.05, 0.2]),
        w = rng.pick(&[16u32, 33, 48]),
        h = rng.pick(&[9u32, 18, 27]),
        y = rng.pick(&[6.0, 40.0, -5.0]),
        ly = rng.pick(&[0.0, 2.0, -3.0]),
        sun =
            if rng.next().is_multiple_of(2) { "[sun]\ndirection = [0.3, 0.5, -1.0]\n" } else { "" },
        objects = match rng.next() % 3 {
            0 => "",
            1 => "[[objects]]\nkind = \"sphere\"\ncenter = [0.0, 3.0, 0.0]\nradius = 2.0\n",
            _ =>
                "[[objects]]\nkind = \"box\"\ncenter = [1.0, -2.0, 5.0]\nsize = [2.0, 2.0, 2.0]\n\
                  [[objects]]\nkind = \"sphere\"\ncenter = [-4.0, 2.0, 0.0]\nradius = 1.0\n",
        },
    );
    let s = Scene::from_toml(&text, SceneSource::Text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    (s, if rng.next().is_multiple_of(3) { OutputKind::Hdr } else { OutputKind::Ldr })
}
