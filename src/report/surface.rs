//! The report's `surface` knob (issue 13): surfaces `hu_patches`, `projected_grid` (at three
//! grid densities) and `clipmap` (issue 14, at two level sizes) on the same FFT sea — the default scene without its objects — against
//! a dense reference mesh of the same sea (a projected grid of half-pixel cells): per band of the
//! view, the mean error of the height and of the position of the surface point each pixel
//! sees (from the depth buffer), the vertices the mesh submits and the share of them inside
//! the view, and the frame time on the CPU and (where an adapter exists) the GPU. And the
//! `clouds` knob: the cost of sky technique `preetham_clouds` against `preetham` under system
//! `chiu`'s shading.

use anyhow::Context;
use glam::DVec3;
use ocean_core::camera::Camera;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::Scene;
use ocean_core::supersample::{band_error, sea_bands};
use ocean_cpu::shaders::water;

use super::{CPU, Ctx, Row};
use ocean_core::plan::{Shading, Sky, Surface};

/// The settings: (name, surface, projected grid cell in pixels, clipmap quads a level side).
const SETTINGS: [(&str, Surface, f64, u32); 6] = [
    ("hu_patches", Surface::HuPatches, 4.0, 64),
    ("projected_grid 8 px", Surface::ProjectedGrid, 8.0, 64),
    ("projected_grid 4 px", Surface::ProjectedGrid, 4.0, 64),
    ("projected_grid 2 px", Surface::ProjectedGrid, 2.0, 64),
    ("clipmap 32²", Surface::Clipmap, 4.0, 32),
    ("clipmap 64²", Surface::Clipmap, 4.0, 64),
];

/// The reference mesh's cell, pixels.
const REFERENCE_CELL_PX: f64 = 0.5;

/// Progress steps of [`measure`].
pub(super) fn steps(ctx: &Ctx) -> u64 {
    (2 * SETTINGS.len() as u64 + 1) * (ctx.runs as u64 + 1)
}

fn scene(ctx: &Ctx, surface: Surface, cell: f64, clipmap_cells: u32) -> Scene {
    let mut s = Scene::builtin();
    s.objects.clear();
    (s.camera.width, s.camera.height) = ctx.frame_size();
    s.techniques.surface = Some(surface);
    s.quality.projected_grid_cell_px = cell;
    s.quality.clipmap_cells = clipmap_cells;
    s
}

/// The world point each pixel sees on the water (reversed-Z depth: NDC z = near / view
/// depth), `None` for the sky.
fn seen_points(camera: &Camera, depth: &[f32]) -> Vec<Option<DVec3>> {
    let (w, h) = (camera.width, camera.height);
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let z = f64::from(depth[(y * w + x) as usize]);
            if z <= 0.0 {
                return None;
            }
            let ndc = ocean_core::camera::pixel_centre_ndc(x, y, w, h);
            let d = camera.ray_direction(ndc.0, ndc.1);
            let view_depth = ocean_core::camera::NEAR_PLANE_M / z;
            Some(camera.eye + d * (view_depth / d.dot(camera.forward)))
        })
        .collect()
}

/// The vertices the frame's water pass submits and the share of them inside the view.
pub(super) fn vertices_in_view(
    r: &ocean_cpu::Rendered,
    scene: &Scene,
) -> anyhow::Result<(u64, f64)> {
    let fb = &r.buffers;
    let camera = Camera::from_scene(&scene.camera)?;
    let (slopes, bump) = fb.water_slopes(&r.plan);
    let sky = |_: [f32; 3]| [0.0f32; 3];
    let b = fb.water_bindings(
        &r.plan,
        (&slopes, &bump),
        &sky,
        ocean_cpu::shaders::shading::hu::shade_above,
    );
    let inside = |o: water::VertexOut| {
        let c = o.clip;
        c.w > 0.0 && c.x.abs() <= c.w && c.y.abs() <= c.w
    };
    let grid = fb.uniforms.grid.vertex_count();
    let clipmap = fb.uniforms.clip.vertex_count();
    let (n, k) = if clipmap > 0 {
        (clipmap, (0..clipmap).filter(|&k| inside(water::vs_clipmap(k, &b))).count())
    } else if grid > 0 {
        (grid, (0..grid).filter(|&k| inside(water::vs_projected_grid(k, &b))).count())
    } else {
        let mesh = r.plan.water_mesh(scene, &camera)?;
        let n = mesh.vertices.len() as u32;
        (n, mesh.vertices.iter().filter(|v| inside(water::vs_main(v, &b))).count())
    };
    Ok((u64::from(n), k as f64 / f64::from(n.max(1))))
}

/// Measures the knob.
pub(super) fn measure(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let reference = scene(ctx, Surface::ProjectedGrid, REFERENCE_CELL_PX, 64);
    let camera = Camera::from_scene(&reference.camera)?;
    let (w, h) = ctx.frame_size();
    let bands = sea_bands(&camera, h);
    let (_, truth) = ctx.time(|| {
        let plan = FramePlan::new(&reference, OutputKind::Hdr);
        let r = ocean_cpu::render_scene_with_plan(&reference, plan, &mut |_| {})?;
        ctx.step("surface reference");
        Ok(seen_points(&camera, &r.buffers.hdr.depth))
    })?;
    let mut shared = ctx.gpu();
    let mut gpu = match shared.as_mut() {
        Ok(g) => Some(g),
        Err(e) => {
            ctx.bar.suspend(|| eprintln!("report: surface knob has no GPU rows: {e}"));
            None
        }
    };
    const METRICS: [[&str; 3]; 2] = [
        ["height_m_horizon", "height_m_middle", "height_m_near"],
        ["position_m_horizon", "position_m_middle", "position_m_near"],
    ];
    let mut rows = Vec::new();
    for (name, surface, cell, clipmap_cells) in SETTINGS {
        let s = scene(ctx, surface, cell, clipmap_cells);
        let (ms, r) = ctx.time(|| {
            let plan = FramePlan::new(&s, OutputKind::Hdr);
            let r = ocean_cpu::render_scene_with_plan(&s, plan, &mut |_| {})?;
            ctx.step("surface cpu");
            Ok(r)
        })?;
        let seen = seen_points(&camera, &r.buffers.hdr.depth);
        let (n, share) = vertices_in_view(&r, &s)?;
        // No comma in a setting: the CSV contract splits on commas.
        let setting = format!("{name} ({n} vertices; {:.0} % in view)", 100.0 * share);
        // Per band: mean |Δy| and |ΔP| over the pixels where both see the sea.
        let errors: Vec<[f64; 2]> = bands
            .iter()
            .map(|rows_b| {
                let (mut sum, mut count) = ([0.0f64; 2], 0usize);
                for &y in rows_b {
                    for x in 0..w {
                        let i = (y * w + x) as usize;
                        if let (Some(a), Some(b)) = (seen[i], truth[i]) {
                            sum[0] += (a.y - b.y).abs();
                            sum[1] += (a - b).length();
                            count += 1;
                        }
                    }
                }
                sum.map(|v| v / count.max(1) as f64)
            })
            .collect();
        let mut push = |ms: f64, backend: &'static str| {
            for (m, metric) in METRICS.iter().enumerate() {
                for (b, rows_b) in bands.iter().enumerate() {
                    if !rows_b.is_empty() {
                        rows.push(Row {
                            knob: "surface",
                            setting: setting.clone(),
                            error_metric: metric[b],
                            error: errors[b][m],
                            time_ms: ms,
                            backend,
                        });
                    }
                }
            }
        };
        push(ms, CPU);
        if let Some(g) = gpu.as_mut() {
            // The GPU draws the same mesh (the cross-check holds its picture to the CPU's):
            // its rows carry the CPU's geometric error with its own time.
            let plan = FramePlan::new(&s, OutputKind::Hdr);
            let (gms, _) = ctx.time(|| {
                let f = g.run_with(&s, &plan, ocean_gpu::Readback::Output)?;
                ctx.step("surface gpu");
                Ok(f.map(ocean_gpu::FrameMap::Hdr).context("the HDR frame")?.texels.len())
            })?;
            push(gms, "gpu");
        }
    }
    Ok(rows)
}

/// Progress steps of [`measure_clouds`].
pub(super) fn clouds_steps(ctx: &Ctx) -> u64 {
    4 * (ctx.runs as u64 + 1)
}

/// The `clouds` knob: the default scene under system `chiu`'s shading with sky `preetham` and
/// `preetham_clouds`: frame time on both back ends, and how far the clouds move the picture
/// (mean |Δ log(1 + L)| over the frame against the clear sky's).
pub(super) fn measure_clouds(ctx: &Ctx) -> anyhow::Result<Vec<Row>> {
    let sky_scene = |sky: Sky| {
        let mut s = Scene::builtin();
        (s.camera.width, s.camera.height) = ctx.frame_size();
        s.techniques.shading = Some(Shading::Chiu);
        s.techniques.surface = Some(Surface::ProjectedGrid);
        s.techniques.sky = Some(sky);
        s
    };
    let (w, h) = ctx.frame_size();
    let all: Vec<u32> = (0..h).collect();
    let mut frames: Vec<Vec<[f32; 4]>> = Vec::new();
    let mut rows = Vec::new();
    let mut shared = ctx.gpu();
    let mut gpu = shared.as_mut().ok();
    for sky in [Sky::Preetham, Sky::PreethamClouds] {
        let s = sky_scene(sky);
        let (ms, f) = ctx.time(|| {
            let r = ocean_cpu::render_scene(&s, OutputKind::Hdr, &mut |_| {})?;
            ctx.step("clouds cpu");
            Ok(r.buffers.hdr.color)
        })?;
        let change = frames.first().map_or(0.0, |clear| band_error(&f, clear, w, &all));
        frames.push(f);
        rows.push(Row {
            knob: "clouds",
            setting: sky.name().into(),
            error_metric: "log_l_change",
            error: change,
            time_ms: ms,
            backend: CPU,
        });
        if let Some(g) = gpu.as_mut() {
            let plan = FramePlan::new(&s, OutputKind::Hdr);
            let (gms, _) = ctx.time(|| {
                g.run_with(&s, &plan, ocean_gpu::Readback::Output)?;
                ctx.step("clouds gpu");
                Ok(())
            })?;
            rows.push(Row {
                knob: "clouds",
                setting: sky.name().into(),
                error_metric: "log_l_change",
                error: change,
                time_ms: gms,
                backend: "gpu",
            });
        }
    }
    Ok(rows)
}
