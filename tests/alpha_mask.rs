//! glTF `alphaMode: MASK` in all three algorithms: texels whose alpha is below the cutoff are
//! no surface. A quad whose texture's alpha is a checker shows the background through its
//! cut-out squares in every algorithm, Phong and the ray tracer agree on a cut-out quad before
//! a box, and a cut-out caster lets light through where its alpha is 0. Vertex colours' alpha
//! (`COLOR_0`) multiplies in, interpolated over each triangle.

mod common;

use common::textured_quad::{
    png_bytes, quad_gltf, render, scene_of, vertex_alpha_quad_gltf, write,
};
use rastray::render::Algorithm;

const ALGORITHMS: [Algorithm; 3] = [Algorithm::Gouraud, Algorithm::Phong, Algorithm::Ray];

/// Side of the texture and of the known-answer renders, pixels.
const SIDE: u32 = 64;
/// Side of the checker's squares, texels.
const SQUARE: u32 = 8;

/// Whether texel (x, y) of the checker is opaque (alpha 1); the others have alpha 0.
fn opaque(x: u32, y: u32) -> bool {
    (x / SQUARE + y / SQUARE).is_multiple_of(2)
}

/// An RGBA image: a red gradient left to right over green, alpha a checker of 8-texel squares.
fn checker_alpha() -> image::RgbaImage {
    image::RgbaImage::from_fn(SIDE, SIDE, |x, y| {
        let alpha = if opaque(x, y) { 255 } else { 0 };
        image::Rgba([(60 + 3 * x) as u8, 160, 40, alpha])
    })
}

/// The glTF quad textured by the checker, with `material_extra` in its material, written as
/// `name` in a folder of its own (tests run at once: none rewrites a texture another reads).
fn masked_quad(name: &str, material_extra: &str) -> std::path::PathBuf {
    let folder = format!("alpha-{name}");
    write(&folder, "checker.png", &png_bytes(&checker_alpha()));
    let uvs = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let gltf = quad_gltf("checker.png", "{}", material_extra, 1.0, uvs);
    write(&folder, name, gltf.as_bytes())
}

/// The quad of `model` filling a 60° view square-on (pixel (i, j)'s centre meets texel (i,
/// j)'s), lit by ambient 1 alone, before a blue background.
fn square_on(model: &std::path::Path) -> rastray::Scene {
    rastray::Scene {
        background: glam::Vec3::Z,
        ..scene_of(model, "")
    }
}

#[test]
fn a_masked_quad_shows_the_background_through_its_cut_out_texels_in_every_algorithm() {
    let masked = masked_quad("masked.gltf", r#","alphaMode":"MASK""#);
    let opaque_quad = masked_quad("opaque.gltf", "");
    let image = checker_alpha();
    // What the render should be: the texel's colour where it is opaque, the background (blue)
    // where it is cut out.
    let expected: Vec<u8> = (0..SIDE * SIDE)
        .flat_map(|k| {
            let (x, y) = (k % SIDE, k / SIDE);
            let [r, g, b, a] = image.get_pixel(x, y).0;
            if a == 255 { [r, g, b] } else { [0, 0, 255] }
        })
        .collect();
    let texels: Vec<u8> = image.pixels().flat_map(|p| [p[0], p[1], p[2]]).collect();
    for algorithm in ALGORITHMS {
        let got = render(&square_on(&masked), algorithm, SIDE, 1).to_srgb8();
        let psnr = common::psnr(&got, &expected);
        // 30 dB: texels read at their centres come back within a code value or two; a pixel
        // on the wrong side of a square's edge costs a whole colour.
        assert!(
            psnr >= 30.0,
            "{algorithm:?}: {psnr:.1} dB against the cut-out"
        );
        // The centre of each square: exactly texture or exactly background.
        for (x, y) in (0..SIDE / SQUARE).flat_map(|i| (0..SIDE / SQUARE).map(move |j| (i, j))) {
            let (i, j) = (x * SQUARE + SQUARE / 2, y * SQUARE + SQUARE / 2);
            let at = ((j * SIDE + i) * 3) as usize;
            let blue = got[at..at + 3] == [0, 0, 255];
            assert_eq!(blue, !opaque(i, j), "{algorithm:?}: pixel ({i}, {j})");
        }
        // Without MASK the alpha is ignored: the whole image, as before.
        let plain = render(&square_on(&opaque_quad), algorithm, SIDE, 1).to_srgb8();
        let psnr = common::psnr(&plain, &texels);
        assert!(psnr >= 30.0, "{algorithm:?} opaque: {psnr:.1} dB");
    }
}

#[test]
fn display_modes_see_through_the_cut_out_texels() {
    let masked = masked_quad("modes.gltf", r#","alphaMode":"MASK""#);
    let scene = square_on(&masked);
    for algorithm in ALGORITHMS {
        let options = rastray::render::RenderOptions {
            mode: rastray::render::DisplayMode::Normals,
            ..rastray::render::RenderOptions::new(algorithm, SIDE, SIDE)
        };
        let frame = common::render(&common::world(&scene), &scene.camera, options).0;
        // The normal +Z is (128, 128, 255) where the quad is; the background, blue, shows
        // where it is cut out.
        for (i, j) in [(4, 4), (12, 4), (4, 12), (12, 12), (36, 44), (44, 44)] {
            let red = frame.srgb8_at(i, j)[0];
            if opaque(i, j) {
                assert!(red.abs_diff(128) <= 1, "{algorithm:?} ({i}, {j}): {red}");
            } else {
                assert_eq!(red, 0, "{algorithm:?} ({i}, {j})");
            }
        }
    }
}

#[test]
fn a_cutoff_above_every_alpha_cuts_the_whole_quad_and_one_of_zero_none_of_it() {
    for (cutoff, covered) in [("0.0", SIDE * SIDE), ("1.5", 0)] {
        let extra = format!(r#","alphaMode":"MASK","alphaCutoff":{cutoff}"#);
        let model = masked_quad(&format!("cutoff{cutoff}.gltf"), &extra);
        for algorithm in ALGORITHMS {
            let got = render(&square_on(&model), algorithm, SIDE, 1).to_srgb8();
            let drawn = got.chunks(3).filter(|p| *p != [0, 0, 255]).count() as u32;
            assert_eq!(drawn, covered, "{algorithm:?}, alphaCutoff {cutoff}");
        }
    }
}

#[test]
fn phong_and_the_ray_tracer_agree_on_a_cut_out_quad_before_a_box() {
    let masked = masked_quad("tilted.gltf", r#","alphaMode":"MASK""#);
    let scene = common::scene(&format!(
        "background = [0.1, 0.1, 0.2]\nambient = 0.2\n[[light]]\nposition = [2.0, 3.0, 4.0]\n\
         intensity = 0.8\n[camera]\nposition = [1.5, 1.0, 3.5]\ntarget = [0.0, 0.0, 0.0]\n\
         fov = 45.0\n[[object]]\ntype = \"mesh\"\npath = {:?}\n\
         [[object]]\ntype = \"box\"\ncenter = [0.0, 0.0, -1.0]\nsize = [1.5, 1.5, 0.5]\n",
        masked.display().to_string()
    ));
    let phong = render(&scene, Algorithm::Phong, 160, 1).to_srgb8();
    let ray = render(&scene, Algorithm::Ray, 160, 1).to_srgb8();
    let psnr = common::psnr(&phong, &ray);
    eprintln!("cut-out quad before a box: Phong against ray tracing {psnr:.1} dB");
    // 35 dB: the two choose the same texels; where a pixel centre falls within rounding of a
    // square's edge, one may cut and the other not.
    assert!(psnr >= 35.0, "Phong against ray tracing {psnr:.1} dB");
}

/// A floor lit from straight above through a horizontal caster at height 2 (its left half, x < 0,
/// alpha 0, its right half alpha 1), seen from between caster and floor, looking down.
fn shadow_scene(caster: &std::path::Path) -> rastray::Scene {
    common::scene(&format!(
        "background = [0.0, 0.0, 0.0]\nambient = 0.2\n[[light]]\nposition = [0.0, 10.0, 0.0]\n\
         intensity = 0.8\n[camera]\nposition = [0.0, 1.5, 0.0]\ntarget = [0.0, 0.0, 0.0]\n\
         up = [0.0, 0.0, -1.0]\nfov = 60.0\n[[object]]\ntype = \"mesh\"\npath = {:?}\n\
         up = \"z\"\nposition = [0.0, 2.0, 0.0]\n[[object]]\ntype = \"box\"\n\
         center = [0.0, -0.05, 0.0]\nsize = [10.0, 0.1, 10.0]\n\
         material = {{ color = [1.0, 1.0, 1.0], diffuse = 1.0, specular = 0.0 }}\n",
        caster.display().to_string()
    ))
}

#[test]
fn a_cut_out_caster_lets_light_through_where_its_alpha_is_zero() {
    // Left half transparent, right half opaque.
    let halves = image::RgbaImage::from_fn(SIDE, SIDE, |x, _| {
        image::Rgba([200, 200, 200, if x < SIDE / 2 { 0 } else { 255 }])
    });
    write("alpha", "halves.png", &png_bytes(&halves));
    let uvs = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let caster = |name: &str, extra: &str| {
        let gltf = quad_gltf("halves.png", "{}", extra, 1.0, uvs);
        write("alpha", name, gltf.as_bytes())
    };
    let masked = caster("caster_masked.gltf", r#","alphaMode":"MASK""#);
    let opaque_caster = caster("caster_opaque.gltf", "");
    let (lit, shadowed) = floor_halves(&shadow_scene(&masked));
    let (left, right) = floor_halves(&shadow_scene(&opaque_caster));
    eprintln!("masked caster: {lit:.1} | {shadowed:.1}; opaque caster: {left:.1} | {right:.1}");
    // Lit: ambient 0.2 + diffuse 0.8 on a white floor is white (255); in shadow, ambient
    // 0.2 alone is sRGB 124.
    assert!(lit > 250.0, "light through the cut half: {lit:.1}");
    assert!(
        (shadowed - 124.0).abs() < 3.0,
        "shadow of the opaque half: {shadowed:.1}"
    );
    assert!(
        (left - 124.0).abs() < 3.0 && (right - 124.0).abs() < 3.0,
        "{left} {right}"
    );
}

/// The mean red of [`shadow_scene`]'s floor ray traced with shadows at 64×64, over the columns
/// left of the middle (under the caster's left half) and right of it, the middle eight columns
/// left out.
fn floor_halves(scene: &rastray::Scene) -> (f64, f64) {
    let mut options = rastray::render::RenderOptions::new(Algorithm::Ray, 64, 64);
    options.shadows = true;
    let frame = common::render(&common::world(scene), &scene.camera, options).0;
    let image = frame.to_srgb8();
    let image = &image;
    let mean = |columns: std::ops::Range<usize>| {
        let values: Vec<f64> = (0..64)
            .flat_map(|y| columns.clone().map(move |x| image[(y * 64 + x) * 3] as f64))
            .collect();
        values.iter().sum::<f64>() / values.len() as f64
    };
    (mean(0..28), mean(36..64))
}

/// Alpha 0 at the quad's left corners (x = −1) and 1 at its right ones: interpolated, the alpha
/// at x is (x + 1) / 2.
const LEFT_TO_RIGHT: [f32; 4] = [0.0, 1.0, 1.0, 0.0];

#[test]
fn vertex_alpha_cuts_a_masked_quad_where_it_falls_below_the_cutoff_in_every_algorithm() {
    for (cutoff, first_drawn) in [(0.25, 16), (0.5, 32), (0.75, 48)] {
        let extra = format!(r#","alphaMode":"MASK","alphaCutoff":{cutoff}"#);
        let gltf = vertex_alpha_quad_gltf(LEFT_TO_RIGHT, &extra);
        let model = write(
            "alpha-vertex",
            &format!("ramp{cutoff}.gltf"),
            gltf.as_bytes(),
        );
        for algorithm in ALGORITHMS {
            let got = render(&square_on(&model), algorithm, SIDE, 1).to_srgb8();
            // Pixel column i's centre is at alpha (i + 0.5) / 64: at least 1/128 from every
            // cutoff tried, so each column is wholly cut (blue) or wholly drawn (white).
            for (k, pixel) in got.chunks(3).enumerate() {
                let (i, j) = (k as u32 % SIDE, k as u32 / SIDE);
                let expected = if i < first_drawn {
                    [0, 0, 255]
                } else {
                    [255; 3]
                };
                assert_eq!(
                    pixel, expected,
                    "{algorithm:?}, alphaCutoff {cutoff}: pixel ({i}, {j})"
                );
            }
        }
    }
    // Without MASK the vertex alpha is ignored: the whole quad is drawn.
    let model = write(
        "alpha-vertex",
        "ramp-opaque.gltf",
        vertex_alpha_quad_gltf(LEFT_TO_RIGHT, "").as_bytes(),
    );
    for algorithm in ALGORITHMS {
        let got = render(&square_on(&model), algorithm, SIDE, 1).to_srgb8();
        assert!(got.chunks(3).all(|p| p == [255; 3]), "{algorithm:?}");
    }
}

#[test]
fn vertex_alpha_multiplies_the_base_colour_factors_alpha() {
    // Alpha 0.8 everywhere from the vertices, times a factor of 0.5: 0.4, below the default
    // cutoff of 0.5, so the whole quad is cut; with a factor of 1 none of it is.
    for (factor, drawn) in [(0.5, 0), (1.0, SIDE * SIDE)] {
        let gltf = vertex_alpha_quad_gltf([0.8; 4], r#","alphaMode":"MASK""#).replace(
            r#""metallicFactor":0.0"#,
            &format!(r#""baseColorFactor":[1,1,1,{factor}],"metallicFactor":0.0"#),
        );
        let model = write(
            "alpha-vertex",
            &format!("factor{factor}.gltf"),
            gltf.as_bytes(),
        );
        for algorithm in ALGORITHMS {
            let got = render(&square_on(&model), algorithm, SIDE, 1).to_srgb8();
            let covered = got.chunks(3).filter(|p| *p != [0, 0, 255]).count() as u32;
            assert_eq!(covered, drawn, "{algorithm:?}, factor {factor}");
        }
    }
}

#[test]
fn a_caster_cut_by_its_vertex_alpha_lets_light_through_its_cut_half() {
    let gltf = vertex_alpha_quad_gltf(LEFT_TO_RIGHT, r#","alphaMode":"MASK""#);
    let caster = write("alpha-vertex", "caster.gltf", gltf.as_bytes());
    let (lit, shadowed) = floor_halves(&shadow_scene(&caster));
    eprintln!("vertex-alpha caster: {lit:.1} | {shadowed:.1}");
    assert!(lit > 250.0, "light through the cut half: {lit:.1}");
    assert!(
        (shadowed - 124.0).abs() < 3.0,
        "shadow of the kept half: {shadowed:.1}"
    );
}

#[test]
fn a_mirrored_instance_keeps_its_vertex_alpha_at_the_right_corners_in_every_algorithm() {
    // Two nodes name the quad, both mirrored in x (the second 3 behind the first): one mesh
    // drawn as two instances. Mirrored, the alpha at x is (1 − x) / 2, so the right half is cut.
    // The Z-buffer draws placed copies whose corners are swapped to keep fronts in front; the
    // ray tracer reads the shared mesh: both must cut the same half.
    let gltf = vertex_alpha_quad_gltf(LEFT_TO_RIGHT, r#","alphaMode":"MASK""#)
        .replace(
            r#""scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}]"#,
            r#""scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0,"scale":[-1,1,1]},{"mesh":0,"scale":[-1,1,1],"translation":[0,0,-3]}]"#,
        );
    assert!(gltf.contains(r#""nodes":[0,1]"#));
    let model = write("alpha-vertex", "mirrored.gltf", gltf.as_bytes());
    // The file's bounds are centred at z = −1.5: put the front quad back at z = 0.
    let scene = rastray::Scene {
        background: glam::Vec3::Z,
        ..scene_of(&model, "position = [0.0, 0.0, -1.5]")
    };
    for algorithm in ALGORITHMS {
        let got = render(&scene, algorithm, SIDE, 1).to_srgb8();
        // Column i's centre has alpha 1 − (i + 0.5) / 64 on the front quad; where that is cut,
        // the quad behind is cut too (or not there).
        for (k, pixel) in got.chunks(3).enumerate() {
            let (i, j) = (k as u32 % SIDE, k as u32 / SIDE);
            let expected = if i < SIDE / 2 { [255; 3] } else { [0, 0, 255] };
            assert_eq!(pixel, expected, "{algorithm:?}: pixel ({i}, {j})");
        }
    }
}
