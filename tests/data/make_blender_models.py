"""Writes the STL and PLY test models of rastray with Blender's own exporters.

    blender -b --factory-startup --python tests/data/make_blender_models.py

(run from the crate root; made with Blender 3.4.1 from Debian 12). Outputs, each a few kB:

  tests/data/stl/cube_binary.stl      a 2×2×2 cube (12 triangles), binary
  tests/data/stl/cube_ascii.stl       the same cube, ASCII
  tests/data/stl/suzanne_binary.stl   Suzanne (968 triangles), binary
  tests/data/ply/cube_colors_ascii.ply    the cube with vertex colours, UVs and normals, ASCII
  tests/data/ply/cube_colors_binary.ply   the same, binary little-endian
  tests/data/ply/cube_plain_binary.ply    the cube without colours, UVs or normals
  tests/data/ply/suzanne_ascii.ply        Suzanne, positions and faces only, ASCII
  tests/data/obj/cube.obj                 the cube as OBJ (Y up: Blender's OBJ exporter turns it)

The cube's vertex colours are the corner's position mapped to 0..1 per axis ((x+1)/2, …),
so that a reader's colours can be checked against its positions. Blender's STL and PLY
exporters keep Blender's axes (Z up).
"""

import os

import bmesh
import bpy

ROOT = os.getcwd()


def out(*parts):
    path = os.path.join(ROOT, "tests", "data", *parts)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    return path


def only(obj):
    bpy.ops.object.select_all(action="DESELECT")
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def clear():
    bpy.ops.object.select_all(action="SELECT")
    bpy.ops.object.delete()


clear()
bpy.ops.mesh.primitive_cube_add(size=2.0, calc_uvs=True)
cube = bpy.context.active_object
cube.name = "Cube"
colors = cube.data.vertex_colors.new(name="Col")
for loop in cube.data.loops:
    co = cube.data.vertices[loop.vertex_index].co
    colors.data[loop.index].color = ((co.x + 1) / 2, (co.y + 1) / 2, (co.z + 1) / 2, 1.0)
only(cube)
bpy.ops.export_mesh.stl(filepath=out("stl", "cube_binary.stl"), use_selection=True, ascii=False)
bpy.ops.export_mesh.stl(filepath=out("stl", "cube_ascii.stl"), use_selection=True, ascii=True)
bpy.ops.export_mesh.ply(
    filepath=out("ply", "cube_colors_ascii.ply"), use_selection=True, use_ascii=True,
    use_colors=True, use_uv_coords=True, use_normals=True,
)
bpy.ops.export_mesh.ply(
    filepath=out("ply", "cube_colors_binary.ply"), use_selection=True, use_ascii=False,
    use_colors=True, use_uv_coords=True, use_normals=True,
)
bpy.ops.export_mesh.ply(
    filepath=out("ply", "cube_plain_binary.ply"), use_selection=True, use_ascii=False,
    use_colors=False, use_uv_coords=False, use_normals=False,
)
bpy.ops.export_scene.obj(
    filepath=out("obj", "cube.obj"), use_selection=True, use_materials=False,
    use_normals=False, use_uvs=False,
)

clear()
bpy.ops.mesh.primitive_monkey_add(size=2.0)
suzanne = bpy.context.active_object
suzanne.name = "Suzanne"
only(suzanne)
bpy.ops.export_mesh.stl(filepath=out("stl", "suzanne_binary.stl"), use_selection=True, ascii=False)
bpy.ops.export_mesh.ply(
    filepath=out("ply", "suzanne_ascii.ply"), use_selection=True, use_ascii=True,
    use_colors=False, use_uv_coords=False, use_normals=False,
)
