//! The config file: defaults for the flags a user always types. It lives at `$RASTRAY_CONFIG`,
//! else `$XDG_CONFIG_HOME/rastray/config.toml`, else `~/.config/rastray/config.toml`; a missing
//! file sets nothing. A flag on the command line always wins; `--no-config` reads no file.
//!
//! ```toml
//! algorithm = "ray"      # gouraud, phong, ray
//! size = "1280x720"
//! samples = 2            # 1 to 8
//! graphics = "halfblock" # as --graphics
//! color = "256"          # truecolor, 256
//! up = "z"               # x, y, z, -x, -y, -z
//! threads = 4
//! ```

use std::fmt::Write;
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};

use clap::ValueEnum;
use rastray::input_file::{MAX_SCENE_BYTES, read_bounded_text};
use rastray::render::{MAX_SAMPLES, MAX_THREADS, Size};
use rastray::scene::UpAxis;
use rastray::text_escape::Escaped;

use super::ColorArg;
use super::algorithm_arg::AlgorithmArg;
use super::graphics_arg::GraphicsArg;

/// The keys a config file may set, in the order `rastray config` prints them.
const KEYS: [&str; 7] = [
    "algorithm",
    "size",
    "samples",
    "graphics",
    "color",
    "up",
    "threads",
];

/// Defaults read from the config file; `None` where it sets nothing.
#[derive(Debug, Default, Clone)]
pub struct Defaults {
    pub algorithm: Option<AlgorithmArg>,
    pub size: Option<Size>,
    pub samples: Option<u32>,
    pub graphics: Option<GraphicsArg>,
    pub color: Option<ColorArg>,
    pub up: Option<UpAxis>,
    pub threads: Option<NonZeroUsize>,
}

/// Where the config file is looked for, and why there.
#[derive(Debug, Clone)]
pub struct Location {
    pub path: PathBuf,
    /// The variable that chose it: `RASTRAY_CONFIG`, `XDG_CONFIG_HOME` or `HOME`.
    pub from: &'static str,
}

/// The config file's place, from the environment read through `var`; `None` when no variable
/// names one (no `HOME` either).
pub fn location(var: impl Fn(&str) -> Option<String>) -> Option<Location> {
    let set = |name: &str| var(name).filter(|v| !v.is_empty());
    if let Some(path) = set("RASTRAY_CONFIG") {
        return Some(Location {
            path: PathBuf::from(path),
            from: "RASTRAY_CONFIG",
        });
    }
    if let Some(home) = set("XDG_CONFIG_HOME") {
        return Some(Location {
            path: Path::new(&home).join("rastray/config.toml"),
            from: "XDG_CONFIG_HOME",
        });
    }
    set("HOME").map(|home| Location {
        path: Path::new(&home).join(".config/rastray/config.toml"),
        from: "HOME",
    })
}

/// The defaults of the file at `location`: none when there is no file.
pub fn load(location: Option<&Location>) -> anyhow::Result<Defaults> {
    let Some(location) = location else {
        return Ok(Defaults::default());
    };
    if !location.path.exists() {
        return Ok(Defaults::default());
    }
    let text = read_bounded_text(&location.path, MAX_SCENE_BYTES, "a config file")
        .map_err(|e| anyhow::anyhow!("{}: {e}", shown(&location.path)))?;
    parse(&text, &location.path)
}

/// The defaults `text`, the file at `path`, sets; an error names the file, the line and the key.
pub fn parse(text: &str, path: &Path) -> anyhow::Result<Defaults> {
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].lines().count().max(1))
            .unwrap_or(1);
        anyhow::anyhow!("{}:{line}: {}", shown(path), e.message())
    })?;
    let mut defaults = Defaults::default();
    for (key, value) in &table {
        let line = line_of(text, key);
        let refuse = |why: String| anyhow::anyhow!("{}:{line}: key `{key}`: {why}", shown(path));
        let string = || {
            value
                .as_str()
                .ok_or_else(|| refuse(format!("expected a string, found {}", value.type_str())))
        };
        let integer = |range: std::ops::RangeInclusive<i64>| {
            value
                .as_integer()
                .filter(|n| range.contains(n))
                .ok_or_else(|| {
                    refuse(format!(
                        "expected a whole number from {} to {}, found {value}",
                        range.start(),
                        range.end()
                    ))
                })
        };
        match key.as_str() {
            "algorithm" => defaults.algorithm = Some(choice(string()?).map_err(refuse)?),
            "graphics" => defaults.graphics = Some(choice(string()?).map_err(refuse)?),
            "color" => defaults.color = Some(choice(string()?).map_err(refuse)?),
            "size" => defaults.size = Some(super::parse_size(string()?).map_err(refuse)?),
            "up" => defaults.up = Some(super::up_arg::parse_up(string()?).map_err(refuse)?),
            "samples" => defaults.samples = Some(integer(1..=i64::from(MAX_SAMPLES))? as u32),
            "threads" => {
                defaults.threads = NonZeroUsize::new(integer(1..=MAX_THREADS as i64)? as usize);
            }
            _ => {
                return Err(refuse(format!(
                    "unknown key; a config file sets {}",
                    KEYS.join(", ")
                )));
            }
        }
    }
    Ok(defaults)
}

/// A value of a clap value enum, spelled as on the command line.
fn choice<T: ValueEnum>(s: &str) -> Result<T, String> {
    T::from_str(s, true).map_err(|_| {
        let names: Vec<String> = T::value_variants()
            .iter()
            .filter_map(|v| v.to_possible_value())
            .map(|v| v.get_name().to_string())
            .collect();
        format!("`{s}` is not one of {}", names.join(", "))
    })
}

/// The line (from 1) where `key` is set: the first line that starts with it, bare or quoted.
fn line_of(text: &str, key: &str) -> usize {
    text.lines()
        .position(|l| {
            let l = l.trim_start();
            let rest = l
                .strip_prefix(key)
                .or_else(|| l.strip_prefix(&format!("\"{key}\"")));
            rest.is_some_and(|r| r.trim_start().starts_with('='))
        })
        .map_or(1, |i| i + 1)
}

fn shown(path: &Path) -> String {
    Escaped(&path.display().to_string()).to_string()
}

/// What `rastray config` prints: the file in use and the values it sets.
pub fn describe(location: Option<&Location>, no_config: bool) -> anyhow::Result<String> {
    let mut out = String::new();
    let Some(location) = location.filter(|_| !no_config) else {
        let why = if no_config {
            "--no-config"
        } else {
            "neither RASTRAY_CONFIG, XDG_CONFIG_HOME nor HOME is set"
        };
        let _ = writeln!(out, "no config file read ({why}); built-in defaults");
        return Ok(out);
    };
    let path = shown(&location.path);
    if !location.path.exists() {
        let _ = writeln!(
            out,
            "no config file at {path} (from {}); built-in defaults",
            location.from
        );
        return Ok(out);
    }
    let defaults = load(Some(location))?;
    let _ = writeln!(out, "config file: {path} (from {})", location.from);
    let name = |v: Option<Option<clap::builder::PossibleValue>>| {
        v.flatten().map(|v| format!("\"{}\"", v.get_name()))
    };
    let values = [
        name(defaults.algorithm.map(|a| a.to_possible_value())),
        defaults.size.map(|s| format!("\"{s}\"")),
        defaults.samples.map(|n| n.to_string()),
        name(defaults.graphics.map(|g| g.to_possible_value())),
        name(defaults.color.map(|c| c.to_possible_value())),
        defaults.up.map(|u| format!("\"{}\"", u.name())),
        defaults.threads.map(|n| n.to_string()),
    ];
    let mut any = false;
    for (key, value) in KEYS.iter().zip(values) {
        if let Some(value) = value {
            let _ = writeln!(out, "{key} = {value}");
            any = true;
        }
    }
    if !any {
        let _ = writeln!(out, "(it sets nothing)");
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rastray::Algorithm;

    #[test]
    fn every_key_is_read() {
        let text = "algorithm = \"ray\"\nsize = \"64x32\"\nsamples = 2\ngraphics = \"halfblock\"\ncolor = \"256\"\nup = \"-z\"\nthreads = 3\n";
        let d = parse(text, Path::new("c.toml")).unwrap();
        assert_eq!(d.algorithm, Some(AlgorithmArg(Algorithm::Ray)));
        assert_eq!(d.size.map(|s| (s.width, s.height)), Some((64, 32)));
        assert_eq!(d.samples, Some(2));
        assert_eq!(d.graphics, Some(GraphicsArg::Halfblock));
        assert_eq!(d.color, Some(ColorArg::Ansi256));
        assert_eq!(d.up, Some(UpAxis::NegZ));
        assert_eq!(d.threads, NonZeroUsize::new(3));
    }

    #[test]
    fn errors_name_the_file_line_and_key() {
        let err = |text: &str| parse(text, Path::new("c.toml")).unwrap_err().to_string();
        let unknown = err("size = \"8x8\"\n\nalgoritm = \"ray\"\n");
        assert!(unknown.starts_with("c.toml:3: key `algoritm`"), "{unknown}");
        let bad = err("samples = 9\n");
        assert!(
            bad.starts_with("c.toml:1: key `samples`") && bad.contains("1 to 8"),
            "{bad}"
        );
        let bad = err("# defaults\nalgorithm = \"fast\"\n");
        assert!(
            bad.contains("c.toml:2: key `algorithm`") && bad.contains("gouraud"),
            "{bad}"
        );
        let bad = err("up = 3\n");
        assert!(bad.contains("expected a string"), "{bad}");
        let syntax = err("size = \n");
        assert!(syntax.starts_with("c.toml:1:"), "{syntax}");
    }

    #[test]
    fn the_file_is_looked_for_where_the_environment_says() {
        let env = |pairs: &'static [(&'static str, &'static str)]| {
            move |k: &str| pairs.iter().find(|p| p.0 == k).map(|p| p.1.to_string())
        };
        let at = |pairs| location(env(pairs)).map(|l| (l.path, l.from));
        assert_eq!(
            at(&[("RASTRAY_CONFIG", "/a.toml"), ("HOME", "/h")]),
            Some((PathBuf::from("/a.toml"), "RASTRAY_CONFIG"))
        );
        assert_eq!(
            at(&[("XDG_CONFIG_HOME", "/x"), ("HOME", "/h")]),
            Some((PathBuf::from("/x/rastray/config.toml"), "XDG_CONFIG_HOME"))
        );
        assert_eq!(
            at(&[("XDG_CONFIG_HOME", ""), ("HOME", "/h")]),
            Some((PathBuf::from("/h/.config/rastray/config.toml"), "HOME"))
        );
        assert_eq!(at(&[]), None);
    }
}
