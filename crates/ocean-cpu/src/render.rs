//! The CPU renderer's entry points: a scene in, the frame's maps and picture out, through the
//! frame graph ([`crate::frame::render_frame`]).

use ocean_core::graph::{FrameInputs, FrameState};
use ocean_core::plan::{FramePlan, OutputKind, Pass};
use ocean_core::scene::Scene;

use crate::frame::{Environment, Error, FrameBuffers, render_frame};

/// A rendered frame.
pub struct Rendered {
    /// The plan it ran.
    pub plan: FramePlan,
    /// Every map and the HDR picture.
    pub buffers: FrameBuffers,
    /// The 8-bit sRGB RGBA picture, when the plan tonemaps.
    pub ldr: Option<Vec<u8>>,
}

/// Renders a validated scene by its single-frame plan; `on_pass` is called as each pass
/// starts.
pub fn render_scene(
    scene: &Scene,
    output: OutputKind,
    on_pass: &mut dyn FnMut(Pass),
) -> Result<Rendered, Error> {
    render_scene_with_plan(scene, FramePlan::new(scene, output), on_pass)
}

/// Renders a validated scene by a given plan (e.g. [`FramePlan::full`], to compare with the
/// pruned one).
pub fn render_scene_with_plan(
    scene: &Scene,
    plan: FramePlan,
    on_pass: &mut dyn FnMut(Pass),
) -> Result<Rendered, Error> {
    render_animation_frame(scene, plan, &mut FrameState::default(), on_pass)
}

/// Renders frame `state.frame` of an animation by `plan` (a plan for several frames plays a
/// looping sea's cycle, precomputed in `state` by the first frame), then advances `state`.
pub fn render_animation_frame(
    scene: &Scene,
    plan: FramePlan,
    state: &mut FrameState,
    on_pass: &mut dyn FnMut(Pass),
) -> Result<Rendered, Error> {
    let frame = FrameInputs::new(scene, &plan, state)?;
    let mut buffers = render_frame(&frame, Environment::Planned, state, on_pass)?;
    drop(frame);
    state.advance();
    let ldr = buffers.ldr.take();
    Ok(Rendered { plan, buffers, ldr })
}

/// The 8-bit sRGB RGBA picture of a scene (row-major, top row first).
pub fn render_ldr(scene: &Scene) -> Result<Vec<u8>, Error> {
    let r = render_scene(scene, OutputKind::Ldr, &mut |_| {})?;
    Ok(r.ldr.unwrap_or_default())
}
