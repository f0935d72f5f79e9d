//! What one `rastray render` writes, decided before anything renders: every input (sorted),
//! each as one image, one animation, or a turntable's frames, named by the output template,
//! cut to this run's shard. Whatever would go wrong for every file (a template that does not
//! tell inputs apart, two outputs on one path, a format the name does not allow, an output over
//! an input) is refused here, with exit code 2.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use anyhow::bail;
use rastray::export::{
    Destination, Field, FieldValues, ImageFormat, Output, OutputTemplate, Turntable,
};
use rastray::preset_view::PresetView;
use rastray::text_escape::Escaped;

use super::frames_arg::FrameRange;
use super::shard_arg::Shard;

/// What one output holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JobKind {
    /// One image from the scene's camera.
    Still,
    /// Frame `k` of the turntable, as a still image.
    Frame(u32),
    /// The whole turntable, as one animation.
    Animation,
}

/// One output file: which input, what of it, where and how it is written.
#[derive(Debug, Clone)]
pub struct Job {
    /// Position in [`Plan::inputs`].
    pub input: usize,
    /// The preset view it is drawn from, or `None` for the scene's camera.
    pub view: Option<PresetView>,
    pub kind: JobKind,
    pub destination: Destination,
    pub output: Output,
}

/// Every output of this run, in order: inputs sorted, then frames.
#[derive(Debug)]
pub struct Plan {
    /// The inputs in sorted order; `None` is the built-in default scene.
    pub inputs: Vec<Option<PathBuf>>,
    /// This shard's jobs.
    pub jobs: Vec<Job>,
    /// Several inputs: a failing one is reported and skipped rather than ending the run.
    pub batch: bool,
}

/// What the command line asked for.
#[derive(Debug)]
pub struct Request<'a> {
    pub inputs: &'a [PathBuf],
    pub template: &'a str,
    pub format: Option<ImageFormat>,
    pub turntable: Option<Turntable>,
    pub frames: Option<FrameRange>,
    pub shard: Option<Shard>,
    /// The algorithm's name, for `{algo}`.
    pub algo: &'a str,
    /// The preset views (`--view`), each written as its own output; empty for the scene's camera.
    pub views: &'a [PresetView],
}

impl Plan {
    /// The display name of input `i`: its path, or `default scene`.
    pub fn input_name(&self, i: usize) -> String {
        match &self.inputs[i] {
            Some(path) => Escaped(&path.display().to_string()).to_string(),
            None => "default scene".to_string(),
        }
    }
}

/// Plans the run `request` asks for, or says why none of it can be written.
pub fn plan(request: &Request) -> anyhow::Result<Plan> {
    let template = OutputTemplate::parse(request.template)?;
    let mut inputs: Vec<Option<PathBuf>> = request.inputs.iter().cloned().map(Some).collect();
    // Sorted, so that `{index}` and the shards do not depend on the order a shell or a job
    // runner lists the files in.
    inputs.sort();
    inputs.dedup();
    if inputs.is_empty() {
        inputs.push(None);
    }
    let batch = inputs.len() > 1;
    if batch && !template.tells_inputs_apart() {
        bail!(
            "{} inputs need an output template that tells them apart: put {{stem}}, {{name}} or {{index}} in -o, as -o 'out/{{stem}}.png' (given: `{}`)",
            inputs.len(),
            Escaped(request.template)
        );
    }
    if batch && inputs.iter().any(|i| i.as_deref() == Some(Path::new("-"))) {
        bail!("standard input (`-`) is read as the only input of a render");
    }
    if template.has(Field::View) && request.views.is_empty() {
        bail!("the output template's {{view}} field needs --view");
    }
    if request.views.len() > 1 && !template.has(Field::View) {
        bail!(
            "{} views need an output template with a {{view}} field (-o 'out-{{view}}.png'); without it, give one view",
            request.views.len()
        );
    }
    let views: Vec<Option<PresetView>> = match request.views {
        [] => vec![None],
        views => views.iter().copied().map(Some).collect(),
    };
    let frames = frame_numbers(&template, request)?;
    let mut all = Vec::new();
    for (i, input) in inputs.iter().enumerate() {
        let path = input.as_deref().unwrap_or(Path::new("default"));
        for &view in &views {
            let fill = |frame| {
                template.fill(&FieldValues {
                    input: path,
                    index: i,
                    view: view.map(PresetView::name),
                    algo: request.algo,
                    frame,
                })
            };
            match &frames {
                Some(frames) => all.extend(
                    frames
                        .clone()
                        .map(|k| (i, view, JobKind::Frame(k), fill(Some(k)))),
                ),
                None if request.turntable.is_some() => {
                    all.push((i, view, JobKind::Animation, fill(None)))
                }
                None => all.push((i, view, JobKind::Still, fill(None))),
            }
        }
    }
    refuse_repeats(&all, &inputs)?;
    let listed: Vec<PathBuf> = inputs.iter().flatten().cloned().collect();
    let range = match request.shard {
        Some(shard) => shard.range(all.len()),
        None => 0..all.len(),
    };
    let mut jobs = Vec::with_capacity(range.len());
    for (input, view, kind, path) in all.drain(range) {
        let destination = if path == Path::new("-") {
            Destination::Stdout
        } else {
            Destination::for_path(&path)?
        };
        // An input named as an output is refused before its name's extension is judged:
        // `-o scene.toml` is told it is the scene.
        destination.refuse_inputs(&listed)?;
        let turntable = match kind {
            JobKind::Animation => request.turntable,
            JobKind::Still | JobKind::Frame(_) => None,
        };
        let output = Output::for_destination(&destination, request.format, turntable)?;
        jobs.push(Job {
            input,
            view,
            kind,
            destination,
            output,
        });
    }
    Ok(Plan {
        inputs,
        jobs,
        batch,
    })
}

/// The turntable frames written as stills, when the template has `{frame}`: `--frames`, else
/// all of them. `None` when each input makes one file.
fn frame_numbers(
    template: &OutputTemplate,
    request: &Request,
) -> anyhow::Result<Option<std::ops::RangeInclusive<u32>>> {
    let has_frame = template.has(Field::Frame);
    match (request.turntable, has_frame, request.frames) {
        (None, true, _) => bail!("the output template's {{frame}} field needs --turntable N"),
        (None, false, Some(_)) => bail!("--frames needs --turntable N"),
        (Some(_), false, Some(_)) => bail!(
            "--frames writes each frame as an image: put {{frame}} in the output template, as -o 'frames/{{frame:04}}.png'"
        ),
        (Some(t), true, Some(range)) if range.last >= t.frames => bail!(
            "--frames {}..{}: the turntable has frames 0 to {}",
            range.first,
            range.last,
            t.frames - 1
        ),
        (Some(_), true, Some(range)) => Ok(Some(range.frames())),
        (Some(t), true, None) => Ok(Some(0..=t.frames - 1)),
        (_, false, None) => Ok(None),
    }
}

/// Refuses two outputs on one path (say two inputs with the same stem in two folders).
fn refuse_repeats(
    all: &[(usize, Option<PresetView>, JobKind, PathBuf)],
    inputs: &[Option<PathBuf>],
) -> anyhow::Result<()> {
    let name = |i: usize| {
        inputs[i]
            .as_deref()
            .map(|p| Escaped(&p.display().to_string()).to_string())
            .unwrap_or_else(|| "the default scene".to_string())
    };
    let mut seen: HashMap<&Path, usize> = HashMap::new();
    for (input, _, _, path) in all {
        if let Some(&before) = seen.get(path.as_path()) {
            bail!(
                "{}: the output template names this file for {} and again for {}; add {{index}} or {{name}} to tell them apart",
                Escaped(&path.display().to_string()),
                name(before),
                name(*input)
            );
        }
        seen.insert(path, *input);
    }
    Ok(())
}
