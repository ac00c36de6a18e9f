//! ROS map files: the YAML of `map_server` / nav2 plus its PGM or PNG image.
//!
//! Every `map_server` field is honoured: `image` (relative to the YAML unless absolute),
//! `resolution`, `origin` (x, y, yaw), `negate` (0/1 or a bool), `occupied_thresh`,
//! `free_thresh`, `mode` (trinary, scale, raw). nav2 insists on `negate` and both
//! thresholds; we default them to 0, 0.65 and 0.196 when absent (and list the
//! defaulted keys in [`MapMeta::defaulted`]), and accept a 2-element origin as yaw 0.
//! Unknown keys are ignored, as nav2 does. Pixels become occupancy exactly as in nav2,
//! see [`super::image`].
//!
//! Writing produces the trinary `map_saver` form: an 8-bit grey PNG or P5 PGM with
//! 254 free, 0 occupied, 205 unknown, and a YAML with `mode: trinary`,
//! `occupied_thresh: 0.65`, `free_thresh: 0.196`; both files are written atomically.

use super::image::{MapMode, PixelImage, Thresholds};
use super::{pgm, png_io, OccupancyGrid, FREE, OCCUPIED, UNKNOWN};
use crate::error::{ArenaError, Result};
use crate::fileio::{atomic_write, read_regular};
use crate::limits;
use serde_yaml::Value;
use std::path::{Path, PathBuf};

/// What a map file said besides the grid itself (a typed, read-only object in Python).
#[derive(Debug, Clone, PartialEq)]
pub struct MapMeta {
    pub yaml_path: String,
    pub image_path: String,
    /// The image's encoding, found from its bytes (not its name).
    pub image_format: ImageFormat,
    /// Channels of the decoded image (1 grey, 2 grey+alpha, 3 RGB, 4 RGBA).
    pub image_channels: usize,
    pub image_bit_depth: u8,
    pub mode: MapMode,
    pub negate: bool,
    pub occupied_thresh: f64,
    pub free_thresh: f64,
    /// Optional keys that were absent and took their default.
    pub defaulted: Vec<String>,
}

/// Image encoding for [`save_map`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Pgm,
}

impl ImageFormat {
    pub fn parse(s: &str) -> Result<Self> {
        match s.to_ascii_lowercase().as_str() {
            "png" => Ok(ImageFormat::Png),
            "pgm" => Ok(ImageFormat::Pgm),
            _ => Err(ArenaError::invalid(format!(
                "image_format must be 'png' or 'pgm', got {s:?}"
            ))),
        }
    }
    /// The format's name, also the image file's extension.
    pub fn name(self) -> &'static str {
        match self {
            ImageFormat::Png => "png",
            ImageFormat::Pgm => "pgm",
        }
    }
}

struct YamlFields {
    image: String,
    resolution: f64,
    origin: [f64; 3],
    thresholds: Thresholds,
    defaulted: Vec<String>,
}

fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Number(n) => n.as_f64(),
        Value::String(s) => s.trim().parse().ok(),
        _ => None,
    }
}

fn parse_yaml(path: &Path, text: &str) -> Result<YamlFields> {
    let bad = |m: String| ArenaError::map_format(path, m);
    let doc: Value = serde_yaml::from_str(text).map_err(|e| bad(format!("not valid YAML: {e}")))?;
    let map = doc.as_mapping().ok_or_else(|| {
        bad("expected a YAML mapping of map_server keys (image, resolution, origin, ...)".into())
    })?;
    let yaml = YamlKeys { path, map };
    let image = yaml.image()?;
    let resolution = yaml.resolution()?;
    let origin = yaml.origin()?;
    let mut defaulted = Vec::new();
    let thresholds = yaml.thresholds(&mut defaulted)?;
    Ok(YamlFields {
        image,
        resolution,
        origin,
        thresholds,
        defaulted,
    })
}

/// The keys of one map YAML, each read and checked on its own; errors name the file.
struct YamlKeys<'a> {
    path: &'a Path,
    map: &'a serde_yaml::Mapping,
}

impl YamlKeys<'_> {
    fn get(&self, k: &str) -> Option<&Value> {
        self.map.get(Value::String(k.into()))
    }

    fn bad(&self, m: String) -> ArenaError {
        ArenaError::map_format(self.path, m)
    }

    /// `image`: the map image file, required.
    fn image(&self) -> Result<String> {
        match self.get("image") {
            None => Err(self.bad("missing required key 'image' (the map image file)".into())),
            Some(Value::String(s)) if !s.trim().is_empty() => Ok(s.trim().to_string()),
            Some(v) => Err(self.bad(format!("'image' must be a file name, got {}", show(v)))),
        }
    }

    /// `resolution`: metres per pixel, required, within the allowed range.
    fn resolution(&self) -> Result<f64> {
        let resolution = match self.get("resolution") {
            None => {
                return Err(self.bad("missing required key 'resolution' (metres per pixel)".into()))
            }
            Some(v) => number(v).ok_or_else(|| {
                self.bad(format!("'resolution' must be a number, got {}", show(v)))
            })?,
        };
        limits::check_resolution(resolution).map_err(|e| self.bad(e.to_string()))?;
        Ok(resolution)
    }

    /// `origin`: `[x, y]` or `[x, y, yaw]` of the lower-left pixel, required, in range.
    fn origin(&self) -> Result<[f64; 3]> {
        match self.get("origin") {
            None => Err(self
                .bad("missing required key 'origin' ([x, y, yaw] of the lower-left pixel)".into())),
            Some(Value::Sequence(s)) if s.len() == 2 || s.len() == 3 => {
                let mut o = [0.0; 3];
                for (k, v) in s.iter().enumerate() {
                    o[k] = number(v).filter(|x| x.is_finite()).ok_or_else(|| {
                        self.bad(format!(
                            "'origin' must hold finite numbers, got {}",
                            show(v)
                        ))
                    })?;
                }
                limits::check_origin(o).map_err(|e| self.bad(e.to_string()))?;
                Ok(o)
            }
            Some(v) => Err(self.bad(format!(
                "'origin' must be a list [x, y] or [x, y, yaw], got {}",
                show(v)
            ))),
        }
    }

    /// The optional keys that turn pixels into cells (`occupied_thresh`, `free_thresh`,
    /// `negate`, `mode`); each one absent gets its map_server default and is named in
    /// `defaulted`.
    fn thresholds(&self, defaulted: &mut Vec<String>) -> Result<Thresholds> {
        let occupied_thresh = self.unit("occupied_thresh")?;
        let occupied_thresh = or_default(occupied_thresh, 0.65, "occupied_thresh", defaulted);
        let free_thresh = self.unit("free_thresh")?;
        let free_thresh = or_default(free_thresh, 0.196, "free_thresh", defaulted);
        let negate = or_default(self.negate()?, false, "negate", defaulted);
        let mode = or_default(self.mode()?, MapMode::Trinary, "mode", defaulted);
        Ok(Thresholds {
            mode,
            negate,
            occupied_thresh,
            free_thresh,
        })
    }

    /// An optional number in [0, 1].
    fn unit(&self, k: &str) -> Result<Option<f64>> {
        match self.get(k) {
            None => Ok(None),
            Some(v) => match number(v) {
                Some(x) if (0.0..=1.0).contains(&x) => Ok(Some(x)),
                _ => Err(self.bad(format!("'{k}' must be a number in [0, 1], got {}", show(v)))),
            },
        }
    }

    /// `negate`: optional, a boolean or 0/1.
    fn negate(&self) -> Result<Option<bool>> {
        match self.get("negate") {
            None => Ok(None),
            Some(Value::Bool(b)) => Ok(Some(*b)),
            Some(v) => match number(v) {
                Some(x) if x == 0.0 || x == 1.0 => Ok(Some(x == 1.0)),
                _ => Err(self.bad(format!(
                    "'negate' must be 0, 1, true or false, got {}",
                    show(v)
                ))),
            },
        }
    }

    /// `mode`: optional, trinary, scale or raw.
    fn mode(&self) -> Result<Option<MapMode>> {
        match self.get("mode") {
            None => Ok(None),
            Some(Value::String(s)) => MapMode::parse(s.trim()).map(Some).ok_or_else(|| {
                self.bad(format!("'mode' must be trinary, scale or raw, got {s:?}"))
            }),
            Some(v) => Err(self.bad(format!(
                "'mode' must be trinary, scale or raw, got {}",
                show(v)
            ))),
        }
    }
}

/// `value`, or `default` with `key` named in `defaulted` when the key is absent.
fn or_default<T>(value: Option<T>, default: T, key: &str, defaulted: &mut Vec<String>) -> T {
    value.unwrap_or_else(|| {
        defaulted.push(key.to_string());
        default
    })
}

/// A YAML value on one line (flow style via JSON), cut to a readable length.
fn show(v: &Value) -> String {
    let s = serde_json::to_string(v).unwrap_or_else(|_| format!("{v:?}"));
    match s.char_indices().nth(80) {
        Some((i, _)) => format!("{}…", &s[..i]),
        None => s,
    }
}

/// Largest map YAML read (bytes): real ones are a few hundred bytes.
pub const MAX_YAML_BYTES: u64 = 1 << 20;

/// Largest map image file read (bytes): enough for the pixel budget as 16-bit ASCII PGM
/// ("65535 " per sample), plus a header.
fn max_image_bytes() -> Result<u64> {
    Ok(limits::max_pixels()?
        .saturating_mul(6)
        .saturating_add(1 << 20))
}

/// A helpful sentence when the image named by the YAML does not exist: the yaml's
/// stem with an image extension, or any lone image in the folder.
fn missing_image_hint(yaml: &Path) -> String {
    let dir = yaml.parent().unwrap_or(Path::new("."));
    let stem = yaml
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_default();
    for ext in ["pgm", "png", "PGM", "PNG"] {
        let cand = dir.join(format!("{stem}.{ext}"));
        if cand.is_file() {
            return format!(
                "; '{}' exists beside the YAML: did you mean `image: {}`?",
                cand.display(),
                format_args!("{stem}.{ext}")
            );
        }
    }
    String::new()
}

/// Decode an image file by its content (PNG signature or P2/P5 magic).
pub fn read_image(path: &Path) -> Result<(PixelImage, ImageFormat)> {
    let bytes = read_regular(path, "map image", max_image_bytes()?)?;
    let bad = |m: String| ArenaError::map_format(path, m);
    if bytes.is_empty() {
        return Err(bad("map image is empty (0 bytes)".into()));
    }
    if bytes.starts_with(b"\x89PNG") {
        Ok((png_io::decode(&bytes).map_err(bad)?, ImageFormat::Png))
    } else if bytes.first() == Some(&b'P') {
        Ok((pgm::decode(&bytes).map_err(bad)?, ImageFormat::Pgm))
    } else {
        Err(bad(
            "unsupported or corrupt map image: neither PNG nor PGM (P2/P5)".into(),
        ))
    }
}

/// Load a ROS map YAML and its image as a trinary grid (254/0/205).
pub fn load_map(yaml_path: impl AsRef<Path>) -> Result<(OccupancyGrid, MapMeta)> {
    let yaml_path = yaml_path.as_ref();
    let bytes = read_regular(yaml_path, "map YAML", MAX_YAML_BYTES)?;
    let text = String::from_utf8(bytes)
        .map_err(|_| ArenaError::map_format(yaml_path, "map YAML is not UTF-8 text"))?;
    let y = parse_yaml(yaml_path, &text)?;
    let image_path: PathBuf = match Path::new(&y.image) {
        p if p.is_absolute() => p.to_path_buf(),
        p => yaml_path.parent().unwrap_or(Path::new(".")).join(p),
    };
    if std::fs::symlink_metadata(&image_path).is_err() {
        return Err(ArenaError::map_format(
            yaml_path,
            format!(
                "map image '{}' (from `image: {}`) does not exist{}",
                image_path.display(),
                y.image,
                missing_image_hint(yaml_path)
            ),
        ));
    }
    let (img, format) = read_image(&image_path)?;
    limits::check_grid_header(img.width, img.height, y.resolution, y.origin)
        .map_err(|e| ArenaError::map_format(yaml_path, e.to_string()))?;
    let data = img.to_occupancy(&y.thresholds);
    let grid = OccupancyGrid {
        width: img.width,
        height: img.height,
        resolution: y.resolution,
        origin: y.origin,
        data,
    };
    let meta = MapMeta {
        yaml_path: yaml_path.display().to_string(),
        image_path: image_path.display().to_string(),
        image_format: format,
        image_channels: img.channels,
        image_bit_depth: img.bit_depth(),
        mode: y.thresholds.mode,
        negate: y.thresholds.negate,
        occupied_thresh: y.thresholds.occupied_thresh,
        free_thresh: y.thresholds.free_thresh,
        defaulted: y.defaulted,
    };
    Ok((grid, meta))
}

/// The map_saver YAML text for `grid` with its image named `image_name`.
pub fn map_yaml(grid: &OccupancyGrid, image_name: &str) -> String {
    let [x, y, yaw] = grid.origin;
    format!(
        "image: {image_name}\nmode: trinary\nresolution: {:?}\norigin: [{x:?}, {y:?}, {yaw:?}]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
        grid.resolution
    )
}

/// Write `grid` as a trinary map: `STEM.png|pgm` beside `yaml_path`, then the YAML.
/// Returns the image path. Values other than 254/0/205 are refused.
pub fn save_map(
    grid: &OccupancyGrid,
    yaml_path: impl AsRef<Path>,
    format: ImageFormat,
) -> Result<PathBuf> {
    let yaml_path = yaml_path.as_ref();
    if grid.width == 0 || grid.height == 0 || grid.data.len() != grid.width * grid.height {
        return Err(ArenaError::invalid(format!(
            "cannot save a {}×{} map holding {} cells",
            grid.width,
            grid.height,
            grid.data.len()
        )));
    }
    if !(grid.resolution.is_finite() && grid.resolution > 0.0)
        || grid.origin.iter().any(|v| !v.is_finite())
    {
        return Err(ArenaError::invalid(format!(
            "resolution must be finite > 0 and origin finite, got {} and {:?}",
            grid.resolution, grid.origin
        )));
    }
    if let Some(v) = grid
        .data
        .iter()
        .find(|&&v| v != FREE && v != OCCUPIED && v != UNKNOWN)
    {
        return Err(ArenaError::invalid(format!(
            "map data must be trinary (254 free, 0 occupied, 205 unknown), found {v}"
        )));
    }
    let stem = yaml_path
        .file_stem()
        .ok_or_else(|| ArenaError::io(yaml_path, "not a file path"))?
        .to_string_lossy()
        .to_string();
    let image_name = format!("{stem}.{}", format.name());
    let image_path = yaml_path.with_file_name(&image_name);
    let bytes = match format {
        ImageFormat::Png => png_io::encode(&grid.data, grid.width, grid.height)
            .map_err(|e| ArenaError::io(&image_path, e))?,
        ImageFormat::Pgm => pgm::encode(&grid.data, grid.width, grid.height),
    };
    // Both files or neither: an image this call created is removed if the YAML fails.
    let image_existed = image_path.exists();
    atomic_write(&image_path, &bytes)?;
    if let Err(e) = atomic_write(yaml_path, map_yaml(grid, &image_name).as_bytes()) {
        if !image_existed {
            let _ = std::fs::remove_file(&image_path);
        }
        return Err(e);
    }
    Ok(image_path)
}

#[cfg(test)]
#[path = "mapfile_tests.rs"]
mod tests;
