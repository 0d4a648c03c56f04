//! The view-dependent water mesh (seed 000 §3): conformity (no T-junctions) with exact
//! predicates, watertightness and coverage to the horizon through the software rasterizer,
//! displacement weights, height-dependent LOD, determinism and degenerate inputs.
//!
//! Every checker is run once against a deliberately broken mesh and must reject it.
//! `cargo test --release --test geometry -- --nocapture` prints the measured figures.

use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI};

use ocean_core::geometry::{FarPatch, NearPatch, PatchParams, WaterMesh, WaterVertex};
use ocean_cpu::raster::{BlendMode, CompareFunction, CullMode, RasterState, RenderTarget, Vertex};

// ---------------------------------------------------------------------------------------------
// Exact predicates on f32 points (x, z).

/// s + e = a + b exactly (Knuth's TwoSum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// The exact sign of a sum of f64 terms (Shewchuk's Grow-Expansion: the expansion's most
/// significant non-zero component has the sign of the sum).
fn exact_sign(terms: &[f64; 6]) -> i32 {
    let mut e = [0.0f64; 6];
    for (len, &t) in terms.iter().enumerate() {
        let mut q = t;
        for c in e.iter_mut().take(len) {
            let (s, err) = two_sum(q, *c);
            *c = err;
            q = s;
        }
        e[len] = q;
    }
    e.iter().rev().find(|&&c| c != 0.0).map_or(0, |&c| if c > 0.0 { 1 } else { -1 })
}

/// The exact sign of the y component of (b − a) × (c − a) for points stored as (x, z):
/// +1 when a, b, c are counter-clockwise seen from above. Every product of two f32 is exact
/// in f64, and the a_x·a_z terms cancel, leaving six exact products.
fn orient_up(a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> i32 {
    let [ax, az, bx, bz, cx, cz] = [a[0], a[1], b[0], b[1], c[0], c[1]].map(f64::from);
    exact_sign(&[bz * cx, -bz * ax, -az * cx, -bx * cz, bx * az, ax * cz])
}

/// Whether `p` lies strictly inside the segment a–b (exactly).
fn strictly_inside(p: [f32; 2], a: [f32; 2], b: [f32; 2]) -> bool {
    let between = |k: usize| (a[k].min(b[k]) <= p[k]) && (p[k] <= a[k].max(b[k]));
    between(0) && between(1) && p != a && p != b && orient_up(a, b, p) == 0
}

#[test]
fn exact_orientation_sees_one_ulp() {
    let a = [1.0e6f32, 3.0];
    let b = [3.0e6f32, 9.0];
    let c = [2.0e6f32, 6.0]; // on the line a–b
    assert_eq!(orient_up(a, b, c), 0);
    assert!(strictly_inside(c, a, b));
    let up = [c[0], f32::from_bits(6.0f32.to_bits() + 1)];
    let down = [c[0], f32::from_bits(6.0f32.to_bits() - 1)];
    assert_eq!(orient_up(a, b, up) * orient_up(a, b, down), -1);
    assert!(!strictly_inside(up, a, b) && !strictly_inside(down, a, b));
    // Counter-clockwise seen from above: +z then +x.
    assert_eq!(orient_up([0.0, 0.0], [0.0, 1.0], [1.0, 0.0]), 1);
    assert_eq!(orient_up([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]), -1);
    // Cancellation the naive f64 formula gets wrong: huge and tiny coordinates.
    let tiny = [1.0e-30f32, 1.0e-30];
    assert_eq!(orient_up([0.0, 0.0], [1.0e30, 1.0e30], tiny), 0);
    let off = [1.0e-30f32, f32::from_bits(1.0e-30f32.to_bits() + 1)];
    assert_ne!(orient_up([0.0, 0.0], [1.0e30, 1.0e30], off), 0);
}

// ---------------------------------------------------------------------------------------------
// Conformity checker.

/// Checks that the mesh is one conforming, consistently oriented triangulation of a disc:
/// every triangle strictly counter-clockwise seen from above; no two vertices at the same
/// position; every edge used once or twice, twice only in opposite directions; the edges
/// used once form a single closed loop (the outer boundary); no vertex lies strictly inside
/// a boundary edge (a T-junction); V − E + F = 1.
fn check_conforming(vertices: &[WaterVertex], indices: &[[u32; 3]]) -> Result<(), String> {
    let pos = |i: u32| vertices[i as usize].pos;
    let mut seen = HashMap::new();
    for (i, v) in vertices.iter().enumerate() {
        if let Some(j) = seen.insert(v.pos.map(f32::to_bits), i) {
            return Err(format!("vertices {j} and {i} both at {:?}", v.pos));
        }
    }
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for (t, tri) in indices.iter().enumerate() {
        if tri.iter().any(|&i| i as usize >= vertices.len()) {
            return Err(format!("triangle {t} indexes past the vertices"));
        }
        let [a, b, c] = tri.map(pos);
        if orient_up(a, b, c) <= 0 {
            return Err(format!(
                "triangle {t} {tri:?} is not counter-clockwise: {a:?} {b:?} {c:?}"
            ));
        }
        for k in 0..3 {
            let e = (tri[k], tri[(k + 1) % 3]);
            if directed.insert(e, t).is_some() {
                return Err(format!("directed edge {e:?} used twice (overlap or flip)"));
            }
        }
    }
    // Edges used once: their reverse is absent.
    let open: Vec<(u32, u32)> =
        directed.keys().copied().filter(|&(a, b)| !directed.contains_key(&(b, a))).collect();
    let undirected = directed.len() - (directed.len() - open.len()) / 2;
    let mut next: HashMap<u32, u32> = HashMap::new();
    for &(a, b) in &open {
        if next.insert(a, b).is_some() {
            return Err(format!("boundary vertex {a} starts two boundary edges"));
        }
    }
    let start = open.iter().map(|e| e.0).min().ok_or("no boundary")?;
    let (mut v, mut steps) = (start, 0);
    loop {
        v = *next.get(&v).ok_or(format!("boundary breaks at vertex {v}"))?;
        steps += 1;
        if v == start {
            break;
        }
        if steps > open.len() {
            return Err("boundary walk does not close".into());
        }
    }
    if steps != open.len() {
        return Err(format!(
            "boundary edges form several loops ({} edges, the first loop has {steps})",
            open.len()
        ));
    }
    let ends: Vec<u32> = next.keys().copied().collect();
    for &(a, b) in &open {
        for &p in &ends {
            if p != a && p != b && strictly_inside(pos(p), pos(a), pos(b)) {
                return Err(format!("T-junction: vertex {p} inside boundary edge {a}–{b}"));
            }
        }
    }
    let used = {
        let mut u = vec![false; vertices.len()];
        indices.iter().flatten().for_each(|&i| u[i as usize] = true);
        u.iter().filter(|&&x| x).count()
    };
    let euler = used as i64 - undirected as i64 + indices.len() as i64;
    if euler != 1 {
        return Err(format!("V − E + F = {euler}, not a disc"));
    }
    Ok(())
}

/// Splits near triangle `t` at its hypotenuse midpoint without splitting the neighbour
/// across it: a T-junction (what a missing forced split leaves).
fn unforced_split(mesh: &WaterMesh, t: usize) -> (Vec<WaterVertex>, Vec<[u32; 3]>) {
    let (mut v, mut ix) = (mesh.vertices.clone(), mesh.indices.clone());
    let [a, l, r] = ix[t];
    let (pl, pr) = (v[l as usize].pos, v[r as usize].pos);
    v.push(WaterVertex { pos: [(pl[0] + pr[0]) / 2.0, (pl[1] + pr[1]) / 2.0], weight: 1.0 });
    let m = (v.len() - 1) as u32;
    ix[t] = [m, a, l];
    ix.push([m, r, a]);
    (v, ix)
}

// ---------------------------------------------------------------------------------------------
// Views.

/// A look-at camera with world up +y (a fallback up of +z when looking straight up or down).
#[derive(Clone, Copy, Debug)]
struct Camera {
    eye: [f64; 3],
    forward: [f64; 3],
    fov_y: f64,
    width: u32,
    height: u32,
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / n)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl Camera {
    fn new(eye: [f64; 3], yaw_deg: f64, pitch_deg: f64) -> Self {
        let (y, p) = (yaw_deg.to_radians(), pitch_deg.to_radians());
        let forward = [y.sin() * p.cos(), p.sin(), y.cos() * p.cos()];
        Self { eye, forward, fov_y: 55f64.to_radians(), width: 192, height: 128 }
    }

    fn aspect(&self) -> f64 {
        f64::from(self.width) / f64::from(self.height)
    }

    /// (right, up, forward), orthonormal.
    fn basis(&self) -> [[f64; 3]; 3] {
        let f = normalize(self.forward);
        let up = if f[0].hypot(f[2]) > 1e-9 { [0.0, 1.0, 0.0] } else { [0.0, 0.0, 1.0] };
        let r = normalize(cross(f, up));
        [r, cross(r, f), f]
    }

    /// The view ray through the point (sx, sy) of the framebuffer (y down).
    fn ray(&self, sx: f64, sy: f64) -> [f64; 3] {
        let [r, u, f] = self.basis();
        let t = (0.5 * self.fov_y).tan();
        let x = (2.0 * sx / f64::from(self.width) - 1.0) * t * self.aspect();
        let y = (1.0 - 2.0 * sy / f64::from(self.height)) * t;
        [0, 1, 2].map(|k| f[k] + x * r[k] + y * u[k])
    }

    /// Horizontal distance from the eye at which the ray through (sx, sy) meets y = 0.
    fn ground_distance(&self, sx: f64, sy: f64) -> Option<f64> {
        let d = self.ray(sx, sy);
        let t = -self.eye[1] / d[1];
        (t > 0.0 && t.is_finite()).then(|| t * d[0].hypot(d[2]))
    }

    /// Clip-space vertices of the mesh (camera-relative f32, as a renderer draws them): a
    /// reversed infinite perspective, z_clip = near, w = depth.
    fn project(&self, mesh: &WaterMesh) -> Vec<Vertex<0>> {
        let [r, u, f] = self.basis();
        let focal = 1.0 / (0.5 * self.fov_y).tan();
        let offset = [mesh.origin[0] - self.eye[0], mesh.origin[1] - self.eye[2]];
        mesh.vertices
            .iter()
            .map(|v| {
                // What the vertex shader gets: an f32 camera-relative position.
                let p = [
                    (f64::from(v.pos[0]) + offset[0]) as f32,
                    -self.eye[1] as f32,
                    (f64::from(v.pos[1]) + offset[1]) as f32,
                ]
                .map(f64::from);
                let (x, y, z) = (dot(p, r), dot(p, u), dot(p, f));
                let clip = [x * focal / self.aspect(), y * focal, 1e-3, z];
                Vertex::new(clip.map(|c| c as f32), [])
            })
            .collect()
    }

    fn mesh(&self, params: &PatchParams) -> WaterMesh {
        WaterMesh::for_view(params, self.eye, self.forward, self.fov_y, self.aspect())
            .expect("a valid view")
    }
}

/// How many times each pixel is covered (additive blending, no depth test).
fn coverage(cam: &Camera, mesh: &WaterMesh, indices: &[[u32; 3]], cull: CullMode) -> Vec<u32> {
    let mut target = RenderTarget::new(cam.width, cam.height);
    let state = RasterState {
        cull_mode: cull,
        depth_compare: CompareFunction::Always,
        depth_write: false,
        blend: BlendMode::Add,
        ..RasterState::default()
    };
    let vertices = cam.project(mesh);
    ocean_cpu::raster::draw_indexed(&mut target, &state, &vertices, indices, |_| {
        Some([1.0, 0.0, 0.0, 0.0])
    });
    target.color.iter().map(|c| c[0] as u32).collect()
}

/// Checks a coverage count against the view: a pixel whose centre ray, and the rays a
/// quarter pixel above and below it, all meet the plane within `reach` metres must be
/// covered exactly once; one where none of the three meets the plane at all, never. The
/// rest — pixels whose centre lies within a quarter pixel of the horizon line (or of the
/// mesh's outer ring at `reach`, within 1e-6 rad of the horizon) — must be covered at most
/// once. Returns the counts (certain pixels, band pixels).
fn check_coverage(cam: &Camera, counts: &[u32], reach: f64) -> Result<(usize, usize), String> {
    let (mut certain, mut band) = (0, 0);
    for py in 0..cam.height {
        for px in 0..cam.width {
            let c = counts[(py * cam.width + px) as usize];
            let sx = f64::from(px) + 0.5;
            let hits: Vec<Option<f64>> = [-0.25, 0.0, 0.25]
                .iter()
                .map(|dy| cam.ground_distance(sx, f64::from(py) + 0.5 + dy))
                .collect();
            if hits.iter().all(|h| h.is_some_and(|d| d < reach)) {
                certain += 1;
                if c != 1 {
                    return Err(format!("pixel ({px}, {py}) covered {c} times, not once"));
                }
            } else if hits.iter().all(Option::is_none) {
                if c != 0 {
                    return Err(format!("pixel ({px}, {py}) above the horizon covered {c} times"));
                }
            } else {
                band += 1;
                if c > 1 {
                    return Err(format!("pixel ({px}, {py}) at the horizon covered {c} times"));
                }
            }
        }
    }
    Ok((certain, band))
}

/// Where the mesh certainly reaches: the outer ring's inscribed circle, less a margin.
fn reach(mesh: &WaterMesh, params: &PatchParams) -> f64 {
    mesh.far_outer_radius_m * (PI / f64::from(params.far_segments)).cos() * 0.999
}

/// Heights, pitches and yaws of the sweep.
const HEIGHTS: [f64; 6] = [0.5, 2.0, 10.0, 100.0, 1000.0, 10_000.0];

fn sweep() -> Vec<Camera> {
    let mut cams = Vec::new();
    for (i, &h) in HEIGHTS.iter().enumerate() {
        for (k, &pitch) in [-90.0, -60.0, -20.0, -3.0, 0.0, 25.0].iter().enumerate() {
            let yaw = [0.0, 37.0, 90.0, 161.0, 245.0, 300.0][(i + k) % 6];
            let x = [0.0, 0.37, -1.2e6, 2.5e5][(i + 2 * k) % 4];
            let z = [0.0, -3.7, 8.1e5, 1.1e6][(2 * i + k) % 4];
            cams.push(Camera::new([x, h, z], yaw, pitch));
            // Under water, looking the mirrored way.
            cams.push(Camera::new([x, -h, z], yaw + 11.0, -pitch));
        }
    }
    cams
}

// ---------------------------------------------------------------------------------------------
// Tests.

#[test]
fn union_mesh_is_conforming_for_every_view() {
    let params = PatchParams::default();
    for cam in sweep() {
        let mesh = cam.mesh(&params);
        if let Err(e) = check_conforming(&mesh.vertices, &mesh.indices) {
            panic!("{cam:?}: {e}");
        }
    }
    // Exactly above and below the plane, and with the eye on it.
    for pitch in [-90.0, 90.0, 0.0] {
        let mesh = Camera::new([5.5, 0.0, -7.25], 12.0, pitch).mesh(&params);
        check_conforming(&mesh.vertices, &mesh.indices).unwrap();
    }
}

#[test]
fn conformity_checker_rejects_broken_meshes() {
    let params = PatchParams::default();
    let mesh = Camera::new([3.0, 2.0, -1.0], 30.0, -20.0).mesh(&params);
    check_conforming(&mesh.vertices, &mesh.indices).unwrap();
    // A T-junction: split a near triangle whose hypotenuse is shared, without its neighbour.
    let t = (0..mesh.near_triangles)
        .find(|&t| {
            let [_, l, r] = mesh.indices[t];
            mesh.indices.iter().any(|o| (0..3).any(|k| o[k] == r && o[(k + 1) % 3] == l))
        })
        .unwrap();
    let (v, ix) = unforced_split(&mesh, t);
    let err = check_conforming(&v, &ix).unwrap_err();
    assert!(err.contains("T-junction") || err.contains("loops"), "{err}");
    // A duplicated triangle, a flipped one, a duplicated vertex, a missing triangle.
    let mut ix = mesh.indices.clone();
    ix.push(ix[5]);
    assert!(check_conforming(&mesh.vertices, &ix).is_err());
    let mut ix = mesh.indices.clone();
    ix[7].swap(1, 2);
    assert!(check_conforming(&mesh.vertices, &ix).is_err());
    let mut v = mesh.vertices.clone();
    v.push(v[3]);
    assert!(check_conforming(&v, &mesh.indices).is_err());
    let mut ix = mesh.indices.clone();
    ix.remove(mesh.near_triangles / 2);
    assert!(check_conforming(&mesh.vertices, &ix).is_err());
}

#[test]
fn near_boundary_is_shared_bit_exactly_with_the_far_patch() {
    // The near patch's boundary edges are the strip's inner edges, with the same vertex
    // indices (hence the same f32 positions): each appears once in the near triangles and
    // once, reversed, in the strip.
    let params = PatchParams::default();
    let mesh = Camera::new([1.0e6 + 0.3, 4.0, -2.0e6 - 0.4], 200.0, -10.0).mesh(&params);
    let near_edges: HashMap<(u32, u32), ()> = mesh.indices[..mesh.near_triangles]
        .iter()
        .flat_map(|t| (0..3).map(move |k| ((t[k], t[(k + 1) % 3]), ())))
        .collect();
    let boundary: Vec<(u32, u32)> =
        near_edges.keys().copied().filter(|&(a, b)| !near_edges.contains_key(&(b, a))).collect();
    assert_eq!(boundary.len(), 4 * params.boundary_segments as usize);
    let strip = &mesh.indices[mesh.near_triangles..mesh.near_triangles + mesh.stitch_triangles];
    for &(a, b) in &boundary {
        let found = strip.iter().any(|t| (0..3).any(|k| t[k] == b && t[(k + 1) % 3] == a));
        assert!(found, "boundary edge {a}–{b} not stitched");
    }
    // The boundary is the square |x| = S/2 or |z| = S/2, exactly.
    let half = (0.5 * params.near_size_m) as f32;
    for &(a, _) in &boundary {
        let p = mesh.vertices[a as usize].pos;
        assert!(p[0].abs() == half || p[1].abs() == half, "{p:?}");
    }
}

#[test]
fn rasterised_union_covers_every_ground_pixel_exactly_once() {
    let params = PatchParams::default();
    let views = [
        Camera::new([0.3, 2.0, -0.2], 20.0, -25.0),
        Camera::new([1.0e6 + 0.49, 30.0, 3.0e5], 140.0, -8.0),
        Camera::new([-7.0, 0.5, 4.0], 250.0, -2.0),
        Camera::new([0.0, 300.0, 0.0], 300.0, -50.0),
    ];
    for cam in views {
        let mesh = cam.mesh(&params);
        // Back faces culled: the mesh faces up, so nothing may disappear.
        let counts = coverage(&cam, &mesh, &mesh.indices, CullMode::Back);
        let (certain, band) = check_coverage(&cam, &counts, reach(&mesh, &params))
            .unwrap_or_else(|e| panic!("{cam:?}: {e}"));
        assert!(certain > (cam.width * cam.height / 4) as usize, "{cam:?}: {certain}");
        println!("{cam:?}: {certain} pixels once, {band} in the horizon band");
    }
}

#[test]
fn coverage_checker_finds_a_hole_and_a_double_cover() {
    let params = PatchParams::default();
    let cam = Camera::new([0.3, 2.0, -0.2], 20.0, -25.0);
    let mesh = cam.mesh(&params);
    // Remove the near triangle straight ahead of the eye, 6 m out.
    let target = [0.3 + 6.0 * 20f64.to_radians().sin(), -0.2 + 6.0 * 20f64.to_radians().cos()];
    let hit = mesh.indices[..mesh.near_triangles]
        .iter()
        .position(|t| {
            let p = t.map(|i| mesh.vertices[i as usize].pos);
            let q = [target[0] as f32, target[1] as f32];
            (0..3).all(|k| orient_up(p[k], p[(k + 1) % 3], q) > 0)
        })
        .unwrap();
    let mut ix = mesh.indices.clone();
    ix.remove(hit);
    let counts = coverage(&cam, &mesh, &ix, CullMode::None);
    let err = check_coverage(&cam, &counts, reach(&mesh, &params)).unwrap_err();
    assert!(err.contains("0 times"), "{err}");
    // Drawing a triangle twice.
    let mut ix = mesh.indices.clone();
    ix.push(mesh.indices[hit]);
    let counts = coverage(&cam, &mesh, &ix, CullMode::None);
    let err = check_coverage(&cam, &counts, reach(&mesh, &params)).unwrap_err();
    assert!(err.contains("2 times"), "{err}");
    // The mesh drawn upside down (front faces culled) covers nothing.
    let counts = coverage(&cam, &mesh, &mesh.indices, CullMode::Front);
    assert!(counts.iter().all(|&c| c == 0));
}

#[test]
fn coverage_reaches_the_horizon_from_any_height_and_pitch() {
    let params = PatchParams::default();
    let views = [
        Camera::new([0.0, 10_000.0, 0.0], 0.0, -90.0),
        Camera::new([12.3, 10_000.0, -4.0], 75.0, -30.0),
        Camera::new([12.3, 10_000.0, -4.0], 75.0, 0.0),
        Camera::new([0.0, 0.5, 0.0], 10.0, 0.0),
        Camera::new([0.0, 0.5, 0.0], 10.0, -90.0),
        Camera::new([3.0, 2.0, 1.0], 190.0, 10.0),
        Camera::new([3.0, -6.0, 1.0], 190.0, 30.0),
        Camera::new([3.0, -6.0, 1.0], 45.0, 90.0),
        Camera { fov_y: 120f64.to_radians(), ..Camera::new([0.0, 50.0, 0.0], 33.0, -40.0) },
        Camera { fov_y: 120f64.to_radians(), ..Camera::new([0.0, 50.0, 0.0], 33.0, -90.0) },
        Camera { fov_y: 10f64.to_radians(), ..Camera::new([0.0, 50.0, 0.0], 33.0, -1.0) },
    ];
    for cam in views {
        let mesh = cam.mesh(&params);
        let counts = coverage(&cam, &mesh, &mesh.indices, CullMode::None);
        let (certain, band) = check_coverage(&cam, &counts, reach(&mesh, &params))
            .unwrap_or_else(|e| panic!("{cam:?}: {e}"));
        println!("{cam:?}: {certain} pixels once, {band} in the horizon band");
    }
    // The horizon through a row of pixel centres (row 70): those pixels are in the band.
    let cam = Camera::new([0.0, 20.0, 0.0], 0.0, 0.0);
    let row = 70.5;
    let pitch = -((1.0 - 2.0 * row / f64::from(cam.height)) * (0.5 * cam.fov_y).tan()).atan();
    let cam = Camera::new(cam.eye, 0.0, -pitch.to_degrees());
    let mesh = cam.mesh(&params);
    let counts = coverage(&cam, &mesh, &mesh.indices, CullMode::None);
    let (_, band) = check_coverage(&cam, &counts, reach(&mesh, &params)).unwrap();
    assert_eq!(band, cam.width as usize, "pitch {}°", pitch.to_degrees());

    // Negative control: a far patch cut at 20 km leaves the pixels near the horizon of an eye
    // 1 km up uncovered (1 pixel below the horizon is 130 km away).
    let cam = Camera::new([0.0, 1000.0, 0.0], 10.0, -10.0);
    let mesh = cam.mesh(&params);
    let near = |i: u32| {
        let p = mesh.vertices[i as usize].pos;
        p[0].hypot(p[1]) < 20_000.0
    };
    let ix: Vec<[u32; 3]> =
        mesh.indices.iter().copied().filter(|t| t.iter().all(|&i| near(i))).collect();
    let counts = coverage(&cam, &mesh, &ix, CullMode::None);
    let err = check_coverage(&cam, &counts, reach(&mesh, &params)).unwrap_err();
    assert!(err.contains("0 times"), "{err}");
}

/// Checks the displacement weights: 0 on the near patch's boundary and on every far vertex;
/// inside, min(1, distance to the boundary / taper).
fn check_weights(mesh: &WaterMesh, params: &PatchParams) -> Result<(), String> {
    let half = 0.5 * params.near_size_m;
    for (i, v) in mesh.vertices.iter().enumerate() {
        let expected = if i >= mesh.near_vertices {
            0.0
        } else {
            let inside = half - f64::from(v.pos[0].abs().max(v.pos[1].abs()));
            if inside <= 0.0 {
                0.0
            } else if params.weight_taper_m == 0.0 {
                1.0
            } else {
                (inside / params.weight_taper_m).min(1.0)
            }
        };
        if (f64::from(v.weight) - expected).abs() > 1e-6 {
            return Err(format!("vertex {i} at {:?}: weight {} not {expected}", v.pos, v.weight));
        }
    }
    Ok(())
}

#[test]
fn displacement_weights_vanish_on_the_boundary_and_the_far_patch() {
    for taper in [PatchParams::default().weight_taper_m, 0.0] {
        let params = PatchParams { weight_taper_m: taper, ..PatchParams::default() };
        for cam in
            [Camera::new([0.4, 1.0, 0.2], 0.0, -30.0), Camera::new([9.0, 700.0, 1.0], 99.0, 0.0)]
        {
            let mesh = cam.mesh(&params);
            check_weights(&mesh, &params).unwrap();
            let ones = mesh.vertices[..mesh.near_vertices].iter().filter(|v| v.weight == 1.0);
            let zeros = mesh.vertices[..mesh.near_vertices].iter().filter(|v| v.weight == 0.0);
            assert!(ones.count() > 0);
            assert_eq!(zeros.count(), 4 * params.boundary_segments as usize);
            // Negative controls: a boundary vertex lifted, a far vertex weighted.
            let near = NearPatch::build(&params, cam.eye).unwrap();
            let mut broken = mesh.clone();
            broken.vertices[near.boundary[3] as usize].weight = 1.0;
            assert!(check_weights(&broken, &params).is_err());
            let mut broken = mesh.clone();
            broken.vertices[mesh.near_vertices + 2].weight = 1e-3;
            assert!(check_weights(&broken, &params).is_err());
        }
    }
}

/// Whether counts never increase along the sweep, and do decrease overall.
fn decreasing(counts: &[usize]) -> bool {
    counts.windows(2).all(|w| w[1] <= w[0]) && counts[counts.len() - 1] < counts[0]
}

#[test]
fn level_of_detail_follows_the_height() {
    let params = PatchParams::default();
    let g = params.grid_spacing_m;
    let (mut total, mut close) = (Vec::new(), Vec::new());
    for h in HEIGHTS {
        let eye = [0.25, h, -0.4];
        let near = NearPatch::build(&params, eye).unwrap();
        total.push(near.indices.len());
        // Triangles with a vertex within 64 m of the eye.
        close.push(
            near.indices
                .iter()
                .filter(|t| {
                    t.iter().any(|&i| {
                        let p = near.vertices[i as usize].pos.map(f64::from);
                        (p[0] - eye[0]).hypot(p[1] - eye[2]) < 64.0
                    })
                })
                .count(),
        );
        // The finest edge is never shorter than the grid spacing…
        let finest = near
            .indices
            .iter()
            .flat_map(|t| {
                let p = t.map(|i| near.vertices[i as usize].pos.map(f64::from));
                (0..3)
                    .map(move |k| (p[k][0] - p[(k + 1) % 3][0]).hypot(p[k][1] - p[(k + 1) % 3][1]))
            })
            .fold(f64::INFINITY, f64::min);
        assert!(finest >= g, "H = {h}: edge {finest} < {g}");
        // …and reaches it under a low eye.
        if h <= 2.0 {
            assert_eq!(finest, g, "H = {h}");
            assert_eq!(near.deepest_level, params.max_depth);
        }
        let mesh = WaterMesh::for_view(&params, eye, [0.0, -0.3, 1.0], 1.0, 1.5).unwrap();
        println!("H = {h:>7} m: near depth ≤ {:>2}, {}", near.deepest_level, mesh.summary());
    }
    println!("near triangles {total:?}, within 64 m {close:?}");
    assert!(decreasing(&total), "{total:?}");
    assert!(decreasing(&close), "{close:?}");
    // Negative control for the comparator.
    assert!(!decreasing(&[10, 8, 9, 3]) && !decreasing(&[5, 5, 5]));
}

#[test]
fn meshes_are_deterministic() {
    let params = PatchParams::default();
    for cam in
        [Camera::new([1.0e6, 3.0, -2.0e6], 10.0, -5.0), Camera::new([0.0, -40.0, 0.0], 80.0, 20.0)]
    {
        let a = cam.mesh(&params);
        let b = cam.mesh(&params);
        assert!(a == b);
        let far = FarPatch::precompute(&params, cam.fov_y, cam.aspect()).unwrap();
        let c = WaterMesh::for_view_with(&params, &far, cam.eye, cam.forward).unwrap();
        assert!(a == c);
        // The comparison can fail: a slightly different eye gives another mesh.
        let moved = Camera { eye: [cam.eye[0] + 1.0, cam.eye[1], cam.eye[2]], ..cam }.mesh(&params);
        assert!(a != moved);
    }
}

#[test]
fn snapping_keeps_vertices_on_the_displacement_grid() {
    // Moving the eye by less than half a cell changes nothing; by a whole cell, the mesh
    // moves with it: the same vertices shifted by one grid step in world space.
    let params = PatchParams::for_ocean(1000.0, 256); // g = 3.90625 m
    let g = params.grid_spacing_m;
    let a = NearPatch::build(&params, [1000.0 * g + 0.1, 1e4, 7.0 * g]).unwrap();
    let b = NearPatch::build(&params, [1000.0 * g - 0.1 * g, 1e4, 7.0 * g + 0.2]).unwrap();
    assert_eq!(a, b);
    assert_eq!(a.origin_cell, [1000, 7]);
    assert_eq!(a.origin, [1000.0 * g, 7.0 * g]);
    for v in &a.vertices {
        for c in v.pos {
            assert_eq!((f64::from(c) / g).fract(), 0.0, "{c} off the grid");
        }
    }
    let c = NearPatch::build(&params, [1001.0 * g, 1e4, 7.0 * g]).unwrap();
    assert_eq!(c.origin_cell, [1001, 7]);
    assert_eq!(c.vertices.len(), a.vertices.len());
}

#[test]
fn degenerate_inputs_are_errors() {
    let p = PatchParams::default();
    let ok = |eye, fwd, fov, aspect| WaterMesh::for_view(&p, eye, fwd, fov, aspect);
    let (eye, fwd) = ([0.0, 2.0, 0.0], [0.0, -0.2, 1.0]);
    assert!(ok(eye, fwd, 1.0, 1.5).is_ok());
    assert!(ok([f64::NAN, 2.0, 0.0], fwd, 1.0, 1.5).is_err());
    assert!(ok([0.0, f64::NAN, 0.0], fwd, 1.0, 1.5).is_err());
    assert!(ok([0.0, f64::INFINITY, 0.0], fwd, 1.0, 1.5).is_err());
    assert!(ok([0.0, 2.0, 1e300], fwd, 1.0, 1.5).is_err());
    assert!(ok(eye, [0.0, f64::NAN, 1.0], 1.0, 1.5).is_err());
    assert!(ok(eye, [0.0, 0.0, 0.0], 1.0, 1.5).is_err());
    for fov in [0.0, PI, f64::NAN, -1.0] {
        assert!(ok(eye, fwd, fov, 1.5).is_err(), "fov {fov}");
    }
    for aspect in [0.0, f64::NAN, f64::INFINITY] {
        assert!(ok(eye, fwd, 1.0, aspect).is_err(), "aspect {aspect}");
    }
    let bad = [
        PatchParams { near_size_m: 500.0, ..PatchParams::default() },
        PatchParams { max_depth: 19, ..PatchParams::default() },
        PatchParams { boundary_segments: 48, ..PatchParams::default() },
        PatchParams { split_threshold: f64::NAN, ..PatchParams::default() },
        PatchParams { far_ring_ratio: 1.0, ..PatchParams::default() },
        PatchParams { far_segments: 7, ..PatchParams::default() },
        PatchParams { far_segments: 8, ..PatchParams::default() },
        PatchParams { far_max_radius: 10.0, ..PatchParams::default() },
        PatchParams::for_grid(f64::NAN),
    ];
    for b in bad {
        assert!(WaterMesh::for_view(&b, eye, fwd, 1.0, 1.5).is_err(), "{b:?}");
    }
    // Valid extremes.
    for (eye, fwd) in [
        ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 1e4, 0.0], [0.0, -1.0, 0.0]),
        ([0.0, -1e4, 0.0], [0.0, 1.0, 0.0]),
        ([1e9, 2.0, -1e9], [1.0, 0.0, 0.0]),
        ([0.0, 2.0, 0.0], [0.0, 1.0, 0.0]),
    ] {
        let mesh = ok(eye, fwd, FRAC_PI_2, 1.0).unwrap();
        check_conforming(&mesh.vertices, &mesh.indices).unwrap();
    }
}

#[test]
fn random_views_and_parameters_stay_conforming() {
    // A deterministic spread of eyes (anywhere inside a grid cell), yaws, heights and
    // parameter sets, including the smallest near patch (4 cells) and a coarse far grid.
    let sets = [
        PatchParams::default(),
        PatchParams::for_grid(200.0),
        PatchParams::for_ocean(1000.0, 256),
        PatchParams { weight_taper_m: 0.0, boundary_segments: 1, ..PatchParams::for_grid(0.25) },
        PatchParams { far_segments: 16, far_ring_ratio: 1.5, ..PatchParams::for_grid(2.0) },
        PatchParams { far_segments: 16, ..PatchParams::for_grid(200.0) },
        PatchParams { split_threshold: 0.5, far_segments: 1024, ..PatchParams::default() },
    ];
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut uniform = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut checked = 0;
    for params in &sets {
        for _ in 0..12 {
            let g = params.grid_spacing_m;
            let eye = [
                (uniform() - 0.5) * 2e5 * g,
                (uniform() * 2.0 - 1.0) * 10f64.powf(uniform() * 4.5 - 0.5),
                (uniform() - 0.5) * 2e5 * g,
            ];
            let cam = Camera {
                fov_y: (10.0 + 110.0 * uniform()).to_radians(),
                ..Camera::new(eye, 360.0 * uniform(), 180.0 * uniform() - 90.0)
            };
            let mesh = cam.mesh(params);
            if let Err(e) = check_conforming(&mesh.vertices, &mesh.indices) {
                panic!("{params:?} {cam:?}: {e}");
            }
            // The zip adds one triangle per boundary vertex and one per ring vertex.
            assert_eq!(
                mesh.stitch_triangles,
                4 * params.boundary_segments as usize + params.far_segments as usize
            );
            checked += 1;
        }
    }
    println!("{checked} random meshes conforming");
}

/// The kept near patch (made once per params and eye) is the patch built anew, and another
/// eye gets its own (not the kept one).
#[test]
fn the_kept_near_patch_is_the_fresh_one() {
    let p = PatchParams::default();
    let eye = [3.25, 12.0, -7.5];
    let first = NearPatch::kept(&p, eye).unwrap();
    assert_eq!(first, NearPatch::build(&p, eye).unwrap());
    assert_eq!(NearPatch::kept(&p, eye).unwrap(), first);
    let higher = [3.25, 40.0, -7.5];
    let other = NearPatch::kept(&p, higher).unwrap();
    assert_eq!(other, NearPatch::build(&p, higher).unwrap());
    assert_ne!(other, first);
}

/// The kept water mesh of a frame (`DrawMesh::kept`, per patch parameters and view) is the
/// mesh built anew, bit for bit, and for the same view the same lists (what lets the GPU
/// back end keep one upload); a turned camera and a plan without the far patch get their own.
#[test]
fn the_kept_water_mesh_is_the_fresh_one() {
    use ocean_core::camera::Camera;
    use ocean_core::graph::DrawMesh;
    use ocean_core::plan::{FramePlan, OutputKind, Pass};
    use ocean_core::scene::Scene;
    use std::sync::Arc;

    let bytes = |m: &DrawMesh| {
        let v: &[u8] = bytemuck::cast_slice(m.vertices.as_slice());
        let i: &[u8] = bytemuck::cast_slice(m.indices.as_slice());
        (v.to_vec(), i.to_vec(), m.origin.map(f64::to_bits))
    };
    let check = |scene: &Scene, plan: &FramePlan| {
        let camera = Camera::from_scene(&scene.camera).unwrap();
        let kept = DrawMesh::kept(plan, scene, &camera).unwrap();
        assert!(!kept.vertices.is_empty(), "the default scene draws a mesh");
        let fresh: DrawMesh = plan.water_mesh(scene, &camera).unwrap().into();
        assert!(bytes(&kept) == bytes(&fresh), "the kept mesh is not the fresh one");
        let again = DrawMesh::kept(plan, scene, &camera).unwrap();
        assert!(Arc::ptr_eq(&again.vertices, &kept.vertices), "the same view, another list");
        assert!(Arc::ptr_eq(&again.indices, &kept.indices));
        kept
    };
    let scene = Scene::builtin();
    let plan = FramePlan::new(&scene, OutputKind::Ldr);
    assert!(plan.runs(Pass::FarPatch), "the default plan draws the far patch");
    let first = check(&scene, &plan);

    let mut turned = scene.clone();
    turned.camera.look_at[0] += 20.0;
    let other = check(&turned, &plan);
    assert!(!Arc::ptr_eq(&other.vertices, &first.vertices), "a turned camera got the kept mesh");
    assert!(bytes(&other) != bytes(&first), "a turned camera drew the same far patch");

    // Looking straight down from 25 m the plan leaves the far patch out; the full plan,
    // same camera and parameters, draws it: the key tells the two apart.
    let mut down = scene.clone();
    down.camera.position = [3.0, 25.0, -7.0];
    down.camera.look_at = [3.0, 0.0, -7.1];
    let near_plan = FramePlan::new(&down, OutputKind::Ldr);
    assert!(!near_plan.runs(Pass::FarPatch), "{near_plan}");
    let alone = check(&down, &near_plan);
    let full = check(&down, &FramePlan::full(&down, OutputKind::Ldr));
    assert!(alone.vertices.len() < full.vertices.len(), "the near patch alone is smaller");
}
