//! The rasteriser envelope's unit tests: barycentrics, varyings, coverage and depth.

use super::*;

fn v(x: f64, y: f64, z: f64) -> ScreenIv {
    let p = |a: f64| Iv::point(a as f32);
    ScreenIv { x: p(x), y: p(y), z: p(z), inv_w: p(1.0), on: None }
}

/// The barycentrics at a sample of a thin triangle (the projected grid's, 16 px² with
/// its least singular value 2 px) hold those of every triangle whose vertices lie in the
/// boxes, snapped or not; the edge functions' quotient makes them several times tighter
/// than the plane's bound alone, whose gradient error grows with the distance from its
/// anchor. Negative control: the bounds of boxes half as wide miss some.
#[test]
fn the_barycentrics_hold_every_triangle_in_the_boxes_and_are_tight() {
    let c = [[52.377f64, 96.2535], [63.422, 89.127], [58.229, 89.530]];
    let (half, snap) = (0.0024, 1.0 / 256.0);
    let setup_with = |half: f64, snap: f64| {
        let tri: [ScreenIv; 3] = std::array::from_fn(|k| ScreenIv {
            x: Iv::new(c[k][0] - half, c[k][0] + half),
            y: Iv::new(c[k][1] - half, c[k][1] + half),
            z: Iv::point(0.002),
            inv_w: Iv::point(0.03),
            on: None,
        });
        setup(&tri, 256, 144, snap).unwrap()
    };
    let (t, narrow) = (setup_with(half, snap), setup_with(half / 2.0, snap / 2.0));
    let mut g = ocean_core::rng::SplitMix64::new(7);
    let (mut samples, mut missed, mut widths) = (0, 0, [0.0; 2]);
    for (sx, sy) in [(56.5, 92.5), (58.5, 90.5), (55.5, 93.5), (60.5, 90.5)] {
        let (b, bn) = (barycentrics(&t, sx, sy), barycentrics(&narrow, sx, sy));
        let plane = t.bary[1].map(|p| p.at(sx, sy)).unwrap();
        let mut seen = [f64::INFINITY, f64::NEG_INFINITY];
        for _ in 0..20_000 {
            // Vertices anywhere in their boxes (half of them at the boxes' corners, where
            // the extremes lie), snapped or not.
            let corners = g.next_open_closed() < 0.5;
            let mut at = |k: usize, d: usize| {
                let u = g.next_open_closed();
                let s = if corners { if u < 0.5 { -1.0 } else { 1.0 } } else { 2.0 * u - 1.0 };
                c[k][d] + s * (half + snap)
            };
            let v: [[f64; 2]; 3] = std::array::from_fn(|k| [at(k, 0), at(k, 1)]);
            let area = |a: [f64; 2], b: [f64; 2], p: [f64; 2]| {
                (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
            };
            let whole = area(v[0], v[1], v[2]);
            let l1 = area(v[2], v[0], [sx, sy]) / whole;
            let l2 = area(v[0], v[1], [sx, sy]) / whole;
            assert!((b.l1.0..=b.l1.1).contains(&l1), "λ₁ {l1} outside {:?}", b.l1);
            assert!((b.l2.0..=b.l2.1).contains(&l2), "λ₂ {l2} outside {:?}", b.l2);
            let inside = |r: (f64, f64), l: f64| (r.0..=r.1).contains(&l);
            missed += usize::from(!inside(bn.l1, l1) || !inside(bn.l2, l2));
            seen = [seen[0].min(l1), seen[1].max(l1)];
            samples += 1;
        }
        println!(
            "({sx}, {sy}): λ₁ over the boxes spans {:.4}, bound {:.4}, the plane's alone {:.4}",
            seen[1] - seen[0],
            b.l1.1 - b.l1.0,
            plane.1 - plane.0
        );
        widths[0] += b.l1.1 - b.l1.0;
        widths[1] += plane.1 - plane.0;
    }
    // The claim is "several times tighter": at least 2.5× over the four samples (3.3–3.8×
    // at each when this was written).
    assert!(2.5 * widths[0] < widths[1], "{widths:?}: not tighter than the plane's bound");
    println!("{samples} triangles; {missed} outside the bounds of boxes half as wide");
    assert!(missed > 0, "the bounds of boxes half as wide held all {samples} triangles");
}

/// The interpolation bound by the vertices' moves (`Interp::moved_vertices`) holds the
/// perspective interpolation of every triangle in the boxes (the projected grid's thin
/// triangle again, a distant one: 1/w near 0.025, values 40 m apart by a metre or two,
/// each known within 2 mm), and is several times tighter than the barycentrics' box.
/// Negative control: the bound of boxes half as wide misses some.
#[test]
fn moving_vertices_bound_the_varying_tighter_than_the_barycentrics_box() {
    let c = [[52.377f64, 96.2535], [63.422, 89.127], [58.229, 89.530]];
    let (half, snap) = (0.0024, 1.0 / 256.0);
    let m = [-40.2f64, -41.5, -40.9];
    let (m_err, q) = (0.002, [0.0251f64, 0.0243, 0.0247]);
    let q_err = 1e-8;
    let setup_with = |half: f64, snap: f64| {
        let tri: [ScreenIv; 3] = std::array::from_fn(|k| ScreenIv {
            x: Iv::new(c[k][0] - half, c[k][0] + half),
            y: Iv::new(c[k][1] - half, c[k][1] + half),
            z: Iv::point(0.002),
            inv_w: Iv::new(q[k] - q_err, q[k] + q_err),
            on: None,
        });
        setup(&tri, 256, 144, snap).unwrap()
    };
    let vals = m.map(|m| Iv::new(m - m_err, m + m_err));
    let (t, narrow) = (setup_with(half, snap), setup_with(half / 2.0, snap / 2.0));
    let mut g = ocean_core::rng::SplitMix64::new(11);
    let (mut samples, mut missed, mut widths) = (0, 0, [0.0; 2]);
    for (sx, sy) in [(56.5, 92.5), (58.5, 90.5), (55.5, 93.5), (60.5, 90.5)] {
        let (b, bn) = (barycentrics(&t, sx, sy), barycentrics(&narrow, sx, sy));
        let moved = b.moved_vertices(vals).unwrap();
        let narrow_moved = bn.moved_vertices(vals).unwrap();
        let boxed = Interp { boxes: [[(f64::NEG_INFINITY, f64::INFINITY); 3]; 2], ..b };
        let whole_bound = b.varying(vals);
        let box_only = boxed.varying(vals);
        assert!(boxed.moved_vertices(vals).is_none());
        for _ in 0..20_000 {
            let corners = g.next_open_closed() < 0.5;
            let mut pick = |centre: f64, r: f64| {
                let u = g.next_open_closed();
                let s = if corners { if u < 0.5 { -1.0 } else { 1.0 } } else { 2.0 * u - 1.0 };
                centre + s * r
            };
            let v: [[f64; 2]; 3] =
                std::array::from_fn(|k| [pick(c[k][0], half + snap), pick(c[k][1], half + snap)]);
            let mv: [f64; 3] = std::array::from_fn(|k| pick(m[k], m_err));
            let qv: [f64; 3] = std::array::from_fn(|k| pick(q[k], q_err));
            let area = |a: [f64; 2], b: [f64; 2], p: [f64; 2]| {
                (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
            };
            let whole = area(v[0], v[1], v[2]);
            let l = [
                area(v[1], v[2], [sx, sy]),
                area(v[2], v[0], [sx, sy]),
                area(v[0], v[1], [sx, sy]),
            ]
            .map(|e| e / whole);
            let num: f64 = (0..3).map(|k| l[k] * qv[k] * mv[k]).sum();
            let den: f64 = (0..3).map(|k| l[k] * qv[k]).sum();
            let x = num / den;
            // 1e-12: the sums here are f64 too.
            let within = |r: (f64, f64)| r.0 - 1e-12 <= x && x <= r.1 + 1e-12;
            assert!(within(moved), "{x} outside {moved:?} at ({sx}, {sy})");
            assert!(within((whole_bound.lo, whole_bound.hi)), "{x} outside {whole_bound:?}");
            missed += usize::from(!within(narrow_moved));
            samples += 1;
        }
        widths[0] += moved.1 - moved.0;
        widths[1] += box_only.hi - box_only.lo;
        println!(
            "({sx}, {sy}): moved vertices {:.3e} wide, the barycentrics' box {:.3e}",
            moved.1 - moved.0,
            box_only.hi - box_only.lo
        );
    }
    assert!(3.0 * widths[0] < widths[1], "{widths:?}: not several times tighter");
    println!("{samples} triangles; {missed} outside the bound of boxes half as wide");
    assert!(missed > 0, "the bound of boxes half as wide held all {samples} triangles");
}

/// A large triangle: its interior certain, its outside not covered, a band along its
/// edges possible, and the depth at an interior sample close to the plane's.
#[test]
fn a_triangle_is_certain_inside_possible_at_its_edges() {
    let t =
        setup(&[v(1.0, 1.0, 0.2), v(30.0, 2.0, 0.4), v(5.0, 28.0, 0.6)], 32, 32, SNAP_PX).unwrap();
    assert!(matches!(cover(&t, 8.5, 8.5), Cover::Certain(_)));
    assert_eq!(cover(&t, 30.5, 30.5), Cover::No);
    // On the edge from (1, 1) to (30, 2), well inside in x.
    let y_edge = 1.0 + (15.5 - 1.0) / 29.0;
    assert!(matches!(cover(&t, 15.5, y_edge + 0.01), Cover::Possible(_)));
    let Cover::Certain(z) = cover(&t, 10.5, 10.5) else { panic!() };
    assert!(z.lo > 0.2 && z.hi < 0.6 && z.hi - z.lo < 0.02, "{z:?}");
}

/// Beyond one side plane at every vertex for every value of the boxes: culled; a vertex
/// whose box reaches inside, or vertices beyond different planes: kept.
#[test]
fn a_triangle_beyond_one_side_plane_is_culled() {
    let v = |x: f64, y: f64, w: f64| {
        [Iv::new(x, x + 0.1), Iv::new(y, y), Iv::point(0.05), Iv::new(w, w)]
    };
    assert!(outside_a_side([v(5.0, 0.0, 2.0), v(9.0, 1.0, 3.0), v(37096.0, -34.0, -628.0)]));
    assert!(outside_a_side([v(0.0, -5.0, 2.0), v(1.0, -9.0, 3.0), v(0.5, -700.0, -628.0)]));
    assert!(!outside_a_side([v(1.95, 0.0, 2.0), v(9.0, 1.0, 3.0), v(8.0, 0.0, 1.0)]));
    assert!(!outside_a_side([v(5.0, 0.0, 2.0), v(-9.0, 1.0, 3.0), v(8.0, 0.0, 1.0)]));
}

/// A depth-only pass of two overlapping triangles keeps the nearer where both certainly
/// cover, and the clear value outside.
#[test]
fn the_nearer_triangle_wins() {
    let far = [v(0.0, 0.0, 0.8), v(16.0, 0.0, 0.8), v(0.0, 16.0, 0.8)];
    let near = [v(0.0, 0.0, 0.3), v(16.0, 0.0, 0.3), v(0.0, 16.0, 0.3)];
    let (env, amb) = depth_pass(&[far, near], 16, 16, 1.0, SNAP_PX);
    let at = |x: usize, y: usize| env[y * 16 + x];
    assert!(at(3, 3).contains(0.3) && !at(3, 3).contains(0.8));
    assert!(at(15, 15).contains(1.0) && !at(15, 15).contains(0.3));
    assert!(!amb[3 * 16 + 3] && amb.iter().any(|&a| a));
}

/// A varying interpolated as lavapipe does, by f32 plane equations of a·q and q anchored
/// at the target's origin and their quotient, at every sample of a small triangle far
/// from the origin (a 4096² target, lavapipe's 1/256-px snap): inside
/// [`Interp::varying`]; and outside the bound without the planes' allowance somewhere (the
/// negative control: the old bound, which a boat's triangle in the 256×144 reflection map
/// of `coastal_island` left on lavapipe).
#[test]
fn plane_equations_anchored_far_away_stay_inside_the_varying_bound() {
    let (w, h) = (4096u32, 4096u32);
    let p = [[4000.25f32, 3990.125], [4004.125, 3991.875], [4001.0, 3995.75]];
    let q = [0.02f32, 0.03, 0.045];
    let a = [0.866f32, 0.8662, 0.8658];
    let tri = exact_triangle(p, q);
    let t = setup(&tri, w, h, 1.0 / 256.0).unwrap();
    let (num, den) = (f32_plane(p, std::array::from_fn(|k| a[k] * q[k])), f32_plane(p, q));
    let (mut samples, mut past_old) = (0, 0);
    for py in 3988..3998 {
        for px in 3998..4006 {
            let (sx, sy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
            if cover(&t, sx, sy) == Cover::No {
                continue;
            }
            let got = num(sx as f32, sy as f32) / den(sx as f32, sy as f32);
            let interp = barycentrics(&t, sx, sy);
            let bound = interp.varying(a.map(Iv::point));
            assert!(bound.contains(got), "{got} at ({px}, {py}) outside {bound:?}");
            let old =
                Interp { anchor: [0.0; 3], lam: [0.0; 3], ..interp }.varying(a.map(Iv::point));
            past_old += usize::from(!old.contains(got));
            samples += 1;
        }
    }
    assert!(samples > 4 && past_old > 0, "{samples} samples, {past_old} past the old bound");
}

/// A horizon triangle of `chiu_shallow`'s projected grid (diagnostic dump, 256×144): two
/// vertices 170 m away at 1/w = 0.0057, the third 3.3·10⁶ m away at 1/w = 10⁻⁷, four pixels
/// below it. Interpolated as lavapipe does (f32 planes of a·q and q, from each vertex as
/// base, anchored at the origin), every sample lies inside [`Interp::varying`]; the quotient's
/// error is now scaled by the value at the sample (|v| within the corners' range, −2400 m
/// there), not by the far vertex's 3.3·10⁶ m, which made these pixels' envelope unbounded
/// (`chiu_shallow`'s 1,030): the bound is now 190 m wide at most, the vertices' moves within
/// the snap. Negative control: a GPU interpolating without perspective leaves it.
#[test]
fn a_horizon_triangle_s_varying_holds_f32_planes() {
    let p = [[76.82f32, 59.23], [81.49, 59.38], [81.63, 55.40]];
    let q = [0.005_666_85f32, 0.005_668_35, 1.007_174e-7];
    let a = [-65.2941f32, -59.3255, -3_328_705.0];
    let tri = exact_triangle(p, q);
    let t = setup(&tri, 256, 144, 1.0 / 256.0).unwrap();
    let (mut samples, mut left, mut widest) = (0, 0, 0.0f64);
    for py in 55..60 {
        for px in 76..82 {
            let (sx, sy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
            if cover(&t, sx, sy) == Cover::No {
                continue;
            }
            let interp = barycentrics(&t, sx, sy);
            let bound = interp.varying(a.map(Iv::point));
            let pos = p.map(|p| [f64::from(p[0]), f64::from(p[1]), 0.0]);
            let l = screen_barycentrics(&pos, sx, sy);
            let linear = (0..3).map(|k| l[k] * f64::from(a[k])).sum::<f64>();
            left += usize::from(!(bound.lo <= linear && linear <= bound.hi));
            assert!(bound.hi - bound.lo < 1e3, "({px}, {py}): {bound:?}");
            widest = widest.max(bound.hi - bound.lo);
            for base in 0..3 {
                let order = [base, (base + 1) % 3, (base + 2) % 3];
                let (pb, qb, ab) = (order.map(|k| p[k]), order.map(|k| q[k]), order.map(|k| a[k]));
                let num = f32_plane(pb, std::array::from_fn(|k| ab[k] * qb[k]));
                let got = num(sx as f32, sy as f32) / f32_plane(pb, qb)(sx as f32, sy as f32);
                assert!(bound.contains(got), "{got} at ({px}, {py}) from {base} outside {bound:?}");
                samples += 1;
            }
        }
    }
    eprintln!(
        "{samples} f32 planes' samples inside (widest {widest:.1} m); {left} screen-linear outside"
    );
    assert!(samples > 10 && left > 0, "{samples} samples, {left} screen-linear outside");
}

/// A triangle known exactly: screen points `p`, 1/w `q`, depth 0.001.
fn exact_triangle(p: [[f32; 2]; 3], q: [f32; 3]) -> [ScreenIv; 3] {
    std::array::from_fn(|k| ScreenIv {
        x: Iv::point(p[k][0]),
        y: Iv::point(p[k][1]),
        z: Iv::point(0.001),
        inv_w: Iv::point(q[k]),
        on: None,
    })
}

/// The barycentrics of (px, py) in the triangle of screen points `pos` (x, y first).
fn screen_barycentrics(pos: &[[f64; 3]], px: f64, py: f64) -> [f64; 3] {
    let area = (pos[1][0] - pos[0][0]) * (pos[2][1] - pos[0][1])
        - (pos[2][0] - pos[0][0]) * (pos[1][1] - pos[0][1]);
    let l1 = ((px - pos[0][0]) * (pos[2][1] - pos[0][1])
        - (pos[2][0] - pos[0][0]) * (py - pos[0][1]))
        / area;
    let l2 = ((pos[1][0] - pos[0][0]) * (py - pos[0][1])
        - (px - pos[0][0]) * (pos[1][1] - pos[0][1]))
        / area;
    [1.0 - l1 - l2, l1, l2]
}

/// A sea-floor triangle with a vertex far behind the camera (chiu_shallow's: w from 50 to
/// −4·10⁴), cut by the near plane: the clipper's new vertices slide along the cut edge by
/// hundreds of pixels within the bounds, and no plane through their boxes can be bounded,
/// so from the boxes alone the pieces' depth is unbounded. From the original triangle's
/// plane ([`piece_to_screen`]) it is known within 10⁻⁴ at every sample (z there is about
/// 0.02; 6·10⁻⁵ measured), and holds the depth
/// of a GPU whose new vertices lie anywhere on the edge (and off it by the clipper's
/// roundings). Negative control: a GPU whose far vertex lies off the plane by 2 % of its w
/// leaves the bound.
#[test]
fn a_clipped_piece_s_depth_comes_from_its_triangle_s_plane() {
    let (w, h, snap) = (256u32, 144u32, 1.0 / 256.0);
    // Reversed-Z with an infinite far plane: clip z is the near distance, w the view depth.
    let exact =
        [[-30.0, -20.0, 1.0, 50.0], [-5.0e4, -3.0e4, 1.0, -4.0e4], [40.0, -25.0, 1.0, 80.0]];
    let rel = 3e-7;
    let tri: [[Iv; 4]; 3] =
        exact.map(|v| v.map(|c: f64| Iv::new(c - c.abs() * rel, c + c.abs() * rel)));
    let parts = clip_near_far(tri).expect("decided");
    assert!(!parts.is_empty());
    // The GPU's piece: its vertices on the span of `exact` at the clipper's barycentrics
    // (moved along the edge by t), with the far vertex moved off the plane by `lift`.
    let gpu_depth = |part: &[ClipVertex; 3], slide: f64, lift: f64, px: f64, py: f64| {
        let mut b_exact = exact;
        b_exact[1][3] *= 1.0 + lift;
        let pos: [[f64; 3]; 3] = part.map(|p| {
            let mut b = p.bary;
            if p.bary_err > 0.0 {
                // Slide along the cut edge: move weight between the two vertices it mixes.
                let (i, j) =
                    ((0..3).find(|&k| b[k] > 0.0).unwrap(), (0..3).rfind(|&k| b[k] > 0.0).unwrap());
                b[i] += slide * p.bary_err;
                b[j] -= slide * p.bary_err;
            }
            let c: [f64; 4] = std::array::from_fn(|k| (0..3).map(|j| b[j] * b_exact[j][k]).sum());
            [
                (c[0] / c[3] + 1.0) * f64::from(w) / 2.0,
                (1.0 - c[1] / c[3]) * f64::from(h) / 2.0,
                c[2] / c[3],
            ]
        });
        let [l0, l1, l2] = screen_barycentrics(&pos, px, py);
        (l0.min(l1).min(l2) >= 0.0).then_some(l0 * pos[0][2] + l1 * pos[1][2] + l2 * pos[2][2])
    };
    let (mut judged, mut widest, mut unbounded_before, mut left) = (0, 0.0f64, 0, 0);
    for part in &parts {
        let s = piece_to_screen(part, &tri, w, h).expect("in front");
        assert!(s.iter().all(|v| v.on.is_some()));
        let (with, without) =
            (setup(&s, w, h, snap), setup(&s.map(|v| ScreenIv { on: None, ..v }), w, h, snap));
        let (Some(with), Some(without)) = (with, without) else { continue };
        for py in 0..h {
            for px in 0..w {
                let (sx, sy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
                if cover(&with, sx, sy) == Cover::No {
                    continue;
                }
                let z = depth(&with, sx, sy);
                let before = depth(&without, sx, sy);
                let width = before.hi - before.lo;
                unbounded_before += usize::from(width.is_nan() || width >= 1e-3);
                for slide in [-1.0, 0.0, 1.0] {
                    if let Some(d) = gpu_depth(part, slide, 0.0, sx, sy) {
                        assert!(
                            z.lo <= d && d <= z.hi,
                            "({px}, {py}) slide {slide}: {d} outside {z:?}"
                        );
                        judged += 1;
                        widest = widest.max(z.hi - z.lo);
                    }
                    if let Some(d) = gpu_depth(part, slide, 0.02, sx, sy) {
                        left += usize::from(!(z.lo <= d && d <= z.hi));
                    }
                }
            }
        }
    }
    assert!(judged > 1000, "{judged} samples");
    assert!(widest < 1e-4, "widest bound {widest}");
    eprintln!(
        "{judged} samples, widest {widest:.2e}, {unbounded_before} unbounded from the boxes, {left} left by the lifted GPU"
    );
    assert!(unbounded_before > 1000, "the boxes alone bounded all but {unbounded_before}");
    assert!(left > 100, "a GPU off the plane left the bound at {left} samples");
}

/// The same cut floor triangle's varyings: from the piece's own vertices, whose boxes slide
/// by hundreds of pixels, a varying is unbounded over most of the piece; from the original
/// triangle's values over a small box around the sample ([`Interp::from_original`]) a test
/// such as a clip plane's `value < 0` is decided at most of the piece's samples (75 %
/// measured; none from the piece's vertices: what is left is the clipper's rounding of the new
/// vertices' w, 4 % of it under `CLIP_SLACK`), and the bound holds the value of a GPU whose
/// new vertices lie anywhere on the edge. Negative control: a GPU that interpolates
/// without perspective (screen-linear weights) leaves the bound.
#[test]
fn a_clipped_piece_s_varyings_come_from_its_triangle() {
    let exact =
        [[-30.0, -20.0, 1.0, 50.0], [-5.0e4, -3.0e4, 1.0, -4.0e4], [40.0, -25.0, 1.0, 80.0]];
    let values = [12.0, -4.0e4, 60.0];
    let size = [256u32, 144];
    // The GPU's piece as in the depth test above; its vertices' values the clipper's mix of
    // `vals`, interpolated with perspective at the sample.
    let gpu_value = |part: &[ClipVertex; 3], slide: f64, perspective: bool, px: f64, py: f64| {
        let v = clipped_gpu_piece(part, &exact, values, slide, perspective, size);
        let pos = v.map(|v| v.0);
        let l = screen_barycentrics(&pos, px, py);
        if l.iter().any(|&l| l < 0.0) {
            return None;
        }
        let den: f64 = (0..3).map(|j| l[j] * pos[j][2]).sum();
        Some((0..3).map(|j| l[j] * pos[j][2] * v[j].1).sum::<f64>() / den)
    };
    let (mut judged, mut widest, mut unbounded_before, mut left) = (0, 0.0f64, 0, 0);
    let (mut widths, mut sides) = (Vec::new(), [0usize; 3]);
    clipped_samples(&exact, values, size, |s| {
        let before = s.interp.varying(s.piece);
        unbounded_before += usize::from(before.full || before.hi - before.lo >= 40.0);
        let Some(v) = s.interp.from_original(s.tri, s.a, s.piece) else { return };
        // A discard such as `value < 0` (the maps' clip plane): decided or not.
        let decided = |v: Iv| !v.full && (v.lo > 0.0 || v.hi < 0.0);
        sides[0] += usize::from(decided(before));
        sides[1] += usize::from(decided(narrowed(before, Some(v))));
        sides[2] += 1;
        let ([px, py], [sx, sy]) = (s.pixel, s.at);
        for slide in [-1.0, 0.0, 1.0] {
            if let Some(g) = gpu_value(s.part, slide, true, sx, sy) {
                assert!(v.lo <= g && g <= v.hi, "({px}, {py}) slide {slide}: {g} outside {v:?}");
                judged += 1;
                widest = widest.max(v.hi - v.lo);
                widths.push(v.hi - v.lo);
            }
            if let Some(g) = gpu_value(s.part, slide, false, sx, sy) {
                left += usize::from(!(v.lo <= g && g <= v.hi));
            }
        }
    });
    widths.sort_by(f64::total_cmp);
    eprintln!(
        "{judged} samples, widest {widest:.3e}, median {:.3e}, {unbounded_before} wider than 40 from the piece's vertices, {left} left by the screen-linear GPU",
        widths.get(widths.len() / 2).copied().unwrap_or(f64::NAN)
    );
    assert!(judged > 1000, "{judged} samples");
    eprintln!(
        "`value < 0` decided at {} of {} samples ({} from the piece's vertices)",
        sides[1], sides[2], sides[0]
    );
    assert!(2 * sides[1] > sides[2], "decided at {} of {}", sides[1], sides[2]);
    assert!(
        2 * sides[0] < sides[2],
        "the piece's vertices alone decided {} of {}",
        sides[0],
        sides[2]
    );
    assert!(unbounded_before > 1000, "the piece's vertices bounded all but {unbounded_before}");
    assert!(left > 100, "a screen-linear GPU left the bound at {left} samples");
}

/// A covered sample of a clipper's piece ([`clipped_samples`]).
struct ClippedSample<'a> {
    /// The original triangle's clip positions (f32's rounding as boxes) and values.
    tri: &'a [[Iv; 4]; 3],
    a: [Iv; 3],
    part: &'a [ClipVertex; 3],
    /// The piece's vertices' values.
    piece: [Iv; 3],
    interp: &'a Interp,
    pixel: [u32; 2],
    at: [f64; 2],
}

/// Every sample the pieces of triangle `exact` (clip positions, within f32's rounding)
/// that the near plane cuts may cover in a target of `size` at lavapipe's 1/256 px, its
/// vertices holding `values`.
fn clipped_samples(
    exact: &[[f64; 4]; 3],
    values: [f64; 3],
    [w, h]: [u32; 2],
    mut visit: impl FnMut(ClippedSample<'_>),
) {
    let rel = 3e-7;
    let tri: [[Iv; 4]; 3] =
        exact.map(|v| v.map(|c: f64| Iv::new(c - c.abs() * rel, c + c.abs() * rel)));
    let a = values.map(|v| Iv::new(v, v));
    for part in &clip_near_far(tri).expect("decided") {
        let s = piece_to_screen(part, &tri, w, h).expect("in front");
        let Some(t) = setup(&s, w, h, 1.0 / 256.0) else { continue };
        let piece = part.map(|p| part_value(a, p.bary, p.bary_err));
        for py in 0..h {
            for px in 0..w {
                let at = [f64::from(px) + 0.5, f64::from(py) + 0.5];
                if cover(&t, at[0], at[1]) == Cover::No {
                    continue;
                }
                let interp = barycentrics(&t, at[0], at[1]);
                let (tri, pixel, interp) = (&tri, [px, py], &interp);
                visit(ClippedSample { tri, a, part, piece, interp, pixel, at });
            }
        }
    }
}

/// The GPU's piece of a clipper's `part` of the triangle `exact` (clip positions) whose
/// vertices hold `values`: each new vertex slid along its edge by `slide` times the
/// clipper's allowance; per vertex its screen position, 1/w (1 without `perspective`) and
/// value, all exact.
fn clipped_gpu_piece(
    part: &[ClipVertex; 3],
    exact: &[[f64; 4]; 3],
    values: [f64; 3],
    slide: f64,
    perspective: bool,
    [w, h]: [u32; 2],
) -> [([f64; 3], f64); 3] {
    part.map(|p| {
        let mut b = p.bary;
        if p.bary_err > 0.0 {
            let i = (0..3).find(|&k| b[k] > 0.0).unwrap();
            let j = (0..3).rfind(|&k| b[k] > 0.0).unwrap();
            b[i] += slide * p.bary_err;
            b[j] -= slide * p.bary_err;
        }
        let c: [f64; 4] = std::array::from_fn(|k| (0..3).map(|j| b[j] * exact[j][k]).sum());
        let x = (c[0] / c[3] + 1.0) * f64::from(w) / 2.0;
        let y = (1.0 - c[1] / c[3]) * f64::from(h) / 2.0;
        let q = if perspective { 1.0 / c[3] } else { 1.0 };
        ([x, y, q], (0..3).map(|j| b[j] * values[j]).sum::<f64>())
    })
}

/// The varying at (px, py) as lavapipe interpolates it: f32 planes of a·q and q through the
/// vertices of `v` (snapped to its 1/256 px), taking vertex `base`'s value and anchored at
/// the target's origin, then their quotient. `None` outside the piece.
fn f32_planes_value(v: &[([f64; 3], f64); 3], base: usize, px: f64, py: f64) -> Option<f64> {
    let snapped = |c: f64| ((c * 256.0).round() / 256.0) as f32;
    let order = [base, (base + 1) % 3, (base + 2) % 3];
    let p = order.map(|k| [snapped(v[k].0[0]), snapped(v[k].0[1])]);
    let (q, a) = (order.map(|k| v[k].0[2] as f32), order.map(|k| v[k].1 as f32));
    let l = screen_barycentrics(&p.map(|p| [f64::from(p[0]), f64::from(p[1]), 0.0]), px, py);
    if l.iter().any(|&l| l < 0.0) {
        return None;
    }
    let (x, y) = (px as f32, py as f32);
    let num = f32_plane(p, std::array::from_fn(|k| a[k] * q[k]))(x, y);
    Some(f64::from(num / f32_plane(p, q)(x, y)))
}

/// The plane through values `v` at the f32 points `p`, as lavapipe sets it up: its gradient
/// from the differences to vertex 0, anchored at the target's origin, all in f32.
fn f32_plane(p: [[f32; 2]; 3], v: [f32; 3]) -> impl Fn(f32, f32) -> f32 {
    let (e1x, e1y) = (p[1][0] - p[0][0], p[1][1] - p[0][1]);
    let (e2x, e2y) = (p[2][0] - p[0][0], p[2][1] - p[0][1]);
    let det = e1x * e2y - e2x * e1y;
    let (d1, d2) = (v[1] - v[0], v[2] - v[0]);
    let dx = (d1 * e2y - d2 * e1y) / det;
    let dy = (d2 * e1x - d1 * e2x) / det;
    let a0 = v[0] - dx * p[0][0] - dy * p[0][1];
    move |px: f32, py: f32| a0 + dx * px + dy * py
}

/// chiu_shallow's case that held its maps' discards undecided: a nearly constant varying
/// (the floor's height, 0.5 ‰ across) on the pieces of a floor triangle the near plane cuts,
/// whose new vertex lies ~10⁵ px off screen at 1/w = 20 while the others are at 0.04. Its
/// bound is then all the interpolation's arithmetic: lavapipe's f32 planes, anchored at the
/// origin through each vertex in turn, stay inside it. Negative control: without the planes'
/// term (each vertex's gradient times its arm) they leave it.
#[test]
fn f32_planes_on_a_clipped_piece_stay_inside_its_original_bound() {
    // chiu_shallow's floor triangle (diagnostic dump), scaled out of f32's exact points.
    let exact = [
        [-40.520733, 2.765579, 0.05, 22.488653],
        [-40.520733, -10.108689, 0.05, -14.476148],
        [0.0, 2.765579, 0.05, 22.488653],
    ];
    let values = [-0.9982, -0.9987, -0.9979];
    let size = [256u32, 144];
    let (mut judged, mut left, mut widest, mut most_used) = (0, 0, 0.0f64, 0.0f64);
    clipped_samples(&exact, values, size, |s| {
        let Some(v) = s.interp.from_original(s.tri, s.a, s.piece) else { return };
        let cut = s.interp.cut.expect("a piece");
        let bare = Interp { cut: Some(cut.without_planes()), ..*s.interp };
        let bare = bare.from_original(s.tri, s.a, s.piece).expect("bounded");
        let ([px, py], [sx, sy]) = (s.pixel, s.at);
        for slide in [-1.0, 0.0, 1.0] {
            let gpu = clipped_gpu_piece(s.part, &exact, values, slide, true, size);
            for base in 0..3 {
                let Some(g) = f32_planes_value(&gpu, base, sx, sy) else { continue };
                let inside = |b: Iv| b.lo <= g && g <= b.hi;
                assert!(inside(v), "({px}, {py}) slide {slide} from {base}: {g} outside {v:?}");
                judged += 1;
                left += usize::from(!inside(bare));
                widest = widest.max(v.hi - v.lo);
                let used = (g - 0.5 * (v.lo + v.hi)).abs() / (0.5 * (v.hi - v.lo));
                most_used = most_used.max(used);
            }
        }
    });
    eprintln!(
        "{judged} f32 planes' samples inside (widest {widest:.2e}, at most {most_used:.2e} of a half-width used), {left} outside without the planes' term"
    );
    assert!(judged > 1000, "{judged} samples");
    assert!(left > 0, "no sample left the bound without the planes' term");
}

/// Two triangles of a square that share its diagonal (the same vertices, so the same ids):
/// the samples on the diagonal, which the bounds give to neither, are certainly drawn by one
/// of them (the clear colour cannot show there) and not ambiguous. Negative controls: without
/// ids, or with a vertex of the diagonal a different one in each triangle, the diagonal is
/// ambiguous and the clear colour in its envelope; a fragment whose discard is undecided keeps
/// it ambiguous.
#[test]
fn a_shared_edge_of_a_colour_pass_leaves_no_gap() {
    let (a, b, c, d) = (v(0.0, 0.0, 0.5), v(16.0, 0.0, 0.5), v(16.0, 16.0, 0.5), v(0.0, 16.0, 0.5));
    let tris = [[a, b, c], [a, c, d]];
    let pass = |ids: &[Option<[u32; 3]>], kept: Option<bool>| {
        color_pass_greater(&tris, ids, 16, 16, SNAP_PX, [0.0; 4], |k, _| Shaded {
            color: [
                Iv::point(if k == 0 { 1.0 } else { 0.5 }),
                Iv::point(0.0),
                Iv::point(0.0),
                Iv::point(1.0),
            ],
            kept: if k == 1 { kept } else { Some(true) },
        })
    };
    let diagonal = |env: &[[Iv; 4]], amb: &[bool]| -> (usize, usize) {
        let (mut open, mut amb_n) = (0, 0);
        for i in 0..16 {
            let p = i * 16 + i;
            open += usize::from(env[p][3].contains(0.0));
            amb_n += usize::from(amb[p]);
        }
        (open, amb_n)
    };
    let (env, amb) = pass(&[Some([0, 1, 2]), Some([0, 2, 3])], Some(true));
    assert_eq!(diagonal(&env, &amb), (0, 0), "the shared diagonal");
    assert!(env[16 + 1][0].contains(1.0) && env[16 + 1][0].contains(0.5));
    let (env, amb) = pass(&[], Some(true));
    assert_eq!(diagonal(&env, &amb), (16, 16), "no ids");
    let (env, amb) = pass(&[Some([0, 1, 2]), Some([4, 2, 3])], Some(true));
    assert_eq!(diagonal(&env, &amb), (16, 16), "not the same vertex");
    let (env, amb) = pass(&[Some([0, 1, 2]), Some([0, 2, 3])], None);
    assert_eq!(diagonal(&env, &amb).1, 16, "the discard undecided");
}
