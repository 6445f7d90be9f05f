# Prints "MEAN <file> <r> <g> <b> <all>" for each linear image given after "--",
# read by Blender (which reads OpenEXR without further packages):
#   blender -b --factory-startup -P scripts/blender/image_means.py -- a.exr b.exr
import sys

import bpy
import numpy as np

for path in sys.argv[sys.argv.index("--") + 1:]:
    pixels = np.array(bpy.data.images.load(path).pixels[:]).reshape(-1, 4)[:, :3]
    r, g, b = pixels.mean(axis=0)
    print(f"MEAN {path} {r:.6f} {g:.6f} {b:.6f} {pixels.mean():.6f}")
