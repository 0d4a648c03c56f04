//! `ocean render`: the frame of Hu et al. 2004 on the CPU oracle or on wgpu, written as 8-bit
//! sRGB PNG or linear HDR EXR.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail};
use indicatif::{ProgressBar, ProgressStyle};
use ocean_core::plan::{FramePlan, OutputKind, Pass};
use ocean_gpu::FrameMap;

use ocean::output::parse_size;

use crate::backend::{Backend, encode};

/// Arguments of `ocean render`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    #[command(flatten)]
    system: ocean::scene_arg::SystemArg,
    /// Which renderer.
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    backend: Backend,
    /// Output file, .png (8-bit sRGB) or .exr (linear HDR).
    #[arg(short, long, default_value = "ocean.png")]
    output: PathBuf,
    /// Time of the frame in seconds (overrides the scene's `ocean.time_s`).
    #[arg(long, allow_negative_numbers = true)]
    time: Option<f64>,
    /// Image size WIDTHxHEIGHT (overrides the scene's camera).
    #[arg(long, allow_hyphen_values = true)]
    size: Option<String>,
    /// Samples per pixel N = k² (1, 4, 9, …, 256): the frame is rendered at k× the width and
    /// height (a regular k × k grid of samples in each pixel) and its linear HDR radiance
    /// box-filtered down, then tonemapped (the supersampled ground truth; on the GPU the
    /// filter and the tonemap run on the CPU, after the read-back).
    #[arg(long, default_value_t = 1, value_name = "N", allow_negative_numbers = true, value_parser = parse_spp)]
    spp: u32,
    #[command(flatten)]
    memory: ocean::memory_arg::MemoryArg,
    /// Render an animation: frames A..B (B excluded) or A..=B (B included), frame n at the
    /// scene's time plus n/FPS, one file per frame named by the output's pattern (e.g.
    /// 'out/frame_{:05}.png'). Frame n is the same whatever the range, shard or resumption.
    #[arg(long, value_name = "A..B", value_parser = parse_frames)]
    frames: Option<ocean::animation::FrameRange>,
    /// Frames per second of --frames.
    #[arg(long, default_value_t = 30.0, value_name = "F")]
    fps: f64,
    /// With --frames: render only every n-th frame, those with (frame − A) mod n = i
    /// (i counted from 0), so n machines can share a sequence with nothing to coordinate.
    #[arg(long, value_name = "i/n", value_parser = parse_shard)]
    shard: Option<ocean::animation::Shard>,
    /// Also write every float resource of the frame (wave maps, Fresnel tables, shadow,
    /// reflection and refraction maps, mip chains, foam field, HDR frame, bloom chains) as EXR
    /// with named channels, the picture, and manifest.json (what each is: pass, technique,
    /// format, size, channels, units, conventions; the scene and the plan) into DIR.
    #[arg(long, value_name = "DIR")]
    dump_passes: Option<PathBuf>,
    /// With --frames: render frames whose file exists too (by default they are kept, so a
    /// killed run resumes where it stopped).
    #[arg(long)]
    overwrite: bool,
    /// With --frames: step any number of earlier frames for a stateful scene's state (foam,
    /// spray). Without it a run that would step more than 100,000 frames undrawn is refused
    /// before it starts.
    #[arg(long)]
    replay_any: bool,
}

/// Runs `ocean render`.
pub fn run(args: Args) -> anyhow::Result<()> {
    if args.frames.is_none() && (args.shard.is_some() || args.overwrite || args.replay_any) {
        bail!("--shard, --overwrite and --replay-any belong to an animation: add --frames A..B");
    }
    if args.dump_passes.is_some() && (args.frames.is_some() || args.spp != 1) {
        bail!("--dump-passes dumps one frame at 1 sample per pixel: leave out --frames and --spp");
    }
    let kind = match args.output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase) {
        Some(e) if e == "png" => OutputKind::Ldr,
        Some(e) if e == "exr" => OutputKind::Hdr,
        _ => bail!("output {} must end in .png or .exr", args.output.display()),
    };
    if let Some(range) = args.frames {
        return crate::frames::run(crate::frames::Sequence {
            scene: args.scene.as_ref(),
            system: &args.system,
            time: args.time,
            size: args.size.as_deref(),
            spp: args.spp,
            memory: &args.memory,
            backend: args.backend,
            kind,
            pattern: &args.output,
            range,
            fps: args.fps,
            shard: args.shard.unwrap_or_default(),
            overwrite: args.overwrite,
            replay_any: args.replay_any,
        });
    }
    // Before any work: a render of minutes must not end in "cannot write".
    let out = ocean::output::OutputFile::reserve(&args.output)?;
    args.memory.limit_inputs();
    let mut scene = ocean::scene_arg::load_scene(args.scene.as_ref(), &args.system)?;
    if let Some(t) = args.time {
        scene.ocean.time_s = t;
    }
    if let Some(s) = &args.size {
        (scene.camera.width, scene.camera.height) = parse_size(s)?;
    }
    ocean::scene_arg::revalidate(&scene, "--time/--size")?;
    let (w, h) = (scene.camera.width, scene.camera.height);
    let k = ocean_core::supersample::grid_side(args.spp).map_err(|e| anyhow!("--spp: {e}"))?;
    let (scene, kind, output_kind) = if k > 1 {
        let mut sampled = scene.clone();
        sampled.camera.width = w * k;
        sampled.camera.height = h * k;
        ocean::scene_arg::revalidate(
            &sampled,
            &format!("--spp {} (a {}×{} frame)", args.spp, w * k, h * k),
        )?;
        (sampled, OutputKind::Hdr, kind)
    } else {
        (scene, kind, kind)
    };
    args.memory.check(&scene, &FramePlan::new(&scene, kind), &[args.backend.memory()])?;
    let start = Instant::now();
    let (ldr, hdr, passes, backend) = match args.backend {
        Backend::Cpu => {
            let r = render_cpu(&scene, kind, start)?;
            let passes = r
                .buffers
                .timings
                .iter()
                .map(|(p, d)| format!("{} {:.0} ms", p.name(), d.as_secs_f64() * 1e3))
                .collect();
            if let Some(dir) = &args.dump_passes {
                let map = |id| r.buffers.map(id).map(|(w, h, t)| ((w, h), t));
                let ldr = r.ldr.as_deref();
                dump(dir, &scene, args.scene.as_deref(), &r.plan, None, &map, ldr, None)?;
            }
            (r.ldr, r.buffers.hdr.color, passes, "CPU".to_owned())
        }
        Backend::Gpu => {
            render_gpu(&scene, kind, args.dump_passes.as_deref(), args.scene.as_deref())?
        }
    };
    let (ldr, hdr) = if k > 1 {
        let hdr = ocean_core::supersample::box_filter(&hdr, w, h, k);
        let ldr = (output_kind == OutputKind::Ldr)
            .then(|| {
                let mut t = ocean_core::tonemap::TonemapUniforms::for_image(
                    scene.camera.exposure,
                    &scene.post,
                    w,
                    h,
                )?;
                // Post `bloom` of the filtered frame at the output's size (the pyramid and
                // the vignette belong to the picture, not to the supersampled frame).
                let mut out = scene.clone();
                (out.camera.width, out.camera.height) = (w, h);
                let glow = FramePlan::new(&out, OutputKind::Ldr).runs(Pass::Bloom).then(|| {
                    let inputs = ocean_core::graph::BloomInputs::new(&out);
                    t.bloom_scale = inputs.scale(&out);
                    let frame = ocean_cpu::sampler::Texture2D::new(w, h, hdr.clone());
                    ocean_cpu::shaders::bloom::level0(
                        &ocean_cpu::shaders::bloom::dispatch(&frame, &inputs).1,
                    )
                });
                let rgba = match &glow {
                    Some(g) => {
                        ocean_cpu::shaders::tonemap::tonemap_to_rgba8_with_bloom(&hdr, w, h, &t, g)
                    }
                    None => ocean_cpu::shaders::tonemap::tonemap_to_rgba8(&hdr, w, h, &t),
                };
                anyhow::Ok(rgba)
            })
            .transpose()?;
        (ldr, hdr)
    } else {
        (ldr, hdr)
    };
    let bytes = encode(output_kind, ldr, &hdr, w, h)?;
    out.commit(&bytes)?;
    let passes: Vec<String> = passes;
    let spp = if k > 1 { format!(", {} spp", args.spp) } else { String::new() };
    eprintln!(
        "wrote {} ({w}×{h}{spp}, {backend}, {:.2} s: {})",
        args.output.display(),
        start.elapsed().as_secs_f64(),
        passes.join(", ")
    );
    Ok(())
}

/// What a still frame made: the 8-bit picture (if the plan tonemaps), the HDR frame, each
/// pass's time, and the back end's name.
type Rendered = (Option<Vec<u8>>, Vec<[f32; 4]>, Vec<String>, String);

/// The GPU render of a still frame, and its dump (`--dump-passes DIR`) with the spray's
/// probed step.
fn render_gpu(
    scene: &ocean_core::scene::Scene,
    kind: OutputKind,
    dump_to: Option<&std::path::Path>,
    path: Option<&std::path::Path>,
) -> anyhow::Result<Rendered> {
    let mut renderer = ocean_gpu::Renderer::new()?;
    let plan = FramePlan::new(scene, kind);
    let readback =
        if dump_to.is_some() { ocean_gpu::Readback::All } else { ocean_gpu::Readback::Output };
    let f = renderer.run_with(scene, &plan, readback)?;
    if let Some(dir) = dump_to {
        let map = |id| f.map(id).map(|m| ((m.width, m.height), &m.texels[..]));
        let adapter = Some(renderer.adapter());
        // One more step of the spray on the device, for the envelope's verdict on it.
        let displacement = map(ocean_core::plan::ResourceId::Displacement);
        let spray = ocean::verdict::spray::probe(&renderer, scene, &plan, displacement)?;
        let ldr = f.ldr.as_deref();
        dump(dir, scene, path, &plan, adapter, &map, ldr, spray.as_ref())?;
    }
    let hdr = f.map(FrameMap::Hdr).map(|m| m.texels.clone()).unwrap_or_default();
    let passes = f
        .gpu_timings
        .iter()
        .map(|(p, d)| format!("{} {:.1} ms", p.name(), d.as_secs_f64() * 1e3))
        .collect();
    Ok((f.ldr, hdr, passes, format!("GPU {}", f.adapter.name)))
}

/// `--dump-passes`: the frame's resources and manifest into `dir` (`ocean::dump`), with the
/// spray's probed step where the GPU ran one.
#[expect(clippy::too_many_arguments, reason = "a dump's parts, each from its back end")]
fn dump(
    dir: &std::path::Path,
    scene: &ocean_core::scene::Scene,
    path: Option<&std::path::Path>,
    plan: &FramePlan,
    adapter: Option<&ocean_gpu::AdapterReport>,
    map: &ocean::dump::MapOf<'_>,
    ldr: Option<&[u8]>,
    spray: Option<&ocean::verdict::spray::SprayProbe>,
) -> anyhow::Result<()> {
    let (shown, text) = match path {
        Some(p) => (
            p.display().to_string(),
            ocean_core::input::read_text(p, ocean_core::scene::MAX_SCENE_FILE_BYTES)
                .map_err(|e| anyhow!("cannot read {e}"))?,
        ),
        None => ("(the built-in default scene)".to_owned(), String::new()),
    };
    let files = ocean::dump::write(dir, scene, (&shown, &text), plan, adapter, map, ldr, spray)?;
    eprintln!("dumped {} file(s) to {}: {}", files.len(), dir.display(), files.join(", "));
    Ok(())
}

/// The CPU render with a progress bar for renders that take over a second.
fn render_cpu(
    scene: &ocean_core::scene::Scene,
    kind: OutputKind,
    start: Instant,
) -> anyhow::Result<ocean_cpu::Rendered> {
    let mut bar: Option<ProgressBar> = None;
    let total = Pass::ALL.len() as u64;
    let mut on_pass = |pass: Pass| {
        if bar.is_none() && start.elapsed() > Duration::from_secs(1) {
            let b = ProgressBar::new(total);
            b.set_style(
                ProgressStyle::with_template("{elapsed:>4} [{bar:30}] {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            bar = Some(b);
        }
        if let Some(b) = &bar {
            b.set_message(pass.name());
            b.set_position(Pass::ALL.iter().position(|p| *p == pass).unwrap_or(0) as u64);
        }
    };
    let rendered = ocean_cpu::render_scene(scene, kind, &mut on_pass)?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    Ok(rendered)
}

/// `--frames`.
fn parse_frames(s: &str) -> Result<ocean::animation::FrameRange, String> {
    ocean::animation::FrameRange::parse(s).map_err(|e| e.to_string())
}

/// `--shard`.
fn parse_shard(s: &str) -> Result<ocean::animation::Shard, String> {
    ocean::animation::Shard::parse(s).map_err(|e| e.to_string())
}

/// `--spp`: a count, with a range error (not clap's "unexpected argument") for a negative one.
fn parse_spp(s: &str) -> Result<u32, String> {
    s.trim().parse::<u32>().map_err(|_| {
        format!(
            "`{s}` is not a sample count: a perfect square from 1 to {}",
            ocean_core::supersample::MAX_SPP
        )
    })
}
