# Builds vkrt's corpus of glTF assets in Blender and writes each with Blender's own
# glTF exporter, as a user would: several materials, textures (base colour,
# metallic-roughness, normal, emission; PNG and JPEG, drawn here with numpy, never
# downloaded), parented objects turned and scaled, meshes used several times, and
# what real exports carry (degenerate triangles, a mostly black emission texture, a
# mirrored object, textures the exporter re-encodes). scenes/gltf/README.md lists
# the assets; .glb writes one binary file, .gltf the separate .gltf + .bin + images.
#
#   blender -b --factory-startup --python-exit-code 1 -P scripts/blender/gltf_corpus.py -- \
#       --asset radio --out scenes/gltf/corpus/radio.glb
#
# Blender is z-up and its front view looks along +y; the exporter turns that into
# glTF's y-up, with the assets' fronts toward +z. Lengths are metres.
import argparse
import math
import os
import shutil
import sys
import tempfile

import bmesh
import bpy
from mathutils import Matrix, Vector

try:
    import numpy as np
except ImportError:
    sys.exit("gltf_corpus.py: needs numpy in Blender's Python: apt-get install python3-numpy")

ASSETS = ["radio", "dining_set", "crates", "vase", "sign"]


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="gltf_corpus.py")
    p.add_argument("--asset", required=True, choices=ASSETS)
    p.add_argument("--out", required=True, help="FILE.glb (one binary file) or FILE.gltf (.gltf + .bin + images)")
    args = p.parse_args(argv)
    if not args.out.endswith((".glb", ".gltf")):
        p.error("--out must end in .glb or .gltf")
    return args


# ---------------------------------------------------------------------------
# Images: arrays of height x width x 3 in [0, 1], top row first, written as PNG
# or JPEG (by the file name) through Blender's own image writer.

def smooth_noise(rng, height, width, cells, octaves=4):
    # Tileable value noise: random grids, finer and weaker each octave,
    # interpolated with smoothstep and wrapped at the edges.
    out = np.zeros((height, width))
    amplitude, total = 1.0, 0.0
    for octave in range(octaves):
        cy, cx = cells[0] * 2 ** octave, cells[1] * 2 ** octave
        grid = rng.random((cy, cx))
        y = np.arange(height) * cy / height
        x = np.arange(width) * cx / width
        y0, x0 = np.floor(y).astype(int), np.floor(x).astype(int)
        fy, fx = y - y0, x - x0
        fy, fx = (fy * fy * (3 - 2 * fy))[:, None], (fx * fx * (3 - 2 * fx))[None, :]
        y1, x1 = (y0 + 1) % cy, (x0 + 1) % cx
        top = grid[y0][:, x0] * (1 - fx) + grid[y0][:, x1] * fx
        bottom = grid[y1][:, x0] * (1 - fx) + grid[y1][:, x1] * fx
        out += amplitude * (top * (1 - fy) + bottom * fy)
        total += amplitude
        amplitude *= 0.5
    return out / total


def mix(a, b, t):
    # Per-pixel blend of two colours by t (height x width).
    a, b = np.asarray(a, float), np.asarray(b, float)
    return a * (1 - t[..., None]) + b * t[..., None]


def normal_map(height_field, strength):
    # A tangent-space normal map (glTF's: x right, y up the image) of a height
    # field given top row first.
    dx = (np.roll(height_field, -1, axis=1) - np.roll(height_field, 1, axis=1)) * 0.5 * strength
    dup = (np.roll(height_field, 1, axis=0) - np.roll(height_field, -1, axis=0)) * 0.5 * strength
    n = np.stack([-dx, -dup, np.ones_like(dx)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return n * 0.5 + 0.5


def write_image(pixels, path, data=False):
    # Writes the image with Blender and loads it back as a file image, which the
    # exporter copies as it is where it can (or re-encodes, as for channel maps).
    height, width, _ = pixels.shape
    image = bpy.data.images.new(os.path.basename(path), width, height)
    rgba = np.ones((height, width, 4), dtype=np.float32)
    rgba[..., :3] = np.clip(pixels, 0, 1)[::-1]
    image.pixels.foreach_set(rgba.ravel())
    image.file_format = "JPEG" if path.endswith(".jpg") else "PNG"
    image.filepath_raw = path
    image.save(filepath=path, quality=88)
    bpy.data.images.remove(image)
    loaded = bpy.data.images.load(path)
    if data:
        loaded.colorspace_settings.name = "Non-Color"
    return loaded


def disc(height, width, cy, cx, radius):
    # 1 inside a disc (pixel units), 0 outside, a pixel of antialiasing.
    y, x = np.mgrid[0:height, 0:width]
    return np.clip(radius + 0.5 - np.hypot(y - cy, x - cx), 0, 1)


# ---------------------------------------------------------------------------
# Materials: Principled BSDFs wired as the exporter reads them.

def material(name, base=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.5, base_tex=None, mr_tex=None,
             normal_tex=None, normal_strength=1.0, emission_tex=None, emission_strength=1.0, uv_scale=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    tree = m.node_tree
    bsdf = tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*base, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    mapping = None
    if uv_scale:
        # A Mapping node on the UVs: the exporter writes KHR_texture_transform.
        coords = tree.nodes.new("ShaderNodeTexCoord")
        mapping = tree.nodes.new("ShaderNodeMapping")
        mapping.inputs["Scale"].default_value = (uv_scale, uv_scale, 1.0)
        tree.links.new(coords.outputs["UV"], mapping.inputs["Vector"])

    def texture(image):
        node = tree.nodes.new("ShaderNodeTexImage")
        node.image = image
        if mapping:
            tree.links.new(mapping.outputs["Vector"], node.inputs["Vector"])
        return node

    if base_tex:
        tree.links.new(texture(base_tex).outputs["Color"], bsdf.inputs["Base Color"])
    if mr_tex:
        # glTF's channels: roughness in green, metallic in blue.
        split = tree.nodes.new("ShaderNodeSeparateColor")
        tree.links.new(texture(mr_tex).outputs["Color"], split.inputs["Color"])
        tree.links.new(split.outputs["Green"], bsdf.inputs["Roughness"])
        tree.links.new(split.outputs["Blue"], bsdf.inputs["Metallic"])
    if normal_tex:
        node = tree.nodes.new("ShaderNodeNormalMap")
        node.inputs["Strength"].default_value = normal_strength
        tree.links.new(texture(normal_tex).outputs["Color"], node.inputs["Color"])
        tree.links.new(node.outputs["Normal"], bsdf.inputs["Normal"])
    if emission_tex:
        tree.links.new(texture(emission_tex).outputs["Color"], bsdf.inputs["Emission"])
        bsdf.inputs["Emission Strength"].default_value = emission_strength
    return m


# ---------------------------------------------------------------------------
# Meshes, built in bmesh and kept as mesh data so that several objects can share one.

def finish(bm, name, materials, smooth_angle=None):
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    for m in materials:
        mesh.materials.append(m)
    if smooth_angle is not None:
        # Smooth shading with sharp edges above the angle: the exporter splits
        # the normals there, as Blender shows them.
        for poly in mesh.polygons:
            poly.use_smooth = True
        mesh.use_auto_smooth = True
        mesh.auto_smooth_angle = math.radians(smooth_angle)
    return mesh


def face_uvs(bm):
    # Each face of a box gets the whole texture, upright on the sides.
    uv = bm.loops.layers.uv.verify()
    for face in bm.faces:
        n = face.normal
        up = Vector((0, 0, 1)) if abs(n.z) < 0.9 else Vector((0, 1, 0))
        right = up.cross(n)
        c = face.calc_center_median()
        us = [(v.co - c).dot(right) for v in face.verts]
        vs = [(v.co - c).dot(up) for v in face.verts]
        for loop in face.loops:
            p = loop.vert.co - c
            loop[uv].uv = ((p.dot(right) - min(us)) / (max(us) - min(us)),
                           (p.dot(up) - min(vs)) / (max(vs) - min(vs)))


def box(name, size, materials, bevel=0.0, segments=2, at=(0, 0, 0), bottom=True):
    # A box of size (x, y, z), its bottom face at z = 0 (or centred), bevelled.
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    bmesh.ops.scale(bm, vec=Vector(size), verts=bm.verts)
    bm.normal_update()
    face_uvs(bm)
    if bevel > 0:
        bmesh.ops.bevel(bm, geom=bm.edges[:] + bm.verts[:], offset=bevel, offset_type="OFFSET",
                        segments=segments, profile=0.5, affect="EDGES")
    shift = Vector(at) + Vector((0, 0, size[2] / 2 if bottom else 0))
    bmesh.ops.translate(bm, vec=shift, verts=bm.verts)
    return finish(bm, name, materials, smooth_angle=35)


def cylinder(name, radius, depth, materials, segments=24, tip=False, at=(0, 0, 0)):
    # A capped cylinder along z from at.z to at.z + depth. With tip, the top ring
    # is scaled to a point as a modeller would taper it, leaving its vertices
    # apart but coincident: zero-area triangles on the side and in the cap.
    bm = bmesh.new()
    bmesh.ops.create_cone(bm, cap_ends=True, cap_tris=False, segments=segments, radius1=radius,
                          radius2=radius, depth=depth, calc_uvs=True)
    if tip:
        for v in bm.verts:
            if v.co.z > 0:
                v.co.x = v.co.y = 0.0
    bmesh.ops.translate(bm, vec=Vector(at) + Vector((0, 0, depth / 2)), verts=bm.verts)
    return finish(bm, name, materials, smooth_angle=40)


def grid(name, size, cuts, materials, collapse=()):
    # A plane in x, y facing +z, cuts[0] x cuts[1] quads, UVs from the position.
    # collapse: (i, j) grid vertices moved onto their right-hand neighbour with its
    # UV, as an unfinished merge leaves them: each makes zero-area triangles.
    sx, sy = size
    nx, ny = cuts
    verts, uvs = [], []
    for j in range(ny + 1):
        for i in range(nx + 1):
            ii = i + 1 if (i, j) in collapse else i
            x, y = (ii / nx - 0.5) * sx, (j / ny - 0.5) * sy
            verts.append((x, y, 0.0))
            uvs.append((ii / nx, j / ny))
    faces = [(j * (nx + 1) + i, j * (nx + 1) + i + 1, (j + 1) * (nx + 1) + i + 1, (j + 1) * (nx + 1) + i)
             for j in range(ny) for i in range(nx)]
    bm = bmesh.new()
    bverts = [bm.verts.new(v) for v in verts]
    layer = bm.loops.layers.uv.verify()
    for f in faces:
        face = bm.faces.new([bverts[k] for k in f])
        for loop, k in zip(face.loops, f):
            loop[layer].uv = uvs[k]
    return finish(bm, name, materials)


def torus(name, major, minor, materials):
    bpy.ops.mesh.primitive_torus_add(major_radius=major, minor_radius=minor, major_segments=40,
                                     minor_segments=10)
    obj = bpy.context.object
    mesh = obj.data
    mesh.name = name
    bpy.data.objects.remove(obj)
    for m in materials:
        mesh.materials.append(m)
    for poly in mesh.polygons:
        poly.use_smooth = True
    return mesh


def join(name, meshes, smooth_angle=35):
    # One mesh of several parts (and their materials), as Ctrl+J makes.
    materials = []
    for mesh in meshes:
        for m in mesh.materials:
            if m not in materials:
                materials.append(m)
    bm = bmesh.new()
    for mesh in meshes:
        for poly in mesh.polygons:
            poly.material_index = materials.index(mesh.materials[poly.material_index])
        bm.from_mesh(mesh)
        bpy.data.meshes.remove(mesh)
    return finish(bm, name, materials, smooth_angle=smooth_angle)


def camera_at(eye, target, angle_y):
    # The scene's camera at eye looking at target, of vertical field angle_y degrees.
    camera = bpy.data.cameras.new("camera")
    camera.sensor_fit = "VERTICAL"
    camera.angle_y = math.radians(angle_y)
    cam = place("camera", camera, location=eye)
    cam.rotation_euler = (target - eye).to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.camera = cam


def place(name, mesh=None, parent=None, location=(0, 0, 0), rotation=(0, 0, 0), scale=(1, 1, 1)):
    # An object (an empty without mesh) in the scene, its transform relative to its parent.
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    obj.parent = parent
    obj.location = location
    obj.rotation_euler = [math.radians(a) for a in rotation]
    obj.scale = scale
    return obj


# ---------------------------------------------------------------------------
# The assets.

def wood_pixels(rng, size, light, dark, rings):
    noise = smooth_noise(rng, size, size, (4, 2))
    y = np.linspace(0, 1, size, endpoint=False)[:, None]
    grain = 0.5 + 0.5 * np.sin(2 * math.pi * (rings * y + 3.0 * noise))
    fine = smooth_noise(rng, size, size, (64, 4), octaves=2)
    return mix(dark, light, np.clip(0.75 * grain + 0.5 * fine - 0.1, 0, 1)), grain


def radio(textures):
    # A tabletop radio, no camera and no lights: a walnut body, a front panel with
    # a speaker grille, a dial and a small green power light (a mostly black JPEG
    # emission texture), two knobs of one mesh, four feet of another, a handle and
    # a tapered antenna carrying a ball, all under a turned and scaled root.
    rng = np.random.default_rng(1)
    wood, _ = wood_pixels(rng, 512, (0.45, 0.26, 0.13), (0.22, 0.11, 0.05), rings=9)
    walnut = material("walnut", roughness=0.35, base_tex=write_image(wood, f"{textures}/walnut.jpg"))

    h, w = 256, 512
    y, x = np.mgrid[0:h, 0:w]
    u, v = x / w, 1 - y / h
    grille = (u > 0.04) & (u < 0.56) & (v > 0.1) & (v < 0.9)
    dial = (u > 0.62) & (u < 0.96) & (v > 0.25) & (v < 0.75)
    # Perforations on a staggered grid, 14 px apart.
    row = np.round(y / 12.0)
    cx = (x + 7 * (row % 2)) / 14.0
    hole = np.clip(5.5 - np.hypot((cx - np.round(cx)) * 14, (y / 12.0 - row) * 12), 0, 1) * grille
    ticks = dial & (np.abs(v - 0.62) < 0.08) & ((x % 10) < 2)
    needle = dial & (np.abs(u - 0.74) < 0.003) & (v > 0.32) & (v < 0.7)
    led = disc(h, w, 0.12 * h, 0.9 * w, 6)
    brushed = smooth_noise(rng, h, w, (64, 2), octaves=2)

    base = np.empty((h, w, 3))
    base[:] = (0.72, 0.72, 0.70)
    base += (brushed[..., None] - 0.5) * 0.08
    base[grille] = (0.10, 0.10, 0.11)
    base[hole > 0.5] = (0.02, 0.02, 0.02)
    base[dial] = (0.86, 0.80, 0.62)
    base[ticks] = (0.15, 0.12, 0.10)
    base[needle] = (0.75, 0.08, 0.05)
    base = mix(base, (0.10, 0.45, 0.12), led)
    mr = np.zeros((h, w, 3))
    mr[..., 1] = 0.28 + 0.1 * brushed
    mr[..., 2] = 1.0
    mr[grille, 1] = 0.5
    mr[dial, 1], mr[dial, 2] = 0.25, 0.0
    mr[..., 1] = mr[..., 1] * (1 - led) + 0.1 * led
    mr[..., 2] *= 1 - led
    height = -0.8 * hole + 0.6 * dial + 1.5 * led
    emission = mix(np.zeros((h, w, 3)), (0.3, 1.0, 0.35), led)
    panel_material = material("panel", base_tex=write_image(base, f"{textures}/panel_base.png"),
                              mr_tex=write_image(mr, f"{textures}/panel_mr.png", data=True),
                              normal_tex=write_image(normal_map(height, 2.0), f"{textures}/panel_normal.png", data=True),
                              emission_tex=write_image(emission, f"{textures}/panel_emission.jpg"),
                              emission_strength=6.0)
    chrome = material("chrome", base=(0.9, 0.9, 0.9), metallic=1.0, roughness=0.12)
    rubber = material("rubber", base=(0.03, 0.03, 0.03), roughness=0.8)
    aluminium = material("knob", base=(0.8, 0.78, 0.75), metallic=1.0, roughness=0.3)

    body_w, body_d, body_h = 0.32, 0.12, 0.22
    root = place("Radio", rotation=(0, 0, -20), scale=(1.5, 1.5, 1.5))
    body = place("body", box("body", (body_w, body_d, body_h), [walnut], bevel=0.012, segments=3), root,
                 location=(0, 0, 0.01))
    # The panel: a grid of 8 x 4 quads facing -y (the front), two of its vertices
    # collapsed onto their neighbours.
    panel = grid("panel", (0.28, 0.13), (8, 4), [panel_material], collapse={(2, 1), (5, 3)})
    panel.transform(Matrix.Rotation(math.radians(90), 4, "X"))
    place("panel", panel, body, location=(0, -body_d / 2 - 0.0015, 0.135))
    knob = cylinder("knob", 0.018, 0.016, [aluminium], segments=32)
    for i, x in enumerate((-0.07, 0.07)):
        place(f"knob.{i}", knob, body, location=(x, -body_d / 2, 0.038), rotation=(90, 0, 25 * i))
    foot = cylinder("foot", 0.012, 0.01, [rubber], segments=16, at=(0, 0, -0.01))
    for i, (x, y) in enumerate([(-1, -1), (1, -1), (1, 1), (-1, 1)]):
        place(f"foot.{i}", foot, body, location=(x * 0.13, y * 0.04, 0))
    place("handle", torus("handle", 0.09, 0.008, [rubber]), body, location=(0, 0, body_h), rotation=(90, 0, 0),
          scale=(1.0, 0.55, 1.0))
    antenna = place("antenna", cylinder("antenna", 0.004, 0.3, [chrome], segments=16, tip=True), body,
                    location=(0.12, 0.03, body_h - 0.01), rotation=(0, 35, 0))
    # The ball: a cube subdivided and pushed onto a sphere. (A UV sphere's smooth
    # normals came out of Blender 3.4 different in their last bits from run to
    # run; this one's are the same every time, so the file is reproducible.)
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0, calc_uvs=True)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=3, use_grid_fill=True)
    for v in bm.verts:
        v.co = v.co.normalized() * 0.008
    place("antenna_tip", finish(bm, "ball", [chrome], smooth_angle=60), antenna, location=(0, 0, 0.3))


def dining_set(textures):
    # A table and four chairs on a rug, no camera and no lights: the table's four
    # legs share one mesh, the four chairs another (one chair of two materials,
    # one of them mirrored by a negative scale, one pulled out and turned); the
    # rug's pattern repeats through a texture transform. Each chair carries the
    # zero-area triangles of a seat whose corner was collapsed.
    rng = np.random.default_rng(2)
    wood, grain = wood_pixels(rng, 512, (0.78, 0.58, 0.36), (0.55, 0.36, 0.19), rings=14)
    oak = material("oak", roughness=0.4, base_tex=write_image(wood, f"{textures}/oak.jpg"),
                   normal_tex=write_image(normal_map(grain[::2, ::2] * 0.6, 1.0), f"{textures}/oak_normal.png",
                                          data=True))
    n = 256
    y, x = np.mgrid[0:n, 0:n]
    weave = 0.5 + 0.5 * np.sin(2 * math.pi * x / 8) * np.sin(2 * math.pi * y / 8)
    fabric_base = mix((0.16, 0.24, 0.34), (0.24, 0.34, 0.46), weave * 0.7 + 0.3 * smooth_noise(rng, n, n, (8, 8)))
    fabric = material("fabric", roughness=0.9, base_tex=write_image(fabric_base, f"{textures}/fabric.png"),
                      normal_tex=write_image(normal_map(weave, 0.6), f"{textures}/fabric_normal.png", data=True))
    steel = material("steel_black", base=(0.04, 0.04, 0.045), metallic=1.0, roughness=0.45)
    border = (np.minimum(np.minimum(x, n - 1 - x), np.minimum(y, n - 1 - y)) < 24)
    diamond = ((np.abs(x - n / 2) + np.abs(y - n / 2)) % 64) < 20
    rug_base = np.empty((n, n, 3))
    rug_base[:] = (0.55, 0.16, 0.12)
    rug_base[diamond] = (0.85, 0.70, 0.45)
    rug_base[border] = (0.15, 0.12, 0.25)
    rug_base *= 0.85 + 0.3 * smooth_noise(rng, n, n, (16, 16))[..., None]
    rug = material("rug", roughness=0.95, base_tex=write_image(rug_base, f"{textures}/rug.png"), uv_scale=3.0)

    root = place("DiningSet", rotation=(0, 0, 10))
    place("rug", grid("rug", (2.6, 1.9), (1, 1), [rug]), root, location=(0, 0, 0.002))
    top = place("tabletop", box("tabletop", (1.6, 0.9, 0.04), [oak], bevel=0.006), root, location=(0, 0, 0.72))
    leg = box("table_leg", (0.06, 0.06, 0.72), [steel], bevel=0.004)
    for i, (sx, sy) in enumerate([(-1, -1), (1, -1), (1, 1), (-1, 1)]):
        place(f"table_leg.{i}", leg, top, location=(sx * 0.72, sy * 0.36, -0.72))

    # The chair: its back toward +y, the seat's front toward -y.
    parts = [box("seat", (0.44, 0.44, 0.03), [oak], bevel=0.004, at=(0, 0, 0.42)),
             box("cushion", (0.40, 0.40, 0.04), [fabric], bevel=0.012, segments=3, at=(0, -0.01, 0.45))]
    for sx, sy in [(-1, -1), (1, -1), (1, 1), (-1, 1)]:
        parts.append(box("chair_leg", (0.035, 0.035, 0.42), [oak], bevel=0.003, at=(sx * 0.2, sy * 0.2, 0)))
    for sx in (-1, 1):
        parts.append(box("post", (0.035, 0.035, 0.45), [oak], bevel=0.003, at=(sx * 0.2, 0.2, 0.45)))
    parts.append(box("rail", (0.44, 0.025, 0.14), [oak], bevel=0.004, at=(0, 0.2, 0.72)))
    # Underneath the seat, a strip of four quads whose middle vertex was
    # collapsed onto its neighbour.
    strip = grid("strip", (0.36, 0.04), (4, 1), [oak], collapse={(2, 0), (2, 1)})
    strip.transform(Matrix.Translation((0, 0.1, 0.419)) @ Matrix.Rotation(math.pi, 4, "X"))
    parts.append(strip)
    chair = join("chair", parts)
    for i, (location, turn, scale) in enumerate([((-0.4, -0.72, 0), 180, 1), ((0.42, -0.86, 0), 192, 1),
                                                 ((-0.4, 0.72, 0), 0, 1), ((0.4, 0.72, 0), 0, -1)]):
        place(f"chair.{i}", chair, root, location=location, rotation=(0, 0, turn), scale=(scale, 1, 1))


def crates(textures):
    # A warehouse corner seen from a camera, lit by a sun and a bulb (Blender's
    # watts, which the exporter converts to the lux and candela glTF asks for):
    # five crates of one mesh stacked and turned under one parent, a painted
    # barrel, a concrete floor whose textures share one texture transform and
    # whose grid has collapsed vertices.
    rng = np.random.default_rng(3)
    n = 512
    y, x = np.mgrid[0:n, 0:n]
    edge = np.minimum(np.minimum(x, n - 1 - x), np.minimum(y, n - 1 - y))
    frame = edge < 48
    plank_gap = (~frame) & ((y % 104) < 4)
    corner = (np.minimum(x, n - 1 - x) < 64) & (np.minimum(y, n - 1 - y) < 64)
    fibres = smooth_noise(rng, n, n, (64, 4), octaves=3)
    crate_base = mix((0.42, 0.30, 0.17), (0.62, 0.47, 0.28), fibres)
    crate_base[frame] *= 0.8
    crate_base[plank_gap] = (0.08, 0.05, 0.03)
    crate_base[corner] = (0.35, 0.36, 0.38)
    crate_height = np.where(frame, 1.0, 0.0) - 1.0 * plank_gap + 0.3 * fibres
    crate_mr = np.zeros((n, n, 3))
    crate_mr[..., 1] = 0.65 + 0.25 * fibres
    crate_mr[corner, 1], crate_mr[corner, 2] = 0.35, 1.0
    crate = material("crate", base_tex=write_image(crate_base, f"{textures}/crate_base.jpg"),
                     mr_tex=write_image(crate_mr[::2, ::2], f"{textures}/crate_mr.png", data=True),
                     normal_tex=write_image(normal_map(crate_height[::2, ::2], 1.5), f"{textures}/crate_normal.png",
                                            data=True))
    m = 256
    stains = smooth_noise(rng, m, m, (4, 4), octaves=5)
    concrete_base = mix((0.36, 0.36, 0.35), (0.58, 0.57, 0.55), stains)
    concrete_mr = np.zeros((m, m, 3))
    concrete_mr[..., 1] = 0.55 + 0.4 * stains
    pits = smooth_noise(rng, m, m, (32, 32), octaves=2)
    concrete = material("concrete", base_tex=write_image(concrete_base, f"{textures}/concrete_base.jpg"),
                        mr_tex=write_image(concrete_mr, f"{textures}/concrete_mr.png", data=True),
                        normal_tex=write_image(normal_map(pits, 2.0), f"{textures}/concrete_normal.png", data=True),
                        uv_scale=2.0)
    paint = material("barrel_paint", base=(0.08, 0.22, 0.45), roughness=0.35)

    place("floor", grid("floor", (6, 6), (12, 12), [concrete], collapse={(3, 4), (3, 5), (8, 2)}))
    stack = place("stack", location=(0.3, 0.4, 0), rotation=(0, 0, 15))
    mesh = box("crate", (0.6, 0.6, 0.6), [crate], bevel=0.01, bottom=False)
    for i, (location, turn, scale) in enumerate([((0, 0, 0.3), 0, 1), ((0.64, 0.05, 0.3), 8, 1),
                                                 ((0.3, 0.0, 0.9), -20, 1), ((-0.62, -0.45, 0.18), 40, 0.6),
                                                 ((-0.7, 0.55, 0.24), 70, 0.8)]):
        place(f"crate.{i}", mesh, stack, location=location, rotation=(0, 0, turn), scale=(scale,) * 3)
    place("barrel", cylinder("barrel", 0.28, 0.85, [paint], segments=32), location=(1.55, -0.5, 0))

    camera_at(Vector((2.6, -3.6, 1.7)), Vector((0.25, 0.2, 0.45)), 45)

    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 3.0
    place("sun", sun, location=(0, 0, 5), rotation=(40, 0, 30))
    bulb = bpy.data.lights.new("bulb", "POINT")
    bulb.energy = 60.0
    bulb.color = (1.0, 0.85, 0.6)
    place("bulb", bulb, location=(-1.2, -1.0, 2.2))


def lathe(name, profile, segments, materials):
    # A surface of revolution about z of (radius, z) points, UVs around and along
    # it, one seam of doubled vertices; a profile point of radius 0 leaves a ring
    # of coincident vertices, as a spin in Blender does, and zero-area triangles.
    length = [0.0]
    for (r0, z0), (r1, z1) in zip(profile, profile[1:]):
        length.append(length[-1] + math.hypot(r1 - r0, z1 - z0))
    bm = bmesh.new()
    layer = bm.loops.layers.uv.verify()
    rings = [[bm.verts.new((r * math.cos(2 * math.pi * k / segments), r * math.sin(2 * math.pi * k / segments), z))
              for k in range(segments + 1)] for r, z in profile]
    for j in range(len(profile) - 1):
        for k in range(segments):
            quad = [rings[j][k], rings[j][k + 1], rings[j + 1][k + 1], rings[j + 1][k]]
            uvs = [(k / segments, length[j] / length[-1]), ((k + 1) / segments, length[j] / length[-1]),
                   ((k + 1) / segments, length[j + 1] / length[-1]), (k / segments, length[j + 1] / length[-1])]
            face = bm.faces.new(quad)
            for loop, uv in zip(face.loops, uvs):
                loop[layer].uv = uv
    # The seam's doubled vertices share positions: weld their normals as Blender
    # does for a mesh whose seam is only a UV seam.
    bmesh.ops.remove_doubles(bm, verts=[ring[0] for ring in rings] + [ring[-1] for ring in rings], dist=1e-7)
    return finish(bm, name, materials, smooth_angle=60)


def vase(textures):
    # A glazed vase on a marble pedestal seen from a camera in portrait, no lights
    # and no emission: a lathed mesh of about 9,000 triangles whose ends are
    # rings collapsed onto the axis (outside and in), a crackle normal map, and the tangents the
    # exporter writes when asked (which vkrt does not read).
    rng = np.random.default_rng(4)
    n = 512
    y, x = np.mgrid[0:n, 0:n]
    v = 1 - y / n
    glaze = mix((0.36, 0.22, 0.12), (0.45, 0.62, 0.52), np.clip((v - 0.15) * 2.5, 0, 1))
    band = (np.abs(v - 0.55) < 0.03) | (np.abs(v - 0.47) < 0.008)
    wave = np.abs(v - 0.51 - 0.02 * np.sin(2 * math.pi * x / n * 12)) < 0.006
    glaze[band | wave] = (0.12, 0.16, 0.32)
    glaze *= 0.9 + 0.2 * smooth_noise(rng, n, n, (8, 8))[..., None]
    cells = smooth_noise(rng, 256, 256, (24, 24), octaves=1)
    crackle = np.clip(1 - np.abs(cells - 0.5) * 40, 0, 1)
    ceramic = material("glaze", roughness=0.12, base_tex=write_image(glaze, f"{textures}/glaze.jpg"),
                       normal_tex=write_image(normal_map(-crackle, 0.8), f"{textures}/crackle_normal.png",
                                              data=True))
    m = 256
    warp = smooth_noise(rng, m, m, (3, 3), octaves=5)
    veins = np.abs(np.sin(2 * math.pi * (np.mgrid[0:m, 0:m][1] / m * 2 + 4 * warp)))
    marble_base = mix((0.35, 0.34, 0.33), (0.92, 0.91, 0.88), np.clip(veins * 1.6, 0, 1))
    marble = material("marble", roughness=0.25, base_tex=write_image(marble_base, f"{textures}/marble.jpg"))

    profile = [(0.0, 0.0), (0.065, 0.0), (0.07, 0.004)]
    for k in range(1, 57):
        t = k / 56
        r = 0.055 + 0.09 * math.exp(-((t - 0.33) / 0.24) ** 2) - 0.012 * t + 0.022 * math.exp(-((t - 1) / 0.07) ** 2)
        profile.append((r, 0.004 + 0.44 * t))
    lip_r, lip_z = profile[-1]
    profile += [(lip_r - 0.006, lip_z), (lip_r - 0.008, lip_z - 0.03), (0.0, lip_z - 0.05)]
    root = place("Display", rotation=(0, 0, 0))
    pedestal = place("pedestal", box("pedestal", (0.32, 0.32, 0.6), [marble], bevel=0.01), root)
    place("vase", lathe("vase", profile, 72, [ceramic]), pedestal, location=(0, 0, 0.6), rotation=(0, 0, 30))

    camera_at(Vector((0.9, -1.5, 1.25)), Vector((0, 0, 0.72)), 35)
    bpy.context.scene.render.resolution_x, bpy.context.scene.render.resolution_y = 600, 800


def sign(textures):
    # A glowing shop sign on a brick wall at dusk, seen from a camera under a dim
    # sun: one material whose textures read two mappings. The bricks (base colour and
    # normal map) repeat four times through a Mapping node (KHR_texture_transform on
    # TEXCOORD_0); the sign's glow, an emission texture black but for its tubes, lies
    # on a second UV map, "decal", that frames the sign alone and runs past [0, 1]
    # elsewhere, where the image's black edge is extended (TEXCOORD_1, clamped).
    rng = np.random.default_rng(5)
    n = 256
    y, x = np.mgrid[0:n, 0:n]
    offset = (y // 32 % 2) * 32
    mortar = ((y % 32) < 3) | (((x + offset) % 64) < 3)
    tone = smooth_noise(rng, n, n, (8, 4), octaves=3)
    brick_base = mix((0.38, 0.14, 0.09), (0.58, 0.26, 0.16), tone)
    brick_base[mortar] = (0.55, 0.53, 0.5)
    height = np.where(mortar, 0.0, 1.0) + 0.15 * smooth_noise(rng, n, n, (32, 32), octaves=2)
    h, w = 128, 512
    gy, gx = np.mgrid[0:h, 0:w]
    inner = (gx >= 14) & (gx < w - 14) & (gy >= 14) & (gy < h - 14)
    outer = (gx >= 8) & (gx < w - 8) & (gy >= 8) & (gy < h - 8)
    tubes = (outer & ~inner).astype(float)
    for k in range(4):
        cx = 96 + 107 * k
        tubes = np.maximum(tubes, disc(h, w, 64, cx, 30) - disc(h, w, 64, cx, 23))
    glow = tubes[..., None] * np.array([1.0, 0.32, 0.55])
    wall = material("brick_wall", roughness=0.85, base_tex=write_image(brick_base, f"{textures}/bricks.jpg"),
                    normal_tex=write_image(normal_map(height, 3.0), f"{textures}/bricks_normal.png", data=True),
                    uv_scale=4.0)
    tree = wall.node_tree
    decal = tree.nodes.new("ShaderNodeUVMap")
    decal.uv_map = "decal"
    glow_node = tree.nodes.new("ShaderNodeTexImage")
    glow_node.image = write_image(glow, f"{textures}/sign_glow.png")
    glow_node.extension = "EXTEND"
    tree.links.new(decal.outputs["UV"], glow_node.inputs["Vector"])
    bsdf = tree.nodes["Principled BSDF"]
    tree.links.new(glow_node.outputs["Color"], bsdf.inputs["Emission"])
    bsdf.inputs["Emission Strength"].default_value = 8.0
    pavement = material("pavement", base=(0.3, 0.3, 0.32), roughness=0.9)

    # The wall stands in x, z (the grid's y turned up); the sign spans x from -1 to
    # 1 and the grid's y from 0.35 to 0.85 (the image's 4:1).
    mesh = grid("wall", (4, 2.5), (8, 5), [wall])
    layer = mesh.uv_layers.new(name="decal")
    for loop in mesh.loops:
        co = mesh.vertices[loop.vertex_index].co
        layer.data[loop.index].uv = ((co.x + 1.0) / 2.0, (co.y - 0.35) / 0.5)
    place("wall", mesh, location=(0, 0, 1.25), rotation=(90, 0, 0))
    place("pavement", grid("pavement", (6, 3), (6, 3), [pavement]), location=(0, -1.5, 0))

    camera_at(Vector((1.2, -4.2, 1.3)), Vector((0, 0, 1.3)), 40)
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 0.5
    place("sun", sun, location=(0, 0, 5), rotation=(50, 0, -40))


def main():
    args = arguments()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = 800, 600
    textures = tempfile.mkdtemp(prefix="vkrt-gltf-corpus-")
    {"radio": radio, "dining_set": dining_set, "crates": crates, "vase": vase, "sign": sign}[args.asset](textures)
    out = os.path.abspath(args.out)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    bpy.ops.export_scene.gltf(filepath=out, export_format="GLB" if out.endswith(".glb") else "GLTF_SEPARATE",
                              export_cameras=True, export_lights=True, export_apply=True, export_yup=True,
                              export_tangents=args.asset == "vase")
    shutil.rmtree(textures)


main()
