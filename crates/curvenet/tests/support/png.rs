//! Test support shared by the render tests of the library and the CLI (included with
//! `#[path]`): PNG files decoded with the `png` crate.

/// Decodes an 8-bit RGB PNG: `(width, height, rgb)`, `None` for anything else.
pub fn decode_rgb(bytes: &[u8]) -> Option<(u32, u32, Vec<u8>)> {
    let mut reader = ::png::Decoder::new(std::io::Cursor::new(bytes)).read_info().ok()?;
    let mut rgb = vec![0; reader.output_buffer_size()?];
    let info = reader.next_frame(&mut rgb).ok()?;
    if (info.color_type, info.bit_depth) != (::png::ColorType::Rgb, ::png::BitDepth::Eight) {
        return None;
    }
    rgb.truncate(info.buffer_size());
    Some((info.width, info.height, rgb))
}
