//! Edge functions on snapped coordinates, in exact i64 arithmetic, with the top-left rule.
//!
//! For an edge from `a` to `b` (snapped, framebuffer y down) and a sample point `p`:
//!
//! ```text
//! E(p) = s · [(b.x − a.x)(p.y − a.y) − (b.y − a.y)(p.x − a.x)]
//! ```
//!
//! with `s = ±1` chosen per triangle so that the interior is `E > 0` whatever the winding.
//! Written as `E = A·p.x + B·p.y + C`, `A = −s(b.y − a.y)`, `B = s(b.x − a.x)`.
//!
//! Top-left rule (Vulkan as lavapipe does it, D3D's convention, framebuffer y down): a sample
//! exactly on an edge (`E = 0`) is covered only if the edge is a *left* edge (interior to its
//! right: `A > 0`) or a *top* edge (exactly horizontal with the interior below it: `A = 0` and
//! `B > 0`). Stated in terms of `A`, `B` of the oriented edge, this holds for both windings.
//! So a sample is covered iff `E − bias ≥ 0` with `bias = 0` on top/left edges and 1 elsewhere
//! (E is an integer).

use super::fixed_point::{FIXED_HALF, FIXED_ONE};

/// One oriented edge function, evaluated at pixel centres.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// Change of E from one pixel to the next in x: `A · FIXED_ONE`.
    pub step_x: i64,
    /// Change of E from one pixel row to the next: `B · FIXED_ONE`.
    pub step_y: i64,
    /// E at the centre of pixel (0, 0).
    pub origin: i64,
    /// 0 on a top or left edge, 1 otherwise: covered iff `E − bias ≥ 0`.
    pub bias: i64,
}

impl Edge {
    /// The edge from `a` to `b` (snapped (x, y)), with orientation `sign` (±1).
    pub fn new(a: (i64, i64), b: (i64, i64), sign: i64) -> Self {
        debug_assert!(sign == 1 || sign == -1);
        let coef_a = -sign * (b.1 - a.1);
        let coef_b = sign * (b.0 - a.0);
        let top_left = coef_a > 0 || (coef_a == 0 && coef_b > 0);
        Self {
            step_x: coef_a * FIXED_ONE,
            step_y: coef_b * FIXED_ONE,
            origin: coef_a * (FIXED_HALF - a.0) + coef_b * (FIXED_HALF - a.1),
            bias: i64::from(!top_left),
        }
    }

    /// E at the centre of pixel (x, y), exactly.
    #[inline]
    pub fn at(&self, x: i64, y: i64) -> i64 {
        self.origin + self.step_x * x + self.step_y * y
    }

    /// Narrows the pixel range `[x0, x1]` (inclusive) of row `y` to the pixels this edge
    /// covers; returns an empty range (`x0 > x1`) when there are none. Exact: the same pixels
    /// as testing `at(x, y) − bias ≥ 0` one by one.
    #[inline]
    pub fn clip_span(&self, y: i64, x0: i64, x1: i64) -> (i64, i64) {
        // Covered iff v + step_x · k ≥ 0 with k = x − x0.
        let v = self.at(x0, y) - self.bias;
        let a = self.step_x;
        if a > 0 {
            // k ≥ ceil(−v / a)
            let k_min = -v.div_euclid(a);
            (x0 + k_min.max(0), x1)
        } else if a < 0 {
            // k ≤ floor(v / −a)
            let k_max = v.div_euclid(-a);
            (x0, x1.min(x0 + k_max))
        } else if v >= 0 {
            (x0, x1)
        } else {
            (x0, x0 - 1)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `clip_span` against testing every pixel, for edges of every slope and sign, including
    /// ones through pixel centres (where the bias decides).
    #[test]
    fn clip_span_equals_the_per_pixel_test() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = |range: i64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % (2 * range as u64 + 1)) as i64 - range
        };
        let mut covered_somewhere = 0;
        for k in 0..20_000 {
            // Every fourth edge has both ends on pixel centres.
            let centre = |v: i64| if k % 4 == 0 { v * FIXED_ONE + FIXED_HALF } else { v };
            let grid = if k % 4 == 0 { 40 } else { 40 * FIXED_ONE };
            let a = (centre(next(grid)), centre(next(grid)));
            let b = if k % 8 == 1 {
                (centre(next(grid)), a.1) // horizontal
            } else if k % 8 == 3 {
                (a.0, centre(next(grid))) // vertical
            } else {
                (centre(next(grid)), centre(next(grid)))
            };
            let edge = Edge::new(a, b, if k % 2 == 0 { 1 } else { -1 });
            let y = next(40);
            let (x0, x1) = (next(40), next(40));
            let (x0, x1) = (x0.min(x1), x0.max(x1));
            let (s0, s1) = edge.clip_span(y, x0, x1);
            for x in x0..=x1 {
                let inside = edge.at(x, y) - edge.bias >= 0;
                assert_eq!(inside, s0 <= x && x <= s1, "{edge:?} y {y} x {x}");
                covered_somewhere += i32::from(inside);
            }
        }
        assert!(covered_somewhere > 1000);
    }

    #[test]
    fn top_left_classification() {
        // Clockwise on screen (y down) is sign +1: right along the top, down the right side,
        // back up the left side.
        let top = Edge::new((0, 0), (256, 0), 1);
        let right = Edge::new((256, 0), (0, 256), 1);
        let left = Edge::new((0, 256), (0, 0), 1);
        assert_eq!((top.bias, right.bias, left.bias), (0, 1, 0));
        // The same triangle counter-clockwise (sign −1): same classification.
        let top = Edge::new((256, 0), (0, 0), -1);
        let left = Edge::new((0, 0), (0, 256), -1);
        let right = Edge::new((0, 256), (256, 0), -1);
        assert_eq!((top.bias, right.bias, left.bias), (0, 1, 0));
        // A bottom edge is never included.
        let bottom = Edge::new((256, 256), (0, 256), 1);
        assert_eq!(bottom.bias, 1);
    }
}
