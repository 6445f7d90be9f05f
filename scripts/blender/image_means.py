# Prints "MEAN <file> <r> <g> <b> <all>" for each linear image given after "--",
# read by Blender (which reads OpenEXR without further packages), and for each image
# after the first, "BLOCKS <file> <fraction> <lit>": of the first image's lit 8 x 8
# blocks (mean over the block's pixels and channels at least a tenth of the first
# image's mean), how many `lit`, and the fraction whose mean in this image lies
# within 10% of the first's:
#   blender -b --factory-startup -P scripts/blender/image_means.py -- reference.exr a.exr b.exr
import sys

import bpy
import numpy as np


def load(path):
    image = bpy.data.images.load(path)
    w, h = image.size
    return np.array(image.pixels[:]).reshape(h, w, 4)[:, :, :3]


def block_means(pixels, side=8):
    h, w = (pixels.shape[0] // side) * side, (pixels.shape[1] // side) * side
    grey = pixels[:h, :w].mean(axis=2)
    return grey.reshape(h // side, side, w // side, side).mean(axis=(1, 3))


paths = sys.argv[sys.argv.index("--") + 1:]
images = [load(p) for p in paths]
for path, pixels in zip(paths, images):
    r, g, b = pixels.reshape(-1, 3).mean(axis=0)
    print(f"MEAN {path} {r:.6f} {g:.6f} {b:.6f} {pixels.mean():.6f}")
reference = block_means(images[0])
lit = reference >= 0.1 * images[0].mean()
for path, pixels in zip(paths[1:], images[1:]):
    blocks = block_means(pixels)
    within = np.abs(blocks - reference) <= 0.1 * reference
    print(f"BLOCKS {path} {within[lit].mean():.4f} {int(lit.sum())}")
