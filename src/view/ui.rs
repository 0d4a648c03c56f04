//! The viewer's egui panel (parameters, presets, camera jumps) and overlay (frame time, GPU
//! time per pass, the plan, the adapter), and the frame statistics behind both.

use std::collections::VecDeque;
use std::time::Duration;

use egui::{Color32, RichText};
use ocean_core::plan::{FramePlan, Pass};
use ocean_core::spectrum::SpectrumKind;

use super::controller::CameraController;
use super::params::{Preset, ViewParams, range};

/// Frames the overlay averages over.
const RECENT: usize = 60;
/// Frames left out of the exit summary: the first frames compile pipelines and draw modes.
const WARM_UP: u64 = 3;

/// What the panel asks the viewer to do.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Action {
    /// Back to the scene's camera.
    JumpHome,
    /// Level the view.
    Horizon,
}

/// Read-only state the overlay shows.
pub(super) struct Overlay<'a> {
    pub stats: &'a Stats,
    pub plan: Option<&'a FramePlan>,
    pub adapter: &'a str,
    pub controller: &'a CameraController,
    pub time_s: f64,
    pub size: (u32, u32),
    pub error: Option<&'a str>,
    pub wave_source: Option<&'static str>,
}

/// Frame times: the last [`RECENT`] for the overlay, all after [`WARM_UP`] for the summary.
#[derive(Default)]
pub(super) struct Stats {
    recent_interval_ms: VecDeque<f64>,
    recent_cpu_ms: VecDeque<f64>,
    last_passes: Vec<(Pass, f64)>,
    last_waves_cpu_ms: Option<f64>,
    interval_ms: Vec<f64>,
    cpu_ms: Vec<f64>,
    pass_ms: Vec<(Pass, Vec<f64>)>,
}

impl Stats {
    /// One presented frame: the wall time since the previous one (`dt`, s) and the time the
    /// CPU spent on it (scene, plan, mesh, encoding, submission; s).
    pub fn record(&mut self, dt: f64, cpu_s: f64, waves_cpu: Option<Duration>, index: u64) {
        if index > 0 {
            push(&mut self.recent_interval_ms, dt * 1e3);
        }
        push(&mut self.recent_cpu_ms, cpu_s * 1e3);
        self.last_waves_cpu_ms = waves_cpu.map(|d| d.as_secs_f64() * 1e3);
        if index >= WARM_UP {
            self.interval_ms.push(dt * 1e3);
            self.cpu_ms.push(cpu_s * 1e3);
        }
    }

    /// GPU time per pass of frame `index`, which arrives a frame or two after it.
    pub fn record_passes(&mut self, passes: &[(Pass, Duration)], index: u64) {
        self.last_passes = passes.iter().map(|(p, d)| (*p, d.as_secs_f64() * 1e3)).collect();
        if index < WARM_UP {
            return;
        }
        for (p, ms) in &self.last_passes {
            match self.pass_ms.iter_mut().find(|(q, _)| q == p) {
                Some((_, v)) => v.push(*ms),
                None => self.pass_ms.push((*p, vec![*ms])),
            }
        }
    }

    /// Median of the recent frame intervals, ms.
    pub fn frame_ms(&self) -> Option<f64> {
        median(self.recent_interval_ms.iter().copied().collect())
    }

    /// The exit summary: median (10th–90th percentile) frame interval, render time and GPU
    /// time per pass after the warm-up frames.
    pub fn summary(&self, frames: u64, adapter: &str) -> String {
        let stat = |v: &[f64]| -> String {
            let mut s = v.to_vec();
            s.sort_by(f64::total_cmp);
            match s.len() {
                0 => "n/a".into(),
                n => format!(
                    "{:.1} ms ({:.1}–{:.1})",
                    s[n / 2],
                    s[(n - 1) / 10],
                    s[(n - 1) - (n - 1) / 10]
                ),
            }
        };
        let mut out = format!(
            "view: {frames} frames on {adapter}; after {WARM_UP} warm-up frames, median (p10–p90): \
             frame interval {}, CPU per frame {}",
            stat(&self.interval_ms),
            stat(&self.cpu_ms)
        );
        if !self.pass_ms.is_empty() {
            let passes: Vec<String> = self
                .pass_ms
                .iter()
                .map(|(p, v)| format!("{} {:.2}", p.name(), median(v.clone()).unwrap_or(0.0)))
                .collect();
            out.push_str(&format!("; GPU ms per pass (median): {}", passes.join(", ")));
        }
        out
    }
}

fn push(q: &mut VecDeque<f64>, v: f64) {
    if q.len() == RECENT {
        q.pop_front();
    }
    q.push_back(v);
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    Some(v[v.len() / 2])
}

/// Draws the panel and the overlay; changes go into `params`, jumps into `actions`.
pub(super) fn draw(
    ctx: &egui::Context,
    params: &mut ViewParams,
    overlay: &Overlay<'_>,
    actions: &mut Vec<Action>,
) {
    egui::Window::new("ocean")
        .default_pos([8.0, 8.0])
        .default_width(280.0)
        .resizable(false)
        .show(ctx, |ui| panel(ui, params, overlay, actions));
    egui::Window::new("frame")
        .anchor(egui::Align2::RIGHT_TOP, [-8.0, 8.0])
        .resizable(false)
        .show(ctx, |ui| stats(ui, overlay));
}

fn panel(ui: &mut egui::Ui, p: &mut ViewParams, overlay: &Overlay<'_>, actions: &mut Vec<Action>) {
    ui.horizontal_wrapped(|ui| {
        for preset in Preset::ALL {
            if ui.button(preset.label()).clicked() {
                *p = p.with_preset(preset);
            }
        }
    });
    egui::CollapsingHeader::new("Sea").default_open(true).show(ui, |ui| {
        egui::ComboBox::from_label("spectrum").selected_text(spectrum_label(p.spectrum)).show_ui(
            ui,
            |ui| {
                for k in [
                    SpectrumKind::Phillips,
                    SpectrumKind::PiersonMoskowitz,
                    SpectrumKind::Jonswap,
                    SpectrumKind::Tma,
                ] {
                    ui.selectable_value(&mut p.spectrum, k, spectrum_label(k));
                }
            },
        );
        slider(ui, &mut p.wind_speed, range::WIND_SPEED, "wind U₁₀, m/s", false);
        slider(ui, &mut p.wind_direction_deg, (0.0, 360.0), "wind towards, °", false);
        slider(ui, &mut p.fetch_km, range::FETCH_KM, "fetch, km", true);
        ui.checkbox(&mut p.deep, "deep water");
        ui.add_enabled_ui(!p.deep, |ui| {
            slider(ui, &mut p.depth_m, range::DEPTH_M, "depth, m", true);
        });
        slider(ui, &mut p.choppiness, range::CHOPPINESS, "choppiness λ", false);
        slider(
            ui,
            &mut p.gerstner_amplitude_m,
            range::GERSTNER_AMPLITUDE_M,
            "Gerstner A, m",
            false,
        );
        slider(
            ui,
            &mut p.gerstner_wavelength_m,
            range::GERSTNER_WAVELENGTH_M,
            "Gerstner λ, m",
            true,
        );
        slider(ui, &mut p.patch_size_m, range::PATCH_SIZE_M, "patch size, m", true);
    });
    // Seed 004's demo: wave height and length, the water's level, and (the time scale) the
    // waves' speed.
    egui::CollapsingHeader::new("Coast").default_open(false).show(ui, |ui| {
        slider(ui, &mut p.coastal_amplitude_m, range::COASTAL_AMPLITUDE_M, "coastal A, m", false);
        slider(ui, &mut p.coastal_wavelength_m, range::COASTAL_WAVELENGTH_M, "coastal λ, m", true);
        slider(ui, &mut p.water_level_m, range::WATER_LEVEL_M, "water level, m", false);
        slider(ui, &mut p.time_scale, range::TIME_SCALE, "wave speed (time scale)", false);
    });
    egui::CollapsingHeader::new("Sun").default_open(true).show(ui, |ui| {
        ui.checkbox(&mut p.sun, "sun");
        ui.add_enabled_ui(p.sun, |ui| {
            slider(ui, &mut p.sun_elevation_deg, range::SUN_ELEVATION_DEG, "elevation, °", false);
            slider(ui, &mut p.sun_azimuth_deg, (-180.0, 180.0), "azimuth, °", false);
        });
    });
    egui::CollapsingHeader::new("Water").default_open(true).show(ui, |ui| {
        for (c, name) in p.water_color.iter_mut().zip(["red", "green", "blue"]) {
            ui.add(
                egui::Slider::new(c, range::WATER_COLOR.0..=range::WATER_COLOR.1)
                    .logarithmic(true)
                    .clamping(egui::SliderClamping::Edits)
                    .text(format!("colour {name}")),
            );
        }
        slider(ui, &mut p.extinction_per_m, range::EXTINCTION_PER_M, "extinction K, 1/m", true);
    });
    egui::CollapsingHeader::new("Time").default_open(true).show(ui, |ui| {
        slider(ui, &mut p.time_scale, range::TIME_SCALE, "time scale", false);
        ui.checkbox(&mut p.paused, "paused (Space)");
        ui.label(format!("t = {:.2} s", overlay.time_s));
    });
    egui::CollapsingHeader::new("Camera").default_open(true).show(ui, |ui| {
        ui.horizontal(|ui| {
            if ui.button("scene camera (R)").clicked() {
                actions.push(Action::JumpHome);
            }
            if ui.button("horizon (H)").clicked() {
                actions.push(Action::Horizon);
            }
        });
        let c = overlay.controller;
        ui.label(format!(
            "at ({:.1}, {:.1}, {:.1}) m, speed {:.1} m/s",
            c.position.x, c.position.y, c.position.z, c.speed
        ));
        ui.label(
            RichText::new(
                "drag (left or right button) to look · WASD fly · Q/E down/up · Shift fast · \
                 scroll speed · F1 hide · Esc quit",
            )
            .small(),
        );
    });
    if let Some(e) = overlay.error {
        ui.colored_label(Color32::LIGHT_RED, format!("not applied: {e}"));
    }
}

fn stats(ui: &mut egui::Ui, o: &Overlay<'_>) {
    let s = o.stats;
    match s.frame_ms() {
        Some(ms) => ui.label(format!("{ms:.1} ms/frame ({:.1} fps)", 1e3 / ms)),
        None => ui.label("…"),
    };
    if let Some(ms) = median(s.recent_cpu_ms.iter().copied().collect()) {
        ui.label(format!("CPU {ms:.1} ms/frame · {}×{}", o.size.0, o.size.1));
    }
    if s.last_passes.is_empty() {
        ui.label(RichText::new("GPU time per pass: no timestamp queries").weak());
    } else {
        egui::Grid::new("passes").num_columns(2).show(ui, |ui| {
            for (p, ms) in &s.last_passes {
                ui.label(p.name());
                ui.label(format!("{ms:.2} ms"));
                ui.end_row();
            }
        });
    }
    match (o.wave_source, s.last_waves_cpu_ms) {
        // The CPU synthesis is timed on the CPU (its upload has no GPU pass).
        (Some(src @ "cpu-upload"), Some(ms)) => {
            ui.label(RichText::new(format!("waves: {src}, {ms:.1} ms on the CPU")).small())
        }
        (Some(src), _) => ui.label(RichText::new(format!("waves: {src}")).small()),
        _ => ui.label(RichText::new("waves: not in the plan").small()),
    };
    if let Some(plan) = o.plan {
        ui.separator();
        ui.label("plan (hover for the reason)");
        for p in &plan.passes {
            ui.label(format!("+ {}", p.name.name())).on_hover_text(&p.reason);
        }
        for p in &plan.skipped {
            ui.label(RichText::new(format!("- {} (skipped)", p.name.name())).weak())
                .on_hover_text(&p.reason);
        }
    }
    ui.separator();
    ui.label(RichText::new(o.adapter).small());
}

/// A slider over `lo..=hi` that leaves a scene's value outside the range as it is (egui
/// clamps existing values by default, which would change the scene by drawing the panel);
/// only the user's own edits are kept within the range.
fn slider(ui: &mut egui::Ui, v: &mut f64, (lo, hi): (f64, f64), text: &str, log: bool) {
    ui.add(
        egui::Slider::new(v, lo..=hi)
            .logarithmic(log)
            .clamping(egui::SliderClamping::Edits)
            .text(text),
    );
}

fn spectrum_label(k: SpectrumKind) -> &'static str {
    match k {
        SpectrumKind::Phillips => "Phillips",
        SpectrumKind::PiersonMoskowitz => "Pierson–Moskowitz",
        SpectrumKind::Jonswap => "JONSWAP",
        SpectrumKind::Tma => "TMA (finite depth)",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::view::params::sun_direction;
    use ocean_core::scene::Scene;

    fn run(ctx: &egui::Context, f: impl FnMut(&egui::Context)) {
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(1280.0, 2000.0),
            )),
            ..Default::default()
        };
        // The texture deltas would go to the GPU in the viewer: cleared, as nothing paints here.
        ctx.run_pass(input, f).textures_delta.clear();
    }

    /// A scene file may hold values the sliders do not reach; showing the panel must not
    /// pull them into the sliders' ranges (which would change the picture untouched).
    #[test]
    fn drawing_the_panel_leaves_a_scenes_out_of_range_values_alone() {
        let mut scene = Scene::builtin();
        scene.ocean.wind_speed = 45.0;
        scene.ocean.wind_direction_deg = -30.0;
        scene.ocean.fetch_km = 5000.0;
        scene.ocean.patch_size_m = 4096.0;
        scene.ocean.choppiness = 3.0;
        scene.water.color = [0.0, 0.0, 0.6];
        scene.water.extinction_per_m = 5.0;
        if let Some(sun) = &mut scene.sun {
            sun.direction = sun_direction(-20.0, 10.0);
        }
        scene.validate().expect("a valid scene");
        let mut p = ViewParams::from_scene(&scene);
        let before = p.clone();
        let stats = Stats::default();
        let controller = CameraController::new(&scene.camera);
        let overlay = Overlay {
            stats: &stats,
            plan: None,
            adapter: "test",
            controller: &controller,
            time_s: 0.0,
            size: (1280, 720),
            error: None,
            wave_source: None,
        };
        let ctx = egui::Context::default();
        let mut actions = Vec::new();
        for _ in 0..3 {
            run(&ctx, |ctx| draw(ctx, &mut p, &overlay, &mut actions));
        }
        assert!(actions.is_empty());
        assert_eq!(p, before);
        assert_eq!(p.apply(&scene).expect("applies"), scene);

        // Negative control: egui's default slider does clamp an existing value.
        let mut v = 45.0;
        run(&ctx, |ctx| {
            egui::Window::new("control").show(ctx, |ui| {
                ui.add(egui::Slider::new(&mut v, 0.0..=40.0));
            });
        });
        assert_eq!(v, 40.0);
    }
}
