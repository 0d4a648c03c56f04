//! Rasterizer tests: exact coverage and the top-left rule, sub-pixel snapping, perspective-correct
//! interpolation against analytic planes, clipping, depth-order independence, determinism across
//! thread counts, and robustness. Every comparator has a negative control.

use ocean_cpu::raster::{
    BlendMode, CompareFunction, CullMode, FragmentInput, FrontFace, RasterState, RenderTarget,
    Vertex, draw,
};

// ---------------------------------------------------------------------------------------------
// Helpers

/// A small deterministic generator (SplitMix64), so the tests need no dependency.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
}

/// A vertex at framebuffer position (x, y) (pixels, y down) with w = 1, z = 0.5. For
/// power-of-two sizes and x, y on a 1/1024 grid, the rasterizer's viewport transform gives back
/// x, y exactly.
fn fb(x: f64, y: f64, width: u32, height: u32) -> Vertex<0> {
    let ndc_x = 2.0 * x / f64::from(width) - 1.0;
    let ndc_y = 1.0 - 2.0 * y / f64::from(height);
    Vertex::new([ndc_x as f32, ndc_y as f32, 0.5, 1.0], [])
}

/// State that counts fragments: no depth test, additive blending.
fn counting_state() -> RasterState {
    RasterState {
        depth_compare: CompareFunction::Always,
        depth_write: false,
        blend: BlendMode::Add,
        ..RasterState::default()
    }
}

/// How many fragments each pixel received.
fn coverage(width: u32, height: u32, tris: &[[Vertex<0>; 3]]) -> Vec<u32> {
    let mut target = RenderTarget::new(width, height);
    draw(&mut target, &counting_state(), tris, |_| Some([1.0, 0.0, 0.0, 0.0]));
    target.color.iter().map(|c| c[0] as u32).collect()
}

/// Pixels whose centre lies in the half-open rectangle [x0, x1) × [y0, y1): what the top-left
/// rule gives for an axis-aligned rectangle whose corners are on the 1/256 grid.
fn rect_coverage(width: u32, height: u32, x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<u32> {
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            out.push(u32::from(x0 <= cx && cx < x1 && y0 <= cy && cy < y1));
        }
    }
    out
}

/// The comparator for coverage: the pixels where two counts differ.
fn coverage_mismatches(actual: &[u32], expected: &[u32]) -> Vec<usize> {
    assert_eq!(actual.len(), expected.len());
    (0..actual.len()).filter(|&i| actual[i] != expected[i]).collect()
}

/// Reverses the winding of a triangle when `flip`.
fn wind<const V: usize>(t: [Vertex<V>; 3], flip: bool) -> [Vertex<V>; 3] {
    if flip { [t[0], t[2], t[1]] } else { t }
}

fn bits(target: &RenderTarget) -> Vec<u32> {
    target
        .color
        .iter()
        .flat_map(|c| c.map(f32::to_bits))
        .chain(target.depth.iter().map(|d| d.to_bits()))
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Exact coverage on shared edges

/// A jittered n × n grid over the rectangle, triangulated with random diagonals and windings.
/// Boundary points move only along the boundary; interior points snap to pixel centres, to
/// the 1/256 grid or to a finer 1/1024 grid (so the rasterizer's own snapping is exercised).
fn jittered_square(rng: &mut Rng, rect: [f64; 4], n: usize) -> Vec<[Vertex<0>; 3]> {
    let [x0, y0, x1, y1] = rect;
    let q = |v: f64, grid: f64| (v * grid).round() / grid;
    let mut pts = vec![[0.0f64; 2]; (n + 1) * (n + 1)];
    for j in 0..=n {
        for i in 0..=n {
            let mut x = x0 + (x1 - x0) * i as f64 / n as f64;
            let mut y = y0 + (y1 - y0) * j as f64 / n as f64;
            let jitter = |rng: &mut Rng, v: f64| match rng.below(3) {
                0 => (v + rng.range(-2.0, 2.0)).floor() + 0.5,
                1 => q(v + rng.range(-2.0, 2.0), 256.0),
                _ => q(v + rng.range(-2.0, 2.0), 1024.0),
            };
            if i != 0 && i != n {
                x = jitter(rng, x);
            }
            if j != 0 && j != n {
                y = jitter(rng, y);
            }
            pts[j * (n + 1) + i] = [x, y];
        }
    }
    let mut tris = Vec::new();
    let v = |i: usize, j: usize| {
        let [x, y] = pts[j * (n + 1) + i];
        fb(x, y, 128, 128)
    };
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            let pair =
                if rng.below(2) == 0 { [[a, b, c], [a, c, d]] } else { [[a, b, d], [b, c, d]] };
            for t in pair {
                tris.push(wind(t, rng.below(2) == 0));
            }
        }
    }
    tris
}

#[test]
fn triangulated_square_covers_every_pixel_exactly_once() {
    let mut rng = Rng(1);
    // Edges through pixel centres (top/left edges in, bottom/right out), and edges between them.
    let rects = [
        [7.5, 9.5, 119.5, 121.5],
        [7.0 + 77.0 / 256.0, 9.0 + 3.0 / 256.0, 119.0 + 200.0 / 256.0, 120.0 + 129.0 / 256.0],
    ];
    for rect in rects {
        for _ in 0..4 {
            let tris = jittered_square(&mut rng, rect, 12);
            let expected = rect_coverage(128, 128, rect[0], rect[1], rect[2], rect[3]);
            let counts = coverage(128, 128, &tris);
            let bad = coverage_mismatches(&counts, &expected);
            assert!(
                bad.is_empty(),
                "rect {rect:?}: {} pixels wrong, first {:?}",
                bad.len(),
                &bad[..bad.len().min(8)]
            );

            // Negative controls: a duplicated triangle and a missing one are both seen.
            let mut doubled = tris.clone();
            doubled.push(tris[37]);
            assert!(!coverage_mismatches(&coverage(128, 128, &doubled), &expected).is_empty());
            let holed: Vec<_> = tris[1..].to_vec();
            assert!(!coverage_mismatches(&coverage(128, 128, &holed), &expected).is_empty());
        }
    }
}

/// Points around the boundary of a rectangle, in order, corners included.
fn rect_boundary(rng: &mut Rng, rect: [f64; 4], per_side: usize) -> Vec<[f64; 2]> {
    let [x0, y0, x1, y1] = rect;
    let corners = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    let mut out = Vec::new();
    for k in 0..4 {
        let (a, b) = (corners[k], corners[(k + 1) % 4]);
        out.push(a);
        // Half of the points on pixel centres (along the side), half on the 1/1024 grid;
        // sorted after snapping so the walk around the boundary stays monotonic.
        let along = usize::from(a[0] == b[0]); // the coordinate that varies along this side
        let mut cs: Vec<f64> = (0..per_side)
            .map(|_| {
                let c = a[along] + rng.range(0.02, 0.98) * (b[along] - a[along]);
                if rng.below(2) == 0 { c.floor() + 0.5 } else { (c * 1024.0).round() / 1024.0 }
            })
            .collect();
        cs.sort_by(|p, q| (p - a[along]).abs().total_cmp(&(q - a[along]).abs()));
        for c in cs {
            let mut p = a;
            p[along] = c;
            out.push(p);
        }
    }
    out
}

#[test]
fn fan_around_a_shared_vertex_covers_every_pixel_exactly_once() {
    let mut rng = Rng(2);
    let rects = [
        [8.5, 8.5, 72.5, 72.5],
        [8.0 + 5.0 / 256.0, 8.5, 72.0 + 250.0 / 256.0, 71.0 + 1.0 / 256.0],
    ];
    let centres = [[40.5, 40.5], [40.0 + 77.0 / 256.0, 41.0 + 200.0 / 256.0], [33.5, 50.0]];
    for rect in rects {
        for centre in centres {
            for per_side in [1, 5, 16] {
                let boundary = rect_boundary(&mut rng, rect, per_side);
                let c = fb(centre[0], centre[1], 128, 128);
                let tris: Vec<_> = (0..boundary.len())
                    .map(|k| {
                        let [ax, ay] = boundary[k];
                        let [bx, by] = boundary[(k + 1) % boundary.len()];
                        let t = [c, fb(ax, ay, 128, 128), fb(bx, by, 128, 128)];
                        wind(t, rng.below(2) == 0)
                    })
                    .collect();
                let expected = rect_coverage(128, 128, rect[0], rect[1], rect[2], rect[3]);
                let bad = coverage_mismatches(&coverage(128, 128, &tris), &expected);
                assert!(bad.is_empty(), "rect {rect:?} centre {centre:?}: {} wrong", bad.len());
            }
        }
    }
}

#[test]
fn top_left_rule() {
    let (w, h) = (64, 64);
    let covered = |tri: [Vertex<0>; 3], x: u32, y: u32| {
        let a = coverage(w, h, &[tri])[(y * w + x) as usize];
        let b = coverage(w, h, &[wind(tri, true)])[(y * w + x) as usize];
        assert_eq!(a, b, "winding changed coverage of ({x}, {y})");
        a == 1
    };
    let v = |x, y| fb(x, y, w, h);
    // Top edge y = 10.5, left edge x = 10.5, hypotenuse x + y = 41 on its right.
    let a = [v(10.5, 10.5), v(30.5, 10.5), v(10.5, 30.5)];
    assert!(covered(a, 15, 10), "centre on a top edge is drawn");
    assert!(covered(a, 10, 15), "centre on a left edge is drawn");
    assert!(covered(a, 10, 10), "vertex on a pixel centre, top-left corner");
    assert!(!covered(a, 20, 20), "centre on a right (sloped) edge is not drawn");
    assert!(!covered(a, 15, 9) && !covered(a, 9, 15));
    // The other half of the square: bottom edge y = 30.5, right edge x = 30.5, the same
    // hypotenuse on its left.
    let b = [v(30.5, 10.5), v(30.5, 30.5), v(10.5, 30.5)];
    assert!(covered(b, 20, 20), "centre on a left (sloped) edge is drawn");
    assert!(!covered(b, 30, 20), "centre on a right edge is not drawn");
    assert!(!covered(b, 20, 30), "centre on a bottom edge is not drawn");
    assert!(covered(b, 29, 29));
    // A bottom edge with the apex above, and a top edge with the apex below.
    let up = [v(20.5, 5.5), v(30.5, 15.5), v(10.5, 15.5)];
    assert!(!covered(up, 20, 15) && covered(up, 20, 14));
    let down = [v(10.5, 40.5), v(30.5, 40.5), v(20.5, 50.5)];
    assert!(covered(down, 20, 40) && !covered(down, 20, 39));
    // Together the two halves cover the square once.
    let bad =
        coverage_mismatches(&coverage(w, h, &[a, b]), &rect_coverage(w, h, 10.5, 10.5, 30.5, 30.5));
    assert!(bad.is_empty());
}

// ---------------------------------------------------------------------------------------------
// Sub-pixel snapping

/// A rectangle [left, 40.25) × [top, 40.25) as two triangles.
fn rect_tris(left: f64, top: f64) -> Vec<[Vertex<0>; 3]> {
    let v = |x, y| fb(x, y, 64, 64);
    let (a, b, c, d) = (v(left, top), v(40.25, top), v(40.25, 40.25), v(left, 40.25));
    vec![[a, b, c], [a, c, d]]
}

#[test]
fn sub_pixel_snapping_is_8_bits_round_half_even() {
    // The left edge at x = 10.5 goes through the centres of column 10, which the left-edge rule
    // draws; likewise the top edge at y = 10.5 and row 10.
    let base = coverage(64, 64, &rect_tris(10.5, 10.5));
    assert_eq!(base, rect_coverage(64, 64, 10.5, 10.5, 40.25, 40.25));
    // Moves below half a step snap back: ±1/1024; and ties go to even: 10.5·256 = 2688 is
    // even, so 2688 ± ½ (±1/512 px) both round to 2688. (Round-half-up would move the
    // +1/512 edge to 2689 and lose column/row 10.)
    for d in [1.0 / 1024.0, -1.0 / 1024.0, 1.0 / 512.0, -1.0 / 512.0] {
        assert_eq!(coverage(64, 64, &rect_tris(10.5 + d, 10.5)), base, "x moved by {d}");
        assert_eq!(coverage(64, 64, &rect_tris(10.5, 10.5 + d)), base, "y moved by {d}");
    }
    // A whole step to the right/down moves the edge past the centres: exactly column (row)
    // 10 is lost, rows (columns) 10..=39.
    let moved_x = coverage(64, 64, &rect_tris(10.5 + 1.0 / 256.0, 10.5));
    let lost: Vec<usize> = coverage_mismatches(&moved_x, &base);
    let expected: Vec<usize> = (10..40).map(|y| y * 64 + 10).collect();
    assert_eq!(lost, expected);
    let moved_y = coverage(64, 64, &rect_tris(10.5, 10.5 + 1.0 / 256.0));
    let expected: Vec<usize> = (10..40).map(|x| 10 * 64 + x).collect();
    assert_eq!(coverage_mismatches(&moved_y, &base), expected);
    // A step to the left keeps column 10 and gains nothing (column 9's centre is at 9.5).
    assert_eq!(coverage(64, 64, &rect_tris(10.5 - 1.0 / 256.0, 10.5)), base);
    // 2689.5 is a tie that rounds up to the even 2690: the edge moves by 2/256.
    assert_eq!(coverage(64, 64, &rect_tris(10.5 + 3.0 / 512.0, 10.5)), moved_x);
}

// ---------------------------------------------------------------------------------------------
// Perspective, clipping

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn normalize(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    a.map(|c| c / l)
}

/// A right-handed perspective camera with wgpu's clip conventions (z in [0, w]), in f64.
struct Camera {
    eye: V3,
    right: V3,
    up: V3,
    fwd: V3,
    focal: f64,
    aspect: f64,
    near: f64,
    far: f64,
    width: u32,
    height: u32,
}

impl Camera {
    fn new(eye: V3, yaw: f64, pitch: f64, size: (u32, u32), near: f64, far: f64) -> Self {
        let fwd = [-yaw.sin() * pitch.cos(), -pitch.sin(), -yaw.cos() * pitch.cos()];
        let right = normalize(cross(fwd, [0.0, 1.0, 0.0]));
        let up = cross(right, fwd);
        Self {
            eye,
            right,
            up,
            fwd,
            focal: 1.0 / (30f64.to_radians()).tan(), // 60° vertical field of view
            aspect: f64::from(size.0) / f64::from(size.1),
            near,
            far,
            width: size.0,
            height: size.1,
        }
    }

    /// Clip coordinates of a world point, rounded to f32 as a vertex shader would output them.
    fn clip(&self, p: V3) -> [f32; 4] {
        let v = sub(p, self.eye);
        let (xv, yv, zv) = (dot(self.right, v), dot(self.up, v), -dot(self.fwd, v));
        let a = self.far / (self.near - self.far);
        let b = self.near * self.far / (self.near - self.far);
        [
            (self.focal / self.aspect * xv) as f32,
            (self.focal * yv) as f32,
            (a * zv + b) as f32,
            (-zv) as f32,
        ]
    }

    /// The ray through framebuffer point (px, py), scaled so its view depth grows by 1 per unit.
    fn ray(&self, px: f64, py: f64) -> V3 {
        let nx = 2.0 * px / f64::from(self.width) - 1.0;
        let ny = 1.0 - 2.0 * py / f64::from(self.height);
        let (sx, sy) = (nx * self.aspect / self.focal, ny / self.focal);
        std::array::from_fn(|i| self.right[i] * sx + self.up[i] * sy + self.fwd[i])
    }

    /// Where the ray through (px, py) meets the plane y = 0: (x, z, view depth).
    fn ground_hit(&self, px: f64, py: f64) -> Option<(f64, f64, f64)> {
        let d = self.ray(px, py);
        if d[1] >= 0.0 {
            return None;
        }
        let t = -self.eye[1] / d[1];
        Some((self.eye[0] + t * d[0], self.eye[2] + t * d[2], t))
    }
}

/// A ground quad [x0, x1] × [z0, z1] at y = 0 as two triangles with varyings (x, z).
fn ground_quad(cam: &Camera, x0: f64, x1: f64, z0: f64, z1: f64) -> Vec<[Vertex<2>; 3]> {
    let v = |x: f64, z: f64| Vertex::new(cam.clip([x, 0.0, z]), [x as f32, z as f32]);
    let (a, b, c, d) = (v(x0, z0), v(x1, z0), v(x1, z1), v(x0, z1));
    vec![[a, b, c], [a, c, d]]
}

/// Largest |interpolated − analytic| / bound over the covered pixels, for the varyings (x, z)
/// of the ground plane. The bound: each snapped vertex moves ≤ 1/512 px per axis, which moves
/// the interpolated map by as much, so |error| ≤ |∇v|₁ · 1/512 to first order; 1/256 leaves a
/// factor 2 for second order and the f32 rounding of the clip coordinates (~1e-5 px). Plus f32
/// arithmetic: the weights carry ≲ 8 ulp (4.8e-7) relative error, times the largest |v| at the
/// vertices, `v_max`.
fn ground_error_ratio(
    cam: &Camera,
    image: &RenderTarget,
    v_max: f64,
    value: impl Fn([f32; 4]) -> [f64; 2],
) -> (f64, usize) {
    let analytic = |px: f64, py: f64| cam.ground_hit(px, py).map(|(x, z, _)| [x, z]);
    let mut worst = 0.0f64;
    let mut compared = 0;
    for y in 0..image.height {
        for x in 0..image.width {
            let c = image.pixel(x, y);
            if c[3] == 0.0 {
                continue; // not covered
            }
            let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            let h = 1.0 / 8.0;
            let (Some(v), Some(l), Some(r), Some(u), Some(d)) = (
                analytic(px, py),
                analytic(px - h, py),
                analytic(px + h, py),
                analytic(px, py - h),
                analytic(px, py + h),
            ) else {
                continue;
            };
            let got = value(c);
            for k in 0..2 {
                let grad = ((r[k] - l[k]).abs() + (d[k] - u[k]).abs()) / (2.0 * h);
                let bound = grad / 256.0 + 8.0 * f64::from(f32::EPSILON) / 2.0 * v_max * 3.0;
                worst = worst.max((got[k] - v[k]).abs() / bound);
            }
            compared += 1;
        }
    }
    (worst, compared)
}

#[test]
fn perspective_correct_interpolation_matches_the_analytic_plane() {
    let cam = Camera::new([0.0, 2.0, 0.0], 0.3, 0.35, (128, 96), 0.1, 1000.0);
    let quad = ground_quad(&cam, -10.0, 10.0, -40.0, -2.0);
    let mut image = RenderTarget::new(128, 96);
    draw(&mut image, &RasterState::default(), &quad, |f| {
        Some([f.varyings[0], f.varyings[1], 0.0, 1.0])
    });
    let (ratio, compared) =
        ground_error_ratio(&cam, &image, 40.0, |c| [f64::from(c[0]), f64::from(c[1])]);
    println!("perspective: {compared} pixels, worst error / bound = {ratio:.3}");
    assert!(compared > 3000, "the quad covers much of the view ({compared})");
    assert!(ratio <= 1.0, "worst error / bound = {ratio}");

    // Negative control: screen-space affine interpolation of the same varyings. Interpolating
    // (x·w, z·w, w) perspective-correctly and dividing gives exactly the affine result.
    let affine: Vec<[Vertex<3>; 3]> = quad
        .iter()
        .map(|t| {
            t.map(|v| {
                let w = v.clip[3];
                Vertex::new(v.clip, [v.varyings[0] * w, v.varyings[1] * w, w])
            })
        })
        .collect();
    let mut image = RenderTarget::new(128, 96);
    draw(&mut image, &RasterState::default(), &affine, |f| {
        let v = f.varyings;
        Some([v[0] / v[2], v[1] / v[2], 0.0, 1.0])
    });
    let (ratio, _) = ground_error_ratio(&cam, &image, 40.0, |c| [f64::from(c[0]), f64::from(c[1])]);
    println!("affine (negative control): worst error / bound = {ratio:.1}");
    assert!(ratio > 10.0, "affine interpolation must fail the bound ({ratio})");
}

#[test]
fn near_plane_clipping_of_a_huge_ground_plane() {
    // A 20 km ground quad around the camera: two of its corners are behind the eye (w < 0).
    // The last case puts the far plane across the quad.
    for (yaw, pitch, far) in
        [(0.5, 0.17, 1e5), (2.0, 0.3, 1e5), (-0.8, -0.1, 1e5), (0.0, 0.6, 1e5), (0.4, 0.05, 3e3)]
    {
        let cam = Camera::new([3.0, 2.0, -1.0], yaw, pitch, (128, 96), 0.1, far);
        let l = 1e4;
        let quad = ground_quad(&cam, -l, l, -l, l);
        assert!(quad.iter().flatten().any(|v| v.clip[3] < 0.0));
        let mut image = RenderTarget::new(128, 96);
        let state = counting_state();
        draw(&mut image, &state, &quad, |f: &FragmentInput<2>| {
            assert!(f.varyings.iter().chain(&f.frag_coord).all(|c| c.is_finite()));
            assert!((0.0..=1.0).contains(&f.frag_coord[2]));
            Some([f.varyings[0], f.varyings[1], 0.0, 1.0])
        });

        // Expected coverage of pixel centres; a centre within 1/64 px of the plane's outline
        // (horizon, far edge) is ambiguous under snapping and is skipped.
        let inside = |px: f64, py: f64| {
            cam.ground_hit(px, py).is_some_and(|(x, z, depth)| {
                x.abs() <= l && (z).abs() <= l && depth >= cam.near && depth <= cam.far
            })
        };
        let mut ambiguous = 0;
        let mut covered = 0;
        for y in 0..96 {
            for x in 0..128 {
                let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                let e = 1.0 / 64.0;
                let votes = [(0.0, 0.0), (e, 0.0), (-e, 0.0), (0.0, e), (0.0, -e)]
                    .map(|(dx, dy)| inside(px + dx, py + dy));
                let count = image.pixel(x, y)[3];
                assert!(count == 0.0 || count == 1.0, "({x}, {y}) drawn {count} times");
                if votes.iter().all(|&v| v == votes[0]) {
                    assert_eq!(count == 1.0, votes[0], "pixel ({x}, {y}), yaw {yaw}");
                } else {
                    ambiguous += 1;
                }
                covered += u32::from(count == 1.0);
            }
        }
        println!("clip yaw {yaw} pitch {pitch}: {covered} covered, {ambiguous} ambiguous");
        assert!(ambiguous <= 8, "{ambiguous} ambiguous pixels");
        assert!(covered > 0);

        // Values behind clipping still follow the analytic plane.
        let (ratio, compared) =
            ground_error_ratio(&cam, &image, l, |c| [f64::from(c[0]), f64::from(c[1])]);
        println!("clip yaw {yaw}: {compared} pixels, worst error / bound = {ratio:.3}");
        assert!(ratio <= 1.0, "worst error / bound = {ratio}");
    }
}

#[test]
fn triangles_behind_the_eye_or_at_w_zero() {
    let state = counting_state();
    let count = |tris: &[[Vertex<0>; 3]]| {
        let mut t = RenderTarget::new(32, 32);
        draw(&mut t, &state, tris, |_| Some([1.0, 0.0, 0.0, 0.0]));
        assert!(t.color.iter().flatten().all(|c| c.is_finite()));
        t.color.iter().map(|c| c[0] as u32).sum::<u32>()
    };
    let v = |x, y, z, w| Vertex::new([x, y, z, w], []);
    // Entirely behind the eye (w < 0; the mirror image of a visible triangle).
    assert_eq!(
        count(&[[v(0.5, 0.5, -0.5, -1.0), v(-0.5, 0.5, -0.5, -1.0), v(0.0, -0.5, -0.5, -1.0)]]),
        0
    );
    // Its visible twin covers something.
    assert!(count(&[[v(-0.5, -0.5, 0.5, 1.0), v(0.5, -0.5, 0.5, 1.0), v(0.0, 0.5, 0.5, 1.0)]]) > 0);
    // One vertex behind the eye: exactly the part of the projective triangle with w > 0 is
    // drawn. Pixel centre p is in it iff (p_x, p_y, 1) is a positive combination of the three
    // (x, y, w); the other solution (all weights negative) is the external triangle that an
    // unclipped rasterizer would draw. z/w = 0.5 all over, so near/far do not cut.
    let tri = [v(-0.5, -0.5, 0.5, 1.0), v(0.5, -0.5, 0.5, 1.0), v(0.2, 1.0, -0.5, -1.0)];
    let mut t = RenderTarget::new(32, 32);
    draw(&mut t, &state, &[tri], |_| Some([1.0, 0.0, 0.0, 0.0]));
    let m = tri.map(|v| [v.clip[0], v.clip[1], v.clip[3]].map(f64::from));
    let det3 = |a: V3, b: V3, c: V3| dot(a, cross(b, c));
    let det = det3(m[0], m[1], m[2]);
    let (mut drawn, mut ambiguous) = (0, 0);
    for y in 0..32 {
        for x in 0..32 {
            let p = [(f64::from(x) + 0.5) / 16.0 - 1.0, 1.0 - (f64::from(y) + 0.5) / 16.0, 1.0];
            // Cramer's rule for the weights of the three vertices.
            let wts =
                [det3(p, m[1], m[2]), det3(m[0], p, m[2]), det3(m[0], m[1], p)].map(|d| d / det);
            let got = t.pixel(x, y)[0];
            drawn += u32::from(got == 1.0);
            // Centres on (or within rounding of) an edge: the top-left rule decides them, and
            // it is tested on its own above. This triangle has a few.
            if wts.iter().any(|w| w.abs() < 1e-6) {
                ambiguous += 1;
            } else {
                assert_eq!(got == 1.0, wts.iter().all(|&w| w > 0.0), "({x}, {y}): {wts:?}");
            }
        }
    }
    assert!(drawn > 50 && ambiguous <= 8, "{drawn} drawn, {ambiguous} ambiguous");
    // Vertices at w = 0: on the near plane at infinity, and the degenerate origin.
    for bad in [v(1.0, 1.0, 0.0, 0.0), v(0.0, 0.0, 0.0, 0.0), v(0.0, 0.5, 0.0, 1e-38)] {
        count(&[[v(-0.5, -0.5, 0.5, 1.0), v(0.5, -0.5, 0.5, 1.0), bad]]);
    }
}

#[test]
fn near_and_far_planes_cut_in_depth() {
    // A screen-covering quad at w = 1 whose z_ndc runs from −0.5 at the left edge of the view
    // to 1.5 at the right: z_ndc = 0.5 + x_ndc. Only 0 ≤ z ≤ w survives, i.e. −0.5 ≤ x_ndc ≤
    // 0.5: framebuffer x in [8, 24] on a 32-wide target, columns 8..=23 (no centre on the cut).
    let v = |x: f32, y: f32| Vertex::new([x, y, 0.5 + x, 1.0], []);
    let (a, b, c, d) = (v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0));
    let counts = coverage(32, 16, &[[a, b, c], [a, c, d]]);
    let expected: Vec<u32> = (0..16 * 32).map(|i| u32::from((8..24).contains(&(i % 32)))).collect();
    assert!(coverage_mismatches(&counts, &expected).is_empty(), "{counts:?}");
    // Tilted through w as well: z = 0.5·w + x, w = 1.5 + 0.5·y: z/w = 0.5 + x/w, the same cut
    // in x_ndc whatever the row.
    let v = |x: f32, y: f32| {
        let w = 1.5 + 0.5 * y;
        Vertex::new([x * w, y * w, 0.5 * w + x * w, w], [])
    };
    let (a, b, c, d) = (v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0));
    let counts = coverage(32, 16, &[[a, b, c], [a, c, d]]);
    assert!(coverage_mismatches(&counts, &expected).is_empty(), "{counts:?}");
}

// ---------------------------------------------------------------------------------------------
// Depth

#[test]
fn opaque_depth_test_is_order_independent() {
    // Five overlapping triangles, each at its own constant depth (z = depth · w with varying w,
    // so perspective is involved), each with its own colour.
    let mut rng = Rng(5);
    let tris: Vec<[Vertex<1>; 3]> = (0..5)
        .map(|k| {
            let depth = 0.15 + 0.17 * k as f32;
            std::array::from_fn(|_| {
                let w = rng.range(0.5, 2.0) as f32;
                let (x, y) = (rng.range(-2.5, 2.5) as f32, rng.range(-2.5, 2.5) as f32);
                Vertex::new([x * w, y * w, depth * w, w], [k as f32])
            })
        })
        .collect();
    let render = |order: &[usize], compare| {
        let mut t = RenderTarget::new(48, 48);
        let state = RasterState { depth_compare: compare, ..RasterState::default() };
        if compare == CompareFunction::Greater {
            t.clear_depth(0.0);
        }
        let list: Vec<_> = order.iter().map(|&i| tris[i]).collect();
        draw(&mut t, &state, &list, |f| Some([f.varyings[0], 1.0, 0.0, 1.0]));
        bits(&t)
    };
    let perms = permutations(5);
    assert_eq!(perms.len(), 120);
    for compare in [CompareFunction::Less, CompareFunction::Greater, CompareFunction::LessEqual] {
        let first = render(&perms[0], compare);
        for p in &perms[1..] {
            assert!(render(p, compare) == first, "{compare:?}: order {p:?} differs");
        }
    }
    // Negative control: without the depth test the order shows.
    let first = render(&perms[0], CompareFunction::Always);
    assert!(perms[1..].iter().any(|p| render(p, CompareFunction::Always) != first));
}

fn permutations(n: usize) -> Vec<Vec<usize>> {
    if n == 0 {
        return vec![vec![]];
    }
    let mut out = Vec::new();
    for p in permutations(n - 1) {
        for i in 0..=p.len() {
            let mut q = p.clone();
            q.insert(i, n - 1);
            out.push(q);
        }
    }
    out
}

#[test]
fn depth_is_interpolated_linearly_in_screen_space_and_culling_follows_the_winding() {
    // A triangle with a vertex at each depth: frag_coord.z at a pixel is the screen-space
    // barycentric blend of the vertices' z/w, whatever their w.
    let v = |x: f32, y: f32, z: f32, w: f32| Vertex::new([x * w, y * w, z * w, w], []);
    let tri = [v(-1.0, -1.0, 0.2, 1.0), v(3.0, -1.0, 0.6, 4.0), v(-1.0, 3.0, 0.9, 0.5)];
    let mut t = RenderTarget::new(16, 16);
    draw(&mut t, &RasterState::default(), &[tri], |f| Some([f.frag_coord[2], 0.0, 0.0, 1.0]));
    for y in 0..16 {
        for x in 0..16 {
            // Screen-space plane through the three (x_fb, y_fb, z): z = 0.2 + 0.4·u + 0.7·v
            // with u, v the fractions of the width (from the left) and height (from the bottom).
            let (u, vv) = ((f64::from(x) + 0.5) / 32.0, (16.0 - f64::from(y) - 0.5) / 32.0);
            let expected = 0.2 + 0.4 * u + 0.7 * vv;
            let got = f64::from(t.pixel(x, y)[0]);
            assert!((got - expected).abs() < 1e-6, "({x}, {y}): {got} vs {expected}");
            assert_eq!(t.depth[(y * 16 + x) as usize], t.pixel(x, y)[0]);
        }
    }

    // tri is counter-clockwise on screen (NDC y up): front-facing under Ccw.
    let facing = |state: RasterState| {
        let mut t = RenderTarget::new(16, 16);
        draw(&mut t, &state, &[tri], |f| {
            Some([f32::from(u8::from(f.front_facing)), 1.0, 0.0, 0.0])
        });
        (t.pixel(2, 13)[1] == 1.0).then_some(t.pixel(2, 13)[0] == 1.0)
    };
    let s = RasterState::default();
    assert_eq!(facing(s), Some(true));
    assert_eq!(facing(RasterState { front_face: FrontFace::Cw, ..s }), Some(false));
    assert_eq!(facing(RasterState { cull_mode: CullMode::Back, ..s }), Some(true));
    assert_eq!(facing(RasterState { cull_mode: CullMode::Front, ..s }), None);
    let cw = RasterState { front_face: FrontFace::Cw, cull_mode: CullMode::Back, ..s };
    assert_eq!(facing(cw), None);
}

// ---------------------------------------------------------------------------------------------
// Determinism

/// 3000 random triangles in perspective, some crossing the near plane, with a shader that
/// discards a pattern and blends premultiplied-over with a depth test.
fn busy_scene(seed: u64) -> Vec<[Vertex<3>; 3]> {
    let mut rng = Rng(seed);
    (0..3000)
        .map(|_| {
            let (cx, cy) = (rng.range(-1.3, 1.3), rng.range(-1.3, 1.3));
            let size = if rng.below(20) == 0 { 1.5 } else { 0.15 };
            std::array::from_fn(|_| {
                let w = rng.range(-0.2, 3.0) as f32;
                let x = (cx + rng.range(-size, size)) as f32;
                let y = (cy + rng.range(-size, size)) as f32;
                let z = rng.range(0.0, 1.0) as f32;
                Vertex::new(
                    [x * w, y * w, z * w, w],
                    [rng.unit() as f32, rng.unit() as f32, rng.unit() as f32],
                )
            })
        })
        .collect()
}

fn render_busy(tris: &[[Vertex<3>; 3]]) -> RenderTarget {
    let mut t = RenderTarget::new(203, 157);
    t.clear_color([0.1, 0.2, 0.3, 1.0]);
    let state = RasterState {
        depth_compare: CompareFunction::LessEqual,
        blend: BlendMode::PremultipliedOver,
        ..RasterState::default()
    };
    draw(&mut t, &state, tris, |f| {
        let [r, g, b] = f.varyings;
        if (r * 7.0).fract() < 0.1 {
            return None;
        }
        let a = 0.3 + 0.6 * g;
        Some([r * a, g * f.frag_coord[3].min(4.0) * a, b * f.frag_coord[2] * a, a])
    });
    t
}

#[test]
fn identical_bits_for_any_thread_count_and_run() {
    let tris = busy_scene(8);
    let in_pool = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        pool.install(|| render_busy(&tris))
    };
    let one = bits(&in_pool(1));
    assert!(bits(&in_pool(2)) == one, "2 threads differ from 1");
    assert!(bits(&in_pool(3)) == one, "3 threads differ from 1");
    assert!(bits(&in_pool(2)) == one, "a second run differs");
    assert!(bits(&render_busy(&tris)) == one, "the global pool differs");

    // The scene is not trivial: many distinct colours, some discards, some depth rejections.
    let t = in_pool(1);
    let mut colors: Vec<[u32; 4]> = t.color.iter().map(|c| c.map(f32::to_bits)).collect();
    colors.sort_unstable();
    colors.dedup();
    assert!(colors.len() > 5000, "{} distinct colours", colors.len());

    // Negative control: the comparator sees one ulp in one pixel.
    let mut other = in_pool(1);
    other.color[12345][1] = f32::from_bits(other.color[12345][1].to_bits() + 1);
    assert!(bits(&other) != one);
}

// ---------------------------------------------------------------------------------------------
// Robustness

#[test]
fn degenerate_triangles_draw_nothing() {
    let v = |x, y| fb(x, y, 32, 32);
    let cases = [
        [v(3.0, 3.0), v(3.0, 3.0), v(3.0, 3.0)],
        [v(3.0, 3.0), v(20.0, 20.0), v(3.0, 3.0)],
        [v(3.5, 3.5), v(10.5, 10.5), v(28.5, 28.5)], // collinear through centres
        [v(3.0, 5.5), v(29.0, 5.5), v(17.0, 5.5)],   // horizontal line of centres
        [v(3.0, 3.0), v(3.0 + 1.0 / 1024.0, 20.0), v(3.0, 20.0)], // zero area once snapped
    ];
    for tri in cases {
        assert_eq!(coverage(32, 32, &[tri]).iter().sum::<u32>(), 0, "{tri:?}");
    }
    let nan = Vertex::new([f32::NAN, 0.0, 0.5, 1.0], []);
    let inf = Vertex::new([0.0, f32::INFINITY, 0.5, 1.0], []);
    for bad in [nan, inf] {
        assert_eq!(coverage(32, 32, &[[v(1.0, 1.0), v(30.0, 2.0), bad]]).iter().sum::<u32>(), 0);
    }
}

#[test]
fn enormous_triangles_are_clipped_exactly() {
    // A screen-covering triangle with coordinates ±1e30 (w = 1) covers every pixel once.
    let v = |x: f32, y: f32, w: f32| Vertex::new([x, y, 0.5 * w, w], []);
    let big = [v(-1e30, -1e30, 1.0), v(3e30, -1e30, 1.0), v(-1e30, 3e30, 1.0)];
    assert!(coverage(32, 32, &[big]).iter().all(|&c| c == 1));
    // The same with tiny w: the same projective triangle.
    let tiny = [v(-1e-20, -1e-20, 1e-30), v(3e-20, -1e-20, 1e-30), v(-1e-20, 3e-20, 1e-30)];
    assert!(coverage(32, 32, &[tiny]).iter().all(|&c| c == 1));
    // Split along the diagonal: still once.
    let (a, b, c, d) =
        (v(-1e30, -1e30, 1.0), v(1e30, -1e30, 1.0), v(1e30, 1e30, 1.0), v(-1e30, 1e30, 1.0));
    assert!(coverage(32, 32, &[[a, b, c], [a, c, d]]).iter().all(|&c| c == 1));
}

#[test]
fn extreme_inputs_never_panic_and_stay_finite() {
    let values = [
        0.0,
        -0.0,
        1e-45,
        -1e-45,
        1e-38,
        1e-30,
        -1e-30,
        1e-20,
        0.5,
        -0.5,
        1.0,
        -1.0,
        2.0,
        1e20,
        -1e20,
        1e30,
        -1e30,
        4e37,
        -4e37,
        3e38,
        -3e38,
        f32::MAX,
        f32::MIN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ];
    let mut rng = Rng(9);
    let tris: Vec<[Vertex<2>; 3]> = (0..20_000)
        .map(|_| {
            std::array::from_fn(|_| {
                let clip = std::array::from_fn(|_| values[rng.below(values.len() as u64) as usize]);
                Vertex::new(clip, [rng.unit() as f32, rng.unit() as f32])
            })
        })
        .collect();
    let mut t = RenderTarget::new(64, 48);
    draw(&mut t, &RasterState::default(), &tris, |f| {
        Some([f.varyings[0], f.varyings[1], f.frag_coord[2], f.frag_coord[3].min(1e30)])
    });
    let drawn = t.depth.iter().filter(|&&d| d < 1.0).count();
    println!("extreme inputs: {drawn} pixels drawn");
    assert!(drawn > 0, "some of these triangles are visible");
    assert!(t.color.iter().flatten().all(|c| c.is_finite()));
    assert!(t.depth.iter().all(|d| (0.0..=1.0).contains(d)));
}
