//! `ocean heightfield`: the displacement map of a scene's ocean at a time, as EXR
//! (DESIGN.md: N×N, pixel (i, j) at x = i·L/N, z = j·L/N, channels `height`, `disp_x`,
//! `disp_z`, `slope_x`, `slope_z`, `jacobian`). Under waves `fft` the maps the FFT makes;
//! under waves `gerstner` the sum of the waves evaluated at the same N×N points of the window
//! [0, L)² (the waves are not periodic, so the window is only where the samples lie).

use std::path::PathBuf;

use ocean_core::frame::surface_query;
use ocean_core::plan::{FramePlan, OutputKind, Stage};
use ocean_core::waves::{SurfaceSample, Synthesizer, WaveMaps};

use ocean::output::{Channel, encode_exr, require_extension};

/// Arguments of `ocean heightfield`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    /// Time in seconds (overrides the scene's `ocean.time_s`).
    #[arg(long, allow_negative_numbers = true)]
    time: Option<f64>,
    /// Seed of the random amplitudes (overrides the scene's `ocean.seed`), 0 or more.
    #[arg(long, allow_negative_numbers = true, value_parser = ocean::output::parse_seed)]
    seed: Option<u64>,
    /// Output EXR file.
    #[arg(short, long)]
    output: PathBuf,
}

/// Runs `ocean heightfield`.
pub fn run(args: Args) -> anyhow::Result<()> {
    require_extension(&args.output, "exr")?;
    let out = ocean::output::OutputFile::reserve(&args.output)?;
    let mut scene = crate::load_scene(args.scene.as_ref())?;
    if let Some(t) = args.time {
        scene.ocean.time_s = t;
    }
    if let Some(s) = args.seed {
        scene.ocean.seed = s;
    }
    ocean::scene_arg::revalidate(&scene, "--time/--seed")?;
    let ocean = &scene.ocean;
    let plan = FramePlan::new(&scene, OutputKind::Hdr);
    // Waves summed per vertex (`gerstner`, `coastal`): the height query on the map's grid.
    let (n, channels) = if ocean_core::plan::waves_per_vertex(plan.techniques.of(Stage::Waves).name)
    {
        let n = ocean.resolution as usize;
        let sea = surface_query(&scene, &plan, ocean.time_s)?;
        let step = ocean.patch_size_m / n as f64;
        let samples: Vec<SurfaceSample> =
            (0..n * n).map(|p| sea.sample((p % n) as f64 * step, (p / n) as f64 * step)).collect();
        let field = |f: fn(&SurfaceSample) -> f64| samples.iter().map(|s| f(s) as f32).collect();
        let names = WaveMaps::<f32>::FIELD_NAMES;
        let data: [Vec<f32>; 6] = [
            field(|s| s.height),
            field(|s| s.disp_x),
            field(|s| s.disp_z),
            field(|s| s.slope_x),
            field(|s| s.slope_z),
            field(|s| s.jacobian),
        ];
        (n, names.iter().zip(data).map(|(name, data)| Channel { name, data }).collect())
    } else {
        let modes = ocean.displacement_modes()?;
        let n = modes.resolution();
        let maps =
            Synthesizer::<f32>::new(n)?.synthesize(&modes, ocean.time_s, ocean.choppiness)?;
        (
            n,
            maps.fields()
                .iter()
                .map(|(name, data)| Channel { name, data: data.to_vec() })
                .collect(),
        )
    };
    out.commit(&encode_exr(n, n, channels)?)?;
    eprintln!(
        "wrote {} ({n}×{n}, L = {} m, t = {} s, seed {})",
        args.output.display(),
        ocean.patch_size_m,
        ocean.time_s,
        ocean.seed
    );
    Ok(())
}
