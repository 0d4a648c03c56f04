//! `ocean plan`: the frame graph of a scene: its system and the technique of every stage, the
//! passes it runs and why each is in or out, and the resources with their sizes (docs/design.md:
//! `--json` prints `{"system": …, "techniques": {stage: technique, …}, "passes": [{"name",
//! "reason", …}…], "skipped": […], "resources": […]}`, plus the objects each object pass
//! draws).

use std::path::PathBuf;

use ocean_core::plan::{FramePlan, OutputKind};

/// Arguments of `ocean plan`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    #[command(flatten)]
    system: ocean::scene_arg::SystemArg,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
    /// Plan for EXR (linear HDR) output: no tonemap pass.
    #[arg(long)]
    hdr: bool,
    /// Plan each frame of an animation of this many frames (a looping sea then precomputes
    /// its cycle).
    #[arg(long, default_value_t = 1)]
    frames: u64,
    /// The full plan: every pruning rule off (what the pruned plan is tested against).
    #[arg(long)]
    full: bool,
}

/// Runs `ocean plan`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let scene = ocean::scene_arg::load_scene(args.scene.as_ref(), &args.system)?;
    let output = if args.hdr { OutputKind::Hdr } else { OutputKind::Ldr };
    let plan = if args.full {
        FramePlan::full(&scene, output)
    } else {
        FramePlan::for_frames(&scene, output, args.frames)
    };
    if args.json {
        // `objects` (each object pass's list) stays a top-level key, as before the frame
        // graph moved the lists into the passes.
        let mut v = serde_json::to_value(&plan)?;
        v["objects"] = serde_json::to_value(plan.objects())?;
        let e = ocean_core::plan::memory::MemoryEstimate::of(
            &scene,
            &plan,
            ocean_core::plan::memory::MemoryBackend::Cpu,
        );
        v["memory_estimate_bytes"] = serde_json::to_value(e.total())?;
        // The passes an animation runs on a frame it steps but does not draw (empty: none).
        let steps: Vec<&str> = plan.state_passes().iter().map(|p| p.name()).collect();
        v["state_passes"] = serde_json::to_value(steps)?;
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        print!("{plan}");
        let o = plan.objects();
        println!(
            "  objects drawn: shadow_map {:?}, reflection_map {:?} ({}×{}), refraction_map {:?}, \
             objects {:?}",
            o.shadow_map,
            o.reflection_map,
            plan.reflection_map_size[0],
            plan.reflection_map_size[1],
            o.refraction_map,
            o.objects
        );
        let sizes: Vec<String> = plan
            .resources
            .iter()
            .map(|r| {
                let unused = if r.written { "" } else { " (placeholder)" };
                match r.format {
                    ocean_core::plan::Format::Uniform => {
                        format!("{} {} bytes{unused}", r.id.name(), r.size[0])
                    }
                    _ => format!("{} {}×{}{unused}", r.id.name(), r.size[0], r.size[1]),
                }
            })
            .collect();
        println!("  resources: {}", sizes.join(", "));
        let kept: Vec<&str> = plan.state_passes().iter().map(|p| p.name()).collect();
        if !kept.is_empty() {
            println!(
                "  state: frames carry state to the next one; an animation steps the frames it \
                 does not draw with {}",
                kept.join(", ")
            );
        } else {
            println!("  state: none carried between frames (an animation jumps to its frames)");
        }
        use ocean_core::plan::memory::{MemoryBackend, MemoryEstimate, bytes};
        let e = MemoryEstimate::of(&scene, &plan, MemoryBackend::Cpu);
        let largest = e.largest().map_or(String::new(), |i| {
            format!("; largest {} {} (`{}`)", i.what, bytes(i.bytes), i.key)
        });
        println!("  memory: {} estimated on the CPU{largest}", bytes(e.total()));
    }
    Ok(())
}
