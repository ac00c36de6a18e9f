//! Portable grey maps: P2 (ASCII) and P5 (binary), 8 and 16 bit (big-endian, as the
//! Netpbm spec says), comments anywhere in the header. Writing produces 8-bit P5.

use super::image::{PixelImage, Samples};

/// Decode a PGM. The error string names the problem (the caller adds the path).
pub fn decode(bytes: &[u8]) -> Result<PixelImage, String> {
    let mut pos = 0usize;
    let magic = token(bytes, &mut pos).ok_or("empty file, not a PGM image")?;
    let ascii = match magic {
        b"P2" => true,
        b"P5" => false,
        b"P1" | b"P4" | b"P3" | b"P6" => {
            return Err(format!(
                "{} is a Netpbm bitmap/colour image; only grey maps (P2, P5) are supported",
                String::from_utf8_lossy(magic)
            ))
        }
        _ => return Err("not a PGM image (missing P2/P5 magic number)".into()),
    };
    let mut header = [0u64; 3];
    for (k, name) in ["width", "height", "maxval"].iter().enumerate() {
        let t =
            token(bytes, &mut pos).ok_or_else(|| format!("truncated PGM header (no {name})"))?;
        header[k] = std::str::from_utf8(t)
            .ok()
            .and_then(|s| s.parse().ok())
            .ok_or_else(|| format!("PGM header {name} is not a number"))?;
    }
    let [w, h, maxval] = header;
    if w == 0 || h == 0 {
        return Err(format!("PGM image has zero size ({w}×{h})"));
    }
    if maxval == 0 || maxval > 65535 {
        return Err(format!("PGM maxval {maxval} is outside 1..=65535"));
    }
    // The budget is checked from the header, before anything is allocated.
    crate::limits::check_cells(w as usize, h as usize, "PGM image").map_err(|e| e.to_string())?;
    let n = (w as usize)
        .checked_mul(h as usize)
        .ok_or("PGM size overflows")?;
    let samples = if ascii {
        // Each ASCII sample takes at least two bytes: never reserve more than the file holds.
        let mut v = Vec::with_capacity(n.min(bytes.len() / 2 + 1));
        for i in 0..n {
            let t = token(bytes, &mut pos)
                .ok_or_else(|| format!("PGM data truncated: {i} of {n} samples"))?;
            let x: u32 = std::str::from_utf8(t)
                .ok()
                .and_then(|s| s.parse().ok())
                .ok_or("PGM data holds a non-number")?;
            v.push(x.min(maxval as u32) as u16);
        }
        if maxval < 256 {
            Samples::U8(v.into_iter().map(|x| x as u8).collect())
        } else {
            Samples::U16(v)
        }
    } else {
        pos += 1; // exactly one whitespace byte after maxval
        let bps = if maxval < 256 { 1 } else { 2 };
        let need = n.checked_mul(bps).ok_or("PGM size overflows")?;
        let data = bytes.get(pos..).unwrap_or(&[]);
        if data.len() < need {
            return Err(format!(
                "PGM data truncated: {} of {} bytes",
                data.len(),
                need
            ));
        }
        if bps == 1 {
            Samples::U8(data[..need].to_vec())
        } else {
            Samples::U16(
                data[..need]
                    .chunks_exact(2)
                    .map(|c| u16::from_be_bytes([c[0], c[1]]))
                    .collect(),
            )
        }
    };
    Ok(PixelImage {
        width: w as usize,
        height: h as usize,
        channels: 1,
        maxval: maxval as u32,
        samples,
    })
}

/// Next whitespace-separated header/ASCII token, skipping `#` comments to end of line.
fn token<'a>(b: &'a [u8], pos: &mut usize) -> Option<&'a [u8]> {
    loop {
        while *pos < b.len() && b[*pos].is_ascii_whitespace() {
            *pos += 1;
        }
        if *pos < b.len() && b[*pos] == b'#' {
            while *pos < b.len() && b[*pos] != b'\n' {
                *pos += 1;
            }
            continue;
        }
        break;
    }
    let start = *pos;
    while *pos < b.len() && !b[*pos].is_ascii_whitespace() && b[*pos] != b'#' {
        *pos += 1;
    }
    (start < *pos).then(|| &b[start..*pos])
}

/// Encode 8-bit grey samples as binary P5.
pub fn encode(data: &[u8], width: usize, height: usize) -> Vec<u8> {
    let mut out =
        format!("P5\n# RoboRacer Arena occupancy map\n{width} {height}\n255\n").into_bytes();
    out.extend_from_slice(data);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn p2_with_comments_and_p5_round_trip() {
        let p2 = b"P2\n# a comment\n3 2\n# another\n255\n0 254 205\n1 2 3\n";
        let im = decode(p2).unwrap();
        assert_eq!((im.width, im.height, im.maxval), (3, 2, 255));
        assert_eq!(im.samples, Samples::U8(vec![0, 254, 205, 1, 2, 3]));
        let p5 = encode(&[0, 254, 205, 1, 2, 3], 3, 2);
        assert_eq!(decode(&p5).unwrap().samples, im.samples);
    }

    #[test]
    fn sixteen_bit_binary_is_big_endian() {
        let mut b = b"P5 2 1 65535\n".to_vec();
        b.extend_from_slice(&[0xff, 0xff, 0x01, 0x00]);
        let im = decode(&b).unwrap();
        assert_eq!(im.samples, Samples::U16(vec![65535, 256]));
        assert_eq!(im.bit_depth(), 16);
    }

    #[test]
    fn errors_name_the_problem() {
        assert!(decode(b"").unwrap_err().contains("empty"));
        assert!(decode(b"P5 0 3 255\n").unwrap_err().contains("zero size"));
        assert!(decode(b"P5 4 4 255\n\x00\x00")
            .unwrap_err()
            .contains("truncated"));
        assert!(decode(b"GIF89a").unwrap_err().contains("not a PGM"));
        assert!(decode(b"P6 1 1 255\n\x00\x00\x00")
            .unwrap_err()
            .contains("P6"));
    }
}
