# A white furnace for Blender's Principled BSDF, to compare its dielectric lobes with
# vkrt's (docs/decisions/0040-ggx-multiple-scattering.md): a sphere of base colour 1,
# metallic 0, under a uniform world of radiance 1, seen by an orthographic camera.
# A convex body in a uniform world returns at each pixel its directional albedo at
# that view angle: 1 where a material reflects all the light it gets and no more.
# Prints "FURNACE <roughness> <albedo at the centre> <mean over the disc>".
#
#   blender -b --factory-startup --python-exit-code 1 -P scripts/blender/principled_furnace.py -- \
#       --roughness 0.5 1.0 --spp 256
import argparse
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_still import render_still  # noqa: E402


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser()
    p.add_argument("--roughness", type=float, nargs="+", default=[0.5, 1.0])
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--out", default="/tmp/principled_furnace.exr")
    return p.parse_args(argv)


def furnace(roughness, args):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    world = bpy.data.worlds.new("white")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
    scene.world = world
    bpy.ops.mesh.primitive_uv_sphere_add(segments=128, ring_count=64, radius=1.0)
    bpy.ops.object.shade_smooth()
    m = bpy.data.materials.new("white")
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.distribution = "MULTI_GGX"
    bsdf.inputs["Base Color"].default_value = (1, 1, 1, 1)
    bsdf.inputs["Metallic"].default_value = 0.0
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Sheen Tint"].default_value = 0.0
    bpy.context.object.data.materials.append(m)
    bpy.ops.object.camera_add(location=(0, -5, 0), rotation=(np.pi / 2, 0, 0))
    cam = bpy.context.object
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = 2.0
    scene.camera = cam
    scene.render.resolution_x = scene.render.resolution_y = args.size
    render_still(scene, args.out, args.spp, bounces=64)
    image = bpy.data.images.load(args.out)
    pixels = np.array(image.pixels[:]).reshape(args.size, args.size, 4)[:, :, :3].mean(axis=2)
    c = args.size // 2
    centre = pixels[c - 2:c + 2, c - 2:c + 2].mean()
    y, x = np.mgrid[0:args.size, 0:args.size]
    r = np.hypot(x + 0.5 - c, y + 0.5 - c) / c
    print(f"FURNACE {roughness} {centre:.4f} {pixels[r < 0.95].mean():.4f}")


args = arguments()
for roughness in args.roughness:
    furnace(roughness, args)
