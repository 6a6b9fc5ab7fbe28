use super::*;
#[path = "../../../tests/support/png.rs"]
mod support;
use support::decode_rgb;

#[test]
fn crc_of_iend_is_the_known_constant() {
    assert_eq!(crc32(b"IEND"), 0xAE42_6082);
}

#[test]
fn round_trip_through_an_independent_decoder() {
    for (w, h) in [(7u32, 5u32), (1, 1), (300, 2)] {
        let rgb: Vec<u8> = (0..w * h * 3).map(|i| (i * 37 % 251) as u8).collect();
        let png = encode_rgb(w, h, &rgb);
        assert_eq!(decode_rgb(&png), Some((w, h, rgb)));
    }
    // Short and long buffers are padded with black or cut.
    assert_eq!(decode_rgb(&encode_rgb(2, 1, &[9, 9, 9])), Some((2, 1, vec![9, 9, 9, 0, 0, 0])));
    assert_eq!(decode_rgb(&encode_rgb(1, 1, &[1, 2, 3, 4])), Some((1, 1, vec![1, 2, 3])));
    // Truncated files are errors of the decoder, not panics.
    let png = encode_rgb(7, 5, &[0; 105]);
    for n in [0, 7, 8, 20, 33, png.len() - 13] {
        assert_eq!(decode_rgb(&png[..n]), None, "{n} bytes");
    }
}
