//! The CPU renderer's frame time (issue 3): the default scene at 320×180 and 1280×720, whole
//! frames (waves → tonemap), and before the criterion runs, the share of each pass (median of
//! a few frames, printed to stderr). The goal is a warm 1280×720 frame under 0.25 s on the
//! 2-core reference machine.
//!
//! `cargo bench --bench cpu_frame`

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use ocean_core::plan::{OutputKind, Pass};
use ocean_core::scene::Scene;

fn scene(w: u32, h: u32) -> Scene {
    let mut s = Scene::builtin();
    s.camera.width = w;
    s.camera.height = h;
    s
}

fn pass_shares(w: u32, h: u32) {
    let s = scene(w, h);
    let runs = 7;
    let mut per_pass: Vec<(Pass, Vec<Duration>)> = Vec::new();
    for _ in 0..runs {
        let r = ocean_cpu::render_scene(&s, OutputKind::Ldr, &mut |_| {}).expect("render");
        for (p, d) in r.buffers.timings {
            match per_pass.iter_mut().find(|(q, _)| *q == p) {
                Some((_, v)) => v.push(d),
                None => per_pass.push((p, vec![d])),
            }
        }
    }
    let medians: Vec<(Pass, f64)> = per_pass
        .into_iter()
        .map(|(p, mut v)| {
            v.sort();
            (p, v[v.len() / 2].as_secs_f64() * 1e3)
        })
        .collect();
    let total: f64 = medians.iter().map(|m| m.1).sum();
    eprintln!("cpu_frame {w}x{h}: passes (median of {runs}), sum {total:.1} ms");
    for (p, ms) in medians {
        eprintln!("  {:<15} {ms:8.2} ms  {:5.1} %", p.name(), 100.0 * ms / total);
    }
}

fn bench(c: &mut Criterion) {
    for (w, h) in [(320, 180), (1280, 720)] {
        pass_shares(w, h);
    }
    let mut group = c.benchmark_group("cpu_frame");
    group.sample_size(10);
    for (w, h) in [(320u32, 180u32), (1280, 720)] {
        let s = scene(w, h);
        group.bench_with_input(
            BenchmarkId::new("default_scene", format!("{w}x{h}")),
            &s,
            |b, s| b.iter(|| black_box(ocean_cpu::render_ldr(s).expect("render"))),
        );
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
