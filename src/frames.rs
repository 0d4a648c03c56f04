//! `ocean render --frames A..B`: an animation, one file per frame, resumable and shardable
//! (the rules are in `ocean::animation`).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail, ensure};
use indicatif::{ProgressBar, ProgressStyle};
use ocean_core::graph::FrameState;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::Scene;
use ocean_gpu::FrameMap;

use ocean::animation::{FramePattern, FrameRange, Shard};

use crate::backend::{Backend, encode};

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
    /// `--replay-any`: step any number of earlier frames for their state.
    pub replay_any: bool,
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

/// The most earlier frames a run steps undrawn for their state (foam `accumulated`, the
/// spray's pool) unless `--replay-any` allows more: 100,000 frames of foam take about 1.5 h
/// here (55 ms a step at 1280×720); frame 1,000,000 of `foam_storm.toml` alone would take 14 h.
pub const MAX_REPLAY_FRAMES: u64 = 100_000;

/// How many frames of `range` shard `shard` holds, counted, not listed.
fn shard_len(range: FrameRange, shard: Shard) -> u64 {
    range.len().saturating_sub(shard.index).div_ceil(shard.count)
}

/// Renders the sequence. Frames stream: nothing before the first frame depends on the
/// range's length (a range of 10⁹ frames once listed every frame first: 8.7 GB, no frame in
/// 60 s).
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
    let scene = load_scene(&seq)?;
    let step_s = 1.0 / seq.fps;
    check_last_frame_time(&seq, &scene, step_s)?;
    // One plan for every frame, whatever the range: a looping sea plays its cycle (any
    // count of two or more frames plans alike), so frame n does not depend on the range.
    let plan = FramePlan::for_frames(&scene, seq.kind, seq.range.end.max(2));
    let advance = plan.carries_state().then(|| plan.advance_only());
    seq.memory.check(&scene, &plan, &[seq.backend.memory()])?;
    let job =
        Job { seq: &seq, scene: &scene, plan: &plan, advance: advance.as_ref(), pattern: &pattern };

    let total = shard_len(seq.range, seq.shard);
    if total == 0 {
        eprintln!(
            "nothing to render: shard {}/{} of {}..{} holds no frame (the range has {})",
            seq.shard.index,
            seq.shard.count,
            seq.range.start,
            seq.range.end,
            seq.range.len()
        );
        return Ok(());
    }
    // The first frame to draw, found by looking at the frames before it one by one (on disk
    // and kept): work in proportion to what is already done, not to the range.
    let Some(first) = seq.shard.frames(seq.range).find(|n| !job.on_disk(*n)) else {
        eprintln!(
            "nothing to render: all {total} frame(s) of shard {}/{} are on disk (--overwrite \
             renders them again)",
            seq.shard.index, seq.shard.count
        );
        return Ok(());
    };
    let last = seq.range.start + seq.shard.index + (total - 1) * seq.shard.count;
    // What the request costs before it starts: the frames to draw, and, where the scene
    // carries state from frame to frame, the earlier frames stepped undrawn for it.
    let replay = if advance.is_some() { (last + 1).saturating_sub(total) } else { 0 };
    announce(&seq, total, first, replay);
    if replay > MAX_REPLAY_FRAMES && !seq.replay_any {
        bail!(
            "this run would step {replay} frames undrawn for their state (foam or spray carry \
             state, so frame n needs frames 0..n), more than {MAX_REPLAY_FRAMES}: render a \
             range that starts earlier, fewer shards, or pass --replay-any to run it anyway"
        );
    }
    {
        // Before any work: the folder exists (made if missing) and takes files.
        let path = pattern.path(first);
        make_parent(&path)?;
        drop(ocean::output::OutputFile::reserve(&path)?);
    }

    let mut renderer = match seq.backend {
        Backend::Cpu => Renderer::Cpu,
        Backend::Gpu => Renderer::Gpu(Box::new(ocean_gpu::Renderer::new()?)),
    };
    // One unit a frame the run passes through: drawn, stepped for its state, or on disk.
    let work = if advance.is_some() { last + 1 } else { total };
    let Tally { stepped, drawn, last_drawn, secs } =
        job.render(&mut renderer, first, work, step_s)?;
    eprintln!(
        "wrote {drawn} frame(s) of {}..{}, first {first}, last {last_drawn} (shard {}/{} holds \
         {total}; {} already on disk, kept; {stepped} earlier frame(s) stepped for their \
         state) to {} in {secs:.2} s, {:.2} s a frame",
        seq.range.start,
        seq.range.end,
        seq.shard.index,
        seq.shard.count,
        total - drawn,
        seq.pattern.display(),
        secs / drawn.max(1) as f64
    );
    Ok(())
}

/// The sequence's scene: the file's (or the system's), at `--time` and `--size`, validated.
fn load_scene(seq: &Sequence<'_>) -> anyhow::Result<Scene> {
    seq.memory.limit_inputs();
    let mut scene = ocean::scene_arg::load_scene(seq.scene, seq.system)?;
    if let Some(t) = seq.time {
        scene.ocean.time_s = t;
    }
    if let Some(s) = seq.size {
        (scene.camera.width, scene.camera.height) = ocean::output::parse_size(s)?;
    }
    ocean::scene_arg::revalidate(&scene, "--time/--size")?;
    Ok(scene)
}

/// Every frame's time within the scene's limits, checked on the last one before the first
/// is drawn (--fps 1e-300 failed only after frame 0 was written).
fn check_last_frame_time(seq: &Sequence<'_>, scene: &Scene, step_s: f64) -> anyhow::Result<()> {
    let mut last_frame = scene.clone();
    last_frame.ocean.time_s = scene.ocean.time_s + (seq.range.end - 1) as f64 * step_s;
    ensure!(
        last_frame.ocean.time_s.is_finite(),
        "--frames {}..{} at {} fps: the last frame's time is not a finite number",
        seq.range.start,
        seq.range.end,
        seq.fps
    );
    ocean::scene_arg::revalidate(
        &last_frame,
        &format!(
            "--frames {}..{} at --fps {:?}: the last frame's time, {:?} s,",
            seq.range.start, seq.range.end, seq.fps, last_frame.ocean.time_s
        ),
    )
}

/// Says what the request costs before it starts: `total` frames in the shard, the first to
/// draw, and `replay` earlier frames stepped undrawn for their state.
fn announce(seq: &Sequence<'_>, total: u64, first: u64, replay: u64) {
    eprintln!(
        "frames {}..{} (shard {}/{}): {total} in the shard, the first to draw is frame {first}{}",
        seq.range.start,
        seq.range.end,
        seq.shard.index,
        seq.shard.count,
        if replay > 0 {
            format!(
                "; the scene carries state from frame to frame, so up to {replay} earlier \
                 frame(s) are stepped undrawn first (from frame 0)"
            )
        } else {
            String::new()
        }
    );
}

/// A run's scene and plans, and where its frames go.
struct Job<'a> {
    seq: &'a Sequence<'a>,
    scene: &'a Scene,
    plan: &'a FramePlan,
    /// The advance-only plan that steps a frame undrawn, where the scene carries state from
    /// frame to frame.
    advance: Option<&'a FramePlan>,
    pattern: &'a FramePattern,
}

/// What a run did: frames stepped undrawn and drawn, the last drawn, and how long it took.
struct Tally {
    stepped: u64,
    drawn: u64,
    last_drawn: u64,
    secs: f64,
}

impl Job<'_> {
    /// Whether frame `n` is on disk and kept.
    fn on_disk(&self, n: u64) -> bool {
        !self.seq.overwrite && self.pattern.path(n).exists()
    }

    /// Draws the shard's frames from `first` on (those on disk kept), stepping the frames
    /// before each undrawn where the scene carries state, with a bar of `work` units.
    fn render(
        &self,
        renderer: &mut Renderer,
        first: u64,
        work: u64,
        step_s: f64,
    ) -> anyhow::Result<Tally> {
        let (seq, scene) = (self.seq, self.scene);
        let bar = ProgressBar::new(work);
        bar.set_style(
            ProgressStyle::with_template(
                "{elapsed:>4} [{bar:30}] {pos}/{len} frames passed, {per_sec}, ETA {eta} {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        let start = Instant::now();
        let mut state = FrameState::new(step_s);
        let (mut stepped, mut drawn, mut last_drawn) = (0u64, 0u64, first);
        for next in seq.shard.frames(seq.range).skip_while(|n| *n < first) {
            if self.on_disk(next) {
                if self.advance.is_none() {
                    bar.inc(1);
                }
                continue;
            }
            while state.frame < next {
                let n = state.frame;
                match self.advance {
                    // Frames before it leave state this one continues: step them undrawn.
                    Some(a) => {
                        bar.set_message(format!("stepping frame {n} (state for frame {next})"));
                        renderer
                            .step(scene, a, &mut state)
                            .with_context(|| format!("frame {n}"))?;
                        stepped += 1;
                        bar.inc(1);
                    }
                    None => state.frame = next,
                }
            }
            bar.set_message(format!("frame {next}"));
            let (ldr, hdr) = renderer
                .draw(scene, self.plan, &mut state)
                .with_context(|| format!("frame {next}"))?;
            let path = self.pattern.path(next);
            let bytes = encode(seq.kind, ldr, &hdr, scene.camera.width, scene.camera.height)?;
            make_parent(&path)?;
            let out = ocean::output::OutputFile::reserve(&path)?;
            out.commit(&bytes).with_context(|| format!("frame {next}"))?;
            drawn += 1;
            last_drawn = next;
            bar.inc(1);
        }
        bar.finish_and_clear();
        let secs = start.elapsed().as_secs_f64();
        Ok(Tally { stepped, drawn, last_drawn, secs })
    }
}

/// Makes the folder of an output when it is missing (a pattern may number its folders too:
/// `out/{}/frame.png`).
fn make_parent(path: &Path) -> anyhow::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty() && !d.is_dir()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot make the folder {}", dir.display()))?;
    }
    Ok(())
}
