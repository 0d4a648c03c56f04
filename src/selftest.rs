//! `ocean selftest`: the oracle's verdict on the user's own GPU. Every reference scene (and the
//! four built-in systems) is rendered on the adapter and held to the envelope of any conformant
//! GPU (docs/tolerances.md); then every planted bug (`ocean compare --mutants`) is rendered
//! and must leave it. On a software adapter (lavapipe) the planted bugs are also held to the
//! exact tolerance against the CPU oracle. Ends with one line and a JSON file; exits 1 when a
//! clean scene leaves its envelope.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, bail};
use ocean::verdict::{GpuSide, Verdict, envelope_verdict};
use ocean_core::mutants::{MUTANTS, Mutant, activate};
use ocean_core::plan::{FramePlan, OutputKind, ResourceId};
use ocean_core::scene::Scene;
use ocean_gpu::{Renderer, WaveSynthesis};
use serde_json::json;

/// Arguments of `ocean selftest`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A small frame (160×90: below it the objects' maps are more than 2 % silhouette) and
    /// no exact pass over the planted bugs: about a minute and a half on lavapipe.
    #[arg(long)]
    quick: bool,
    /// Frame size WIDTHxHEIGHT (default 256x144; 160x90 with --quick).
    #[arg(long)]
    size: Option<String>,
    /// The folder of reference scenes (`*.toml`).
    #[arg(long, default_value = "reference/scenes")]
    scenes: PathBuf,
    /// Where the JSON summary goes.
    #[arg(long, default_value = "ocean-selftest.json")]
    json: PathBuf,
}

/// One frame on the adapter, judged by the envelope.
fn judge(
    renderer: &mut Renderer,
    scene: &Scene,
    first_failure: bool,
    quick: bool,
) -> anyhow::Result<Verdict> {
    let plan = FramePlan::new(scene, OutputKind::Ldr);
    let frame = renderer.run(scene, &plan)?;
    // The oracle's frame tells which pixels hold the sky (a small frame: cheap).
    let oracle = ocean_cpu::render_scene(scene, OutputKind::Ldr, &mut |_| {})?;
    let mut side = GpuSide {
        maps: ResourceId::MAPS
            .into_iter()
            .filter_map(|id| frame.map(id).map(|m| (id, ((m.width, m.height), &m.texels[..]))))
            .collect(),
        ldr: frame.ldr.as_deref(),
        oracle_hdr: Some(&oracle.buffers.hdr.color),
        precision: ocean::verdict::precision_of(
            &renderer.adapter().name,
            &renderer.adapter().vendor,
        ),
        first_failure,
        water_every: if quick { 3 } else { 1 },
        spray: None,
    };
    let probe = ocean::verdict::spray::probe(
        renderer,
        scene,
        &frame.plan,
        side.map(ResourceId::Displacement),
    )?;
    side.spray = probe.as_ref();
    envelope_verdict(scene, &frame.plan, &side, &ocean::dump::dumped(&frame.plan))
}

/// The reference scenes (sorted by name) and the built-in systems, at `size`.
fn scenes(dir: &std::path::Path, size: (u32, u32)) -> anyhow::Result<Vec<(String, Scene)>> {
    let mut out = Vec::new();
    if dir.is_dir() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
            .with_context(|| format!("cannot list {}", dir.display()))?
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        files.sort();
        for f in files {
            let name = f.file_stem().map_or_else(String::new, |s| s.to_string_lossy().into_owned());
            out.push((name, Scene::load(&f).with_context(|| format!("{}", f.display()))?));
        }
    } else {
        println!("{}: no such folder; the built-in systems only", dir.display());
    }
    for system in ["hu", "chiu", "welch", "coastal"] {
        let arg = ocean::scene_arg::SystemArg { system: Some(system.to_owned()) };
        out.push((format!("builtin-{system}"), ocean::scene_arg::load_scene(None, &arg)?));
    }
    for (_, s) in &mut out {
        (s.camera.width, s.camera.height) = size;
    }
    Ok(out)
}

/// A planted bug's scene at `size`, or `None` when its reference scene is not at hand.
fn mutant_scene(dir: &std::path::Path, m: &Mutant, size: (u32, u32)) -> Option<Scene> {
    let mut s = Scene::load(&dir.join(format!("{}.toml", m.scene))).ok()?;
    (s.camera.width, s.camera.height) = size;
    Some(s)
}

/// Runs `ocean selftest`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let start = Instant::now();
    let size = match &args.size {
        Some(s) => ocean::output::parse_size(s)?,
        None if args.quick => (160, 90),
        None => (256, 144),
    };
    let gpu = ocean_gpu::Gpu::new()?;
    let mut renderer = Renderer::with_gpu(gpu, WaveSynthesis::GpuFft)?;
    let adapter = renderer.adapter().clone();
    println!(
        "ocean selftest on {} ({}, {}, driver {}), {}x{}",
        adapter.name, adapter.backend, adapter.device_type, adapter.driver, size.0, size.1
    );
    let mut scene_json = Vec::new();
    let (mut clean, mut total) = (0, 0);
    let mut judged_names = std::collections::BTreeSet::new();
    let mut unjudged = std::collections::BTreeSet::new();
    let (mut outside, mut ambiguous) = (Vec::new(), Vec::new());
    for (name, scene) in scenes(&args.scenes, size)? {
        ocean::scene_arg::revalidate(&scene, "--size")?;
        let v = judge(&mut renderer, &scene, false, args.quick).with_context(|| name.clone())?;
        total += 1;
        judged_names.extend(v.judged.iter().copied());
        unjudged.extend(v.not_judged.iter().copied());
        let ok = v.passed();
        if ok {
            clean += 1;
        } else {
            // Every value inside but too little decided is not a bug found: said apart.
            if v.only_too_ambiguous() { &mut ambiguous } else { &mut outside }.push(name.clone());
            for l in &v.lines {
                println!("{l}");
            }
        }
        let said = match (ok, v.only_too_ambiguous()) {
            (true, _) => "within the envelope",
            (false, true) => "TOO AMBIGUOUS to judge (no value outside)",
            (false, false) => "OUTSIDE the envelope",
        };
        println!("  {name:<24} {said} (judged: {})", v.judged.join(", "));
        scene_json.push(json!({"scene": name, "passed": ok, "judged": v.judged, "not_judged": v.not_judged, "resources": v.json}));
    }
    let software = adapter.is_software;
    let exact = software && !args.quick;
    let mut mutant_json = Vec::new();
    let (mut caught, mut caught_exact, mut planted) = (0, 0, 0);
    for m in MUTANTS {
        let Some(scene) = mutant_scene(&args.scenes, m, size) else {
            println!(
                "  {:<36} skipped: scene {} is not in {}",
                m.name,
                m.scene,
                args.scenes.display()
            );
            continue;
        };
        planted += 1;
        // A renderer of its own: pipelines are built once per renderer, from the WGSL as
        // assembled then (with the planted bug while it is active).
        activate(Some(m));
        let mutated = ocean_gpu::Gpu::new()
            .map_err(anyhow::Error::from)
            .and_then(|g| Ok(Renderer::with_gpu(g, WaveSynthesis::GpuFft)?));
        let mut mutated = match mutated {
            Ok(r) => r,
            Err(e) => {
                activate(None);
                return Err(e);
            }
        };
        let v = judge(&mut mutated, &scene, true, args.quick);
        let exact_caught = if exact {
            let c = ocean_verify::cross_check::check_scene(&mut mutated, m.name, &scene);
            Some(c.map(|(c, _)| !c.failures().is_empty()))
        } else {
            None
        };
        activate(None);
        let v = v.with_context(|| m.name)?;
        let hit = !v.passed();
        caught += usize::from(hit);
        let exact_caught = exact_caught.transpose()?;
        caught_exact += usize::from(exact_caught == Some(true));
        println!(
            "  {:<36} {}{}",
            m.name,
            if hit { "caught" } else { "missed" },
            exact_caught.map_or(String::new(), |e| format!(
                " (exact: {})",
                if e { "caught" } else { "missed" }
            ))
        );
        mutant_json.push(json!({"name": m.name, "file": m.file, "scene": m.scene, "caught": hit, "caught_exact": exact_caught, "judged": v.judged}));
    }
    let mut line = format!(
        "{}: {clean}/{total} scenes within the envelope; {caught}/{planted} planted bugs caught",
        adapter.name
    );
    if exact {
        line.push_str(&format!(" ({caught_exact}/{planted} with the exact tolerance)"));
    }
    let not_judged: Vec<&str> = unjudged.difference(&judged_names).copied().collect();
    let json = json!({
        "adapter": {
            "name": adapter.name, "vendor": adapter.vendor, "backend": adapter.backend,
            "device_type": adapter.device_type, "driver": adapter.driver, "software": software,
        },
        "size": [size.0, size.1],
        "quick": args.quick,
        "summary": line,
        "scenes_within": clean,
        "scenes": total,
        "planted_caught": caught,
        "planted_caught_exact": exact.then_some(caught_exact),
        "planted": planted,
        "judged": judged_names,
        "not_judged_yet": not_judged,
        "seconds": start.elapsed().as_secs_f64(),
        "scene_results": scene_json,
        "planted_results": mutant_json,
    });
    ocean::output::write_atomic(&args.json, serde_json::to_string_pretty(&json)?.as_bytes())?;
    let rest = if not_judged.is_empty() {
        "every resource of these frames is judged in some scene".to_owned()
    } else {
        format!("not judged yet: {} (their passes have no envelope)", not_judged.join(", "))
    };
    println!(
        "judged by the envelope: {}; {rest}",
        judged_names.iter().copied().collect::<Vec<_>>().join(", ")
    );
    println!("wrote {} in {:.1} s", args.json.display(), start.elapsed().as_secs_f64());
    println!("{line}");
    let mut failed = Vec::new();
    if !outside.is_empty() {
        failed.push(format!("outside the envelope: {}", outside.join(", ")));
    }
    if !ambiguous.is_empty() {
        failed.push(format!(
            "more than 2 % ambiguous (no value outside; a larger --size decides more): {}",
            ambiguous.join(", ")
        ));
    }
    if !failed.is_empty() {
        bail!("{}", failed.join("; "));
    }
    Ok(())
}
