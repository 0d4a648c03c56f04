//! A steady GPU frame wastes nothing (issue 17, item 2), counted by `ocean_gpu::created` (every
//! `create_*` of the crate goes through it; the source test below fails on one that does not):
//!
//! - for each system, after three warm-up frames, 100 animated frames (time moving, timings
//!   read back as the viewer reads them, every tenth frame's picture read back) make no
//!   texture, view, buffer, bind group, query set, sampler or pipeline; the warm-up did make
//!   them (the counter's control), and so does a resize (the plan's sizes changed), after which
//!   the frames are steady again;
//! - frames whose timestamps nobody reads (a benchmark's, a viewer closing) make no query set
//!   either: their queries come back to the pool once their buffer has mapped; the control
//!   holds the frames' timings unread, and then every frame needs a query set of its own;
//! - the Fresnel tables are computed on the first frame and when η changes, and kept
//!   otherwise (`GpuFrame::reused`), with the same picture as a fresh renderer's;
//! - the same frame twice uploads no uniform block the second time, and a block asked for
//!   twice in a frame with the same bytes (the sky's, read by `sky` and `water`) is one buffer
//!   uploaded once;
//! - the vertex and index lists (the objects', the water mesh's) likewise: the same frame
//!   twice uploads none the second time, a moved object or a turned camera uploads what
//!   changed and draws a fresh renderer's picture.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;

use ocean_core::graph::FrameState;
use ocean_core::plan::{FramePlan, OutputKind, Pass, SYSTEMS, System};
use ocean_core::scene::Scene;
use ocean_gpu::created::{ObjectCounts, created};
use ocean_gpu::{Readback, Renderer};

const W: u32 = 160;
const H: u32 = 90;
/// Frames after a resize before the old sizes' objects are let go.
const KEEP: u64 = ocean_gpu::pool::KEEP_SMALL + 1;

fn scene(system: System, w: u32, h: u32) -> Scene {
    let mut s = Scene::builtin_for(system).with_system(system).unwrap();
    (s.camera.width, s.camera.height) = (w, h);
    s
}

/// One animated frame as the viewer runs it: nothing read back but, when `picture`, the
/// output (returned); the timestamps collected once the GPU is done.
fn frame(
    r: &mut Renderer,
    s: &Scene,
    plan: &FramePlan,
    state: &mut FrameState,
    picture: bool,
) -> Option<Vec<u8>> {
    let readback = if picture { Readback::Output } else { Readback::None };
    let f = r.run_frame(s, plan, state, readback).unwrap();
    r.gpu().wait().unwrap();
    if let Some(p) = f.pending_timings {
        p.try_take().expect("timestamps read back after the wait").unwrap();
    }
    if picture {
        assert!(f.ldr.as_ref().is_some_and(|b| b.iter().any(|&v| v > 0)), "a black picture");
    }
    f.ldr
}

fn steady_frames_make_no_gpu_objects() {
    for info in SYSTEMS {
        let system = info.system;
        let s = scene(system, W, H);
        let plan = FramePlan::new(&s, OutputKind::Ldr);
        let before = created();
        let mut r = Renderer::new().unwrap();
        let mut state = FrameState::new(1.0 / 30.0);
        for _ in 0..3 {
            frame(&mut r, &s, &plan, &mut state, true);
        }
        let warm = created().since(before);
        eprintln!("{}: the renderer and its first three frames made {warm}", system.name());
        assert!(warm.textures > 0 && warm.bind_groups > 0, "the counter counted nothing");

        let start = created();
        let mut pictures = Vec::new();
        for i in 0..100 {
            pictures.extend(frame(&mut r, &s, &plan, &mut state, i % 10 == 0));
        }
        let made = created().since(start);
        eprintln!("{}: 100 steady frames made {made}", system.name());
        assert_eq!(made.objects(), 0, "{}: steady frames made {made}", system.name());
        assert_eq!(pictures.len(), 10);
        assert_ne!(pictures[0], pictures[9], "{}: the sea stood still", system.name());

        // A resize: new targets (the control), then steady again at the new size.
        let big = scene(system, 2 * W, 2 * H);
        let big_plan = FramePlan::new(&big, OutputKind::Ldr);
        let start = created();
        frame(&mut r, &big, &big_plan, &mut state, true);
        let resized = created().since(start);
        assert!(resized.textures > 0, "{}: a resize made no target", system.name());
        for _ in 0..KEEP {
            frame(&mut r, &big, &big_plan, &mut state, true);
        }
        let start = created();
        for _ in 0..20 {
            frame(&mut r, &big, &big_plan, &mut state, false);
        }
        let made = created().since(start);
        assert_eq!(made.objects(), 0, "{}: after the resize: {made}", system.name());
    }
}

fn unread_timings_make_no_query_sets() {
    let s = scene(System::Hu, W, H);
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    let mut r = Renderer::new().unwrap();
    if !r.gpu().timestamps {
        eprintln!(
            "{}: no timestamp queries on this adapter; nothing to check",
            r.gpu().report.name
        );
        return;
    }
    let mut state = FrameState::new(1.0 / 30.0);
    for _ in 0..3 {
        frame(&mut r, &s, &plan, &mut state, true);
    }
    // Frames whose timings are dropped unread (`hold: false`) or held unread.
    let mut unread = |r: &mut Renderer, n: usize, hold: bool| {
        let (start, mut held) = (created(), Vec::new());
        for _ in 0..n {
            let f = r.run_frame(&s, &plan, &mut state, Readback::None).unwrap();
            r.gpu().wait().unwrap();
            if hold {
                held.extend(f.pending_timings);
            }
        }
        created().since(start)
    };
    // Control: timings held unread keep their queries, so each frame makes a set once the
    // pool's one free set (the warm-up's, read and given back) is taken.
    let made = unread(&mut r, 5, true);
    assert_eq!(made.query_sets, 4, "5 frames with their timings held made {made}");
    let made = unread(&mut r, 50, false);
    assert_eq!(made.objects(), 0, "50 frames with their timings dropped made {made}");
}

fn fresnel_tables_are_computed_only_when_eta_changes() {
    let s = scene(System::Hu, W, H);
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    let mut r = Renderer::new().unwrap();
    let first = r.run_with(&s, &plan, Readback::All).unwrap();
    assert!(!first.reused.contains(&Pass::FresnelTable), "the first frame reused a table");
    let second = r.run_with(&s, &plan, Readback::All).unwrap();
    assert!(second.reused.contains(&Pass::FresnelTable), "the tables were computed again");
    assert_eq!(first.ldr, second.ldr, "the kept tables changed the picture");

    let mut other = s.clone();
    other.water.ior = 1.20;
    let other_plan = FramePlan::new(&other, OutputKind::Ldr);
    let changed = r.run_with(&other, &other_plan, Readback::All).unwrap();
    assert!(!changed.reused.contains(&Pass::FresnelTable), "η changed, the tables were kept");
    let fresh = Renderer::new().unwrap().run_with(&other, &other_plan, Readback::All).unwrap();
    assert_eq!(changed.ldr, fresh.ldr, "the recomputed tables differ from a fresh renderer's");
    for map in [ocean_gpu::FrameMap::FresnelAbove, ocean_gpu::FrameMap::FresnelBelow] {
        assert_eq!(changed.map(map), fresh.map(map), "{map:?}");
    }
    assert_ne!(first.ldr, changed.ldr, "η 1.33 and 1.20 drew the same picture");
}

fn uniform_blocks_are_uploaded_once_and_only_on_change() {
    let s = scene(System::Hu, W, H);
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    let mut r = Renderer::new().unwrap();
    r.run_with(&s, &plan, Readback::Output).unwrap();
    let start = created();
    let again = r.run_with(&s, &plan, Readback::Output).unwrap();
    let made = created().since(start);
    assert_eq!(made, ObjectCounts::default(), "the same frame again made or uploaded {made}");
    assert!(again.ldr.is_some());

    let gpu = r.gpu();
    let pool = ocean_gpu::pool::FramePool::new(&gpu.device, &gpu.queue);
    pool.begin_frame();
    let start = created();
    let a = pool.uniform("sky", &[1.0f32; 4]);
    let b = pool.uniform("sky", &[1.0f32; 4]);
    let c = pool.uniform("sky", &[2.0f32; 4]);
    assert_eq!(a, b, "the same block twice in a frame is one buffer");
    assert_ne!(a, c, "another block under the same label shared a buffer");
    assert_eq!(created().since(start).uniform_writes, 2);
    pool.begin_frame();
    let start = created();
    assert_eq!(pool.uniform("sky", &[1.0f32; 4]), a);
    assert_eq!(pool.uniform("sky", &[3.0f32; 4]), c, "the second block kept its buffer");
    let next = created().since(start);
    assert_eq!((next.uniform_writes, next.buffers), (1, 0), "only the changed block: {next}");
}

/// The frame's vertex and index lists (the objects', the water mesh's) are uploaded when
/// they change and not again: the same frame twice uploads none the second time; a moved
/// object uploads its passes' triangles, a turned camera the water mesh, and each draws a
/// fresh renderer's picture.
fn vertex_lists_are_uploaded_once_and_only_on_change() {
    let s = scene(System::Hu, W, H);
    assert!(!s.objects.is_empty(), "the default scene has objects");
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    let mut r = Renderer::new().unwrap();
    let first = r.run_with(&s, &plan, Readback::Output).unwrap();
    let start = created();
    let again = r.run_with(&s, &plan, Readback::Output).unwrap();
    assert_eq!(created().since(start).data_writes, 0, "the same frame uploaded its lists again");
    assert_eq!(first.ldr, again.ldr, "the kept lists changed the picture");

    let mut moved = s.clone();
    moved.objects[0].center[0] += 0.5;
    let mut turned = s.clone();
    turned.camera.look_at[0] += 5.0;
    for (what, changed) in [("a moved object", moved), ("a turned camera", turned)] {
        let changed_plan = FramePlan::new(&changed, OutputKind::Ldr);
        let start = created();
        let frame = r.run_with(&changed, &changed_plan, Readback::Output).unwrap();
        let writes = created().since(start).data_writes;
        eprintln!("{what}: {writes} vertex/index uploads");
        assert!(writes > 0, "{what} uploaded nothing");
        let fresh =
            Renderer::new().unwrap().run_with(&changed, &changed_plan, Readback::Output).unwrap();
        assert_eq!(frame.ldr, fresh.ldr, "{what}: the picture differs from a fresh renderer's");
        assert_ne!(frame.ldr, first.ldr, "{what} drew the first picture");
        // And back: the first frame's lists again, drawn as at first.
        let back = r.run_with(&s, &plan, Readback::Output).unwrap();
        assert_eq!(back.ldr, first.ldr, "{what}, then the first frame: another picture");
    }
}

/// The `create_*` calls of `source` outside comments: what would bypass the counter.
fn uncounted(source: &str) -> Vec<String> {
    const CALLS: [&str; 12] = [
        ".create_texture(",
        ".create_view(",
        ".create_buffer(",
        ".create_buffer_init(",
        ".create_bind_group(",
        ".create_bind_group_layout(",
        ".create_query_set(",
        ".create_sampler(",
        ".create_render_pipeline(",
        ".create_compute_pipeline(",
        ".create_shader_module(",
        ".create_pipeline_layout(",
    ];
    source
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .filter(|l| CALLS.iter().any(|c| l.contains(c)))
        .map(str::to_owned)
        .collect()
}

fn every_gpu_object_of_the_crate_is_counted() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/ocean-gpu/src");
    let mut files = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "rs") || path.ends_with("created.rs") {
            continue;
        }
        files += 1;
        let found = uncounted(&std::fs::read_to_string(&path).unwrap());
        assert!(found.is_empty(), "{}: uncounted {found:?}", path.display());
    }
    assert!(files > 10, "read {files} files of {}", dir.display());
    // Control: a call the scan must see, and the same call in a comment, which it must not.
    let planted = "let t = device.create_texture(&d);\n// device.create_buffer(&d)\n";
    assert_eq!(uncounted(planted).len(), 1);
}

fn main() -> std::process::ExitCode {
    run_tests!(gpu_harness::GPU_ADAPTER;
        cpu: every_gpu_object_of_the_crate_is_counted;
        gpu: steady_frames_make_no_gpu_objects,
            unread_timings_make_no_query_sets,
            fresnel_tables_are_computed_only_when_eta_changes,
            uniform_blocks_are_uploaded_once_and_only_on_change,
            vertex_lists_are_uploaded_once_and_only_on_change;
    )
}
