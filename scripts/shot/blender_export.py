"""Builds a small animated shot in Blender and exports it as glTF 2.0 with a clipblur job beside it.

Runs inside Blender (bpy), headless:

    blender -b --factory-startup --python scripts/shot/blender_export.py -- OUT_DIR

scripts/shot/blender_roundtrip.py runs it and checks what clipblur makes of the result. Writes into
OUT_DIR: checker.png (the texture, generated here), blender_shot.gltf + .bin (GLTF_SEPARATE, the
exporter's defaults otherwise, with cameras on), job.yaml (frame JOB_FRAME, 320x180, a centred
180-degree shutter, a sun and ambient light) and truth.json: what Blender itself says the shot is at
frames TRUTH_FRAMES, converted to glTF's +Y up (Blender (x, y, z) -> (x, z, -y), the exporter's
export_yup): the camera's world position, view and up, and every mesh's evaluated world-space vertices.

The shot, 48 frames at 24 fps, Blender Z up, every key LINEAR:
- a textured floor and back wall (checker.png through their UVs; the floor's tiled 3 x 3 by a Mapping
  node, which the exporter writes as KHR_texture_transform);
- a smooth-shaded, textured sphere rolling across the floor (keyed location and rotation);
- a car body moving along x with a textured wheel parented to it, spinning about its axle (a child
  animated under an animated parent);
- a bar skinned to a two-bone armature whose upper bone bends 60 degrees;
- a small cube whose material is an Emission shader (exported as emissiveFactor);
- a camera that dollies in and pans (keyed location and rotation).
Nothing random and nothing from the clock: the same Blender writes the same files.
"""

import json
import math
import sys
from pathlib import Path

import bmesh
import bpy
from mathutils import Matrix, Vector

FPS = 24
FRAME_START, FRAME_END = 1, 48
JOB_FRAME = 24                       # the frame the job renders
TRUTH_FRAMES = (1, 23, 24, 25, 48)   # frames whose pose truth.json records
CHECKER_SIZE, CHECKER_CELLS = 64, 8
FILM = (320, 180)


def to_gltf(v):
    """Blender Z-up to glTF Y-up, as the exporter's export_yup does: (x, y, z) -> (x, z, -y)."""
    return [v[0], v[2], -v[1]]


def clear_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights, bpy.data.images,
                 bpy.data.armatures, bpy.data.actions):
        for block in list(coll):
            coll.remove(block)


def checker_image(out_dir):
    """A 64x64 checker of 8x8 cells, light and dark grey-blue, saved as PNG and used by path."""
    img = bpy.data.images.new("checker", CHECKER_SIZE, CHECKER_SIZE, alpha=False)
    cell = CHECKER_SIZE // CHECKER_CELLS
    light, dark = (0.85, 0.82, 0.7, 1.0), (0.12, 0.16, 0.3, 1.0)
    pixels = []
    for y in range(CHECKER_SIZE):
        for x in range(CHECKER_SIZE):
            pixels.extend(light if ((x // cell) + (y // cell)) % 2 == 0 else dark)
    img.pixels = pixels
    img.filepath_raw = str(out_dir / "checker.png")
    img.file_format = "PNG"
    img.save()
    return img


def textured_material(name, image, tile=None):
    """Principled BSDF with the image as base colour; `tile` repeats it through a Mapping node (exported
    as KHR_texture_transform)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image
    links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    if tile:
        uv = nodes.new("ShaderNodeUVMap")
        mapping = nodes.new("ShaderNodeMapping")
        mapping.inputs["Scale"].default_value = (tile, tile, 1.0)
        links.new(uv.outputs["UV"], mapping.inputs["Vector"])
        links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    return mat


def plain_material(name, color):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*color, 1.0)
    return mat


def emission_material(name, color):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    emit = nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = (*color, 1.0)
    emit.inputs["Strength"].default_value = 1.0
    mat.node_tree.links.new(emit.outputs["Emission"], nodes["Material Output"].inputs["Surface"])
    return mat


def canonical_order(bm):
    """Vertices and faces sorted by position: bmesh's operators leave an order that differs from run to
    run (measured on 3.4: the sphere's triangles came out in another order, and its smooth normals, summed
    in face order, an ulp apart), and the exporter keeps it."""
    def by(elements, key):  # bmesh sorts by a number only: rank in the Python sort
        elements.index_update()
        rank = {e.index: r for r, e in enumerate(sorted(elements, key=key))}
        elements.sort(key=lambda e: rank[e.index])
        elements.index_update()

    by(bm.verts, lambda v: (v.co.z, v.co.y, v.co.x))
    by(bm.faces, lambda f: sorted(v.index for v in f.verts))


def mesh_object(name, build, material, location=(0, 0, 0), smooth=False):
    """An object from a bmesh built by `build(bm)`, with the UVs bmesh's primitives make (calc_uvs)."""
    mesh = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bm.loops.layers.uv.new("UVMap")  # bmesh's primitives fill UVs only into an existing layer
    build(bm)
    bmesh.ops.triangulate(bm, faces=bm.faces, quad_method="FIXED", ngon_method="EAR_CLIP")
    canonical_order(bm)
    bm.to_mesh(mesh)
    bm.free()
    for poly in mesh.polygons:
        poly.use_smooth = smooth
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def key(obj, frame, **values):
    for prop, value in values.items():
        setattr(obj, prop, value)
        obj.keyframe_insert(prop, frame=frame)


def linear_keys():
    for action in bpy.data.actions:
        for fc in action.fcurves:
            for kp in fc.keyframe_points:
                kp.interpolation = "LINEAR"


def build_static(checker):
    floor = textured_material("floor", checker, tile=3.0)
    mesh_object("floor", lambda bm: bmesh.ops.create_grid(bm, x_segments=1, y_segments=1, size=8.0,
                                                          calc_uvs=True), floor)
    wall = mesh_object("wall", lambda bm: bmesh.ops.create_grid(bm, x_segments=1, y_segments=1, size=3.0,
                                                                calc_uvs=True),
                       textured_material("wall", checker), location=(0, 5, 3))
    wall.rotation_euler = (math.radians(90), 0, 0)
    wall.scale = (2.5, 1.0, 1.0)
    mesh_object("lamp", lambda bm: bmesh.ops.create_cube(bm, size=0.5, calc_uvs=True),
                emission_material("lamp", (1.0, 0.75, 0.3)), location=(2.5, 3.5, 1.2))


def build_sphere(checker):
    sphere = mesh_object("ball", lambda bm: bmesh.ops.create_uvsphere(bm, u_segments=24, v_segments=12,
                                                                      radius=0.6, calc_uvs=True),
                         textured_material("ball", checker), smooth=True)
    key(sphere, FRAME_START, location=(-3.5, 0.5, 0.6), rotation_euler=(0, 0, 0))
    # Rolling along +x: turning about +y; 7 m at radius 0.6 is 11.7 rad, 14 degrees a frame.
    key(sphere, FRAME_END, location=(3.5, 0.5, 0.6), rotation_euler=(0, 7.0 / 0.6, 0.0))


def build_car(checker):
    car = mesh_object("car", lambda bm: bmesh.ops.create_cube(bm, size=1.0, calc_uvs=True),
                      plain_material("car", (0.7, 0.1, 0.08)))
    car.data.transform(Matrix.Diagonal((1.6, 0.6, 0.5, 1.0)))
    key(car, FRAME_START, location=(4.0, -2.0, 0.65))
    key(car, FRAME_END, location=(-2.0, -2.0, 0.65))

    def cylinder(bm):
        bmesh.ops.create_cone(bm, cap_ends=True, segments=16, radius1=0.4, radius2=0.4, depth=0.2,
                              calc_uvs=True, matrix=Matrix.Rotation(math.radians(90), 4, "X"))

    wheel = mesh_object("wheel", cylinder, textured_material("wheel", checker), location=(0.5, -0.4, -0.25))
    wheel.parent = car
    # Rolling without slipping towards -x: 6 m at radius 0.4 is 15 rad about -y of the car.
    key(wheel, FRAME_START, rotation_euler=(0, 0, 0))
    key(wheel, FRAME_END, rotation_euler=(0, -6.0 / 0.4, 0))


def build_skinned_bar():
    arm_data = bpy.data.armatures.new("rig")
    rig = bpy.data.objects.new("rig", arm_data)
    rig.location = (-1.5, 2.0, 0.0)
    bpy.context.scene.collection.objects.link(rig)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode="EDIT")
    lower = arm_data.edit_bones.new("lower")
    lower.head, lower.tail = (0, 0, 0), (0, 0, 1)
    upper = arm_data.edit_bones.new("upper")
    upper.head, upper.tail = (0, 0, 1), (0, 0, 2)
    upper.parent = lower
    bpy.ops.object.mode_set(mode="OBJECT")

    def column(bm):
        bmesh.ops.create_cone(bm, cap_ends=True, segments=12, radius1=0.2, radius2=0.2, depth=2.0,
                              calc_uvs=True, matrix=Matrix.Translation((0, 0, 1)))
        edges = [e for e in bm.edges if abs(e.verts[0].co.z - e.verts[1].co.z) > 1e-6]
        bmesh.ops.subdivide_edges(bm, edges=edges, cuts=7, use_grid_fill=True)

    bar = mesh_object("bar", column, plain_material("bar", (0.2, 0.6, 0.25)), smooth=True)
    bar.parent = rig
    lower_group, upper_group = bar.vertex_groups.new(name="lower"), bar.vertex_groups.new(name="upper")
    for v in bar.data.vertices:
        w = min(max((v.co.z - 0.75) / 0.5, 0.0), 1.0)  # a linear blend over the joint's 0.5 m
        if w < 1.0:
            lower_group.add([v.index], 1.0 - w, "REPLACE")
        if w > 0.0:
            upper_group.add([v.index], w, "REPLACE")
    bar.modifiers.new("rig", "ARMATURE").object = rig

    pose_upper = rig.pose.bones["upper"]
    pose_upper.rotation_mode = "QUATERNION"
    for frame, degrees in ((FRAME_START, 0.0), (FRAME_END, 60.0)):
        pose_upper.rotation_quaternion = Matrix.Rotation(math.radians(degrees), 4, "X").to_quaternion()
        pose_upper.keyframe_insert("rotation_quaternion", frame=frame)


def build_camera():
    cam_data = bpy.data.cameras.new("camera")
    cam_data.lens = 30.0
    cam = bpy.data.objects.new("camera", cam_data)
    bpy.context.scene.collection.objects.link(cam)
    bpy.context.scene.camera = cam
    # A dolly in (y -11 -> -8.5) and a pan left to right (15 degrees about z).
    key(cam, FRAME_START, location=(-0.5, -11.0, 2.6), rotation_euler=(math.radians(81), 0, math.radians(-7)))
    key(cam, FRAME_END, location=(0.5, -8.5, 2.2), rotation_euler=(math.radians(83), 0, math.radians(8)))


def truth(scene):
    """Camera and every mesh's evaluated world-space vertices at TRUTH_FRAMES, in glTF's Y-up."""
    out = {"fps": FPS, "film": list(FILM), "frames": {}}
    for frame in TRUTH_FRAMES:
        scene.frame_set(frame)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        cam = scene.camera.evaluated_get(depsgraph)
        m = cam.matrix_world
        rot = m.to_3x3()
        record = {"camera": {"position": to_gltf(m.translation), "view": to_gltf(rot @ Vector((0, 0, -1))),
                             "up": to_gltf(rot @ Vector((0, 1, 0)))}, "meshes": {}}
        for obj in scene.objects:
            if obj.type != "MESH":
                continue
            ev = obj.evaluated_get(depsgraph)
            mesh = ev.to_mesh()
            record["meshes"][obj.name] = [to_gltf(ev.matrix_world @ v.co) for v in mesh.vertices]
            ev.to_mesh_clear()
        out["frames"][str(frame)] = record
    cam_data = scene.camera.data
    # Sensor fit AUTO on a landscape film fits the sensor width: yfov from the horizontal one.
    hfov = 2.0 * math.atan(cam_data.sensor_width / (2.0 * cam_data.lens))
    out["vfov_degrees"] = math.degrees(2.0 * math.atan(math.tan(hfov / 2.0) * FILM[1] / FILM[0]))
    return out


JOB = f"""# Written by scripts/shot/blender_export.py: frame {JOB_FRAME} of Blender's shot, exported as glTF.
version: 1
scene: blender_shot.gltf
film: {{width: {FILM[0]}, height: {FILM[1]}, background: [0.5, 0.62, 0.8]}}
shutter: {{open: -0.25, close: 0.25}}
frames: {{first: {JOB_FRAME}, last: {JOB_FRAME}, fps: {FPS}}}
lights:
  - {{type: directional, color: [1, 0.96, 0.9], intensity: 0.9, direction: [-0.4, -1, -0.5]}}
ambient: 0.3
render: {{method: clipped, seed: 1}}
output: {{path: blender_shot.exr}}
"""


def main():
    out_dir = Path(sys.argv[sys.argv.index("--") + 1]).resolve()
    out_dir.mkdir(parents=True, exist_ok=True)
    clear_scene()
    scene = bpy.context.scene
    scene.render.fps = FPS
    scene.frame_start, scene.frame_end = FRAME_START, FRAME_END
    scene.render.resolution_x, scene.render.resolution_y = FILM
    checker = checker_image(out_dir)
    build_static(checker)
    build_sphere(checker)
    build_car(checker)
    build_skinned_bar()
    build_camera()
    linear_keys()
    (out_dir / "truth.json").write_text(json.dumps(truth(scene), indent=1) + "\n")
    scene.frame_set(FRAME_START)
    bpy.ops.export_scene.gltf(filepath=str(out_dir / "blender_shot.gltf"), export_format="GLTF_SEPARATE",
                              export_cameras=True)
    (out_dir / "job.yaml").write_text(JOB)


main()
