//! Decoded map images and the pixel → occupancy rule of nav2's `map_io`.
//!
//! nav2 (`nav2_map_server/src/map_io.cpp`, `loadMapFromFile`) reads every image through
//! GraphicsMagick, so a pixel always has red, green and blue quantums (grey images repeat
//! the grey value) and maybe an alpha quantum. Per pixel:
//!
//! * `shade` = mean of R, G, B — and, in **trinary** mode only, of the alpha value too
//!   (opaque = 1) when the image has an alpha channel — scaled to [0, 1];
//! * `occ` = `shade` if `negate` else `1 − shade`;
//! * **trinary**: `occ > occupied_thresh` → occupied, `occ < free_thresh` → free, else unknown;
//! * **scale**: a non-opaque pixel → unknown; otherwise as trinary, but the values in
//!   between become an occupancy percentage. Our grid is trinary (254/0/205), so those
//!   intermediate cells are stored as **unknown (205)**;
//! * **raw**: `round(shade · 255)` *is* the occupancy percentage when it lies in 0..=100
//!   (otherwise unknown); `negate` and the thresholds do not apply. We store percentage
//!   0 as free, 100 as occupied, and — like `map_saver` would when writing a trinary
//!   image — a percentage ≤ 100·free_thresh as free, ≥ 100·occupied_thresh as occupied,
//!   everything else as unknown.
//!
//! Images with a bit depth of 16 are scaled by their maximum value (65535 for PNG,
//! `maxval` for PGM), exactly as GraphicsMagick scales them to its quantum range.

use super::{FREE, OCCUPIED, UNKNOWN};

/// How pixel values become occupancy (the YAML `mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapMode {
    Trinary,
    Scale,
    Raw,
}

impl MapMode {
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "trinary" => Some(MapMode::Trinary),
            "scale" => Some(MapMode::Scale),
            "raw" => Some(MapMode::Raw),
            _ => None,
        }
    }
    pub fn as_str(self) -> &'static str {
        match self {
            MapMode::Trinary => "trinary",
            MapMode::Scale => "scale",
            MapMode::Raw => "raw",
        }
    }
}

/// The thresholds and flags of a map YAML that decide occupancy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thresholds {
    pub mode: MapMode,
    pub negate: bool,
    pub occupied_thresh: f64,
    pub free_thresh: f64,
}

impl Default for Thresholds {
    fn default() -> Self {
        Thresholds {
            mode: MapMode::Trinary,
            negate: false,
            occupied_thresh: 0.65,
            free_thresh: 0.196,
        }
    }
}

/// Decoded samples, 8- or 16-bit.
#[derive(Debug, Clone, PartialEq)]
pub enum Samples {
    U8(Vec<u8>),
    U16(Vec<u16>),
}

/// A decoded image: `channels` interleaved samples per pixel (1 grey, 2 grey+alpha,
/// 3 RGB, 4 RGBA), rows top to bottom, each sample in `0..=maxval`.
#[derive(Debug, Clone, PartialEq)]
pub struct PixelImage {
    pub width: usize,
    pub height: usize,
    pub channels: usize,
    pub maxval: u32,
    pub samples: Samples,
}

impl PixelImage {
    /// True if the last channel is alpha.
    pub fn has_alpha(&self) -> bool {
        self.channels == 2 || self.channels == 4
    }

    /// Bits per sample (8 or 16).
    pub fn bit_depth(&self) -> u8 {
        match self.samples {
            Samples::U8(_) => 8,
            Samples::U16(_) => 16,
        }
    }

    /// Occupancy values (254/0/205) of every pixel, nav2's rule (see the module docs).
    pub fn to_occupancy(&self, t: &Thresholds) -> Vec<u8> {
        match &self.samples {
            Samples::U8(s) => convert(s, self.channels, self.maxval as f64, t),
            Samples::U16(s) => convert(s, self.channels, self.maxval as f64, t),
        }
    }
}

fn convert<T: Copy + Into<f64>>(s: &[T], channels: usize, maxval: f64, t: &Thresholds) -> Vec<u8> {
    let colour = if channels >= 3 { 3 } else { 1 };
    let alpha = channels == 2 || channels == 4;
    s.chunks_exact(channels)
        .map(|px| {
            // Grey images have R = G = B = grey, so their mean is the grey value itself.
            let rgb_sum: f64 =
                px[..colour].iter().map(|&v| v.into()).sum::<f64>() * (3 / colour) as f64;
            let a = if alpha {
                px[channels - 1].into()
            } else {
                maxval
            };
            let shade = if t.mode == MapMode::Trinary && alpha {
                (rgb_sum + a) / 4.0
            } else {
                rgb_sum / 3.0
            } / maxval;
            occupancy(shade, a < maxval, t)
        })
        .collect()
}

/// One pixel: `shade` in [0, 1]; `translucent` = alpha below opaque.
#[inline]
pub fn occupancy(shade: f64, translucent: bool, t: &Thresholds) -> u8 {
    let occ = if t.negate { shade } else { 1.0 - shade };
    let classify = |occ: f64| {
        if t.occupied_thresh < occ {
            OCCUPIED
        } else if occ < t.free_thresh {
            FREE
        } else {
            UNKNOWN
        }
    };
    match t.mode {
        MapMode::Trinary => classify(occ),
        // Intermediate percentages have no trinary value: unknown (see module docs).
        MapMode::Scale if translucent => UNKNOWN,
        MapMode::Scale => classify(occ),
        MapMode::Raw => {
            let pct = (shade * 255.0).round();
            if !(0.0..=100.0).contains(&pct) {
                UNKNOWN
            } else if pct <= 100.0 * t.free_thresh {
                FREE
            } else if pct >= 100.0 * t.occupied_thresh {
                OCCUPIED
            } else {
                UNKNOWN
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn img(channels: usize, px: Vec<u8>) -> PixelImage {
        PixelImage {
            width: px.len() / channels,
            height: 1,
            channels,
            maxval: 255,
            samples: Samples::U8(px),
        }
    }

    #[test]
    fn trinary_grey_thresholds() {
        let t = Thresholds::default();
        // 254 → occ 0.004 free; 0 → occ 1 occupied; 205 → occ 0.196 (not < 0.196) unknown.
        assert_eq!(
            img(1, vec![254, 0, 205, 255, 60]).to_occupancy(&t),
            vec![FREE, OCCUPIED, UNKNOWN, FREE, OCCUPIED]
        );
        let neg = Thresholds { negate: true, ..t };
        assert_eq!(
            img(1, vec![254, 0]).to_occupancy(&neg),
            vec![OCCUPIED, FREE]
        );
    }

    #[test]
    fn trinary_averages_alpha_but_scale_marks_translucent_unknown() {
        let t = Thresholds::default();
        // white but fully transparent: shade = (3·255 + 0)/4/255 = 0.75 → occ 0.25 → unknown
        assert_eq!(img(2, vec![255, 0]).to_occupancy(&t), vec![UNKNOWN]);
        assert_eq!(
            img(4, vec![255, 255, 255, 255, 0, 0, 0, 255]).to_occupancy(&t),
            vec![FREE, OCCUPIED]
        );
        let s = Thresholds {
            mode: MapMode::Scale,
            ..t
        };
        assert_eq!(
            img(2, vec![255, 254, 255, 255, 128, 255]).to_occupancy(&s),
            vec![UNKNOWN, FREE, UNKNOWN]
        );
    }

    #[test]
    fn rgb_mean_and_raw_mode() {
        let t = Thresholds::default();
        // mean(255, 255, 0) = 170 → occ 0.333 → unknown
        assert_eq!(img(3, vec![255, 255, 0]).to_occupancy(&t), vec![UNKNOWN]);
        let r = Thresholds {
            mode: MapMode::Raw,
            ..t
        };
        assert_eq!(
            img(1, vec![0, 100, 50, 19, 65, 101, 255]).to_occupancy(&r),
            vec![FREE, OCCUPIED, UNKNOWN, FREE, OCCUPIED, UNKNOWN, UNKNOWN]
        );
    }

    #[test]
    fn sixteen_bit_scales_by_maxval() {
        let t = Thresholds::default();
        let im = PixelImage {
            width: 3,
            height: 1,
            channels: 1,
            maxval: 65535,
            samples: Samples::U16(vec![65535, 0, 52000]),
        };
        assert_eq!(im.to_occupancy(&t), vec![FREE, OCCUPIED, UNKNOWN]);
    }
}
