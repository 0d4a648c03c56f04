//! The GPU renderer's frame (issue 4): the default scene at 1280×720 and 1920×1080 on the
//! adapter the environment selects (CI and the reference machine: lavapipe, WGPU_BACKEND=vulkan),
//! and the CPU renderer's time for the same frame in the same run.
//!
//! Before the criterion runs it prints, per size, the GPU time of each pass from timestamp
//! queries (median of a few frames; `waves` is the GPU FFT, or, where the CPU synthesis is
//! uploaded, timed on the CPU) and the wall time of a whole frame on each back end with the
//! ratio CPU / GPU. Wall time covers setup, encoding, the GPU work and reading the 8-bit
//! picture back (`Readback::Output`); the CPU frame likewise ends with the 8-bit picture.
//! `gpu_stream` is the real-time viewer's case: frames submitted back to back with nothing
//! read back (`Readback::None`), the GPU waited for once per batch, time per frame. Without an
//! adapter the bench says so and measures nothing.
//!
//! `WGPU_BACKEND=vulkan cargo bench --bench gpu_frame`

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use ocean_core::plan::{FramePlan, OutputKind, Pass};
use ocean_core::scene::Scene;
use ocean_gpu::{Readback, Renderer};

const SIZES: [(u32, u32); 2] = [(1280, 720), (1920, 1080)];

fn scene(w: u32, h: u32) -> Scene {
    let mut s = Scene::builtin();
    s.camera.width = w;
    s.camera.height = h;
    s
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// GPU time per pass and the wall-time ratio, printed.
fn report(renderer: &mut Renderer, w: u32, h: u32) {
    let s = scene(w, h);
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    let runs = 5;
    let mut per_pass: Vec<(Pass, Vec<Duration>)> = Vec::new();
    let (mut gpu_wall, mut cpu_wall, mut waves) = (Vec::new(), Vec::new(), Vec::new());
    renderer.run_with(&s, &plan, Readback::Output).expect("warm-up frame");
    for _ in 0..runs {
        let f = renderer.run_with(&s, &plan, Readback::Output).expect("GPU frame");
        gpu_wall.push(f.wall);
        waves.extend(f.waves_cpu);
        for (p, d) in f.gpu_timings {
            match per_pass.iter_mut().find(|(q, _)| *q == p) {
                Some((_, v)) => v.push(d),
                None => per_pass.push((p, vec![d])),
            }
        }
        let t0 = Instant::now();
        black_box(ocean_cpu::render_ldr(&s).expect("CPU frame"));
        cpu_wall.push(t0.elapsed());
    }
    let (g, c) = (median(gpu_wall), median(cpu_wall));
    eprintln!("gpu_frame {w}x{h} on {} (median of {runs}):", renderer.adapter());
    if per_pass.is_empty() {
        eprintln!("  (no TIMESTAMP_QUERY on this adapter: no GPU time per pass)");
    }
    if !waves.is_empty() {
        eprintln!("  {:<15} {:8.2} ms  (CPU synthesis + upload)", "waves", ms(median(waves)));
    }
    let mut sum = 0.0;
    for (p, v) in per_pass {
        let m = ms(median(v));
        sum += m;
        eprintln!("  {:<15} {m:8.2} ms  GPU", p.name());
    }
    eprintln!(
        "  passes on the GPU {sum:.1} ms; frame wall time: GPU {:.1} ms, CPU renderer {:.1} ms, CPU / GPU = {:.2}",
        ms(g),
        ms(c),
        c.as_secs_f64() / g.as_secs_f64()
    );
}

fn bench(c: &mut Criterion) {
    let mut renderer = match Renderer::new() {
        Ok(r) => r,
        Err(e) => {
            eprintln!("gpu_frame: SKIPPED, no GPU renderer: {e}");
            return;
        }
    };
    for (w, h) in SIZES {
        report(&mut renderer, w, h);
    }
    let mut group = c.benchmark_group("gpu_frame");
    group.sample_size(10).warm_up_time(Duration::from_secs(1));
    for (w, h) in SIZES {
        let s = scene(w, h);
        let plan = FramePlan::new(&s, OutputKind::Ldr);
        group.bench_with_input(BenchmarkId::new("gpu", format!("{w}x{h}")), &s, |b, s| {
            b.iter(|| black_box(renderer.run_with(s, &plan, Readback::Output).expect("GPU frame")))
        });
        group.bench_with_input(BenchmarkId::new("gpu_stream", format!("{w}x{h}")), &s, |b, s| {
            b.iter_custom(|iters| {
                let t0 = Instant::now();
                for _ in 0..iters {
                    black_box(renderer.run_with(s, &plan, Readback::None).expect("GPU frame"));
                }
                renderer.gpu().wait().expect("GPU idle");
                t0.elapsed()
            })
        });
        group.bench_with_input(BenchmarkId::new("cpu", format!("{w}x{h}")), &s, |b, s| {
            b.iter(|| black_box(ocean_cpu::render_ldr(s).expect("CPU frame")))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
