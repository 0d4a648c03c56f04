//! The report's scaling section (issue 17, item 5): the wave synthesis timed against N (its
//! work grows as N² log₂ N) and each system's frame against its pixels, on the CPU oracle and
//! on the GPU (when an adapter is here), each series with the exponent of its least-squares
//! power law. An exponent near 1 is the expected scaling; below 1, fixed costs (start-up,
//! the wave maps, submission) still weigh at the smallest sizes; above 1, something grows
//! faster than the work (cache misses, memory). Drawn as `scaling.svg`, tabled in report.md.
//!
//! The cases are `ocean bench`'s ([`crate::bench`]), at sizes small enough for the report.

use std::fmt::Write as _;

use ocean_core::plan::SYSTEMS;

use crate::bench::{Case, Fit, fit_size};

use super::Ctx;

/// Frame sizes of the quick report and of the full one.
const QUICK_SIZES: [[u32; 2]; 3] = [[80, 45], [160, 90], [320, 180]];
const FULL_SIZES: [[u32; 2]; 3] = [[320, 180], [640, 360], [1280, 720]];
/// Synthesis sizes.
const QUICK_N: [u32; 3] = [32, 64, 128];
const FULL_N: [u32; 4] = [64, 128, 256, 512];

/// The measured cases and their fits.
pub(super) struct Scaling {
    cases: Vec<Case>,
    fits: Vec<Fit>,
    /// The GPU adapter, or why there was none.
    gpu: Result<String, String>,
}

/// Progress steps [`measure`] takes.
pub(super) fn steps(ctx: &Ctx) -> u64 {
    let (sizes, ns) = if ctx.quick { (3, 3) } else { (3, 4) };
    (SYSTEMS.len() * sizes + ns) as u64
}

/// Times every system's frame at three sizes and the synthesis at three or four N, on both
/// back ends where a GPU adapter is found (else on the CPU alone, saying why).
pub(super) fn measure(ctx: &Ctx) -> anyhow::Result<Scaling> {
    let sizes: &[[u32; 2]] = if ctx.quick { &QUICK_SIZES } else { &FULL_SIZES };
    let ns: &[u32] = if ctx.quick { &QUICK_N } else { &FULL_N };
    let runs = if ctx.quick { 1 } else { 5 };
    let mut shared = ctx.gpu();
    let renderer = &mut *shared;
    if let Err(e) = &renderer {
        ctx.bar.suspend(|| eprintln!("report: the scaling plot has no GPU series: {e}"));
    }
    let mut cases = Vec::new();
    for info in SYSTEMS {
        for &size in sizes {
            cases.push(crate::bench::cpu_frame(info.system, size, runs)?);
            if let Ok(r) = renderer.as_mut() {
                cases.push(crate::bench::gpu_frame(r, info.system, size, runs)?);
            }
            ctx.step(&format!("scaling {} {}×{}", info.name, size[0], size[1]));
        }
    }
    let bandwidth = match renderer.as_ref() {
        Ok(r) => Some(crate::bench::copy_bandwidth(r.gpu())?),
        Err(_) => None,
    };
    for &n in ns {
        let gpu = renderer.as_ref().ok().map(|r| r.gpu()).zip(bandwidth);
        // The frame's own GPU kernel only: the other kernel is `ocean bench`'s comparison.
        let mut w = crate::bench::waves(gpu, n, runs)?;
        w.retain(|c| c.name != "gpu_fft_stages" && c.name != "gpu_fft_shared");
        cases.extend(w);
        ctx.step(&format!("scaling waves N = {n}"));
    }
    Ok(Scaling {
        fits: crate::bench::fits(&cases),
        cases,
        gpu: renderer.as_ref().map(|r| r.adapter().to_string()).map_err(Clone::clone),
    })
}

/// The report.md section.
pub(super) fn markdown(s: &Scaling) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "## Scaling\n");
    let _ = writeln!(
        out,
        "Time against the size of the work (`scaling.svg`): the wave synthesis against N² log₂ N, \
         each system's frame (built-in scene, 8-bit picture read back) against its pixels. \
         The exponent is the slope of the least-squares line through log time against log \
         size: 1 is the expected scaling, below 1 fixed costs still weigh at the small sizes. \
         GPU: {}.\n",
        match &s.gpu {
            Ok(a) => a.clone(),
            Err(e) => format!("none ({e})"),
        }
    );
    let _ = writeln!(out, "| what | back end | against | exponent | times (size: ms) |");
    let _ = writeln!(out, "|---|---|---|---|---|");
    for f in &s.fits {
        let times: Vec<String> = s
            .cases
            .iter()
            .filter(|c| c.name == f.name && c.backend == f.backend)
            .map(|c| match (c.size, c.n) {
                (Some([w, h]), _) => format!("{w}×{h}: {:.2}", c.frame_ms),
                (None, Some(n)) => format!("N = {n}: {:.2}", c.frame_ms),
                _ => String::new(),
            })
            .collect();
        let _ = writeln!(
            out,
            "| {} | {} | {} | {:.2} | {} |",
            f.name,
            f.backend,
            f.against,
            f.exponent,
            times.join(", ")
        );
    }
    out.push('\n');
    out
}

/// `scaling.svg`: the synthesis panel (time against N) and the frame panel (time against
/// pixels), each series' points and its fitted line, labelled with its exponent.
pub(super) fn plot(s: &Scaling, path: &std::path::Path) -> anyhow::Result<()> {
    use plotters::prelude::*;
    let e = |e: &dyn std::fmt::Display| anyhow::anyhow!("scaling plot: {e}");
    let root = SVGBackend::new(path, (1500, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let (left, right) = root.split_horizontally(600);
    let palette = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
        RGBColor(255, 127, 14),
        RGBColor(23, 190, 207),
        RGBColor(140, 86, 75),
        RGBColor(127, 127, 127),
    ];
    for (panel, kind) in [(&left, "waves"), (&right, "frame")] {
        let fits: Vec<&Fit> = s
            .fits
            .iter()
            .filter(|f| s.cases.iter().any(|c| c.kind == kind && c.name == f.name))
            .collect();
        let cases: Vec<&Case> = s.cases.iter().filter(|c| c.kind == kind).collect();
        // x: N for the synthesis (the fit is against N² log₂ N), pixels for the frames.
        let x_of = |c: &Case| match (c.size, c.n) {
            (Some([w, h]), _) => f64::from(w) * f64::from(h),
            (None, Some(n)) => f64::from(n),
            _ => f64::NAN,
        };
        let xs = cases.iter().map(|c| x_of(c));
        let ys = cases.iter().map(|c| c.frame_ms);
        let (x0, x1) = xs.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
        let (y0, y1) = ys.fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(y), b.max(y)));
        if cases.is_empty() || !(x0 > 0.0 && y0 > 0.0) {
            continue;
        }
        let (caption, x_desc) = if kind == "waves" {
            ("wave synthesis: time against N (work ∝ N² log₂ N)", "N (grid side)")
        } else {
            ("frame: time against pixels (work ∝ pixels)", "pixels")
        };
        let mut chart = ChartBuilder::on(panel)
            .caption(caption, ("sans-serif", 18))
            .margin(14)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d((x0 / 1.3..x1 * 1.3).log_scale(), (y0 / 2.0..y1 * 2.0).log_scale())
            .map_err(|x| e(&x))?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .x_labels(12)
            .y_labels(12)
            .y_desc("time (ms, median)")
            .x_label_formatter(&|v| {
                if *v >= 1e4 { format!("{:.0}k", v / 1e3) } else { format!("{v:.0}") }
            })
            .y_label_formatter(&|v| format!("{v}"))
            .draw()
            .map_err(|x| e(&x))?;
        for (i, f) in fits.iter().enumerate() {
            let color = palette[i % palette.len()];
            let mut pts: Vec<(f64, f64)> = cases
                .iter()
                .filter(|c| c.name == f.name && c.backend == f.backend)
                .map(|c| (x_of(c), c.frame_ms))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let fitted: Vec<(f64, f64)> = cases
                .iter()
                .filter(|c| c.name == f.name && c.backend == f.backend)
                .filter_map(|c| Some((x_of(c), f.scale_ms * fit_size(c)?.powf(f.exponent))))
                .collect();
            let marker_gpu = f.backend == "gpu";
            chart
                .draw_series(pts.iter().map(|&p| {
                    if marker_gpu {
                        TriangleMarker::new(p, 6, color.filled()).into_dyn()
                    } else {
                        Circle::new(p, 4, color.filled()).into_dyn()
                    }
                }))
                .map_err(|x| e(&x))?;
            let mut line = fitted;
            line.sort_by(|a, b| a.0.total_cmp(&b.0));
            let style = if marker_gpu { color.stroke_width(1) } else { color.stroke_width(2) };
            chart
                .draw_series(LineSeries::new(line, style))
                .map_err(|x| e(&x))?
                .label(format!(
                    "{} {}: exponent {:.2} ({})",
                    f.name, f.backend, f.exponent, f.against
                ))
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], style));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 12))
            .draw()
            .map_err(|x| e(&x))?;
    }
    root.present().map_err(|x| e(&x))?;
    Ok(())
}
