//! `ocean plan`: which passes a scene's frame runs and why each is in or out (DESIGN.md:
//! `--json` prints `{"passes": [{"name", "reason"}…], "skipped": […]}`, plus the objects each
//! object pass draws and the map sizes).

use std::path::PathBuf;

use ocean_core::plan::{FramePlan, OutputKind};

/// Arguments of `ocean plan`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
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
    let scene = crate::load_scene(args.scene.as_ref())?;
    let output = if args.hdr { OutputKind::Hdr } else { OutputKind::Ldr };
    let plan = if args.full {
        FramePlan::full(&scene, output)
    } else {
        FramePlan::for_frames(&scene, output, args.frames)
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&plan)?);
    } else {
        print!("{plan}");
        let o = &plan.objects;
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
    }
    Ok(())
}
