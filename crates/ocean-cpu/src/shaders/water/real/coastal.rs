//! Waves technique `coastal` (`shared/coastal.wgsl`), surface `shore_grid`'s vertex and the
//! screen grids' vertex spacing (`water.wgsl`) over any [`Real`]. The radial wave's table
//! segment is where `u32` puts r·(segments per m) (every segment an interval reaches, united);
//! the phase's reduction to [−½, ½] turn likewise; each branch on a value both ways where the
//! bounds cannot decide it.

use ocean_core::frame::FrameUniforms;

use super::floor;
use super::inputs::{Inputs, LEAST_POSITIVE};
use crate::envelope::{Cond, Real, choose, choose_n, on_floor};
use crate::shaders::shared::coastal::{COASTAL_EDGE_M, COASTAL_FILM_M, COASTAL_SEGMENTS};
use crate::shaders::shared::optics::exp_arith_r;
use crate::shaders::shared::trig::{TAU, cis_reduced_r, cis_turns_r};

/// `CoastalRadial`: the radial wave's state at a point.
#[derive(Clone, Copy)]
struct Radial<R> {
    d: [R; 2],
    r: R,
    dphi: R,
    floor_y: R,
    shoaled: R,
    amp: R,
    turns: R,
    cs: [R; 2],
}

impl<R: Real> Radial<R> {
    fn pack(&self) -> [R; 10] {
        let [d0, d1] = self.d;
        let [c0, c1] = self.cs;
        [d0, d1, self.r, self.dphi, self.floor_y, self.shoaled, self.amp, self.turns, c0, c1]
    }

    fn unpack(v: [R; 10]) -> Self {
        Radial {
            d: [v[0], v[1]],
            r: v[2],
            dphi: v[3],
            floor_y: v[4],
            shoaled: v[5],
            amp: v[6],
            turns: v[7],
            cs: [v[8], v[9]],
        }
    }
}

/// `coastal_filter(kx, kz, h, sigma)`.
fn filter<R: Real>(kx: R, kz: R, h: [R; 2], sigma: [R; 2]) -> R {
    let k_long = (kx * h[0] + kz * h[1]) * sigma[0];
    let k_short = (kz * h[0] - kx * h[1]) * sigma[1];
    exp_arith_r(R::lit(-0.5) * (k_long * k_long + k_short * k_short))
}

/// `coastal_radial(pos)`.
fn radial<R: Real>(pos: [R; 2], inp: &Inputs<'_, R>) -> Radial<R> {
    let l = R::lit;
    let frame = inp.frame;
    let c = &frame.coastal;
    let off = frame.tiling.mesh_offset;
    let floor_y = floor::floor_height(pos[0] + l(off[0]), pos[1] + l(off[1]), inp);
    let depth = (-floor_y).max(l(0.0));
    let d = [pos[0] - l(c.center[0]), pos[1] - l(c.center[1])];
    let r = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let full = [l(f32::NAN); 10];
    // min(u32(x), last) = floor(min(x, last)) for x ≥ 0: past the table, its last segment.
    let last = (COASTAL_SEGMENTS - 1) as f32;
    let v = on_floor((r * l(c.center[2])).min(l(last)), full, |k, _| {
        // u32(f32) saturates: r ≥ 0, so it is the floor, then the table's last segment.
        let i = (k.max(0.0) as u32).min(COASTAL_SEGMENTS - 1) as usize;
        let u = r - l(i as f32) * l(c.center[3]);
        let (p, q) = (c.table[2 * i].map(l), c.table[2 * i + 1].map(l));
        let phi = p[0] + u * (p[1] + u * p[2]);
        let dphi = p[1] + (u + u) * p[2];
        let cap = l(c.time[1]) * depth;
        let shoaled = (q[0] + u * (q[1] + u * q[2])).max(l(0.0));
        let amp = choose(cap.lt(shoaled), || cap, || shoaled);
        let t = -(phi + l(c.time[0]));
        // Past on_floor's cells: t − floor(t + ½) within [−½, ½] but for one ULP of t + ½ (it
        // may round up), for |t| < 2²²; its cis within the polynomials' [−1, 1] but for their
        // roundings. Anything past that (the reduction may leave −1 turn, or −ulp(t)).
        let m = t.least().abs().max(t.most().abs());
        let any = if m < 4_194_304.0 {
            let d = f64::from(f32::EPSILON) * 2.0 * (2.0 * m + 1.0);
            let unit_ish = l(-1.0001).hull(l(1.0001));
            let (lo, hi) = (((-0.5 - d) as f32).next_down(), ((0.5 + d) as f32).next_up());
            [l(lo).hull(l(hi)), unit_ish, unit_ish]
        } else {
            [l(f32::NAN); 3]
        };
        let [turns, c0, c1] = on_floor(t + l(0.5), any, |n, _| {
            let turns = t - l(n);
            let [c0, c1] = cis_turns_r(turns);
            [turns, c0, c1]
        });
        Radial { d, r, dphi, floor_y, shoaled, amp, turns, cs: [c0, c1] }.pack()
    });
    Radial::unpack(v)
}

/// `coastal_shape(w)`: (b, s^(p − 1), m).
fn shape<R: Real>(w: &Radial<R>, frame: &FrameUniforms) -> [R; 3] {
    let l = R::lit;
    let c = &frame.coastal;
    let [cos, sin] = w.cs;
    let m = choose((cos * sin).lt(l(0.0)), || l(c.shape[3]), || l(1.0));
    let mut sp1 = l(1.0);
    for _ in 1..c.shape[2] as u32 {
        sp1 = sp1 * sin;
    }
    let sp = sp1 * sin;
    [sp * w.amp * m - w.amp * (m - l(1.0)), sp1, m]
}

/// `coastal_fade(fx, fz, h, spacing)`.
fn fade<R: Real>(fx: R, fz: R, h: [R; 2], spacing: [R; 2]) -> R {
    let l = R::lit;
    let along = (fx * h[0] + fz * h[1]).abs() * spacing[0];
    let across = (fz * h[0] - fx * h[1]).abs() * spacing[1];
    (l(2.0) - l(8.0) * (along + across)).clamp(l(0.0), l(1.0))
}

/// `coastal_wave(pos, h_dir, sigma, spacing)`: (height, ∂h/∂x, ∂h/∂z, φ in turns).
pub(super) fn wave<R: Real>(
    pos: [R; 2],
    h_dir: [R; 2],
    sigma: [R; 2],
    spacing: [R; 2],
    inp: &Inputs<'_, R>,
) -> [R; 4] {
    let l = R::lit;
    let frame = inp.frame;
    let c = &frame.coastal;
    let w = radial(pos, inp);
    let depth = (-w.floor_y).max(l(0.0));
    let [b, sp1, m] = shape(&w, frame);
    let h = b.clamp(l(0.0), w.amp);
    let dh = choose(
        l(0.0).lt(b).and(b.lt(w.amp)),
        || m * (l(c.shape[2]) * sp1 * w.cs[0] * (l(-TAU) * w.dphi) * w.amp),
        || l(0.0),
    );
    let [h, g0, g1] = choose_n(
        l(0.0).lt(w.r),
        || {
            let r = w.r.at_least(LEAST_POSITIVE);
            let kr = l(TAU) * l(c.swash[3]) * w.dphi / r;
            let k = dh / r * filter(kr * w.d[0], kr * w.d[1], h_dir, sigma);
            let g = [w.d[0] * k, w.d[1] * k];
            let f = l(c.swash[3]) * w.dphi / r;
            let fd = fade(f * w.d[0], f * w.d[1], h_dir, spacing);
            let h = choose(
                fd.lt(l(1.0)),
                || {
                    let mean = l(c.swash[2]) * w.amp;
                    mean + (h - mean) * fd
                },
                || h,
            );
            [h, g[0], g[1]]
        },
        || [h, l(0.0), l(0.0)],
    );
    let (mut h, mut g) = (h, [g0, g1]);
    for j in 0..c.time[2] as usize {
        let cw = c.waves[j];
        let terms = [l(cw[0]) * pos[0], l(cw[2]), l(cw[1]) * pos[1]];
        let pj = R::sum_as_written(&terms, |t| (t[0] + t[1]) + t[2]);
        let [cj, sj] = cis_reduced_r(pj);
        let a = l(cw[3])
            * (depth * l(c.damping[j])).clamp(l(0.0), l(1.0))
            * fade(l(cw[0]), l(cw[1]), h_dir, spacing);
        h = h + a * sj;
        let f = filter(l(TAU) * l(cw[0]), l(TAU) * l(cw[1]), h_dir, sigma);
        let k = a * l(TAU) * cj * f;
        g = [g[0] + l(cw[0]) * k, g[1] + l(cw[1]) * k];
    }
    let film = l(c.swash[0]).min(w.floor_y + l(COASTAL_FILM_M));
    [h.max(film), g[0], g[1], w.turns]
}

/// `coastal_shore(pos, h, spacing)`: (φ in turns, the shore foam's turbulence, the share of
/// the phase the footprint resolves).
pub(super) fn shore<R: Real>(
    pos: [R; 2],
    h: [R; 2],
    spacing: [R; 2],
    inp: &Inputs<'_, R>,
) -> [R; 3] {
    let l = R::lit;
    let frame = inp.frame;
    let c = &frame.coastal;
    let w = radial(pos, inp);
    let resolved = choose(
        l(0.0).lt(w.r),
        || {
            let f = w.dphi / w.r.at_least(LEAST_POSITIVE);
            fade(f * w.d[0], f * w.d[1], h, spacing)
        },
        || l(1.0),
    );
    let breaking = choose(
        l(0.0).lt(w.shoaled),
        || {
            let s = w.shoaled.at_least(LEAST_POSITIVE);
            (l(1.0) - l(c.time[1]) * (-w.floor_y).max(l(0.0)) / s).clamp(l(0.0), l(1.0))
        },
        || l(0.0),
    );
    let crest = choose(
        l(0.0).lt(w.amp),
        || {
            let a = w.amp.at_least(LEAST_POSITIVE);
            shape(&w, frame)[0].clamp(l(0.0), a) / a
        },
        || l(0.0),
    );
    let above = l(c.swash[0]) - w.floor_y;
    let edge = choose(
        l(-COASTAL_FILM_M).lt(w.floor_y).and(l(0.0).lt(above)),
        || (l(1.0) - above / l(COASTAL_EDGE_M)).clamp(l(0.0), l(1.0)),
        || l(0.0),
    );
    [w.turns, (breaking * (l(0.2) + l(0.8) * crest)).max(edge), resolved]
}

/// `grid_spacing(pos)`: (h, along, across).
pub(super) fn grid_spacing<R: Real>(pos: [R; 2], frame: &FrameUniforms) -> [R; 4] {
    let l = R::lit;
    let off = frame.tiling.mesh_offset;
    let plane = [pos[0] + l(off[0]), pos[1] + l(off[1])];
    let horizontal = (plane[0] * plane[0] + plane[1] * plane[1]).sqrt();
    let e = l(frame.view.eye_height);
    let dist = (horizontal * horizontal + e * e).sqrt();
    let across = l(frame.grid.cell_angle) * dist;
    let along = across / (e.abs() / dist.max(l(1e-30))).max(l(1e-4));
    let k = l(-1.0) / horizontal.max(l(1e-30));
    [plane[0] * k, plane[1] * k, along, across]
}

/// Surface `shore_grid`'s point (i, j) of the lattice, relative to the mesh's reference point.
pub(super) fn shore_point<R: Real>(i: u32, j: u32, frame: &FrameUniforms) -> [R; 2] {
    let l = R::lit;
    let g = &frame.grid;
    let [a, s, w, _] = g.corners.map(|c| c.map(l));
    let d = s[0] * (l(1.0) / (l(1.0) - l(j as f32) / s[1]) - l(1.0)) - s[2];
    let x = (l(i as f32) / l(g.cols) * l(2.0) - l(1.0)) * (w[0] + w[1] * (d + s[2]));
    let off = frame.tiling.mesh_offset;
    [a[0] * d + a[2] * x - l(off[0]), a[1] * d + a[3] * x - l(off[1])]
}
