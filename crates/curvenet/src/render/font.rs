//! Text for titles and colour-bar labels: the public-domain 8×8 bitmap font of the `font8x8`
//! crate, scaled by whole pixels so that it stays crisp.

use super::Image;

/// Width in pixels of `text` drawn at `scale`.
pub fn text_width(text: &str, scale: u32) -> u32 {
    text.chars().count() as u32 * 8 * scale
}

/// Height in pixels of a line of text at `scale`.
pub fn text_height(scale: u32) -> u32 {
    8 * scale
}

/// Draws `text` with its top-left corner at `(x, y)`; pixels outside the image are skipped.
/// Characters outside ASCII are drawn as `?`.
pub fn draw_text(img: &mut Image, x: i32, y: i32, text: &str, scale: u32, colour: [u8; 3]) {
    let s = scale.max(1) as i32;
    for (k, ch) in text.chars().enumerate() {
        let code = if ch.is_ascii() { ch as usize } else { '?' as usize };
        let glyph = font8x8::legacy::BASIC_LEGACY[code];
        let x0 = x + k as i32 * 8 * s;
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                // Bit 0 is the leftmost pixel of the row.
                if bits & (1 << col) == 0 {
                    continue;
                }
                for dy in 0..s {
                    for dx in 0..s {
                        img.set(x0 + col * s + dx, y + row as i32 * s + dy, colour);
                    }
                }
            }
        }
    }
}
