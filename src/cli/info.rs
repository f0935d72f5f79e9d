//! `rastray info`: what a scene holds.

use std::path::Path;

use rastray::World;

pub fn run(path: &Path) -> anyhow::Result<()> {
    let (scene, base) = super::load_scene(Some(path))?;
    let world = World::build(&scene, &base)?;
    super::print_warnings(&scene, &world);
    println!("{}", path.display());
    let c = &scene.camera;
    println!(
        "camera   position {}  target {}  up {}  fov {}°",
        fmt_vec(c.position),
        fmt_vec(c.target),
        fmt_vec(c.up),
        c.fov
    );
    println!(
        "ambient  {}   background {}   max_depth {}",
        scene.ambient,
        fmt_vec(scene.background),
        scene.max_depth
    );
    println!("objects  {}", scene.objects.len());
    for (i, (object, built)) in scene.objects.iter().zip(&world.objects).enumerate() {
        println!(
            "  [{i}] {:<12} {:<12} {:>9} triangles  area {:>10.3}  centre {}",
            object.label(),
            object.shape.kind().name(),
            built.mesh.triangle_count(),
            built.mesh.surface_area(),
            fmt_vec(object.shape.center())
        );
    }
    println!("lights   {}", scene.lights.len());
    for (i, light) in scene.lights.iter().enumerate() {
        println!(
            "  [{i}] {:<12} position {}  intensity {}  colour {}",
            light.name.as_deref().unwrap_or("light"),
            fmt_vec(light.position),
            light.intensity,
            fmt_vec(light.color)
        );
    }
    println!("triangles {}", world.triangle_count());
    match world.bounds() {
        Some((lo, hi)) => println!(
            "bounds   min {}  max {}  size {}",
            fmt_vec(lo),
            fmt_vec(hi),
            fmt_vec(hi - lo)
        ),
        None => println!("bounds   (empty scene)"),
    }
    Ok(())
}

fn fmt_vec(v: glam::Vec3) -> String {
    format!("[{:.3}, {:.3}, {:.3}]", v.x, v.y, v.z)
}
