//! The foam stage's uniforms of a scene's frame: here, with the other uniforms, so the foam
//! model (`crate::foam`) knows no scene.

use crate::foam::{FOAM_NOISE_PERIOD, FOAM_STREAK, FieldGrid, FoamBlock, FoamStepUniforms};
use crate::scene::Scene;

impl FoamBlock {
    /// The block of a validated scene's frame under foam technique `technique` and waves
    /// technique `waves`, for a mesh whose reference point is world (x, z) `mesh_origin`.
    pub fn new(
        scene: &Scene,
        technique: crate::stage::Foam,
        waves: crate::stage::Waves,
        mesh_origin: [f64; 2],
    ) -> Self {
        let f = &scene.foam;
        // The texture lies on axes along and across the wind, so the reference point is
        // turned onto them (in f64) before each coordinate is reduced modulo its period.
        let noise_period = f.texture_scale_m * f64::from(FOAM_NOISE_PERIOD);
        let (sin_w, cos_w) = scene.ocean.wind_direction_deg.to_radians().sin_cos();
        let along = mesh_origin[0] * cos_w + mesh_origin[1] * sin_w;
        let across = mesh_origin[1] * cos_w - mesh_origin[0] * sin_w;
        let grid = FieldGrid::of(scene, waves);
        let side = grid.side_m();
        // The fade ends 0.45 of the side from the eye, where the window's nearest edge
        // is at least 0.5 − 1/size sides away; it starts at 0.35.
        let (window_outer, inv_window_band) =
            if grid.windowed { (0.45 * side, 1.0 / (0.1 * side)) } else { (0.0, 0.0) };
        FoamBlock {
            mode: technique.code(),
            intensity: f.coverage as f32,
            threshold: f.threshold as f32,
            inv_softness: (1.0 / f.softness) as f32,
            color: f.color.map(|c| c as f32),
            inv_crest_height: (1.0 / f.crest_height_m) as f32,
            noise_origin: [
                along.rem_euclid(noise_period * FOAM_STREAK) as f32,
                across.rem_euclid(noise_period) as f32,
            ],
            inv_noise_cell: (1.0 / f.texture_scale_m) as f32,
            inv_crest_slope: (1.0 / f.crest_slope) as f32,
            field_origin: mesh_origin.map(|c| c.rem_euclid(side) as f32),
            inv_field_size: (1.0 / side) as f32,
            field_half_texel: (0.5 / f64::from(grid.size)) as f32,
            window_outer: window_outer as f32,
            inv_window_band: inv_window_band as f32,
            seed: f.seed,
            inv_noise_cell_along: (1.0 / (f.texture_scale_m * FOAM_STREAK)) as f32,
            wind: [cos_w as f32, sin_w as f32],
            pad0: 0.0,
            pad1: 0.0,
        }
    }
}

impl FoamStepUniforms {
    /// One step of a validated scene's field `grid` with the window starting at lattice
    /// index `start` (previous step: `prev`), for a mesh whose reference point is world
    /// (x, z) `mesh_origin`.
    pub fn new(
        scene: &Scene,
        grid: &FieldGrid,
        start: [i64; 2],
        prev: [i64; 2],
        mesh_origin: [f64; 2],
    ) -> Self {
        let f = &scene.foam;
        let n = i64::from(grid.size);
        let m = |v: i64| v.rem_euclid(n) as u32;
        let shift = |a: usize| (start[a] - prev[a]).clamp(-n, n) as i32;
        Self {
            size: grid.size,
            analytic: u32::from(grid.windowed),
            start: [m(start[0]), m(start[1])],
            start_prev: [m(prev[0]), m(prev[1])],
            shift: [shift(0), shift(1)],
            start_rel: [
                (start[0] as f64 * grid.cell_m - mesh_origin[0]) as f32,
                (start[1] as f64 * grid.cell_m - mesh_origin[1]) as f32,
            ],
            cell_m: grid.cell_m as f32,
            decay: (-f.step_s / f.decay_s).exp() as f32,
            growth: (f.growth_per_s * f.step_s) as f32,
            threshold: f.threshold as f32,
            inv_softness: (1.0 / f.softness) as f32,
            pad0: 0.0,
        }
    }
}
