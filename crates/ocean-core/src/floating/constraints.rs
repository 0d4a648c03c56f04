//! The distance constraints that hold the five points together, projected exactly.
//!
//! Constraint a joins points i and j: C_a = |p_i − p_j| − L_a, with gradient n_a = (p_i −
//! p_j)/|p_i − p_j| at p_i and −n_a at p_j. A projection moves the points by Δp = −W Jᵀ λ
//! (W the inverse masses, J the constraints' gradients), the smallest change in the mass
//! metric that meets the linearised constraints, with λ from the 9 × 9 system
//! (J W Jᵀ) λ = r, which is symmetric positive definite because the nine pairs are independent. Every correction is a pair of equal and opposite impulses along a pair's
//! axis, so momentum and angular momentum are kept exactly.
//!
//! Why a direct solve rather than Gauss–Seidel sweeps over the pairs (the usual position-based
//! dynamics): four coplanar corners are only held against twisting (two opposite corners up,
//! the other two down) by the engine point a little below the stern, through pairs whose axes
//! are nearly horizontal — the twist moves their lengths by ~(engine depth / length) of the
//! motion. Sweeps shrink that mode's error by ~1 − (0.6/6)² each, so 64 sweeps over all ten pairs still left 0.07 %
//! of the hull's length in a choppy sea (measured). The system's solution removes every mode at
//! once; Cholesky in a fixed order keeps it a pure function of the inputs.

use glam::DVec3;

/// Newton iterations of the position projection: each solves the linearised system, so the
/// error falls quadratically (10⁻³ → 10⁻⁶ → 10⁻¹² → round-off of the hull's length).
pub const POSITION_ITERATIONS: usize = 4;

/// The number of constraints: 3·5 coordinates less the 6 of a rigid motion.
pub(super) const PAIR_COUNT: usize = 9;

/// The pairs, in the fixed order of every solve: the keel rectangle's four sides and one
/// diagonal (rigid in its plane), and the engine to each corner (which fixes the engine and
/// stops the rectangle folding about its diagonal, the one motion the in-plane pairs allow).
/// Nine independent pairs make the body rigid with no pair to spare; the second diagonal
/// would be redundant (its length follows from the others), and its row would make the
/// system below singular.
pub(super) const PAIRS: [(usize, usize); PAIR_COUNT] =
    [(0, 1), (1, 2), (2, 3), (3, 0), (0, 2), (4, 0), (4, 1), (4, 2), (4, 3)];

type Matrix = [[f64; PAIR_COUNT]; PAIR_COUNT];

/// The unit axes n_a of the pairs at `p`; `None` when two points coincide (no direction to
/// constrain), which a body that kept its lengths cannot reach.
fn axes(p: &[DVec3; 5]) -> Option<[DVec3; PAIR_COUNT]> {
    let mut n = [DVec3::ZERO; PAIR_COUNT];
    for (a, &(i, j)) in PAIRS.iter().enumerate() {
        n[a] = (p[i] - p[j]).try_normalize()?;
    }
    Some(n)
}

/// J W Jᵀ: entry (a, b) sums, over the points the pairs share, the inverse mass times the
/// product of the two gradients there, ±(n_a·n_b) (+ when the point has the same end in both).
fn system(n: &[DVec3; PAIR_COUNT], w: &[f64; 5]) -> Matrix {
    let mut m = [[0.0; PAIR_COUNT]; PAIR_COUNT];
    for (a, &(ia, ja)) in PAIRS.iter().enumerate() {
        for (b, &(ib, jb)) in PAIRS.iter().enumerate() {
            let mut shared = 0.0;
            for (s, sign_a) in [(ia, 1.0), (ja, -1.0)] {
                for (t, sign_b) in [(ib, 1.0), (jb, -1.0)] {
                    if s == t {
                        shared += sign_a * sign_b * w[s];
                    }
                }
            }
            m[a][b] = shared * n[a].dot(n[b]);
        }
    }
    m
}

/// Solves m·x = r for a symmetric positive definite m by Cholesky (m = L Lᵀ), in a fixed
/// order. `None` when a pivot is not positive beyond round-off (the constraints are not
/// independent: a degenerate body).
fn solve(m: &Matrix, r: &[f64; PAIR_COUNT]) -> Option<[f64; PAIR_COUNT]> {
    // Dot products as left-to-right folds: one fixed order of the sums.
    let dot = |a: &[f64], b: &[f64], start: f64| a.iter().zip(b).fold(start, |s, (x, y)| s - x * y);
    let mut l = [[0.0; PAIR_COUNT]; PAIR_COUNT];
    for i in 0..PAIR_COUNT {
        for j in 0..=i {
            let s = dot(&l[i][..j], &l[j][..j], m[i][j]);
            if i == j {
                // A pivot below 1e-12 of its diagonal entry is round-off of a dependent
                // constraint, not information: refuse rather than divide by it (NaN too).
                if s.is_nan() || s <= 1e-12 * m[i][i] {
                    return None;
                }
                l[i][i] = s.sqrt();
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    }
    // L y = r, then Lᵀ x = y.
    let mut y = [0.0; PAIR_COUNT];
    for i in 0..PAIR_COUNT {
        y[i] = dot(&l[i][..i], &y[..i], r[i]) / l[i][i];
    }
    let mut x = [0.0; PAIR_COUNT];
    for i in (0..PAIR_COUNT).rev() {
        let column: [f64; PAIR_COUNT] = std::array::from_fn(|k| l[k][i]);
        x[i] = dot(&column[i + 1..], &x[i + 1..], y[i]) / l[i][i];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Applies Δq = −W Jᵀ λ to `q` (positions or velocities).
fn apply(q: &mut [DVec3; 5], n: &[DVec3; PAIR_COUNT], w: &[f64; 5], lambda: &[f64; PAIR_COUNT]) {
    for (a, &(i, j)) in PAIRS.iter().enumerate() {
        let impulse = n[a] * lambda[a];
        q[i] -= impulse * w[i];
        q[j] += impulse * w[j];
    }
}

/// Removes every pair's relative velocity along its axis (J v = 0) in one solve. Leaves `v`
/// unchanged when the body is degenerate (`axes`, `solve`).
pub(super) fn project_velocities(p: &[DVec3; 5], v: &mut [DVec3; 5], w: &[f64; 5]) {
    let Some(n) = axes(p) else { return };
    let r = std::array::from_fn(|a| {
        let (i, j) = PAIRS[a];
        n[a].dot(v[i] - v[j])
    });
    if let Some(lambda) = solve(&system(&n, w), &r) {
        apply(v, &n, w, &lambda);
    }
}

/// Moves the points back to the rest lengths: [`POSITION_ITERATIONS`] Newton steps, each
/// solving (J W Jᵀ) λ = C at the current points. Stops early, leaving the points where they
/// are, if the body is degenerate.
pub(super) fn project_positions(p: &mut [DVec3; 5], w: &[f64; 5], rest: &[f64; PAIR_COUNT]) {
    for _ in 0..POSITION_ITERATIONS {
        let Some(n) = axes(p) else { return };
        let c = std::array::from_fn(|a| {
            let (i, j) = PAIRS[a];
            (p[i] - p[j]).length() - rest[a]
        });
        let Some(lambda) = solve(&system(&n, w), &c) else { return };
        apply(p, &n, w, &lambda);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_solves_a_known_system_and_refuses_a_singular_one() {
        let mut m = [[0.0; PAIR_COUNT]; PAIR_COUNT];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                // Diagonally dominant, symmetric: positive definite.
                *e = if i == j { 4.0 + i as f64 } else { 1.0 / (1.0 + (i + j) as f64) };
            }
        }
        let x_true: [f64; PAIR_COUNT] = std::array::from_fn(|i| (i as f64) - 3.5);
        let r = std::array::from_fn(|i| (0..PAIR_COUNT).map(|j| m[i][j] * x_true[j]).sum());
        let x = solve(&m, &r).unwrap();
        for (a, b) in x.iter().zip(&x_true) {
            // 1e-12: a 9 × 9 elimination of a well-conditioned matrix, ~10³ ulp.
            assert!((a - b).abs() < 1e-12, "{x:?}");
        }
        // Two equal rows and columns: a dependent constraint.
        let (last, other) = (PAIR_COUNT - 1, PAIR_COUNT - 2);
        let mut singular = m;
        singular[last] = singular[other];
        for row in singular.iter_mut() {
            row[last] = row[other];
        }
        assert!(solve(&singular, &r).is_none());
    }
}
