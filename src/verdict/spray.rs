//! Pass `spray`'s step against its envelope, from the device's own inputs: the pool as a frame
//! left it on the device, one more step run there on buffers of its own, and the envelope of
//! that step (ocean-cpu `spray::step_envelope`) from the same pool and the frame's own
//! displacement map. The same pool is the one the frame's sprites were drawn from, so the
//! water's verdict adds the sprites' envelope from it (`main_view::sprites_over`).

use ocean_core::plan::{FramePlan, Pass, ResourceId};
use ocean_core::scene::Scene;
use ocean_core::spray::{Particle, SprayFrame, SprayUniforms};
use ocean_cpu::sampler::Texture2D;

use super::{FrameRef, GpuSide};

/// One step of the spray as a device ran it: the slots before and after, and its uniforms.
#[derive(Clone, Debug)]
pub struct SprayProbe {
    /// The pool as the frame left it on the device.
    pub before: Vec<Particle>,
    /// The pool after one more step on the device.
    pub after: Vec<Particle>,
    /// That step's uniforms.
    pub params: SprayUniforms,
}

/// The frame's displacement map as the GPU read it (its read-back), or the 1×1 zero map a
/// frame without a `waves` pass binds.
fn displacement(map: Option<FrameRef<'_>>) -> (u32, u32, Vec<[f32; 4]>) {
    match map {
        Some(((w, h), t)) => (w, h, t.to_vec()),
        None => (1, 1, vec![[0.0; 4]]),
    }
}

/// The uniforms of step `step` of the spray of `scene` under `plan`.
///
/// # Errors
/// A camera the scene cannot make.
pub fn step_uniforms(scene: &Scene, plan: &FramePlan, step: u64) -> anyhow::Result<SprayUniforms> {
    // The camera alone (the sprites face it), not a frame's inputs: no mesh, sky or boat.
    let camera = ocean_core::camera::Camera::from_scene(&scene.camera)?;
    Ok(SprayFrame::new(scene, plan, &camera, step, 1).steps[0])
}

/// Runs the step after `renderer`'s last frame (of `scene` under `plan`, with the read-back
/// `displacement` map, if the frame has one) on the device: `None` where the frame has no
/// spray.
///
/// # Errors
/// A device error, or uniforms the scene cannot make.
pub fn probe(
    renderer: &ocean_gpu::Renderer,
    scene: &Scene,
    plan: &FramePlan,
    displacement_map: Option<FrameRef<'_>>,
) -> anyhow::Result<Option<SprayProbe>> {
    if !plan.runs(Pass::Spray) {
        return Ok(None);
    }
    let (Some(before), Some(steps)) = (renderer.spray_particles()?, renderer.spray_steps()) else {
        return Ok(None);
    };
    let params = step_uniforms(scene, plan, steps)?;
    let (w, h, map) = displacement(displacement_map);
    let Some(after) = renderer.spray_probe(&before, &params, (w, h, &map))? else {
        return Ok(None);
    };
    Ok(Some(SprayProbe { before, after, params }))
}

/// The probed step's slots against its envelope: two values per slot (position and tag,
/// velocity and age), a slot whose branch is undecided (freed or kept, launched or left)
/// judged against both outcomes united and, where outside, counted as ambiguous.
///
/// # Errors
/// A pool of another size than the plan's.
pub fn verdict(
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
    probe: &SprayProbe,
) -> anyhow::Result<ocean_verify::envelope::RegionVerdict> {
    use ocean_cpu::envelope::Iv;
    if probe.before.len() != probe.after.len() {
        anyhow::bail!(
            "spray_particles: {} slots before the step, {} after",
            probe.before.len(),
            probe.after.len()
        );
    }
    let (w, h, map) = displacement(gpu.map(ResourceId::Displacement));
    let env = ocean_cpu::shaders::spray::step_envelope(
        &probe.before,
        &probe.params,
        &plan.spray_emitters,
        &Texture2D::new(w, h, map),
        gpu.precision.0,
    );
    let envelope: Vec<[Iv; 4]> = env.iter().flat_map(|s| [s.pos, s.vel]).collect();
    let region: Vec<Option<bool>> = env.iter().flat_map(|s| [Some(s.decided); 2]).collect();
    let texels: Vec<[f32; 4]> = probe.after.iter().flat_map(|p| [p.pos, p.vel]).collect();
    Ok(ocean_verify::envelope::judge_region("spray_particles", &envelope, &region, &texels, 2))
}
