//! The `shading` and `post` knobs: one technique against another on the default scene — what
//! each costs per frame on the CPU and the GPU, and how far it moves the picture from the
//! first setting's. Neither trades accuracy for speed against a reference (each is its own
//! model), so the error column is the change, not an error.

use anyhow::Context;
use ocean_core::plan::{FramePlan, OutputKind, Post, Shading, StageTechnique};
use ocean_core::scene::Scene;
use ocean_core::supersample::band_error;

use super::{CPU, Ctx, Row};

/// Progress steps of one technique knob with `settings` settings.
fn steps(ctx: &Ctx, settings: u64) -> u64 {
    2 * settings * (ctx.runs as u64 + 1)
}

/// Steps of the `shading` knob.
pub(super) fn shading_steps(ctx: &Ctx) -> u64 {
    steps(ctx, Shading::ALL.len() as u64)
}

/// Steps of the `post` knob.
pub(super) fn post_steps(ctx: &Ctx) -> u64 {
    steps(ctx, 2)
}

/// Steps of the `frame_format` knob.
pub(super) fn frame_format_steps(ctx: &Ctx) -> u64 {
    steps(ctx, 2)
}

/// The `frame_format` knob: the frame's colour buffers in `rgba32float` and `rgba16float`
/// (seed 002) on the default scene (HDR): frame time on both back ends, and the mean
/// |Δ log(1 + L)| of the f16 frame against the f32 one (what the truncation to binary16 and
/// its f16 reflection and refraction maps cost the picture).
pub(super) fn measure_frame_format(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    use ocean_core::frame_format::FrameFormat;
    let settings = FrameFormat::ALL
        .map(|f| (f.name(), Box::new(move |s: &mut Scene| s.post.frame_format = Some(f)) as Edit));
    measure(ctx, "frame_format", OutputKind::Hdr, "log_l_change", &settings)
}

/// The `shading` knob: every shading technique on the default scene (HDR): frame time on both
/// back ends, and mean |Δ log(1 + L)| over the frame against the first's (`hu`).
pub(super) fn measure_shading(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let settings: Vec<_> = Shading::ALL
        .iter()
        .map(|&t| {
            let name = t.name();
            (name, Box::new(move |s: &mut Scene| s.techniques.shading = Some(t)) as Edit)
        })
        .collect();
    let mut rows = measure(ctx, "shading", OutputKind::Hdr, "log_l_change", &settings)?;
    // GGX's energy balance: the white furnace (F = 1) at the built-in scene's roughness, with
    // the CPU frame's time. `hu` and `chiu` reflect by a Fresnel-weighted mirror, which a
    // white furnace returns whole by construction, so they have no row.
    let ggx_ms = rows
        .iter()
        .find(|r| r.setting == Shading::Ggx.name() && r.backend == CPU)
        .map_or(f64::NAN, |r| r.time_ms);
    let alpha = ocean_core::ggx::alpha_from_roughness(Scene::builtin().ggx.roughness);
    for (metric, theta) in [
        ("white_furnace_loss_0deg", 0.0f64),
        ("white_furnace_loss_45deg", 45.0),
        ("white_furnace_loss_75deg", 75.0),
    ] {
        rows.push(Row {
            knob: "shading",
            setting: Shading::Ggx.name().into(),
            error_metric: metric,
            error: 1.0 - white_furnace(alpha, theta.to_radians()),
            time_ms: ggx_ms,
            backend: CPU,
        });
    }
    Ok(rows)
}

/// ∫ f cos θ_l dω_l of GGX with F = 1 and Smith's height-correlated G for a view θ_v from the
/// normal, as an integral over microfacet normals h (dω_l = 4 (h·v) dω_h, so the integrand is
/// G·D·(h·v)/(n·v)) with θ_h = atan(α tan(πx/2)), which puts the midpoints where D is (512 × 512;
/// tests/ggx.rs holds the same integral to its closed forms).
fn white_furnace(alpha: f64, theta_v: f64) -> f64 {
    use ocean_core::ggx::{ggx_d, smith_g2};
    use std::f64::consts::{FRAC_PI_2, TAU};
    let (nx, np) = (512, 512);
    let v = glam::DVec3::new(theta_v.sin(), theta_v.cos(), 0.0);
    let n = glam::DVec3::Y;
    let mut e = 0.0;
    for i in 0..nx {
        let x = (i as f64 + 0.5) / nx as f64;
        let q = (FRAC_PI_2 * x).tan();
        let th = (alpha * q).atan();
        let dth = alpha * FRAC_PI_2 * (1.0 + q * q) / (1.0 + alpha * alpha * q * q) / nx as f64;
        for j in 0..np {
            let p = (j as f64 + 0.5) * TAU / np as f64;
            let h = glam::DVec3::new(th.sin() * p.cos(), th.cos(), th.sin() * p.sin());
            let hv = h.dot(v);
            let l = 2.0 * hv * h - v;
            let (nl, nv) = (n.dot(l), n.dot(v));
            if hv <= 0.0 || nl <= 0.0 {
                continue;
            }
            let w = th.sin() * dth * TAU / np as f64;
            e += smith_g2(nl, nv, alpha) * ggx_d(th.cos(), alpha) * hv / nv * w;
        }
    }
    e
}

/// The `post` knob: post `tonemap` and `bloom` on the default scene (8-bit output, where the
/// bloom is composited): frame time on both back ends, and the mean |Δ| of the 8-bit values
/// (over 255) against `tonemap`'s picture.
pub(super) fn measure_post(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let settings = [Post::Tonemap, Post::Bloom]
        .map(|t| (t.name(), Box::new(move |s: &mut Scene| s.techniques.post = Some(t)) as Edit));
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
    let mut shared = ctx.gpu();
    let mut gpu = shared.as_mut().ok();
    let mut shots = Vec::new();
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
        let exposure = s.camera.exposure as f32;
        shots.push(super::pictures::Shot {
            setting: (*name).into(),
            rgb: match output {
                OutputKind::Ldr => {
                    f.iter().flat_map(|p| [p[0] as u8, p[1] as u8, p[2] as u8]).collect()
                }
                OutputKind::Hdr => super::pictures::display(&f, exposure),
            },
        });
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
    ctx.pictures.add(super::pictures::Set {
        knob,
        reference_is: format!(
            "{}, the first setting (a change of model, not an error)",
            settings[0].0
        ),
        width: w,
        height: h,
        shots,
        reference: 0,
        rows: None,
    });
    Ok(rows)
}

#[cfg(test)]
mod tests {
    #[test]
    fn white_furnace_matches_its_closed_form_and_the_smooth_limit() {
        // α = 1 at normal incidence: E = 1 − ln 2 (tests/ggx.rs derives it); a smooth
        // surface returns nearly all.
        let rough = super::white_furnace(1.0, 0.0);
        // The bound is the 512 × 512 midpoint rule's error, O(1/n²): measured 2.4e-6 here
        // (the integrand is smooth in x after the change of variable); 1e-5 leaves room for
        // the constant and would catch a quadrature 4× coarser or a wrong Jacobian.
        let err = (rough - (1.0 - std::f64::consts::LN_2)).abs();
        println!("white furnace α = 1, θ_v = 0: {rough}, error {err:.2e} against 1 − ln 2");
        assert!(err < 1e-5, "{rough}");
        let smooth = super::white_furnace(0.04, 0.0);
        assert!(smooth > 0.99 && smooth <= 1.0 + 1e-6, "{smooth}");
        let grazing = super::white_furnace(0.04, 75f64.to_radians());
        assert!(grazing < smooth && grazing > 0.9, "{grazing}");
    }
}
