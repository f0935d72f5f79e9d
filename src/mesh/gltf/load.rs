//! Reading a `.gltf` or `.glb` file: the container, the schema, the buffers, then every mesh
//! instance of the default scene with its node transforms applied.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use ::gltf::json::validation::{Checked, Error as SchemaError, Validate};
use ::gltf::json::{self, mesh::Semantic};
use ::gltf::{Document, Gltf, Node};
use glam::{Mat4, Vec3};

use super::appearance::{ImageCache, PartAppearance, part_appearance};
use super::buffers::load_buffers;
use super::error::GltfError;
use super::material::phong_from_pbr;
use super::primitive::{PrimitiveRead, mirrors, placed_geometry, read_primitive};
use super::warning::ImportWarning;
use crate::input_file::{MAX_MODEL_BYTES, read_bounded};
use crate::memory_budget::Estimate;
use crate::mesh::ModelGeometry;
use crate::mesh::texture::{AlphaMode, Appearance};
use crate::model_folder::ModelFolder;
use crate::scene::Material;

/// Most node instances a file may expand to (a node reached through several parents counts
/// once per path).
pub const MAX_NODE_INSTANCES: usize = 1_000_000;

/// One drawn primitive: a node's primitive with that node's transform applied, or a primitive
/// of a mesh that several nodes name, read once and drawn at each of its `instances`.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfPart {
    /// Which primitive of which node, as `node 2 "Left", mesh 0 "Name" primitive 1`; for a
    /// shared primitive, `mesh 0 "Name" primitive 1`.
    pub label: String,
    /// Its triangles: in the model's space (every node transform applied) when `instances` is
    /// empty; else in its mesh's own space.
    pub geometry: ModelGeometry,
    /// Where a shared primitive is drawn, in scene order; empty for a primitive drawn once.
    pub instances: Vec<GltfInstance>,
    /// Its material mapped to Phong; `None` when the primitive names no material.
    pub material: Option<Material>,
    /// Its base colour texture (with the geometry's corner UVs, when both could be read) and
    /// alpha mode.
    pub appearance: Appearance,
}

impl GltfPart {
    /// The part as it is drawn: itself when it is drawn once; else one part per instance, its
    /// geometry placed in the model's space as it was read before instancing, with the
    /// instance's label.
    pub fn expanded(&self) -> Vec<GltfPart> {
        if self.instances.is_empty() {
            return vec![self.clone()];
        }
        self.instances
            .iter()
            .map(|instance| GltfPart {
                label: instance.label.clone(),
                geometry: placed_geometry(&self.geometry, instance.transform),
                instances: Vec::new(),
                material: self.material,
                // `placed_geometry` swaps a mirrored copy's corners; its alphas follow.
                appearance: match mirrors(instance.transform) {
                    true => self.appearance.with_corners_swapped(),
                    false => self.appearance.clone(),
                },
            })
            .collect()
    }
}

/// One placement of a shared primitive.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfInstance {
    /// Which node draws it, as `node 2 "Left", mesh 0 "Name" primitive 1`.
    pub label: String,
    /// From the mesh's space to the model's: the node's matrix with its parents'. Finite and
    /// invertible (a node whose matrix is not has the primitive baked into a part of its own).
    pub transform: Mat4,
}

/// A glTF file as rastray draws it: one part per primitive drawn once, and one per primitive of a
/// mesh that several nodes name (drawn at each of its instances), in scene order.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfModel {
    /// The drawn primitives; never empty.
    pub parts: Vec<GltfPart>,
    /// What was skipped, each reported once.
    pub warnings: Vec<ImportWarning>,
    /// The buffer and image files read beside the model, in the order they were read.
    pub buffer_files: Vec<PathBuf>,
    /// Whether the file is a GLB container (else glTF's JSON).
    pub binary: bool,
}

impl GltfModel {
    /// Triangles over all parts, each shared part counted once per instance.
    pub fn triangle_count(&self) -> usize {
        self.parts
            .iter()
            .map(|p| p.geometry.triangles.len() * p.instances.len().max(1))
            .sum()
    }

    /// Axis-aligned bounds (min, max) of every part, in the model's space, every instance of a
    /// shared part placed.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        placed_bounds(self.parts.iter().map(|p| (&p.geometry, &p.instances[..])))
    }
}

/// Axis-aligned bounds (min, max) of `parts` (a geometry, and where it is placed: nowhere but
/// where it is when there is no instance); inverted (MAX, MIN) when empty.
pub fn placed_bounds<'a>(
    parts: impl Iterator<Item = (&'a ModelGeometry, &'a [GltfInstance])>,
) -> (Vec3, Vec3) {
    let mut bounds = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for (geometry, instances) in parts {
        if instances.is_empty() {
            let (lo, hi) = geometry.bounds();
            bounds = (bounds.0.min(lo), bounds.1.max(hi));
        }
        for instance in instances {
            for &p in &geometry.positions {
                let p = instance.transform.transform_point3(p);
                bounds = (bounds.0.min(p), bounds.1.max(p));
            }
        }
    }
    bounds
}

/// Reads the glTF or GLB file at `path`; buffers named by relative URIs are read from its folder
/// or below it, and from nowhere else.
pub fn load_gltf(path: &Path) -> Result<GltfModel, GltfError> {
    let bytes = read_bounded(path, MAX_MODEL_BYTES, "a model file").map_err(GltfError::Io)?;
    let (root, blob) = parse(&bytes)?;
    let mut warnings = Vec::new();
    let document = checked_document(root, &mut warnings)?;
    let folder = ModelFolder::of(path).map_err(GltfError::Io)?;
    let mut buffer_files = Vec::new();
    let buffers = load_buffers(&document, blob, &folder, &mut buffer_files)?;
    let mut images = ImageCache::new(&folder, &buffers, &mut buffer_files);
    let instances = node_instances(&document)?;
    let estimate = instanced_estimate(&instances);
    estimate.check(path).map_err(GltfError::OverBudget)?;
    folder.textures().count_model(estimate);
    // A mesh named by more than one node instance is read once, in its own space, and drawn at
    // each; its primitives' parts by mesh index (`None`: skipped or empty).
    let mut uses: HashMap<usize, usize> = HashMap::new();
    for mesh in instances.iter().filter_map(|(node, _)| node.mesh()) {
        *uses.entry(mesh.index()).or_default() += 1;
    }
    let mut shared: HashMap<usize, Vec<Option<usize>>> = HashMap::new();
    let mut parts: Vec<GltfPart> = Vec::new();
    let mut skipped = 0;
    let mut triangles = 0u64;
    for (node, transform) in instances {
        let Some(mesh) = node.mesh() else { continue };
        let node_label = match node.name() {
            Some(name) => format!("node {} {name:?}", node.index()),
            None => format!("node {}", node.index()),
        };
        let share = uses[&mesh.index()] > 1 && placeable(transform);
        if share && let Some(found) = shared.get(&mesh.index()) {
            for (primitive, part) in mesh.primitives().zip(found) {
                triangles += primitive_corners(&primitive);
                if triangles > 3 * crate::memory_budget::triangle_cap() {
                    return Err(GltfError::TooManyTriangles {
                        limit: crate::memory_budget::triangle_cap(),
                    });
                }
                if let Some(part) = *part {
                    let label = format!("{node_label}, {}", parts[part].label);
                    parts[part]
                        .instances
                        .push(GltfInstance { label, transform });
                }
            }
            continue;
        }
        let mut made = Vec::new();
        for primitive in mesh.primitives() {
            let label = match mesh.name() {
                Some(name) => format!(
                    "mesh {} {name:?} primitive {}",
                    mesh.index(),
                    primitive.index()
                ),
                None => format!("mesh {} primitive {}", mesh.index(), primitive.index()),
            };
            // A primitive makes at most as many triangles as it reads indices (strips and fans
            // make nearly that many): bound the total before anything is allocated, since a node
            // hierarchy can instance one mesh many times.
            triangles += primitive_corners(&primitive);
            if triangles > 3 * crate::memory_budget::triangle_cap() {
                return Err(GltfError::TooManyTriangles {
                    limit: crate::memory_budget::triangle_cap(),
                });
            }
            let material = primitive.material();
            let PartAppearance { appearance, uv_set } = match material.index() {
                Some(index) => {
                    let name = match material.name() {
                        Some(name) => format!("material {index} {name:?}"),
                        None => format!("material {index}"),
                    };
                    let read = part_appearance(&material, &name, &mut images, &mut warnings);
                    // A texture past the memory bound fails the load (with the figures), before
                    // any further one is decoded.
                    if let Some(over) = images.folder.textures().refusal() {
                        return Err(GltfError::OverBudget(over));
                    }
                    read
                }
                None => PartAppearance {
                    appearance: Appearance::plain(),
                    uv_set: None,
                },
            };
            let read_transform = if share { Mat4::IDENTITY } else { transform };
            made.push(None);
            match read_primitive(&primitive, &label, &buffers, read_transform, uv_set)? {
                PrimitiveRead::Skipped(warning) => {
                    skipped += 1;
                    warnings.push(warning);
                }
                // Fewer than three indices: nothing to draw, and no part to show for it.
                PrimitiveRead::Triangles(geometry, _) if geometry.triangles.is_empty() => {}
                PrimitiveRead::Triangles(geometry, corner_alphas) => {
                    if let (Some((set, _)), None) = (uv_set, &geometry.corner_uvs) {
                        warnings.push(ImportWarning::NoTextureCoordinates {
                            primitive: label.clone(),
                            set,
                        });
                    }
                    let phong = material.index().map(|_| {
                        let pbr = material.pbr_metallic_roughness();
                        let [r, g, b, _alpha] = pbr.base_color_factor();
                        phong_from_pbr(
                            Vec3::new(r, g, b),
                            pbr.metallic_factor(),
                            pbr.roughness_factor(),
                        )
                    });
                    let placed = format!("{node_label}, {label}");
                    let (label, instances) = match share {
                        true => (
                            label,
                            vec![GltfInstance {
                                label: placed,
                                transform,
                            }],
                        ),
                        false => (placed, Vec::new()),
                    };
                    // Vertex alpha matters only where alpha cuts the part out.
                    let appearance = match appearance.alpha_mode {
                        AlphaMode::Mask { .. } => Appearance {
                            corner_alphas: corner_alphas.map(Arc::from),
                            ..appearance
                        },
                        AlphaMode::Opaque => appearance,
                    };
                    *made.last_mut().expect("pushed above") = Some(parts.len());
                    parts.push(GltfPart {
                        label,
                        geometry,
                        instances,
                        material: phong,
                        appearance,
                    });
                }
            }
        }
        if share {
            shared.insert(mesh.index(), made);
        }
    }
    if parts.is_empty() {
        return Err(GltfError::NoTriangles { skipped });
    }
    let mut seen = HashSet::new();
    warnings.retain(|w| seen.insert(w.clone()));
    Ok(GltfModel {
        parts,
        warnings,
        buffer_files,
        binary: bytes.starts_with(b"glTF"),
    })
}

/// Indices a primitive reads (its positions, unindexed): a bound on its triangles, known before
/// it is read.
fn primitive_corners(primitive: &::gltf::Primitive<'_>) -> u64 {
    primitive
        .indices()
        .or_else(|| primitive.get(&::gltf::Semantic::Positions))
        .map_or(0, |a| a.count() as u64)
}

/// Whether a node's model-space `matrix` can place a shared mesh: finite and invertible, so that
/// rays can be moved into the mesh's space and normals out of it. Any other matrix is baked into
/// a copy of the mesh, as every placement was before instancing.
fn placeable(matrix: Mat4) -> bool {
    let det = glam::Mat3::from_mat4(matrix).determinant();
    matrix.is_finite() && det.is_finite() && det != 0.0 && matrix.inverse().is_finite()
}

/// The triangles, world objects and instances every primitive instance of `instances` will
/// make, counted from accessor counts before any is read: a third of a primitive's indices (or
/// of its positions, unindexed) in triangles, or nearly all of them for strips and fans. A mesh
/// that one node instance names makes one object per primitive; a mesh that several name is
/// stored once and makes an instance per primitive per node instance, placing its triangles.
fn instanced_estimate(instances: &[(Node<'_>, Mat4)]) -> Estimate {
    let mut uses: HashMap<usize, u64> = HashMap::new();
    for mesh in instances.iter().filter_map(|(node, _)| node.mesh()) {
        *uses.entry(mesh.index()).or_default() += 1;
    }
    let mut estimate = Estimate::default();
    for (node, transform) in instances {
        let Some(mesh) = node.mesh() else { continue };
        let shared = uses[&mesh.index()] > 1 && placeable(*transform);
        for primitive in mesh.primitives() {
            let corners = primitive_corners(&primitive);
            let triangles = match primitive.mode() {
                ::gltf::mesh::Mode::Triangles => corners / 3,
                ::gltf::mesh::Mode::TriangleStrip | ::gltf::mesh::Mode::TriangleFan => {
                    corners.saturating_sub(2)
                }
                _ => 0,
            };
            if shared {
                estimate.instances += 1;
                estimate.placed_triangles += triangles;
            } else {
                estimate.triangles += triangles;
                estimate.objects += 1;
            }
        }
    }
    // Each shared mesh's triangles, stored once (bounded by its indices).
    let mut counted = HashSet::new();
    for (node, transform) in instances {
        if let Some(mesh) = node.mesh()
            && uses[&mesh.index()] > 1
            && placeable(*transform)
            && counted.insert(mesh.index())
        {
            estimate.triangles += mesh
                .primitives()
                .map(|p| primitive_corners(&p))
                .sum::<u64>();
        }
    }
    estimate
}

/// The JSON document and the GLB binary chunk of `bytes`, with container errors told apart.
fn parse(bytes: &[u8]) -> Result<(json::Root, Option<Vec<u8>>), GltfError> {
    if bytes.is_empty() {
        return Err(GltfError::Empty);
    }
    if bytes.starts_with(b"glTF") {
        // The crate subtracts the 12-byte header from the declared length unchecked.
        let declared = bytes
            .get(8..12)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
            .ok_or_else(|| GltfError::TruncatedGlb("the 12-byte header is cut short".into()))?;
        if declared < 12 {
            return Err(GltfError::BadGlb(format!(
                "its header declares a length of {declared} bytes"
            )));
        }
        if declared > bytes.len() {
            return Err(GltfError::TruncatedGlb(format!(
                "its header declares {declared} bytes but the file has {}",
                bytes.len()
            )));
        }
    }
    let gltf = Gltf::from_slice_without_validation(bytes).map_err(|error| match error {
        ::gltf::Error::Binary(e) => match e {
            ::gltf::binary::Error::Length { .. }
            | ::gltf::binary::Error::ChunkLength { .. }
            | ::gltf::binary::Error::Io(_) => GltfError::TruncatedGlb(e.to_string()),
            ::gltf::binary::Error::Version(v) => {
                GltfError::BadGlb(format!("container version {v}, expected 2"))
            }
            other => GltfError::BadGlb(other.to_string()),
        },
        ::gltf::Error::Deserialize(e) => GltfError::NotGltf(e.to_string()),
        ::gltf::Error::Io(e) => GltfError::Io(e),
        other => GltfError::NotGltf(other.to_string()),
    })?;
    let root = gltf.document.into_json();
    if !root.asset.version.starts_with("2.") {
        return Err(GltfError::Version(root.asset.version));
    }
    Ok((root, gltf.blob))
}

/// Checks `root` against the glTF schema. Required extensions become warnings (rastray reads
/// none); accessors without a buffer view are allowed, as the specification allows them.
fn checked_document(
    root: json::Root,
    warnings: &mut Vec<ImportWarning>,
) -> Result<Document, GltfError> {
    // The crate's schema check looks POSITION accessors up without a bounds check: do it first.
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            if let Some(index) = primitive
                .attributes
                .get(&Checked::Valid(Semantic::Positions))
                && index.value() >= root.accessors.len()
            {
                return Err(GltfError::Invalid {
                    at: format!("meshes[{m}].primitives[{p}].attributes.POSITION"),
                    problem: format!(
                        "accessor {} does not exist (the file has {})",
                        index.value(),
                        root.accessors.len()
                    ),
                });
            }
        }
    }
    // The crate's `Image::source` unwraps a missing `uri`, and a missing `mimeType` beside a
    // `bufferView`: an image names its bytes one of the two ways, or the file is refused.
    for (i, image) in root.images.iter().enumerate() {
        let problem = match (&image.buffer_view, &image.uri, &image.mime_type) {
            (Some(_), _, None) => Some("an image in a buffer view needs its mimeType"),
            (None, None, _) => Some("an image needs a uri or a bufferView"),
            _ => None,
        };
        if let Some(problem) = problem {
            return Err(GltfError::Invalid {
                at: format!("images[{i}]"),
                problem: problem.to_string(),
            });
        }
    }
    let mut problems = Vec::new();
    root.validate(&root, json::Path::new, &mut |path, error| {
        problems.push((path(), error))
    });
    let tolerated = |path: &json::Path, error: SchemaError| {
        let path = path.as_str();
        (error == SchemaError::Unsupported
            && (path.starts_with("extensionsRequired") || path.starts_with("extensionsUsed")))
            || (error == SchemaError::Missing
                && path.starts_with("accessors[")
                && path.ends_with("].bufferView"))
    };
    if let Some((path, error)) = problems.iter().find(|(p, e)| !tolerated(p, *e)) {
        return Err(GltfError::Invalid {
            at: path.to_string(),
            problem: error.to_string().to_lowercase(),
        });
    }
    warnings.extend(
        root.extensions_required
            .iter()
            .filter(|name| *name != "KHR_texture_transform")
            .map(|name| ImportWarning::UnsupportedExtension { name: name.clone() }),
    );
    Ok(Document::from_json_without_validation(root))
}

/// Every node instance of the default scene (or the first scene; or, with no scene, every node
/// that is no other node's child) with its model-space matrix, parents before children.
fn node_instances(document: &Document) -> Result<Vec<(Node<'_>, Mat4)>, GltfError> {
    let roots: Vec<Node> = match document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        Some(scene) => scene.nodes().collect(),
        None => {
            let children: HashSet<usize> = document
                .nodes()
                .flat_map(|n| n.children().map(|c| c.index()))
                .collect();
            document
                .nodes()
                .filter(|n| !children.contains(&n.index()))
                .collect()
        }
    };
    // Depth-first with explicit enter/leave steps: no recursion to overflow the stack, and a
    // node met again while it is still being entered is a cycle.
    enum Step<'a> {
        Enter(Node<'a>, Mat4),
        Leave(usize),
    }
    let mut on_path = vec![false; document.nodes().len()];
    let mut stack: Vec<Step> = roots
        .into_iter()
        .rev()
        .map(|n| Step::Enter(n, Mat4::IDENTITY))
        .collect();
    let mut instances = Vec::new();
    while let Some(step) = stack.pop() {
        match step {
            Step::Leave(index) => on_path[index] = false,
            Step::Enter(node, parent) => {
                if on_path[node.index()] {
                    return Err(GltfError::NodeCycle(node.index()));
                }
                if instances.len() >= MAX_NODE_INSTANCES {
                    return Err(GltfError::TooManyNodes {
                        limit: MAX_NODE_INSTANCES,
                    });
                }
                on_path[node.index()] = true;
                let matrix = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
                stack.push(Step::Leave(node.index()));
                let children: Vec<Node> = node.children().collect();
                stack.extend(children.into_iter().rev().map(|c| Step::Enter(c, matrix)));
                instances.push((node, matrix));
            }
        }
    }
    Ok(instances)
}
