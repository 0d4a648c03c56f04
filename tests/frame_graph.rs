//! The frame graph (issue 10): one plan, its techniques and resource table, driving the CPU
//! oracle (the GPU side is in `tests/gpu_frame_graph.rs`); systems and `[techniques]` in
//! scenes and on the command line.

#[path = "support/cli.rs"]
mod ocean_cli;

use ocean_core::graph::FrameState;
use ocean_core::plan::{FramePlan, OutputKind, Pass, ResourceId, Stage, System};
use ocean_core::scene::{Scene, SceneError, SceneSource};

#[path = "support/random_scene.rs"]
mod random_scene;
use random_scene::{Rng, random_scene};

fn scene(text: &str) -> Result<Scene, SceneError> {
    Scene::from_toml(text, SceneSource::Text)
}

#[test]
fn every_map_the_cpu_allocates_has_the_plans_size() {
    // Property over random valid plans: each of the CPU's maps is exactly the plan's resource
    // (its size, or 1×1 where the writer is skipped); the LDR picture is the viewport.
    let mut rng = Rng(0x0cea_2026);
    for case in 0..24 {
        let (s, output) = random_scene(&mut rng);
        let plan = FramePlan::new(&s, output);
        let r = ocean_cpu::render_scene_with_plan(&s, plan.clone(), &mut |_| {}).unwrap();
        for id in ResourceId::MAPS {
            let want = plan.resource(id).unwrap_or_else(|| panic!("{id:?} not in the plan"));
            let (w, h, texels) = r.buffers.map(id).unwrap();
            // A mip chain comes back packed (Resource::readback_size).
            let size = want.readback_size();
            assert_eq!([w, h], size, "case {case}: {} {plan}", id.name());
            assert_eq!(texels.len(), (size[0] * size[1]) as usize, "case {case}: {}", id.name());
            assert_eq!(
                want.written,
                id.writer().is_none_or(|p| plan.runs(p)),
                "case {case}: {}",
                id.name()
            );
        }
        match (plan.resource(ResourceId::Ldr), &r.ldr) {
            (Some(l), Some(px)) => assert_eq!(px.len() as u64, 4 * l.texels()),
            (None, None) => assert_eq!(output, OutputKind::Hdr),
            (a, b) => panic!("case {case}: plan {a:?} vs picture {}", b.is_some()),
        }
    }
}

#[test]
fn quality_keys_size_the_resources() {
    let s = scene(
        "[quality]\nfresnel_table_size = 64\nreflection_map_scale = 0.5\n\
         [camera]\nwidth = 160\nheight = 90\n\
         [[objects]]\nkind = \"sphere\"\ncenter = [0.0, 3.0, 0.0]\nradius = 2.0\n",
    )
    .unwrap();
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    let size = |id| plan.resource(id).unwrap().size;
    assert_eq!(size(ResourceId::FresnelAbove), [64, 64]);
    assert_eq!(size(ResourceId::FresnelBelow), [64, 64]);
    assert_eq!(size(ResourceId::ReflectionMap), [80, 45]);
    assert_eq!(size(ResourceId::RefractionMap), [1, 1], "nothing under the water");
    assert_eq!(size(ResourceId::Hdr), [160, 90]);
    let r = ocean_cpu::render_scene_with_plan(&s, plan.clone(), &mut |_| {}).unwrap();
    assert_eq!(r.buffers.fresnel_above.width, 64);
    assert_eq!((r.buffers.reflection_map.width, r.buffers.reflection_map.height), (80, 45));
}

#[test]
fn the_plan_names_the_system_and_a_technique_per_stage() {
    let plan = FramePlan::new(&Scene::builtin(), OutputKind::Ldr);
    assert_eq!(plan.system, System::Hu);
    let json = serde_json::to_value(&plan).unwrap();
    assert_eq!(json["system"], "hu");
    let t = json["techniques"].as_object().unwrap();
    let stages: Vec<&str> = t.keys().map(String::as_str).collect();
    let mut want: Vec<&str> = Stage::ALL.iter().map(|s| s.name()).collect();
    want.sort_unstable();
    let mut got = stages.clone();
    got.sort_unstable();
    assert_eq!(got, want);
    assert_eq!(t["waves"], "fft");
    assert_eq!(t["surface"], "hu_patches");
    assert_eq!(t["shading"], "hu");
    assert_eq!(t["sky"], "preetham");
    assert_eq!(t["far_field"], "variance");
    let water = plan.pass(Pass::Water).unwrap();
    assert_eq!(
        (water.stage, water.technique, water.shader),
        (Some(Stage::Shading), Some("hu"), Some("water"))
    );
    assert!(water.reads.contains(&ResourceId::FresnelAbove));
    assert_eq!(water.writes, [ResourceId::Hdr]);
}

#[test]
fn systems_and_techniques_in_a_scene_are_checked_with_their_position() {
    assert_eq!(scene("system = \"hu\"\n").unwrap().system, System::Hu);
    assert_eq!(scene("system = \"welch\"\n").unwrap().system, System::Welch);
    // Every system is built (issue 15 finished the last, `coastal`).
    assert_eq!(scene("\n\nsystem = \"coastal\"\n").unwrap().system, System::Coastal);
    let e = scene("system = \"nope\"\n").unwrap_err().to_string();
    assert!(e.contains("nope") && e.contains("coastal"), "{e}");
    assert!(scene("[techniques]\nsurface = \"shore_grid\"\n").is_ok());
    let e = scene("\n[techniques]\nsurface = \"shore\"\n").unwrap_err().to_string();
    assert!(
        e.contains("techniques.surface") && e.contains(":3:1") && e.contains("shore_grid"),
        "{e}"
    );
    // Every foam technique is built.
    for foam in ["none", "heuristic", "jacobian", "accumulated"] {
        assert!(scene(&format!("[techniques]\nfoam = \"{foam}\"\n")).is_ok(), "{foam}");
    }
    // Every far field is built.
    for far in ["none", "mip", "variance"] {
        assert!(scene(&format!("[techniques]\nfar_field = \"{far}\"\n")).is_ok(), "{far}");
    }
    let e = scene("[techniques]\nsky = \"sunset\"\n").unwrap_err().to_string();
    assert!(e.contains("techniques.sky") && e.contains("preetham"), "{e}");
    let e = scene("[techniques]\ncolour = \"red\"\n").unwrap_err().to_string();
    assert!(e.contains("colour"), "{e}");
    // An override to the system's own choice is accepted and shows in the plan.
    let s = scene("[techniques]\nsky = \"preetham\"\nfar_field = \"none\"\n").unwrap();
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    assert!(plan.techniques.is_overridden(Stage::Sky));
    assert!(plan.to_string().contains("[techniques]"), "{plan}");
}

#[test]
fn a_looping_animation_precomputes_its_cycle_once_and_plays_it() {
    let s = scene("[ocean]\nloop_period_s = 4.0\nresolution = 32\nbump_resolution = 16\n[camera]\nwidth = 32\nheight = 18\n").unwrap();
    let plan = FramePlan::for_frames(&s, OutputKind::Ldr, 3);
    assert!(plan.runs(Pass::Cycle), "{plan}");
    let mut state = FrameState::new(0.5);
    let mut pictures = Vec::new();
    for n in 0..3 {
        assert_eq!(state.frame, n);
        let computed_before = state.cycle_at(&s.ocean, 0.0).is_some();
        assert_eq!(computed_before, n > 0, "frame {n}: the cycle exists from the first frame on");
        let r =
            ocean_cpu::render_animation_frame(&s, plan.clone(), &mut state, &mut |_| {}).unwrap();
        pictures.push(r.ldr.unwrap());
    }
    // A second precompute of the same sea is a no-op.
    assert!(!state.precompute_cycle(&s.ocean).unwrap());
    // Frame n shows the sea at time_s + n/2: a pure function of (scene, n).
    let mut again = FrameState::new(0.5);
    again.frame = 2;
    again.precompute_cycle(&s.ocean).unwrap();
    let r = ocean_cpu::render_animation_frame(&s, plan.clone(), &mut again, &mut |_| {}).unwrap();
    assert_eq!(r.ldr.unwrap(), pictures[2]);
    assert!(pictures[0] != pictures[2], "the sea moves between frames");
}

use ocean_cli::ocean;

#[test]
fn render_with_an_unknown_system_exits_1_lists_the_systems_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("never.png");
    let o = ocean(&[
        "render",
        "--system",
        "no-such-system",
        "--size",
        "16x9",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    let e = String::from_utf8_lossy(&o.stderr);
    for name in ["hu", "chiu", "welch", "coastal"] {
        assert!(e.contains(name), "{e}");
    }
    assert!(!e.contains("panicked"), "{e}");
    assert!(!out.exists());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "no temporary file either");
    // `coastal` without a scene renders its own island (its waves need a shore).
    let o =
        ocean(&["render", "--system", "coastal", "--size", "16x9", "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.exists());
    std::fs::remove_file(&out).unwrap();
    for cmd in ["plan", "compare", "view"] {
        let o = ocean(&[cmd, "--system", "no-such-system"]);
        assert_eq!(o.status.code(), Some(1), "{cmd}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stderr).contains("welch"), "{cmd}");
    }
}

#[test]
fn plan_json_shows_the_system_and_the_techniques() {
    let o = ocean(&["plan", "--system", "hu", "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["system"], "hu");
    assert_eq!(v["techniques"]["shading"], "hu");
    assert_eq!(v["techniques"].as_object().unwrap().len(), Stage::ALL.len());
    assert!(
        v["passes"]
            .as_array()
            .unwrap()
            .iter()
            .all(|p| p["name"].is_string() && p["reason"].is_string())
    );
    assert!(v["resources"].as_array().unwrap().iter().any(|r| r["id"] == "fresnel_above"));
    let o = ocean(&["plan"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("system hu") && text.contains("stage shading") && text.contains("resources:"),
        "{text}"
    );
}

#[test]
fn the_oracle_runs_the_plans_waves_kernel() {
    use ocean_core::frame::displacement_texels;
    use ocean_core::plan::WavesKernel;
    use ocean_core::waves::Synthesizer;
    use ocean_cpu::shaders::waves::WavesMirror;
    let s =
        scene("[ocean]\nresolution = 64\nbump_resolution = 32\n[camera]\nwidth = 16\nheight = 9\n")
            .unwrap();
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    assert_eq!(plan.waves_kernel, WavesKernel::Shader);
    assert!(plan.pass(Pass::Waves).unwrap().reason.contains("waves.wgsl"), "{plan}");
    let r = ocean_cpu::render_scene_with_plan(&s, plan, &mut |_| {}).unwrap();
    let surface = s.ocean.surface().unwrap();
    let (t, chop) = (s.ocean.time_s, s.ocean.choppiness);
    // Direct evaluation of what the pass must have run: waves.wgsl's mirror, bit for bit.
    let mirror = WavesMirror::new(&surface.displacement).unwrap().run(t, chop).unwrap();
    let bits = |t: &[[f32; 4]]| t.iter().flat_map(|v| v.map(f32::to_bits)).collect::<Vec<_>>();
    assert_eq!(bits(&r.buffers.displacement.texels), bits(&mirror.displacement.texels));
    let bump = WavesMirror::new(&surface.bump).unwrap().run(t, chop).unwrap();
    assert_eq!(bits(&r.buffers.bump.texels), bits(&bump.bump.texels));
    // Negative control: ocean-core's synthesis of the same sea is other bits (within 1e-5).
    let core =
        Synthesizer::<f32>::new(64).unwrap().synthesize(&surface.displacement, t, chop).unwrap();
    assert_ne!(bits(&displacement_texels(&core)), bits(&mirror.displacement.texels));
    // A looping sea is synthesised by ocean-core, as its cycle is.
    let looping =
        scene("[ocean]\nloop_period_s = 8.0\nresolution = 64\nbump_resolution = 32\n").unwrap();
    let plan = FramePlan::new(&looping, OutputKind::Ldr);
    assert_eq!(plan.waves_kernel, WavesKernel::Synthesis);
    assert!(plan.pass(Pass::Waves).unwrap().reason.contains("looping"), "{plan}");
}
