"""Writes the OBJ+MTL test models of rastray with Blender's own OBJ exporter.

    blender -b --factory-startup --python tests/data/make_blender_mtl.py

(run from the crate root; made with Blender 3.4.1 from Debian 12). Outputs, each a few kB:

  tests/data/obj_mtl/two_materials.obj, .mtl   a 2×2×2 cube: its top face "Red Paint"
                                               (written Red_Paint), the rest "Blue"
  tests/data/obj_mtl/textured_quad.obj, .mtl   a 2×2 plane facing +Z (after the exporter's turn to
                                               Y up) with "Checker F" (no Kd) textured by
  tests/data/obj_mtl/textures/letter f.png     16×16: a red-green gradient with a white F, so
                                               that a flip in U or V shows
"""

import os

import bpy

ROOT = os.path.join(os.getcwd(), "tests", "data", "obj_mtl")
os.makedirs(os.path.join(ROOT, "textures"), exist_ok=True)

bpy.ops.wm.read_factory_settings(use_empty=True)


def material(name, color=None, image=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    if color:
        bsdf.inputs["Base Color"].default_value = color
    if image:
        node = m.node_tree.nodes.new("ShaderNodeTexImage")
        node.image = image
        m.node_tree.links.new(node.outputs["Color"], bsdf.inputs["Base Color"])
    return m


def export(name):
    bpy.ops.wm.obj_export(
        filepath=os.path.join(ROOT, name),
        export_selected_objects=True,
        export_materials=True,
        export_uv=True,
        export_normals=True,
        path_mode="RELATIVE",
    )


# The cube: the top face red, the rest blue.
bpy.ops.mesh.primitive_cube_add(size=2)
cube = bpy.context.active_object
cube.data.materials.append(material("Red Paint", (1.0, 0.0, 0.0, 1.0)))
cube.data.materials.append(material("Blue", (0.0, 0.0, 1.0, 1.0)))
for polygon in cube.data.polygons:
    polygon.material_index = 0 if polygon.normal.z > 0.5 else 1
export("two_materials.obj")
bpy.data.objects.remove(cube)

# The texture: a gradient (red along x, green along y, from the bottom-left) with a white F.
size = 16
image = bpy.data.images.new("letter f", size, size)
pixels = []
for y in range(size):
    for x in range(size):
        f = (x in (4, 5) and 3 <= y <= 12) or (y in (11, 12) and 4 <= x <= 11) or (
            y in (7, 8) and 4 <= x <= 9
        )
        pixels += [1.0, 1.0, 1.0, 1.0] if f else [x / (size - 1), y / (size - 1), 0.0, 1.0]
image.pixels = pixels
image.filepath_raw = os.path.join(ROOT, "textures", "letter f.png")
image.file_format = "PNG"
image.save()

# The quad: Blender's plane lies in XY facing +Z; the exporter turns Z up into Y up, so it is
# turned first to face Blender's -Y, which becomes +Z.
bpy.ops.mesh.primitive_plane_add(size=2, rotation=(1.5707963, 0.0, 0.0))
quad = bpy.context.active_object
bpy.ops.object.transform_apply(rotation=True)
quad.data.materials.append(material("Checker F", image=image))
export("textured_quad.obj")
