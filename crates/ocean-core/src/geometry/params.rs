//! Parameters of the view-dependent water mesh: defaults, and the checks that make every
//! later step well defined.

use std::f64::consts::PI;

use crate::{Error, Result};

/// Near-patch side the defaults aim for, metres: large enough that waves beyond it show no
/// visible relief from any height (seed 000 §3: "large enough to cover all ocean waves with
/// visible height variations"), small enough to keep the bintree cheap.
pub const DEFAULT_NEAR_SIZE_M: f64 = 512.0;

/// Largest number of bintree levels per axis: the near patch is at most 2^15 grid cells on a
/// side (grid coordinates stay far inside i32, the mesh inside u32 indices).
pub const MAX_NEAR_LEVELS: u32 = 15;

/// How far from an eye `height_m` above the sea the displacement map's waves still show, m:
/// the distance d at which its longest wave, the patch side L, seen foreshortened spans one
/// pixel of `pixel_rad` (L·H/(d² + H²) = p, so d = √(L·H/p − H²)); beyond it every wave the
/// map holds is below a pixel and the far patch's filtered bump map stands for them. 0 where
/// even L spans less than a pixel (an eye so high that the map's waves never show) and for
/// inputs that are not finite and positive.
///
/// Seed 000's near patch follows the viewer but has a fixed size; the far patch beyond it
/// carries neither the displacement nor its slopes, so an eye high enough that its view lies
/// beyond the patch saw the sea as bump-map speckle without its swell (`tests/hu_from_above.rs`:
/// the wave contrast at 300 m was 0.09 of the projected grid's). Growing the patch to this
/// reach ([`PatchParams::with_reach`]) keeps the swell wherever it is visible.
pub fn wave_reach_m(patch_side_m: f64, height_m: f64, pixel_rad: f64) -> f64 {
    let (l, h, p) = (patch_side_m, height_m, pixel_rad);
    if !(l > 0.0 && h > 0.0 && p > 0.0 && l.is_finite() && h.is_finite() && p.is_finite()) {
        return 0.0;
    }
    let d2 = l * h / p - h * h;
    if d2 > 0.0 { d2.sqrt() } else { 0.0 }
}

/// Largest viewpoint height |eye.y| accepted, metres. Beyond it the far patch's outer ring
/// (`far_max_radius · H`) would approach f32's range.
pub const MAX_HEIGHT_M: f64 = 1.0e6;

/// Safety factor on the radius the far patch's first kept ring needs for the stitch to be
/// valid ([`stitch_radius`]): the ring is placed at least this much farther out.
pub const STITCH_CLEARANCE: f64 = 1.25;

/// Everything that shapes the water mesh. Lengths in metres; the far patch's radii are in
/// units of the viewpoint height H (the far patch is built once for H = 1 and scaled).
///
/// [`PatchParams::for_grid`] derives consistent values from the displacement grid spacing;
/// [`Default`] is `for_grid(1.0)` (the default scene: L = 256 m, N = 256).
#[derive(Clone, Debug, PartialEq)]
pub struct PatchParams {
    /// Spacing L/N of the displacement map's samples. Every near-patch vertex lies on this
    /// grid, so the vertex shader samples the displacement map exactly at its samples.
    pub grid_spacing_m: f64,
    /// Side S of the square near patch; must be `grid_spacing_m · 2^K` with 2 ≤ K ≤
    /// [`MAX_NEAR_LEVELS`] (checked to a relative 1e-9, then used as exactly that).
    pub near_size_m: f64,
    /// Deepest bintree level. Level 0 is the square cut along a diagonal; level 2k has legs
    /// S/2^k along the axes, so `max_depth = 2K` makes the finest legs exactly the grid
    /// spacing, and larger values are rejected (the mesh would be finer than the data).
    pub max_depth: u32,
    /// A near-patch triangle is split while its hypotenuse, seen from the eye, subtends more
    /// than this angle (radians): `hypotenuse > split_threshold · distance`, the distance
    /// from the eye to the triangle's circumscribed disc on the plane. Default 0.05 rad
    /// (≈ 37 pixels of a 720-pixel-high, 55° view).
    pub split_threshold: f64,
    /// Edges per side of the near patch's boundary (a power of two, at most 2^K). The
    /// boundary is always subdivided exactly this finely, whatever the view, so that the far
    /// patch can be stitched to fixed vertices.
    pub boundary_segments: u32,
    /// Width of the band inside the near patch's boundary over which the displacement weight
    /// ramps linearly from 0 (on the boundary) to 1; 0 makes every vertex off the boundary 1.
    /// Default S/16, so that the waves fade out over several triangles rather than one.
    pub weight_taper_m: f64,
    /// Smallest viewpoint height used: H = max(|eye.y|, min_height_m). Under water the mesh
    /// is the one for the mirrored eye above the surface (the surface seen from below).
    pub min_height_m: f64,
    /// Angular segments M of the far patch's polar grid (even, ≥ 8).
    pub far_segments: u32,
    /// Ratio q > 1 between consecutive far rings (a geometric progression).
    pub far_ring_ratio: f64,
    /// Radius of the far patch's innermost precomputed ring, in units of H.
    pub far_min_radius: f64,
    /// Radius the far patch's outermost ring reaches at least, in units of H. The ring at
    /// ρ·H is seen atan(1/ρ) below the horizon: 1e6 puts it within 1e-6 rad of it. A pixel
    /// row spans at least sin(fov_y)/height_px rad (the edge rows of a pinhole camera), so
    /// the uncovered band is under half a pixel for fov_y from 2° to 120° on screens up to
    /// 16384 pixels high. (The horizon itself is at infinity.)
    pub far_max_radius: f64,
}

impl Default for PatchParams {
    fn default() -> Self {
        Self::for_grid(1.0)
    }
}

impl PatchParams {
    /// Parameters for a displacement map of spacing `grid_spacing_m` (= L/N): the near patch
    /// is the power-of-two multiple of the spacing nearest to [`DEFAULT_NEAR_SIZE_M`] (in
    /// log scale, 2^2 to 2^15 cells), refined down to the grid spacing, its boundary cut into
    /// min(64, 2^K) segments per side.
    pub fn for_grid(grid_spacing_m: f64) -> Self {
        let levels = if grid_spacing_m.is_finite() && grid_spacing_m > 0.0 {
            ((DEFAULT_NEAR_SIZE_M / grid_spacing_m).log2().round().max(0.0) as u32)
                .clamp(2, MAX_NEAR_LEVELS)
        } else {
            9
        };
        Self {
            grid_spacing_m,
            near_size_m: grid_spacing_m * f64::from(1u32 << levels),
            max_depth: 2 * levels,
            split_threshold: 0.05,
            boundary_segments: 64.min(1 << levels),
            weight_taper_m: grid_spacing_m * f64::from(1u32 << levels) / 16.0,
            min_height_m: 0.5,
            far_segments: 128,
            far_ring_ratio: 1.05,
            far_min_radius: 1.0e-3,
            far_max_radius: 1.0e6,
        }
    }

    /// Parameters for the displacement map of a patch of side `patch_size_m` sampled
    /// `resolution` times per side ([`Self::for_grid`] of L/N).
    pub fn for_ocean(patch_size_m: f64, resolution: u32) -> Self {
        Self::for_grid(patch_size_m / f64::from(resolution.max(1)))
    }

    /// These parameters with the near patch grown so that it covers every point of the sea
    /// within `reach_m` of the eye (its half side at least `reach_m`): the next power-of-two
    /// multiple of the grid spacing, never smaller than today's side, at most
    /// 2^[`MAX_NEAR_LEVELS`] cells. The refinement goes down to the grid as before, the
    /// boundary keeps its `boundary_segments` and the taper stays a sixteenth of the side.
    /// A `reach_m` that is not finite and positive leaves the parameters as they are.
    pub fn with_reach(mut self, reach_m: f64) -> Self {
        let g = self.grid_spacing_m;
        let current = (self.near_size_m / g).log2().round();
        if !(reach_m.is_finite() && reach_m > 0.0 && g > 0.0 && current.is_finite()) {
            return self;
        }
        let wanted = (2.0 * reach_m / g).log2().ceil();
        let levels = wanted.max(current).min(f64::from(MAX_NEAR_LEVELS));
        if levels <= current {
            return self;
        }
        let levels = levels as u32;
        let side = g * f64::from(1u32 << levels);
        self.near_size_m = side;
        self.max_depth = 2 * levels;
        self.weight_taper_m = side / 16.0;
        self
    }

    /// Checks every field and returns the derived integer layout.
    pub(crate) fn validate(&self) -> Result<Layout> {
        positive("grid_spacing_m", self.grid_spacing_m)?;
        positive("near_size_m", self.near_size_m)?;
        let ratio = self.near_size_m / self.grid_spacing_m;
        let levels = ratio.log2().round();
        let power = levels.exp2();
        if !(2.0..=f64::from(MAX_NEAR_LEVELS)).contains(&levels)
            || (ratio - power).abs() > 1e-9 * power
        {
            return Err(invalid(
                "near_size_m",
                self.near_size_m,
                format!(
                    "must be grid_spacing_m ({}) times a power of two from 4 to 2^{MAX_NEAR_LEVELS}, \
                     so that the bintree's vertices fall on the displacement grid",
                    self.grid_spacing_m
                ),
            ));
        }
        let levels = levels as u32;
        if self.max_depth > 2 * levels {
            return Err(invalid(
                "max_depth",
                f64::from(self.max_depth),
                format!(
                    "must be at most 2·log2(near_size_m / grid_spacing_m) = {}: deeper levels \
                     would have edges shorter than the grid spacing",
                    2 * levels
                ),
            ));
        }
        let b = self.boundary_segments;
        if !b.is_power_of_two() || b > 1 << levels {
            return Err(invalid(
                "boundary_segments",
                f64::from(b),
                format!(
                    "must be a power of two from 1 to near_size_m / grid_spacing_m = {}",
                    1u32 << levels
                ),
            ));
        }
        let boundary_level = b.trailing_zeros();
        if self.max_depth < 2 * boundary_level {
            return Err(invalid(
                "max_depth",
                f64::from(self.max_depth),
                format!(
                    "must be at least 2·log2(boundary_segments) = {}: the boundary is cut at \
                     that depth",
                    2 * boundary_level
                ),
            ));
        }
        positive("split_threshold", self.split_threshold)?;
        if !(self.weight_taper_m.is_finite() && self.weight_taper_m >= 0.0) {
            return Err(invalid(
                "weight_taper_m",
                self.weight_taper_m,
                "must be finite and ≥ 0".into(),
            ));
        }
        positive("min_height_m", self.min_height_m)?;
        if self.min_height_m > MAX_HEIGHT_M {
            return Err(invalid(
                "min_height_m",
                self.min_height_m,
                format!("must be at most {MAX_HEIGHT_M} m"),
            ));
        }
        let m = self.far_segments;
        if m < 16 || !m.is_multiple_of(2) || m > 1 << 16 {
            return Err(invalid(
                "far_segments",
                f64::from(m),
                "must be even, from 16 to 65536".into(),
            ));
        }
        let q = self.far_ring_ratio;
        if !(q.is_finite() && q > 1.0 + 1e-6 && q <= 4.0) {
            return Err(invalid("far_ring_ratio", q, "must be in (1, 4]".into()));
        }
        positive("far_min_radius", self.far_min_radius)?;
        positive("far_max_radius", self.far_max_radius)?;
        let rings = (self.far_max_radius / self.far_min_radius).ln() / q.ln();
        if !(2.0..=1e5).contains(&rings) {
            return Err(invalid(
                "far_max_radius",
                self.far_max_radius,
                format!(
                    "must exceed far_min_radius ({}) by at least two rings and at most 1e5 rings \
                     of ratio {q}",
                    self.far_min_radius
                ),
            ));
        }
        if self.far_max_radius * MAX_HEIGHT_M > 1e30 {
            return Err(invalid(
                "far_max_radius",
                self.far_max_radius,
                format!("times the largest height {MAX_HEIGHT_M} m must stay below 1e30 m"),
            ));
        }
        // The first kept far ring must be far enough out for the stitch at the lowest height,
        // with one more ring beyond it, for the worst eye position (half a cell off centre).
        let half = 0.5 * self.grid_spacing_m * power;
        let off = 0.5 * self.grid_spacing_m;
        let Some(needed) = stitch_radius(half, [off, off], m) else {
            return Err(invalid(
                "far_segments",
                f64::from(m),
                format!(
                    "is too coarse to stitch to a near patch of {} cells: an outer step of \
                     360°/M plus the corner's angle off the side's normal reaches 90°",
                    power
                ),
            ));
        };
        let reach = self.far_max_radius / q * self.min_height_m;
        if reach < STITCH_CLEARANCE * needed {
            return Err(invalid(
                "far_max_radius",
                self.far_max_radius,
                format!(
                    "times min_height_m must reach past the near patch: at least {} (units of \
                     H)",
                    STITCH_CLEARANCE * needed * q / self.min_height_m
                ),
            ));
        }
        Ok(Layout { grid: self.grid_spacing_m, half_cells: 1 << (levels - 1), boundary_level })
    }
}

/// The integer layout of a validated near patch.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Layout {
    /// The grid spacing g, metres.
    pub grid: f64,
    /// h = 2^(K−1): the near patch spans grid coordinates [−h, h] on both axes.
    pub half_cells: i32,
    /// b: the boundary is cut into 2^b edges per side.
    pub boundary_level: u32,
}

impl Layout {
    /// Length of a boundary edge in grid cells.
    pub fn boundary_step(&self) -> i32 {
        (2 * self.half_cells) >> self.boundary_level
    }
}

/// The smallest radius about the eye at which a ring of `segments` vertices can be zipped to
/// the boundary of the square [−half, half]² (the eye at `eye` inside it) with every
/// triangle counter-clockwise; `None` when no radius can.
///
/// Zipping by azimuth (`mesh.rs`), a triangle with its base on the ring has its apex, a
/// boundary vertex, inside the ring's chord once the ring's inscribed radius ρ·cos(π/M)
/// exceeds the farthest corner. A triangle with its base on a side s of the square (at
/// distance D_s from the eye, corners at most θ_s off its normal as seen from the eye) has
/// its apex, a ring vertex, within one ring step 2π/M of the base's end in azimuth, hence at
/// most θ_s + 2π/M off the normal, and beyond the side's line once
/// ρ·cos(θ_s + 2π/M) > D_s. A triangulation of the annulus whose triangles are all
/// counter-clockwise covers it exactly once.
pub fn stitch_radius(half: f64, eye: [f64; 2], segments: u32) -> Option<f64> {
    let step = 2.0 * PI / f64::from(segments);
    let corner = [-half, half]
        .iter()
        .flat_map(|&x| [-half, half].map(|z| (x - eye[0]).hypot(z - eye[1])))
        .fold(0.0, f64::max);
    let mut needed = corner / (0.5 * step).cos();
    // Sides x = ±half (along z) and z = ±half (along x).
    for (normal, along) in [(eye[0], eye[1]), (eye[1], eye[0])] {
        let reach_along = (half + along.abs()).max(half - along.abs());
        for distance in [half - normal, half + normal] {
            let theta = (reach_along / distance).atan() + step;
            if distance <= 0.0 || distance.is_nan() || theta >= 0.5 * PI - 1e-3 {
                return None;
            }
            needed = needed.max(distance / theta.cos());
        }
    }
    Some(needed)
}

pub(crate) fn invalid(name: &'static str, value: f64, reason: String) -> Error {
    Error::InvalidParameter { name, value, reason }
}

fn positive(name: &'static str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(invalid(name, value, "must be finite and > 0".into()))
    }
}
