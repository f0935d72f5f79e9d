//! MTL material libraries, the files an OBJ names with `mtllib`: each `newmtl` block's `Kd`,
//! `Ks`, `Ns` and `map_Kd`, the statements rastray draws. Everything else (`Ka`, `Ke`, `d`,
//! `illum`, other maps) is read past.
//!
//! A library is read line by line and a line rastray cannot read is skipped with a note naming
//! it, so one odd statement never costs the rest of the file's materials. rastray reads MTL
//! itself rather than through `tobj`: `tobj::load_mtl_buf` 4.0.5 panics on `Kd 0.5` (one value,
//! which the MTL format allows for a grey), drops every material of a file at its first
//! unreadable line without saying which, and keeps `map_Kd` options such as `-s 1 1 1` in the
//! texture's name.

use std::collections::HashMap;

use glam::Vec3;

/// One `newmtl` block as written; absent statements are `None`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MtlMaterial {
    /// The name after `newmtl`, spaces kept.
    pub name: String,
    /// `Kd`: the diffuse colour, linear RGB as written (not clamped).
    pub diffuse: Option<Vec3>,
    /// `Ks`: the specular colour, linear RGB as written.
    pub specular: Option<Vec3>,
    /// `Ns`: the specular exponent as written.
    pub shininess: Option<f32>,
    /// `map_Kd`: the diffuse texture's file name, options removed, spaces and `\` kept.
    pub diffuse_map: Option<String>,
}

/// A line of a library that was skipped, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MtlNote {
    /// 1-based line number.
    pub line: usize,
    pub problem: &'static str,
}

/// The materials of an MTL file's `bytes`, in file order, and the lines skipped. A material
/// named twice keeps its later definition, in its first place. Never fails: a line that cannot be read is noted.
pub fn parse_mtl(bytes: &[u8]) -> (Vec<MtlMaterial>, Vec<MtlNote>) {
    let mut materials: Vec<MtlMaterial> = Vec::new();
    // Where each name is in `materials`, and the block being read.
    let mut places: HashMap<String, usize> = HashMap::new();
    let mut current = None;
    let mut notes = Vec::new();
    for (index, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let text = String::from_utf8_lossy(raw);
        let line = text.trim();
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let rest = line[keyword.len()..].trim();
        let mut note = |problem| {
            notes.push(MtlNote {
                line: index + 1,
                problem,
            })
        };
        if keyword == "newmtl" {
            if rest.is_empty() {
                note("`newmtl` without a name");
                continue;
            }
            let fresh = MtlMaterial {
                name: rest.to_string(),
                ..MtlMaterial::default()
            };
            let at = *places.entry(fresh.name.clone()).or_insert(materials.len());
            if at == materials.len() {
                materials.push(fresh);
            } else {
                materials[at] = fresh;
            }
            current = Some(at);
            continue;
        }
        let known = matches!(keyword, "Kd" | "Ks" | "Ns" | "map_Kd");
        let Some(material) = current.map(|at| &mut materials[at]) else {
            if known {
                note("a material statement before any `newmtl`");
            }
            continue;
        };
        match keyword {
            "Kd" | "Ks" => match color(rest) {
                Ok(c) if keyword == "Kd" => material.diffuse = Some(c),
                Ok(c) => material.specular = Some(c),
                Err(problem) => note(problem),
            },
            "Ns" => match single_number(rest) {
                Some(p) => material.shininess = Some(p),
                None => note("`Ns` takes one finite number"),
            },
            "map_Kd" => match texture_name(rest) {
                Some(name) => material.diffuse_map = Some(name.to_string()),
                None => note("`map_Kd` names no file"),
            },
            _ => {}
        }
    }
    (materials, notes)
}

/// A colour statement's value: `r g b`, or one number for a grey.
fn color(rest: &str) -> Result<Vec3, &'static str> {
    let words: Vec<&str> = rest.split_whitespace().collect();
    if matches!(words.first(), Some(&("spectral" | "xyz"))) {
        return Err("spectral and CIE XYZ colours are not read");
    }
    let numbers: Option<Vec<f32>> = words
        .iter()
        .map(|w| w.parse::<f32>().ok().filter(|x| x.is_finite()))
        .collect();
    match numbers.as_deref() {
        Some(&[grey]) => Ok(Vec3::splat(grey)),
        Some(&[r, g, b]) => Ok(Vec3::new(r, g, b)),
        _ => Err("a colour is `r g b` or one number, finite"),
    }
}

/// The one finite number `rest` holds.
fn single_number(rest: &str) -> Option<f32> {
    rest.parse::<f32>().ok().filter(|x| x.is_finite())
}

/// How many values each texture option takes; `-o`, `-s` and `-t` take one to three numbers.
fn option_arguments(option: &str) -> Option<(usize, usize)> {
    Some(match option {
        "-blendu" | "-blendv" | "-cc" | "-clamp" | "-bm" | "-boost" | "-texres" | "-imfchan"
        | "-type" => (1, 1),
        "-mm" => (2, 2),
        "-o" | "-s" | "-t" => (1, 3),
        _ => return None,
    })
}

/// The file name of a texture statement: the text after its options, spaces kept; `None` when
/// nothing is left.
fn texture_name(mut rest: &str) -> Option<&str> {
    loop {
        rest = rest.trim_start();
        let word = rest.split_whitespace().next()?;
        let Some((least, most)) = option_arguments(word) else {
            break;
        };
        rest = &rest[word.len()..];
        for taken in 0..most {
            let trimmed = rest.trim_start();
            let Some(value) = trimmed.split_whitespace().next() else {
                break;
            };
            // Past the required values, only numbers belong to the option.
            if taken >= least && value.parse::<f32>().is_err() {
                break;
            }
            rest = &trimmed[value.len()..];
        }
    }
    let name = rest.trim();
    (!name.is_empty()).then_some(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_exponents_and_textures_are_read_per_material() {
        let text = b"# Blender MTL\r\nnewmtl Wood Floor\r\nNs 250.0\r\nKa 1 1 1\r\n\
            Kd 0.8 0.5 0.2\r\nKs 0.5 0.5 0.5\r\nmap_Kd textures\\oak planks.jpg\r\n\
            newmtl grey\nKd 0.25\nillum 2\n";
        let (materials, notes) = parse_mtl(text);
        assert_eq!(notes, []);
        assert_eq!(
            materials,
            [
                MtlMaterial {
                    name: "Wood Floor".into(),
                    diffuse: Some(Vec3::new(0.8, 0.5, 0.2)),
                    specular: Some(Vec3::splat(0.5)),
                    shininess: Some(250.0),
                    diffuse_map: Some("textures\\oak planks.jpg".into()),
                },
                MtlMaterial {
                    name: "grey".into(),
                    diffuse: Some(Vec3::splat(0.25)),
                    ..MtlMaterial::default()
                },
            ]
        );
    }

    #[test]
    fn texture_options_are_removed_from_the_name() {
        for (rest, name) in [
            ("-s 1 1 1 wood.png", Some("wood.png")),
            ("-o 0.5 -s 2 -clamp on my wood.png", Some("my wood.png")),
            ("-mm 0 1 -bm 0.5 a.png", Some("a.png")),
            ("-blendu off", None),
            ("plain.jpg", Some("plain.jpg")),
            (".\\wood.jpg", Some(".\\wood.jpg")),
            ("-s 2 3.png", Some("3.png")),
        ] {
            assert_eq!(texture_name(rest), name, "{rest}");
        }
    }

    #[test]
    fn a_bad_line_is_noted_and_the_rest_still_reads() {
        let text = b"Kd 1 0 0\nnewmtl a\nKd 1 0\nKs spectral x.rfl\nNs lots\nmap_Kd\n\
            Kd 0 1 0\nnewmtl\nnewmtl a\nKd 0 0 1\n";
        let (materials, notes) = parse_mtl(text);
        let lines: Vec<usize> = notes.iter().map(|n| n.line).collect();
        assert_eq!(lines, [1, 3, 4, 5, 6, 8]);
        // `a` was defined twice: the later block wins.
        assert_eq!(materials.len(), 1);
        assert_eq!(materials[0].diffuse, Some(Vec3::new(0.0, 0.0, 1.0)));
    }

    #[test]
    fn non_finite_values_and_other_encodings_do_not_fail() {
        let (materials, notes) = parse_mtl(b"newmtl \xff\xfe\nKd nan 0 0\nNs inf\n");
        assert_eq!(materials.len(), 1);
        assert_eq!(materials[0].diffuse, None);
        assert_eq!(notes.len(), 2);
    }
}
