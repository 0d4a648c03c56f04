//! Clipping in homogeneous clip space against the Vulkan view volume, as lavapipe does it
//! (Mesa's draw module, `draw_pipe_clip.c`, which llvmpipe sets up without a guard band).
//!
//! Vulkan clips primitives to `−w ≤ x ≤ w`, `−w ≤ y ≤ w`, `0 ≤ z ≤ w` (no depth clamp). The
//! rules, each of which decides bits of the result (measured against lavapipe: the
//! interpolated depth and varyings of randomly placed, partly clipped triangles agree bit for
//! bit with this module and [`super::setup`]):
//!
//! - A vertex's clip mask has bit `p` when its distance to plane `p` is negative. The planes,
//!   in bit order: `x ≤ w`, `x ≥ −w`, `y ≤ w`, `y ≥ −w`, `z ≥ 0`, `z ≤ w`; the distance is
//!   the dot product with the plane written as (a, b, c, d): `((a·x + b·y) + c·z) + d·w`.
//!   Only the planes in the union of the three masks are clipped against, in bit order, and
//!   only the input vertices' masks count (a new vertex is not tested again).
//! - Sutherland–Hodgman over the polygon from its first vertex: keep a vertex whose distance
//!   is ≥ 0; between a vertex and the next, a new vertex when `d_prev · d ≤ 0` and
//!   `d − d_prev ≠ 0` (Mesa's `DIFFERENT_SIGNS`).
//! - The new vertex is interpolated *from the vertex nearer the plane* towards the other one,
//!   `v = near + t · (far − near)` with `t = |d_near| / (|d_near| + |d_far|)` (computed as
//!   Mesa does, `d / (d − d_prev)` or `−d_prev / (d − d_prev)`), on the clip position and on
//!   every varying; no coordinate is pinned to the plane. Its window coordinates are then
//!   computed unfused (C code), while an input vertex's come from the JIT, fused
//!   ([`super::fixed_point::to_window`]).
//! - The polygon is fanned from its first vertex: (v0, v_{i−1}, v_i), Vulkan's provoking
//!   vertex first.
//!
//! Guards of this crate's own: a triangle with a NaN, infinite or enormous (beyond
//! ±[`MAX_CLIP_COORD`]) clip coordinate is dropped. And where Mesa's interpolation cancels
//! catastrophically (a triangle some 10⁷ times larger than its distance to a plane, e.g.
//! coordinates of ±1e30 with w = 1, leaves a new vertex far off the view volume, and lavapipe
//! draws garbage), the triangle is clipped again by the exact fallback: each new vertex is
//! interpolated from the inside vertex and pinned to its plane, with a first plane `w ≥ W_MIN`
//! (`exact`). A result is rejected when a new vertex lies off its own plane by more than
//! 2⁻¹⁰·w, a vertex beyond any plane by more than that or at `w < W_MIN`, or the polygon
//! outgrows [`MAX_POLYGON`]; ordinary triangles
//! land within a few ulp and keep lavapipe's bits.

use super::Vertex;

/// Smallest w a clipped vertex may have; a polygon with a smaller one is dropped. It keeps
/// `1 / w` (≤ 1e30) finite in f32.
pub const W_MIN: f32 = 1e-30;

/// Largest magnitude of a clip coordinate the clipper accepts (2^125 ≈ 4.3e37); a triangle
/// with a larger one is dropped. Below it no distance or interpolated component can overflow
/// f32.
pub const MAX_CLIP_COORD: f32 = (1u128 << 125) as f32;

/// The six planes (a, b, c, d), distance `((a·x + b·y) + c·z) + d·w`, in clip-mask bit order.
const PLANES: [[f32; 4]; 6] = [
    [-1.0, 0.0, 0.0, 1.0], // x ≤ w (right)
    [1.0, 0.0, 0.0, 1.0],  // −w ≤ x (left)
    [0.0, -1.0, 0.0, 1.0], // y ≤ w (top: NDC y is up)
    [0.0, 1.0, 0.0, 1.0],  // −w ≤ y (bottom)
    [0.0, 0.0, 1.0, 0.0],  // 0 ≤ z (near)
    [0.0, 0.0, -1.0, 1.0], // z ≤ w (far)
];

#[inline]
fn distance(p: &[f32; 4], plane: &[f32; 4]) -> f32 {
    p[0] * plane[0] + p[1] * plane[1] + p[2] * plane[2] + p[3] * plane[3]
}

/// A vertex of a clipped polygon: an input vertex, or one the clipper made (whose window
/// coordinates are computed differently, see the module doc).
#[derive(Clone, Copy, Debug)]
pub struct ClipVertex<const V: usize> {
    /// The vertex.
    pub vertex: Vertex<V>,
    /// Whether the clipper made it.
    pub made: bool,
}

/// Most vertices a clipped polygon may have (each plane adds at most two, with vertices exactly
/// on a plane counted twice as Mesa does; beyond it the exact fallback clips).
pub const MAX_POLYGON: usize = 24;

/// A convex polygon of at most [`MAX_POLYGON`] vertices, on the stack.
#[derive(Clone, Copy, Debug)]
pub struct Polygon<const V: usize> {
    vertices: [ClipVertex<V>; MAX_POLYGON],
    len: usize,
}

impl<const V: usize> Polygon<V> {
    fn empty() -> Self {
        Self { vertices: [ClipVertex { vertex: Vertex::ZERO, made: false }; MAX_POLYGON], len: 0 }
    }

    /// The vertices, in the winding of the input triangle.
    pub fn vertices(&self) -> &[ClipVertex<V>] {
        &self.vertices[..self.len]
    }

    /// The triangle fan `(v0, v_i, v_i+1)`, in the winding of the input triangle. Empty if the
    /// polygon has fewer than three vertices.
    pub fn fan(self) -> impl Iterator<Item = [ClipVertex<V>; 3]> {
        let v = self.vertices;
        (1..self.len.saturating_sub(1)).map(move |i| [v[0], v[i], v[i + 1]])
    }

    /// Appends a vertex; false (and nothing appended) when the polygon is full.
    fn push(&mut self, v: ClipVertex<V>) -> bool {
        if self.len == MAX_POLYGON {
            return false;
        }
        self.vertices[self.len] = v;
        self.len += 1;
        true
    }

    /// Whether every vertex lies inside the view volume up to 2⁻¹⁰·w, with w ≥ W_MIN.
    fn on_volume(&self) -> bool {
        self.vertices().iter().all(|v| {
            let c = &v.vertex.clip;
            let tolerance = -c[3] * (1.0 / 1024.0);
            c[3] >= W_MIN && PLANES.iter().all(|p| distance(c, p) >= tolerance)
        })
    }
}

/// Clips a triangle to the view volume (module doc). Returns an empty polygon when nothing is
/// left, or for the inputs the guards drop.
pub fn clip_triangle<const V: usize>(tri: [Vertex<V>; 3]) -> Polygon<V> {
    let acceptable = |c: &f32| c.abs() <= MAX_CLIP_COORD; // false for NaN too
    if !tri.iter().all(|v| v.clip.iter().all(acceptable)) {
        return Polygon::empty();
    }
    let mask = |v: &Vertex<V>| {
        PLANES
            .iter()
            .enumerate()
            .fold(0u32, |m, (p, plane)| if distance(&v.clip, plane) < 0.0 { m | 1 << p } else { m })
    };
    let masks = tri.map(|v| mask(&v));
    let mut clipmask = masks[0] | masks[1] | masks[2];
    let mut poly = Polygon::empty();
    for v in tri {
        poly.push(ClipVertex { vertex: v, made: false });
    }
    if masks[0] & masks[1] & masks[2] != 0 {
        return Polygon::empty(); // all three outside one plane
    }
    while clipmask != 0 && poly.len >= 3 {
        let p = clipmask.trailing_zeros() as usize;
        clipmask &= !(1 << p);
        match clip_polygon(&poly, &PLANES[p]) {
            Some(next) => poly = next,
            None => return exact::clip_triangle(tri),
        }
    }
    if poly.len < 3 {
        return Polygon::empty();
    }
    if !poly.on_volume() {
        return exact::clip_triangle(tri);
    }
    debug_assert!(
        poly.vertices().iter().all(|v| v.vertex.clip.iter().all(|c| c.is_finite())),
        "clipping stays finite below MAX_CLIP_COORD"
    );
    poly
}

/// One Sutherland–Hodgman step against one plane, Mesa's way (module doc); `None` when the
/// polygon would outgrow [`MAX_POLYGON`].
fn clip_polygon<const V: usize>(poly: &Polygon<V>, plane: &[f32; 4]) -> Option<Polygon<V>> {
    let src = poly.vertices();
    let n = src.len();
    let mut out = Polygon::empty();
    let mut prev = &src[0];
    let mut d_prev = distance(&prev.vertex.clip, plane);
    for i in 1..=n {
        let cur = &src[i % n];
        let d = distance(&cur.vertex.clip, plane);
        if d_prev >= 0.0 && !out.push(*prev) {
            return None;
        }
        let different_signs = d * d_prev <= 0.0 && d - d_prev != 0.0;
        if different_signs {
            let denom = d - d_prev;
            let (t, from, to) = if d < 0.0 {
                // Going out.
                if -d < d_prev { (d / denom, cur, prev) } else { (-d_prev / denom, prev, cur) }
            } else if -d_prev < d {
                // Coming back in.
                (-d_prev / denom, prev, cur)
            } else {
                (d / denom, cur, prev)
            };
            let v = ClipVertex { vertex: interpolate(&from.vertex, &to.vertex, t), made: true };
            // Off its own plane by more than rounding: the interpolation cancelled.
            let w = v.vertex.clip[3];
            let on_plane = distance(&v.vertex.clip, plane).abs() <= w * (1.0 / 1024.0); // NaN: no
            if !on_plane || !out.push(v) {
                return None;
            }
        }
        prev = cur;
        d_prev = d;
    }
    Some(out)
}

/// `from + t · (to − from)` on every component (Mesa's `LINTERP`).
fn interpolate<const V: usize>(from: &Vertex<V>, to: &Vertex<V>, t: f32) -> Vertex<V> {
    let lerp = |a: f32, b: f32| a + t * (b - a);
    Vertex {
        clip: std::array::from_fn(|c| lerp(from.clip[c], to.clip[c])),
        varyings: std::array::from_fn(|c| lerp(from.varyings[c], to.varyings[c])),
    }
}

/// The exact fallback clipper (module doc): planes `w ≥ W_MIN`, x, y, near, far in that
/// order, each tested on the current polygon; a new vertex is the exact cut of [`exact::cut`]
/// (f64 determinants), and the coordinate its plane fixes is set exactly (`x = w` on the
/// right plane, …), so even ±1e30 triangles clip to within a few ulp.
mod exact {
    use super::{ClipVertex, Polygon, Vertex, W_MIN};

    /// A plane: the signed distance (inside ≥ 0), the same distance as coefficients
    /// (d = a · p − offset, for the exact cut in [`cut`]) and how to put a point exactly on it.
    struct Plane {
        distance: fn(&[f32; 4]) -> f32,
        a: [f64; 4],
        offset: f64,
        put_on_plane: fn(&mut [f32; 4]),
    }

    const PLANES: [Plane; 7] = [
        Plane {
            distance: |p| p[3] - W_MIN,
            a: [0.0, 0.0, 0.0, 1.0],
            offset: W_MIN as f64,
            put_on_plane: |p| p[3] = W_MIN,
        },
        Plane {
            distance: |p| p[3] - p[0],
            a: [-1.0, 0.0, 0.0, 1.0],
            offset: 0.0,
            put_on_plane: |p| p[0] = p[3],
        },
        Plane {
            distance: |p| p[3] + p[0],
            a: [1.0, 0.0, 0.0, 1.0],
            offset: 0.0,
            put_on_plane: |p| p[0] = -p[3],
        },
        Plane {
            distance: |p| p[3] - p[1],
            a: [0.0, -1.0, 0.0, 1.0],
            offset: 0.0,
            put_on_plane: |p| p[1] = p[3],
        },
        Plane {
            distance: |p| p[3] + p[1],
            a: [0.0, 1.0, 0.0, 1.0],
            offset: 0.0,
            put_on_plane: |p| p[1] = -p[3],
        },
        Plane {
            distance: |p| p[2],
            a: [0.0, 0.0, 1.0, 0.0],
            offset: 0.0,
            put_on_plane: |p| p[2] = 0.0,
        },
        Plane {
            distance: |p| p[3] - p[2],
            a: [0.0, 0.0, -1.0, 1.0],
            offset: 0.0,
            put_on_plane: |p| p[2] = p[3],
        },
    ];

    /// The point where the edge inside → outside crosses `plane`, on every component:
    /// v = (d_in · outside − d_out · inside) / (d_in − d_out). The numerator is formed from
    /// 2 × 2 determinants of the f32 inputs in f64 (the products of two f32 are exact in f64),
    /// so a cut point far smaller than the vertices it lies between (a ±1e30 triangle, or a
    /// far-patch vertex beside the eye) keeps its relative precision, which the f32 lerp
    /// (1 − t)·inside + t·outside loses below ulp(vertex) (issue 5's stability table).
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

    /// Clips a triangle (whose coordinates the caller checked) to the view volume.
    pub fn clip_triangle<const V: usize>(tri: [Vertex<V>; 3]) -> Polygon<V> {
        let mut poly = Polygon::empty();
        for v in tri {
            poly.push(ClipVertex { vertex: v, made: false });
        }
        for plane in &PLANES {
            let inside =
                poly.vertices().iter().filter(|v| (plane.distance)(&v.vertex.clip) >= 0.0).count();
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
        poly
    }

    fn clip_polygon<const V: usize>(poly: &Polygon<V>, plane: &Plane) -> Polygon<V> {
        let src = poly.vertices();
        let mut out = Polygon::empty();
        for (i, cur) in src.iter().enumerate() {
            let next = &src[(i + 1) % src.len()];
            let d_cur = (plane.distance)(&cur.vertex.clip);
            let d_next = (plane.distance)(&next.vertex.clip);
            if d_cur >= 0.0 {
                out.push(*cur);
            }
            if (d_cur >= 0.0) != (d_next >= 0.0) {
                let (inside, outside) = if d_cur >= 0.0 { (cur, next) } else { (next, cur) };
                let mut v = cut(&inside.vertex, &outside.vertex, plane);
                (plane.put_on_plane)(&mut v.clip);
                out.push(ClipVertex { vertex: v, made: true });
            }
        }
        out
    }
}
