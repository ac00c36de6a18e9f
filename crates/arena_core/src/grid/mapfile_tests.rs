//! Tests of map reading and writing on small maps written here, every format and mode.

use super::*;
use crate::grid::image::Samples;

struct TmpDir(PathBuf);
impl TmpDir {
    fn new(tag: &str) -> Self {
        static N: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
        let n = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let d =
            std::env::temp_dir().join(format!("arena_mapfile_{tag}_{}_{n}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        TmpDir(d)
    }
    fn write(&self, name: &str, bytes: &[u8]) -> PathBuf {
        let p = self.0.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    }
}
impl Drop for TmpDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn yaml(image: &str, extra: &str) -> String {
    format!("image: {image}\nresolution: 0.1\norigin: [1.0, -2.0, 0.5]\n{extra}")
}

fn expect_format_err(r: Result<(OccupancyGrid, MapMeta)>, needle: &str) {
    match r {
        Err(ArenaError::MapFormat { message, .. }) => {
            assert!(message.contains(needle), "{message:?} lacks {needle:?}")
        }
        other => panic!("expected MapFormat error containing {needle:?}, got {other:?}"),
    }
}

/// Grey levels 255 (white), 0 (black), 205 (unknown grey), 60 (dark) in a 2×2 image.
const GREYS: [u8; 4] = [255, 0, 205, 60];

#[test]
fn every_png_layout_and_depth_loads_like_nav2() {
    let d = TmpDir::new("png");
    for channels in 1..=4usize {
        for sixteen in [false, true] {
            let mut s16 = Vec::new();
            for g in GREYS {
                let v = g as u16 * 257;
                s16.extend(std::iter::repeat_n(v, if channels >= 3 { 3 } else { 1 }));
                if channels == 2 || channels == 4 {
                    s16.push(65535);
                }
            }
            let samples = if sixteen {
                Samples::U16(s16)
            } else {
                Samples::U8(s16.iter().map(|v| (v / 257) as u8).collect())
            };
            let maxval = if sixteen { 65535 } else { 255 };
            let img = PixelImage {
                width: 2,
                height: 2,
                channels,
                maxval,
                samples,
            };
            let name = format!("m{channels}_{sixteen}.png");
            d.write(&name, &png_io::encode_any(&img).unwrap());
            let y = d.write(
                &format!("m{channels}_{sixteen}.yaml"),
                yaml(&name, "").as_bytes(),
            );
            let (g, meta) = load_map(&y).unwrap();
            // nav2 averages an opaque alpha (= white) into the shade in trinary mode, so
            // 205 becomes free and 60 unknown when the image has an alpha channel.
            let want = if channels % 2 == 0 {
                [FREE, OCCUPIED, FREE, UNKNOWN]
            } else {
                [FREE, OCCUPIED, UNKNOWN, OCCUPIED]
            };
            assert_eq!(g.data, want, "channels {channels} 16-bit {sixteen}");
            assert_eq!(
                (g.width, g.height, g.resolution, g.origin),
                (2, 2, 0.1, [1.0, -2.0, 0.5])
            );
            assert_eq!(
                (
                    meta.image_channels,
                    meta.image_bit_depth,
                    meta.image_format.name()
                ),
                (channels, if sixteen { 16 } else { 8 }, "png")
            );
        }
    }
}

#[test]
fn pgm_p2_p5_eight_and_sixteen_bit() {
    let d = TmpDir::new("pgm");
    d.write("a.pgm", b"P2\n# c\n2 2\n255\n255 0\n205 60\n");
    let mut p5 = b"P5\n2 2\n65535\n".to_vec();
    for g in GREYS {
        p5.extend_from_slice(&(g as u16 * 257).to_be_bytes());
    }
    d.write("b.pgm", &p5);
    d.write("c.pgm", &pgm::encode(&GREYS, 2, 2));
    for name in ["a.pgm", "b.pgm", "c.pgm"] {
        let y = d.write("m.yaml", yaml(name, "").as_bytes());
        let (g, meta) = load_map(&y).unwrap();
        assert_eq!(g.data, vec![FREE, OCCUPIED, UNKNOWN, OCCUPIED], "{name}");
        assert_eq!(meta.image_format, ImageFormat::Pgm);
        assert_eq!(
            meta.defaulted,
            vec!["occupied_thresh", "free_thresh", "negate", "mode"]
        );
    }
}

#[test]
fn modes_negate_and_thresholds() {
    let d = TmpDir::new("modes");
    // grey+alpha: (255, opaque), (255, transparent), (0, opaque), (140, opaque)
    let img = PixelImage {
        width: 4,
        height: 1,
        channels: 2,
        maxval: 255,
        samples: Samples::U8(vec![255, 255, 255, 0, 0, 255, 140, 255]),
    };
    d.write("ga.png", &png_io::encode_any(&img).unwrap());
    let cases: [(&str, [u8; 4]); 5] = [
        ("mode: trinary", [FREE, UNKNOWN, OCCUPIED, UNKNOWN]),
        ("mode: scale", [FREE, UNKNOWN, OCCUPIED, UNKNOWN]),
        (
            "mode: trinary\nnegate: 1",
            [OCCUPIED, OCCUPIED, UNKNOWN, OCCUPIED],
        ),
        (
            "negate: true\noccupied_thresh: 0.5\nfree_thresh: 0.3",
            [OCCUPIED, OCCUPIED, FREE, OCCUPIED],
        ),
        ("mode: raw", [UNKNOWN, UNKNOWN, FREE, UNKNOWN]),
    ];
    for (extra, want) in cases {
        let y = d.write("m.yaml", yaml("ga.png", extra).as_bytes());
        assert_eq!(load_map(&y).unwrap().0.data, want, "{extra}");
    }
    // raw on a grey image: pixel value = percentage
    d.write("raw.pgm", &pgm::encode(&[0, 100, 50, 200], 4, 1));
    let y = d.write("r.yaml", yaml("raw.pgm", "mode: raw\n").as_bytes());
    assert_eq!(
        load_map(&y).unwrap().0.data,
        vec![FREE, OCCUPIED, UNKNOWN, UNKNOWN]
    );
}

#[test]
fn one_by_one_map_and_round_trip_both_formats() {
    let d = TmpDir::new("rt");
    d.write("one.pgm", &pgm::encode(&[254], 1, 1));
    let y = d.write("one.yaml", yaml("one.pgm", "").as_bytes());
    let (g, _) = load_map(&y).unwrap();
    assert_eq!((g.width, g.height, g.data.clone()), (1, 1, vec![FREE]));

    let mut g = OccupancyGrid::filled(5, 3, 0.05, [-1.25, 3.5, -0.25], UNKNOWN);
    g.data[0] = FREE;
    g.data[7] = OCCUPIED;
    for fmt in [ImageFormat::Png, ImageFormat::Pgm] {
        let yp = d.0.join(format!("out_{fmt:?}.yaml"));
        let img = save_map(&g, &yp, fmt).unwrap();
        assert!(img.is_file());
        let (back, meta) = load_map(&yp).unwrap();
        assert_eq!(back, g);
        assert!(meta.defaulted.is_empty());
    }
    let mut bad = g.clone();
    bad.data[1] = 17;
    assert!(matches!(
        save_map(&bad, d.0.join("bad.yaml"), ImageFormat::Png),
        Err(ArenaError::InvalidArgument(_))
    ));
    assert!(!d.0.join("bad.yaml").exists());
}

#[test]
fn broken_yaml_and_images_say_what_is_wrong() {
    let d = TmpDir::new("bad");
    d.write("ok.pgm", &pgm::encode(&[254; 4], 2, 2));
    expect_format_err(
        load_map(d.write("a.yaml", b"resolution: 0.1\norigin: [0, 0, 0]\n")),
        "missing required key 'image'",
    );
    expect_format_err(
        load_map(d.write("b.yaml", b"image: ok.pgm\norigin: [0, 0, 0]\n")),
        "missing required key 'resolution'",
    );
    expect_format_err(
        load_map(d.write(
            "c.yaml",
            b"image: ok.pgm\nresolution: .nan\norigin: [0, 0, 0]\n",
        )),
        "resolution must be in [0.001, 1]",
    );
    expect_format_err(
        load_map(d.write(
            "c2.yaml",
            b"image: ok.pgm\nresolution: -1\norigin: [0, 0, 0]\n",
        )),
        "resolution must be in [0.001, 1]",
    );
    expect_format_err(
        load_map(d.write(
            "d.yaml",
            b"image: ok.pgm\nresolution: fast\norigin: [0, 0, 0]\n",
        )),
        "'resolution' must be a number",
    );
    expect_format_err(
        load_map(d.write("e.yaml", b"image: ok.pgm\nresolution: 0.1\norigin: 3\n")),
        "'origin' must be a list",
    );
    expect_format_err(
        load_map(d.write("f.yaml", yaml("ok.pgm", "mode: fuzzy\n").as_bytes())),
        "trinary, scale or raw",
    );
    expect_format_err(
        load_map(d.write("g.yaml", yaml("ok.pgm", "negate: 2\n").as_bytes())),
        "'negate'",
    );
    expect_format_err(
        load_map(d.write("h.yaml", yaml("ok.pgm", "free_thresh: 3\n").as_bytes())),
        "'free_thresh'",
    );
    expect_format_err(
        load_map(d.write("i.yaml", b"image: [unclosed\n")),
        "not valid YAML",
    );
    expect_format_err(
        load_map(d.write("j.yaml", b"- just\n- a list\n")),
        "mapping",
    );
    // the image is missing, but one named after the YAML exists (porto.yaml → map.pgm)
    d.write("porto.pgm", &pgm::encode(&[254; 4], 2, 2));
    expect_format_err(
        load_map(d.write("porto.yaml", yaml("map.pgm", "").as_bytes())),
        "did you mean `image: porto.pgm`",
    );
    expect_format_err(
        load_map(d.write("k.yaml", yaml("nothere.png", "").as_bytes())),
        "does not exist",
    );
    // corrupt / empty / zero-size images
    d.write("corrupt.png", b"\x89PNG\r\n\x1a\n garbage garbage");
    expect_format_err(
        load_map(d.write("l.yaml", yaml("corrupt.png", "").as_bytes())),
        "corrupt PNG",
    );
    d.write("empty.pgm", b"");
    expect_format_err(
        load_map(d.write("m.yaml", yaml("empty.pgm", "").as_bytes())),
        "empty",
    );
    d.write("zero.pgm", b"P5 0 0 255\n");
    expect_format_err(
        load_map(d.write("n.yaml", yaml("zero.pgm", "").as_bytes())),
        "zero size",
    );
    d.write("pic.jpg", b"\xff\xd8\xff\xe0 jpeg");
    expect_format_err(
        load_map(d.write("o.yaml", yaml("pic.jpg", "").as_bytes())),
        "neither PNG nor PGM",
    );
    // a YAML that does not exist is an I/O error naming it
    match load_map(d.0.join("absent.yaml")) {
        Err(ArenaError::Io { path, .. }) => assert!(path.ends_with("absent.yaml")),
        other => panic!("{other:?}"),
    }
}

#[test]
fn hostile_headers_and_fields_are_refused_before_allocating() {
    let d = TmpDir::new("hostile");
    // Allocation bombs: tiny files declaring huge rasters.
    d.write("p2.pgm", b"P2\n150000 150000\n255\n0 0 0\n");
    d.write("p5.pgm", b"P5 4294967295 4294967295 65535\n\0\0");
    d.write("p5x.pgm", b"P5 18446744073709551615 2 65535\n\0\0");
    for (i, img) in ["p2.pgm", "p5.pgm", "p5x.pgm"].iter().enumerate() {
        expect_format_err(
            load_map(d.write(&format!("bomb{i}.yaml"), yaml(img, "").as_bytes())),
            "",
        );
    }
    let mut png = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png, 1, 1);
        enc.set_color(png::ColorType::Grayscale);
        enc.write_header().unwrap().write_image_data(&[0]).unwrap();
    }
    // Patch IHDR to 2^31-1 squared (the CRC is then wrong, or the size is refused first).
    png[16..20].copy_from_slice(&0x7fff_ffffu32.to_be_bytes());
    png[20..24].copy_from_slice(&0x7fff_ffffu32.to_be_bytes());
    d.write("bomb.png", &png);
    expect_format_err(
        load_map(d.write("bombpng.yaml", yaml("bomb.png", "").as_bytes())),
        "",
    );
    // Implausible resolutions and origins name the field and the range.
    d.write("ok.pgm", &pgm::encode(&[254; 10_000], 100, 100));
    for (i, r) in ["1e300", "1e-300", "1e6", "1000", ".inf"]
        .iter()
        .enumerate()
    {
        let y = format!("image: ok.pgm\nresolution: {r}\norigin: [0, 0, 0]\n");
        expect_format_err(
            load_map(d.write(&format!("r{i}.yaml"), y.as_bytes())),
            "resolution",
        );
    }
    let y = "image: ok.pgm\nresolution: 0.9\norigin: [0, 0, 0]\n";
    assert!(load_map(d.write("r_ok.yaml", y.as_bytes())).is_ok());
    for (i, o) in ["[1e300, -1e300, 0]", "[0, 0, .nan]", "[1e6, 0, 0]"]
        .iter()
        .enumerate()
    {
        let y = format!("image: ok.pgm\nresolution: 0.05\norigin: {o}\n");
        expect_format_err(
            load_map(d.write(&format!("o{i}.yaml"), y.as_bytes())),
            "origin",
        );
    }
    // A 4-element origin is reported on one line.
    let y = "image: ok.pgm\nresolution: 0.05\norigin: [1, 2, 3, 4]\n";
    match load_map(d.write("o4.yaml", y.as_bytes())) {
        Err(e) => assert!(!e.to_string().contains('\n'), "{e}"),
        Ok(_) => panic!("4-element origin accepted"),
    }
    // Inputs must be regular files: a directory and a device say what they are.
    let dirimg = format!(
        "image: {}\nresolution: 0.05\norigin: [0, 0, 0]\n",
        d.0.display()
    );
    let e = load_map(d.write("dir.yaml", dirimg.as_bytes())).unwrap_err();
    assert!(e.to_string().contains("directory"), "{e}");
    #[cfg(unix)]
    {
        let y = "image: /dev/zero\nresolution: 0.05\norigin: [0, 0, 0]\n";
        let e = load_map(d.write("zero.yaml", y.as_bytes())).unwrap_err();
        assert!(e.to_string().contains("device"), "{e}");
        let e = load_map("/dev/zero").unwrap_err();
        assert!(e.to_string().contains("device"), "{e}");
    }
}

#[test]
fn save_writes_both_files_or_neither() {
    let d = TmpDir::new("save");
    let g = OccupancyGrid::filled(4, 3, 0.05, [0.0; 3], FREE);
    // The YAML's name is taken by a directory: the write fails and no image is left.
    std::fs::create_dir_all(d.0.join("m.yaml")).unwrap();
    assert!(save_map(&g, d.0.join("m.yaml"), ImageFormat::Png).is_err());
    assert!(!d.0.join("m.png").exists());
    let img = save_map(&g, d.0.join("ok.yaml"), ImageFormat::Pgm).unwrap();
    assert!(img.exists() && d.0.join("ok.yaml").exists());
}
