//! What pass `spray` takes from a scene and its plan each frame: the spray model
//! (`crate::spray`) knows no scene.

use std::sync::Arc;

use glam::DVec3;

use crate::scene::Scene;
use crate::spray::{GRAVITY, PoolKey, SprayFrame, SprayUniforms, spray_origin};

/// The uniforms of step `step` of the scene's spray seen by `camera`.
pub fn spray_uniforms(
    scene: &Scene,
    camera: &crate::camera::Camera,
    waves: bool,
    emitters: u32,
    step: u64,
) -> SprayUniforms {
    let s = &scene.spray;
    let eye = camera.eye;
    let forward = (DVec3::from_array(scene.camera.look_at) - eye).normalize_or_zero();
    let right = forward.cross(DVec3::Y).try_normalize().unwrap_or(DVec3::X);
    let up = right.cross(forward).normalize_or_zero();
    let v4 = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
    let origin = spray_origin(&scene.objects, scene.ocean.patch_size_m);
    let o = &scene.ocean;
    SprayUniforms {
        step: step as u32,
        count: s.particles,
        emitters,
        seed: (o.seed as u32) ^ 0x5eed_0001,
        dt: s.step_s as f32,
        gravity: GRAVITY,
        speed: s.speed as f32,
        lifetime: s.lifetime_s as f32,
        emit_chance: s.emit_chance as f32,
        inv_patch: (1.0 / o.patch_size_m) as f32,
        half_texel: (0.5 / f64::from(o.resolution)) as f32,
        waves: if waves { 1.0 } else { 0.0 },
        origin_rel: [(origin[0] - eye.x) as f32, (-eye.y) as f32, (origin[1] - eye.z) as f32, 0.0],
        sprite: [(0.5 * s.size_m) as f32, s.intensity as f32, 0.0, 0.0],
        color: [s.color[0] as f32, s.color[1] as f32, s.color[2] as f32, 0.0],
        right: v4(right),
        up: v4(up),
    }
}

impl SprayFrame {
    /// The pass of a frame of `plan` seen by `camera` running `steps` steps from `first`; the
    /// emitters are the plan's ([`crate::plan::FramePlan::spray_emitters`], found once).
    pub fn new(
        scene: &Scene,
        plan: &crate::plan::FramePlan,
        camera: &crate::camera::Camera,
        first: u64,
        steps: u64,
    ) -> Self {
        let emitters = Arc::clone(&plan.spray_emitters);
        let waves = plan.runs(crate::plan::Pass::Waves);
        let n = emitters.len() as u32;
        let at = |k| spray_uniforms(scene, camera, waves, n, k);
        Self {
            key: PoolKey { spray: scene.spray.clone(), emitters },
            first,
            steps: (first..first + steps).map(at).collect(),
            draw: at(first + steps),
        }
    }
}
