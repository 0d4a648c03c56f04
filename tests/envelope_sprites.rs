//! The spray's sprites' envelope (ocean-cpu `spray::sprites_envelope`), from the pool a
//! frame drew: the oracle's own draw and random conformant GPUs' lie inside it on every
//! scene with a spray, over a frame and a depth buffer each GPU holds within bounds; a
//! sprite 2 % brighter and a GPU twice as loose as the rules leave it.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[path = "support/reference_scenes.rs"]
mod reference_scenes;

use ocean_core::frame_format::FrameFormat;
use ocean_core::graph::FrameState;
use ocean_core::plan::{FramePlan, OutputKind, Pass};
use ocean_core::scene::Scene;
use ocean_core::spray::{Particle, SprayFrame, SprayUniforms};
use ocean_cpu::envelope::{Iv, JitterRules, Precision};
use ocean_cpu::shaders::spray;

/// A uniform draw in [0, 1) from a key (splitmix's finaliser).
fn unit(key: u64) -> f64 {
    (ocean_core::rng::mix64(key) >> 11) as f64 / (1u64 << 53) as f64
}

/// What the pass reads and draws onto, for one scene: the pool, the uniforms, and the frame
/// and depth a GPU may hold before it (as intervals).
struct Setup {
    pool: Vec<Particle>,
    frame: ocean_core::frame::FrameUniforms,
    draw: SprayUniforms,
    size: [u32; 2],
    format: FrameFormat,
    base: Vec<[Iv; 4]>,
    depth: Vec<Iv>,
}

impl Setup {
    /// The oracle's pool after its first frame of `scene`; a frame of colours each known
    /// within 10⁻³ of itself; the depth of the particles' median distance (±10⁻⁴ of it) over
    /// the right two thirds, the cleared 0 (the sky) over the left third. So some sprites
    /// are in front, some behind and some cross it.
    fn new(scene: &Scene, plan: &FramePlan) -> Self {
        let mut state = FrameState::new(1.0 / 30.0);
        ocean_cpu::render::render_animation_frame(scene, plan.clone(), &mut state, &mut |_| {})
            .unwrap();
        let pool = state.spray.as_ref().unwrap();
        let inputs = ocean_core::graph::FrameInputs::new(scene, plan, &state).unwrap();
        let draw = SprayFrame::new(scene, plan, &inputs.camera, pool.steps, 0).draw;
        let frame = inputs.uniforms;
        let size = [scene.camera.width, scene.camera.height];
        let mut depths: Vec<f32> = pool
            .particles
            .iter()
            .filter(|p| p.pos[3] != 0.0)
            .map(|p| {
                let c = spray::corner_clip_r::<f32>(p, [0.0, 0.0], &frame, &draw);
                c[2] / c[3]
            })
            .collect();
        depths.sort_by(f32::total_cmp);
        let d0 = f64::from(depths.get(depths.len() / 2).copied().unwrap_or(0.5));
        let n = (size[0] * size[1]) as usize;
        let base = (0..n)
            .map(|i| {
                let c = |k: u64| {
                    let v = f64::from((0.05 + 0.4 * unit(i as u64 * 4 + k)) as f32);
                    Iv::new(v * (1.0 - 1e-3), v * (1.0 + 1e-3))
                };
                [c(0), c(1), c(2), Iv::point(1.0)]
            })
            .collect();
        let depth = (0..n)
            .map(|i| {
                let sky = (i % size[0] as usize) < size[0] as usize / 3;
                if sky { Iv::point(0.0) } else { Iv::new(d0 * (1.0 - 1e-4), d0 * (1.0 + 1e-4)) }
            })
            .collect();
        let (pool, format) = (pool.particles.clone(), plan.frame_format);
        Self { pool, frame, draw, size, format, base, depth }
    }

    /// The envelope of the sprites over the frame, at `precision`'s snap.
    fn envelope(&self, precision: Precision) -> Vec<[Iv; 4]> {
        let mut env = self.base.clone();
        let snap = precision.snap_px();
        let (f, d) = (&self.frame, &self.draw);
        let bounded = spray::sprites_envelope(
            &self.pool,
            f,
            d,
            self.size,
            self.format,
            snap,
            &mut env,
            &self.depth,
        );
        assert!(bounded, "the sprites' envelope is bounded");
        env
    }

    /// A frame and depth buffer a GPU may hold (`seed` draws them within their intervals).
    fn held(&self, seed: u64) -> (Vec<[f32; 4]>, Vec<f32>) {
        let pick = |iv: Iv, key: u64| {
            let v = (iv.lo + unit(key) * (iv.hi - iv.lo)) as f32;
            if iv.contains(v) { v } else { ((iv.lo + iv.hi) * 0.5) as f32 }
        };
        let key = |i: usize, k: u64| seed << 40 ^ (i as u64) << 3 ^ k;
        let color = self
            .base
            .iter()
            .enumerate()
            .map(|(i, b)| std::array::from_fn(|c| pick(b[c], key(i, c as u64))))
            .collect();
        let depth = self.depth.iter().enumerate().map(|(i, d)| pick(*d, key(i, 5))).collect();
        (color, depth)
    }

    /// The oracle's draw over a held frame, its sprites' radiance times `gain`.
    fn oracle(&self, seed: u64, gain: f32) -> Vec<[f32; 4]> {
        let (color, depth) = self.held(seed);
        let mut t =
            ocean_cpu::raster::RenderTarget::with_format(self.size[0], self.size[1], self.format);
        (t.color, t.depth) = (color, depth);
        let mut draw = self.draw;
        draw.sprite[1] *= gain;
        spray::draw_sprites(&mut t, &self.pool, &self.frame, &draw);
        t.color
    }

    /// One random conformant GPU's draw over a held frame.
    fn gpu(&self, seed: u64, rules: JitterRules, precision: Precision) -> Vec<[f32; 4]> {
        let (mut color, depth) = self.held(seed);
        let (f, d, bits) = (&self.frame, &self.draw, precision.subpixel_bits);
        spray::sprites_jitter(
            &self.pool,
            f,
            d,
            self.size,
            self.format,
            &mut color,
            &depth,
            rules,
            bits,
        );
        color
    }
}

/// Values of `frame` outside `env`.
fn outside(env: &[[Iv; 4]], frame: &[[f32; 4]]) -> usize {
    env.iter().zip(frame).map(|(e, g)| (0..4).filter(|&c| !e[c].contains(g[c])).count()).sum()
}

/// The scenes with a spray at 160×90: the reference scenes' and system `chiu`'s own.
fn spray_scenes() -> Vec<(String, Scene, FramePlan)> {
    let mut scenes = reference_scenes::reference_scenes();
    let chiu = ocean::scene_arg::SystemArg { system: Some("chiu".into()) };
    scenes.push(("builtin-chiu".into(), ocean::scene_arg::load_scene(None, &chiu).unwrap()));
    scenes
        .into_iter()
        .filter_map(|(name, mut scene)| {
            (scene.camera.width, scene.camera.height) = (160, 90);
            let plan = FramePlan::new(&scene, OutputKind::Hdr);
            plan.runs(Pass::Spray).then_some((name, scene, plan))
        })
        .collect()
}

#[test]
fn the_oracle_and_conformant_gpus_draw_the_sprites_inside_their_envelope() {
    let (mut sprite_px, mut full_px, mut brighter, mut loose, mut scenes) = (0, 0, 0, 0, 0);
    let mut rel = Vec::new();
    for (name, scene, plan) in spray_scenes() {
        let s = Setup::new(&scene, &plan);
        let live = s.pool.iter().filter(|p| p.pos[3] != 0.0).count();
        assert!(live > 20, "{name}: {live} live particles");
        for precision in [Precision::LAVAPIPE, Precision::VULKAN_MINIMUM] {
            let env = s.envelope(precision);
            for seed in 0..4 {
                assert_eq!(outside(&env, &s.oracle(seed, 1.0)), 0, "{name}: the oracle, {seed}");
            }
            for seed in 0..8 {
                let rules = JitterRules { seed, scale: 1.0 };
                let gpu = s.gpu(100 + seed, rules, precision);
                assert_eq!(outside(&env, &gpu), 0, "{name}: seed {seed}, {precision:?}");
                let rules = JitterRules { seed: 1000 + seed, scale: 2.0 };
                loose += outside(&env, &s.gpu(200 + seed, rules, precision));
            }
            brighter += outside(&env, &s.oracle(7, 1.02));
            // Where the sprites may add light: the envelope's width past the frame's own.
            for (e, b) in env.iter().zip(&s.base) {
                if e[0].full {
                    full_px += 1;
                } else if (0..3).any(|c| e[c].hi > b[c].hi) {
                    sprite_px += 1;
                    rel.extend(e[..3].iter().filter_map(|c| c.rel_half_width()));
                }
            }
        }
        scenes += 1;
    }
    rel.sort_by(f64::total_cmp);
    let q = |p: f64| rel.get(((rel.len().max(1) - 1) as f64 * p) as usize).copied().unwrap_or(0.0);
    println!(
        "sprites on {scenes} scenes × 2 precisions: the oracle (4 frames) and 8 random \
         conformant GPUs inside; {sprite_px} pixels where a sprite may add light, rel half-width \
         p50 {:.1e} p99 {:.1e}; {full_px} \
         pixels unbounded (a sprite too small for the snap to bound its varyings); a sprite 2 \
         % brighter: {brighter} values outside; GPUs twice as loose: {loose}",
        q(0.5),
        q(0.99)
    );
    assert!(scenes >= 2, "scenes with a spray: {scenes}");
    assert!(sprite_px > 100, "pixels a sprite may light: {sprite_px}");
    assert!(brighter > 0, "a sprite 2 % brighter never left the envelope");
    assert!(loose > 0, "a GPU twice as loose as the rules never left the envelope");
}

/// The sprites' one mirror at `f32` is WGSL's arithmetic as written, bit for bit:
/// `transform_point(view_proj, pos + origin_rel + (right·cx + up·cy)·half)` at every corner
/// of every live particle, and `color · max(1 − r², 0) · radiance` across the quad.
#[test]
fn the_sprites_mirror_at_f32_is_the_wgsl_as_written() {
    use glam::{Vec3, Vec4};
    let (mut corners, mut colors) = (0, 0);
    for (name, scene, plan) in spray_scenes() {
        let s = Setup::new(&scene, &plan);
        let (f, d) = (&s.frame, &s.draw);
        let v3 = |a: [f32; 4]| Vec3::new(a[0], a[1], a[2]);
        let m = f.view.view_proj.map(Vec4::from);
        for p in s.pool.iter().filter(|p| p.pos[3] != 0.0) {
            for c in spray::QUAD {
                let rel = v3(p.pos)
                    + v3(d.origin_rel)
                    + (v3(d.right) * c[0] + v3(d.up) * c[1]) * d.sprite[0];
                let want = m[0] * rel.x + m[1] * rel.y + m[2] * rel.z + m[3];
                let got = spray::corner_clip_r::<f32>(p, c, f, d);
                assert_eq!(got.map(f32::to_bits), want.to_array().map(f32::to_bits), "{name}");
                corners += 1;
            }
        }
        for k in 0..=40 {
            let (x, y) = (-1.0 + 0.05 * k as f32, 0.7 - 0.035 * k as f32);
            let a = (1.0 - (x * x + y * y)).max(0.0) * d.sprite[1];
            let want = [d.color[0] * a, d.color[1] * a, d.color[2] * a, 0.0];
            let got = spray::sprite_color_r([x, y], d);
            assert_eq!(got.map(f32::to_bits), want.map(f32::to_bits), "{name} at ({x}, {y})");
            colors += 1;
        }
    }
    assert!(corners > 1000 && colors > 40, "{corners} corners, {colors} colours compared");
}
