//! `rastray info`: what a scene holds.

use super::stdout::outln;
use std::path::Path;

use rastray::scene::ShapeKind;
use rastray::text_escape::Escaped;
use rastray::world::WorldObject;

pub fn run(path: &Path) -> anyhow::Result<()> {
    let (scene, base) = super::load_scene(Some(path))?;
    let report = super::build_world(&scene, &base)?;
    let world = &report.world;
    super::print_warnings(&scene, world);
    outln!("{}", Escaped(&path.display().to_string()));
    let c = &scene.camera;
    outln!(
        "camera   position {}  target {}  up {}  fov {}°",
        fmt_vec(c.position),
        fmt_vec(c.target),
        fmt_vec(c.up),
        c.fov
    );
    outln!(
        "ambient  {}   background {}   max_depth {}",
        scene.ambient,
        fmt_vec(scene.background),
        scene.max_depth
    );
    outln!("objects  {}", scene.objects.len());
    // The world objects each scene object became: one, or one per glTF primitive (grouped in one
    // pass, so that info stays linear in the number of objects).
    let mut parts_of: Vec<Vec<(&WorldObject, Option<&str>)>> =
        vec![Vec::new(); scene.objects.len()];
    for (built, source) in world.objects.iter().zip(&report.sources) {
        if let Some(parts) = parts_of.get_mut(source.object) {
            parts.push((built, source.part.as_deref()));
        }
    }
    for (i, (object, parts)) in scene.objects.iter().zip(&parts_of).enumerate() {
        let triangles: usize = parts.iter().map(|(b, _)| b.mesh.triangle_count()).sum();
        let area: f32 = parts.iter().map(|(b, _)| b.mesh.surface_area()).sum();
        outln!(
            "  [{i}] {:<12} {:<12} {:>9} triangles  area {:>10.3}  centre {}",
            Escaped(object.label()),
            object.shape.kind().name(),
            triangles,
            area,
            fmt_vec(object.shape.center())
        );
        if object.shape.kind() == ShapeKind::Mesh {
            let colored = parts
                .iter()
                .filter(|(b, _)| b.mesh.colors.is_some())
                .count();
            outln!(
                "        vertex colours: {}",
                vertex_colours(colored, parts.len())
            );
        }
        for (built, label) in parts {
            if let Some(label) = label {
                outln!(
                    "        {}: {} triangles  colour {}{}",
                    Escaped(label),
                    built.mesh.triangle_count(),
                    fmt_vec(built.material.color),
                    if built.mesh.colors.is_some() {
                        "  vertex colours"
                    } else {
                        ""
                    }
                );
            }
        }
    }
    outln!("lights   {}", scene.lights.len());
    for (i, light) in scene.lights.iter().enumerate() {
        outln!(
            "  [{i}] {:<12} position {}  intensity {}  colour {}",
            Escaped(light.name.as_deref().unwrap_or("light")),
            fmt_vec(light.position),
            light.intensity,
            fmt_vec(light.color)
        );
    }
    outln!("triangles {}", world.triangle_count());
    match world.bounds() {
        Some((lo, hi)) => outln!(
            "bounds   min {}  max {}  size {}",
            fmt_vec(lo),
            fmt_vec(hi),
            fmt_vec(hi - lo)
        ),
        None => outln!("bounds   (empty scene)"),
    }
    Ok(())
}

/// Whether a model's `parts` have vertex colours, `colored` of them do: "yes", "none", or how
/// many parts have them.
fn vertex_colours(colored: usize, parts: usize) -> String {
    match colored {
        0 => "none".to_string(),
        _ if colored == parts => "yes".to_string(),
        _ => format!("{colored} of {parts} parts"),
    }
}

fn fmt_vec(v: glam::Vec3) -> String {
    format!("[{:.3}, {:.3}, {:.3}]", v.x, v.y, v.z)
}
