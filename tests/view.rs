//! `rastray view` with no terminal: each protocol's payload decoded back to pixels and compared
//! with `rastray render` at the same size.

use std::path::Path;
use std::process::{Command, Output};

use base64::Engine;
use base64::engine::general_purpose::STANDARD;

fn rastray(args: &[&str], dir: &Path) -> Output {
    let o = Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

fn scene() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/default.toml")
        .to_string_lossy()
        .into_owned()
}

fn view(graphics: &str, dir: &Path) -> Vec<u8> {
    rastray(
        &["view", &scene(), "--graphics", graphics, "--width", "80"],
        dir,
    )
    .stdout
}

/// `rastray render` of the default scene at `width`×`height`.
fn rendered(width: u32, height: u32, dir: &Path) -> image::RgbImage {
    let out = dir.join("render.png");
    let size = format!("{width}x{height}");
    rastray(
        &["render", &scene(), "-s", &size, "-o", out.to_str().unwrap()],
        dir,
    );
    image::open(&out).expect("a PNG").to_rgb8()
}

/// Every payload between `start` and `end`, after the first ';' or ':' that follows `start`.
fn payloads<'a>(text: &'a str, start: &str, sep: char, end: &str) -> Vec<&'a str> {
    text.split(start)
        .skip(1)
        .map(|s| {
            let body = &s[..s.find(end).expect("terminated")];
            &body[body.find(sep).expect("a payload") + 1..]
        })
        .collect()
}

#[test]
fn kitty_payload_is_the_rendered_image_pixel_for_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let text = String::from_utf8(view("kitty", dir.path())).unwrap();
    assert!(
        text.starts_with("\x1b_Ga=T,f=100,q=2,c=80,r=23,m=1;"),
        "{}",
        &text[..60]
    );
    let chunks = payloads(&text, "\x1b_G", ';', "\x1b\\");
    assert!(chunks.len() > 1);
    assert!(chunks[..chunks.len() - 1].iter().all(|c| c.len() == 4096));
    assert!(text.matches("m=0;").count() == 1);
    let png = STANDARD.decode(chunks.concat()).expect("base64");
    let shown = image::load_from_memory(&png).unwrap().to_rgb8();
    assert_eq!(shown.dimensions(), (800, 460));
    assert!(shown == rendered(800, 460, dir.path()), "pixels differ");
}

#[test]
fn iterm2_payload_is_the_rendered_image() {
    let dir = tempfile::tempdir().unwrap();
    let text = String::from_utf8(view("iterm2", dir.path())).unwrap();
    assert!(text.contains("width=80;height=23;preserveAspectRatio=1:"));
    let body = payloads(&text, "\x1b]1337;", ':', "\x07");
    assert_eq!(body.len(), 1);
    let png = STANDARD.decode(body[0]).expect("base64");
    let shown = image::load_from_memory(&png).unwrap().to_rgb8();
    assert!(shown == rendered(800, 460, dir.path()), "pixels differ");
}

/// A minimal sixel decoder: palette (`#i;2;r;g;b` in percent), colour choice, `$`, `-`, `!n`.
fn decode_sixel(data: &[u8]) -> image::RgbImage {
    let text = std::str::from_utf8(data).unwrap();
    let body = &text[text.find('q').unwrap() + 1..text.rfind("\x1b\\").unwrap()];
    let raster: Vec<u32> = body[1..body.find('#').unwrap()]
        .split(';')
        .map(|v| v.parse().unwrap())
        .collect();
    let mut img = image::RgbImage::new(raster[2], raster[3]);
    let mut palette = vec![[0u8; 3]; 256];
    let (mut x, mut top, mut colour) = (0u32, 0u32, 0usize);
    let bytes = body.as_bytes();
    let mut i = body.find('#').unwrap();
    let number = |i: &mut usize| -> u32 {
        let start = *i;
        while bytes[*i].is_ascii_digit() {
            *i += 1;
        }
        body[start..*i].parse().unwrap()
    };
    while i < bytes.len() {
        match bytes[i] {
            b'#' => {
                i += 1;
                colour = number(&mut i) as usize;
                if bytes.get(i) == Some(&b';') {
                    let mut v = [0u32; 4];
                    for slot in &mut v {
                        i += 1;
                        *slot = number(&mut i);
                    }
                    palette[colour] = [1, 2, 3].map(|k| ((v[k] * 255 + 50) / 100) as u8);
                }
            }
            b'$' => (x, i) = (0, i + 1),
            b'-' => (x, top, i) = (0, top + 6, i + 1),
            b'!' | b'?'..=b'~' => {
                let n = if bytes[i] == b'!' {
                    i += 1;
                    number(&mut i)
                } else {
                    1
                };
                let bits = bytes[i] - b'?';
                for _ in 0..n {
                    for dy in (0..6).filter(|dy| bits & (1 << dy) != 0) {
                        if x < img.width() && top + dy < img.height() {
                            img.put_pixel(x, top + dy, image::Rgb(palette[colour]));
                        }
                    }
                    x += 1;
                }
                i += 1;
            }
            other => panic!("unexpected sixel byte {other}"),
        }
    }
    img
}

fn psnr(a: &image::RgbImage, b: &image::RgbImage) -> f64 {
    let mse = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(&p, &q)| (f64::from(p) - f64::from(q)).powi(2))
        .sum::<f64>()
        / a.as_raw().len() as f64;
    10.0 * (255.0f64.powi(2) / mse.max(1e-9)).log10()
}

/// Quantization to 256 colours by median cut costs little: at least 30 dB PSNR.
#[test]
fn sixel_decodes_to_the_rendered_image_within_its_palette() {
    let dir = tempfile::tempdir().unwrap();
    let shown = decode_sixel(&view("sixel", dir.path()));
    assert_eq!(shown.dimensions(), (800, 460));
    let db = psnr(&shown, &rendered(800, 460, dir.path()));
    assert!(db >= 30.0, "PSNR {db:.1} dB");
    if let Ok(out) = std::env::var("RASTRAY_VIEW_SIXEL_PNG") {
        shown.save(out).unwrap();
    }
}

#[test]
fn plain_text_has_no_escape_and_fills_the_width() {
    let dir = tempfile::tempdir().unwrap();
    let text = String::from_utf8(view("plain", dir.path())).unwrap();
    assert!(!text.contains('\x1b'));
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 23);
    assert!(lines.iter().all(|l| l.len() <= 80));
    // The objects show as several shades of the ramp, not one flat fill.
    let shades: std::collections::HashSet<char> = text.chars().filter(|c| *c != '\n').collect();
    assert!(shades.len() >= 4, "{text}");
}

/// The sub-cells (2 columns × `rows` rows, bit `row * 2 + column`) that `glyph` fills, for the
/// glyphs of the half-block, quadrant and sextant sets, as Unicode defines them.
fn glyph_mask(glyph: char) -> (u32, u32) {
    const QUADRANTS: &str = " ▘▝▀▖▌▞▛▗▚▐▜▄▙▟█";
    if let Some(mask) = QUADRANTS.chars().position(|c| c == glyph) {
        return (2, mask as u32);
    }
    let code = glyph as u32;
    assert!(
        (0x1FB00..=0x1FB3B).contains(&code),
        "unexpected glyph {glyph:?}"
    );
    // Sextants count masks 1..=62 upward, leaving out 21 (left column) and 42 (right column).
    let mut mask = code - 0x1FB00 + 1;
    if mask >= 21 {
        mask += 1;
    }
    if mask >= 42 {
        mask += 1;
    }
    (3, mask)
}

/// A glyph with its foreground and background colours.
type TextCell = (char, [u8; 3], [u8; 3]);

/// Text cells decoded back into pixels: 6×12 a cell, each sub-cell in the foreground or the
/// background colour by its glyph.
fn decode_cells(text: &str) -> image::RgbImage {
    let lines: Vec<&str> = text.lines().collect();
    let mut cells: Vec<Vec<TextCell>> = Vec::new();
    for line in &lines {
        let (mut fg, mut bg) = ([255u8; 3], [0u8; 3]);
        let mut row = Vec::new();
        let mut rest = *line;
        while let Some(c) = rest.chars().next() {
            if c == '\x1b' {
                let end = rest.find('m').expect("SGR ends");
                let params: Vec<u8> = rest[2..end]
                    .split(';')
                    .filter_map(|p| p.parse().ok())
                    .collect();
                let mut i = 0;
                while i < params.len() {
                    if (params[i] == 38 || params[i] == 48) && params.get(i + 1) == Some(&2) {
                        let rgb = [params[i + 2], params[i + 3], params[i + 4]];
                        if params[i] == 38 {
                            fg = rgb
                        } else {
                            bg = rgb
                        }
                        i += 5;
                    } else {
                        i += 1;
                    }
                }
                rest = &rest[end + 1..];
            } else {
                row.push((c, fg, bg));
                rest = &rest[c.len_utf8()..];
            }
        }
        cells.push(row);
    }
    let (cols, rows) = (cells[0].len() as u32, cells.len() as u32);
    let mut img = image::RgbImage::new(cols * 6, rows * 12);
    for (y, row) in cells.iter().enumerate() {
        assert_eq!(row.len() as u32, cols, "every line has every cell");
        for (x, &(glyph, fg, bg)) in row.iter().enumerate() {
            let (grid_rows, mask) = glyph_mask(glyph);
            for py in 0..12 {
                for px in 0..6 {
                    let sub = (py / (12 / grid_rows)) * 2 + px / 3;
                    let c = if mask >> sub & 1 == 1 { fg } else { bg };
                    img.put_pixel(x as u32 * 6 + px, y as u32 * 12 + py, image::Rgb(c));
                }
            }
        }
    }
    img
}

/// Each cell set, decoded back into pixels, is close to a full render of the same framing, and
/// the finer sets are closer: sextants at least as close as quadrants, quadrants as half blocks.
#[test]
fn text_cells_decode_to_the_rendered_picture() {
    let dir = tempfile::tempdir().unwrap();
    let reference = rendered(480, 276, dir.path());
    let mut previous = 0.0;
    for set in ["halfblock", "quadrant", "sextant"] {
        let text = String::from_utf8(view(set, dir.path())).unwrap();
        assert!(text.lines().all(|l| l.ends_with("\x1b[0m")), "{set}");
        let shown = decode_cells(&text);
        assert_eq!(shown.dimensions(), (480, 276), "{set}: 80×23 cells");
        let db = psnr(&shown, &reference);
        assert!(db >= 30.0, "{set}: PSNR {db:.2} dB");
        assert!(
            db >= previous,
            "{set}: {db:.2} dB, below the coarser set's {previous:.2}"
        );
        previous = db;
    }
}
