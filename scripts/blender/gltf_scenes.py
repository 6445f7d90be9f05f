# Builds vkrt's glTF test scenes in Blender and writes them with Blender's own glTF
# exporter, so the files are what a user's exporter makes (docs/gltf.md). With
# --render it also renders the scene with Cycles, for the comparison in
# docs/measured/gltf_cycles.md.
#
#   blender -b --factory-startup --python-exit-code 1 -P scripts/blender/gltf_scenes.py -- \
#       --scene still_life --out scenes/gltf/still_life.glb [--render cycles.exr --spp 1024]
#
# Materials are Principled BSDFs set only through what glTF carries (base colour,
# metallic, roughness, emission; Specular stays 0.5, glTF's 4% reflectance), and
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

import bpy


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser()
    p.add_argument("--scene", default="still_life", choices=["still_life", "metals"])
    p.add_argument("--out", required=True)
    p.add_argument("--render", help="also render with Cycles to this .exr")
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--seed", type=int, default=0)
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


def give(obj, material):
    obj.data.materials.clear()
    obj.data.materials.append(material)


def lamp_and_camera():
    # A square lamp facing down: an emissive mesh, exported with its strength.
    bpy.ops.mesh.primitive_plane_add(size=1.2, location=(0, 0, 3), rotation=(math.pi, 0, 0))
    give(bpy.context.object, principled("lamp", (0, 0, 0), emission=(1, 1, 1), strength=12.0))
    bpy.ops.object.camera_add(location=(0, -5, 2.4))
    cam = bpy.context.object
    direction = (0, 5, -1.9)
    cam.rotation_euler = (math.atan2(math.hypot(direction[0], direction[1]), -direction[2]), 0, 0)
    cam.data.sensor_fit = "VERTICAL"
    cam.data.angle_y = math.radians(38)
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
    png = os.path.join(tempfile.mkdtemp(), "checker.png")
    checker_png(png)
    bpy.ops.mesh.primitive_plane_add(size=8, location=(0, 0, 0))
    give(bpy.context.object, textured("floor", png, roughness=0.8))
    for x, name, rgb, metallic, roughness in [(-1.3, "gold", (1.0, 0.78, 0.34), 1.0, 0.3),
                                              (0.0, "steel", (0.8, 0.8, 0.8), 1.0, 0.6),
                                              (1.3, "plastic", (0.7, 0.1, 0.1), 0.0, 0.4)]:
        bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=0.55, location=(x, 0.2, 0.55))
        bpy.ops.object.shade_smooth()
        give(bpy.context.object, principled(name, rgb, metallic=metallic, roughness=roughness))
    lamp_and_camera()


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
    {"still_life": still_life, "metals": metals}[args.scene]()
    bpy.ops.export_scene.gltf(filepath=args.out, export_format="GLB", export_cameras=True, export_lights=True,
                              export_apply=True, export_yup=True)
    if args.render:
        scene.render.engine = "CYCLES"
        scene.cycles.device = "CPU"
        scene.cycles.samples = args.spp
        scene.cycles.seed = args.seed
        scene.cycles.use_adaptive_sampling = False
        scene.cycles.use_denoising = False
        scene.cycles.sample_clamp_direct = 0
        scene.cycles.sample_clamp_indirect = 0
        scene.cycles.filter_width = 1.0
        scene.cycles.max_bounces = 8
        scene.cycles.diffuse_bounces = 8
        scene.view_settings.view_transform = "Standard"
        scene.render.image_settings.file_format = "OPEN_EXR"
        scene.render.image_settings.color_depth = "32"
        scene.render.filepath = args.render
        bpy.ops.render.render(write_still=True)


main()
