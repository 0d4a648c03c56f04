//! The height query of whichever waves technique a frame draws ([`WaveSurface`]): above the
//! models it wraps (`query`'s FFT sum, `gerstner`, `coastal`), so none of them imports another
//! through it.

use super::query::{Inversion, SurfaceQuery, SurfaceSample, invert_displacement};

/// The height query of either wave model: what [`crate::frame::surface_query`] returns, so
/// that a floating object, `ocean heightfield` and the tests ask the surface the picture draws
/// without knowing which waves technique made it.
#[derive(Clone, Debug)]
pub enum WaveSurface {
    /// Waves `fft`: the direct sum of eq. 1's modes.
    Fft(SurfaceQuery),
    /// Waves `gerstner`: the sum of the frame's Gerstner waves.
    Gerstner(super::gerstner::GerstnerSea),
    /// Waves `coastal`: the radial and correction waves over the floor (vertical only).
    Coastal(Box<super::coastal::CoastalSea>),
    /// Waves `fft` or `gerstner` near a shore (`[terrain] wave_damping`): `inner`'s
    /// displacement (height, horizontal, and their derivatives) times
    /// w = clamp(h·inv, 0, 1), h the floor's depth under the parameter point, as the vertices
    /// scale theirs (shared/floor.wgsl `shore_weight`; w's own gradient is left out of the
    /// slopes, as the shaders leave it).
    Damped {
        /// The undamped sea.
        inner: Box<WaveSurface>,
        /// The floor.
        terrain: Box<crate::terrain::Terrain>,
        /// 1/(r·λ), 1/m.
        inv: f64,
    },
}

/// How close the damped surface's inversion comes to the world point, m.
const DAMPED_INVERSION_TOLERANCE_M: f64 = 1e-7;

impl WaveSurface {
    /// The fields at the undisplaced point (x0, z0).
    pub fn sample(&self, x0: f64, z0: f64) -> SurfaceSample {
        match self {
            Self::Fft(q) => q.sample(x0, z0),
            Self::Gerstner(g) => g.sample(x0, z0),
            Self::Coastal(c) => c.surface_sample(x0, z0),
            Self::Damped { inner, terrain, inv } => {
                let s = inner.sample(x0, z0);
                let w = ((-terrain.height(x0, z0)).max(0.0) * inv).clamp(0.0, 1.0);
                let (dxx, dzz, dxz) = (s.disp_x_dx * w, s.disp_z_dz * w, s.disp_x_dz * w);
                SurfaceSample {
                    height: s.height * w,
                    disp_x: s.disp_x * w,
                    disp_z: s.disp_z * w,
                    slope_x: s.slope_x * w,
                    slope_z: s.slope_z * w,
                    disp_x_dx: dxx,
                    disp_z_dz: dzz,
                    disp_x_dz: dxz,
                    jacobian: (1.0 + dxx) * (1.0 + dzz) - dxz * dxz,
                }
            }
        }
    }

    /// The parameter point whose displaced position is the world point (x, z).
    pub fn invert(&self, x: f64, z: f64) -> Inversion {
        match self {
            Self::Fft(q) => q.invert(x, z),
            Self::Gerstner(g) => g.invert(x, z),
            // The coastal waves move the surface vertically only: the point is its own.
            Self::Coastal(c) => Inversion {
                x0: x,
                z0: z,
                residual_m: 0.0,
                iterations: 0,
                converged: true,
                sample: c.surface_sample(x, z),
            },
            Self::Damped { .. } => invert_displacement(
                |x0, z0| self.sample(x0, z0),
                x,
                z,
                DAMPED_INVERSION_TOLERANCE_M,
            ),
        }
    }

    /// The height of the displaced surface above the world point (x, z).
    pub fn height_at(&self, x: f64, z: f64) -> f64 {
        self.invert(x, z).sample.height
    }

    /// The unit normal of the displaced surface above the world point (x, z).
    pub fn normal_at(&self, x: f64, z: f64) -> [f64; 3] {
        self.invert(x, z).sample.normal()
    }
}
