//! `ocean bench`: a fixed set of frames and wave syntheses timed on both back ends, for
//! comparing machines (issue 17). Each system's built-in scene at 1280×720, 1920×1080 and
//! 3840×2160 on the CPU oracle and on the GPU, and the wave synthesis at N = 128 … 1024 (the
//! CPU's `Synthesizer<f32>`, the GPU FFT); `--quick` runs the four systems at 320×180 and the
//! synthesis at N = 64 and 128, well under a minute here.
//!
//! Per case, after one untimed warm-up: the median over the timed runs of
//! - `frame_ms`: the whole frame as a caller sees it (GPU: recording, submission, GPU work
//!   and reading the 8-bit picture back; CPU: every pass and the picture);
//! - `encode_ms` (GPU): a real-time frame recorded and submitted with nothing read back, the
//!   call returning without waiting (the CPU's share of a real-time frame; as in `ocean view`,
//!   one frame state carries the spray and the foam from frame to frame, so their warm-up is
//!   paid before the timing, and the GPU is idle when the timed call starts), and
//!   `encode_cpu_ms`, the calling thread's CPU time in that call (Unix): where a software
//!   GPU shares the cores (lavapipe), the wall time also counts waiting for one, so the CPU
//!   time is the figure to hold to a budget; `encode_split_ms`, where the median call's time
//!   went (`ocean_gpu::EncodeSplit`): the frame's inputs (`prepare`),
//!   the passes recorded (`record`), wgpu's `finish` and the `submit`, so that a driver's
//!   share can be told from the renderer's;
//! - `steady_ms` (GPU): what a real-time user sees, without read-back: [`STEADY_FRAMES`]
//!   real-time frames recorded and submitted back to back, one wait at the end, the total
//!   divided by their count (the GPU's and the CPU's work overlap as in a viewer);
//! - per pass, of the median run itself (so that they add up inside its total): GPU time
//!   from timestamp queries where the adapter has them, the CPU's wall time per pass;
//! - `peak_rss_mib`: the process's peak resident memory during the case (Linux: VmHWM,
//!   reset before each case through /proc/self/clear_refs; `null` elsewhere). On a software
//!   adapter (lavapipe) the GPU's memory is in it; on a hardware GPU it is not.
//!
//! Times on a shared machine are noisy: compare ratios within one run.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::Context;
use ocean::memory_arg::peak_rss_mib;
use ocean_core::graph::FrameState;
use ocean_core::plan::{FramePlan, OutputKind, Pass, SYSTEMS, System};
use ocean_core::scene::Scene;
use serde::Serialize;

/// `--shading`: a [`ocean_gpu::ShadingPath`] by its name.
fn shading_path(name: &str) -> Result<ocean_gpu::ShadingPath, String> {
    ocean_gpu::ShadingPath::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = ocean_gpu::ShadingPath::ALL.iter().map(|p| p.name()).collect();
        format!("`{name}` is not a shading path: {}", names.join(", "))
    })
}

/// Arguments of `ocean bench`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The small set (320×180 frames, N = 64 and 128), for CI.
    #[arg(long)]
    quick: bool,
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
    /// Back ends to time: cpu, gpu or both.
    #[arg(long, default_value = "both", value_parser = ["cpu", "gpu", "both"])]
    backend: String,
    /// Only the frames or only the wave synthesis.
    #[arg(long, value_parser = ["frames", "waves"])]
    only: Option<String>,
    /// Timed runs per case after the warm-up (default: 3 quick, 5 full).
    #[arg(long)]
    runs: Option<u32>,
    /// How the GPU shades the water and the objects: `compute` (a visibility buffer shaded in
    /// compute passes) or `fragment` (default: what the device allows, compute on Vulkan).
    /// The two give the same bits; timing both tells which pays on a GPU.
    #[arg(long, value_parser = shading_path)]
    shading: Option<ocean_gpu::ShadingPath>,
    /// Also write the JSON to this file.
    #[arg(short, long)]
    output: Option<PathBuf>,
}

/// The calling thread's CPU time so far (`None` where the platform has no such clock).
fn thread_cpu() -> Option<Duration> {
    #[cfg(unix)]
    {
        let t = rustix::time::clock_gettime(rustix::time::ClockId::ThreadCPUTime);
        Some(Duration::new(u64::try_from(t.tv_sec).ok()?, u32::try_from(t.tv_nsec).ok()?))
    }
    #[cfg(not(unix))]
    None
}

/// One timed case.
#[derive(Clone, Debug, Serialize)]
pub struct Case {
    /// `frame` or `waves`.
    pub kind: &'static str,
    /// The system (frames) or the synthesis (`cpu_synthesizer_f32`, `gpu_fft`).
    pub name: String,
    /// `cpu` or `gpu`.
    pub backend: &'static str,
    /// Image size (frames), pixels.
    pub size: Option<[u32; 2]>,
    /// Grid size (waves).
    pub n: Option<u32>,
    /// Median whole-frame (or whole-synthesis) time, ms.
    pub frame_ms: f64,
    /// GPU frames: median time to record and submit with nothing read back, ms.
    pub encode_ms: Option<f64>,
    /// GPU frames: the calling thread's median CPU time in that call, ms (Unix).
    pub encode_cpu_ms: Option<f64>,
    /// GPU frames: the steps of that median call, ms.
    pub encode_split_ms: Option<SplitMs>,
    /// GPU frames: median time per frame of [`STEADY_FRAMES`] submitted back to back without
    /// read-back and one wait, ms.
    pub steady_ms: Option<f64>,
    /// Time per pass of the median run (the one whose total is `frame_ms`), ms (GPU:
    /// timestamp queries; CPU: wall time), in frame order.
    pub passes: Vec<(String, f64)>,
    /// Peak resident memory during the case, MiB.
    pub peak_rss_mib: Option<f64>,
    /// GPU synthesis: the time its unavoidable memory traffic (the mode table read, the
    /// three maps written: 80·N² bytes) takes at the device's copy bandwidth, ms; `frame_ms`
    /// over this is how far from bandwidth-bound it runs.
    pub bandwidth_bound_ms: Option<f64>,
}

/// [`ocean_gpu::EncodeSplit`] of the median encode, ms.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SplitMs {
    /// The frame's inputs on the CPU.
    pub prepare: f64,
    /// The passes recorded.
    pub record: f64,
    /// wgpu's `CommandEncoder::finish`.
    pub finish: f64,
    /// `Queue::submit`.
    pub submit: f64,
}

impl SplitMs {
    /// The split of the run whose wall time is the median of `runs` (the one `median` picks),
    /// so that its steps add up inside that run's `encode_ms`; `None` for no run.
    fn of_median_run(runs: &[(f64, ocean_gpu::EncodeSplit)]) -> Option<Self> {
        let mut sorted = runs.to_vec();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (_, s) = sorted.get(sorted.len() / 2)?;
        Some(Self {
            prepare: ms(s.prepare),
            record: ms(s.record),
            finish: ms(s.finish),
            submit: ms(s.submit),
        })
    }
}

/// The whole run.
#[derive(Debug, Serialize)]
pub struct Bench {
    /// Whether it was `--quick`.
    pub quick: bool,
    /// Timed runs per case.
    pub runs: u32,
    /// The CPU's logical cores.
    pub cores: usize,
    /// The GPU adapter, when one was used.
    pub adapter: Option<String>,
    /// The same, field by field.
    pub adapter_info: Option<AdapterInfo>,
    /// The GPU's measured copy bandwidth (a 64 MiB buffer copy, bytes read + written), GB/s.
    pub gpu_copy_gb_s: Option<f64>,
    /// How the GPU shaded the water and the objects: `compute` (a visibility buffer shaded
    /// in a compute pass) or `fragment` (`ocean_gpu::ShadingPath`).
    pub shading_path: Option<&'static str>,
    /// Every case.
    pub cases: Vec<Case>,
    /// How each system's frame time scales with its pixels, and the synthesis with
    /// N² log₂ N, per back end: the exponent of a least-squares line through the cases'
    /// (log size, log time).
    pub fits: Vec<Fit>,
    /// Wall time of the whole run, s.
    pub total_s: f64,
}

/// The GPU adapter of a run, field by field: whose figures these are.
#[derive(Clone, Debug, Serialize)]
pub struct AdapterInfo {
    /// Its name ("NVIDIA H200", "llvmpipe (LLVM 15.0.6, 256 bits)").
    pub name: String,
    /// The PCI vendor id ("0x10de").
    pub vendor: String,
    /// Discrete, integrated, CPU, …
    pub device_type: String,
    /// The driver and its version.
    pub driver: String,
    /// wgpu's backend ("Vulkan").
    pub backend: String,
    /// Whether it is a software rasterizer on the CPU.
    pub software: bool,
}

impl AdapterInfo {
    fn of(a: &ocean_gpu::AdapterReport) -> Self {
        Self {
            name: a.name.clone(),
            vendor: a.vendor.clone(),
            device_type: a.device_type.clone(),
            driver: a.driver.clone(),
            backend: a.backend.clone(),
            software: a.is_software,
        }
    }
}

/// A fitted power law: time ∝ size^exponent.
#[derive(Clone, Debug, Serialize)]
pub struct Fit {
    /// The system (frames) or the synthesis.
    pub name: String,
    /// `cpu` or `gpu`.
    pub backend: &'static str,
    /// What the size is: `pixels` or `N² log2 N`.
    pub against: &'static str,
    /// The fitted exponent (1: linear in the size).
    pub exponent: f64,
    /// The fit's time at size 1, ms: time ≈ scale_ms · size^exponent.
    pub scale_ms: f64,
    /// How many cases it went through.
    pub points: usize,
}

/// The least-squares line through (ln x, ln y): (slope, intercept); `None` under two points
/// or one x.
pub fn log_log_fit(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let logs: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let (mx, my) = logs.iter().fold((0.0, 0.0), |(a, b), &(x, y)| (a + x / n, b + y / n));
    let sxx: f64 = logs.iter().map(|&(x, _)| (x - mx) * (x - mx)).sum();
    let sxy: f64 = logs.iter().map(|&(x, y)| (x - mx) * (y - my)).sum();
    (logs.len() >= 2 && sxx > 0.0).then(|| {
        let slope = sxy / sxx;
        (slope, my - slope * mx)
    })
}

/// What a case's time is fitted against: pixels for a frame, N² log₂ N for a synthesis.
pub(crate) fn fit_size(c: &Case) -> Option<f64> {
    match (c.size, c.n) {
        (Some([w, h]), _) => Some(f64::from(w) * f64::from(h)),
        (None, Some(n)) => Some(f64::from(n) * f64::from(n) * f64::from(n).log2()),
        _ => None,
    }
}

/// The fits of every (name, back end) with cases at two sizes or more.
pub(crate) fn fits(cases: &[Case]) -> Vec<Fit> {
    let mut keys: Vec<(&str, &'static str, &'static str)> = Vec::new();
    for c in cases {
        if !keys.iter().any(|k| k.0 == c.name && k.1 == c.backend && k.2 == c.kind) {
            keys.push((&c.name, c.backend, c.kind));
        }
    }
    keys.into_iter()
        .filter_map(|(name, backend, kind)| {
            let points: Vec<(f64, f64)> = cases
                .iter()
                .filter(|c| c.name == name && c.backend == backend && c.kind == kind)
                .filter_map(|c| Some((fit_size(c)?, c.frame_ms)))
                .collect();
            let (exponent, intercept) = log_log_fit(&points)?;
            let against = if kind == "frame" { "pixels" } else { "N² log2 N" };
            Some(Fit {
                name: name.to_owned(),
                backend,
                against,
                exponent,
                scale_ms: intercept.exp(),
                points: points.len(),
            })
        })
        .collect()
}

const FULL_SIZES: [[u32; 2]; 3] = [[1280, 720], [1920, 1080], [3840, 2160]];
const QUICK_SIZES: [[u32; 2]; 1] = [[320, 180]];
const FULL_N: [u32; 4] = [128, 256, 512, 1024];
const QUICK_N: [u32; 2] = [64, 128];

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// The timed runs of a case: each run's total and its passes, so that the case reports one
/// whole run (the median one by total) whose passes add up inside its total.
#[derive(Default)]
struct Runs(Vec<(f64, Vec<(String, f64)>)>);

impl Runs {
    fn add(&mut self, total_ms: f64, timings: &[(Pass, Duration)]) {
        // A pass timed twice in a frame (two Fresnel tables) counts once, summed.
        let mut passes: Vec<(String, f64)> = Vec::new();
        for (p, d) in timings {
            match passes.iter_mut().find(|(q, _)| q == p.name()) {
                Some((_, v)) => *v += ms(*d),
                None => passes.push((p.name().to_owned(), ms(*d))),
            }
        }
        self.0.push((total_ms, passes));
    }

    /// The median run by total: (its total, its passes).
    fn median_run(mut self) -> (f64, Vec<(String, f64)>) {
        self.0.sort_by(|a, b| a.0.total_cmp(&b.0));
        let k = self.0.len() / 2;
        self.0.into_iter().nth(k).unwrap_or((f64::NAN, Vec::new()))
    }
}

fn reset_peak() {
    // "5" resets the peak resident set size (proc(5)); where it cannot, the peak is the
    // process's since it started, which the table still reports.
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

fn scene(system: System, [w, h]: [u32; 2]) -> anyhow::Result<Scene> {
    let mut s = Scene::builtin_for(system).with_system(system)?;
    (s.camera.width, s.camera.height) = (w, h);
    Ok(s)
}

pub(crate) fn cpu_frame(system: System, size: [u32; 2], runs: u32) -> anyhow::Result<Case> {
    Ok(cpu_frame_of(&scene(system, size)?, system.name(), runs)?.0)
}

/// [`cpu_frame`] of any scene, named `name`, and the last run's frame (8-bit RGBA and the HDR
/// frame) for the report's pictures.
pub(crate) fn cpu_frame_of(
    s: &Scene,
    name: &str,
    runs: u32,
) -> anyhow::Result<(Case, ocean_cpu::Rendered)> {
    reset_peak();
    let mut last = ocean_cpu::render_scene(s, OutputKind::Ldr, &mut |_| {})?;
    let mut timed = Runs::default();
    for _ in 0..runs {
        let t0 = Instant::now();
        last = ocean_cpu::render_scene(s, OutputKind::Ldr, &mut |_| {})?;
        timed.add(ms(t0.elapsed()), &last.buffers.timings);
    }
    let (frame_ms, passes) = timed.median_run();
    let case = Case {
        kind: "frame",
        name: name.to_owned(),
        backend: "cpu",
        size: Some([s.camera.width, s.camera.height]),
        n: None,
        frame_ms,
        encode_ms: None,
        encode_cpu_ms: None,
        encode_split_ms: None,
        steady_ms: None,
        passes,
        peak_rss_mib: peak_rss_mib(),
        bandwidth_bound_ms: None,
    };
    Ok((case, last))
}

/// Frames submitted back to back for `steady_ms`.
pub const STEADY_FRAMES: u32 = 8;

pub(crate) fn gpu_frame(
    r: &mut ocean_gpu::Renderer,
    system: System,
    size: [u32; 2],
    runs: u32,
) -> anyhow::Result<Case> {
    gpu_frame_of(r, &scene(system, size)?, system.name(), runs)
}

/// [`gpu_frame`] of any scene, named `name`.
pub(crate) fn gpu_frame_of(
    r: &mut ocean_gpu::Renderer,
    s: &Scene,
    name: &str,
    runs: u32,
) -> anyhow::Result<Case> {
    use ocean_gpu::Readback;
    let plan = FramePlan::new(s, OutputKind::Ldr);
    reset_peak();
    r.run_with(s, &plan, Readback::Output)?;
    let (mut timed, mut encodes, mut steady) = (Runs::default(), Vec::new(), Vec::new());
    let mut encode_cpu = Vec::new();
    // The real-time frames run as the viewer's do: one state carried from frame to frame, so
    // the spray's and the foam's warm-up (which a still frame simulates in full) and the
    // boats' settle run are paid once, before the timing, and every timed frame steps them
    // on by 1/60 s of sea time.
    let mut live = FrameState::new(1.0 / 60.0).with_carried_boats();
    r.run_frame(s, &plan, &mut live, Readback::None)?;
    for _ in 0..runs {
        let f = r.run_with(s, &plan, Readback::Output)?;
        timed.add(ms(f.wall), &f.gpu_timings);
        r.gpu().wait()?;
        let cpu = thread_cpu();
        let f = r.run_frame(s, &plan, &mut live, Readback::None)?;
        encodes.push((ms(f.wall), f.encode));
        if let (Some(a), Some(b)) = (cpu, thread_cpu()) {
            encode_cpu.push(ms(b.saturating_sub(a)));
        }
        r.gpu().wait()?;
        let start = Instant::now();
        for _ in 0..STEADY_FRAMES {
            r.run_frame(s, &plan, &mut live, Readback::None)?;
        }
        r.gpu().wait()?;
        steady.push(ms(start.elapsed()) / f64::from(STEADY_FRAMES));
    }
    let (frame_ms, passes) = timed.median_run();
    Ok(Case {
        kind: "frame",
        name: name.to_owned(),
        backend: "gpu",
        size: Some([s.camera.width, s.camera.height]),
        n: None,
        frame_ms,
        encode_ms: Some(median(encodes.iter().map(|e| e.0).collect())),
        encode_cpu_ms: (!encode_cpu.is_empty()).then(|| median(encode_cpu)),
        encode_split_ms: SplitMs::of_median_run(&encodes),
        steady_ms: Some(median(steady)),
        passes,
        peak_rss_mib: peak_rss_mib(),
        bandwidth_bound_ms: None,
    })
}

/// The device's copy bandwidth, GB/s: a 64 MiB buffer copied (read and written), the median
/// of five after a warm-up.
pub(crate) fn copy_bandwidth(gpu: &ocean_gpu::Gpu) -> anyhow::Result<f64> {
    let size = 64u64 << 20;
    let buffer = |usage| {
        gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ocean.bench.copy"),
            size,
            usage,
            mapped_at_creation: false,
        })
    };
    let (from, to) = (buffer(wgpu::BufferUsages::COPY_SRC), buffer(wgpu::BufferUsages::COPY_DST));
    let mut times = Vec::new();
    for i in 0..6 {
        let t0 = Instant::now();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&from, 0, &to, 0, size);
        gpu.queue.submit([encoder.finish()]);
        gpu.wait()?;
        if i > 0 {
            times.push(t0.elapsed().as_secs_f64());
        }
    }
    Ok(2.0 * size as f64 / median(times) / 1e9)
}

pub(crate) fn waves(
    gpu: Option<(&ocean_gpu::Gpu, f64)>,
    n: u32,
    runs: u32,
) -> anyhow::Result<Vec<Case>> {
    use ocean_core::waves::{Synthesizer, WaveMaps};
    use ocean_gpu::waves::{FftKernel, GpuWaves};
    let ocean = ocean_core::scene::Ocean { resolution: n, ..ocean_core::scene::Ocean::default() };
    let modes = ocean.displacement_modes()?;
    let mut cases = Vec::new();
    let case = |name: &str, backend, times: Vec<f64>, bound: Option<f64>| Case {
        kind: "waves",
        name: name.to_owned(),
        backend,
        size: None,
        n: Some(n),
        frame_ms: median(times),
        encode_ms: None,
        encode_cpu_ms: None,
        encode_split_ms: None,
        steady_ms: None,
        passes: Vec::new(),
        peak_rss_mib: peak_rss_mib(),
        bandwidth_bound_ms: bound,
    };
    reset_peak();
    let mut synth = Synthesizer::<f32>::new(n as usize)?;
    let mut maps = WaveMaps::<f32>::new(n as usize, ocean.patch_size_m);
    let mut times = Vec::new();
    for i in 0..=runs {
        let t0 = Instant::now();
        synth.synthesize_into(&modes, 0.5 * f64::from(i), 1.0, &mut maps)?;
        if i > 0 {
            times.push(ms(t0.elapsed()));
        }
    }
    cases.push(case("cpu_synthesizer_f32", "cpu", times, None));
    let Some((gpu, gb_s)) = gpu else { return Ok(cases) };
    // The mode table (32 bytes a mode) read, three Rgba32Float maps written.
    let bound_ms = 80.0 * f64::from(n) * f64::from(n) / (gb_s * 1e9) * 1e3;
    // The frame's choice for this adapter, then both kernels (the shared one up to its N).
    let mut kernels = vec![
        ("gpu_fft", FftKernel::for_adapter(&gpu.info, n as usize)),
        ("gpu_fft_stages", FftKernel::Stages),
    ];
    if n <= ocean_gpu::waves::FFT_SHARED_MAX {
        kernels.push(("gpu_fft_shared", FftKernel::Shared));
    }
    for (name, kernel) in kernels {
        reset_peak();
        let w = GpuWaves::with_kernel(&gpu.device, &modes, kernel)?;
        let mut times = Vec::new();
        for i in 0..=runs {
            let t0 = Instant::now();
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            w.encode(&gpu.queue, &mut encoder, 0.5 * f64::from(i), 1.0)?;
            gpu.queue.submit([encoder.finish()]);
            gpu.wait()?;
            if i > 0 {
                times.push(ms(t0.elapsed()));
            }
        }
        cases.push(case(name, "gpu", times, Some(bound_ms)));
    }
    Ok(cases)
}

/// Runs the set `args` chooses; `progress` hears each case's name as it starts.
///
/// # Errors
/// A GPU asked for and not found, or a case that fails to render.
pub fn measure(
    quick: bool,
    backend: &str,
    (only, shading): (Option<&str>, Option<ocean_gpu::ShadingPath>),
    runs: u32,
    progress: &mut dyn FnMut(&str),
) -> anyhow::Result<Bench> {
    let start = Instant::now();
    let (cpu, gpu) = (backend != "gpu", backend != "cpu");
    let mut renderer = if gpu {
        Some(
            ocean_gpu::Renderer::new()
                .context("`ocean bench` on the GPU (--backend cpu skips it)")?,
        )
    } else {
        None
    };
    if let (Some(r), Some(path)) = (renderer.as_mut(), shading) {
        r.set_shading_path(path).with_context(|| format!("shading in {}", path.name()))?;
    }
    let mut sizes: &[[u32; 2]] = if quick { &QUICK_SIZES } else { &FULL_SIZES };
    let mut ns: &[u32] = if quick { &QUICK_N } else { &FULL_N };
    match only {
        Some("frames") => ns = &[],
        Some("waves") => sizes = &[],
        _ => {}
    }
    let mut cases = Vec::new();
    for info in SYSTEMS {
        for &size in sizes {
            let label = format!("{} {}×{}", info.name, size[0], size[1]);
            if cpu {
                progress(&format!("frame {label} cpu"));
                cases.push(cpu_frame(info.system, size, runs)?);
            }
            if let Some(r) = renderer.as_mut() {
                progress(&format!("frame {label} gpu"));
                cases.push(gpu_frame(r, info.system, size, runs)?);
            }
        }
    }
    let bandwidth = match renderer.as_ref() {
        Some(r) => Some(copy_bandwidth(r.gpu())?),
        None => None,
    };
    for &n in ns {
        progress(&format!("waves N = {n}"));
        let g = renderer.as_ref().map(|r| r.gpu()).zip(bandwidth);
        let mut w = waves(g, n, runs)?;
        if !cpu {
            w.retain(|c| c.backend == "gpu");
        }
        cases.extend(w);
    }
    Ok(Bench {
        quick,
        runs,
        cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
        adapter: renderer.as_ref().map(|r| r.adapter().to_string()),
        adapter_info: renderer.as_ref().map(|r| AdapterInfo::of(r.adapter())),
        gpu_copy_gb_s: bandwidth,
        shading_path: renderer.as_ref().map(|r| r.shading_path().name()),
        fits: fits(&cases),
        cases,
        total_s: start.elapsed().as_secs_f64(),
    })
}

/// The table: one row per case.
pub fn table(b: &Bench) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "ocean bench{}: median of {} runs after a warm-up; {} cores; GPU: {}; {:.0} s",
        if b.quick { " --quick" } else { "" },
        b.runs,
        b.cores,
        b.adapter.as_deref().unwrap_or("not used"),
        b.total_s
    );
    if let Some(bw) = b.gpu_copy_gb_s {
        let _ = writeln!(out, "GPU buffer copy: {bw:.1} GB/s (read + written)");
        if let Some(p) = b.shading_path {
            let _ = writeln!(out, "water and objects shaded in {p} passes");
        }
    }
    let _ = writeln!(
        out,
        "{:<6} {:<20} {:>9} {:<4} {:>10} {:>10} {:>8} {:>10} {:>9}  passes (ms)",
        "kind", "name", "size", "on", "total ms", "encode ms", "CPU ms", "steady ms", "peak MiB"
    );
    for c in &b.cases {
        let size = match (c.size, c.n) {
            (Some([w, h]), _) => format!("{w}×{h}"),
            (None, Some(n)) => format!("{n}²"),
            _ => String::new(),
        };
        let opt = |v: Option<f64>, p: usize| v.map_or("—".to_owned(), |v| format!("{v:.p$}"));
        let mut passes: Vec<String> = c.passes.iter().map(|(p, v)| format!("{p} {v:.2}")).collect();
        if let Some(e) = c.encode_split_ms {
            passes.push(format!(
                "encode: prepare {:.3}, record {:.3}, finish {:.3}, submit {:.3}",
                e.prepare, e.record, e.finish, e.submit
            ));
        }
        if let Some(bound) = c.bandwidth_bound_ms {
            passes.push(format!("bandwidth bound {bound:.4} ms ({:.0}× it)", c.frame_ms / bound));
        }
        let _ = writeln!(
            out,
            "{:<6} {:<20} {:>9} {:<4} {:>10.2} {:>10} {:>8} {:>10} {:>9}  {}",
            c.kind,
            c.name,
            size,
            c.backend,
            c.frame_ms,
            opt(c.encode_ms, 2),
            opt(c.encode_cpu_ms, 2),
            opt(c.steady_ms, 2),
            opt(c.peak_rss_mib, 0),
            passes.join(", ")
        );
    }
    if !b.fits.is_empty() {
        let _ = writeln!(out, "scaling (time ∝ size^exponent, least squares in log-log):");
        for f in &b.fits {
            let _ = writeln!(
                out,
                "  {:<20} {:<4} against {:<10} exponent {:.2} ({} points)",
                f.name, f.backend, f.against, f.exponent, f.points
            );
        }
    }
    out
}

/// Runs `ocean bench`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let runs = args.runs.unwrap_or(if args.quick { 3 } else { 5 }).max(1);
    // Before minutes of measuring: the output's folder exists and takes a file.
    let out = args.output.as_deref().map(ocean::output::OutputFile::reserve).transpose()?;
    let bar = indicatif::ProgressBar::new_spinner();
    let choice = (args.only.as_deref(), args.shading);
    let b = measure(args.quick, &args.backend, choice, runs, &mut |what| {
        bar.set_message(what.to_owned());
        bar.tick();
    })?;
    bar.finish_and_clear();
    let json = serde_json::to_string_pretty(&b)?;
    if let Some(out) = out {
        out.commit(json.as_bytes())?;
    }
    if args.json {
        println!("{json}");
    } else {
        print!("{}", table(&b));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_slope_of_a_power_law_is_its_exponent() {
        let points: Vec<(f64, f64)> = [1.0, 4.0, 9.0].iter().map(|&x| (x, 3.0 * x * x)).collect();
        let (slope, intercept) = log_log_fit(&points).unwrap_or((f64::NAN, f64::NAN));
        assert!((slope - 2.0).abs() < 1e-12 && (intercept.exp() - 3.0).abs() < 1e-12);
        assert_eq!(log_log_fit(&points[..1]), None);
        assert_eq!(log_log_fit(&[(2.0, 1.0), (2.0, 5.0)]), None);
    }
}
