//! PNG maps through the `png` crate: grey, grey+alpha, RGB, RGBA and palette images at
//! any bit depth (palettes and sub-byte greys are expanded to 8 bit, tRNS to alpha;
//! 16-bit samples are kept). Writing produces 8-bit grey PNG.

use super::image::{PixelImage, Samples};
use std::io::Cursor;

/// Largest decoded image we accept (bytes): far above any real map (10 MP RGBA16 = 80 MB).
const DECODE_LIMIT: usize = 2 << 30;

/// Decode a PNG. The error string names the problem (the caller adds the path).
pub fn decode(bytes: &[u8]) -> Result<PixelImage, String> {
    let mut dec = png::Decoder::new_with_limits(
        Cursor::new(bytes),
        png::Limits {
            bytes: DECODE_LIMIT,
        },
    );
    dec.set_transformations(png::Transformations::EXPAND);
    let mut reader = dec.read_info().map_err(|e| format!("corrupt PNG: {e}"))?;
    // The budget is checked from the IHDR header, before the pixels are allocated.
    let (hw, hh) = (reader.info().width, reader.info().height);
    crate::limits::check_cells(hw as usize, hh as usize, "PNG image").map_err(|e| e.to_string())?;
    let size = reader
        .output_buffer_size()
        .ok_or("PNG too large to decode")?;
    let mut buf = vec![0u8; size];
    let info = reader
        .next_frame(&mut buf)
        .map_err(|e| format!("corrupt PNG: {e}"))?;
    let (w, h) = (info.width as usize, info.height as usize);
    if w == 0 || h == 0 {
        return Err(format!("PNG image has zero size ({w}×{h})"));
    }
    let channels = match info.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => return Err("PNG palette was not expanded".into()),
    };
    let row_samples = w * channels;
    let (samples, maxval) = match info.bit_depth {
        png::BitDepth::Sixteen => {
            let mut v = Vec::with_capacity(row_samples * h);
            for row in buf.chunks(info.line_size).take(h) {
                v.extend(
                    row[..row_samples * 2]
                        .chunks_exact(2)
                        .map(|c| u16::from_be_bytes([c[0], c[1]])),
                );
            }
            (Samples::U16(v), 65535)
        }
        png::BitDepth::Eight => {
            let mut v = Vec::with_capacity(row_samples * h);
            for row in buf.chunks(info.line_size).take(h) {
                v.extend_from_slice(&row[..row_samples]);
            }
            (Samples::U8(v), 255)
        }
        d => return Err(format!("unexpected PNG bit depth {d:?} after expansion")),
    };
    Ok(PixelImage {
        width: w,
        height: h,
        channels,
        maxval,
        samples,
    })
}

/// Encode 8-bit grey samples as PNG.
pub fn encode(data: &[u8], width: usize, height: usize) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width as u32, height as u32);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Fast);
        let mut wr = enc.write_header().map_err(|e| e.to_string())?;
        wr.write_image_data(data).map_err(|e| e.to_string())?;
        wr.finish().map_err(|e| e.to_string())?;
    }
    Ok(out)
}

/// Encode any supported layout (tests write every colour type and depth with this).
pub fn encode_any(img: &PixelImage) -> Result<Vec<u8>, String> {
    let color = match img.channels {
        1 => png::ColorType::Grayscale,
        2 => png::ColorType::GrayscaleAlpha,
        3 => png::ColorType::Rgb,
        4 => png::ColorType::Rgba,
        c => return Err(format!("{c} channels")),
    };
    let (depth, bytes): (_, Vec<u8>) = match &img.samples {
        Samples::U8(s) => (png::BitDepth::Eight, s.clone()),
        Samples::U16(s) => (
            png::BitDepth::Sixteen,
            s.iter().flat_map(|v| v.to_be_bytes()).collect(),
        ),
    };
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, img.width as u32, img.height as u32);
        enc.set_color(color);
        enc.set_depth(depth);
        let mut wr = enc.write_header().map_err(|e| e.to_string())?;
        wr.write_image_data(&bytes).map_err(|e| e.to_string())?;
        wr.finish().map_err(|e| e.to_string())?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_layout_round_trips() {
        for channels in 1..=4 {
            let n = 3 * 2 * channels;
            for samples in [
                Samples::U8((0..n as u8).collect()),
                Samples::U16((0..n as u16).map(|v| v * 1000).collect()),
            ] {
                let maxval = if matches!(samples, Samples::U8(_)) {
                    255
                } else {
                    65535
                };
                let im = PixelImage {
                    width: 3,
                    height: 2,
                    channels,
                    maxval,
                    samples,
                };
                let back = decode(&encode_any(&im).unwrap()).unwrap();
                assert_eq!(back, im);
            }
        }
    }

    #[test]
    fn grey8_encode_and_corrupt_input() {
        let png = encode(&[0, 254, 205, 7], 2, 2).unwrap();
        assert_eq!(
            decode(&png).unwrap().samples,
            Samples::U8(vec![0, 254, 205, 7])
        );
        assert!(decode(&png[..20]).unwrap_err().contains("corrupt PNG"));
        assert!(decode(b"definitely not a png")
            .unwrap_err()
            .contains("corrupt PNG"));
    }
}
