//! The planted bugs (`ocean_core::mutants`): each is a real one-line change of valid WGSL that
//! runs in its scene, and the oracle catches every one with the exact (lavapipe) tolerance.
//!
//! The CPU test needs no GPU: every mutant's text occurs exactly once in its file, changes at
//! least one stage of its scene, and leaves WGSL that naga validates. The GPU test renders each
//! mutant's scene at 160×90 with the mutated WGSL on the GPU and the correct oracle on the CPU
//! (`ocean compare --mutant`): every float map and the picture are compared, and at least one
//! check must fail; the same scenes unmutated must pass (the control). `ocean selftest --quick`
//! runs here too: every scene within the envelope, every bug in a pass the envelope judges
//! caught.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;

#[path = "support/cli.rs"]
mod cli;

use cli::ocean;

use std::collections::BTreeSet;
use std::path::PathBuf;

use naga::valid::{Capabilities, ValidationFlags, Validator};
use ocean_core::mutants::{MUTANTS, Mutant, activate};
use ocean_core::scene::Scene;
use ocean_core::shader_source::{stage_names, stage_source_with};
use ocean_gpu::{Renderer, WaveSynthesis};
use ocean_verify::cross_check::check_scene;

/// The frame size of the GPU test: small, as the cross-check's.
const SIZE: (u32, u32) = (160, 90);

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scene(m: &Mutant) -> Scene {
    let path = root().join("reference/scenes").join(format!("{}.toml", m.scene));
    let mut s = Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", m.name));
    (s.camera.width, s.camera.height) = SIZE;
    s
}

/// Every stage's assembled WGSL for the scene's techniques, with `mutant` active or not.
fn stages(s: &Scene, mutant: Option<&'static Mutant>) -> Vec<(&'static str, String)> {
    activate(mutant);
    let techniques = s.techniques();
    let out = stage_names()
        .map(|stage| (stage, stage_source_with(stage, &techniques).unwrap()))
        .collect();
    activate(None);
    out
}

fn every_mutant_is_one_line_of_valid_wgsl_that_its_scene_runs() {
    assert!(MUTANTS.len() >= 24, "{} planted bugs; the bank holds at least 24", MUTANTS.len());
    let names: BTreeSet<&str> = MUTANTS.iter().map(|m| m.name).collect();
    assert_eq!(names.len(), MUTANTS.len(), "two planted bugs share a name");
    let files: BTreeSet<&str> = MUTANTS.iter().map(|m| m.file).collect();
    assert!(files.len() >= 12, "the bank touches only {} files: {files:?}", files.len());
    let systems: BTreeSet<String> =
        MUTANTS.iter().map(|m| scene(m).system.name().to_owned()).collect();
    assert_eq!(systems.len(), 4, "the bank's scenes cover only {systems:?}");
    let mut problems = Vec::new();
    for m in MUTANTS {
        let text = std::fs::read_to_string(root().join("shaders").join(m.file)).unwrap();
        let count = text.matches(m.find).count();
        if count != 1 || m.find == m.replace || m.find.contains('\n') || m.replace.contains('\n') {
            problems.push(format!("{}: `{}` occurs {count} times in {}", m.name, m.find, m.file));
            continue;
        }
        let s = scene(m);
        let (clean, mutated) = (stages(&s, None), stages(&s, Some(m)));
        let changed: Vec<_> = clean.iter().zip(&mutated).filter(|(a, b)| a.1 != b.1).collect();
        if changed.is_empty() {
            problems.push(format!("{}: no stage of scene {} includes {}", m.name, m.scene, m.file));
        }
        for (_, (stage, src)) in changed {
            let valid = naga::front::wgsl::parse_str(src)
                .map_err(|e| e.emit_to_string(src))
                .and_then(|module| {
                    Validator::new(ValidationFlags::all(), Capabilities::empty())
                        .validate(&module)
                        .map(|_| ())
                        .map_err(|e| e.emit_to_string(src))
                });
            if let Err(e) = valid {
                problems.push(format!("{}: stage {stage} does not validate:\n{e}", m.name));
            }
        }
    }
    // The check itself: a mutant whose text is not in its file is found (negative control).
    let stray = Mutant {
        name: "x",
        file: "tonemap.wgsl",
        find: "no such text",
        replace: "",
        changes: "",
        scene: "calm",
    };
    let text = std::fs::read_to_string(root().join("shaders").join(stray.file)).unwrap();
    assert_eq!(text.matches(stray.find).count(), 0);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

fn the_command_line_lists_the_bank_and_refuses_an_unknown_name() {
    let o = ocean(&["compare", "--mutants"]);
    let listed = String::from_utf8(o.stdout).unwrap();
    assert!(o.status.success());
    for m in MUTANTS {
        assert!(listed.lines().any(|l| l.starts_with(m.name) && l.contains(m.file)), "{}", m.name);
    }
    let o = ocean(&["compare", "--mutant", "no-such-bug"]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("no planted bug `no-such-bug`") && e.contains(MUTANTS[0].name), "{e}");
}

/// Renders `s` on the GPU (with this thread's active mutant) and on the oracle: the failed
/// checks, and the pictures' FLIP mean (for the report of what a picture-only rule misses).
fn failures(name: &str, s: &Scene) -> (Vec<String>, Option<f32>) {
    let gpu = ocean_gpu::Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let mut renderer = Renderer::with_gpu(gpu, WaveSynthesis::GpuFft).unwrap();
    let (check, _) = check_scene(&mut renderer, name, s).unwrap_or_else(|e| panic!("{name}: {e}"));
    (check.failures(), check.image.as_ref().map(|i| i.flip_mean))
}

fn every_mutant_is_caught_with_the_exact_tolerance() {
    // Control: each scene of the bank passes unmutated.
    let scenes: BTreeSet<&str> = MUTANTS.iter().map(|m| m.scene).collect();
    for name in &scenes {
        let m = MUTANTS.iter().find(|m| m.scene == *name).unwrap();
        let (f, _) = failures(name, &scene(m));
        assert!(f.is_empty(), "{name} fails without a planted bug:\n{}", f.join("\n"));
    }
    let mut missed = Vec::new();
    // The hardware picture rule (FLIP mean > 0.02, ImageLimits::HARDWARE) alone, for contrast.
    let mut by_picture = 0;
    for m in MUTANTS {
        activate(Some(m));
        let (f, flip) = failures(m.name, &scene(m));
        activate(None);
        let flip = flip.unwrap_or(0.0);
        by_picture += usize::from(flip > 0.02);
        println!(
            "{:<36} {:<26} caught by {:>2} check(s); FLIP mean {flip:.4}",
            m.name,
            m.file,
            f.len()
        );
        if f.is_empty() {
            missed.push(format!("{} ({}: {})", m.name, m.file, m.changes));
        }
    }
    println!(
        "{}/{} planted bugs caught with the exact tolerance; {by_picture}/{} by a picture rule of \
         FLIP mean > 0.02 alone",
        MUTANTS.len() - missed.len(),
        MUTANTS.len(),
        MUTANTS.len()
    );
    assert!(missed.is_empty(), "not caught:\n{}", missed.join("\n"));
}

/// `ocean selftest --quick` on this adapter (lavapipe in CI): every reference scene and built-in
/// system within the envelope, the whole bank planted, and every planted bug in a pass the
/// envelope judges (tonemap, bloom, waves, foam's field, the shadow and reflection maps,
/// wave_mips, fresnel_table, the three skies, the water of shadings `hu`, `ggx` and `coastal`,
/// of Gerstner's and the coastal waves, of foam `jacobian`) caught; the summary line and the
/// JSON agree.
fn selftest_quick_judges_every_scene_and_catches_the_judged_passes_bugs() {
    let json = std::env::temp_dir().join(format!("ocean-selftest-{}.json", std::process::id()));
    let json_s = json.to_string_lossy().into_owned();
    let scenes = root().join("reference/scenes").to_string_lossy().into_owned();
    let o = ocean(&["selftest", "--quick", "--scenes", &scenes, "--json", &json_s]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "{out}{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let _ = std::fs::remove_file(&json);
    let reference = std::fs::read_dir(root().join("reference/scenes"))
        .unwrap()
        .flatten()
        .filter(|e| e.path().extension().is_some_and(|x| x == "toml"))
        .count();
    assert_eq!(v["scenes"], reference + 4, "every reference scene and the four systems");
    assert_eq!(v["scenes_within"], v["scenes"], "{out}");
    assert_eq!(v["planted"], MUTANTS.len(), "the whole bank");
    let judged: Vec<&str> =
        v["judged"].as_array().unwrap().iter().map(|j| j.as_str().unwrap()).collect();
    for pass_output in [
        "ldr",
        "bloom_up",
        "displacement",
        "bump",
        "foam_field",
        "shadow_map",
        "hdr",
        "spray_particles",
    ] {
        assert!(judged.contains(&pass_output), "{pass_output} not judged: {judged:?}");
    }
    for r in v["planted_results"].as_array().unwrap() {
        let file = r["file"].as_str().unwrap();
        // The files of the passes the envelope judges (fresnel.wgsl through the Fresnel tables).
        let judged_files = [
            "tonemap.wgsl",
            "bloom.wgsl",
            "wave_mips.wgsl",
            "fresnel_table.wgsl",
            "shared/fresnel.wgsl",
            "waves.wgsl",
            "foam.wgsl",
            "shadow.wgsl",
            "shared/preetham.wgsl",
            "sky/preetham_clouds.wgsl",
            "shared/sky_lut.wgsl",
            // The water pass under shadings `hu`, `ggx` and `chiu`: a swapped channel, an
            // unnormalised half vector, a flipped Fresnel branch and chiu's tilted reflection
            // (over the coastal waves) are caught; water.wgsl's far-field variance 1 % too large
            // stays inside the water's wide envelope over wave maps (docs/tolerances.md).
            "shading/hu.wgsl",
            "shading/ggx.wgsl",
            "shading/chiu.wgsl",
            // Shading and waves `coastal`, judged where the water is certainly nearer than the
            // island and the boat; Gerstner's phase and foam `jacobian` over analytic waves;
            // the objects' reflection map and the shadow test.
            "shading/coastal.wgsl",
            "shared/coastal.wgsl",
            "shared/gerstner.wgsl",
            "foam/jacobian.wgsl",
            "objects.wgsl",
            "shared/shadow.wgsl",
            // The spray's step and sprites, from the pool the GPU held (its launch speed,
            // the sprites' colour).
            "spray.wgsl",
        ];
        if judged_files.contains(&file) {
            assert_eq!(r["caught"], true, "a bug in a judged pass was missed: {r}");
        }
    }
    let line = out.lines().last().unwrap();
    let caught = v["planted_caught"].as_u64().unwrap();
    assert!(
        line.ends_with(&format!(
            "{0}/{0} scenes within the envelope; {caught}/{1} planted bugs caught",
            reference + 4,
            MUTANTS.len()
        )),
        "{line}"
    );
    println!("{line}");
}

fn main() -> std::process::ExitCode {
    run_tests!(gpu_harness::GPU_ADAPTER;
        cpu: every_mutant_is_one_line_of_valid_wgsl_that_its_scene_runs,
            the_command_line_lists_the_bank_and_refuses_an_unknown_name;
        gpu: every_mutant_is_caught_with_the_exact_tolerance,
            selftest_quick_judges_every_scene_and_catches_the_judged_passes_bugs;
    )
}
