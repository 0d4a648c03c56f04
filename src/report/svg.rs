//! The report's drawing: a small SVG writer (the plots are drawn by hand so that every label,
//! break mark and legend sits where the reader needs it) and the rasteriser that turns an SVG
//! into a PNG with the bundled font (resvg; DejaVu Sans in `reference/fonts`, so the bitmap
//! needs no fonts from the system and looks the same on every machine).

use std::fmt::Write as _;

use anyhow::Context;

/// DejaVu Sans (Bitstream Vera licence, `reference/fonts/LICENSE`): every text of the report's
/// SVGs is set in it, in the browser (the SVG names it first) and in the PNGs.
pub(super) const FONT: &[u8] = include_bytes!("../../reference/fonts/DejaVuSans.ttf");

/// The font family the SVGs ask for.
pub(super) const FAMILY: &str = "DejaVu Sans, Verdana, Arial, sans-serif";

/// Width of `text` set at `size` px in DejaVu Sans, px: the advance widths of its glyphs (an
/// unknown glyph counts as 0.6 em).
pub(super) fn text_width(text: &str, size: f64) -> f64 {
    thread_local! {
        static FACE: Option<ttf_parser::Face<'static>> = ttf_parser::Face::parse(FONT, 0).ok();
    }
    FACE.with(|face| match face {
        Some(f) => {
            let em = f64::from(f.units_per_em());
            text.chars()
                .map(|c| {
                    f.glyph_index(c)
                        .and_then(|g| f.glyph_hor_advance(g))
                        .map_or(0.6, |a| f64::from(a) / em)
                })
                .sum::<f64>()
                * size
        }
        None => 0.6 * size * text.chars().count() as f64,
    })
}

/// `text` with the characters XML and HTML give a meaning escaped.
pub(super) fn esc(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            _ => s.push(c),
        }
    }
    s
}

/// An SVG document being written.
pub(super) struct Svg {
    body: String,
    width: f64,
    height: f64,
}

/// Horizontal anchor of a text.
#[derive(Clone, Copy)]
pub(super) enum Anchor {
    Start,
    Middle,
    End,
}

impl Svg {
    /// An empty white picture of `width` × `height` px.
    pub(super) fn new(width: f64, height: f64) -> Self {
        let mut body = String::new();
        let _ = write!(body, r##"<rect width="{width}" height="{height}" fill="#ffffff"/>"##);
        Self { body, width, height }
    }

    /// A line.
    pub(super) fn line(&mut self, (x0, y0): (f64, f64), (x1, y1): (f64, f64), style: &str) {
        let _ = write!(
            self.body,
            r#"<line x1="{x0:.1}" y1="{y0:.1}" x2="{x1:.1}" y2="{y1:.1}" {style}/>"#
        );
    }

    /// A polyline through `points`.
    pub(super) fn polyline(&mut self, points: &[(f64, f64)], style: &str) {
        let pts: Vec<String> = points.iter().map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
        let _ = write!(self.body, r#"<polyline points="{}" fill="none" {style}/>"#, pts.join(" "));
    }

    /// A rectangle.
    pub(super) fn rect(&mut self, (x, y): (f64, f64), (w, h): (f64, f64), style: &str) {
        let _ = write!(
            self.body,
            r#"<rect x="{x:.1}" y="{y:.1}" width="{w:.1}" height="{h:.1}" {style}/>"#
        );
    }

    /// A circle.
    pub(super) fn circle(&mut self, (x, y): (f64, f64), r: f64, style: &str) {
        let _ = write!(self.body, r#"<circle cx="{x:.1}" cy="{y:.1}" r="{r}" {style}/>"#);
    }

    /// A marker of kind `square` (else a circle) centred at (x, y).
    pub(super) fn marker(&mut self, at: (f64, f64), square: bool, r: f64, style: &str) {
        if square {
            self.rect((at.0 - r, at.1 - r), (2.0 * r, 2.0 * r), style);
        } else {
            self.circle(at, r, style);
        }
    }

    /// A text whose baseline starts, centres or ends at (x, y).
    pub(super) fn text(&mut self, (x, y): (f64, f64), size: f64, anchor: Anchor, text: &str) {
        self.text_styled((x, y), size, anchor, text, r##"fill="#222222""##);
    }

    /// A text with extra attributes (`fill`, `font-weight`).
    pub(super) fn text_styled(
        &mut self,
        (x, y): (f64, f64),
        size: f64,
        anchor: Anchor,
        text: &str,
        style: &str,
    ) {
        let anchor = match anchor {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        };
        let _ = write!(
            self.body,
            r#"<text x="{x:.1}" y="{y:.1}" font-size="{size}" text-anchor="{anchor}" {style}>{}</text>"#,
            esc(text)
        );
    }

    /// A text turned 90° anticlockwise, centred at (x, y) (a y-axis title).
    pub(super) fn vertical_text(&mut self, (x, y): (f64, f64), size: f64, text: &str) {
        let _ = write!(
            self.body,
            r##"<text x="{x:.1}" y="{y:.1}" font-size="{size}" text-anchor="middle" fill="#222222" transform="rotate(-90 {x:.1} {y:.1})">{}</text>"##,
            esc(text)
        );
    }

    /// A PNG picture, embedded, drawn into the box at (x, y) of size (w, h).
    pub(super) fn png(&mut self, (x, y): (f64, f64), (w, h): (f64, f64), png: &[u8]) {
        let _ = write!(
            self.body,
            r#"<image x="{x:.1}" y="{y:.1}" width="{w:.1}" height="{h:.1}" href="data:image/png;base64,{}"/>"#,
            base64(png)
        );
    }

    /// The document.
    pub(super) fn finish(self) -> String {
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="{FAMILY}">{}</svg>
"#,
            self.body,
            w = self.width,
            h = self.height
        )
    }
}

/// Standard base64 (RFC 4648, padded) of `bytes`.
pub(super) fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[(n >> (18 - 6 * k) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The PNG of `svg` at `scale` × its size, every text in the bundled font.
pub(super) fn png_of(svg: &str, scale: f32) -> anyhow::Result<Vec<u8>> {
    use resvg::{tiny_skia, usvg};
    let mut options = usvg::Options::default();
    {
        let db = options.fontdb_mut();
        db.load_font_data(FONT.to_vec());
        db.set_sans_serif_family("DejaVu Sans");
    }
    options.font_family = "DejaVu Sans".into();
    let tree = usvg::Tree::from_str(svg, &options).context("the report's SVG does not parse")?;
    let size = tree.size().to_int_size().scale_by(scale).context("an empty SVG")?;
    let mut pixmap =
        tiny_skia::Pixmap::new(size.width(), size.height()).context("a picture too large")?;
    resvg::render(&tree, tiny_skia::Transform::from_scale(scale, scale), &mut pixmap.as_mut());
    pixmap.encode_png().context("PNG encoding")
}

/// An 8-bit RGB picture as PNG bytes.
pub(super) fn png_rgb(rgb: &[u8], width: u32, height: u32) -> anyhow::Result<Vec<u8>> {
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(rgb, width, height, image::ExtendedColorType::Rgb8)
        .context("PNG encoding")?;
    Ok(out)
}

use image::ImageEncoder as _;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        // RFC 4648 §10.
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded, "{plain}");
        }
    }

    #[test]
    fn text_is_measured_in_the_bundled_font() {
        // DejaVu Sans: 'i' is narrower than 'W'; a string is the sum of its glyphs.
        let (i, w) = (text_width("i", 10.0), text_width("W", 10.0));
        assert!(i > 1.0 && i < w, "{i} {w}");
        assert!((text_width("iW", 10.0) - i - w).abs() < 1e-9);
    }

    #[test]
    fn the_png_has_the_text_drawn_in_the_bundled_font() {
        let mut with = Svg::new(120.0, 40.0);
        with.text((10.0, 28.0), 20.0, Anchor::Start, "Ocean");
        let without = Svg::new(120.0, 40.0);
        let dark = |svg: Svg| {
            let png = png_of(&svg.finish(), 1.0).unwrap();
            let img = image::load_from_memory(&png).unwrap().to_rgb8();
            assert_eq!(img.dimensions(), (120, 40));
            img.pixels().filter(|p| p.0[0] < 128).count()
        };
        // Control: the same picture without the text has no dark pixel at all.
        assert_eq!(dark(without), 0);
        assert!(dark(with) > 50, "the text was not drawn (no font?)");
    }
}
