//! PNG bytes to 8-bit RGB, shared by the wall reader ([`crate::read_png`]) and the crew's
//! image readers: bounded by the header's size before anything is allocated for the pixels,
//! and refusing what the `png` crate would panic on.

use image::RgbImage;

/// Why PNG bytes could not be decoded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PngDecodeError {
    /// The header gives more pixels than allowed.
    TooLarge {
        /// Width from the header.
        width: u32,
        /// Height from the header.
        height: u32,
    },
    /// Not a PNG, or a damaged one; the reason.
    Malformed(String),
}

/// PNG bytes as 8-bit RGB (16-bit samples cut to 8, grey spread to three channels, alpha
/// dropped, palettes expanded), refusing more than `max_pixels` from the header before
/// allocating for them. Shared by the wall reader and the crew's image readers.
pub fn decode_png_rgb(bytes: &[u8], max_pixels: u64) -> Result<RgbImage, PngDecodeError> {
    let malformed = |e: String| PngDecodeError::Malformed(e);
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().map_err(|e| malformed(e.to_string()))?;
    let (width, height) = reader.info().size();
    if u64::from(width) * u64::from(height) > max_pixels {
        return Err(PngDecodeError::TooLarge { width, height });
    }
    // The png crate (0.18) panics on a palette that is not whole colours, or on more
    // transparency entries than colours, when it expands them (found by fuzzing).
    let info = reader.info();
    if let Some(palette) = &info.palette {
        if palette.len() % 3 != 0 {
            return Err(malformed(format!(
                "the palette (PLTE) is {} bytes, not a whole number of 3-byte colours",
                palette.len()
            )));
        }
        let transparent = info.trns.as_ref().map_or(0, |t| t.len());
        if info.color_type == png::ColorType::Indexed && transparent > palette.len() / 3 {
            return Err(malformed(format!(
                "the transparency table (tRNS) has {transparent} entries for {} palette colours",
                palette.len() / 3
            )));
        }
    }
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| malformed(format!("{width}×{height} does not fit in memory")))?;
    let mut buf = vec![0u8; size];
    let frame = reader
        .next_frame(&mut buf)
        .map_err(|e| malformed(e.to_string()))?;
    buf.truncate(frame.buffer_size());
    let pixels = width as usize * height as usize;
    let rgb = match frame.color_type {
        png::ColorType::Rgb => buf,
        png::ColorType::Rgba => {
            for i in 0..pixels {
                buf.copy_within(4 * i..4 * i + 3, 3 * i);
            }
            buf.truncate(3 * pixels);
            buf
        }
        png::ColorType::Grayscale | png::ColorType::GrayscaleAlpha => {
            let step = if frame.color_type == png::ColorType::Grayscale {
                1
            } else {
                2
            };
            buf.iter().step_by(step).flat_map(|&g| [g, g, g]).collect()
        }
        png::ColorType::Indexed => {
            return Err(malformed("an indexed image was not expanded".into()))
        }
    };
    RgbImage::from_raw(width, height, rgb)
        .ok_or_else(|| malformed("the decoded image is short".into()))
}
