//! The four systems side by side (issue 18, item 3): every system that has landed, on the
//! same reference viewpoints, with its picture, its frame time per pass on both back ends, the
//! vertices its water mesh submits, its far-band error against its own `--spp 64` frame, and
//! the passes the planner leaves out; and what each system does that the others do not, read
//! from the technique table (`ocean_core::plan::SYSTEMS`), not written by hand.
//!
//! A viewpoint is an edit of each system's own built-in scene (the default sea; coastal's
//! island): the camera's height and pitch along its own heading, the sun, the wind. The same
//! words mean the same view for every system, while each keeps the scene its paper is about.

use std::fmt::Write as _;

use anyhow::Context;
use ocean_core::camera::Camera;
use ocean_core::plan::{FramePlan, OutputKind, SYSTEMS, Stage, System};
use ocean_core::scene::Scene;
use ocean_core::supersample::{band_error, box_filter, sea_bands};

use super::Ctx;
use crate::bench::Case;

/// A reference viewpoint: its name, what it is, and the edit of a system's scene.
pub(super) struct Viewpoint {
    /// Short name (file names, table rows).
    pub name: &'static str,
    /// What it is.
    pub what: &'static str,
    edit: fn(&mut Scene),
}

/// Puts the camera `height` m above the sea, pitched `pitch_deg` down along its heading.
fn look(s: &mut Scene, height: f64, pitch_deg: f64) {
    let c = &mut s.camera;
    let (dx, dz) = (c.look_at[0] - c.position[0], c.look_at[2] - c.position[2]);
    let d = (dx * dx + dz * dz).sqrt().max(1e-9);
    c.position[1] = height;
    let p = pitch_deg.to_radians();
    c.look_at =
        [c.position[0] + dx / d * 100.0, height - 100.0 * p.tan(), c.position[2] + dz / d * 100.0];
}

/// The sun at `elevation_deg` ahead of the camera, `azimuth_deg` to its right.
fn sun_ahead(s: &mut Scene, elevation_deg: f64, azimuth_deg: f64) {
    let c = &s.camera;
    let (dx, dz) = (c.look_at[0] - c.position[0], c.look_at[2] - c.position[2]);
    let heading = dz.atan2(dx) + azimuth_deg.to_radians();
    let e = elevation_deg.to_radians();
    if let Some(sun) = &mut s.sun {
        sun.time_of_day_h = None;
        sun.direction = [e.cos() * heading.cos(), e.sin(), e.cos() * heading.sin()];
    }
}

/// The viewpoints, in the page's order.
pub(super) const VIEWPOINTS: [Viewpoint; 4] = [
    Viewpoint {
        name: "level_8m",
        what: "eye 8 m above the sea, looking level at the horizon; the scene's sun",
        edit: |s| look(s, 8.0, 0.0),
    },
    Viewpoint {
        name: "up_40m",
        what: "eye 40 m up, 20° down; the scene's sun",
        edit: |s| look(s, 40.0, 20.0),
    },
    Viewpoint {
        name: "grazing_sun",
        what: "eye 8 m up, 4° down; the sun 3° above the horizon, 10° right of ahead",
        edit: |s| {
            look(s, 8.0, 4.0);
            sun_ahead(s, 3.0, 10.0);
        },
    },
    Viewpoint {
        name: "storm",
        what: "eye 8 m up, 6° down; wind 20 m/s (the FFT spectrum's; the Gerstner and coastal \
               waves keep their own tables)",
        edit: |s| {
            look(s, 8.0, 6.0);
            s.ocean.wind_speed = 20.0;
        },
    },
];

/// One system on one viewpoint.
pub(super) struct Shot {
    /// The system.
    pub system: System,
    /// Index into [`VIEWPOINTS`].
    pub viewpoint: usize,
    /// The CPU frame's 8-bit RGB.
    pub rgb: Vec<u8>,
    /// The CPU oracle's frame and passes.
    pub cpu: Case,
    /// The GPU's, where an adapter is here (`--quick`: at the first viewpoint only).
    pub gpu: Option<Case>,
    /// Vertices the water mesh submits, and the share inside the view.
    pub vertices: (u64, f64),
    /// Mean |Δ log(1 + L)| of the horizon and middle bands against the system's own 64-sample
    /// frame; `None` where the report left it out (`--quick` does not measure it).
    pub far_error: Option<[f64; 2]>,
    /// Passes the planner leaves out of the full graph.
    pub left_out: Vec<&'static str>,
}

/// The section's measurements.
pub(super) struct Systems {
    /// Frame size.
    pub size: (u32, u32),
    /// Every system × viewpoint.
    pub shots: Vec<Shot>,
    /// The GPU adapter, or why there was none.
    pub gpu: Result<String, String>,
}

impl Systems {
    /// Every system's shot at the first viewpoint, and every pass any of them timed on either
    /// back end, in first-seen order.
    pub(super) fn first_viewpoint(&self) -> (Vec<&Shot>, Vec<&str>) {
        let firsts: Vec<&Shot> = self.shots.iter().filter(|t| t.viewpoint == 0).collect();
        let mut passes: Vec<&str> = Vec::new();
        for t in &firsts {
            for (p, _) in t.cpu.passes.iter().chain(t.gpu.iter().flat_map(|g| g.passes.iter())) {
                if !passes.contains(&p.as_str()) {
                    passes.push(p);
                }
            }
        }
        (firsts, passes)
    }
}

/// Systems the section shows: all of them.
pub(super) fn systems() -> impl Iterator<Item = System> {
    SYSTEMS.iter().map(|s| s.system)
}

/// Progress steps of [`measure`].
pub(super) fn steps(_ctx: &Ctx) -> u64 {
    (systems().count() * VIEWPOINTS.len()) as u64
}

/// The frame size of the section.
fn size(ctx: &Ctx) -> (u32, u32) {
    if ctx.quick { (160, 90) } else { (384, 216) }
}

/// Renders and times every system on every viewpoint.
pub(super) fn measure(ctx: &Ctx) -> anyhow::Result<Systems> {
    let (w, h) = size(ctx);
    let runs = if ctx.quick { 1 } else { 3 };
    let mut shared = ctx.gpu();
    let gpu = &mut *shared;
    if let Err(e) = &gpu {
        ctx.bar.suspend(|| eprintln!("report: the systems section has no GPU times: {e}"));
    }
    let mut shots = Vec::new();
    for system in systems() {
        for (v, viewpoint) in VIEWPOINTS.iter().enumerate() {
            let mut s = Scene::builtin_for(system).with_system(system)?;
            (s.camera.width, s.camera.height) = (w, h);
            (viewpoint.edit)(&mut s);
            if let Err((key, msg)) = s.validate() {
                anyhow::bail!("{} {}: {key}: {msg}", system.name(), viewpoint.name);
            }
            let name = format!("{} {}", system.name(), viewpoint.name);
            let (cpu, r) = crate::bench::cpu_frame_of(&s, &name, runs)?;
            let ldr = r.ldr.as_ref().context("the plan tonemaps")?;
            let rgb: Vec<u8> = ldr.chunks(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
            // --quick times the GPU at the first viewpoint only.
            let gpu_case = match gpu.as_mut() {
                Ok(g) if !ctx.quick || v == 0 => {
                    Some(crate::bench::gpu_frame_of(g, &s, &name, runs)?)
                }
                _ => None,
            };
            let vertices = super::surface::vertices_in_view(&r, &s)?;
            let far_error = if !ctx.quick {
                let truth_scene = {
                    let mut t = s.clone();
                    (t.camera.width, t.camera.height) = (w * 8, h * 8);
                    t.techniques.far_field = Some(ocean_core::plan::FarField::None);
                    t
                };
                let truth = ocean_cpu::render_scene(&truth_scene, OutputKind::Hdr, &mut |_| {})?;
                let truth = box_filter(&truth.buffers.hdr.color, w, h, 8);
                let bands = sea_bands(&Camera::from_scene(&s.camera)?, h);
                Some([0, 1].map(|b| {
                    if bands[b].is_empty() {
                        f64::NAN
                    } else {
                        band_error(&r.buffers.hdr.color, &truth, w, &bands[b])
                    }
                }))
            } else {
                None
            };
            let full = FramePlan::full(&s, OutputKind::Ldr);
            let left_out = FramePlan::new(&s, OutputKind::Ldr)
                .pruned_from(&full)
                .iter()
                .map(|p| p.name())
                .collect();
            shots.push(Shot {
                system,
                viewpoint: v,
                rgb,
                cpu,
                gpu: gpu_case,
                vertices,
                far_error,
                left_out,
            });
            ctx.step(&format!("systems {name}"));
        }
    }
    let gpu = gpu.as_ref().map(|g| g.adapter().to_string()).map_err(Clone::clone);
    Ok(Systems { size: (w, h), shots, gpu })
}

/// Each system's techniques that no other system uses, with where each comes from: rows of
/// (system, stage, technique, source).
pub(super) fn unique_techniques() -> Vec<(&'static str, &'static str, &'static str, &'static str)> {
    let mut out = Vec::new();
    for info in SYSTEMS {
        for stage in Stage::ALL {
            let t = info.techniques.of(stage);
            let shared =
                SYSTEMS.iter().any(|o| o.system != info.system && o.techniques.of(stage) == t);
            if !shared {
                out.push((info.name, stage.name(), t.name, t.source));
            }
        }
    }
    out
}

/// Milliseconds, or a dash.
fn ms(v: Option<f64>) -> String {
    v.filter(|v| v.is_finite()).map_or("—".into(), |v| format!("{v:.1}"))
}

/// The section's tables as HTML: the viewpoint table, the passes of each system at the first
/// viewpoint on both back ends, and the unique techniques.
pub(super) fn html(s: &Systems) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "<p>Each system on its own built-in scene ({}×{} px), seen from the same viewpoints: {}. GPU: {}.</p>",
        s.size.0,
        s.size.1,
        VIEWPOINTS
            .iter()
            .map(|v| format!("<b>{}</b> ({})", v.name, v.what))
            .collect::<Vec<_>>()
            .join("; "),
        match &s.gpu {
            Ok(a) => super::svg::esc(a),
            Err(e) => format!("none ({})", super::svg::esc(e)),
        }
    );
    let _ = writeln!(
        o,
        "<table><tr><th>system</th><th>viewpoint</th><th>CPU frame (ms)</th><th>GPU frame (ms)</th>\
         <th>water vertices submitted (in view)</th><th>horizon error</th><th>middle error</th><th>passes the planner leaves out</th></tr>"
    );
    for t in &s.shots {
        let far = |b: usize| {
            t.far_error.map_or("—".into(), |e| {
                if e[b].is_finite() { format!("{:.4}", e[b]) } else { "no sea in band".into() }
            })
        };
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{} ({:.0} %)</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            t.system.name(),
            VIEWPOINTS[t.viewpoint].name,
            ms(Some(t.cpu.frame_ms)),
            ms(t.gpu.as_ref().map(|g| g.frame_ms)),
            t.vertices.0,
            100.0 * t.vertices.1,
            far(0),
            far(1),
            if t.left_out.is_empty() { "—".into() } else { t.left_out.join(", ") }
        );
    }
    let _ = writeln!(o, "</table>");
    let _ = writeln!(
        o,
        "<p>Errors: mean |Δ log(1 + L)| over the band's rows against the system's own frame at 64 samples per pixel (far field <code>none</code>); horizon: the sea within 2° of the horizon, middle: 2°–8°.{}</p>",
        if s.shots.iter().all(|t| t.far_error.is_none()) {
            " <code>--quick</code> leaves them out (—), and times the GPU at the first viewpoint only."
        } else {
            ""
        }
    );
    // Passes at the first viewpoint.
    let _ = writeln!(
        o,
        "<h3>Frame time per pass ({} viewpoint, ms: CPU / GPU)</h3>",
        VIEWPOINTS[0].name
    );
    let (firsts, passes) = s.first_viewpoint();
    let _ = write!(o, "<table><tr><th>pass</th>");
    for t in &firsts {
        let _ = write!(o, "<th>{}</th>", t.system.name());
    }
    let _ = writeln!(o, "</tr>");
    for p in &passes {
        let _ = write!(o, "<tr><td>{p}</td>");
        for t in &firsts {
            let of = |c: &Case| c.passes.iter().find(|(q, _)| q == p).map(|(_, v)| *v);
            let (c, g) = (of(&t.cpu), t.gpu.as_ref().and_then(of));
            let _ = write!(o, "<td>{} / {}</td>", ms(c), ms(g));
        }
        let _ = writeln!(o, "</tr>");
    }
    let _ = writeln!(o, "</table>");
    let _ = writeln!(o, "<h3>What each system does that the others do not</h3>");
    let _ =
        writeln!(o, "<table><tr><th>system</th><th>stage</th><th>technique</th><th>from</th></tr>");
    for (sys, stage, t, source) in unique_techniques() {
        let _ = writeln!(
            o,
            "<tr><td>{sys}</td><td>{stage}</td><td><code>{t}</code></td><td>{}</td></tr>",
            super::svg::esc(source)
        );
    }
    let _ = writeln!(o, "</table>");
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_viewpoint_is_a_valid_scene_for_every_system() {
        for system in systems() {
            for v in &VIEWPOINTS {
                let mut s = Scene::builtin_for(system).with_system(system).unwrap();
                (v.edit)(&mut s);
                assert!(s.validate().is_ok(), "{} {}", system.name(), v.name);
            }
        }
        // The level view looks level; the high one is 40 m up.
        let mut s = Scene::builtin();
        (VIEWPOINTS[0].edit)(&mut s);
        assert!((s.camera.look_at[1] - s.camera.position[1]).abs() < 1e-9);
        (VIEWPOINTS[1].edit)(&mut s);
        assert_eq!(s.camera.position[1], 40.0);
    }

    #[test]
    fn unique_techniques_come_from_the_table() {
        let rows = unique_techniques();
        // Welch's Gerstner waves and GGX are its own; hu's patches are hu's.
        assert!(rows.iter().any(|r| r.0 == "welch" && r.2 == "gerstner"));
        assert!(rows.iter().any(|r| r.0 == "hu" && r.2 == "hu_patches"));
        // fft is shared by hu and chiu, so neither lists it.
        assert!(!rows.iter().any(|r| r.2 == "fft"));
    }
}
