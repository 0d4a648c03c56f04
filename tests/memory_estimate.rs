//! The memory estimate (`ocean_core::plan::memory`) against what the CPU back end really
//! allocates: a counting allocator (`cap`, with its `stats`) records the peak heap of each
//! render, and the estimate must lie between that peak and [`MAX_OVERESTIMATE`] times it, so
//! that a render the limit accepts fits and one it refuses would not have been close.
//!
//! Each case runs in a child process of this test binary: the allocator's peak cannot be
//! reset, and a case must not see another's peak.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use std::alloc::System;

use cap::Cap;
use ocean_core::plan::memory::{MemoryBackend, MemoryEstimate, bytes};
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::{Scene, SceneSource};

#[global_allocator]
static ALLOCATOR: Cap<System> = Cap::new(System, usize::MAX);

/// How far above the measured peak the estimate may be: it adds items that are never alive
/// together (the wave scratch is freed before the water pass).
const MAX_OVERESTIMATE: f64 = 4.0;

fn spheres(n: usize) -> String {
    (0..n)
        .map(|i| {
            format!(
                "[[objects]]\nkind = \"sphere\"\ncenter = [{}.0, {}.0, -30.0]\nradius = 0.4\n",
                (i % 20) as i64 - 10,
                i / 20 % 10
            )
        })
        .collect()
}

fn cases() -> Vec<(&'static str, String, OutputKind)> {
    let small = "[camera]\nwidth = 160\nheight = 90\n";
    let sun = "[sun]\ndirection = [0.3, 0.5, -1.0]\n";
    vec![
        ("160×90", small.into(), OutputKind::Ldr),
        ("1280×720 with sun and objects", format!("{sun}{}", spheres(4)), OutputKind::Ldr),
        ("1280×720 EXR", format!("{sun}{}", spheres(4)), OutputKind::Hdr),
        (
            "resolution 1024",
            format!("{small}[ocean]\nresolution = 1024\nbump_resolution = 1024\n"),
            OutputKind::Ldr,
        ),
        ("fresnel 2048", format!("{small}[quality]\nfresnel_table_size = 2048\n"), OutputKind::Ldr),
        (
            "lod 0.001, resolution 1024",
            format!("{small}[ocean]\nresolution = 1024\n[quality]\nlod_split_threshold = 0.001\n"),
            OutputKind::Ldr,
        ),
        ("200 spheres in view", format!("{small}{sun}{}", spheres(200)), OutputKind::Ldr),
        ("2000 spheres", format!("{small}{sun}{}", spheres(2000)), OutputKind::Ldr),
    ]
}

fn scene(text: &str) -> Scene {
    Scene::from_toml(text, SceneSource::Text).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_estimate_bounds_the_peak_heap_of_a_cpu_render() {
    if let Ok(i) = std::env::var("OCEAN_MEMORY_CASE") {
        let (_, text, kind) = cases().swap_remove(i.parse().unwrap());
        let scene = scene(&text);
        let before = ALLOCATOR.allocated();
        let r = ocean_cpu::render_scene(&scene, kind, &mut |_| {}).unwrap();
        drop(r);
        println!("PEAK {}", ALLOCATOR.max_allocated() - before);
        return;
    }
    let mut failures = Vec::new();
    for (i, (name, text, kind)) in cases().into_iter().enumerate() {
        let out = std::process::Command::new(std::env::current_exe().unwrap())
            .args(["--exact", "the_estimate_bounds_the_peak_heap_of_a_cpu_render", "--nocapture"])
            .env("OCEAN_MEMORY_CASE", i.to_string())
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        let peak: u64 = stdout
            .lines()
            .find_map(|l| l.strip_prefix("PEAK "))
            .unwrap_or_else(|| panic!("{name}: no peak from the child: {stdout}"))
            .parse()
            .unwrap();
        let s = scene(&text);
        let estimate =
            MemoryEstimate::of(&s, &FramePlan::new(&s, kind), MemoryBackend::Cpu).total();
        let ratio = estimate as f64 / peak as f64;
        eprintln!(
            "{name:32} peak {:>10}  estimate {:>10}  ratio {ratio:.2}",
            bytes(peak),
            bytes(estimate)
        );
        if name == "resolution 1024" {
            // Negative control: without its wave-synthesis items the estimate falls below the
            // measured peak, so the bound above can fail.
            let e = MemoryEstimate::of(&s, &FramePlan::new(&s, kind), MemoryBackend::Cpu);
            let without: u64 =
                e.items.iter().filter(|i| !i.what.contains("synthesis")).map(|i| i.bytes).sum();
            assert!(
                without < peak,
                "{name}: {} without the waves, peak {}",
                bytes(without),
                bytes(peak)
            );
        }
        if !(1.0..=MAX_OVERESTIMATE).contains(&ratio) {
            failures.push(format!(
                "{name}: estimate {} for a peak of {} (ratio {ratio:.2})",
                bytes(estimate),
                bytes(peak)
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_limit_below_the_estimate_refuses_with_the_key_that_drives_it() {
    let s = scene("[ocean]\nresolution = 4096\nbump_resolution = 4096\n");
    let e = MemoryEstimate::of(&s, &FramePlan::new(&s, OutputKind::Ldr), MemoryBackend::Cpu);
    let err = e.check(1 << 30).unwrap_err().to_string();
    assert!(err.contains("ocean.") && err.contains("--memory-limit"), "{err}");
    assert!(e.check(e.total()).is_ok(), "the estimate itself is within a limit equal to it");
}
