//! `rastray info`: what a scene holds.

use super::stdout::outln;
use std::borrow::Cow;
use std::path::Path;

use glam::Vec3;
use rastray::mesh::{Measurements, MeshFile, instance_transform, measure};
use rastray::pool_thread::on_pool_thread;
use rastray::scene::Shape;
use rastray::text_escape::Escaped;
use rastray::world::{Detail, MeshFileCache, WorldObject};

/// One part's vertices placed in the world (borrowed from its world mesh, or placed anew for
/// an instance) and its triangles on them.
type PlacedPart<'a> = (Cow<'a, [Vec3]>, &'a [[u32; 3]]);

pub fn run(path: &Path, up: Option<rastray::scene::UpAxis>) -> anyhow::Result<()> {
    // Reading, building and measuring run on the pool, whose threads then share their
    // parallel steps.
    on_pool_thread(|| report(path, up))
}

/// The scene or model at `path` read, built and measured, and printed.
fn report(path: &Path, up: Option<rastray::scene::UpAxis>) -> anyhow::Result<()> {
    let mut cache = MeshFileCache::default();
    let (scene, base) = super::load_scene(Some(path), up, &mut cache)?;
    // Only what is printed is built: no normals, no texture coordinates.
    let report = super::build_world_with(&scene, &base, Some(path), &mut cache, Detail::Shape)?;
    let world = &report.world;
    super::print_warnings(&scene, world);
    outln!("{}", Escaped(&path.display().to_string()));
    let c = &scene.camera;
    // How much the view shows: its angle in perspective, its world height in orthographic.
    let extent = match (c.projection, c.height) {
        (rastray::scene::Projection::Orthographic, Some(height)) => {
            format!("orthographic  height {height}")
        }
        _ => format!("fov {}°", c.fov),
    };
    outln!(
        "camera   position {}  target {}  up {}  {extent}",
        fmt_vec(c.position),
        fmt_vec(c.target),
        fmt_vec(c.up),
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
    let mut measured = Vec::with_capacity(scene.objects.len());
    for (i, (object, parts)) in scene.objects.iter().zip(&parts_of).enumerate() {
        let triangles: usize = parts
            .iter()
            .map(|(b, _)| b.local_mesh().triangle_count())
            .sum();
        let model = match &object.shape {
            Shape::Mesh { path, .. } => cache.get(&base.join(path)).ok(),
            _ => None,
        };
        let file_parts = model.as_ref().map(|m| m.parts()).unwrap_or_default();
        // A model part is measured from its world mesh, the file's welded vertices placed (a
        // shape world's mesh: see `Detail::Shape`). A part shared by several instances is
        // measured once per instance, its file's vertices placed as the instance places them.
        let placed: Vec<PlacedPart> = match &model {
            Some(model) => {
                // The file's centre, which instances are placed about: a pass over its
                // vertices, taken only for a file that has instances.
                let centre = if file_parts.iter().any(|p| !p.instances.is_empty()) {
                    let (lo, hi) = model.bounds();
                    (lo + hi) * 0.5
                } else {
                    Vec3::ZERO
                };
                let mut built = parts.iter().map(|(b, _)| &b.mesh);
                file_parts
                    .iter()
                    .flat_map(|p| {
                        if p.instances.is_empty() {
                            let mesh = built.next();
                            return mesh
                                .map(|m| (Cow::from(&m.positions[..]), &m.triangles[..]))
                                .into_iter()
                                .collect();
                        }
                        built.nth(p.instances.len() - 1);
                        let triangles = &p.geometry.triangles[..];
                        p.instances
                            .iter()
                            .map(|instance| {
                                let to_world =
                                    instance_transform(object, centre, instance.transform);
                                let moved = p.geometry.positions.iter();
                                let moved = moved.map(|&q| to_world.transform_point3(q)).collect();
                                (Cow::Owned(moved), triangles)
                            })
                            .collect::<Vec<_>>()
                    })
                    .collect()
            }
            None => Vec::new(),
        };
        let meshes: Vec<(&[Vec3], &[[u32; 3]])> = if placed.is_empty() {
            parts
                .iter()
                .map(|(b, _)| (&b.mesh.positions[..], &b.mesh.triangles[..]))
                .collect()
        } else {
            placed.iter().map(|(p, t)| (&p[..], *t)).collect()
        };
        let world_measure = measure(&meshes);
        measured.push(world_measure);
        // A mesh object is measured in its file's units (its scale divided out); the scene's
        // total below is in world units.
        let m = match &object.shape {
            Shape::Mesh { scale, .. } => world_measure.unscaled(*scale),
            _ => world_measure,
        };
        outln!(
            "  [{i}] {:<12} {:<12} {:>9} triangles  area {:>10.3}  centre {}  {}{}",
            Escaped(object.label()),
            object.shape.kind().name(),
            triangles,
            m.area,
            fmt_vec(object.shape.center()),
            m.closure(),
            m.volume
                .map(|v| format!("  volume {v:.3}"))
                .unwrap_or_default()
        );
        outln!("        {}", measurements(&m));
        if let (Shape::Mesh { up, .. }, Some(model)) = (&object.shape, &model) {
            outln!("        {}, up {up}", Escaped(&describe(model)));
        }
        // The file part each world object came from: one object a part, or one an instance of
        // a part that several nodes place.
        let part_of_object: Vec<usize> = file_parts
            .iter()
            .enumerate()
            .flat_map(|(n, p)| std::iter::repeat_n(n, p.instances.len().max(1)))
            .collect();
        for (k, (built, label)) in parts.iter().enumerate() {
            if let Some(label) = label {
                let texture = part_of_object
                    .get(k)
                    .and_then(|&n| file_parts.get(n))
                    .and_then(|p| p.texture);
                let texture = texture.map(|(name, t)| {
                    let (w, h) = t.size();
                    format!("  texture {} {w}×{h}", Escaped(name))
                });
                outln!(
                    "        {}: {} triangles  colour {}{}{}",
                    Escaped(label),
                    built.local_mesh().triangle_count(),
                    fmt_vec(built.material.color),
                    if built.local_mesh().colors.is_some() {
                        "  vertex colours"
                    } else {
                        ""
                    },
                    texture.unwrap_or_default()
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
    let total = Measurements::total(&measured);
    outln!(
        "measure  (world units) area {:.3}  volume {}  {}",
        total.area,
        total
            .volume
            .map_or("(no closed object)".into(), |v| format!(
                "{v:.3} (closed objects)"
            )),
        measurements(&total)
    );
    // The process ends next, and exiting hands all its memory back at once: freeing the model
    // and the world array by array first took 7-11 ms of the 1.31M-triangle icosphere's
    // `info`, each array returned on its own while the pool's threads run.
    std::mem::forget(report);
    std::mem::forget(cache);
    Ok(())
}

/// What a model file is and holds beyond its triangles: `STL binary, no vertex colours, no
/// texture coordinates`, and how many of its parts have a material of the file's.
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
    let materials = model
        .parts()
        .iter()
        .filter(|p| p.material.is_some())
        .count();
    match materials {
        0 => {}
        1 => text += ", 1 part with a material of the file's",
        n => text += &format!(", {n} parts with materials of the file's"),
    }
    if let MeshFile::Ply(ply) = model
        && let Some(texture) = &ply.texture
    {
        text += &match &ply.appearance.base_color {
            Some(binding) => {
                let (w, h) = binding.texture.size();
                format!(", texture {texture} {w}×{h}")
            }
            None => format!(", texture {texture} (not read)"),
        };
    }
    text
}

/// Size and topology, as `size [1.000, 1.000, 1.000]  non-manifold edges 0  degenerate
/// triangles 0`.
fn measurements(m: &Measurements) -> String {
    let mut text = format!(
        "size {}  non-manifold edges {}  degenerate triangles {}",
        fmt_vec(m.size()),
        m.non_manifold_edges,
        m.degenerate_triangles
    );
    if m.misoriented_edges > 0 {
        text += &format!("  inconsistently wound edges {}", m.misoriented_edges);
    }
    text
}

fn fmt_vec(v: glam::Vec3) -> String {
    format!("[{:.3}, {:.3}, {:.3}]", v.x, v.y, v.z)
}
