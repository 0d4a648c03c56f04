//! Surface `clipmap` (issue 14, seed 002): the levels the water pass draws (the CPU mirror of
//! `vs_clipmap`, whose arithmetic the GPU's matches: the cross-check scene
//! `reference/scenes/clipmap_storm.toml`) are one watertight sheet — no crack, no T-junction,
//! no overlap — for a sweep of eyes including moves of a fraction of a quad; a world-fixed
//! point keeps its height while the eye moves within a level; the sea reaches the horizon.

use std::collections::{HashMap, HashSet};

use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::{Scene, SceneSource};
use ocean_cpu::frame::FrameBuffers;
use ocean_cpu::shaders::water::{self, VertexOut};

fn scene(waves: &str, eye: [f64; 3], extra: &str) -> Scene {
    let text = format!(
        "[techniques]\nsurface = \"clipmap\"\nwaves = \"{waves}\"\nfar_field = \"mip\"\n\
         [ocean]\nwind_speed = 12.0\npatch_size_m = 64.0\nresolution = 64\nbump_resolution = 64\n\
         choppiness = 1.0\ntime_s = 3.0\n\
         [gerstner]\ncount = 24\nmedian_wavelength_m = 6.0\nmedian_amplitude_m = 0.08\n\
         choppiness = 0.8\n\
         [camera]\nposition = [{}, {}, {}]\nlook_at = [{}, 0.0, {}]\nwidth = 32\nheight = 18\n\
         {extra}",
        eye[0],
        eye[1],
        eye[2],
        eye[0] + 3.0,
        eye[2] - 40.0
    );
    Scene::from_toml(&text, SceneSource::Text).expect("scene")
}

fn render(scene: &Scene) -> FrameBuffers {
    let plan = FramePlan::new(scene, OutputKind::Hdr);
    ocean_cpu::render::render_scene_with_plan(scene, plan, &mut |_| {}).expect("render").buffers
}

/// Every vertex `vs_clipmap` makes for the frame's uniforms `u` (three per triangle).
fn vertices(fb: &FrameBuffers, u: &ocean_core::frame::FrameUniforms) -> Vec<VertexOut> {
    let unbound = water::Unbound::default();
    let b = water::Bindings::vertex_stage(u, &fb.displacement, &unbound);
    let c = &u.clip;
    let n = c.vertex_count();
    assert!(n > 0, "the frame has no clipmap");
    (0..n).map(|k| water::vs_clipmap(k, &b)).collect()
}

/// What the triangles make: vertices welded where their displaced positions are the same
/// bits (as the rasterizer sees them), zero-area triangles (two equal corners) dropped.
#[derive(Debug)]
struct Sheet {
    vertices: usize,
    edges: usize,
    faces: usize,
    /// Edges of one face only.
    boundary_edges: usize,
    /// Closed loops those edges make.
    boundary_loops: usize,
    /// Σ signed area of the undisplaced triangles (units of level 0's quad, squared).
    area: f64,
}

impl Sheet {
    fn of(verts: &[VertexOut], cell_m: f32) -> Result<Self, String> {
        let key = |v: &VertexOut| [v.rel.x.to_bits(), v.rel.y.to_bits(), v.rel.z.to_bits()];
        let mut ids: HashMap<[u32; 3], usize> = HashMap::new();
        let mut edges: HashMap<(usize, usize), u32> = HashMap::new();
        let (mut faces, mut area) = (0, 0.0);
        for t in verts.chunks(3) {
            let k = [key(&t[0]), key(&t[1]), key(&t[2])];
            if k[0] == k[1] || k[1] == k[2] || k[0] == k[2] {
                continue;
            }
            let p = t.iter().map(|v| [f64::from(v.pos.x), f64::from(v.pos.y)]).collect::<Vec<_>>();
            let a = 0.5
                * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                    - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]));
            // Zero area on the plane is allowed: where one axis is morphed and the other is
            // not, a triangle's corners line up along an edge, and displaced it fills the gap
            // between that edge and the two it spans (as Asirvatham & Hoppe's zero-area
            // perimeter triangles do).
            if a < 0.0 {
                return Err(format!("triangle {t:?} is turned over (area {a})"));
            }
            area += a / f64::from(cell_m * cell_m);
            faces += 1;
            let mut id = [0; 3];
            for (c, kc) in k.iter().enumerate() {
                let n = ids.len();
                id[c] = *ids.entry(*kc).or_insert(n);
            }
            for (a, b) in [(id[0], id[1]), (id[1], id[2]), (id[2], id[0])] {
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        if let Some((e, n)) = edges.iter().find(|(_, n)| **n > 2) {
            return Err(format!("edge {e:?} is shared by {n} triangles"));
        }
        let boundary: Vec<(usize, usize)> =
            edges.iter().filter(|(_, n)| **n == 1).map(|(e, _)| *e).collect();
        // Loops: components of the boundary graph, each vertex of degree 2.
        let mut adjacent: HashMap<usize, Vec<usize>> = HashMap::new();
        for &(a, b) in &boundary {
            adjacent.entry(a).or_default().push(b);
            adjacent.entry(b).or_default().push(a);
        }
        if let Some((v, n)) = adjacent.iter().find(|(_, n)| n.len() != 2) {
            return Err(format!("boundary vertex {v} has {} boundary edges", n.len()));
        }
        let mut seen = HashSet::new();
        let mut loops = 0;
        for &start in adjacent.keys() {
            if seen.insert(start) {
                loops += 1;
                let mut stack = vec![start];
                while let Some(v) = stack.pop() {
                    for &w in &adjacent[&v] {
                        if seen.insert(w) {
                            stack.push(w);
                        }
                    }
                }
            }
        }
        let vertices = edges.keys().flat_map(|&(a, b)| [a, b]).collect::<HashSet<_>>().len();
        Ok(Self {
            vertices,
            edges: edges.len(),
            faces,
            boundary_edges: boundary.len(),
            boundary_loops: loops,
            area,
        })
    }

    /// A disc: V − E + F = 1, one boundary loop, the outer square's area.
    fn check_disc(&self, u: &ocean_core::frame::FrameUniforms) -> Result<(), String> {
        let c = &u.clip;
        let side = f64::from(c.cells) * f64::from(c.eye[c.levels as usize - 1][2]);
        let euler = self.vertices as i64 - self.edges as i64 + self.faces as i64;
        if euler != 1 || self.boundary_loops != 1 {
            return Err(format!("not a disc: V − E + F = {euler}, {self:?}"));
        }
        // The outer edge of the coarsest level at α = 1: n/2 edges a side.
        if self.boundary_edges != 2 * c.cells as usize {
            return Err(format!("outer boundary of {} edges, not 2n", self.boundary_edges));
        }
        // The triangles' areas are summed in f64 from f32 positions, each exact to its
        // vertices' rounding (rel 6e-8 of coordinates up to the outer half side); 1e-6 of the
        // square is well above that and far below a missing or doubled quad of the outer
        // levels. A hole near the eye is too small for any area check (a level-0 quad is
        // 1/(n·2^(L−1))² of the square): V − E + F and the boundary counts above catch it.
        if (self.area - side * side).abs() > 1e-6 * side * side {
            return Err(format!("area {} ≠ the outer square's {}", self.area, side * side));
        }
        Ok(())
    }
}

const EYES: [[f64; 3]; 8] = [
    [0.0, 5.0, 0.0],
    [0.1, 5.0, 0.03],
    [0.37, 5.0, -0.21],
    [0.5, 5.0, 0.5],
    [0.99, 2.0, -1.49],
    [12345.6, 30.0, -9876.5],
    [-3.3, -4.0, 7.75],
    [250.25, 0.3, 1.0e5],
];

#[test]
fn levels_are_one_watertight_sheet_for_a_sweep_of_eyes() {
    for (i, eye) in EYES.iter().enumerate() {
        // Gerstner waves for every eye, the FFT map for two, and both cell counts.
        let waves = if i % 4 == 1 { "fft" } else { "gerstner" };
        let cells = if i % 2 == 0 { 16 } else { 24 };
        let s = scene(waves, *eye, &format!("[quality]\nclipmap_cells = {cells}\n"));
        let fb = render(&s);
        let u = fb.uniforms;
        let verts = vertices(&fb, &u);
        let sheet = Sheet::of(&verts, u.clip.cell_m).unwrap_or_else(|e| panic!("{eye:?}: {e}"));
        sheet.check_disc(&u).unwrap_or_else(|e| panic!("{waves} eye {eye:?}: {e}"));
        // The displacement is there: the sheet is not the flat plane.
        let moved = verts.iter().filter(|v| v.rel.y != -(eye[1] as f32)).count();
        assert!(moved > verts.len() / 10, "{waves} {eye:?}: {moved} of {} moved", verts.len());
    }
}

#[test]
fn without_the_morph_or_with_a_misplaced_hole_the_check_fails() {
    let s = scene("gerstner", EYES[2], "[quality]\nclipmap_cells = 16\n");
    let fb = render(&s);
    // No morph: the odd vertices of each level's boundary are T-junctions on the next level's
    // edges (cracks once displaced).
    let mut u = fb.uniforms;
    u.clip.inv_band = 0.0;
    let e = Sheet::of(&vertices(&fb, &u), u.clip.cell_m).and_then(|s| s.check_disc(&u));
    assert!(e.is_err(), "no morph passed: {e:?}");
    // Level 3's hole one quad off: overlap on one side, a gap on the other.
    let mut u = fb.uniforms;
    u.clip.level[3][2] += 1;
    let e = Sheet::of(&vertices(&fb, &u), u.clip.cell_m).and_then(|s| s.check_disc(&u));
    assert!(e.is_err(), "a misplaced hole passed: {e:?}");
}

/// World lattice point (units of level 0's quad) → height, for the level-0 vertices that are
/// not morphed (α = 0, more than a quad inside the band's start).
fn level0_heights(fb: &FrameBuffers, eye: [f64; 3]) -> HashMap<[i64; 2], f32> {
    let u = fb.uniforms;
    let c = u.clip;
    let n = c.cells as usize;
    let s0 = f64::from(c.cell_m);
    let origin =
        [eye[0] + f64::from(u.tiling.mesh_offset[0]), eye[2] + f64::from(u.tiling.mesh_offset[1])];
    let mut out = HashMap::new();
    for v in vertices(fb, &u).iter().take(6 * n * n) {
        let w = [origin[0] + f64::from(v.pos.x), origin[1] + f64::from(v.pos.y)];
        let d = ((w[0] - eye[0]).abs()).max((w[1] - eye[2]).abs()) / s0;
        if d < f64::from(c.morph_start) - 1.0 {
            let g = w.map(|x| (x / s0).round());
            // Not swimming: an unmorphed vertex sits on the world lattice. Its position is
            // the f32 offset from the mesh's reference point plus that point in f64: within
            // level 0's few metres the offset's ulp is ~5e-7 m, so 1e-6 m is the f32 rounding;
            // a swimming vertex is off by a fraction of the cell (≥ 1e-2 m here).
            assert!(
                (g[0] * s0 - w[0]).abs() < 1e-6 && (g[1] * s0 - w[1]).abs() < 1e-6,
                "{w:?} is off the lattice"
            );
            out.insert(g.map(|x| x as i64), v.rel.y + eye[1] as f32);
        }
    }
    out
}

#[test]
fn a_world_point_keeps_its_height_while_the_eye_moves_within_a_level() {
    let base = [2.0, 4.0, -1.0];
    let h0 = level0_heights(&render(&scene("gerstner", base, "")), base);
    // A tenth of a quad, then several quads (the reference point moves with the eye).
    for shift in [0.05, 0.3, 2.7] {
        let eye = [base[0] + shift, base[1], base[2] - 0.5 * shift];
        let h1 = level0_heights(&render(&scene("gerstner", eye, "")), eye);
        let common: Vec<_> = h0.keys().filter(|k| h1.contains_key(*k)).collect();
        assert!(common.len() > 100, "shift {shift}: {} common points", common.len());
        let worst = common.iter().map(|k| (h0[*k] - h1[*k]).abs()).fold(0.0f32, f32::max);
        // 1e-5 m is the height-query bound. The height is an f32 sum of the waves at
        // a phase whose argument is formed from the same world point (exact lattice
        // coordinates): the rounding of the f32 phase (ulp ~5e-7 rad at a few radians) times
        // A·k per wave is ~1e-7 m, summed over the waves ~1e-6 m; a point that swam by a tenth
        // of a quad moves by ~1e-2 m (the negative control below).
        assert!(worst <= 1e-5, "shift {shift}: a point's height moved by {worst} m");
    }
    // Negative control: the same points a hundredth of a second later do move.
    let mut later = scene("gerstner", base, "");
    later.ocean.time_s += 0.01;
    let h2 = level0_heights(&render(&later), base);
    let worst = h0.keys().map(|k| (h0[k] - h2[k]).abs()).fold(0.0f32, f32::max);
    assert!(worst > 1e-4, "time moved nothing: {worst}");
}

/// Rows below the horizon (a level view from `height` m) that hold sky pixels.
fn sky_rows_below_the_horizon(height: f64, extra: &str) -> Vec<u32> {
    let text = format!(
        "[techniques]\nsurface = \"clipmap\"\nwaves = \"gerstner\"\nfar_field = \"mip\"\n\
         [camera]\nposition = [0.0, {height}, 0.0]\nlook_at = [0.0, {height}, -100.0]\n\
         width = 8\nheight = 720\n{extra}"
    );
    let s = Scene::from_toml(&text, SceneSource::Text).expect("scene");
    let fb = render(&s);
    let t = &fb.hdr;
    // The horizon is the image's middle (row 360's top edge); rows from 361 on see the sea
    // at least 1.5 pixels (2.2 mrad) below it.
    (361..t.height)
        .filter(|&y| (0..t.width).any(|x| t.depth[(y * t.width + x) as usize] <= 0.0))
        .collect()
}

#[test]
fn the_sea_reaches_the_horizon() {
    for h in [0.3, 2.0, 40.0, 5000.0] {
        let rows = sky_rows_below_the_horizon(h, "");
        assert!(rows.is_empty(), "eye at {h} m: sky in rows {rows:?}");
    }
    // Negative control: 1 cm quads, 16 a level, stop 24 levels later at 590 km, which an eye
    // 5 km up sees 8.5 mrad (about 6 rows) below the horizon.
    let rows = sky_rows_below_the_horizon(
        5000.0,
        "[quality]\nclipmap_cell_m = 0.01\nclipmap_cells = 16\n",
    );
    assert!(rows.len() >= 3, "a short clipmap reached the horizon: {rows:?}");
}
