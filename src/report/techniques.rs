//! The `shading` and `post` knobs: one technique against another on the default scene — what
//! each costs per frame on the CPU and the GPU, and how far it moves the picture from the
//! first setting's. Neither trades accuracy for speed against a reference (each is its own
//! model), so the error column is the change, not an error.

use anyhow::Context;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::Scene;
use ocean_core::supersample::band_error;

use super::{CPU, Ctx, Row};

/// Progress steps of one technique knob with `settings` settings.
fn steps(ctx: &Ctx, settings: u64) -> u64 {
    2 * settings * (ctx.runs as u64 + 1)
}

/// Steps of the `shading` knob.
pub(super) fn shading_steps(ctx: &Ctx) -> u64 {
    steps(ctx, 3)
}

/// Steps of the `post` knob.
pub(super) fn post_steps(ctx: &Ctx) -> u64 {
    steps(ctx, 2)
}

/// The `shading` knob: `hu`, `chiu` and `ggx` on the default scene (HDR): frame time on both
/// back ends, and mean |Δ log(1 + L)| over the frame against `hu`'s.
pub(super) fn measure_shading(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let settings = ["hu", "chiu", "ggx"].map(|name| {
        (name, Box::new(move |s: &mut Scene| s.techniques.shading = Some(name.into())) as Edit)
    });
    measure(ctx, "shading", OutputKind::Hdr, "log_l_change", &settings)
}

/// The `post` knob: post `tonemap` and `bloom` on the default scene (8-bit output, where the
/// bloom is composited): frame time on both back ends, and the mean |Δ| of the 8-bit values
/// (over 255) against `tonemap`'s picture.
pub(super) fn measure_post(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let settings = ["tonemap", "bloom"].map(|name| {
        (name, Box::new(move |s: &mut Scene| s.techniques.post = Some(name.into())) as Edit)
    });
    measure(ctx, "post", OutputKind::Ldr, "ldr_mean_change", &settings)
}

type Edit = Box<dyn Fn(&mut Scene)>;

/// The frame as the metric reads it: the HDR RGB, or the 8-bit values as f32.
fn frame_values(r: &ocean_cpu::render::Rendered, output: OutputKind) -> Vec<[f32; 4]> {
    match (output, &r.ldr) {
        (OutputKind::Ldr, Some(ldr)) => ldr
            .chunks(4)
            .map(|p| [f32::from(p[0]), f32::from(p[1]), f32::from(p[2]), 0.0])
            .collect(),
        _ => r.buffers.hdr.color.clone(),
    }
}

fn change(output: OutputKind, a: &[[f32; 4]], b: &[[f32; 4]], w: u32, h: u32) -> f64 {
    match output {
        OutputKind::Ldr => {
            let sum: f64 = a
                .iter()
                .zip(b)
                .map(|(p, q)| (0..3).map(|c| f64::from((p[c] - q[c]).abs())).sum::<f64>())
                .sum();
            sum / (3.0 * 255.0 * a.len().max(1) as f64)
        }
        OutputKind::Hdr => band_error(a, b, w, &(0..h).collect::<Vec<u32>>()),
    }
}

fn measure(
    ctx: &Ctx,
    knob: &'static str,
    output: OutputKind,
    metric: &'static str,
    settings: &[(&'static str, Edit)],
) -> anyhow::Result<Vec<Row>> {
    let (w, h) = ctx.frame_size();
    let mut first: Option<Vec<[f32; 4]>> = None;
    let mut rows = Vec::new();
    let mut gpu = ocean_gpu::Renderer::new().ok();
    for (name, edit) in settings {
        let mut s = Scene::builtin();
        (s.camera.width, s.camera.height) = (w, h);
        edit(&mut s);
        if let Err((key, msg)) = s.validate() {
            anyhow::bail!("{knob} {name}: {key}: {msg}");
        }
        let (ms, f) = ctx.time(|| {
            let r = ocean_cpu::render_scene(&s, output, &mut |_| {})?;
            ctx.step(knob);
            Ok(frame_values(&r, output))
        })?;
        let d = first.as_ref().map_or(0.0, |f0| change(output, &f, f0, w, h));
        first.get_or_insert(f);
        let row = |time_ms, backend| Row {
            knob,
            setting: (*name).into(),
            error_metric: metric,
            error: d,
            time_ms,
            backend,
        };
        rows.push(row(ms, CPU));
        if let Some(g) = gpu.as_mut() {
            let plan = FramePlan::new(&s, output);
            let (gms, ()) = ctx.time(|| {
                g.run_with(&s, &plan, ocean_gpu::Readback::Output).context("GPU frame")?;
                ctx.step(knob);
                Ok(())
            })?;
            rows.push(row(gms, "gpu"));
        }
    }
    Ok(rows)
}
