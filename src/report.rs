//! `ocean report`: error against run time for each quality knob, what the planner saves on the
//! reference scenes, the four systems side by side, scaling, and the numerical-stability table
//! (issues 5, 17, 18).
//!
//! Writes into `--out-dir`: `index.html` (the report to read: [`html`]), `report.md` (the same
//! tables as text, for diffs in review), `error_vs_time.csv` (columns `knob,setting,
//! error_metric,error,time_ms,backend`), `error_vs_time.svg` and `.png` (one labelled panel per
//! knob: [`plot`]), `scaling.svg` ([`scaling`]), `systems.png` (every system on every
//! viewpoint: [`systems`]) and `pictures/` (each setting's crop and FLIP map: [`pictures`]).
//!
//! A knob is one entry of [`KNOBS`]: a name, what it varies, and a function that measures
//! every setting against the best one and returns rows. A measurement on another back end
//! (the GPU path) is one more entry whose rows carry its `backend`; the CSV, the plot and the
//! Pareto tables group by (knob, metric, backend) already.
//!
//! Timings are medians of several runs of the same work in this process (2 with `--quick`,
//! 7 without), after one untimed warm-up run; the machine is shared, so compare times within
//! one report only.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use ocean_core::fresnel::{fresnel_exact, fresnel_schlick};
use ocean_core::plan::{FramePlan, OutputKind, Pass};
use ocean_core::scene::Scene;
use ocean_core::tables::{FresnelTable1D, FresnelTexture, TextureMapping};
use ocean_core::waves::{Synthesizer, WaveMaps};
use ocean_cpu::raster::RenderTarget;
use ocean_cpu::shaders::shared::frame::unit;
use ocean_cpu::shaders::water;

use ocean::output::write_atomic;

mod far_field;
mod html;
mod markdown;
mod pictures;
mod plot;
mod scaling;
mod surface;
mod svg;
mod systems;
mod systems_figures;
mod techniques;

/// Arguments of `ocean report`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Fewer settings, smaller frames, 2 runs per timing: about a minute on a 2-core machine.
    #[arg(long)]
    quick: bool,
    /// Folder for index.html (the report to read), report.md, error_vs_time.{csv,svg,png},
    /// scaling.svg, systems.png and pictures/ (created if missing).
    #[arg(long, default_value = "report")]
    out_dir: PathBuf,
}

/// One measured setting of a knob.
#[derive(Clone, Debug)]
struct Row {
    knob: &'static str,
    setting: String,
    error_metric: &'static str,
    error: f64,
    time_ms: f64,
    backend: &'static str,
}

/// What the measurements share: the size of the work and the progress bar.
struct Ctx {
    quick: bool,
    runs: usize,
    bar: ProgressBar,
    /// The frames of the knobs that change the picture, for the page's crops.
    pictures: pictures::Pictures,
    /// One GPU renderer for every measurement (made at first use; its pipelines and pools
    /// then warm for all), or why there is none.
    gpu: std::cell::RefCell<Option<Result<ocean_gpu::Renderer, String>>>,
}

impl Ctx {
    /// Frame size of the image knobs.
    fn frame_size(&self) -> (u32, u32) {
        if self.quick { (160, 90) } else { (640, 360) }
    }

    /// Median wall time of `runs` calls of `f`, ms, and the last result.
    fn time<T>(&self, mut f: impl FnMut() -> anyhow::Result<T>) -> anyhow::Result<(f64, T)> {
        let mut times = Vec::with_capacity(self.runs);
        let mut last = Some(f()?); // warm-up: caches, allocator, page faults
        for _ in 0..self.runs {
            let t0 = Instant::now();
            last = Some(f()?);
            times.push(t0.elapsed().as_secs_f64() * 1e3);
        }
        times.sort_by(f64::total_cmp);
        Ok((times[times.len() / 2], last.context("at least one run")?))
    }

    /// Median wall times of `fs`, ms, and each one's last result, the calls interleaved
    /// (f₀, f₁, …, f₀, f₁, …) after one untimed round, so that a burst of other work on the
    /// machine slows every setting alike rather than one.
    fn time_interleaved<T>(&self, fs: &mut [Work<'_, T>]) -> anyhow::Result<Vec<(f64, T)>> {
        let mut last: Vec<T> = fs.iter_mut().map(|f| f()).collect::<anyhow::Result<_>>()?;
        let mut times = vec![Vec::with_capacity(self.runs); fs.len()];
        for _ in 0..self.runs {
            for (i, f) in fs.iter_mut().enumerate() {
                let t0 = Instant::now();
                last[i] = f()?;
                times[i].push(t0.elapsed().as_secs_f64() * 1e3);
            }
        }
        Ok(times
            .into_iter()
            .zip(last)
            .map(|(mut t, r)| {
                t.sort_by(f64::total_cmp);
                (t[t.len() / 2], r)
            })
            .collect())
    }

    /// The report's GPU renderer, or why there is none.
    fn gpu(&self) -> std::cell::RefMut<'_, Result<ocean_gpu::Renderer, String>> {
        std::cell::RefMut::map(self.gpu.borrow_mut(), |g| {
            g.get_or_insert_with(|| ocean_gpu::Renderer::new().map_err(|e| e.to_string()))
        })
    }

    fn step(&self, what: &str) {
        self.bar.set_message(what.to_string());
        self.bar.inc(1);
    }
}

/// A knob of the report.
struct Knob {
    name: &'static str,
    varies: &'static str,
    /// How many progress steps `measure` takes.
    steps: fn(&Ctx) -> u64,
    measure: fn(&Ctx) -> anyhow::Result<Vec<Row>>,
}

/// Every knob, in report order. Add a back end or a knob here.
const KNOBS: &[Knob] = &[
    Knob {
        name: "fresnel",
        varies: "how F is evaluated: eq. 2 per pixel, the 2D texture (whole-hemisphere and \
                 grazing mappings) at \
                 16² … 512², the paper's half-range texture, a 1D table in cos θ, Schlick; \
                 error over the hemisphere of view directions and over the water pixels of the \
                 default scene; time of the lookups of one 1280×720 frame",
        steps: |_| 1,
        measure: fresnel_knob,
    },
    Knob {
        name: "wave_resolution",
        varies: "displacement-map resolution N at the default scene's L = 256 m: RMS height error \
                 against the finest N at the coarsest grid's points (shared by every N, so the \
                 error is what the coarser band leaves out); f32 synthesis time",
        steps: |c| if c.quick { 5 } else { 6 },
        measure: wave_resolution_knob,
    },
    Knob {
        name: "precision",
        varies: "f32 against f64 synthesis of the default scene's displacement map (N = 256)",
        steps: |_| 2,
        measure: precision_knob,
    },
    Knob {
        name: "bump_resolution",
        varies: "bump-map resolution (the default scene's 32 m bump tile): image error against \
                 the finest, CPU frame time",
        steps: |c| (if c.quick { 4 } else { 5 }) * (c.runs as u64 + 1),
        measure: bump_resolution_knob,
    },
    Knob {
        name: "reflection_map_resolution",
        varies: "reflection map side as a fraction of the viewport ([quality] \
                 reflection_map_scale): image error against the full size, CPU frame time",
        steps: |c| 4 * (c.runs as u64 + 1),
        measure: reflection_map_knob,
    },
    Knob {
        name: "backend",
        varies: "the default scene on the CPU oracle (the reference) and on wgpu (the adapter \
                 WGPU_BACKEND picks; lavapipe in CI; wave maps from the GPU FFT): image error \
                 against the CPU frame, frame time (GPU: submission to readback of the 8-bit \
                 output). Without an adapter the knob has no GPU row and says why",
        steps: |c| 2 * (c.runs as u64 + 1),
        measure: backend_knob,
    },
    Knob {
        name: "far_field",
        varies: "what becomes of the waves a pixel cannot resolve ([techniques] far_field: none, \
                 mip, variance) on the default scene: mean |Δ log(1 + L)| per band of the sea \
                 (horizon < 2°, middle 2°–8°, near, by depression) against its --spp 64 frame \
                 of far field none; frame time on the CPU and the GPU (HDR read-back); and the \
                 cost of --spp itself (4, 16, 64 samples, CPU)",
        steps: far_field::steps,
        measure: far_field::measure,
    },
    Knob {
        name: "surface",
        varies: "the water mesh ([techniques] surface: hu_patches; projected_grid at 8, 4, 2 px \
                 cells) on the default scene's sea without its objects, against a projected grid \
                 of half-pixel cells: mean error of the height and of the position of the point \
                 each pixel sees (depth buffer), per band of the sea; in the setting, the \
                 vertices submitted and the share inside the view; frame time on the CPU and the \
                 GPU (the GPU rows carry the CPU's geometry, which the cross-check holds it to)",
        steps: surface::steps,
        measure: surface::measure,
    },
    Knob {
        name: "clouds",
        varies: "sky preetham against preetham_clouds (seed 001 eq. 4) under shading chiu on the \
                 default scene: what the clouds cost per frame on the CPU and the GPU, and how far \
                 they move the picture (mean |Δ log(1 + L)| against the clear sky's frame)",
        steps: surface::clouds_steps,
        measure: surface::measure_clouds,
    },
    Knob {
        name: "shading",
        varies: "the water's shading ([techniques] shading: hu, chiu, ggx) on the default scene: \
                 frame time on the CPU and the GPU, and how far each moves the picture (mean \
                 |Δ log(1 + L)| against hu's frame; each is its own model, so this is a change, \
                 not an error; GGX's energy balance is tests/ggx.rs' white furnace)",
        steps: techniques::shading_steps,
        measure: techniques::measure_shading,
    },
    Knob {
        name: "post",
        varies: "post tonemap against bloom (seed 002) on the default scene's 8-bit output: what \
                 the bloom costs per frame on the CPU and the GPU, and how far it moves the \
                 picture (mean |Δ| of the 8-bit values over 255)",
        steps: techniques::post_steps,
        measure: techniques::measure_post,
    },
    Knob {
        name: "frame_format",
        varies: "the frame's colour buffers ([post] frame_format: rgba32float, rgba16float as \
                 seed 002) on the default scene: frame time on the CPU and the GPU, and the mean \
                 |Δ log(1 + L)| of the f16 HDR frame against the f32 one",
        steps: techniques::frame_format_steps,
        measure: techniques::measure_frame_format,
    },
    Knob {
        name: "lod",
        varies: "near-patch refinement threshold ([quality] lod_split_threshold, radians): \
                 image error against the finest, CPU frame time",
        steps: |c| (if c.quick { 5 } else { 6 }) * (c.runs as u64 + 1),
        measure: lod_knob,
    },
];

const CPU: &str = "cpu";

// ---------------------------------------------------------------------------------------------
// fresnel

/// The bumped local view vectors the water pass looks F up at, one per water pixel seen from
/// above, for a CPU render of `scene`: water.wgsl's `fs_main` up to its texture lookup.
fn frame_view_vectors(scene: &Scene) -> anyhow::Result<Vec<[f64; 3]>> {
    let plan = FramePlan::new(scene, OutputKind::Hdr);
    let rendered = ocean_cpu::render_scene_with_plan(scene, plan.clone(), &mut |_| {})?;
    let fb = &rendered.buffers;
    let camera = ocean_core::camera::Camera::from_scene(&scene.camera)?;
    let mesh = plan.water_mesh(scene, &camera)?;
    let sky = |_: [f32; 3]| [0.0f32; 3];
    let (slope_chain, bump_chain) = fb.water_slopes(&plan);
    let b = fb.water_bindings(
        &plan,
        (&slope_chain, &bump_chain),
        &sky,
        ocean_cpu::shaders::shading::hu::shade_above,
    );
    let mut target = RenderTarget::new(camera.width, camera.height);
    target.clear_depth(0.0);
    target.clear_color([0.0; 4]);
    // The water pass's own draw and fs_main's own functions, up to its texture lookup.
    let mesh = mesh.into();
    ocean_cpu::frame::draw_water(&mut target, &mesh, &b, &|input, b| {
        let n = water::bumped_normal(input, b);
        let view = unit(-input.rel);
        if view.y < 0.0 {
            return Some([0.0; 4]);
        }
        // The bumped local (x, y) itself, so the lookup of every method starts from the same
        // vector whatever mapping the frame's texture uses.
        Some([view.x - n.x, view.z - n.z, 1.0, 1.0])
    });
    Ok(target
        .color
        .iter()
        .filter(|p| p[2] == 1.0)
        .map(|p| {
            let (x, y) = (f64::from(p[0]), f64::from(p[1]));
            let r2 = x * x + y * y;
            // A bumped vector beyond the rim is looked up as the grazing view at its azimuth.
            if r2 > 1.0 { [x / r2.sqrt(), y / r2.sqrt(), 0.0] } else { [x, y, (1.0 - r2).sqrt()] }
        })
        .collect())
}

fn fresnel_knob(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let eta = 1.333f64;
    let rows_theta = if ctx.quick { 96 } else { 192 };
    // The hemisphere: θ uniform (every grazing band sampled), weighted by sin θ for the RMS.
    let mut hemisphere = Vec::new();
    for k in 0..rows_theta {
        let theta = (k as f64 + 0.5) * std::f64::consts::FRAC_PI_2 / rows_theta as f64;
        for l in 0..4 * rows_theta {
            let phi = (l as f64 + 0.5) * std::f64::consts::TAU / (4 * rows_theta) as f64;
            let v = [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()];
            hemisphere.push((v, theta.sin()));
        }
    }
    let mut scene = Scene::builtin();
    (scene.camera.width, scene.camera.height) = ctx.frame_size();
    let pixels: Vec<([f64; 3], f64)> =
        frame_view_vectors(&scene)?.into_iter().map(|v| (v, 1.0)).collect();
    anyhow::ensure!(!pixels.is_empty(), "the default scene shows no water seen from above");

    type Method = Box<dyn Fn([f64; 3]) -> f32>;
    let mut methods: Vec<(String, Method)> = vec![(
        "eq. 2 per pixel (f32)".into(),
        Box::new(move |v: [f64; 3]| fresnel_exact(v[2] as f32, eta as f32)),
    )];
    for n in [16, 32, 64, 128, 256, 512] {
        let t = FresnelTexture::new(n, eta, TextureMapping::Hemisphere)?;
        methods.push((format!("2D texture {n}²"), Box::new(move |v| t.lookup_fresnel(v))));
    }
    // The renderer's mapping: the rim on texel centres, radius ∝ sqrt(1 − cos θ).
    for n in [16, 32, 64, 128, 256, 512] {
        let t = FresnelTexture::new(n, eta, TextureMapping::Grazing)?;
        methods.push((format!("2D grazing {n}²"), Box::new(move |v| t.lookup_fresnel(v))));
    }
    let half = FresnelTexture::new(256, eta, TextureMapping::PaperHalfRange)?;
    methods.push(("paper's half-range 256²".into(), Box::new(move |v| half.lookup_fresnel(v))));
    let table = FresnelTable1D::new(256, eta)?;
    methods.push(("1D table 256".into(), Box::new(move |v| table.lookup(v[2] as f32))));
    methods.push((
        "Schlick (f32)".into(),
        Box::new(move |v: [f64; 3]| fresnel_schlick(v[2] as f32, eta as f32)),
    ));

    // docs/design.md's tolerance table bounds the 256² texture within 76° of the normal.
    let cos_76 = 76f64.to_radians().cos();
    let within_76: Vec<([f64; 3], f64)> =
        hemisphere.iter().copied().filter(|(v, _)| v[2] >= cos_76).collect();
    let errors = |f: &Method, set: &[([f64; 3], f64)]| {
        let (mut max, mut sum_w_e2, mut sum_w) = (0.0f64, 0.0, 0.0);
        for &(v, w) in set {
            let e = (f64::from(f(v)) - fresnel_exact(v[2], eta)).abs();
            max = max.max(e);
            sum_w_e2 += w * e * e;
            sum_w += w;
        }
        (max, (sum_w_e2 / sum_w).sqrt())
    };
    let frame_lookups = 1280.0 * 720.0;
    let mut rows = Vec::new();
    for (name, f) in &methods {
        let (ms, sum) =
            ctx.time(|| Ok(hemisphere.iter().map(|&(v, _)| f64::from(f(v))).sum::<f64>()))?;
        std::hint::black_box(sum);
        let time_ms = ms * frame_lookups / hemisphere.len() as f64;
        let (h_max, h_rms) = errors(f, &hemisphere);
        let (p_max, p_rms) = errors(f, &pixels);
        let (h76_max, _) = errors(f, &within_76);
        for (metric, error) in [
            ("max_abs_theta_le_76deg", h76_max),
            ("max_abs_hemisphere", h_max),
            ("rms_hemisphere", h_rms),
            ("max_abs_frame_pixels", p_max),
            ("rms_frame_pixels", p_rms),
        ] {
            rows.push(Row {
                knob: "fresnel",
                setting: name.clone(),
                error_metric: metric,
                error,
                time_ms,
                backend: CPU,
            });
        }
    }
    ctx.step("fresnel");
    Ok(rows)
}

// ---------------------------------------------------------------------------------------------
// wave_resolution, precision

fn wave_resolution_knob(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let base = Scene::builtin().ocean;
    let sizes: &[usize] =
        if ctx.quick { &[32, 64, 128, 256, 512] } else { &[32, 64, 128, 256, 512, 1024] };
    let coarse = sizes[0];
    let mut fields = Vec::new();
    for &n in sizes {
        let ocean = ocean_core::scene::Ocean { resolution: n as u32, ..base.clone() };
        let modes = ocean.displacement_modes()?;
        let mut synth = Synthesizer::<f32>::new(n)?;
        let (ms, maps) =
            ctx.time(|| Ok(synth.synthesize(&modes, ocean.time_s, ocean.choppiness)?))?;
        // Heights at the coarsest grid's points, which every finer grid holds.
        let stride = n / coarse;
        let at: Vec<f64> = (0..coarse)
            .flat_map(|j| (0..coarse).map(move |i| (i, j)))
            .map(|(i, j)| f64::from(maps.height[maps.index(i * stride, j * stride)]))
            .collect();
        fields.push((n, ms, at));
        ctx.step(&format!("wave_resolution {n}"));
    }
    let reference = fields.last().context("one size")?.2.clone();
    Ok(fields
        .into_iter()
        .map(|(n, ms, at)| {
            let e2 = at.iter().zip(&reference).map(|(a, b)| (a - b).powi(2)).sum::<f64>();
            Row {
                knob: "wave_resolution",
                setting: format!("N = {n}"),
                error_metric: "rms_height_m",
                error: (e2 / at.len() as f64).sqrt(),
                time_ms: ms,
                backend: CPU,
            }
        })
        .collect())
}

fn precision_knob(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let ocean = Scene::builtin().ocean;
    let modes = ocean.displacement_modes()?;
    let n = modes.resolution();
    let mut s64 = Synthesizer::<f64>::new(n)?;
    let (ms64, m64): (f64, WaveMaps<f64>) =
        ctx.time(|| Ok(s64.synthesize(&modes, ocean.time_s, ocean.choppiness)?))?;
    ctx.step("precision f64");
    let mut s32 = Synthesizer::<f32>::new(n)?;
    let (ms32, m32): (f64, WaveMaps<f32>) =
        ctx.time(|| Ok(s32.synthesize(&modes, ocean.time_s, ocean.choppiness)?))?;
    ctx.step("precision f32");
    let diff: Vec<f64> =
        m32.height.iter().zip(&m64.height).map(|(a, b)| f64::from(*a) - b).collect();
    let max = diff.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    let rms = (diff.iter().map(|d| d * d).sum::<f64>() / diff.len() as f64).sqrt();
    let row = |setting: &str, metric, error, time_ms| Row {
        knob: "precision",
        setting: setting.into(),
        error_metric: metric,
        error,
        time_ms,
        backend: CPU,
    };
    Ok(vec![
        row("f64 (N = 256)", "max_abs_height_m", 0.0, ms64),
        row("f64 (N = 256)", "rms_height_m", 0.0, ms64),
        row("f32 (N = 256)", "max_abs_height_m", max, ms32),
        row("f32 (N = 256)", "rms_height_m", rms, ms32),
    ])
}

// ---------------------------------------------------------------------------------------------
// Image knobs

/// A CPU frame: the 8-bit RGB picture and the linear HDR RGB.
struct Frame {
    rgb: Vec<u8>,
    hdr: Vec<[f32; 4]>,
    width: u32,
    height: u32,
}

fn render_frame(scene: &Scene) -> anyhow::Result<Frame> {
    let r = ocean_cpu::render_scene(scene, OutputKind::Ldr, &mut |_| {})?;
    let ldr = r.ldr.context("the plan tonemaps")?;
    Ok(Frame {
        rgb: ldr.chunks(4).flat_map(|p| [p[0], p[1], p[2]]).collect(),
        hdr: r.buffers.hdr.color,
        width: scene.camera.width,
        height: scene.camera.height,
    })
}

/// FLIP mean (LDR, NVIDIA's ꟻLIP at its default 67 pixels per degree) and the RMSE of the
/// linear HDR RGB between a test frame and the reference.
fn image_errors(reference: &Frame, test: &Frame) -> (f64, f64) {
    let a = nv_flip::FlipImageRgb8::with_data(reference.width, reference.height, &reference.rgb);
    let b = nv_flip::FlipImageRgb8::with_data(test.width, test.height, &test.rgb);
    let map = nv_flip::flip(a, b, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let flip_mean = f64::from(nv_flip::FlipPool::from_image(&map).mean());
    let mut e2 = 0.0f64;
    for (p, q) in reference.hdr.iter().zip(&test.hdr) {
        for c in 0..3 {
            e2 += (f64::from(p[c]) - f64::from(q[c])).powi(2);
        }
    }
    (flip_mean, (e2 / (3 * reference.hdr.len()) as f64).sqrt())
}

/// A setting of an image knob: how it changes the scene.
type SceneEdit = Box<dyn Fn(&mut Scene)>;

/// A timed piece of work of [`Ctx::time_interleaved`].
type Work<'a, T> = Box<dyn FnMut() -> anyhow::Result<T> + 'a>;

/// Renders the default scene with each setting applied (the last is the reference) and
/// returns the rows of both image metrics.
fn image_knob(
    ctx: &Ctx,
    knob: &'static str,
    settings: Vec<(String, SceneEdit)>,
) -> anyhow::Result<Vec<Row>> {
    let mut base = Scene::builtin();
    (base.camera.width, base.camera.height) = ctx.frame_size();
    let mut scenes = Vec::new();
    for (name, apply) in &settings {
        let mut scene = base.clone();
        apply(&mut scene);
        if let Err((key, msg)) = scene.validate() {
            anyhow::bail!("{knob} {name}: {key}: {msg}");
        }
        scenes.push(scene);
    }
    let mut renders: Vec<Work<'_, Frame>> = scenes
        .iter()
        .map(|scene| {
            let f: Work<'_, Frame> = Box::new(move || {
                let frame = render_frame(scene);
                ctx.step(knob);
                frame
            });
            f
        })
        .collect();
    let timed = ctx.time_interleaved(&mut renders)?;
    drop(renders);
    let frames: Vec<(String, f64, Frame)> = settings
        .iter()
        .zip(timed)
        .map(|((name, _), (ms, frame))| (name.clone(), ms, frame))
        .collect();
    let reference = &frames.last().context("one setting")?.2;
    ctx.pictures.add(pictures::Set {
        knob,
        reference_is: format!("{}, the finest setting", frames[frames.len() - 1].0),
        width: reference.width,
        height: reference.height,
        shots: frames
            .iter()
            .map(|(name, _, f)| pictures::Shot { setting: name.clone(), rgb: f.rgb.clone() })
            .collect(),
        reference: frames.len() - 1,
        rows: None,
    });
    let mut rows = Vec::new();
    for (name, ms, frame) in &frames {
        let (flip, rmse) = image_errors(reference, frame);
        for (metric, error) in [("flip_mean", flip), ("rmse_linear", rmse)] {
            rows.push(Row {
                knob,
                setting: name.clone(),
                error_metric: metric,
                error,
                time_ms: *ms,
                backend: CPU,
            });
        }
    }
    Ok(rows)
}

fn bump_resolution_knob(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let sizes: &[u32] = if ctx.quick { &[64, 128, 256, 512] } else { &[64, 128, 256, 512, 1024] };
    let settings = sizes
        .iter()
        .map(|&n| {
            let apply: SceneEdit = Box::new(move |s: &mut Scene| s.ocean.bump_resolution = n);
            (format!("{n}²"), apply)
        })
        .collect();
    image_knob(ctx, "bump_resolution", settings)
}

fn reflection_map_knob(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let settings = [0.125, 0.25, 0.5, 1.0]
        .into_iter()
        .map(|scale| {
            let apply: SceneEdit =
                Box::new(move |s: &mut Scene| s.quality.reflection_map_scale = scale);
            (format!("{scale} × viewport"), apply)
        })
        .collect();
    image_knob(ctx, "reflection_map_resolution", settings)
}

fn backend_knob(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let mut scene = Scene::builtin();
    (scene.camera.width, scene.camera.height) = ctx.frame_size();
    let plan = FramePlan::new(&scene, OutputKind::Ldr);
    let mut shared = ctx.gpu();
    let mut gpu = match shared.as_mut() {
        Ok(r) => Some(r),
        Err(e) => {
            ctx.bar.suspend(|| eprintln!("report: backend knob has no GPU row: {e}"));
            None
        }
    };
    let size = ctx.frame_size();
    let mut works: Vec<Work<'_, Frame>> = vec![Box::new(|| {
        let f = render_frame(&scene);
        ctx.step("backend cpu");
        f
    })];
    if let Some(renderer) = gpu.as_mut() {
        let (scene, plan) = (&scene, &plan);
        works.push(Box::new(move || {
            let frame = renderer.run_with(scene, plan, ocean_gpu::Readback::Output)?;
            let ldr = frame.ldr.context("the plan tonemaps")?;
            ctx.step("backend gpu");
            Ok(Frame {
                rgb: ldr.chunks(4).flat_map(|p| [p[0], p[1], p[2]]).collect(),
                hdr: Vec::new(),
                width: size.0,
                height: size.1,
            })
        }));
    }
    let timed = ctx.time_interleaved(&mut works)?;
    drop(works);
    let reference = &timed.first().context("the CPU frame")?.1;
    ctx.pictures.add(pictures::Set {
        knob: "backend",
        reference_is: "the CPU oracle's frame".into(),
        width: size.0,
        height: size.1,
        shots: timed
            .iter()
            .zip([CPU, "gpu"])
            .map(|((_, f), b)| pictures::Shot { setting: format!("{b} frame"), rgb: f.rgb.clone() })
            .collect(),
        reference: 0,
        rows: None,
    });
    let mut rows = Vec::new();
    for ((ms, frame), backend) in timed.iter().zip([CPU, "gpu"]) {
        let (flip, _) = image_errors(reference, frame);
        rows.push(Row {
            knob: "backend",
            setting: format!("{backend} frame"),
            error_metric: "flip_mean",
            error: flip,
            time_ms: *ms,
            backend,
        });
    }
    Ok(rows)
}

fn lod_knob(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let thresholds: &[f64] = if ctx.quick {
        &[0.4, 0.2, 0.1, 0.05, 0.025]
    } else {
        &[0.4, 0.2, 0.1, 0.05, 0.025, 0.0125]
    };
    let settings = thresholds
        .iter()
        .map(|&t| {
            let apply: SceneEdit = Box::new(move |s: &mut Scene| s.quality.lod_split_threshold = t);
            (format!("split {t} rad"), apply)
        })
        .collect();
    image_knob(ctx, "lod", settings)
}

// ---------------------------------------------------------------------------------------------
// Planner

/// One reference scene's plan, the passes its pruning leaves out, and the frame times.
struct PlannerRow {
    scene: String,
    pruned: Vec<Pass>,
    culled: String,
    full_ms: f64,
    pruned_ms: f64,
    differing: usize,
}

fn planner(ctx: &Ctx) -> anyhow::Result<Vec<PlannerRow>> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference/scenes");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .with_context(|| format!("cannot list {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    let mut out = Vec::new();
    for path in paths {
        let mut scene = Scene::load(&path)?;
        (scene.camera.width, scene.camera.height) = ctx.frame_size();
        let pruned = FramePlan::new(&scene, OutputKind::Ldr);
        let full = FramePlan::full(&scene, OutputKind::Ldr);
        let frame = |plan: &FramePlan| -> anyhow::Result<Vec<[f32; 4]>> {
            Ok(ocean_cpu::render_scene_with_plan(&scene, plan.clone(), &mut |_| {})?
                .buffers
                .hdr
                .color)
        };
        let mut pair: Vec<Work<'_, Vec<[f32; 4]>>> =
            vec![Box::new(|| frame(&full)), Box::new(|| frame(&pruned))];
        // --quick: one round, untimed warm-up left out (the pictures' bit-for-bit check is
        // what the quick report is for; the full report times 7 rounds).
        let mut timed = if ctx.quick {
            let mut once = Vec::new();
            for f in &mut pair {
                let t0 = Instant::now();
                let r = f()?;
                once.push((t0.elapsed().as_secs_f64() * 1e3, r));
            }
            once
        } else {
            ctx.time_interleaved(&mut pair)?
        }
        .into_iter();
        drop(pair);
        let (full_ms, a) = timed.next().context("two plans")?;
        let (pruned_ms, b) = timed.next().context("two plans")?;
        let differing =
            a.iter().zip(&b).filter(|(p, q)| p.map(f32::to_bits) != q.map(f32::to_bits)).count();
        let (o, f) = (pruned.objects(), full.objects());
        let culled = [
            ("objects", o.objects.len(), f.objects.len()),
            ("reflection_map", o.reflection_map.len(), f.reflection_map.len()),
            ("refraction_map", o.refraction_map.len(), f.refraction_map.len()),
        ]
        .iter()
        .filter(|(_, k, n)| k < n)
        .map(|(p, k, n)| format!("{p} {k}/{n}"))
        .collect::<Vec<_>>()
        .join(", ");
        let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        ctx.step(&format!("planner {name}"));
        out.push(PlannerRow {
            scene: name,
            pruned: pruned.pruned_from(&full),
            culled,
            full_ms,
            pruned_ms,
            differing,
        });
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// Pareto

/// The rows of `rows` not dominated by another (≤ error and ≤ time, one strictly).
fn pareto<'a>(rows: &[&'a Row]) -> Vec<&'a Row> {
    rows.iter()
        .filter(|r| {
            !rows.iter().any(|o| {
                o.error <= r.error
                    && o.time_ms <= r.time_ms
                    && (o.error < r.error || o.time_ms < r.time_ms)
            })
        })
        .copied()
        .collect()
}

/// A knob's rows, (metric, backend) group by group, each with whether it is on its group's
/// Pareto front.
fn marked_rows<'a>(rows: &'a [Row], knob: &str) -> Vec<(&'a Row, bool)> {
    let mut out = Vec::new();
    for (k, metric, backend) in groups(rows).into_iter().filter(|g| g.0 == knob) {
        let g: Vec<&Row> = rows
            .iter()
            .filter(|r| r.knob == k && r.error_metric == metric && r.backend == backend)
            .collect();
        let front = pareto(&g);
        out.extend(g.iter().map(|r| (*r, front.iter().any(|f| std::ptr::eq(*f, *r)))));
    }
    out
}

/// A `lod` row of FLIP on the CPU, for the tests of the report's parts.
#[cfg(test)]
fn test_row(setting: &str, error: f64, time_ms: f64) -> Row {
    Row {
        knob: "lod",
        setting: setting.into(),
        error_metric: "flip_mean",
        error,
        time_ms,
        backend: CPU,
    }
}

/// (knob, metric, backend) groups in first-seen order.
fn groups(rows: &[Row]) -> Vec<(&'static str, &'static str, &'static str)> {
    let mut g = Vec::new();
    for r in rows {
        let key = (r.knob, r.error_metric, r.backend);
        if !g.contains(&key) {
            g.push(key);
        }
    }
    g
}

/// The text of report.md's section `heading` (up to the next `## `).
fn section(md: &str, heading: &str) -> String {
    md.split(heading)
        .nth(1)
        .map(|rest| format!("{heading}{}", rest.split("\n## ").next().unwrap_or("")))
        .unwrap_or_default()
}

/// Runs `ocean report`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let start = Instant::now();
    let dir = &args.out_dir;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let mut ctx = Ctx {
        quick: args.quick,
        runs: if args.quick { 2 } else { 7 },
        bar: ProgressBar::hidden(),
        pictures: pictures::Pictures::default(),
        gpu: std::cell::RefCell::new(None),
    };
    let scenes =
        std::fs::read_dir(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference/scenes"))
            .map(|d| d.count() as u64)
            .unwrap_or(8);
    let total = KNOBS.iter().map(|k| (k.steps)(&ctx)).sum::<u64>()
        + scenes
        + 1
        + scaling::steps(&ctx)
        + systems::steps(&ctx);
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{elapsed:>4} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    ctx.bar = bar;
    // Where the report's time went, for its header (and for keeping --quick quick).
    let mut spent: Vec<(String, f64)> = Vec::new();
    let mut lap = Instant::now();
    let mut took = |what: &str| {
        spent.push((what.to_string(), lap.elapsed().as_secs_f64()));
        lap = Instant::now();
    };
    let mut rows = Vec::new();
    for knob in KNOBS {
        rows.extend((knob.measure)(&ctx).with_context(|| format!("knob {}", knob.name))?);
        took(knob.name);
    }
    let planner = planner(&ctx)?;
    took("planner");
    let scaling = scaling::measure(&ctx).context("the scaling measurements")?;
    took("scaling");
    let systems = systems::measure(&ctx).context("the systems section")?;
    took("systems");
    let stability = ocean_verify::stability::cases()?;
    ctx.step("stability");
    took("stability");
    ctx.bar.set_message("writing");

    write_atomic(&dir.join("error_vs_time.csv"), markdown::csv(&rows).as_bytes())?;
    let knob_names: Vec<&'static str> = KNOBS.iter().map(|k| k.name).collect();
    let overview = plot::overview(&rows, &knob_names);
    write_atomic(&dir.join("error_vs_time.svg"), overview.as_bytes())?;
    write_atomic(&dir.join("error_vs_time.png"), &svg::png_of(&overview, 1.0)?)?;
    let knob_plots: Vec<(&'static str, String)> =
        knob_names.iter().map(|k| (*k, plot::knob(&rows, k))).collect();
    // plotters writes the SVG itself: into a temporary name, then renamed.
    let scaling_path = dir.join("scaling.svg");
    let tmp = dir.join(format!(".scaling.svg.tmp-{}", std::process::id()));
    scaling::plot(&scaling, &tmp)?;
    std::fs::rename(&tmp, &scaling_path)
        .with_context(|| format!("cannot write {}", scaling_path.display()))?;
    let scaling_svg = std::fs::read_to_string(&scaling_path)?;
    write_atomic(&dir.join("systems.png"), &svg::png_of(&systems_figures::sheet(&systems)?, 1.0)?)?;
    let shown = ctx.pictures.write(dir)?;
    took("writing");
    let elapsed_s = start.elapsed().as_secs_f64();
    let spent = spent.iter().map(|(w, s)| format!("{w} {s:.1} s")).collect::<Vec<_>>().join(", ");
    let md = markdown::markdown(&args, ctx.runs, &rows, &planner, &stability, elapsed_s)
        .replacen(
            "\n\n## Pareto",
            &format!(" Ran on {}. Time spent: {spent}.\n\n## Pareto", html::machine(&systems.gpu)),
            1,
        )
        .replacen(
            "## Numerical stability",
            &format!("{}## Numerical stability", scaling::markdown(&scaling)),
            1,
        );
    write_atomic(&dir.join("report.md"), md.as_bytes())?;
    let command = if args.quick { "ocean report --quick" } else { "ocean report" };
    let page = html::page(&html::Page {
        command: format!("{command} --out-dir {}", dir.display()),
        elapsed_s,
        spent,
        machine: html::machine(&systems.gpu),
        rows: &rows,
        overview: &overview,
        knob_plots: &knob_plots,
        pictures: &shown,
        systems: &systems,
        stability: &stability,
        planner_md: section(&md, "## Planner"),
        scaling_md: section(&md, "## Scaling"),
        scaling_svg: &scaling_svg,
    });
    write_atomic(&dir.join("index.html"), page.as_bytes())?;
    ctx.bar.finish_and_clear();
    let failing = stability.iter().filter(|c| !c.passes()).count();
    eprintln!(
        "wrote {} (open it in a browser), report.md, error_vs_time.{{csv,svg,png}}, scaling.svg, \
         systems.png and pictures/ in {:.0} s{}",
        dir.join("index.html").display(),
        start.elapsed().as_secs_f64(),
        if failing > 0 { format!("; {failing} stability case(s) FAIL") } else { String::new() }
    );
    Ok(())
}
