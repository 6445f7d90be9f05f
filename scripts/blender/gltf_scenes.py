# Builds vkrt's glTF test scenes in Blender and writes them with Blender's own glTF
# exporter, so the files are what a user's exporter makes (docs/gltf.md). With
# --render it also renders the scene with Cycles, for the comparison in
# docs/measured/gltf_cycles.md.
#
#   blender -b --factory-startup --python-exit-code 1 -P scripts/blender/gltf_scenes.py -- \
#       --scene still_life --out scenes/gltf/still_life.glb [--render cycles.exr --spp 1024 [--runs 16]]
#
# Materials are Principled BSDFs set only through what glTF carries (base colour,
# metallic, roughness, emission, transmission, clear coat; Specular stays 0.5,
# glTF's 4% reflectance, but on the "layers" scene's plastic), and
# Cycles renders them as they are, with its multiple-scattering GGX, which vkrt's
# compensated GGX stands for (docs/decisions/0040-ggx-multiple-scattering.md; the
# diffuse lobes still differ, docs/decisions/0029-metallic-roughness.md); the
# world is the uniform grey of radiance 0.05 that vkrt puts behind a glTF file
# with lights of its own.
import argparse
import math
import os
import struct
import sys
import tempfile
import zlib

import bmesh
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_still import render_still  # noqa: E402


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser()
    p.add_argument("--scene", default="still_life", choices=["still_life", "metals", "leaves", "glass", "layers",
                                                                "water_glass", "velvet"])
    p.add_argument("--out", required=True)
    p.add_argument("--render", help="also render with Cycles to this .exr")
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--bounces", type=int, default=8, help="Cycles' bounces of every kind (vkrt's --bounces)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--runs", type=int, default=1,
                   help="render RUNS independent images of SPP / RUNS samples each, seeds SEED to SEED + RUNS - 1, "
                        "to RENDER with _0, _1, ... before its extension (for vkrt stack)")
    p.add_argument("--no-specular", action="store_true",
                   help="set every opaque dielectric's Specular to 0 before export and render (the exporter then "
                        "writes specularFactor 0): both renderers' dielectrics are then their diffuse lobes alone, "
                        "without Principled's specular layer added on top (docs/decisions/0040-ggx-multiple-scattering.md)")
    p.add_argument("--width", type=int, default=400)
    p.add_argument("--height", type=int, default=300)
    return p.parse_args(argv)


def principled(name, rgb, metallic=0.0, roughness=1.0, emission=None, strength=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.distribution = "MULTI_GGX"
    bsdf.inputs["Base Color"].default_value = (*rgb, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Sheen Tint"].default_value = 0.0
    if emission:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return m


def checker_png(path, squares=8, size=256, light=200, dark=60):
    # An 8-bit grey checkerboard PNG (ISO/IEC 15948), written here so that the
    # script needs nothing beyond Blender's own Python.
    side = size // squares
    rows = b"".join(b"\x00" + bytes(light if ((x // side) + (y // side)) % 2 == 0 else dark for x in range(size))
                    for y in range(size))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 0, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def textured(name, png, roughness):
    # A dielectric whose base colour is an image (sRGB), packed into the .blend so
    # that the exporter embeds it in the .glb.
    m = principled(name, (1, 1, 1), roughness=roughness)
    image = bpy.data.images.load(png)
    image.pack()
    node = m.node_tree.nodes.new("ShaderNodeTexImage")
    node.image = image
    m.node_tree.links.new(node.outputs["Color"], m.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    return m


def checker_floor(name="floor"):
    # An 8 x 8 floor of roughness 0.8 textured with the grey checkerboard, its squares 1 m.
    png = os.path.join(tempfile.mkdtemp(), "checker.png")
    checker_png(png)
    bpy.ops.mesh.primitive_plane_add(size=8, location=(0, 0, 0))
    give(bpy.context.object, textured(name, png, roughness=0.8))


def give(obj, material):
    obj.data.materials.clear()
    obj.data.materials.append(material)


def lamp():
    # A square lamp facing down: an emissive mesh, exported with its strength.
    bpy.ops.mesh.primitive_plane_add(size=1.2, location=(0, 0, 3), rotation=(math.pi, 0, 0))
    give(bpy.context.object, principled("lamp", (0, 0, 0), emission=(1, 1, 1), strength=12.0))


def lamp_and_camera():
    lamp()
    aim_camera((0, -5, 2.4), (0, 5, -1.9), 38)


def aim_camera(location, direction, degrees_high):
    # A camera at `location` looking along `direction` (in the y-z plane), its
    # vertical field of view `degrees_high`.
    bpy.ops.object.camera_add(location=location)
    cam = bpy.context.object
    cam.rotation_euler = (math.atan2(math.hypot(direction[0], direction[1]), -direction[2]), 0, 0)
    cam.data.sensor_fit = "VERTICAL"
    cam.data.angle_y = math.radians(degrees_high)
    bpy.context.scene.camera = cam


def still_life():
    # Blender is z-up; the exporter turns it into glTF's y-up.
    bpy.ops.mesh.primitive_plane_add(size=8, location=(0, 0, 0))
    give(bpy.context.object, principled("ground", (0.7, 0.7, 0.7)))
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=0.6, location=(-0.5, 0.2, 0.6))
    bpy.ops.object.shade_smooth()
    give(bpy.context.object, principled("orange", (0.8, 0.35, 0.1)))
    bpy.ops.mesh.primitive_cube_add(size=0.8, location=(0.8, -0.3, 0.4), rotation=(0, 0, math.radians(30)))
    give(bpy.context.object, principled("blue", (0.15, 0.3, 0.75)))
    lamp_and_camera()


def metals():
    # Gold, steel and red plastic spheres of three roughnesses on a rough floor
    # textured with a checkerboard of 1 m squares.
    checker_floor()
    for x, name, rgb, metallic, roughness in [(-1.3, "gold", (1.0, 0.78, 0.34), 1.0, 0.3),
                                              (0.0, "steel", (0.8, 0.8, 0.8), 1.0, 0.6),
                                              (1.3, "plastic", (0.7, 0.1, 0.1), 0.0, 0.4)]:
        bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=0.55, location=(x, 0.2, 0.55))
        bpy.ops.object.shade_smooth()
        give(bpy.context.object, principled(name, rgb, metallic=metallic, roughness=roughness))
    lamp_and_camera()


def leaf_png(path, size=256):
    # An 8-bit RGBA PNG of one leaf: an ellipse pointed at both ends, green shading
    # toward its rim, a pale midrib; alpha 255 inside, 0 outside (a cut-out).
    rows = bytearray()
    for y in range(size):
        rows.append(0)
        v = (y + 0.5) / size * 2 - 1
        for x in range(size):
            u = (x + 0.5) / size * 2 - 1
            half_width = 0.45 * (1 - v * v) ** 0.8
            inside = abs(v) < 0.96 and abs(u) < half_width
            rim = min(abs(u) / half_width, 1.0) if half_width > 0 else 1.0
            rib = abs(u) < 0.025 and inside
            r, g, b = (150, 190, 90) if rib else (int(40 + 30 * rim), int(120 + 40 * (1 - rim)), int(30 + 10 * rim))
            rows += bytes((r, g, b, 255 if inside else 0))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 6, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b""))


def cut_out(name, png, roughness):
    # A dielectric whose base colour and alpha are an RGBA image, in Blender's
    # "Alpha Clip" blend mode: the exporter writes alphaMode MASK, alphaCutoff 0.5.
    m = textured(name, png, roughness)
    image_node = m.node_tree.nodes["Image Texture"]
    m.node_tree.links.new(image_node.outputs["Alpha"], m.node_tree.nodes["Principled BSDF"].inputs["Alpha"])
    m.blend_method = "CLIP"
    m.alpha_threshold = 0.5
    m.shadow_method = "CLIP"
    return m


def threshold_alpha_for_cycles():
    # Cycles ignores a material's blend mode and takes any alpha as partial
    # transparency; glTF's MASK (and EEVEE's Alpha Clip) is opaque where the alpha
    # reaches the cutoff and absent elsewhere. After the export, each clipped
    # material's alpha goes through that step for Cycles: alpha >= threshold.
    for m in bpy.data.materials:
        if m.blend_method != "CLIP" or not m.use_nodes:
            continue
        tree = m.node_tree
        bsdf = tree.nodes["Principled BSDF"]
        source = bsdf.inputs["Alpha"].links[0].from_socket
        step = tree.nodes.new("ShaderNodeMath")
        step.operation = "LESS_THAN"  # 1 where alpha < threshold: then 1 - that
        step.inputs[1].default_value = m.alpha_threshold
        tree.links.new(source, step.inputs[0])
        invert = tree.nodes.new("ShaderNodeMath")
        invert.operation = "SUBTRACT"
        invert.inputs[0].default_value = 1.0
        tree.links.new(step.outputs[0], invert.inputs[1])
        tree.links.new(invert.outputs[0], bsdf.inputs["Alpha"])


def leaves():
    # Cut-out leaves (alpha MASK) on a branch of planes over the ground, lit by the
    # sun (a delta light, angle 0: hard shadows) under the grey world, and a sheet
    # of red plastic at opacity 0.5 (alpha BLEND) that lets half the light through.
    png = os.path.join(tempfile.mkdtemp(), "leaf.png")
    leaf_png(png)
    bpy.ops.mesh.primitive_plane_add(size=8, location=(0, 0, 0))
    give(bpy.context.object, principled("ground", (0.6, 0.6, 0.55), roughness=0.5))
    leaf = cut_out("leaf", png, roughness=0.6)
    for x, y, z, tilt, turn, size in [(-1.0, 0.3, 1.3, 20, 10, 1.0), (-0.2, 0.0, 1.5, -15, 40, 1.1),
                                      (0.6, 0.4, 1.2, 30, -30, 0.9), (0.2, -0.5, 1.0, 10, 80, 0.8),
                                      (-0.6, -0.4, 1.7, -25, -60, 1.0), (1.2, -0.2, 1.6, 15, 20, 1.0)]:
        bpy.ops.mesh.primitive_plane_add(size=size, location=(x, y, z),
                                         rotation=(math.radians(tilt), 0, math.radians(turn)))
        give(bpy.context.object, leaf)
    sheet = principled("sheet", (0.8, 0.1, 0.1), roughness=0.5)
    sheet.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = 0.5
    sheet.blend_method = "BLEND"
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(1.6, 1.2, 0.8), rotation=(0, math.radians(-20), 0))
    give(bpy.context.object, sheet)
    bpy.ops.object.light_add(type="SUN", location=(0, 0, 5), rotation=(math.radians(30), math.radians(15), 0))
    sun = bpy.context.object
    sun.data.energy = 4.0
    sun.data.angle = 0.0
    aim_camera((0, -5.5, 3.2), (0, 5.5, -2.4), 40)


def glass(name, rgb, ior, thickness, roughness=0.0):
    # Glass (Principled transmission 1, smooth by default). The exporter writes
    # KHR_materials_transmission and KHR_materials_ior, and KHR_materials_volume, which
    # makes the glass a solid that refracts as Cycles' does, from the Thickness of a
    # "glTF Material Output" node group (the exporter's own convention).
    m = principled(name, rgb, roughness=roughness)
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Transmission"].default_value = 1.0
    bsdf.inputs["Transmission Roughness"].default_value = roughness
    bsdf.inputs["IOR"].default_value = ior
    group = bpy.data.node_groups.get("glTF Material Output")
    if group is None:
        group = bpy.data.node_groups.new("glTF Material Output", "ShaderNodeTree")
        group.inputs.new("NodeSocketFloat", "Thickness")
    node = m.node_tree.nodes.new("ShaderNodeGroup")
    node.node_tree = group
    node.inputs["Thickness"].default_value = thickness
    return m


def glasses():
    # A clear glass sphere and a green glass block on the checkerboard floor, under
    # the lamp: refraction, Fresnel reflection and the light they focus.
    checker_floor()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.6, location=(-0.6, 0.2, 0.6))
    bpy.ops.object.shade_smooth()
    give(bpy.context.object, glass("clear", (1.0, 1.0, 1.0), 1.5, 1.2))
    # The block stands 1 mm above the floor: a face on the floor's plane would leave
    # each renderer to pick one of two surfaces at the same distance.
    bpy.ops.mesh.primitive_cube_add(size=0.8, location=(0.8, -0.2, 0.401), rotation=(0, 0, math.radians(25)))
    give(bpy.context.object, glass("green", (0.6, 0.9, 0.6), 1.45, 0.8))
    lamp_and_camera()


def layers():
    # The layers over a dielectric that glTF's extensions carry, on the checkerboard
    # floor under the lamp: red car paint under a clear coat (Principled Clearcoat 1,
    # Clearcoat Roughness 0.05: KHR_materials_clearcoat), a frosted glass sphere
    # (roughness 0.3: rough KHR_materials_transmission, solid), and a blue plastic
    # whose Specular 1 and Specular Tint 0.5 the exporter writes as
    # KHR_materials_specular (with KHR_materials_ior 1.45, Principled's default IOR).
    checker_floor()
    paint = principled("car_paint", (0.5, 0.02, 0.02), metallic=0.5, roughness=0.4)
    paint.node_tree.nodes["Principled BSDF"].inputs["Clearcoat"].default_value = 1.0
    paint.node_tree.nodes["Principled BSDF"].inputs["Clearcoat Roughness"].default_value = 0.05
    plastic = principled("tinted_plastic", (0.1, 0.25, 0.7), roughness=0.3)
    plastic.node_tree.nodes["Principled BSDF"].inputs["Specular"].default_value = 1.0
    plastic.node_tree.nodes["Principled BSDF"].inputs["Specular Tint"].default_value = 0.5
    for x, material in [(-1.3, paint), (0.0, glass("frosted", (1.0, 1.0, 1.0), 1.5, 1.1, roughness=0.3)),
                        (1.3, plastic)]:
        bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.55, location=(x, 0.2, 0.55))
        bpy.ops.object.shade_smooth()
        give(bpy.context.object, material)
    lamp_and_camera()


def velvet(name, base, sheen, sigma):
    # Cloth as Blender's glTF exporter reads it (io_scene_gltf2 3.4): a Principled
    # BSDF for the base (dielectric, roughness 1) plus a Velvet BSDF, added, whose
    # colour and sigma the exporter writes as KHR_materials_sheen's sheenColorFactor
    # and sheenRoughnessFactor, the shape its importer builds from the extension.
    m = principled(name, base, roughness=1.0)
    nodes, links = m.node_tree.nodes, m.node_tree.links
    cloth = nodes.new("ShaderNodeBsdfVelvet")
    cloth.inputs["Color"].default_value = (*sheen, 1.0)
    cloth.inputs["Sigma"].default_value = sigma
    add = nodes.new("ShaderNodeAddShader")
    links.new(add.inputs[0], nodes["Principled BSDF"].outputs[0])
    links.new(add.inputs[1], cloth.outputs[0])
    links.new(nodes["Material Output"].inputs["Surface"], add.outputs[0])
    return m


def velvets():
    # Three cloth-covered spheres on the checkerboard floor under the lamp: deep red
    # under a pink sheen of roughness 0.5, navy under a white sheen of 0.3, and a
    # white base under a narrow gold sheen of 0.15, where the sheen shows at the rims.
    checker_floor()
    for x, material in [(-1.3, velvet("red_velvet", (0.3, 0.02, 0.05), (0.8, 0.3, 0.4), 0.5)),
                        (0.0, velvet("navy_velvet", (0.02, 0.03, 0.15), (1.0, 1.0, 1.0), 0.3)),
                        (1.3, velvet("white_velvet", (0.8, 0.8, 0.8), (1.0, 0.8, 0.3), 0.15))]:
        bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.55, location=(x, 0.2, 0.55))
        bpy.ops.object.shade_smooth()
        give(bpy.context.object, material)
    lamp_and_camera()


def without_specular():
    # Specular 0 on every Principled BSDF that is neither metal nor glass.
    for m in bpy.data.materials:
        if not m.use_nodes:
            continue
        for node in m.node_tree.nodes:
            if node.type == "BSDF_PRINCIPLED" and node.inputs["Metallic"].default_value == 0.0 and \
                    node.inputs["Transmission"].default_value == 0.0:
                node.inputs["Specular"].default_value = 0.0


def cylinder(radius, depth, bottom, open_top=False):
    # A smooth-shaded cylinder of 64 sides standing on z = bottom, its rims sharp
    # (auto smooth: the exporter writes the split normals), its top face removed when
    # open_top.
    bpy.ops.mesh.primitive_cylinder_add(vertices=64, radius=radius, depth=depth,
                                        location=(0, 0.2, bottom + depth / 2))
    obj = bpy.context.object
    if open_top:
        bm = bmesh.new()
        bm.from_mesh(obj.data)
        top = max(bm.faces, key=lambda f: f.calc_center_median().z)
        bmesh.ops.delete(bm, geom=[top], context="FACES_ONLY")
        bm.to_mesh(obj.data)
        bm.free()
    bpy.ops.object.shade_smooth()
    obj.data.use_auto_smooth = True
    obj.data.auto_smooth_angle = math.radians(30)
    return obj


def water_glass():
    # A glass of water on the checkerboard table under the lamp: a tumbler (an open
    # cylinder that Blender's Solidify modifier gives walls and a bottom 0.04 thick,
    # glass of ior 1.5) holding water (ior 1.33) to two thirds of its height. The
    # water stands 0.002 clear of the glass on every side: glTF has no nesting of
    # media, so each surface meets air in both renderers (a water-glass interface
    # would need the ratio of the two indices on one surface).
    checker_floor("table")
    wall = 0.04
    tumbler = cylinder(0.45, 1.0, 0.001, open_top=True)
    solid = tumbler.modifiers.new("walls", "SOLIDIFY")
    solid.thickness = wall
    solid.offset = -1.0
    solid.use_even_offset = True
    give(tumbler, glass("tumbler", (1.0, 1.0, 1.0), 1.5, wall))
    water = cylinder(0.45 - wall - 0.002, 0.6, 0.001 + wall + 0.002)
    give(water, glass("water", (0.9, 0.96, 1.0), 1.33, 0.8))
    lamp()
    aim_camera((0, -3.0, 1.5), (0, 3.2, -1.05), 30)  # closer than the others': the glass fills more of it


def main():
    args = arguments()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x = args.width
    scene.render.resolution_y = args.height
    world = bpy.data.worlds.new("grey")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.05, 0.05, 0.05, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world
    {"still_life": still_life, "metals": metals, "leaves": leaves, "glass": glasses, "layers": layers,
     "water_glass": water_glass, "velvet": velvets}[args.scene]()
    if args.no_specular:
        without_specular()
    bpy.ops.export_scene.gltf(filepath=args.out, export_format="GLB", export_cameras=True, export_lights=True,
                              export_apply=True, export_yup=True)
    if args.render:
        threshold_alpha_for_cycles()
        if args.runs == 1:
            render_still(scene, args.render, args.spp, bounces=args.bounces, seed=args.seed)
        else:
            stem, extension = os.path.splitext(args.render)
            for k in range(args.runs):
                render_still(scene, f"{stem}_{k}{extension}", args.spp // args.runs, bounces=args.bounces,
                             seed=args.seed + k)


main()
