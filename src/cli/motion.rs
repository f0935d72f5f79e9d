//! `rastray view --spin` and `--watch`: the picture drawn again and again in place, a
//! turntable turning or the scene redrawn when its files change, until a key or Ctrl-C.
//!
//! On a terminal the keyboard is read raw (Ctrl-C arrives as a key) and frames are paced as
//! the editor paces them ([`Pacer`]): after each frame a cursor-position query, and no new frame
//! until the terminal has answered, so that a slow link never queues stale frames. The terminal
//! is put back (cursor shown, raw mode off) on every way out, the guard's drop included.
//! Elsewhere (a pipe, a file) the frames are written one after another.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant, SystemTime};

use anyhow::Context;
use clap::Args;
use rastray::World;
use rastray::export::Turntable;
use rastray::render::{Frame, Progress, RenderOptions, Renderer};
use rastray::scene::Camera;
use rastray::terminal_image::preview::PreviewImage;
use rastray::terminal_image::{CellArea, Protocol, kitty};
use rastray::tui::terminal::pacer::{self, Pacer};
use rastray::tui::terminal::term_input::{Reply, TermInput};
use ratatui::crossterm::event::{Event, KeyCode, KeyEventKind, KeyModifiers};
use signal_hook::consts::{SIGINT, SIGTERM};

/// Shortest time between two frames: at most 30 frames a second.
const FRAME_INTERVAL: Duration = Duration::from_millis(33);
/// How often `--watch` looks at the files' modification times.
const WATCH_INTERVAL: Duration = Duration::from_millis(250);

#[derive(Debug, Args)]
pub struct MotionArgs {
    /// Play a turntable in the terminal, about the camera's up vector, until a key or Ctrl-C.
    #[arg(long)]
    pub spin: bool,
    /// --spin: frames per turn (1 to 3600).
    #[arg(long, value_name = "N", default_value_t = 72, requires = "spin",
          value_parser = clap::value_parser!(u32).range(1..=3600))]
    pub frames: u32,
    /// --spin: stop after K turns.
    #[arg(long, value_name = "K", requires = "spin",
          value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub loops: Option<u32>,
    /// Draw again whenever the scene file or its model files change on disk, until a key or
    /// Ctrl-C.
    #[arg(long)]
    pub watch: bool,
}

impl MotionArgs {
    /// Whether the picture is drawn more than once.
    pub fn active(&self) -> bool {
        self.spin || self.watch
    }
}

/// What the view draws and how: the scene's world and camera, and the files it was read from.
pub struct Shown {
    pub world: Arc<World>,
    pub camera: Camera,
    /// The scene file and the model files it loaded, watched by `--watch`.
    pub inputs: Vec<PathBuf>,
}

/// How each frame becomes bytes: the protocol, the cell area and the render settings.
pub struct Picture {
    pub protocol: Protocol,
    pub area: CellArea,
    pub options: RenderOptions,
}

/// Plays `motion` of what `load` gives (called again when a watched file changes), drawn as
/// `picture`, until a key, Ctrl-C, SIGTERM or the last of `--loops` turns. Ends with exit code
/// 0 after a key or the last turn, and 128 + the signal's number after SIGINT or SIGTERM (Ctrl-C
/// typed on a raw terminal counts as SIGINT), as a shell expects of an interrupted command.
pub fn play(
    motion: &MotionArgs,
    picture: &Picture,
    mut load: impl FnMut() -> anyhow::Result<Shown>,
) -> anyhow::Result<ExitCode> {
    let interactive = std::io::stdin().is_terminal() && std::io::stdout().is_terminal();
    let stop = Arc::new(AtomicBool::new(false));
    // The number of the signal that stopped the motion, 0 while none has.
    let signalled = Arc::new(AtomicUsize::new(0));
    for number in [SIGINT, SIGTERM] {
        signal_hook::flag::register_usize(number, Arc::clone(&signalled), number as usize)?;
    }
    let (send, input) = mpsc::channel();
    let mut screen = Screen::new(interactive, picture.area.rows)?;
    if interactive {
        rastray::tui::terminal::tty_input::spawn(move |i| send.send(i).is_ok())?;
    }
    let mut pacer = if interactive {
        Pacer::new()
    } else {
        Pacer::unpaced()
    };
    let mut shown = load()?;
    let mut stamps = modified(&shown.inputs);
    let mut renderer = Renderer::new(picture.options);
    let mut frame = Frame::default();
    let turntable = Turntable {
        frames: motion.frames,
        fps: 30,
    };
    let last = motion
        .loops
        .map(|loops| u64::from(loops) * u64::from(motion.frames));
    let (mut drawn, mut dirty) = (0_u64, true);
    let (mut next_frame, mut next_check) = (Instant::now(), Instant::now() + WATCH_INTERVAL);
    loop {
        while let Ok(event) = input.try_recv() {
            handle(event, &stop, &signalled, &mut pacer);
        }
        let now = Instant::now();
        if stop.load(Ordering::Relaxed)
            || signalled.load(Ordering::Relaxed) != 0
            || last.is_some_and(|last| drawn >= last)
        {
            break;
        }
        if motion.watch && now >= next_check {
            next_check = now + WATCH_INTERVAL;
            let now_stamps = modified(&shown.inputs);
            if now_stamps != stamps {
                stamps = now_stamps;
                // A file caught half written fails to load: the last picture stays, and the
                // next change is tried again.
                if let Ok(fresh) = load() {
                    shown = fresh;
                    stamps = modified(&shown.inputs);
                    dirty = true;
                }
            }
        }
        if (motion.spin || dirty) && now >= next_frame && pacer.may_draw(now) {
            let camera = if motion.spin {
                turntable.camera(&shown.camera, (drawn % u64::from(motion.frames)) as u32)
            } else {
                shown.camera
            };
            renderer.render(&shown.world, &camera, &Progress::new(), &mut frame)?;
            let bytes = encode(picture, &PreviewImage::from_frame(&frame), interactive)?;
            screen.draw(&bytes, picture.protocol.has_pixels())?;
            if interactive && pacer.should_ask() {
                screen.write(pacer::QUERY)?;
                pacer.carrying(bytes.len());
                pacer.asked(now, false, bytes.len() as u64);
            } else {
                pacer.drew(false);
            }
            (drawn, dirty, next_frame) = (drawn + 1, false, now + FRAME_INTERVAL);
        }
        let wake = [Some(next_frame), pacer.wake_at(), Some(next_check)]
            .into_iter()
            .flatten()
            .min()
            .unwrap_or(now)
            .max(Instant::now() + Duration::from_millis(2));
        if let Ok(event) = input.recv_timeout(wake - Instant::now()) {
            handle(event, &stop, &signalled, &mut pacer);
        }
    }
    if interactive && pacer.awaiting() {
        // Answers still on their way would reach the shell as typed text.
        std::thread::sleep(pacer::LAST_ANSWER);
    }
    screen.finish()?;
    Ok(match signalled.load(Ordering::Relaxed) {
        0 => ExitCode::SUCCESS,
        number => {
            eprintln!("stopped by {}", super::batch_run::signal_name(number));
            ExitCode::from(128 + number as u8)
        }
    })
}

/// The id of the picture a kitty terminal replaces frame after frame.
const KITTY_IMAGE_ID: u32 = 7_390_001;

/// The bytes of one frame. On a kitty terminal each frame replaces the last as the same image
/// (one image id, the cursor left in place), so that the terminal does not keep them all.
fn encode(picture: &Picture, image: &PreviewImage, terminal: bool) -> anyhow::Result<Vec<u8>> {
    let bytes = if terminal && picture.protocol == Protocol::Kitty {
        kitty::encode_pieces(image, picture.area, Some(KITTY_IMAGE_ID)).map(|p| p.concat())
    } else {
        picture.protocol.encode(image, picture.area)
    };
    bytes.context("cannot encode the picture")
}

/// One input: Ctrl-C stops as SIGINT would, another key stops, an answer notes the frame
/// drawn.
fn handle(event: TermInput, stop: &AtomicBool, signalled: &AtomicUsize, pacer: &mut Pacer) {
    match event {
        TermInput::Event(Event::Key(key)) if key.kind != KeyEventKind::Release => {
            let ctrl_c = key.code == KeyCode::Char('c') && key.modifiers == KeyModifiers::CONTROL;
            if ctrl_c {
                signalled.store(SIGINT as usize, Ordering::Relaxed);
            }
            stop.store(true, Ordering::Relaxed);
        }
        TermInput::Reply(Reply::CursorPosition { .. }) => pacer.answered(Instant::now()),
        _ => {}
    }
}

/// The modification time of each file (`None` for one that cannot be read now).
fn modified(files: &[PathBuf]) -> Vec<Option<SystemTime>> {
    files
        .iter()
        .map(|f| std::fs::metadata(f).and_then(|m| m.modified()).ok())
        .collect()
}

/// Standard output as the frames' place: on a terminal, a block of `rows` lines kept for the
/// picture, each frame drawn from its top corner, raw input on and the cursor hidden until
/// [`Screen::finish`] or drop.
struct Screen {
    out: std::io::Stdout,
    terminal: bool,
    rows: u32,
    started: bool,
    raw: bool,
}

impl Screen {
    fn new(terminal: bool, rows: u32) -> anyhow::Result<Screen> {
        let mut screen = Screen {
            out: std::io::stdout(),
            terminal,
            rows,
            started: false,
            raw: false,
        };
        if terminal {
            ratatui::crossterm::terminal::enable_raw_mode()?;
            screen.raw = true;
            // Hide the cursor.
            screen.write(b"\x1b[?25l")?;
        }
        Ok(screen)
    }

    fn write(&mut self, bytes: &[u8]) -> anyhow::Result<()> {
        self.out.write_all(bytes)?;
        self.out.flush()?;
        Ok(())
    }

    /// Draws one frame's `bytes` over the last (pictures in pixels end with a new line).
    fn draw(&mut self, bytes: &[u8], pixels: bool) -> anyhow::Result<()> {
        let mut all = Vec::with_capacity(bytes.len() + 64);
        if self.terminal {
            if !self.started {
                // Room below for the whole picture, so that drawing never scrolls and the
                // saved corner stays where it is.
                all.extend(b"\r\n".repeat(self.rows as usize));
                all.extend(format!("\x1b[{}A\x1b7", self.rows).as_bytes());
            }
            // Back to the picture's corner, inside one synchronized update.
            all.extend(b"\x1b[?2026h\x1b8");
        }
        all.extend(bytes);
        if self.terminal {
            all.extend(b"\x1b[?2026l");
        } else if pixels {
            all.extend(b"\n");
        }
        self.started = true;
        self.write(&all)
    }

    /// Leaves the cursor below the picture, shown, and the keyboard cooked.
    fn finish(mut self) -> anyhow::Result<()> {
        self.restore();
        Ok(())
    }

    fn restore(&mut self) {
        if !self.raw {
            return;
        }
        self.raw = false;
        let below = if self.started {
            format!("\x1b8\x1b[{}B\r\n", self.rows)
        } else {
            String::new()
        };
        let _ = self.out.write_all(format!("{below}\x1b[?25h").as_bytes());
        let _ = self.out.flush();
        let _ = ratatui::crossterm::terminal::disable_raw_mode();
    }
}

impl Drop for Screen {
    fn drop(&mut self) {
        self.restore();
    }
}
