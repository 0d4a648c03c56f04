//! Mirror of `shaders/present.wgsl`: the real-time viewer's copy of the frame's 8-bit output
//! into a window. Loading a `Rgba8Unorm` byte k gives the float k/255 and storing it into a
//! `Bgra8Unorm`/`Rgba8Unorm` target rounds back to k, so the stage is the identity on the
//! colour bytes and sets alpha to 255; [`present`] is that, the reference the viewer's
//! screenshot test holds the window against.

use crate::shaders::shared::fullscreen::fullscreen_position;
use crate::shaders::wgsl::{Vec2, Vec4, vec2};

/// `VertexOut` of `present.wgsl`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOut {
    /// `@builtin(position)`.
    pub position: Vec4,
}

/// `vs_main`: the full-screen triangle.
pub fn vs_main(vertex_index: u32) -> VertexOut {
    VertexOut { position: fullscreen_position(vertex_index) }
}

/// `fs_main` at a pixel of an RGBA8 image (`width` texels a row): the texel's colour bytes
/// with alpha 255; zeros outside the image (robust `textureLoad`).
pub fn fs_main(frame_output: &[u8], width: u32, height: u32, position: Vec2) -> [u8; 4] {
    let (x, y) = (position.x as i32, position.y as i32);
    if x < 0 || y < 0 || x as u32 >= width || y as u32 >= height {
        return [0, 0, 0, 255];
    }
    let i = 4 * (y as usize * width as usize + x as usize);
    [frame_output[i], frame_output[i + 1], frame_output[i + 2], 255]
}

/// The whole stage over a `width × height` RGBA8 image: what the window holds afterwards,
/// as RGBA bytes.
pub fn present(frame_output: &[u8], width: u32, height: u32) -> Vec<u8> {
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .flat_map(|(x, y)| {
            fs_main(frame_output, width, height, vec2(x as f32 + 0.5, y as f32 + 0.5))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn copies_colour_and_makes_the_window_opaque() {
        let image = [1, 2, 3, 4, 250, 251, 252, 0];
        assert_eq!(present(&image, 2, 1), vec![1, 2, 3, 255, 250, 251, 252, 255]);
        assert_eq!(fs_main(&image, 2, 1, vec2(2.5, 0.5)), [0, 0, 0, 255]);
        assert_eq!(vs_main(1).position, Vec4::from([3.0, -1.0, 0.0, 1.0]));
    }
}
