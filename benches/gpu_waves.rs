//! GPU wave synthesis (`ocean_gpu::waves::GpuWaves`: h̃(k, t), the eight spectra, the
//! radix-2 Stockham FFT and the packing into three textures) at N = 256 and 512, next to the
//! CPU's ocean-core `Synthesizer<f32>` (all six maps) and the stage's CPU mirror of the same
//! size, in one run. A GPU iteration records the frame, submits it and waits for the device
//! (no readback): wall time per frame as the caller sees it. On lavapipe that is CPU time of
//! the driver's threads, so the ratio to the CPU synthesis is a property of this machine.
//!
//! Without an adapter the GPU entries are skipped (the reason is printed).
//! `WGPU_BACKEND=vulkan cargo bench --bench gpu_waves`

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use ocean_core::scene::Ocean;
use ocean_core::waves::{Synthesizer, WaveMaps};
use ocean_cpu::shaders::waves::WavesMirror;
use ocean_gpu::waves::GpuWaves;

async fn open_gpu() -> Result<(wgpu::Device, wgpu::Queue, String), String> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = wgpu::util::initialize_adapter_from_env_or_default(&instance, None)
        .await
        .map_err(|e| e.to_string())?;
    let name = adapter.get_info().name;
    let (device, queue) = adapter
        .request_device(&wgpu::DeviceDescriptor {
            label: Some("ocean.bench"),
            required_limits: adapter.limits(),
            ..Default::default()
        })
        .await
        .map_err(|e| e.to_string())?;
    Ok((device, queue, name))
}

fn bench(c: &mut Criterion) {
    let gpu = pollster::block_on(open_gpu());
    match &gpu {
        Ok((_, _, name)) => println!("GPU: {name}"),
        Err(e) => println!("GPU entries skipped: no adapter ({e})"),
    }
    let mut group = c.benchmark_group("gpu_waves");
    group.sample_size(20);
    for n in [256usize, 512] {
        let ocean = Ocean { resolution: n as u32, ..Ocean::default() };
        let modes = ocean.displacement_modes().expect("default ocean is valid");

        let mut synth = Synthesizer::<f32>::new(n).expect("synthesizer");
        let mut maps = WaveMaps::<f32>::new(n, ocean.patch_size_m);
        group.bench_with_input(BenchmarkId::new("cpu_synthesizer_f32", n), &n, |b, _| {
            let mut t = 0.0;
            b.iter(|| {
                t += 0.016;
                synth.synthesize_into(&modes, t, 1.0, &mut maps).expect("maps");
                black_box(&maps.height);
            })
        });

        let mirror = WavesMirror::new(&modes).expect("power-of-two N");
        group.bench_with_input(BenchmarkId::new("cpu_mirror", n), &n, |b, _| {
            let mut t = 0.0;
            b.iter(|| {
                t += 0.016;
                black_box(mirror.run(t, 1.0).expect("mirror"));
            })
        });

        if let Ok((device, queue, _)) = &gpu {
            let waves = GpuWaves::new(device, &modes).expect("GpuWaves");
            group.bench_with_input(BenchmarkId::new("gpu_frame", n), &n, |b, _| {
                let mut t = 0.0;
                b.iter(|| {
                    t += 0.016;
                    let mut encoder = device.create_command_encoder(&Default::default());
                    waves.encode(queue, &mut encoder, t, 1.0).expect("encode");
                    queue.submit([encoder.finish()]);
                    device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
