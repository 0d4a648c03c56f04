//! The `waves` stage: its CPU mirror (`ocean_cpu::shaders::waves`) against ocean-core's FFT
//! synthesis, the GPU (`ocean_gpu::waves`) against the mirror dispatch by dispatch, the phase
//! at t = 10⁶ s and looping on both, and a negative control for every comparator.
//!
//! Measures (printed with `--nocapture`):
//! - "rel": max |value − reference| over a field divided by the max |reference| of that field
//!   (as in tests/waves.rs); mirror vs ocean-core must be ≤ 1e-5 (docs/design.md, FFT synthesis in
//!   f32).
//! - GPU vs mirror: every element within abs 1e-6 + rel 1e-5·|mirror| (docs/design.md, CPU vs GPU
//!   float buffers) *and* rel ≤ 1e-5 per field — the second is the stricter one for the
//!   spectra, whose values are mostly below 1e-6.
//!
//! GPU tests need an adapter (`WGPU_BACKEND=vulkan` with Mesa's lavapipe is enough). Without
//! one they are reported ignored, with why (tests/support/gpu_harness.rs; those with a CPU
//! part run that part first), unless `OCEAN_REQUIRE_GPU=1`, which makes that a failure (CI).
//! Each GPU test prints the adapter that ran.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;

use std::f64::consts::TAU;
use std::sync::OnceLock;

use ocean_core::GRAVITY as G;
use ocean_core::dispersion::Dispersion;
use ocean_core::waves::uniforms::{WavesUniforms, wave_mode_table};
use ocean_core::waves::{ModeParams, Synthesizer, WaveMaps, WaveModes};
use ocean_cpu::shaders::waves::{self as mirror, Dispatch, WaveTextures, WavesMirror};
use ocean_gpu::waves::{GpuWaves, WaveTexture, WavesError};

// ---------------------------------------------------------------------------------------------
// Inputs

/// Phillips-like F(kx, kz) with one-sided spreading, so that F(k) ≠ F(−k) (the two halves of
/// h̃ differ) — as in tests/waves.rs.
fn spectrum_density(kx: f64, kz: f64) -> f64 {
    let l_wind = 10.0 * 10.0 / G;
    let l_small = l_wind / 1000.0;
    let k2 = kx * kx + kz * kz;
    if k2 == 0.0 {
        return 0.0;
    }
    let cos_wind = (kx * 0.3f64.cos() + kz * 0.3f64.sin()) / k2.sqrt();
    let spreading = if cos_wind >= 0.0 { cos_wind * cos_wind } else { 0.1 * cos_wind * cos_wind };
    0.01 * (-1.0 / (k2 * l_wind * l_wind)).exp() / (k2 * k2)
        * spreading
        * (-k2 * l_small * l_small).exp()
}

fn build(n: usize, dispersion: Dispersion) -> WaveModes {
    WaveModes::new(&ModeParams::new(200.0, n, 7), dispersion, spectrum_density).expect("modes")
}

const SIZES: [usize; 3] = [16, 64, 256];
const CHOPPINESS: [f64; 2] = [0.0, 1.3];
/// A loop period for the looping cases, s.
const LOOP_S: f64 = 20.0;

// ---------------------------------------------------------------------------------------------
// Comparators

/// The six fields (height, disp_x, disp_z, slope_x, slope_z, jacobian) of the packed textures,
/// in `WaveMaps::FIELD_NAMES` order; also checks that `bump` repeats the same values.
fn fields_of(textures: &[Vec<[f32; 4]>; 3]) -> [Vec<f32>; 6] {
    let [disp, slopes, bump] = textures;
    for ((d, s), b) in disp.iter().zip(slopes).zip(bump) {
        assert_eq!([s[0], s[1], d[1], d[3]].map(f32::to_bits), b.map(f32::to_bits));
        assert_eq!([s[2], s[3]], [0.0, 0.0]);
    }
    let channel = |t: &Vec<[f32; 4]>, c: usize| t.iter().map(|v| v[c]).collect::<Vec<f32>>();
    [
        channel(disp, 1),
        channel(disp, 0),
        channel(disp, 2),
        channel(slopes, 0),
        channel(slopes, 1),
        channel(disp, 3),
    ]
}

fn texels(t: &WaveTextures) -> [Vec<[f32; 4]>; 3] {
    [t.displacement.texels.clone(), t.displacement_slopes.texels.clone(), t.bump.texels.clone()]
}

fn maps_fields<T: ocean_core::waves::MapFloat>(m: &WaveMaps<T>) -> [Vec<f64>; 6] {
    m.fields().map(|(_, f)| f.iter().map(|v| v.cast_to_f64()).collect())
}

/// rel of one field: max |a − b| / max |b| (the absolute error where b is all 0).
fn rel_error(a: &[f32], b: &[f64]) -> f64 {
    let max_b = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = a.iter().zip(b).fold(0.0f64, |m, (&x, &y)| m.max((f64::from(x) - y).abs()));
    if max_b > 0.0 { err / max_b } else { err }
}

fn rel_errors(a: &[Vec<f32>; 6], b: &[Vec<f64>; 6]) -> [f64; 6] {
    std::array::from_fn(|f| rel_error(&a[f], &b[f]))
}

fn worst(e: &[f64]) -> f64 {
    e.iter().copied().fold(0.0, f64::max)
}

/// docs/design.md: CPU vs GPU float buffers.
const GPU_REL: f64 = 1e-5;
const GPU_ABS: f64 = 1e-6;
/// docs/design.md: FFT synthesis vs the reference, f32.
const SYNTHESIS_REL: f64 = 1e-5;

/// GPU (`a`) against the mirror (`b`) for one field.
#[derive(Debug)]
struct Comparison {
    /// max |a − b| / max |b|.
    rel: f64,
    /// max |a − b|.
    max_abs: f64,
    /// Where the largest |a − b| is, and how many elements differ at all.
    worst_index: usize,
    differing: usize,
    /// Elements outside abs + rel·|b|.
    outside: usize,
}

impl Comparison {
    fn new(a: &[f32], b: &[f32]) -> Self {
        assert_eq!(a.len(), b.len());
        let max_b = b.iter().fold(0.0f64, |m, v| m.max(f64::from(*v).abs()));
        let (mut max_abs, mut worst_index, mut differing, mut outside) = (0.0, 0, 0, 0);
        for (i, (&x, &y)) in a.iter().zip(b).enumerate() {
            let d = (f64::from(x) - f64::from(y)).abs();
            if x.to_bits() != y.to_bits() && d > 0.0 {
                differing += 1;
            }
            if d.is_nan() || d > GPU_ABS + GPU_REL * f64::from(y).abs() {
                outside += 1;
            }
            if d > max_abs || d.is_nan() {
                max_abs = d;
                worst_index = i;
            }
        }
        let rel = if max_b > 0.0 { max_abs / max_b } else { max_abs };
        Self { rel, max_abs, worst_index, differing, outside }
    }

    fn ok(&self) -> bool {
        self.outside == 0 && self.rel <= GPU_REL
    }
}

/// Splits a 4·N² complex buffer into its 8 real components (array f, re/im).
fn components(buffer: &[[f32; 2]], n: usize) -> Vec<Vec<f32>> {
    let plane = n * n;
    (0..8).map(|c| buffer[(c / 2) * plane..][..plane].iter().map(|v| v[c % 2]).collect()).collect()
}

// ---------------------------------------------------------------------------------------------
// GPU access

struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
}

static GPU: OnceLock<Result<Gpu, String>> = OnceLock::new();

async fn open_gpu() -> Result<Gpu, String> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = wgpu::util::initialize_adapter_from_env_or_default(&instance, None)
        .await
        .map_err(|e| format!("no adapter: {e}"))?;
    gpu_harness::testable(&adapter.get_info())?;
    let (device, queue) = adapter
        .request_device(&wgpu::DeviceDescriptor {
            label: Some("ocean.test"),
            required_limits: adapter.limits(),
            ..Default::default()
        })
        .await
        .map_err(|e| format!("adapter {} gave no device: {e}", adapter.get_info().name))?;
    Ok(Gpu { device, queue, info: adapter.get_info() })
}

/// The harness's probe: opens the shared device once, before the tests run.
fn probe() -> Result<(), String> {
    GPU.get_or_init(|| pollster::block_on(open_gpu())).as_ref().map(|_| ()).map_err(Clone::clone)
}

/// The shared device, or `None` without one (the harness then reports the test ignored, as
/// its GPU part did not run) — a failure instead when `OCEAN_REQUIRE_GPU=1`.
fn gpu(test: &str) -> Option<&'static Gpu> {
    match GPU.get_or_init(|| pollster::block_on(open_gpu())) {
        Ok(g) => {
            println!(
                "{test}: adapter \"{}\" ({:?}, {:?} backend, driver {} {})",
                g.info.name, g.info.device_type, g.info.backend, g.info.driver, g.info.driver_info
            );
            Some(g)
        }
        Err(reason) => {
            if gpu_harness::gpu_required() {
                panic!("{test}: OCEAN_REQUIRE_GPU=1 but {reason}");
            }
            None
        }
    }
}

impl Gpu {
    fn waves(&self, modes: &WaveModes) -> GpuWaves {
        GpuWaves::new(&self.device, modes).expect("GpuWaves")
    }

    /// Runs a whole frame and reads back the three textures.
    fn run(&self, waves: &GpuWaves, t: f64, choppiness: f64) -> [Vec<[f32; 4]>; 3] {
        let mut encoder = self.device.create_command_encoder(&Default::default());
        waves.encode(&self.queue, &mut encoder, t, choppiness).expect("encode");
        self.queue.submit([encoder.finish()]);
        WaveTexture::ALL
            .map(|w| waves.read_texture(&self.device, &self.queue, w).expect("readback"))
    }

    /// Runs dispatches 0 … `last` (< pack) of a frame and reads back the buffer the last wrote.
    fn run_prefix(&self, waves: &GpuWaves, t: f64, choppiness: f64, last: usize) -> Vec<[f32; 2]> {
        waves.write_uniforms(&self.queue, t, choppiness).expect("uniforms");
        let mut encoder = self.device.create_command_encoder(&Default::default());
        waves.encode_dispatches(&mut encoder, 0..last + 1);
        self.queue.submit([encoder.finish()]);
        waves.read_buffer(&self.device, &self.queue, waves.output_of(last)).expect("readback")
    }
}

// ---------------------------------------------------------------------------------------------
// (a) The mirror against ocean-core

fn mirror_matches_ocean_core_synthesis() {
    for n in SIZES {
        for dispersion in [Dispersion::deep(G), Dispersion::new(G, f64::INFINITY, LOOP_S).unwrap()]
        {
            let modes = build(n, dispersion);
            let mirror = WavesMirror::new(&modes).unwrap();
            let mut s64 = Synthesizer::<f64>::new(n).unwrap();
            let mut s32 = Synthesizer::<f32>::new(n).unwrap();
            for t in [0.0, 3.7, 1e6] {
                for chop in CHOPPINESS {
                    let got = fields_of(&texels(&mirror.run(t, chop).unwrap()));
                    let e64 =
                        rel_errors(&got, &maps_fields(&s64.synthesize(&modes, t, chop).unwrap()));
                    let e32 =
                        rel_errors(&got, &maps_fields(&s32.synthesize(&modes, t, chop).unwrap()));
                    println!(
                        "mirror N={n:3} loop={} t={t:9} λ={chop}: rel vs f64 [{}], vs f32 [{}]",
                        dispersion.is_looping(),
                        e64.map(|e| format!("{e:.1e}")).join(" "),
                        e32.map(|e| format!("{e:.1e}")).join(" "),
                    );
                    assert!(worst(&e64) <= SYNTHESIS_REL, "vs f64: {e64:?}");
                    assert!(worst(&e32) <= SYNTHESIS_REL, "vs f32: {e32:?}");
                }
            }
        }
    }
}

fn mirror_small_grids() {
    // N = 2 holds only k = 0 and Nyquist bins (all zero); 4 and 8 have one or three rings.
    for n in [2, 4, 8] {
        let modes = build(n, Dispersion::deep(G));
        let got = fields_of(&texels(&WavesMirror::new(&modes).unwrap().run(2.5, 1.3).unwrap()));
        let want =
            maps_fields(&Synthesizer::<f64>::new(n).unwrap().synthesize(&modes, 2.5, 1.3).unwrap());
        let e = rel_errors(&got, &want);
        assert!(worst(&e) <= SYNTHESIS_REL, "N={n}: {e:?}");
    }
}

fn mirror_flat_fields_without_choppiness() {
    let modes = build(64, Dispersion::deep(G));
    let f = fields_of(&texels(&WavesMirror::new(&modes).unwrap().run(12.5, 0.0).unwrap()));
    assert!(f[1].iter().chain(&f[2]).all(|&v| v == 0.0), "displacement must be exactly 0");
    assert!(f[5].iter().all(|&v| v == 1.0), "J must be exactly 1");
}

fn non_power_of_two_is_an_error() {
    let modes = build(48, Dispersion::deep(G));
    let err = WavesMirror::new(&modes).unwrap_err().to_string();
    assert!(err.contains("power of two"), "{err}");
    if let Some(gpu) = gpu("non_power_of_two_is_an_error") {
        let err = GpuWaves::new(&gpu.device, &modes).unwrap_err();
        assert!(matches!(err, WavesError::Core(_)) && err.to_string().contains("power of two"));
    }
}

// ---------------------------------------------------------------------------------------------
// (b) The GPU against the mirror, dispatch by dispatch and texture by texture

const TEXTURE_CHANNELS: [(&str, [&str; 4]); 3] = [
    ("displacement", ["disp_x", "height", "disp_z", "jacobian"]),
    ("displacement_slopes", ["slope_x", "slope_z", "0", "0"]),
    ("bump", ["slope_x", "slope_z", "height", "jacobian"]),
];

/// Compares the three textures channel by channel; returns the failures, prints each.
fn compare_textures(
    label: &str,
    gpu: &[Vec<[f32; 4]>; 3],
    cpu: &[Vec<[f32; 4]>; 3],
    n: usize,
    print: bool,
) -> Vec<String> {
    let mut failures = Vec::new();
    for (t, (name, channels)) in TEXTURE_CHANNELS.iter().enumerate() {
        for (c, channel) in channels.iter().enumerate() {
            let a: Vec<f32> = gpu[t].iter().map(|v| v[c]).collect();
            let b: Vec<f32> = cpu[t].iter().map(|v| v[c]).collect();
            let cmp = Comparison::new(&a, &b);
            let line = format!(
                "{label} {name}.{channel}: rel {:.2e}, max abs {:.2e} at texel ({}, {}), {} of {} \
                 texels differ, {} outside tolerance",
                cmp.rel,
                cmp.max_abs,
                cmp.worst_index % n,
                cmp.worst_index / n,
                cmp.differing,
                a.len(),
                cmp.outside
            );
            if print {
                println!("{line}");
            }
            if !cmp.ok() {
                failures.push(line);
            }
        }
    }
    failures
}

fn gpu_matches_the_mirror_dispatch_by_dispatch() {
    let gpu = gpu("gpu_matches_the_mirror_dispatch_by_dispatch")
        .expect("the harness runs GPU tests with a GPU");
    for n in SIZES {
        let modes = build(n, Dispersion::deep(G));
        let mirror = WavesMirror::new(&modes).unwrap();
        let waves = gpu.waves(&modes);
        // The phase's cos and sin are `cis_turns` (+ − × only) and the rest is the same
        // arithmetic (FFT, multipliers, packing), which lavapipe evaluates as written (no
        // fusion): there the two must agree bit for bit at every time.
        for (t, chop) in [(0.0, 0.0), (0.0, 1.3), (3.7, 1.3), (1e6, 1.3)] {
            let mut differing = 0;
            let mut traced = Vec::new();
            let cpu = mirror.run_traced(&mirror.uniforms(t, chop).unwrap(), &mut |d, buf| {
                traced.push((d, buf.to_vec()))
            });
            assert_eq!(traced.len() + 1, waves.dispatch_count());
            let mut worst_rel = 0.0f64;
            for (index, (dispatch, expected)) in traced.iter().enumerate() {
                let got = gpu.run_prefix(&waves, t, chop, index);
                let (ga, ea) = (components(&got, n), components(expected, n));
                for (c, (a, b)) in ga.iter().zip(&ea).enumerate() {
                    let cmp = Comparison::new(a, b);
                    worst_rel = worst_rel.max(cmp.rel);
                    differing += cmp.differing;
                    let at = cmp.worst_index;
                    let line = format!(
                        "N={n} t={t} λ={chop} after {dispatch:?}, array {} {}: rel {:.2e}, max \
                         abs {:.2e} at bin ({}, {}), {} of {} differ, {} outside tolerance",
                        c / 2,
                        ["re", "im"][c % 2],
                        cmp.rel,
                        cmp.max_abs,
                        at % n,
                        at / n,
                        cmp.differing,
                        a.len(),
                        cmp.outside
                    );
                    if *dispatch == Dispatch::Spectrum || !cmp.ok() {
                        println!("{line}");
                    }
                    assert!(cmp.ok(), "{line}");
                }
            }
            println!(
                "N={n} t={t} λ={chop}: worst rel over all dispatches {worst_rel:.2e}, {differing} \
                 values differ"
            );
            if gpu.info.name.contains("llvmpipe") {
                assert_eq!(differing, 0, "lavapipe at t = {t} must match the mirror bit for bit");
            }
            let gpu_textures = gpu.run(&waves, t, chop);
            let failures = compare_textures(
                &format!("N={n} t={t} λ={chop}"),
                &gpu_textures,
                &texels(&cpu),
                n,
                true,
            );
            assert!(failures.is_empty(), "{failures:#?}");
        }
    }
}

/// The phase's (cos, sin) on the GPU against the mirror's `cis_turns` (shared/trig.wgsl), over the turns the
/// stage feeds it, p ∈ [−½, ½]; and, for the record, the driver's own cos and sin against
/// Rust's (what the stage used before `cis_turns`).
fn gpu_cos_sin_against_rust() {
    let gpu = gpu("gpu_cos_sin_against_rust").expect("the harness runs GPU tests with a GPU");
    const COUNT: u32 = 1 << 16;
    // `cis_turns` and its constants exactly as the stages import them (shared/trig.wgsl).
    let trig = ocean_core::registry::SHARED
        .iter()
        .find(|f| f.file == "shared/trig.wgsl")
        .expect("shared/trig.wgsl in the registry")
        .source;
    let source = format!(
        "{}\n
        @group(0) @binding(0) var<storage, read> theta: array<f32>;
        @group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;
        @compute @workgroup_size(64)
        fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
            let p = theta[id.x] / TAU;
            out[id.x] = vec4<f32>(cos(theta[id.x]), sin(theta[id.x]), cis_turns(p));
        }}",
        trig
    );
    let theta: Vec<f32> =
        (0..COUNT).map(|i| mirror::TAU * ((i as f32 + 0.5) / COUNT as f32 - 0.5)).collect();
    let device = &gpu.device;
    use wgpu::util::DeviceExt;
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: &theta.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>(),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let size = u64::from(COUNT) * 16;
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(source.as_str().into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: None,
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: input.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: output.as_entire_binding() },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(COUNT / 64, 1, 1);
    }
    encoder.copy_buffer_to_buffer(&output, 0, &staging, 0, size);
    gpu.queue.submit([encoder.finish()]);
    staging.map_async(wgpu::MapMode::Read, .., |r| r.expect("map"));
    device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    let bytes = staging.get_mapped_range(..).expect("mapped").to_vec();
    let got: Vec<f32> =
        bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
    let ulps =
        |a: f32, b: f32| (i64::from(a.to_bits() as i32) - i64::from(b.to_bits() as i32)).abs();
    let (mut max_ulp, mut max_abs, mut differing, mut worst_theta) = (0, 0.0f32, 0, 0.0);
    let mut cis_differing = 0;
    for (i, &th) in theta.iter().enumerate() {
        for (g, r) in [(got[4 * i], th.cos()), (got[4 * i + 1], th.sin())] {
            let d = (g - r).abs();
            if g != r {
                differing += 1;
            }
            // ULPs are only meaningful away from the zeros of cos and sin.
            if r.abs() > 1e-3 && ulps(g, r) > max_ulp {
                max_ulp = ulps(g, r);
                worst_theta = th;
            }
            max_abs = max_abs.max(d);
        }
        let want = mirror::cis_turns(th / mirror::TAU);
        if [got[4 * i + 2], got[4 * i + 3]].map(f32::to_bits) != want.map(f32::to_bits) {
            cis_differing += 1;
        }
    }
    println!(
        "GPU cos/sin vs Rust f32 over θ ∈ [−π, π] ({COUNT} points): {differing} of {} differ, \
         max {max_ulp} ulp (|value| > 1e-3, at θ = {worst_theta}), max abs {max_abs:.2e}; \
         cis_turns: {cis_differing} of {COUNT} differ from the mirror",
        2 * COUNT
    );
    // Evidence, not a device requirement: the drivers' cos and sin are a few ulps off Rust's.
    assert!(max_abs <= 1e-6, "cos/sin differ by {max_abs:e}");
    // cis_turns is + − × only: lavapipe evaluates it as written.
    if gpu.info.name.contains("llvmpipe") {
        assert_eq!(cis_differing, 0, "cis_turns on lavapipe differs from the mirror");
    }
}

fn gpu_matches_ocean_core_at_large_time() {
    let gpu =
        gpu("gpu_matches_ocean_core_at_large_time").expect("the harness runs GPU tests with a GPU");
    let n = 64;
    for dispersion in [Dispersion::deep(G), Dispersion::new(G, 30.0, LOOP_S).unwrap()] {
        let modes = build(n, dispersion);
        let waves = gpu.waves(&modes);
        let mut s64 = Synthesizer::<f64>::new(n).unwrap();
        for t in [1e6, 1e6 + 0.123_456_7, -2.5e5] {
            let got = fields_of(&gpu.run(&waves, t, 1.3));
            let e = rel_errors(&got, &maps_fields(&s64.synthesize(&modes, t, 1.3).unwrap()));
            println!(
                "GPU vs ocean-core f64, loop={} t={t}: rel [{}]",
                dispersion.is_looping(),
                e.map(|e| format!("{e:.1e}")).join(" ")
            );
            assert!(worst(&e) <= SYNTHESIS_REL, "{e:?}");
        }
    }
}

/// The shared-memory FFT (two dispatches a frame, the spectrum fused into the rows and the
/// packing into the columns; `FftKernel::Shared`, the default up to N = 1024) against the
/// one-stage dispatches on the same device: the same operations in another order of memory
/// traffic. The CPU mirror shows them bit-identical (`ocean_cpu::shaders::waves::shared_memory`
/// unit test); on the GPU they must be within the GPU↔mirror
/// tolerance, and the count of values that are not bit-identical is printed.
fn shared_memory_fft_matches_the_one_stage_fft() {
    use ocean_gpu::waves::FftKernel;
    let gpu = gpu("shared_memory_fft_matches_the_one_stage_fft")
        .expect("the harness runs GPU tests with a GPU");
    // log2(N) even and odd (the shared kernel's last stage alone); four lines a workgroup
    // (N ≤ 256), two (512) and one (1024).
    for n in [4, 16, 32, 128, 256, 512, 1024] {
        let modes = build(n, Dispersion::deep(G));
        let shared = GpuWaves::with_kernel(&gpu.device, &modes, FftKernel::Shared).unwrap();
        let stages = GpuWaves::with_kernel(&gpu.device, &modes, FftKernel::Stages).unwrap();
        assert_eq!(GpuWaves::new(&gpu.device, &modes).unwrap().kernel(), FftKernel::Shared);
        let (a, b) = (gpu.run(&shared, 3.7, 1.3), gpu.run(&stages, 3.7, 1.3));
        let (fa, fb) = (fields_of(&a), fields_of(&b));
        let differ: usize =
            fa.iter().zip(&fb).map(|(x, y)| x.iter().zip(y).filter(|(p, q)| p != q).count()).sum();
        let wide: [Vec<f64>; 6] = fb.clone().map(|f| f.iter().map(|&v| f64::from(v)).collect());
        let e = rel_errors(&fa, &wide);
        println!(
            "N = {n}: shared vs one-stage FFT: {differ} of {} values not bit-identical, rel [{}]",
            6 * n * n,
            e.map(|e| format!("{e:.1e}")).join(" ")
        );
        assert!(worst(&e) <= GPU_REL, "{e:?}");
        // Lavapipe (CI) compiles both forms alike: measured bit-identical at every N.
        if gpu.info.name.contains("llvmpipe") {
            assert_eq!(differ, 0, "lavapipe: the two FFT kernels differ");
        }
        // The control: the sea a second later is far outside.
        let later = fields_of(&gpu.run(&shared, 4.7, 1.3));
        assert!(worst(&rel_errors(&later, &wide)) > 100.0 * GPU_REL);
    }
    let too_big = build(2048, Dispersion::deep(G));
    assert!(matches!(
        GpuWaves::with_kernel(&gpu.device, &too_big, FftKernel::Shared),
        Err(WavesError::TooLarge { .. })
    ));
    assert_eq!(GpuWaves::new(&gpu.device, &too_big).unwrap().kernel(), FftKernel::Stages);
}

// ---------------------------------------------------------------------------------------------
// (c) Phase at t = 10⁶ s and looping

/// Modes whose h̃ has one term per bin: h0 zeroed on one bin of each ±k pair, so that with
/// λ = 0 the spectrum's first array holds h0(k) e^{iθ} (or its partner's conjugate) and the
/// phase θ can be read back.
fn half_plane(n: usize, dispersion: Dispersion) -> WaveModes {
    let mut modes = build(n, dispersion);
    let drop: Vec<usize> = (0..n * n).filter(|&b| modes.partner(b) < b).collect();
    for b in drop {
        modes.h0_mut()[b] = num_complex::Complex::new(0.0, 0.0);
    }
    modes
}

/// The largest |θ − θ_f64| (wrapped) over the kept bins of a half-plane spectrum buffer, where
/// θ = arg(buffer / h0) with h0 as uploaded (f32), against ocean-core's `Dispersion::phase`.
fn phase_error(modes: &WaveModes, spectrum: &[[f32; 2]], t: f64) -> f64 {
    let table = wave_mode_table(modes);
    let mut worst = 0.0f64;
    for (bin, mode) in table.iter().enumerate() {
        if mode.h0 == [0.0, 0.0] {
            continue;
        }
        let h = num_complex::Complex::new(f64::from(spectrum[bin][0]), f64::from(spectrum[bin][1]));
        let h0 = num_complex::Complex::new(f64::from(mode.h0[0]), f64::from(mode.h0[1]));
        let theta = (h / h0).arg();
        let want = modes.dispersion().phase(modes.wavenumbers()[bin], t);
        let d = (theta - want).rem_euclid(TAU);
        worst = worst.max(d.min(TAU - d));
    }
    worst
}

fn phase_is_accurate_at_a_million_seconds() {
    let n = 64;
    let gpu = gpu("phase_is_accurate_at_a_million_seconds");
    for dispersion in [Dispersion::deep(G), Dispersion::new(G, f64::INFINITY, LOOP_S).unwrap()] {
        let modes = half_plane(n, dispersion);
        let mirror = WavesMirror::new(&modes).unwrap();
        let waves = gpu.map(|g| g.waves(&modes));
        for t in [0.5, 1e6, 1e6 + 0.123_456_7, 1e9] {
            let mut spectrum = Vec::new();
            mirror.run_traced(&mirror.uniforms(t, 0.0).unwrap(), &mut |d, buf| {
                if d == Dispatch::Spectrum {
                    spectrum = buf.to_vec();
                }
            });
            let e_mirror = phase_error(&modes, &spectrum, t);
            let e_gpu = match (gpu, &waves) {
                (Some(g), Some(w)) => Some(phase_error(&modes, &g.run_prefix(w, t, 0.0, 0), t)),
                _ => None,
            };
            println!(
                "phase error, loop={} t={t:e}: mirror {e_mirror:.2e} rad, GPU {} rad",
                dispersion.is_looping(),
                e_gpu.map_or("skipped".into(), |e| format!("{e:.2e}"))
            );
            assert!(e_mirror <= 1e-4);
            assert!(e_gpu.is_none_or(|e| e <= 1e-4));
        }
    }
    // Negative control: the same measure on the phase formed in f32 (f32(ω)·f32(t), reduced
    // in f32) sees errors far beyond the limit at 10⁶ s.
    let modes = half_plane(n, Dispersion::deep(G));
    let t = 1e6;
    let naive = |bin: usize| {
        let theta = (modes.omegas()[bin] as f32 * t as f32).rem_euclid(TAU as f32);
        let h0 = modes.h0()[bin];
        let e = num_complex::Complex::cis(f64::from(theta));
        let h = h0 * e;
        [h.re as f32, h.im as f32]
    };
    let spectrum: Vec<[f32; 2]> = (0..n * n).map(naive).collect();
    let e = phase_error(&modes, &spectrum, t);
    println!("negative control: f32 phase at t = 1e6 s: {e:.2e} rad");
    assert!(e > 1e-4);
}

fn looping_repeats_bit_for_bit() {
    let n = 64;
    let modes = build(n, Dispersion::new(G, f64::INFINITY, LOOP_S).unwrap());
    let mirror = WavesMirror::new(&modes).unwrap();
    let bits = |t: &[Vec<[f32; 4]>; 3]| -> Vec<u32> {
        t.iter().flatten().flat_map(|v| v.map(f32::to_bits)).collect()
    };
    // t and t + T exact in f64: identical reduced time, identical maps.
    for t in [0.0, 7.25, 1e6, 1e6 + 13.5] {
        let a = bits(&texels(&mirror.run(t, 1.3).unwrap()));
        let b = bits(&texels(&mirror.run(t + LOOP_S, 1.3).unwrap()));
        assert!(a == b, "mirror: h(t + T) ≠ h(t) at t = {t}");
        let c = bits(&texels(&mirror.run(t + 0.5, 1.3).unwrap()));
        assert!(a != c, "negative control: the maps must change within the period");
    }
    if let Some(gpu) = gpu("looping_repeats_bit_for_bit") {
        let waves = gpu.waves(&modes);
        for t in [7.25, 1e6] {
            let a = bits(&gpu.run(&waves, t, 1.3));
            let b = bits(&gpu.run(&waves, t + LOOP_S, 1.3));
            assert!(a == b, "GPU: h(t + T) ≠ h(t) at t = {t}");
            assert!(a != bits(&gpu.run(&waves, t + 0.5, 1.3)));
        }
        println!("GPU: h(t + 20 s) == h(t) bit for bit at t = 7.25 s and 1e6 s");
    }
}

// ---------------------------------------------------------------------------------------------
// (d) Negative controls

/// The conjugated twiddles (e^{−2πi m/N}: a forward transform) and a perturbed h0 (the largest
/// mode × (1 + 1e-3)).
fn wrong_twiddles(mirror: &WavesMirror) -> Vec<[f32; 2]> {
    mirror.twiddles().iter().map(|w| [w[0], -w[1]]).collect()
}

fn perturb_largest_h0(table: &mut [ocean_core::waves::uniforms::WaveModeData]) {
    let norm = |m: &ocean_core::waves::uniforms::WaveModeData| m.h0[0].hypot(m.h0[1]);
    let largest = (0..table.len())
        .max_by(|&a, &b| norm(&table[a]).total_cmp(&norm(&table[b])))
        .expect("a non-empty table");
    table[largest].h0 = table[largest].h0.map(|v| v * 1.001);
}

fn mirror_comparator_rejects_wrong_twiddles_and_h0() {
    let n = 64;
    let modes = build(n, Dispersion::deep(G));
    let mut s64 = Synthesizer::<f64>::new(n).unwrap();
    let reference = maps_fields(&s64.synthesize(&modes, 3.7, 1.3).unwrap());

    let mut bad = WavesMirror::new(&modes).unwrap();
    let w = wrong_twiddles(&bad);
    bad.twiddles_mut().copy_from_slice(&w);
    let e = worst(&rel_errors(&fields_of(&texels(&bad.run(3.7, 1.3).unwrap())), &reference));
    println!("mirror with conjugated twiddles vs ocean-core: rel {e:.2e}");
    assert!(e > SYNTHESIS_REL);

    let mut bad = WavesMirror::new(&modes).unwrap();
    perturb_largest_h0(bad.modes_mut());
    let e = worst(&rel_errors(&fields_of(&texels(&bad.run(3.7, 1.3).unwrap())), &reference));
    println!("mirror with the largest h0 × 1.001 vs ocean-core: rel {e:.2e}");
    assert!(e > SYNTHESIS_REL);
}

fn gpu_comparator_rejects_wrong_twiddles_and_h0() {
    // The comparator itself, each of its two limits: one value moved just past abs + rel·|b|
    // fails and just inside passes (a field of max 1, the value 0.01, so the per-field rel stays
    // far below its limit); and on a field of max 1e-4 (a spectrum), where the element limit
    // is loose, one value moved just past 1e-5 of the field's max fails, just inside passes.
    let b: Vec<f32> = (0..64).map(|i| (i as f32 * 0.37).sin()).collect();
    let mut b = b;
    b[5] = 0.01;
    let limit = GPU_ABS + GPU_REL * f64::from(b[5]).abs();
    let moved = |b: &[f32], i: usize, by: f64| {
        let mut a = b.to_vec();
        a[i] = (f64::from(b[i]) + by) as f32;
        a
    };
    assert!(Comparison::new(&moved(&b, 5, 0.99 * limit), &b).ok());
    assert!(!Comparison::new(&moved(&b, 5, 1.01 * limit), &b).ok());
    let small: Vec<f32> = b.iter().map(|v| v * 1e-4).collect();
    let max = small.iter().fold(0.0f64, |m, v| m.max(f64::from(*v).abs()));
    assert!(Comparison::new(&moved(&small, 9, 0.99 * GPU_REL * max), &small).ok());
    assert!(!Comparison::new(&moved(&small, 9, 1.01 * GPU_REL * max), &small).ok());

    let Some(gpu) = gpu("gpu_comparator_rejects_wrong_twiddles_and_h0") else { return };
    let n = 64;
    let modes = build(n, Dispersion::deep(G));
    let mirror = WavesMirror::new(&modes).unwrap();
    let expected = texels(&mirror.run(3.7, 1.3).unwrap());
    let waves = gpu.waves(&modes);
    assert!(compare_textures("good", &gpu.run(&waves, 3.7, 1.3), &expected, n, false).is_empty());

    waves.write_twiddles(&gpu.queue, &wrong_twiddles(&mirror)).unwrap();
    let failures = compare_textures("twiddles", &gpu.run(&waves, 3.7, 1.3), &expected, n, false);
    println!("GPU with conjugated twiddles: {} of 12 channels fail", failures.len());
    assert!(!failures.is_empty());
    waves.write_twiddles(&gpu.queue, mirror.twiddles()).unwrap();

    let mut table = mirror.modes().to_vec();
    perturb_largest_h0(&mut table);
    waves.write_mode_table(&gpu.queue, &table).unwrap();
    let failures = compare_textures("h0", &gpu.run(&waves, 3.7, 1.3), &expected, n, false);
    println!("GPU with the largest h0 × 1.001: {} of 12 channels fail", failures.len());
    assert!(!failures.is_empty());
    waves.write_mode_table(&gpu.queue, mirror.modes()).unwrap();
    assert!(
        compare_textures("restored", &gpu.run(&waves, 3.7, 1.3), &expected, n, false).is_empty()
    );
}

/// The uniforms the GPU gets are the mirror's (one definition in ocean-core).
fn uniforms_are_shared() {
    let modes = build(16, Dispersion::deep(G));
    let m = WavesMirror::new(&modes).unwrap();
    let u = m.uniforms(1e6, 0.5).unwrap();
    assert_eq!(u, WavesUniforms::new(16, modes.dispersion(), 1e6, 0.5).unwrap());
    assert_eq!(mirror::mul_hi(u32::MAX, u32::MAX), u32::MAX - 1);
    assert_eq!(
        mirror::mul_hi(0x1234_5678, 0x9abc_def0),
        ((0x1234_5678u64 * 0x9abc_def0u64) >> 32) as u32
    );
}

fn main() -> std::process::ExitCode {
    let requirement = gpu_harness::Requirement { probe, ..gpu_harness::GPU_ADAPTER };
    run_tests!(requirement;
        cpu: mirror_matches_ocean_core_synthesis, mirror_small_grids,
            mirror_flat_fields_without_choppiness, mirror_comparator_rejects_wrong_twiddles_and_h0,
            uniforms_are_shared;
        gpu: gpu_matches_the_mirror_dispatch_by_dispatch, gpu_cos_sin_against_rust,
            gpu_matches_ocean_core_at_large_time, shared_memory_fft_matches_the_one_stage_fft;
        gpu_part: non_power_of_two_is_an_error, phase_is_accurate_at_a_million_seconds,
            looping_repeats_bit_for_bit, gpu_comparator_rejects_wrong_twiddles_and_h0;
    )
}
