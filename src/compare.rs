//! `ocean compare`: renders a scene on the CPU oracle and on the GPU, prints the per-pass and
//! final metrics against DESIGN.md's tolerances, writes both pictures, their difference and
//! FLIP maps and a JSON summary, and exits non-zero beyond tolerance.

use std::path::PathBuf;

use anyhow::{Context, bail};
use ocean_verify::cross_check::{check_scene, map_pass, write_artefacts};

/// Arguments of `ocean compare`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    #[command(flatten)]
    system: ocean::scene_arg::SystemArg,
    /// Folder for the images and the JSON summary (created if missing).
    #[arg(long, default_value = "ocean-compare")]
    out_dir: PathBuf,
    /// Image size WIDTHxHEIGHT (overrides the scene's camera).
    #[arg(long, allow_hyphen_values = true)]
    size: Option<String>,
    #[command(flatten)]
    memory: ocean::memory_arg::MemoryArg,
}

/// Runs `ocean compare`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let mut scene = ocean::scene_arg::load_scene(args.scene.as_ref(), &args.system)?;
    if let Some(s) = &args.size {
        (scene.camera.width, scene.camera.height) = ocean::output::parse_size(s)?;
    }
    ocean::scene_arg::revalidate(&scene, "--size")?;
    {
        use ocean_core::plan::memory::MemoryBackend;
        let plan = ocean_core::plan::FramePlan::new(&scene, ocean_core::plan::OutputKind::Ldr);
        args.memory.check(&scene, &plan, &[MemoryBackend::Cpu, MemoryBackend::Gpu])?;
    }
    let name = args
        .scene
        .as_ref()
        .and_then(|p| p.file_stem())
        .map_or_else(|| "default".to_owned(), |s| s.to_string_lossy().into_owned());
    // The GPU runs the plan's `waves` kernel as the oracle does: waves.wgsl (its mirror on the
    // CPU; on lavapipe the same bits), or ocean-core's synthesis uploaded where the plan says.
    let gpu = ocean_gpu::Gpu::new()?;
    let mut renderer = ocean_gpu::Renderer::with_gpu(gpu, ocean_gpu::WaveSynthesis::GpuFft)?;
    let (check, renders) = check_scene(&mut renderer, &name, &scene)?;
    println!(
        "{name} {}x{}: CPU oracle vs {} (waves: {})",
        check.size.0,
        check.size.1,
        check.adapter,
        check.wave_source.unwrap_or("skipped")
    );
    println!(
        "limits: float maps rel {:e} / abs {:e}; picture: {}",
        ocean_verify::compare::FLOAT_REL,
        ocean_verify::compare::FLOAT_ABS,
        check.image_limits.origin
    );
    for m in &check.maps {
        let pass = map_pass(&m.name).map_or("", |p| p.name());
        println!("  [{pass:<14}] {}", m.line());
    }
    if let Some(i) = &check.image {
        println!("  [{:<14}] {}", "tonemap", i.line(&check.image_limits));
    }
    write_artefacts(&args.out_dir, &check, &renders)
        .with_context(|| format!("cannot write to {}", args.out_dir.display()))?;
    println!("wrote {}/{name}.{{cpu,gpu,diff,flip}}.png and {name}.json", args.out_dir.display());
    let failures = check.failures();
    if !failures.is_empty() {
        bail!("CPU and GPU differ beyond tolerance:\n{}", failures.join("\n"));
    }
    Ok(())
}
