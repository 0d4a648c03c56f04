//! `ocean compare`: renders a scene on the CPU oracle and on the GPU, prints the per-pass and
//! final metrics against docs/design.md's tolerances, writes both pictures, their difference and
//! FLIP maps and a JSON summary, and exits non-zero beyond tolerance.

use std::path::PathBuf;

use anyhow::{Context, bail};
use ocean::verdict::{GpuSide, envelope_verdict};
use ocean_verify::cross_check::{artefacts, check_scene, map_pass};
use ocean_verify::envelope::Tolerance;

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
    /// Compare a folder in the layout of `ocean render --dump-passes` (from another engine,
    /// or another run) with the CPU oracle's frame of the scene, resource by resource, under
    /// `--tolerance` (by default the exact rule for a software adapter's dump, the envelope
    /// for any other or an unknown one); no GPU is used. The scene is SCENE, else the one in
    /// DIR/manifest.json, else the default.
    #[arg(long, value_name = "DIR")]
    against: Option<PathBuf>,
    /// With --against: a resource of the oracle's plan that the dump does not hold (not in
    /// its manifest's list) is a failure; without it, it is reported `not in dump`.
    #[arg(long, requires = "against")]
    require_all: bool,
    /// Plant a bug: the GPU runs its WGSL with the named one-line change (the oracle stays
    /// correct), to see that the comparison catches it. `--mutants` lists them.
    #[arg(long, value_name = "NAME", conflicts_with = "against")]
    mutant: Option<String>,
    /// How the GPU's resources are held: `exact` (docs/design.md's float and picture rows,
    /// lavapipe's figures) or `envelope` (what any conformant GPU may produce:
    /// docs/tolerances.md: every float resource and the 8-bit picture; pixels or resources
    /// without an envelope, such as the spray's sprites where the pool the GPU drew is not
    /// known, are reported as not judged). Default: exact on a software adapter, the envelope
    /// on hardware — with --against, the dump's adapter, the envelope when the manifest does
    /// not say.
    #[arg(long, value_enum, conflicts_with = "mutants")]
    tolerance: Option<ToleranceArg>,
    /// List the planted bugs (name, file, what each changes, the scene that runs it) and exit.
    #[arg(long, conflicts_with_all = ["against", "mutant"])]
    mutants: bool,
}

/// `--tolerance`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum ToleranceArg {
    /// docs/design.md's float and picture rows.
    Exact,
    /// The envelope of any conformant GPU.
    Envelope,
}

impl ToleranceArg {
    fn resolve(arg: Option<Self>, software: Option<bool>) -> Tolerance {
        match arg {
            Some(ToleranceArg::Exact) => Tolerance::Exact,
            Some(ToleranceArg::Envelope) => Tolerance::Envelope,
            None => Tolerance::for_software(software),
        }
    }
}

/// Runs `ocean compare`.
pub fn run(args: Args) -> anyhow::Result<()> {
    args.memory.limit_inputs();
    if args.mutants {
        for m in ocean_core::mutants::MUTANTS {
            println!("{:<28} {:<28} {:<22} {}", m.name, m.file, m.scene, m.changes);
        }
        return Ok(());
    }
    let mutant = args
        .mutant
        .as_deref()
        .map(ocean_core::mutants::find)
        .transpose()
        .map_err(|e| anyhow::anyhow!("--mutant: {e}"))?;
    ocean_core::mutants::activate(mutant);
    if let Some(dir) = &args.against {
        return against(&args, dir);
    }
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
    let tolerance = ToleranceArg::resolve(args.tolerance, Some(check.adapter.is_software));
    let mut envelope_json = None;
    let failures = match tolerance {
        Tolerance::Exact => {
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
            check.failures()
        }
        Tolerance::Envelope => {
            use ocean_core::plan::ResourceId;
            println!("limits: the envelope of any conformant GPU (docs/tolerances.md)");
            let gpu = &renders.gpu;
            let plan = &gpu.plan;
            let ran: Vec<ResourceId> = ocean::dump::dumped(plan);
            let mut side = GpuSide {
                maps: ResourceId::MAPS
                    .into_iter()
                    .filter_map(|id| {
                        gpu.map(id).map(|m| (id, ((m.width, m.height), &m.texels[..])))
                    })
                    .collect(),
                ldr: gpu.ldr.as_deref(),
                oracle_hdr: Some(&renders.cpu.buffers.hdr.color),
                precision: ocean::verdict::precision_of(&check.adapter.name, &check.adapter.vendor),
                first_failure: false,
                water_every: 1,
                spray: None,
            };
            let probe = ocean::verdict::spray::probe(
                &renderer,
                &scene,
                plan,
                side.map(ResourceId::Displacement),
            )?;
            side.spray = probe.as_ref();
            let v = envelope_verdict(&scene, plan, &side, &ran)?;
            for l in &v.lines {
                println!("{l}");
            }
            envelope_json = Some(serde_json::json!({
                "scene": name,
                "adapter": check.adapter.name,
                "tolerance": "envelope",
                "resources": v.json,
            }));
            v.failures
        }
    };
    std::fs::create_dir_all(&args.out_dir)
        .with_context(|| format!("cannot make {}", args.out_dir.display()))?;
    for (file, bytes) in artefacts(&check, &renders)? {
        ocean::output::write_atomic(&args.out_dir.join(file), &bytes)?;
    }
    if let Some(json) = envelope_json {
        ocean::output::write_atomic(
            &args.out_dir.join(format!("{name}.envelope.json")),
            serde_json::to_string_pretty(&json)?.as_bytes(),
        )?;
    }
    println!(
        "wrote {}/{name}.{{cpu,gpu,diff,flip}}.png and {name}.json ({} tolerance)",
        args.out_dir.display(),
        tolerance.name()
    );
    if let Some(m) = mutant {
        if failures.is_empty() {
            println!("planted bug {} ({}: {}) NOT caught", m.name, m.file, m.changes);
        } else {
            println!("planted bug {} caught by {} check(s)", m.name, failures.len());
        }
    }
    if !failures.is_empty() {
        bail!("CPU and GPU differ beyond tolerance:\n{}", failures.join("\n"));
    }
    Ok(())
}

/// The dump's 8-bit picture (`DIR/ldr.png`) as RGBA, `None` where the dump has none.
///
/// # Errors
/// A file that is not a PNG within the decode budget, or not `w`×`h`.
fn dumped_picture(dir: &std::path::Path, w: u32, h: u32) -> anyhow::Result<Option<Vec<u8>>> {
    let path = dir.join("ldr.png");
    if std::fs::symlink_metadata(&path).is_err() {
        return Ok(None);
    }
    let image = ocean_core::input::decode_png(&path).map_err(|e| anyhow::anyhow!("{e}"))?;
    if (image.width(), image.height()) != (w, h) {
        bail!(
            "{} is {}x{}, the oracle's picture {w}x{h}",
            path.display(),
            image.width(),
            image.height()
        );
    }
    Ok(Some(image.to_rgba8().into_raw()))
}

/// `ocean compare --against DIR`: the oracle's frame against a dump folder.
fn against(args: &Args, dir: &std::path::Path) -> anyhow::Result<()> {
    use ocean_core::plan::OutputKind;

    if !dir.is_dir() {
        bail!("--against {}: not a folder (a dump of `ocean render --dump-passes`)", dir.display());
    }
    let manifest = ocean::dump::read_manifest(dir)?.unwrap_or_default();
    let mut scene = manifest.scene(
        &format!("{}/manifest.json", dir.display()),
        args.scene.as_ref(),
        &args.system,
    )?;
    if let Some(s) = &args.size {
        (scene.camera.width, scene.camera.height) = ocean::output::parse_size(s)?;
    }
    ocean::scene_arg::revalidate(&scene, "--size, or the manifest's frame")?;
    let plan = ocean_core::plan::FramePlan::new(&scene, OutputKind::Ldr);
    args.memory.check(&scene, &plan, &[ocean_core::plan::memory::MemoryBackend::Cpu])?;
    std::fs::create_dir_all(&args.out_dir)
        .with_context(|| format!("cannot make {}", args.out_dir.display()))?;
    let made_by = made_by(&manifest);
    let software = manifest.adapter.as_ref().and_then(|a| a["software"].as_bool());
    let tolerance = ToleranceArg::resolve(args.tolerance, software);
    if tolerance == Tolerance::Envelope {
        return against_envelope(args, dir, &manifest, &scene, &plan, &made_by);
    }
    println!(
        "{} (made by {made_by}) against the CPU oracle ({}x{}, limits: rel {:e} / abs {:e}, one \
         binary16 step on rgba16float resources)",
        dir.display(),
        scene.camera.width,
        scene.camera.height,
        ocean_verify::compare::FLOAT_REL,
        ocean_verify::compare::FLOAT_ABS
    );
    let r = ocean_cpu::render_scene(&scene, OutputKind::Ldr, &mut |_| {})?;
    let mut found = Found::default();
    found.compare_resources(args, dir, &manifest, &plan, &r)?;
    // The picture: the dump's `ldr.png` against the oracle's, by the picture row of the
    // adapter that made it (the manifest's `software`; the hardware row when it does not say).
    if let Some(ours) = r.ldr.as_deref() {
        found.compare_picture(dir, (scene.camera.width, scene.camera.height), software, ours);
    }
    let Found { mut failures, summary, not_in_dump } = found;
    if args.require_all && !not_in_dump.is_empty() {
        failures.push(format!("not in dump (--require-all): {}", not_in_dump.join(", ")));
    }
    let json = serde_json::json!({
        "against": dir.display().to_string(),
        "adapter": manifest.adapter,
        "resources": summary,
        "not_in_dump": not_in_dump,
    });
    ocean::output::write_atomic(
        &args.out_dir.join("against.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;
    println!("wrote {}/<resource>.diff.png and against.json", args.out_dir.display());
    if !failures.is_empty() {
        bail!(
            "{} differs from the oracle beyond tolerance:\n{}",
            dir.display(),
            failures.join("\n")
        );
    }
    Ok(())
}

/// The adapter a dump's manifest says made it, for the report's first line.
fn made_by(manifest: &ocean::dump::Manifest) -> String {
    manifest.adapter.as_ref().map_or_else(
        || "an unknown adapter".to_owned(),
        |a| {
            let s = |k: &str| a[k].as_str().unwrap_or("?").to_owned();
            format!(
                "{} ({}, {}, driver {})",
                s("name"),
                s("backend"),
                s("device_type"),
                s("driver")
            )
        },
    )
}

/// What `--against` found, resource by resource.
#[derive(Default)]
struct Found {
    /// One line per resource beyond tolerance or unreadable.
    failures: Vec<String>,
    /// The JSON entries, one per resource compared.
    summary: Vec<serde_json::Value>,
    /// The oracle's resources the dump does not hold.
    not_in_dump: Vec<&'static str>,
}

impl Found {
    /// The oracle's float resources `r` against the dump's, each difference map written to
    /// `args.out_dir`; what the dump lists that the oracle's plan does not make is reported,
    /// not judged.
    fn compare_resources(
        &mut self,
        args: &Args,
        dir: &std::path::Path,
        manifest: &ocean::dump::Manifest,
        plan: &ocean_core::plan::FramePlan,
        r: &ocean_cpu::Rendered,
    ) -> anyhow::Result<()> {
        use ocean::output::{encode_png, write_atomic};
        use ocean_verify::compare::compare_float_in;
        use ocean_verify::cross_check::float_diff_png;

        let planned = ocean::dump::dumped(plan);
        for name in manifest.resources.iter().flatten() {
            if !planned.iter().any(|id| id.name() == name) {
                println!("  [{:<14}] {name:<20} not in the oracle's plan (not compared)", "");
            }
        }
        for id in planned {
            let Some((w, h, ours)) = r.buffers.map(id) else { continue };
            let pass = id.writer().map_or("", |p| p.name());
            // The resources the manifest lists; without a list, the files that are there.
            let held = match &manifest.resources {
                Some(list) => list.iter().any(|n| n == id.name()),
                None => std::fs::symlink_metadata(dir.join(ocean::dump::file_name(id))).is_ok(),
            };
            if !held {
                println!("  [{pass:<14}] {:<20} not in dump", id.name());
                self.not_in_dump.push(id.name());
                continue;
            }
            let theirs = match ocean::dump::read(dir, id) {
                Ok(t) => t,
                Err(e) => {
                    println!("  [{pass:<14}] {:<20} MISSING {e:#}", id.name());
                    self.failures.push(format!("{}: {e:#}", id.name()));
                    self.summary.push(serde_json::json!({"name": id.name(), "passed": false, "error": format!("{e:#}")}));
                    continue;
                }
            };
            let format = plan.resource(id).map_or(Default::default(), |r| r.format.storage());
            let stats =
                compare_float_in(id.name(), true, ((w, h), ours), (theirs.0, &theirs.1), format);
            println!("  [{pass:<14}] {}", stats.line());
            if theirs.0 == (w, h) {
                let png = encode_png(float_diff_png(ours, &theirs.1, format), w, h)?;
                write_atomic(&args.out_dir.join(format!("{}.diff.png", id.name())), &png)?;
            }
            if !stats.passed() {
                self.failures.push(stats.line());
            }
            self.summary.push(stats.to_json());
        }
        Ok(())
    }

    /// The dump's `ldr.png` against the oracle's picture `ours` of size `(w, h)`, by the
    /// picture row of the adapter that made it (`software`; the hardware row when unknown).
    fn compare_picture(
        &mut self,
        dir: &std::path::Path,
        (w, h): (u32, u32),
        software: Option<bool>,
        ours: &[u8],
    ) {
        let limits = if software == Some(true) {
            ocean_verify::compare::ImageLimits::SOFTWARE
        } else {
            ocean_verify::compare::ImageLimits::HARDWARE
        };
        match dumped_picture(dir, w, h) {
            Ok(None) => {
                println!("  [{:<14}] {:<20} not in dump", "tonemap", "ldr");
                self.not_in_dump.push("ldr");
            }
            Ok(Some(theirs)) => {
                let stats = ocean_verify::compare::compare_image(ours, &theirs, w, h);
                println!("  [{:<14}] {} ({})", "tonemap", stats.line(&limits), limits.origin);
                let failed = stats.failures(&limits);
                if !failed.is_empty() {
                    self.failures.push(format!("ldr: {}", failed.join("; ")));
                }
                let mut json = stats.to_json(&limits);
                json["name"] = "ldr".into();
                json["limits"] = limits.origin.into();
                self.summary.push(json);
            }
            Err(e) => {
                println!("  [{:<14}] {:<20} MISSING {e:#}", "tonemap", "ldr");
                self.failures.push(format!("ldr: {e:#}"));
                self.summary.push(
                    serde_json::json!({"name": "ldr", "passed": false, "error": format!("{e:#}")}),
                );
            }
        }
    }
}

/// `--against DIR --tolerance envelope`: the dump's picture against the `tonemap` envelope of
/// the dump's own HDR frame (and bloom); its float resources listed as not judged (their passes
/// have no envelope yet). The oracle's frame is not rendered: the envelope is of the dump's
/// inputs.
fn against_envelope(
    args: &Args,
    dir: &std::path::Path,
    manifest: &ocean::dump::Manifest,
    scene: &ocean_core::scene::Scene,
    plan: &ocean_core::plan::FramePlan,
    made_by: &str,
) -> anyhow::Result<()> {
    use ocean_core::plan::ResourceId;
    println!(
        "{} (made by {made_by}), {}x{}: held to the envelope of any conformant GPU \
         (docs/tolerances.md)",
        dir.display(),
        scene.camera.width,
        scene.camera.height
    );
    let listed = |id: ResourceId| match &manifest.resources {
        Some(list) => list.iter().any(|n| n == id.name()),
        None => std::fs::symlink_metadata(dir.join(ocean::dump::file_name(id))).is_ok(),
    };
    let mut held = Vec::new();
    let mut not_in_dump = Vec::new();
    for id in ocean::dump::dumped(plan) {
        if listed(id) {
            held.push(id);
        } else {
            println!(
                "  [{:<14}] {:<20} not in dump",
                id.writer().map_or("", |p| p.name()),
                id.name()
            );
            not_in_dump.push(id.name());
        }
    }
    let mut read = Vec::new();
    for id in ResourceId::MAPS.into_iter().filter(|&id| listed(id)) {
        read.push((id, ocean::dump::read(dir, id)?));
    }
    let (w, h) = (scene.camera.width, scene.camera.height);
    if let Some((_, ((hw, hh), _))) = read.iter().find(|(id, _)| *id == ResourceId::Hdr)
        && (*hw, *hh) != (w, h)
    {
        bail!("{}: hdr is {hw}x{hh}, the frame {w}x{h}", dir.display());
    }
    let ldr = dumped_picture(dir, w, h)?;
    // The oracle's frame says which pixels hold the sky.
    let oracle = ocean_cpu::render_scene(scene, ocean_core::plan::OutputKind::Ldr, &mut |_| {})?;
    let side = GpuSide {
        maps: read.iter().map(|(id, (size, t))| (*id, (*size, &t[..]))).collect(),
        ldr: ldr.as_deref(),
        oracle_hdr: Some(&oracle.buffers.hdr.color[..]),
        precision: manifest.adapter.as_ref().map_or(ocean::verdict::precision_of("", ""), |a| {
            ocean::verdict::precision_of(
                a["name"].as_str().unwrap_or(""),
                a["vendor"].as_str().unwrap_or(""),
            )
        }),
        first_failure: false,
        water_every: 1,
        spray: None,
    };
    // The spray's step, where the dump holds one (`ocean render --dump-passes` on a GPU).
    let spray = ocean::dump::read_spray_step(dir, manifest, scene, plan)?;
    let side = GpuSide { spray: spray.as_ref(), ..side };
    let v = envelope_verdict(scene, plan, &side, &held)?;
    for l in &v.lines {
        println!("{l}");
    }
    let (mut failures, json) = (v.failures, v.json);
    if args.require_all && !not_in_dump.is_empty() {
        failures.push(format!("not in dump (--require-all): {}", not_in_dump.join(", ")));
    }
    let json = serde_json::json!({
        "against": dir.display().to_string(),
        "adapter": manifest.adapter,
        "tolerance": "envelope",
        "resources": json,
        "not_in_dump": not_in_dump,
    });
    ocean::output::write_atomic(
        &args.out_dir.join("against.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;
    println!("wrote {}/against.json", args.out_dir.display());
    if !failures.is_empty() {
        bail!(
            "{} leaves the envelope of any conformant GPU:\n{}",
            dir.display(),
            failures.join("\n")
        );
    }
    Ok(())
}
