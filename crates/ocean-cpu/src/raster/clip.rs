//! Clipping in homogeneous clip space against the Vulkan view volume.
//!
//! Vulkan clips primitives to `−w ≤ x ≤ w`, `−w ≤ y ≤ w`, `0 ≤ z ≤ w` (no depth clamp). llvmpipe
//! sets its draw module up with "clipping - enabled, with no guardband", so it clips to all six
//! planes; so does this module, rather than relying on a guard band for x and y. Consequences:
//! no pixel centre ever lies on an x/y clip plane (they run along the target's border, pixel
//! centres are at +0.5), so x/y clipping changes coverage only through the rounding of the new
//! vertices; and every vertex that reaches the fixed-point stage is inside the target, which is
//! what bounds the integer arithmetic (see [`super::fixed_point`]).
//!
//! One more plane, `w ≥ W_MIN`, comes first: the view volume alone admits the point
//! (0, 0, 0, 0), whose perspective divide is 0/0. No real camera puts a vertex there.
//!
//! Algorithm: Sutherland–Hodgman, one plane at a time in the fixed order of [`PLANES`]. A new
//! vertex on an edge is always interpolated *from the inside vertex towards the outside one*,
//! `v = inside + t · (outside − inside)` with `t = d_in / (d_in − d_out)`, on every component
//! (clip position and varyings, linearly in clip space, as a GPU does). So an edge shared by
//! two triangles is cut at bit-identical points whichever way round each triangle walks it,
//! and the two triangles stay watertight.

use super::Vertex;

/// Smallest w a clipped vertex may have. It keeps `1 / w` (≤ 1e30) and the perspective weights
/// `b / w` (summed over three vertices) finite in f32; real cameras have w ≥ the near distance.
pub const W_MIN: f32 = 1e-30;

/// Signed distance to one clip plane; the inside is `d ≥ 0`.
type PlaneDistance = fn(&[f32; 4]) -> f32;

/// The clip planes, in the order they are applied.
pub const PLANES: [PlaneDistance; 7] = [
    |p| p[3] - W_MIN, // w ≥ W_MIN
    |p| p[3] - p[0],  // x ≤ w (right)
    |p| p[3] + p[0],  // −w ≤ x (left)
    |p| p[3] - p[1],  // y ≤ w (top: NDC y is up)
    |p| p[3] + p[1],  // −w ≤ y (bottom)
    |p| p[2],         // 0 ≤ z (near)
    |p| p[3] - p[2],  // z ≤ w (far)
];

/// Most vertices a clipped triangle can have: each plane adds at most one.
pub const MAX_POLYGON: usize = 3 + PLANES.len();

/// A convex polygon of at most [`MAX_POLYGON`] vertices, on the stack.
#[derive(Clone, Copy, Debug)]
pub struct Polygon<const V: usize> {
    vertices: [Vertex<V>; MAX_POLYGON],
    len: usize,
}

impl<const V: usize> Polygon<V> {
    fn from_triangle(tri: [Vertex<V>; 3]) -> Self {
        let mut vertices = [tri[0]; MAX_POLYGON];
        vertices[..3].copy_from_slice(&tri);
        Self { vertices, len: 3 }
    }

    /// The vertices, in the winding of the input triangle.
    pub fn vertices(&self) -> &[Vertex<V>] {
        &self.vertices[..self.len]
    }

    /// The triangle fan `(v0, v_i, v_i+1)`: same winding as the input triangle. Empty if the
    /// polygon has fewer than three vertices.
    pub fn fan(self) -> impl Iterator<Item = [Vertex<V>; 3]> {
        let v = self.vertices;
        (1..self.len.saturating_sub(1)).map(move |i| [v[0], v[i], v[i + 1]])
    }

    fn push(&mut self, v: Vertex<V>) {
        debug_assert!(self.len < MAX_POLYGON, "a convex polygon gains ≤ 1 vertex per plane");
        self.vertices[self.len] = v;
        self.len += 1;
    }

    fn empty() -> Self {
        let mut p = Self::from_triangle([Vertex::ZERO; 3]);
        p.len = 0;
        p
    }
}

/// Clips a triangle to the view volume. Returns an empty polygon when nothing is left, when a
/// clip coordinate is NaN or infinite, or when clipping overflowed f32 (inputs beyond ~1e38).
pub fn clip_triangle<const V: usize>(tri: [Vertex<V>; 3]) -> Polygon<V> {
    if tri.iter().any(|v| v.clip.iter().any(|c| !c.is_finite())) {
        return Polygon::empty();
    }

    // Out-codes: bit k set when the vertex is outside plane k.
    let outcode = |v: &Vertex<V>| -> u32 {
        PLANES
            .iter()
            .enumerate()
            .map(|(k, d)| u32::from(d(&v.clip) < 0.0) << k)
            .fold(0, |a, b| a | b)
    };
    let codes = tri.map(|v| outcode(&v));
    if codes[0] & codes[1] & codes[2] != 0 {
        return Polygon::empty(); // all three outside one plane
    }
    let mut poly = Polygon::from_triangle(tri);
    let straddled = codes[0] | codes[1] | codes[2];
    if straddled == 0 {
        return poly;
    }

    for (k, distance) in PLANES.iter().enumerate() {
        if straddled & (1 << k) == 0 {
            continue;
        }
        poly = clip_polygon(&poly, *distance);
        if poly.len < 3 {
            return Polygon::empty();
        }
    }
    if poly.vertices().iter().any(|v| v.clip.iter().any(|c| !c.is_finite())) {
        return Polygon::empty();
    }
    poly
}

/// One Sutherland–Hodgman step against one plane.
fn clip_polygon<const V: usize>(poly: &Polygon<V>, distance: PlaneDistance) -> Polygon<V> {
    let src = poly.vertices();
    let mut out = Polygon::empty();
    for (i, cur) in src.iter().enumerate() {
        let next = &src[(i + 1) % src.len()];
        let d_cur = distance(&cur.clip);
        let d_next = distance(&next.clip);
        if d_cur >= 0.0 {
            out.push(*cur);
        }
        if (d_cur >= 0.0) != (d_next >= 0.0) {
            let (inside, outside, d_in, d_out) =
                if d_cur >= 0.0 { (cur, next, d_cur, d_next) } else { (next, cur, d_next, d_cur) };
            out.push(interpolate(inside, outside, d_in / (d_in - d_out)));
        }
    }
    out
}

/// `inside + t · (outside − inside)` on every component.
fn interpolate<const V: usize>(inside: &Vertex<V>, outside: &Vertex<V>, t: f32) -> Vertex<V> {
    debug_assert!((0.0..=1.0).contains(&t), "t = {t}");
    Vertex {
        clip: std::array::from_fn(|c| inside.clip[c] + t * (outside.clip[c] - inside.clip[c])),
        varyings: std::array::from_fn(|c| {
            inside.varyings[c] + t * (outside.varyings[c] - inside.varyings[c])
        }),
    }
}
