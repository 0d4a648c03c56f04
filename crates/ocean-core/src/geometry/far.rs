//! The far patch (seed 000 §3, Fig. 2b): a planar polar mesh around the eye, precomputed once
//! for a viewpoint at height H = 1 and a given field of view, then scaled by H and rotated by
//! the camera's yaw each frame.
//!
//! **Where the ground can be seen.** Put the eye at the origin, H = 1 above the plane, looking
//! along +Z with pitch p ∈ [−90°, 90°] and no roll; X is to the right. A ground point
//! (X, Z) is inside the frustum (half-angle tangents t_x = aspect·tan(fov_y/2),
//! t_y = tan(fov_y/2)) only if
//! - |X| ≤ t_x (Z cos p − sin p) ≤ t_x √(Z² + 1) (Cauchy–Schwarz): over all pitches, inside
//!   the hyperbola t_x⁻²X² = Z² + 1 — the paper's "two conic curves" a⁻²x² = z² + 1, the
//!   envelope of the frustum's side planes as the view pitches about the x-axis;
//! - Z ≥ −t_y: behind the eye only when looking down past the vertical, by at most half the
//!   vertical fov (the pitch never passes −90°).
//!
//! Straight down the yaw is undefined (the camera's "up" decides how the footprint is
//! turned), so the disc ρ ≤ √(t_x² + t_y²), which holds the footprint in any orientation, is
//! added. For a ring of radius ρ (units of H) the visible azimuths φ (from the forward
//! direction) then lie in one arc |φ| ≤ φ_arc(ρ), and φ_arc never grows with ρ
//! ([`visible_half_angle`]).
//!
//! **Mesh.** Rings ρ_k = far_min_radius · q^k (k = 0 … R, ρ_R ≥ far_max_radius), each cut at
//! the M azimuths φ_j = j·2π/M (one vertex per (k, j), shared by all the cells around it).
//! Row r, between rings r and r+1, holds the cells j ∈ [−n_r, n_r), enough to cover the arc
//! φ_arc(ρ_r cos(π/M)) plus one cell on each side (or all M cells once that reaches half the
//! circle). Using the arc at the inner chord's distance ρ_r cos(π/M) makes the row cover the
//! sliver between ring r's chord and its arc too, so the union of the rows holds every
//! visible point between the first ring and ρ_R cos(π/M).
//!
//! Only the rings outside the near patch are kept each frame; `mesh.rs` stitches the first
//! kept ring to the near patch's boundary.

use std::f64::consts::PI;

use super::params::{PatchParams, invalid};
use crate::Result;

/// The precomputed far patch for one field of view.
#[derive(Clone, Debug, PartialEq)]
pub struct FarPatch {
    /// M, angular segments.
    segments: u32,
    /// ρ_k, ring radii in units of H, increasing.
    rings: Vec<f64>,
    /// n_r for each row r (between rings r and r+1): the row holds cells j ∈ [−n_r, n_r);
    /// n_r = M/2 is the full circle.
    half_cells: Vec<u32>,
    /// (sin φ_j, cos φ_j) for j = 0 … M−1.
    unit: Vec<[f64; 2]>,
}

impl FarPatch {
    /// Precomputes the far patch for a vertical field of view `fov_y_rad` ∈ (0, π) and an
    /// aspect ratio (width / height) `aspect` > 0.
    pub fn precompute(params: &PatchParams, fov_y_rad: f64, aspect: f64) -> Result<Self> {
        params.validate()?;
        if !(fov_y_rad.is_finite() && fov_y_rad > 0.0 && fov_y_rad < PI) {
            return Err(invalid("fov_y_rad", fov_y_rad, "must be in (0, π)".into()));
        }
        if !(aspect.is_finite() && aspect > 0.0 && aspect < 1e6) {
            return Err(invalid("aspect", aspect, "must be finite and > 0".into()));
        }
        let t_y = (0.5 * fov_y_rad).tan();
        let t_x = aspect * t_y;
        if !(t_x.is_finite() && t_y.is_finite()) {
            return Err(invalid("fov_y_rad", fov_y_rad, "too close to π".into()));
        }
        let m = params.far_segments;
        let step = 2.0 * PI / f64::from(m);
        let q = params.far_ring_ratio;
        let mut rings = vec![params.far_min_radius];
        while *rings.last().expect("one ring") < params.far_max_radius {
            rings.push(params.far_min_radius * q.powi(rings.len() as i32));
        }
        let chord = (PI / f64::from(m)).cos();
        let half_cells = rings[..rings.len() - 1]
            .iter()
            .map(|&rho| {
                let arc = visible_half_angle(rho * chord, t_x, t_y);
                let cells = (arc / step).ceil() + 1.0;
                if cells >= f64::from(m / 2) { m / 2 } else { cells as u32 }
            })
            .collect();
        let unit = (0..m)
            .map(|j| {
                let phi = f64::from(j) * step;
                [phi.sin(), phi.cos()]
            })
            .collect();
        Ok(Self { segments: m, rings, half_cells, unit })
    }

    /// Places the far patch for one frame: eye at height `height_m` (H, > 0) above the plane,
    /// looking along the azimuth `yaw_rad` (the horizontal direction (sin yaw, cos yaw) in
    /// world (x, z): yaw 0 looks along +z, π/2 along +x).
    pub fn place(&self, yaw_rad: f64, height_m: f64) -> Result<PlacedFarPatch<'_>> {
        if !yaw_rad.is_finite() {
            return Err(invalid("yaw_rad", yaw_rad, "must be finite".into()));
        }
        if !(height_m.is_finite() && height_m > 0.0) {
            return Err(invalid("height_m", height_m, "must be finite and > 0".into()));
        }
        Ok(PlacedFarPatch { patch: self, sin_yaw: yaw_rad.sin(), cos_yaw: yaw_rad.cos(), height_m })
    }

    /// M, the angular segments.
    pub fn segments(&self) -> u32 {
        self.segments
    }

    /// The ring radii ρ_k in units of H.
    pub fn ring_radii(&self) -> &[f64] {
        &self.rings
    }

    /// n_r for row r (between rings r and r+1): the row holds the cells j ∈ [−n_r, n_r)
    /// around the forward direction; M/2 means the whole circle.
    pub fn row_half_cells(&self, row: usize) -> u32 {
        self.half_cells[row]
    }
}

/// The far patch scaled and rotated for one frame.
#[derive(Clone, Copy, Debug)]
pub struct PlacedFarPatch<'a> {
    patch: &'a FarPatch,
    sin_yaw: f64,
    cos_yaw: f64,
    height_m: f64,
}

impl PlacedFarPatch<'_> {
    /// The precomputed patch.
    pub fn patch(&self) -> &FarPatch {
        self.patch
    }

    /// H, metres.
    pub fn height_m(&self) -> f64 {
        self.height_m
    }

    /// World (x, z) offset from the eye of vertex (ring, j), metres; j is taken modulo M.
    /// Azimuth yaw + φ_j: φ grows counter-clockwise seen from above (from +z towards +x).
    pub fn offset(&self, ring: usize, j: i64) -> [f64; 2] {
        let [s, c] = self.patch.unit[j.rem_euclid(i64::from(self.patch.segments)) as usize];
        let r = self.height_m * self.patch.rings[ring];
        // (sin, cos) of yaw + φ.
        [r * (self.sin_yaw * c + self.cos_yaw * s), r * (self.cos_yaw * c - self.sin_yaw * s)]
    }
}

/// φ_arc(ρ): the largest |azimuth from forward| of a visible ground point at distance ρ (units
/// of H) for any pitch, fov half-angle tangents `t_x`, `t_y`, any roll when looking straight
/// down (see the module doc). π when the whole circle can be seen. Never increases with ρ.
pub fn visible_half_angle(rho: f64, t_x: f64, t_y: f64) -> f64 {
    if rho <= t_x.hypot(t_y) {
        return PI;
    }
    // cos φ ≥ −t_y/ρ (Z ≥ −t_y), and ρ² sin²φ ≤ t_x²(ρ² cos²φ + 1) ⇔ cos²φ ≥ κ.
    let behind = -t_y / rho;
    let kappa = (rho * rho - t_x * t_x) / (rho * rho * (1.0 + t_x * t_x));
    let cos_min = if kappa <= 0.0 {
        behind
    } else {
        let s = kappa.sqrt();
        // Past the hyperbola's side branches the circle re-enters on the back branch only
        // while Z ≥ −t_y still allows it; one arc covering both is kept.
        if behind <= -s { behind } else { s }
    };
    cos_min.clamp(-1.0, 1.0).acos()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether (X, Z) (units of H) is visible for some pitch in [−90°, 90°] (sampled finely)
    /// with no roll.
    fn visible(x: f64, z: f64, t_x: f64, t_y: f64) -> bool {
        (0..=360).any(|k| {
            let p = (f64::from(k) / 2.0 - 90.0).to_radians();
            // Camera axes: forward (0, sin p, cos p), up (0, cos p, −sin p); point (x, −1, z).
            let zc = -p.sin() + z * p.cos();
            let yc = -p.cos() - z * p.sin();
            zc > 0.0 && x.abs() <= t_x * zc && yc.abs() <= t_y * zc
        })
    }

    #[test]
    fn arc_holds_every_visible_point_and_shrinks_with_distance() {
        for (fov, aspect) in [(55f64, 16.0 / 9.0), (90.0, 1.0), (20.0, 0.5), (120.0, 2.0)] {
            let t_y = (0.5 * fov.to_radians()).tan();
            let t_x = aspect * t_y;
            let mut last = PI;
            for i in 0..120 {
                let rho = 0.01 * 1.12f64.powi(i);
                let arc = visible_half_angle(rho, t_x, t_y);
                assert!(arc <= last, "grew at ρ = {rho}");
                last = arc;
                for k in 0..180 {
                    let phi = f64::from(2 * k).to_radians() - PI;
                    if visible(rho * phi.sin(), rho * phi.cos(), t_x, t_y) {
                        assert!(phi.abs() <= arc + 1e-9, "fov {fov}: ρ {rho} φ {phi} > {arc}");
                    }
                }
            }
            // Far away the arc tends to the horizontal half-fov atan(t_x).
            let far = visible_half_angle(1e6, t_x, t_y);
            assert!((far - t_x.atan()).abs() < 1e-6, "{far} vs {}", t_x.atan());
        }
    }

    #[test]
    fn arc_is_not_trivially_wide() {
        // Negative control for the test above: the arc is tight where it should be.
        let t_y = 0.5f64;
        let t_x = 0.9;
        let arc = visible_half_angle(100.0, t_x, t_y);
        assert!(arc < t_x.atan() + 0.01);
    }
}
