//! `rastray info`: what a scene holds.

use super::stdout::outln;
use std::path::Path;

use rastray::mesh::MeshFile;
use rastray::scene::Shape;
use rastray::text_escape::Escaped;
use rastray::world::{MeshFileCache, WorldObject};

pub fn run(path: &Path, up: Option<rastray::scene::UpAxis>) -> anyhow::Result<()> {
    let (scene, base) = super::load_scene(Some(path), up)?;
    let mut cache = MeshFileCache::default();
    let report = super::build_world_cached(&scene, &base, &mut cache)?;
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
        if let Shape::Mesh { path, up, .. } = &object.shape
            && let Ok(model) = cache.get(&base.join(path))
        {
            outln!("        {}, up {up}", Escaped(&describe(&model)));
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

/// What a model file is and holds beyond its triangles: `STL binary, no vertex colours, no
/// texture coordinates`.
fn describe(model: &MeshFile) -> String {
    let geometries = model.geometries();
    let colours = geometries.iter().any(|g| g.colors.is_some());
    let uvs = geometries.iter().any(|g| g.corner_uvs.is_some());
    let has = |yes: bool, what: &str| {
        if yes {
            what.to_string()
        } else {
            format!("no {what}")
        }
    };
    let mut text = format!(
        "{}, {}, {}",
        model.format(),
        has(colours, "vertex colours"),
        has(uvs, "texture coordinates")
    );
    if let MeshFile::Ply(ply) = model
        && let Some(texture) = &ply.texture
    {
        text += &format!(", texture {texture} (not drawn)");
    }
    text
}

fn fmt_vec(v: glam::Vec3) -> String {
    format!("[{:.3}, {:.3}, {:.3}]", v.x, v.y, v.z)
}
