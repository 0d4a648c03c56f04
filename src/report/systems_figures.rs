//! The systems section's figures: the contact sheet (every system on every viewpoint, the
//! pictures embedded, rendered to `systems.png`) and the chart of frame time by pass and
//! far-band error (inline in the page).

use super::svg::{Anchor, Svg, png_rgb};
use ocean_core::plan::System;

use super::systems::{Systems, VIEWPOINTS, systems};

/// The contact sheet: a row per system, a column per viewpoint, labelled (SVG with the
/// pictures embedded; the PNG is rendered from it).
pub(super) fn sheet(s: &Systems) -> anyhow::Result<String> {
    let (w, h) = (f64::from(s.size.0).max(240.0), f64::from(s.size.1).max(135.0));
    let (left, top, gap) = (110.0, 34.0, 6.0);
    let names: Vec<System> = systems().collect();
    let mut svg = Svg::new(
        left + VIEWPOINTS.len() as f64 * (w + gap),
        top + names.len() as f64 * (h + gap) + 4.0,
    );
    for (v, vp) in VIEWPOINTS.iter().enumerate() {
        svg.text_styled(
            (left + v as f64 * (w + gap) + w / 2.0, 22.0),
            14.0,
            Anchor::Middle,
            vp.name,
            r##"fill="#111111" font-weight="bold""##,
        );
    }
    for (row, system) in names.iter().enumerate() {
        let y = top + row as f64 * (h + gap);
        svg.text_styled(
            (left - 10.0, y + h / 2.0 + 5.0),
            15.0,
            Anchor::End,
            system.name(),
            r##"fill="#111111" font-weight="bold""##,
        );
        for shot in s.shots.iter().filter(|t| t.system == *system) {
            let x = left + shot.viewpoint as f64 * (w + gap);
            svg.png((x, y), (w, h), &png_rgb(&shot.rgb, s.size.0, s.size.1)?);
            svg.text_styled(
                (x + 4.0, y + h - 5.0),
                10.0,
                Anchor::Start,
                &format!(
                    "CPU {:.0} ms{}",
                    shot.cpu.frame_ms,
                    shot.gpu
                        .as_ref()
                        .map_or(String::new(), |g| format!(" · GPU {:.1} ms", g.frame_ms))
                ),
                r##"fill="#ffffff" stroke="#000000" stroke-width="2.5" paint-order="stroke""##,
            );
        }
    }
    Ok(svg.finish())
}

/// The systems at the first viewpoint as a chart: per system, its CPU and GPU frame as bars
/// stacked by pass (the same colour for a pass everywhere), and beside them its far-band
/// errors against its own 64-sample frame — how the systems compare, without a table.
pub(super) fn chart(s: &Systems) -> String {
    // More colours than the frame graph has passes (14 now), so none repeats.
    const PALETTE: [&str; 16] = [
        "#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7",
        "#9c755f", "#bab0ac", "#1b9e77", "#7570b3", "#d95f02", "#66a61e", "#e7298a", "#17becf",
    ];
    let (firsts, passes) = s.first_viewpoint();
    let colour =
        |p: &str| PALETTE[passes.iter().position(|q| *q == p).unwrap_or(0) % PALETTE.len()];
    let (left, bar_w, gap, right_w) = (150.0, 560.0, 40.0, 300.0);
    let row_h = 52.0;
    let top = 58.0;
    let height = top + row_h * firsts.len() as f64 + 100.0;
    let mut svg = Svg::new(left + bar_w + gap + right_w + 20.0, height);
    let bold = r##"fill="#111111" font-weight="bold""##;
    svg.text_styled(
        (left, 20.0),
        14.0,
        Anchor::Start,
        &format!("frame time by pass, {} viewpoint (ms)", VIEWPOINTS[0].name),
        bold,
    );
    let right = left + bar_w + gap;
    svg.text_styled((right, 20.0), 14.0, Anchor::Start, "far-band error (4 viewpoints)", bold);
    let max_ms = firsts
        .iter()
        .flat_map(|t| std::iter::once(t.cpu.frame_ms).chain(t.gpu.iter().map(|g| g.frame_ms)))
        .filter(|v| v.is_finite())
        .fold(1.0f64, f64::max);
    // Ticks at a round step giving four to eight of them.
    let step = [1.0, 2.0, 5.0]
        .iter()
        .flat_map(|m| (-1..5).map(move |k| m * 10f64.powi(k)))
        .filter(|st| max_ms / st <= 8.0)
        .fold(f64::INFINITY, f64::min);
    let x = |ms: f64| left + ms / max_ms * bar_w;
    let mut t = 0.0;
    while t <= max_ms {
        svg.line(
            (x(t), top - 6.0),
            (x(t), top + row_h * firsts.len() as f64),
            r##"stroke="#e4e4e4""##,
        );
        svg.text((x(t), top - 10.0), 10.0, Anchor::Middle, &super::plot::tick_text(t));
        t += step;
    }
    let max_err = s
        .shots
        .iter()
        .filter_map(|t| t.far_error)
        .flat_map(|e| e.into_iter())
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    for (row, shot) in firsts.iter().enumerate() {
        let y = top + row as f64 * row_h;
        svg.text_styled((left - 36.0, y + 24.0), 14.0, Anchor::End, shot.system.name(), bold);
        for (k, (label, case)) in
            [("CPU", Some(&shot.cpu)), ("GPU", shot.gpu.as_ref())].into_iter().enumerate()
        {
            let by = y + 4.0 + k as f64 * 20.0;
            svg.text((left - 4.0, by + 12.0), 10.0, Anchor::End, label);
            let Some(case) = case else {
                svg.text((left + 4.0, by + 12.0), 10.0, Anchor::Start, "no GPU time");
                continue;
            };
            let mut at = 0.0;
            for (p, ms) in &case.passes {
                svg.rect(
                    (x(at), by),
                    ((x(at + ms) - x(at)).max(0.0), 16.0),
                    &format!(r#"fill="{}""#, colour(p)),
                );
                at += ms;
            }
            // What the frame took beyond its timed passes (submission, read-back, set-up).
            let rest = (case.frame_ms - at).max(0.0);
            svg.rect((x(at), by), (x(at + rest) - x(at), 16.0), r##"fill="#dddddd""##);
            svg.text(
                (x(case.frame_ms) + 4.0, by + 12.0),
                10.0,
                Anchor::Start,
                &format!("{:.0}", case.frame_ms),
            );
        }
        // The far-band errors: one dot per viewpoint, horizon and 2°–8°.
        let ex = |e: f64| right + 40.0 + e / max_err.max(1e-9) * (right_w - 60.0);
        svg.line(
            (right + 40.0, y + 40.0),
            (right + right_w - 20.0, y + 40.0),
            r##"stroke="#cccccc""##,
        );
        let mine: Vec<[f64; 2]> = s
            .shots
            .iter()
            .filter(|t| t.system == shot.system)
            .filter_map(|t| t.far_error)
            .collect();
        if mine.is_empty() {
            svg.text((right + 40.0, y + 24.0), 10.0, Anchor::Start, "not measured (--quick)");
        }
        for e in &mine {
            for (b, (yy, fill)) in
                [(y + 14.0, "#c0392b"), (y + 30.0, "#1f5fa8")].into_iter().enumerate()
            {
                if e[b].is_finite() {
                    svg.circle(
                        (ex(e[b]), yy),
                        4.0,
                        &format!(r#"fill="{fill}" fill-opacity="0.8""#),
                    );
                }
            }
        }
        svg.text((right + 34.0, y + 18.0), 9.5, Anchor::End, "horizon");
        svg.text((right + 34.0, y + 34.0), 9.5, Anchor::End, "2°–8°");
    }
    if max_err > 0.0 {
        let yb = top + row_h * firsts.len() as f64 + 4.0;
        for f in [0.0, 0.5, 1.0] {
            let v = f * max_err;
            let px = right + 40.0 + f * (right_w - 60.0);
            svg.text((px, yb + 10.0), 10.0, Anchor::Middle, &format!("{v:.2}"));
        }
        svg.text(
            (right + 40.0 + (right_w - 60.0) / 2.0, yb + 24.0),
            10.0,
            Anchor::Middle,
            "mean |Δ log(1 + L)| vs its 64-sample frame",
        );
    }
    // The legend: every pass, then the untimed rest.
    let (mut lx, mut ly) = (left, top + row_h * firsts.len() as f64 + 42.0);
    for p in passes.iter().copied().chain(std::iter::once("other (submit, read-back)")) {
        let w = 18.0 + super::svg::text_width(p, 10.0) + 12.0;
        if lx + w > left + bar_w {
            (lx, ly) = (left, ly + 14.0);
        }
        let fill = if p.starts_with("other") { "#dddddd" } else { colour(p) };
        svg.rect((lx, ly - 9.0), (12.0, 10.0), &format!(r#"fill="{fill}""#));
        svg.text((lx + 16.0, ly), 10.0, Anchor::Start, p);
        lx += w;
    }
    svg.finish()
}

#[cfg(test)]
mod tests {
    use super::super::systems::Shot;
    use super::*;
    use crate::bench::Case;

    fn case(backend: &'static str, passes: &[(&str, f64)]) -> Case {
        Case {
            kind: "frame",
            name: "x".into(),
            backend,
            size: Some([16, 9]),
            n: None,
            frame_ms: passes.iter().map(|p| p.1).sum::<f64>() + 1.0,
            encode_ms: None,
            encode_cpu_ms: None,
            encode_split_ms: None,
            steady_ms: None,
            passes: passes.iter().map(|(p, v)| ((*p).to_string(), *v)).collect(),
            peak_rss_mib: None,
            bandwidth_bound_ms: None,
        }
    }

    #[test]
    fn the_chart_stacks_every_pass_and_shows_the_far_errors() {
        let shot = |system, far_error| Shot {
            system,
            viewpoint: 0,
            rgb: vec![0; 16 * 9 * 3],
            cpu: case("cpu", &[("waves", 10.0), ("water", 30.0)]),
            gpu: Some(case("gpu", &[("water", 5.0), ("bloom", 2.0)])),
            vertices: (100, 0.5),
            far_error,
            left_out: Vec::new(),
        };
        let mut s = Systems {
            size: (16, 9),
            shots: vec![
                shot(System::Hu, Some([0.03, 0.05])),
                shot(System::Welch, Some([0.1, 0.06])),
            ],
            gpu: Ok("test".into()),
        };
        let svg = chart(&s);
        for p in ["waves", "water", "bloom", "other (submit, read-back)", "hu", "welch"] {
            assert!(svg.contains(&format!(">{p}<")), "{p} missing");
        }
        assert!(svg.contains("vs its 64-sample frame") && !svg.contains("not measured"));
        // Control: without far errors (--quick) the panel says so.
        for t in &mut s.shots {
            t.far_error = None;
        }
        assert!(chart(&s).contains("not measured (--quick)"));
    }
}
