# The Cycles settings vkrt's comparisons render with: CPU, no denoising, clamping,
# adaptive sampling or glossy filter (Filter Glossy roughens what follows a diffuse
# bounce, trading caustics for less noise), a box filter of one pixel, the Standard view (linear values
# out), a 32-bit OpenEXR still. Imported by the scripts beside it.
import bpy


def render_still(scene, path, spp, bounces, seed=0):
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = spp
    scene.cycles.seed = seed
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.sample_clamp_direct = 0
    scene.cycles.sample_clamp_indirect = 0
    scene.cycles.blur_glossy = 0.0
    scene.cycles.filter_width = 1.0
    scene.cycles.max_bounces = bounces
    scene.cycles.diffuse_bounces = bounces
    scene.cycles.glossy_bounces = bounces
    scene.cycles.transmission_bounces = bounces
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
