"""Rendering an asset: a glTF file (or the built-in spheres) to a linear float32 image, then a
quick sRGB preview with numpy. Usage: python render_asset.py [asset.gltf|asset.glb]"""
import sys

import numpy as np

import brdfcl

if len(sys.argv) > 1:
    image = brdfcl.render(gltf=sys.argv[1], size=(640, 360), spp=4, environment="studio")
else:
    image = brdfcl.render(size=(384, 384))  # the built-in sphere sweep
print("linear radiance", image.shape, image.dtype, "max", image.max())
srgb = np.where(image <= 0.0031308, 12.92 * image, 1.055 * np.power(np.clip(image, 0, None), 1 / 2.4) - 0.055)
np.save("render.npy", image)
print("saved render.npy; preview with matplotlib: plt.imshow(np.clip(srgb, 0, 1))")
