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
//! Algorithm: Sutherland–Hodgman, one plane at a time in the fixed order of `PLANES` (w; x and
//! y; near and far). A new vertex on an edge is the point
//! `v = (d_in · outside − d_out · inside) / (d_in − d_out)` on every component (clip position
//! and varyings, linearly in clip space, as a GPU does), always with the inside vertex first,
//! so an edge shared by two triangles is cut at bit-identical points whichever way round each
//! triangle walks it, and the two triangles stay watertight.
//!
//! Accuracy, for triangles of any size: the numerator is formed from 2 × 2 determinants of the
//! f32 inputs in f64 (exact products, see [`cut`]), so a cut point far smaller than the
//! vertices it lies between (a ±1e30 triangle, or a far-patch vertex beside the eye, cut at
//! x = w = 1) keeps its relative precision; the lerp `(1 − t)·inside + t·outside` in f32 loses
//! everything below ulp(vertex) there (issue 5's stability table: a ±1e6 triangle's diagonal
//! edge put 95 pixels of a 64 × 48 view on the wrong side). The coordinate that the plane fixes
//! is then set exactly (`x = w` on the right plane, `w = W_MIN` on the w plane, …). (Mesa
//! interpolates `inside + t · (outside − inside)` in f32 and does not pin the coordinate; the
//! two agree to rounding for triangles of ordinary size: in the reference scenes' goldens,
//! 1 to 5 pixels at the view's left and right edges moved by 1/255.)

use super::Vertex;

/// Smallest w a clipped vertex may have. It keeps `1 / w` (≤ 1e30) and the perspective weights
/// `b / w` (summed over three vertices) finite in f32; real cameras have w ≥ the near distance.
pub const W_MIN: f32 = 1e-30;

/// Largest magnitude of a clip coordinate the clipper accepts (2^125 ≈ 4.3e37); a triangle
/// with a larger one is dropped. Below it no distance (≤ 2^126), difference of distances
/// (≤ 2^127) or interpolated component can overflow f32; above it, clipping could produce
/// infinities. Realistic inputs are many orders of magnitude smaller.
pub const MAX_CLIP_COORD: f32 = (1u128 << 125) as f32;

/// One clip plane: the signed distance of a clip position (inside is `d ≥ 0`), the same
/// distance as coefficients (d = a · p − offset, for the exact cut in [`cut`]), and the exact
/// value of the coordinate a point on the plane has.
#[derive(Clone, Copy)]
struct Plane {
    distance: fn(&[f32; 4]) -> f32,
    a: [f64; 4],
    offset: f64,
    put_on_plane: fn(&mut [f32; 4]),
}

/// The clip planes, in the order they are applied: w first (it makes every later w positive),
/// then x and y (they bound x and y by w before z is cut), then near and far.
const PLANES: [Plane; 7] = [
    Plane {
        distance: |p| p[3] - W_MIN, // w ≥ W_MIN
        a: [0.0, 0.0, 0.0, 1.0],
        offset: W_MIN as f64,
        put_on_plane: |p| p[3] = W_MIN,
    },
    Plane {
        distance: |p| p[3] - p[0], // x ≤ w (right)
        a: [-1.0, 0.0, 0.0, 1.0],
        offset: 0.0,
        put_on_plane: |p| p[0] = p[3],
    },
    Plane {
        distance: |p| p[3] + p[0], // −w ≤ x (left)
        a: [1.0, 0.0, 0.0, 1.0],
        offset: 0.0,
        put_on_plane: |p| p[0] = -p[3],
    },
    Plane {
        distance: |p| p[3] - p[1], // y ≤ w (top: NDC y is up)
        a: [0.0, -1.0, 0.0, 1.0],
        offset: 0.0,
        put_on_plane: |p| p[1] = p[3],
    },
    Plane {
        distance: |p| p[3] + p[1], // −w ≤ y (bottom)
        a: [0.0, 1.0, 0.0, 1.0],
        offset: 0.0,
        put_on_plane: |p| p[1] = -p[3],
    },
    Plane {
        distance: |p| p[2], // 0 ≤ z (near)
        a: [0.0, 0.0, 1.0, 0.0],
        offset: 0.0,
        put_on_plane: |p| p[2] = 0.0,
    },
    Plane {
        distance: |p| p[3] - p[2], // z ≤ w (far)
        a: [0.0, 0.0, -1.0, 1.0],
        offset: 0.0,
        put_on_plane: |p| p[2] = p[3],
    },
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

    fn empty() -> Self {
        Self { vertices: [Vertex::ZERO; MAX_POLYGON], len: 0 }
    }

    /// The vertices, in the winding of the input triangle.
    pub fn vertices(&self) -> &[Vertex<V>] {
        &self.vertices[..self.len]
    }

    /// The triangle fan `(v0, v_i, v_i+1)`, in the winding of the input triangle. Empty if the
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
}

/// Clips a triangle to the view volume. Returns an empty polygon when nothing is left, or when
/// a clip coordinate is NaN or beyond ±[`MAX_CLIP_COORD`] (infinities included).
pub fn clip_triangle<const V: usize>(tri: [Vertex<V>; 3]) -> Polygon<V> {
    let acceptable = |c: &f32| c.abs() <= MAX_CLIP_COORD; // false for NaN too
    if !tri.iter().all(|v| v.clip.iter().all(acceptable)) {
        return Polygon::empty();
    }
    let mut poly = Polygon::from_triangle(tri);
    for plane in &PLANES {
        // Tested on the current polygon, not the input: a new vertex may lie outside a plane
        // that every input vertex was inside (the w plane's new vertices, whose x, y, z carry
        // cancellation error, are the case in point).
        let inside = poly.vertices().iter().filter(|v| (plane.distance)(&v.clip) >= 0.0).count();
        if inside == 0 {
            return Polygon::empty();
        }
        if inside < poly.len {
            poly = clip_polygon(&poly, plane);
            if poly.len < 3 {
                return Polygon::empty();
            }
        }
    }
    debug_assert!(
        poly.vertices().iter().all(|v| v.clip.iter().all(|c| c.is_finite()) && v.clip[3] > 0.0),
        "clipping stays finite below MAX_CLIP_COORD and keeps w > 0"
    );
    poly
}

/// One Sutherland–Hodgman step against one plane.
fn clip_polygon<const V: usize>(poly: &Polygon<V>, plane: &Plane) -> Polygon<V> {
    let src = poly.vertices();
    let mut out = Polygon::empty();
    for (i, cur) in src.iter().enumerate() {
        let next = &src[(i + 1) % src.len()];
        let d_cur = (plane.distance)(&cur.clip);
        let d_next = (plane.distance)(&next.clip);
        if d_cur >= 0.0 {
            out.push(*cur);
        }
        if (d_cur >= 0.0) != (d_next >= 0.0) {
            let (inside, outside, d_in, d_out) =
                if d_cur >= 0.0 { (cur, next, d_cur, d_next) } else { (next, cur, d_next, d_cur) };
            debug_assert!(d_in >= 0.0 && d_out < 0.0, "{d_in} {d_out}");
            let mut v = cut(inside, outside, plane);
            (plane.put_on_plane)(&mut v.clip);
            out.push(v);
        }
    }
    out
}

/// The point where the edge from `inside` to `outside` meets `plane`, on every component
/// (clip position and varyings, linear in clip space):
/// v = (d_in · outside − d_out · inside) / (d_in − d_out), d = a · p − offset.
///
/// The numerator is formed as Σ_k a_k (inside_k · outside_c − outside_k · inside_c) −
/// offset · (outside_c − inside_c): each term a 2 × 2 determinant of f32 values, whose two
/// products are exact in f64 (24 + 24 < 53 bits) and whose difference is rounded once. The
/// plain lerp `(1 − t) · inside + t · outside` cancels catastrophically when the vertices are
/// far larger than the cut point (an edge from (−1e6, −1e6) to (1e6, 1e6) cut at x = w = 1:
/// the lerp's y is off by ~0.06, pixels at the view's edge; a far-patch vertex beside the eye
/// has such ratios); the determinant form keeps the f64 relative precision of the result.
fn cut<const V: usize>(inside: &Vertex<V>, outside: &Vertex<V>, plane: &Plane) -> Vertex<V> {
    let (i, o) = (inside.clip.map(f64::from), outside.clip.map(f64::from));
    let d_in = (0..4).map(|k| plane.a[k] * i[k]).sum::<f64>() - plane.offset;
    let d_out = (0..4).map(|k| plane.a[k] * o[k]).sum::<f64>() - plane.offset;
    let denominator = d_in - d_out;
    let component = |ic: f64, oc: f64| {
        let mut n = -plane.offset * (oc - ic);
        for k in 0..4 {
            if plane.a[k] != 0.0 {
                n += plane.a[k] * (i[k] * oc - o[k] * ic);
            }
        }
        (n / denominator) as f32
    };
    Vertex {
        clip: std::array::from_fn(|c| component(i[c], o[c])),
        varyings: std::array::from_fn(|c| {
            component(f64::from(inside.varyings[c]), f64::from(outside.varyings[c]))
        }),
    }
}
