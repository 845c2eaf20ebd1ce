//! Small helpers shared by the figure writers: error text and PNG encoding.

pub(super) fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// 8-bit RGB pixels, row 0 at the top, as PNG file bytes.
pub(super) fn encode_png((w, h): (u32, u32), rgb: &[u8]) -> Result<Vec<u8>, png::EncodingError> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, w, h);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(rgb)?;
        writer.finish()?;
    }
    Ok(bytes)
}
