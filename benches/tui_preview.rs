//! The editor's preview path on the default scene in a 160×48-cell pane: render the 160×96
//! frame with a new `Renderer`, encode it, and draw the whole screen into a buffer. Terminal
//! output is not included (see docs for the key-to-screen figures measured in tmux).

use std::path::PathBuf;
use std::sync::Arc;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::scene::default_scene;
use rastray::terminal_image::preview::PreviewImage;
use rastray::tui::input::action::Action;
use rastray::tui::state::app::App;
use rastray::tui::update::apply;
use rastray::tui::worker::{RenderReply, Slot};
use ratatui::Terminal;
use ratatui::backend::TestBackend;

fn preview(c: &mut Criterion) {
    let scene = default_scene();
    let world = Arc::new(World::build(&scene, &PathBuf::from(".")).unwrap());
    // 196×52 cells leave a 160×48-cell preview inside the editor's layout.
    let mut terminal = Terminal::new(TestBackend::new(196, 52)).unwrap();
    let mut app = App::new(scene.clone(), None, PathBuf::from("."));
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong, Algorithm::Ray] {
        apply(&mut app, Action::Algorithm(algorithm));
        let options = RenderOptions::new(algorithm, 160, 96);
        c.bench_function(
            &format!("preview 160x48 cells {algorithm}: render+draw"),
            |b| {
                b.iter(|| {
                    let mut frame = Frame::default();
                    Renderer::new(options)
                        .render(&world, &scene.camera, &Progress::new(), &mut frame)
                        .unwrap();
                    let shot = RenderReply::Shot {
                        id: 1,
                        slot: Slot::Main,
                        image: PreviewImage::from_frame(&frame),
                        millis: 0.0,
                        triangles: world.triangle_count(),
                        last: true,
                    };
                    apply(&mut app, Action::Rendered(Box::new(shot)));
                    terminal.draw(|f| f.render_widget(&app, f.area())).unwrap();
                })
            },
        );
    }
}

criterion_group!(benches, preview);
criterion_main!(benches);
