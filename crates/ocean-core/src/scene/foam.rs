//! The `[foam]` table of the foam techniques (`heuristic`, `jacobian`, `accumulated`; the
//! model is [`crate::foam`]).

use serde::{Deserialize, Serialize};

/// The `[foam]` table: white water drawn over the shaded sea (stage `foam`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Foam {
    /// The foam's largest coverage of a pixel, 0–1 (how white a fully turbulent crest is).
    pub coverage: f64,
    /// The foam's albedo, linear RGB (lit by the sun and the sky's ambient light).
    pub color: [f64; 3],
    /// `jacobian`, `accumulated`: foam where the horizontal displacement's Jacobian J is
    /// below this (J < 1 where the surface is compressed, J < 0 where it folds).
    pub threshold: f64,
    /// Width of the ramp in J over which foam rises from 0 to full: below the threshold
    /// (`jacobian`, `accumulated`), below J = 1 (`heuristic`'s compression factor).
    pub softness: f64,
    /// `heuristic`: the height above the mean sea plane (m) at which a crest counts as fully
    /// high (seed 002: "the normal and height of the wave"); foam needs the crest high, steep
    /// and compressed (J < 1) at once.
    pub crest_height_m: f64,
    /// `heuristic`: the slope of the displaced surface at which a crest counts as fully
    /// steep.
    pub crest_slope: f64,
    /// Side of one cell of the foam texture's value noise, m.
    pub texture_scale_m: f64,
    /// Seed of the foam texture's noise.
    pub seed: u32,
    /// `accumulated`: foam decays as e^(−t/decay_s).
    pub decay_s: f64,
    /// `accumulated`: foam added per second where J is a full `softness` below the threshold.
    pub growth_per_s: f64,
    /// `accumulated`: the fixed step, s (one step per frame).
    pub step_s: f64,
    /// `accumulated`: steps run before a state's first frame, on that frame's sea (a still
    /// frame shows foam that has built up).
    pub warmup_steps: u32,
    /// `accumulated` under waves `gerstner`: texels per side of the world-fixed lattice
    /// around the camera that carries the foam (under `fft` the displacement map's grid
    /// carries it).
    pub grid: u32,
    /// `accumulated` under waves `gerstner`: the lattice's spacing, m.
    pub cell_m: f64,
}

impl Default for Foam {
    fn default() -> Self {
        Self {
            coverage: 0.9,
            color: [0.8, 0.82, 0.85],
            threshold: 0.8,
            softness: 0.5,
            crest_height_m: 0.8,
            crest_slope: 0.12,
            texture_scale_m: 1.5,
            seed: 7,
            decay_s: 2.5,
            growth_per_s: 3.0,
            step_s: 1.0 / 30.0,
            warmup_steps: 60,
            grid: 256,
            cell_m: 0.5,
        }
    }
}

// The field a scene chooses: here, above the foam model, which then knows no scene.
impl crate::foam::FieldGrid {
    /// The field of a scene whose waves technique is `waves`.
    pub fn of(scene: &super::Scene, waves: crate::stage::Waves) -> Self {
        if waves.per_vertex() {
            Self { size: scene.foam.grid, cell_m: scene.foam.cell_m, windowed: true }
        } else {
            let n = scene.ocean.resolution;
            Self { size: n, cell_m: scene.ocean.patch_size_m / f64::from(n), windowed: false }
        }
    }
}
