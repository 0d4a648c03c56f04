//! The frame graph on both back ends (issue 10): the GPU obeys the plan's `[quality]` sizes
//! and its cycle, and every resource both back ends allocate has the plan's size — checked
//! with the cross-check's comparators (float maps within docs/design.md's rel 1e-5 / abs 1e-6, the
//! picture within the adapter's tolerance row, and each map's size equal to the plan's).
//!
//! Before the frame graph the GPU hard-coded 256² Fresnel textures and a viewport-sized
//! reflection map: `quality_scenes_match_the_cpu_oracle` failed on its first scene (64² vs
//! 256², 80×45 vs 160×90, 77.5 % of pixels within 1/255).

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;
#[path = "support/extreme_scene.rs"]
mod extreme_scene;
#[path = "support/random_scene.rs"]
mod random_scene;
#[path = "support/reference_scenes.rs"]
mod reference_scenes;

use std::path::PathBuf;

use ocean_core::graph::FrameState;
use ocean_core::plan::{FramePlan, OutputKind, Pass, ResourceId};
use ocean_core::scene::{Scene, SceneSource};
use ocean_gpu::{Readback, Renderer, WaveSynthesis};
use ocean_verify::compare::{compare_float, compare_image};
use ocean_verify::cross_check::{check_plan, check_scene, cpu_map, write_artefacts};
use random_scene::{Rng, random_scene};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn renderer() -> Renderer {
    let gpu = ocean_gpu::Gpu::new().unwrap_or_else(|e| panic!("gpu_frame_graph: {e}"));
    let r = Renderer::with_gpu(gpu, WaveSynthesis::GpuFft).expect("renderer");
    eprintln!("gpu_frame_graph: adapter {}", r.adapter());
    r
}

/// The reference default scene at 160×90 with `quality` appended.
fn default_with(quality: &str) -> Scene {
    let text = std::fs::read_to_string(root().join("reference/scenes/default.toml")).unwrap();
    let text = format!("{text}\n[quality]\n{quality}\n");
    let mut s = Scene::from_toml(&text, SceneSource::Text).unwrap_or_else(|e| panic!("{e}"));
    (s.camera.width, s.camera.height) = (160, 90);
    s
}

/// Renders on both back ends, prints the comparison, and returns its failures (artefacts in
/// `target/gpu-frame-graph/` on failure).
fn failures_of(
    r: &mut Renderer,
    name: &str,
    scene: &Scene,
    plan: Option<FramePlan>,
) -> Vec<String> {
    let (check, renders) = match plan {
        Some(p) => check_plan(r, name, scene, p),
        None => check_scene(r, name, scene),
    }
    .expect("both renders");
    eprintln!("{name}:");
    for line in check.lines() {
        eprintln!("  {line}");
    }
    let f = check.failures();
    if !f.is_empty() {
        write_artefacts(&root().join("target/gpu-frame-graph"), &check, &renders)
            .expect("writable");
    }
    f
}

fn quality_scenes_match_the_cpu_oracle() {
    let mut r = renderer();
    let cases = [
        ("fresnel64_reflection0.5", "fresnel_table_size = 64\nreflection_map_scale = 0.5"),
        ("fresnel32_reflection0.25", "fresnel_table_size = 32\nreflection_map_scale = 0.25"),
        ("fresnel17_reflection0.33", "fresnel_table_size = 17\nreflection_map_scale = 0.33"),
        ("fresnel512_lod0.2", "fresnel_table_size = 512\nlod_split_threshold = 0.2"),
        ("lod0.02_reflection0.8", "lod_split_threshold = 0.02\nreflection_map_scale = 0.8"),
    ];
    let mut failures = Vec::new();
    for (name, q) in cases {
        let s = default_with(q);
        let plan = FramePlan::new(&s, OutputKind::Ldr);
        // The plan's sizes are what the keys say (the check below holds both back ends to them).
        let size = |id| plan.resource(id).unwrap().size;
        assert_eq!(size(ResourceId::FresnelAbove)[0], s.quality.fresnel_table_size, "{name}");
        let want = [160, 90]
            .map(|v: u32| ((f64::from(v) * s.quality.reflection_map_scale).round() as u32).max(1));
        assert_eq!(size(ResourceId::ReflectionMap), want, "{name}");
        failures.extend(failures_of(&mut r, name, &s, None));
    }
    // The same from under the water (no sky pass: the background is the plan's clear colour).
    let mut under = default_with("fresnel_table_size = 64\nreflection_map_scale = 0.5");
    under.camera.position = [0.0, -2.5, 20.0];
    under.camera.look_at = [0.0, 25.0, -15.0];
    failures.extend(failures_of(&mut r, "underwater_fresnel64", &under, None));
    // Every far field (the reference scenes run the default, `variance`).
    for far in [ocean_core::plan::FarField::None, ocean_core::plan::FarField::Mip] {
        let mut s = default_with("fresnel_table_size = 128");
        s.techniques.far_field = Some(far);
        failures.extend(failures_of(&mut r, &format!("far_field_{far}"), &s, None));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

fn every_resource_both_back_ends_allocate_has_the_plans_size() {
    // Property over random valid plans (tiny frames; both PNG and EXR plans): the comparison
    // fails on any map whose CPU, GPU or plan size differ, and on values beyond the limits.
    let mut r = renderer();
    let mut rng = Rng(0x6e0_2026);
    let mut failures = Vec::new();
    for case in 0..10 {
        let (s, output) = random_scene(&mut rng);
        let plan = FramePlan::new(&s, output);
        let (check, _) =
            check_plan(&mut r, &format!("random{case}"), &s, plan.clone()).expect("renders");
        for m in &check.maps {
            assert!(m.plan_size.is_some(), "case {case}: {} has no plan size", m.name);
            if !m.sizes_agree() {
                failures.push(format!("case {case}: {}", m.line()));
            }
        }
        // Beyond the sizes, the frames agree as everywhere else.
        failures.extend(check.failures().into_iter().map(|f| format!("case {case}: {f}")));
        assert_eq!(check.maps.len(), ResourceId::MAPS.len());
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

fn the_gpu_plays_the_cycle_the_plan_precomputes() {
    let text = "[ocean]\nloop_period_s = 4.0\nresolution = 64\nbump_resolution = 32\n\
                [camera]\nwidth = 96\nheight = 54\n";
    let s = Scene::from_toml(text, SceneSource::Text).unwrap();
    let plan = FramePlan::for_frames(&s, OutputKind::Ldr, 3);
    assert!(plan.runs(Pass::Cycle), "{plan}");
    let mut r = renderer();
    // 0.37 s apart: frames fall between the cycle's instants, so playing the cycle (nearest
    // instant) and synthesising at t differ — the negative control below.
    let (mut cpu_state, mut gpu_state) = (FrameState::new(0.37), FrameState::new(0.37));
    for n in 0..3 {
        let cpu = ocean_cpu::render_animation_frame(&s, plan.clone(), &mut cpu_state, &mut |_| {})
            .unwrap();
        let gpu = r.run_frame(&s, &plan, &mut gpu_state, Readback::All).unwrap();
        assert_eq!(gpu.wave_source, Some("cycle-upload"), "frame {n}");
        for id in [ResourceId::Displacement, ResourceId::Bump] {
            let g = gpu.map(id).unwrap();
            let stats = compare_float(
                id.name(),
                true,
                cpu_map(&cpu.buffers, id),
                ((g.width, g.height), &g.texels),
            );
            assert!(stats.passed() && stats.max_abs == 0.0, "frame {n}: {}", stats.line());
        }
        let image = compare_image(cpu.ldr.as_ref().unwrap(), gpu.ldr.as_ref().unwrap(), 96, 54);
        let limits = ocean_verify::compare::ImageLimits::for_adapter(r.adapter());
        assert!(image.failures(&limits).is_empty(), "frame {n}: {:?}", image.failures(&limits));
        // Negative control: the single-frame plan synthesises at the frame's own time.
        let t = s.ocean.time_s + n as f64 * 0.37;
        let mut at_t = s.clone();
        at_t.ocean.time_s = t;
        let single = r.run(&at_t, &FramePlan::new(&at_t, OutputKind::Ldr)).unwrap();
        let synthesised = single.map(ResourceId::Displacement).unwrap();
        let played = gpu.map(ResourceId::Displacement).unwrap();
        if n > 0 {
            assert!(synthesised.texels != played.texels, "frame {n}: the cycle was not played");
        }
    }
    assert_eq!((cpu_state.frame, gpu_state.frame), (3, 3));
}

/// Negative control of the size check: maps that agree in values but not with the plan's
/// size fail, and so do CPU and GPU maps of different sizes.
fn the_size_check_fails_on_a_map_of_another_size() {
    let texels = [[0.5f32; 4]; 4];
    let mut m = compare_float("fresnel_above", true, ((2, 2), &texels), ((2, 2), &texels));
    assert!(m.passed());
    m.plan_size = Some((2, 2));
    assert!(m.passed());
    m.plan_size = Some((4, 1));
    assert!(!m.passed() && !m.sizes_agree());
    assert!(m.line().contains("plan Some((4, 1))"), "{}", m.line());
    let m = compare_float("x", true, ((2, 2), &texels), ((4, 1), &texels));
    assert!(!m.passed());
}

/// The GPU back end's HDR frame of `scene` (EXR plan: no tonemap).
fn gpu_hdr(r: &mut Renderer, scene: &Scene) -> Vec<[f32; 4]> {
    let plan = FramePlan::new(scene, OutputKind::Hdr);
    let f = r.run_with(scene, &plan, Readback::Output).unwrap_or_else(|e| panic!("{e}"));
    f.map(ocean_gpu::FrameMap::Hdr).expect("the HDR frame").texels.clone()
}

/// Issue 11, item 3: object geometry beyond the device's `max_buffer_size` is cut into
/// several vertex buffers drawn in order (before, 10,000 spheres panicked inside wgpu). The
/// cut is forced here with a small cap: 100 triangles a buffer, 23 buffers a sphere.
fn object_geometry_cut_into_small_buffers_draws_the_same_picture() {
    let mut r = renderer();
    let mut scene = default_with("");
    scene.objects.push(scene.objects[0].clone());
    scene.objects[2].center[0] += 3.0;
    let whole = gpu_hdr(&mut r, &scene);
    r.set_max_vertex_buffer_bytes(100 * 3 * 36);
    let cut = gpu_hdr(&mut r, &scene);
    assert!(whole == cut, "the cut geometry draws another picture");
    // Negative control: the comparison sees one object less.
    scene.objects.pop();
    assert!(gpu_hdr(&mut r, &scene) != cut, "removing an object changed nothing");
}

/// The invariant of issue 11 on the GPU: a sample of the scenes at the validation's limits
/// (`tests/scene_properties.rs` runs them all on the CPU) renders only finite pixels.
fn extreme_scenes_render_finite_pixels_on_the_gpu() {
    let mut r = renderer();
    let mut rng = extreme_scene::Rng(5);
    let mut cases: Vec<(String, String)> =
        extreme_scene::per_key_extremes().into_iter().step_by(3).collect();
    cases.extend((0..12).map(|i| (format!("random {i}"), extreme_scene::random_extreme(&mut rng))));
    let mut accepted = 0;
    for (name, text) in &cases {
        let Some(scene) = extreme_scene::parse(text) else { continue };
        accepted += 1;
        let hdr = gpu_hdr(&mut r, &scene);
        let bad = hdr.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
        assert_eq!(bad, 0, "{name}: {bad} non-finite HDR pixels on the GPU\n{text}");
    }
    eprintln!("{accepted} of {} extreme scenes rendered on the GPU, all finite", cases.len());
    assert!(accepted >= cases.len() / 2, "only {accepted} accepted");
}

/// Every map and the picture of a frame, as bits.
fn frame_bits(r: &mut Renderer, scene: &Scene) -> Vec<(String, Vec<u32>)> {
    let plan = FramePlan::new(scene, OutputKind::Ldr);
    let f = r.run(scene, &plan).unwrap_or_else(|e| panic!("{e}"));
    let mut out: Vec<(String, Vec<u32>)> = f
        .maps
        .iter()
        .map(|(m, t)| (format!("{m:?}"), t.texels.iter().flatten().map(|v| v.to_bits()).collect()))
        .collect();
    out.push(("ldr".into(), f.ldr.unwrap().into_iter().map(u32::from).collect()));
    out
}

/// The maps and pictures of two renders that differ, by name, with the count of differing
/// values.
fn differing(a: &[(String, Vec<u32>)], b: &[(String, Vec<u32>)]) -> Vec<(String, usize)> {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .filter_map(|((n, x), (_, y))| {
            let d = if x.len() == y.len() {
                x.iter().zip(y).filter(|(p, q)| p != q).count()
            } else {
                x.len().max(y.len())
            };
            (d > 0).then(|| (n.clone(), d))
        })
        .collect()
}

/// The water and the objects (main view, reflection and refraction maps) shaded in compute
/// from the visibility buffer (issue 37) store the same bits as the fragment shaders that
/// shade each fragment where it is rasterised: every map and the
/// picture of every reference scene at 96×54 (all four systems, every surface, 16-bit frames,
/// the camera under the water). On lavapipe the renderer picks the compute path by itself.
/// Negative control: the same comparison between the scene and the scene 1 ms later finds
/// the HDR frame changed.
fn the_shading_paths_store_the_same_bits() {
    use ocean_gpu::ShadingPath;
    let mut r = renderer();
    assert_eq!(r.shading_path(), ShadingPath::Compute, "lavapipe holds the visibility buffer");
    let scenes = reference_scenes::reference_scenes();
    assert!(scenes.len() >= 28, "{} reference scenes", scenes.len());
    let mut control = None;
    for (name, mut scene) in scenes {
        (scene.camera.width, scene.camera.height) = (96, 54);
        r.set_shading_path(ShadingPath::Compute).unwrap();
        let compute = frame_bits(&mut r, &scene);
        r.set_shading_path(ShadingPath::Fragment).unwrap();
        let fragment = frame_bits(&mut r, &scene);
        let d = differing(&compute, &fragment);
        assert!(d.is_empty(), "{name}: the compute and fragment paths differ: {d:?}");
        eprintln!(
            "{name}: {} maps and the picture, the same bits on both paths",
            compute.len() - 1
        );
        if name == "default" {
            let mut later = scene.clone();
            later.ocean.time_s += 0.001;
            r.set_shading_path(ShadingPath::Compute).unwrap();
            control = Some(differing(&compute, &frame_bits(&mut r, &later)));
        }
    }
    let control = control.expect("the default scene");
    assert!(
        control.iter().any(|(n, c)| n == "Hdr" && *c > 0),
        "the control (1 ms later) was not told apart: {control:?}"
    );
    eprintln!("control, 1 ms later: {control:?}");
}

fn main() -> std::process::ExitCode {
    run_tests!(gpu_harness::GPU_ADAPTER;
        cpu: the_size_check_fails_on_a_map_of_another_size;
        gpu: quality_scenes_match_the_cpu_oracle,
            every_resource_both_back_ends_allocate_has_the_plans_size,
            the_gpu_plays_the_cycle_the_plan_precomputes,
            object_geometry_cut_into_small_buffers_draws_the_same_picture,
            extreme_scenes_render_finite_pixels_on_the_gpu,
            the_shading_paths_store_the_same_bits;
    )
}
