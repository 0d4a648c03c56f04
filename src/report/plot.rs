//! Error against run time, drawn so that the plot explains itself (issue 18): each point
//! labelled with its setting, each back end's Pareto front drawn as a line, dominated settings
//! greyed, the reference (error 0) drawn in a strip of its own under the log axis instead of
//! vanishing from it, one metric per panel, units on both axes, the legend above the data.
//!
//! `overview` draws one panel per knob (its headline metric, [`headline_metric`]); `knob`
//! draws one panel per metric of one knob for its section of the HTML page.

use super::Row;
use super::svg::Svg;

mod panel;

use panel::draw_panel;

/// Colour of each back end's points and front.
fn colour(backend: &str) -> &'static str {
    if backend == "gpu" { "#c0392b" } else { "#1f5fa8" }
}

/// Colour of a dominated setting.
const GREY: &str = "#a8a8a8";

/// Colour of the page's rule of "good enough" and of the suggested settings.
const GOOD: &str = "#1e8a3c";

/// Style of the strip that holds the settings of error 0 (the reference).
const ZERO_STRIP: &str = r##"fill="#e3f1e3" stroke="#444444" stroke-width="1""##;

/// What a metric measures, with its unit, for the y-axis.
pub(super) fn metric_label(metric: &str) -> String {
    let band = |m: &str| m.rsplit('_').next().unwrap_or("").to_string();
    match metric {
        "flip_mean" => "mean FLIP error (0–1)".into(),
        "rmse_linear" => "RMSE of linear RGB".into(),
        "rms_height_m" => "RMS height error (m)".into(),
        "max_abs_height_m" => "max |Δ height| (m)".into(),
        "log_l_change" => "mean |Δ log(1 + L)| (change)".into(),
        "ldr_mean_change" => "mean |Δ 8-bit| / 255 (change)".into(),
        "max_abs_theta_le_76deg" => "max |ΔF|, θ ≤ 76°".into(),
        "max_abs_hemisphere" => "max |ΔF|, hemisphere".into(),
        "rms_hemisphere" => "RMS ΔF, hemisphere".into(),
        "max_abs_frame_pixels" => "max |ΔF|, frame pixels".into(),
        "rms_frame_pixels" => "RMS ΔF, frame pixels".into(),
        m if m.starts_with("white_furnace_loss") => {
            format!("white-furnace loss at {}", m.rsplit('_').next().unwrap_or(""))
        }
        m if m.starts_with("log_l_") => format!("mean |Δ log(1 + L)|, {} band", band(m)),
        m if m.starts_with("height_m_") => format!("mean height error (m), {} band", band(m)),
        m if m.starts_with("position_m_") => {
            format!("mean position error (m), {} band", band(m))
        }
        m => m.to_string(),
    }
}

/// What the x-axis of a knob's panels measures.
pub(super) fn time_label(knob: &str) -> &'static str {
    match knob {
        "fresnel" => "time (ms per 1280×720 frame of lookups)",
        "wave_resolution" | "precision" => "synthesis time (ms)",
        _ => "frame time (ms)",
    }
}

/// The metric a knob's overview panel shows: FLIP where it has it (what a viewer sees), the
/// horizon band for the far field (what it is for), else its first.
pub(super) fn headline_metric(rows: &[&Row]) -> Option<&'static str> {
    ["flip_mean", "log_l_horizon", "rms_frame_pixels", "position_m_middle", "rms_height_m"]
        .into_iter()
        .find(|m| rows.iter().any(|r| r.error_metric == *m))
        .or_else(|| rows.first().map(|r| r.error_metric))
}

/// The error under which a setting of a knob's headline metric counts as good enough for the
/// page's suggestion, and why; `None` for metrics that measure a change of model, where no
/// setting is more correct than another.
pub(super) fn good_enough(metric: &str) -> Option<(f64, &'static str)> {
    match metric {
        "flip_mean" => Some((0.01, "≤ 0.01: seen only by flipping between the two")),
        "rms_frame_pixels" => Some((1e-3, "≤ 0.001: under one 8-bit step of a reflection")),
        "rms_height_m" => Some((0.01, "≤ 1 cm")),
        "log_l_horizon" => Some((0.02, "≤ 0.02: about 2 % in luminance")),
        "position_m_middle" => Some((0.05, "≤ 5 cm")),
        _ => None,
    }
}

/// The page's suggestion for one (knob, back end): the fastest setting whose headline error
/// is within [`good_enough`], with its error and time.
pub(super) fn suggestion<'a>(rows: &[&'a Row]) -> Option<&'a Row> {
    let (bound, _) = good_enough(rows.first()?.error_metric)?;
    let mut ok: Vec<&Row> =
        rows.iter().copied().filter(|r| r.error <= bound && r.time_ms.is_finite()).collect();
    ok.sort_by(|a, b| a.time_ms.total_cmp(&b.time_ms));
    ok.first().copied()
}

/// One panel: rows of one metric (any back ends) of one knob.
pub(super) struct Panel<'a> {
    /// Title above the panel.
    pub title: String,
    /// x-axis title.
    pub x_label: &'static str,
    /// y-axis title.
    pub y_label: String,
    /// The points.
    pub rows: Vec<&'a Row>,
}

/// A figure of `panels` in `columns` columns, each `size` px, as SVG text.
pub(super) fn figure(panels: &[Panel<'_>], columns: usize, size: (f64, f64)) -> String {
    let columns = columns.clamp(1, panels.len().max(1));
    let rows = panels.len().div_ceil(columns).max(1);
    let mut svg = Svg::new(size.0 * columns as f64, size.1 * rows as f64);
    for (i, p) in panels.iter().enumerate() {
        let origin = ((i % columns) as f64 * size.0, (i / columns) as f64 * size.1);
        draw_panel(&mut svg, origin, size, p);
    }
    svg.finish()
}

/// The overview: one panel per knob, its headline metric.
pub(super) fn overview(rows: &[Row], knobs: &[&'static str]) -> String {
    let panels: Vec<Panel<'_>> = knobs
        .iter()
        .filter_map(|knob| {
            let of: Vec<&Row> = rows.iter().filter(|r| r.knob == *knob).collect();
            let metric = headline_metric(&of)?;
            Some(Panel {
                title: (*knob).to_string(),
                x_label: time_label(knob),
                y_label: metric_label(metric),
                rows: of.into_iter().filter(|r| r.error_metric == metric).collect(),
            })
        })
        .collect();
    figure(&panels, 3, (520.0, 400.0))
}

/// One knob's figure: a panel per metric.
pub(super) fn knob(rows: &[Row], knob: &'static str) -> String {
    let mut metrics: Vec<&'static str> = Vec::new();
    for r in rows.iter().filter(|r| r.knob == knob) {
        if !metrics.contains(&r.error_metric) {
            metrics.push(r.error_metric);
        }
    }
    let panels: Vec<Panel<'_>> = metrics
        .iter()
        .map(|m| Panel {
            title: format!("{knob}: {m}"),
            x_label: time_label(knob),
            y_label: metric_label(m),
            rows: rows.iter().filter(|r| r.knob == knob && r.error_metric == *m).collect(),
        })
        .collect();
    figure(&panels, 3, (460.0, 360.0))
}

/// A log axis from 10^lo to 10^hi mapped onto [a, b] px.
#[derive(Clone, Copy)]
struct LogAxis {
    lo: f64,
    hi: f64,
    a: f64,
    b: f64,
}

impl LogAxis {
    /// An axis covering `values` (positive) with margins, at least one decade wide.
    fn covering(values: impl Iterator<Item = f64>, a: f64, b: f64) -> Option<Self> {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.filter(|v| *v > 0.0 && v.is_finite()) {
            (lo, hi) = (lo.min(v.log10()), hi.max(v.log10()));
        }
        if !lo.is_finite() {
            return None;
        }
        let pad = ((1.0 - (hi - lo)) / 2.0).max(0.0) + 0.12 * (hi - lo).max(0.5);
        Some(Self { lo: lo - pad, hi: hi + pad, a, b })
    }

    fn at(&self, v: f64) -> f64 {
        self.a + (v.log10() - self.lo) / (self.hi - self.lo) * (self.b - self.a)
    }

    /// Tick values: every decade, and 2 and 5 times it where the axis spans under 3 decades.
    fn ticks(&self) -> Vec<(f64, bool)> {
        let mut t = Vec::new();
        let fine = self.hi - self.lo < 3.0;
        for k in self.lo.floor() as i32..=self.hi.ceil() as i32 {
            for (m, major) in [(1.0, true), (2.0, false), (5.0, false)] {
                let v = m * 10f64.powi(k);
                let l = v.log10();
                if l >= self.lo && l <= self.hi && (major || fine) {
                    t.push((v, major));
                }
            }
        }
        t
    }
}

/// A tick's text: plain decimals from 0.001 to 10⁴, else scientific.
pub(super) fn tick_text(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if (1e-3..1e4).contains(&v) {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.0e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::test_row as row;

    #[test]
    fn the_reference_is_drawn_and_every_point_labelled() {
        let rows =
            [row("fine", 0.0, 10.0), row("coarse", 0.1, 2.0), row("slow and bad", 0.2, 20.0)];
        let svg = figure(
            &[Panel {
                title: "lod".into(),
                x_label: "frame time (ms)",
                y_label: "FLIP".into(),
                rows: rows.iter().collect(),
            }],
            1,
            (400.0, 300.0),
        );
        for label in ["fine", "coarse", "slow and bad", "error 0 (reference)", "Pareto front"] {
            assert!(svg.contains(&format!(">{label}<")), "{label} missing");
        }
        // The dominated setting is grey, the front is one line through two points.
        assert!(svg.contains(&format!(r#"fill="{GREY}" stroke"#)));
        // FLIP has a rule: nothing but the reference meets it here, so the ring is on it (the
        // legend's ring is the other).
        assert_eq!(svg.matches(&format!(r#"stroke="{GOOD}" stroke-width="2""#)).count(), 2);
        assert_eq!(svg.matches("<polyline").count(), 1);
        // Control: without the reference there is no zero strip.
        let svg = figure(
            &[Panel {
                title: "lod".into(),
                x_label: "frame time (ms)",
                y_label: "FLIP".into(),
                rows: rows[1..].iter().collect(),
            }],
            1,
            (400.0, 300.0),
        );
        assert!(!svg.contains("error 0 (reference)"));
        // A setting within the rule: the dashed line at the bound, and the ring moves to it.
        let ok = [row("ok", 0.005, 5.0), row("coarse", 0.1, 2.0), row("fine", 0.0, 10.0)];
        let svg = figure(
            &[Panel {
                title: "lod".into(),
                x_label: "frame time (ms)",
                y_label: "FLIP".into(),
                rows: ok.iter().collect(),
            }],
            1,
            (400.0, 300.0),
        );
        assert!(svg.contains("good enough: ≤ 0.01"), "{svg}");
        assert_eq!(suggestion(&ok.iter().collect::<Vec<_>>()).unwrap().setting, "ok");
    }

    #[test]
    fn log_ticks_cover_at_least_a_decade() {
        let a = LogAxis::covering([3.0, 4.0].into_iter(), 0.0, 100.0).unwrap();
        assert!(a.hi - a.lo >= 1.0);
        assert!(a.ticks().iter().any(|t| t.1) || a.ticks().len() >= 2, "{:?}", a.ticks());
        assert_eq!(tick_text(0.01), "0.01");
        assert_eq!(tick_text(20.0), "20");
        assert_eq!(tick_text(1e-5), "1e-5");
        assert_eq!(tick_text(0.0), "0");
    }
}
