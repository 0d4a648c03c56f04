//! Mirror of `shaders/shared/fullscreen.wgsl`.

use crate::shaders::wgsl::{Vec4, vec4};

/// Clip position of vertex 0, 1, 2 of the full-screen triangle: (−1, −1), (3, −1), (−1, 3),
/// z = 0, w = 1.
pub fn fullscreen_position(vertex_index: u32) -> Vec4 {
    let x = ((vertex_index << 1) & 2) as f32 * 2.0 - 1.0;
    let y = (vertex_index & 2) as f32 * 2.0 - 1.0;
    vec4(x, y, 0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_three_corners() {
        let p: Vec<[f32; 4]> = (0..3).map(|i| fullscreen_position(i).into()).collect();
        assert_eq!(p, [[-1.0, -1.0, 0.0, 1.0], [3.0, -1.0, 0.0, 1.0], [-1.0, 3.0, 0.0, 1.0]]);
    }
}
