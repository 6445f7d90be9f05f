"""Checks that Cycles maps an equirectangular environment image as vkrt does
(kernel/environment.glsl): an 8 x 4 image whose texel (x, y) holds (x, y, 0) is
looked at along vkrt's +x, +z and -z (Blender +X, -Y, +Y) through a 0.5-degree
camera; vkrt sees positions (3.5, 1.5), (5.5, 1.5), (1.5, 1.5) there.

    blender -b --factory-startup --python scripts/blender/equirect_mapping.py | grep RESULT
"""
import bpy, math
W, H = 8, 4
img = bpy.data.images.new("pos", W, H, float_buffer=True)
px = []
# Blender's pixel rows run from the bottom; our texel (x, y) counts rows from the top.
for by in range(H):
    y = H - 1 - by
    for x in range(W):
        px += [float(x), float(y), 0.0, 1.0]
img.pixels = px
img.filepath_raw = "/tmp/vkrt_equirect_pos.exr"
img.file_format = 'OPEN_EXR'
img.save()
scene = bpy.context.scene
for o in list(scene.objects):
    bpy.data.objects.remove(o)
world = bpy.data.worlds.new("w"); scene.world = world; world.use_nodes = True
nt = world.node_tree
env = nt.nodes.new("ShaderNodeTexEnvironment"); env.image = img; env.interpolation = 'Linear'
bg = nt.nodes["Background"]
nt.links.new(env.outputs["Color"], bg.inputs["Color"])
cam_data = bpy.data.cameras.new("c"); cam_data.angle = math.radians(0.5)
cam = bpy.data.objects.new("c", cam_data); scene.collection.objects.link(cam); scene.camera = cam
scene.render.engine = 'CYCLES'; scene.cycles.samples = 1; scene.cycles.device = 'CPU'; scene.cycles.use_denoising = False
scene.render.resolution_x = 1; scene.render.resolution_y = 1; scene.render.filter_size = 0.01
scene.view_settings.view_transform = 'Standard'
scene.render.image_settings.file_format = 'OPEN_EXR'
# Blender direction of glTF/vkrt +x is +X; vkrt +z is Blender -Y; vkrt +y is Blender +Z.
for name, rot in [("+x", (math.pi/2, 0, -math.pi/2)), ("+z(vkrt)=-Y", (math.pi/2, 0, math.pi)), ("-z(vkrt)=+Y", (math.pi/2, 0, 0))]:
    cam.rotation_euler = rot
    scene.render.filepath = "/tmp/vkrt_equirect_out.exr"
    bpy.ops.render.render(write_still=True)
    r = bpy.data.images.load("/tmp/vkrt_equirect_out.exr", check_existing=False)
    print("RESULT", name, list(r.pixels)[:3])
