//! The report's `far_field` knob (issue 12): far fields `none`, `mip` and `variance` on the
//! default scene against its `--spp 64` frame (far field `none`, the same model point-sampled
//! 64 times per pixel), per band of the sea (ocean-core's `sea_bands`: the depression below
//! the horizon < 2°, 2°–8°, beyond), and each one's frame time on the CPU and, where an
//! adapter exists, on the GPU; and the cost of `--spp` itself (4 and 16 samples against 64).

use anyhow::Context;
use ocean_core::camera::Camera;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::Scene;
use ocean_core::supersample::{band_error, box_filter, grid_side, sea_bands};
use ocean_gpu::FrameMap;

use super::{CPU, Ctx, Row};
use ocean_core::plan::{FarField, StageTechnique};

/// The far fields the knob measures: every one.
const FAR_FIELDS: &[FarField] = FarField::ALL;

/// Sample counts whose cost the knob measures against the 64-sample truth.
const SPPS: [u32; 2] = [4, 16];

/// The error metric of band `b` (ocean-core's `BAND_NAMES`, in its order): mean
/// |Δ log(1 + L)| over its rows.
const METRICS: [&str; 3] = ["log_l_horizon", "log_l_middle", "log_l_near"];

/// Progress steps of [`measure`]: per timed setting one warm-up and `runs` timed frames.
pub(super) fn steps(ctx: &Ctx) -> u64 {
    (2 * FAR_FIELDS.len() + SPPS.len() + 1) as u64 * (ctx.runs as u64 + 1)
}

/// The default scene at the knob's size with far field `far`, rendered at k× the size.
fn scene(ctx: &Ctx, far: FarField, k: u32) -> Scene {
    let mut s = Scene::builtin();
    let (w, h) = ctx.frame_size();
    (s.camera.width, s.camera.height) = (w * k, h * k);
    s.techniques.far_field = Some(far);
    s
}

/// The HDR frame of `scene` on the CPU, box-filtered down by `k`.
fn cpu_hdr(ctx: &Ctx, scene: &Scene, k: u32) -> anyhow::Result<Vec<[f32; 4]>> {
    let r = ocean_cpu::render_scene(scene, OutputKind::Hdr, &mut |_| {})?;
    let (w, h) = ctx.frame_size();
    Ok(box_filter(&r.buffers.hdr.color, w, h, k))
}

/// Measures the knob: three rows (one per band) per far field and back end, and per sample
/// count.
pub(super) fn measure(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let (w, h) = ctx.frame_size();
    let base = scene(ctx, FarField::None, 1);
    let bands = sea_bands(&Camera::from_scene(&base.camera)?, h);
    let truth_scene = scene(ctx, FarField::None, 8);
    let (truth_ms, truth) = ctx.time(|| {
        let f = cpu_hdr(ctx, &truth_scene, 8);
        ctx.step("far_field 64 spp");
        f
    })?;
    let mut rows = Vec::new();
    let mut shots: Vec<(String, Vec<[f32; 4]>)> = vec![("none 64 spp".into(), truth.clone())];
    let mut push = |setting: String, frame: &[[f32; 4]], ms: f64, backend: &'static str| {
        for (b, rows_b) in bands.iter().enumerate() {
            if !rows_b.is_empty() {
                rows.push(Row {
                    knob: "far_field",
                    setting: setting.clone(),
                    error_metric: METRICS[b],
                    error: band_error(frame, &truth, w, rows_b),
                    time_ms: ms,
                    backend,
                });
            }
        }
    };
    push("none 64 spp".into(), &truth, truth_ms, CPU);
    for spp in SPPS {
        let k = grid_side(spp)?;
        let s = scene(ctx, FarField::None, k);
        let (ms, f) = ctx.time(|| {
            let f = cpu_hdr(ctx, &s, k);
            ctx.step("far_field spp");
            f
        })?;
        push(format!("none {spp} spp"), &f, ms, CPU);
        shots.push((format!("none {spp} spp"), f));
    }
    for &far in FAR_FIELDS {
        let s = scene(ctx, far, 1);
        let (ms, f) = ctx.time(|| {
            let f = cpu_hdr(ctx, &s, 1);
            ctx.step("far_field cpu");
            f
        })?;
        push(far.to_string(), &f, ms, CPU);
        shots.push((far.to_string(), f));
    }
    // The pictures: the band within 2° of the horizon and as many rows of sky above it.
    let band = bands.iter().find(|b| !b.is_empty());
    if let (Some(first), Some(last)) =
        (band.and_then(|b| b.iter().min()), band.and_then(|b| b.iter().max()))
    {
        let exposure = base.camera.exposure as f32;
        ctx.pictures.add(super::pictures::Set {
            knob: "far_field",
            reference_is: "far field none at 64 samples per pixel (--spp 64)".into(),
            width: w,
            height: h,
            shots: shots
                .iter()
                .map(|(name, f)| super::pictures::Shot {
                    setting: name.clone(),
                    rgb: super::pictures::display(f, exposure),
                })
                .collect(),
            reference: 0,
            rows: Some((first.saturating_sub(last - first + 1), last + 1)),
        });
    }
    match ctx.gpu().as_mut() {
        Ok(gpu) => {
            for &far in FAR_FIELDS {
                let s = scene(ctx, far, 1);
                let plan = FramePlan::new(&s, OutputKind::Hdr);
                let (ms, f) = ctx.time(|| {
                    let frame = gpu.run_with(&s, &plan, ocean_gpu::Readback::Output)?;
                    let hdr = frame.map(FrameMap::Hdr).context("the HDR frame")?.texels.clone();
                    ctx.step("far_field gpu");
                    Ok(hdr)
                })?;
                push(far.to_string(), &f, ms, "gpu");
            }
        }
        Err(e) => {
            ctx.bar.suspend(|| eprintln!("report: far_field knob has no GPU rows: {e}"));
        }
    }
    Ok(rows)
}
