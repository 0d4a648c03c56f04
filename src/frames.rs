//! `ocean render --frames A..B`: an animation, one file per frame, resumable and shardable
//! (the rules are in `ocean::animation`).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail, ensure};
use indicatif::{ProgressBar, ProgressStyle};
use ocean_core::plan::{FramePlan, FrameState, OutputKind};
use ocean_core::scene::Scene;
use ocean_gpu::FrameMap;

use ocean::animation::{FramePattern, FrameRange, Shard};

use crate::render::{Backend, encode};

/// What `ocean render --frames` was asked.
pub(crate) struct Sequence<'a> {
    pub scene: Option<&'a PathBuf>,
    pub system: &'a ocean::scene_arg::SystemArg,
    pub time: Option<f64>,
    pub size: Option<&'a str>,
    pub spp: u32,
    pub memory: &'a ocean::memory_arg::MemoryArg,
    pub backend: Backend,
    pub kind: OutputKind,
    pub pattern: &'a Path,
    pub range: FrameRange,
    pub fps: f64,
    pub shard: Shard,
    pub overwrite: bool,
}

/// A drawn frame: the 8-bit picture (when the plan tonemaps) and the HDR frame.
type Drawn = (Option<Vec<u8>>, Vec<[f32; 4]>);

/// One back end, kept across the frames (the GPU's pipelines and state are made once).
enum Renderer {
    Cpu,
    Gpu(Box<ocean_gpu::Renderer>),
}

impl Renderer {
    /// Draws frame `state.frame` by `plan` and advances `state`: (8-bit picture, HDR frame).
    fn draw(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        state: &mut FrameState,
    ) -> anyhow::Result<Drawn> {
        Ok(match self {
            Self::Cpu => {
                let r = ocean_cpu::render::render_animation_frame(
                    scene,
                    plan.clone(),
                    state,
                    &mut |_| {},
                )?;
                (r.ldr, r.buffers.hdr.color)
            }
            Self::Gpu(g) => {
                let f = g.run_frame(scene, plan, state, ocean_gpu::Readback::Output)?;
                let hdr = f.map(FrameMap::Hdr).map(|m| m.texels.clone()).unwrap_or_default();
                (f.ldr, hdr)
            }
        })
    }

    /// Steps frame `state.frame` by `plan` (an advance-only plan) without reading anything
    /// back, and advances `state`.
    fn step(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        state: &mut FrameState,
    ) -> anyhow::Result<()> {
        match self {
            Self::Cpu => {
                ocean_cpu::render::render_animation_frame(scene, plan.clone(), state, &mut |_| {})?;
            }
            Self::Gpu(g) => {
                g.run_frame(scene, plan, state, ocean_gpu::Readback::None)?;
            }
        }
        Ok(())
    }
}

/// Renders the sequence.
pub(crate) fn run(seq: Sequence<'_>) -> anyhow::Result<()> {
    ensure!(
        seq.fps.is_finite() && seq.fps > 0.0,
        "--fps {}: frames per second must be a finite number above 0",
        seq.fps
    );
    if seq.spp != 1 {
        bail!("--spp with --frames is not supported yet: render the frames at 1 sample per pixel");
    }
    let pattern = FramePattern::parse(seq.pattern)?;
    let mut scene = ocean::scene_arg::load_scene(seq.scene, seq.system)?;
    if let Some(t) = seq.time {
        scene.ocean.time_s = t;
    }
    if let Some(s) = seq.size {
        (scene.camera.width, scene.camera.height) = ocean::output::parse_size(s)?;
    }
    ocean::scene_arg::revalidate(&scene, "--time/--size")?;
    let step_s = 1.0 / seq.fps;
    let last_time = scene.ocean.time_s + (seq.range.end - 1) as f64 * step_s;
    ensure!(
        last_time.is_finite(),
        "--frames {}..{} at {} fps: the last frame's time is not a finite number",
        seq.range.start,
        seq.range.end,
        seq.fps
    );
    // One plan for every frame, whatever the range: a looping sea plays its cycle (any
    // count of two or more frames plans alike), so frame n does not depend on the range.
    let plan = FramePlan::for_frames(&scene, seq.kind, seq.range.end.max(2));
    let advance = plan.carries_state().then(|| plan.advance_only());
    seq.memory.check(&scene, &plan, &[seq.backend.memory()])?;

    let mine: Vec<u64> = seq.shard.frames(seq.range).collect();
    let todo: Vec<u64> =
        mine.iter().copied().filter(|n| seq.overwrite || !pattern.path(*n).exists()).collect();
    let on_disk = mine.len() - todo.len();
    if let Some(first) = todo.first() {
        // Before any work: the folder exists (made if missing) and takes files.
        let path = pattern.path(*first);
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot make the folder {}", dir.display()))?;
        }
        drop(ocean::output::OutputFile::reserve(&path)?);
    }
    let Some(&last) = todo.last() else {
        eprintln!(
            "nothing to render: all {} frame(s) of shard {}/{} are on disk (--overwrite renders them again)",
            mine.len(),
            seq.shard.index,
            seq.shard.count
        );
        return Ok(());
    };

    let mut renderer = match seq.backend {
        Backend::Cpu => Renderer::Cpu,
        Backend::Gpu => Renderer::Gpu(Box::new(ocean_gpu::Renderer::new()?)),
    };
    let bar = ProgressBar::new(todo.len() as u64);
    bar.set_style(
        ProgressStyle::with_template(
            "{elapsed:>4} [{bar:30}] {pos}/{len} frames, {per_sec}, ETA {eta} {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let start = Instant::now();
    let mut state = FrameState::new(step_s);
    let mut stepped = 0u64;
    let mut pending = todo.iter().copied().peekable();
    while let Some(&next) = pending.peek() {
        let n = state.frame;
        if n < next {
            match &advance {
                // Frames before it leave state this one continues: step them undrawn.
                Some(a) => {
                    bar.set_message(format!("stepping frame {n} (state for frame {next})"));
                    renderer.step(&scene, a, &mut state).with_context(|| format!("frame {n}"))?;
                    stepped += 1;
                }
                None => state.frame = next,
            }
            continue;
        }
        bar.set_message(format!("frame {n}"));
        let (ldr, hdr) =
            renderer.draw(&scene, &plan, &mut state).with_context(|| format!("frame {n}"))?;
        let path = pattern.path(n);
        let bytes = encode(seq.kind, ldr, &hdr, scene.camera.width, scene.camera.height)?;
        let out = ocean::output::OutputFile::reserve(&path)?;
        out.commit(&bytes).with_context(|| format!("frame {n}"))?;
        pending.next();
        bar.inc(1);
        if n == last {
            break;
        }
    }
    bar.finish_and_clear();
    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "wrote {} frame(s) of {}..{}, first {}, last {last} (shard {}/{} holds {}; {on_disk} \
         already on disk, kept; {stepped} earlier frame(s) stepped for their state) to {} in \
         {secs:.2} s, {:.2} s a frame",
        todo.len(),
        seq.range.start,
        seq.range.end,
        todo[0],
        seq.shard.index,
        seq.shard.count,
        mine.len(),
        seq.pattern.display(),
        secs / todo.len() as f64
    );
    Ok(())
}
