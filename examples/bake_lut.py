"""Baking a LUT: the split-sum GGX DFG table (A, B) for an engine, saved as .npy and as a C array.
lut[j, i] is the texel at N.V = i / (size - 1), roughness = j / (size - 1)."""
import numpy as np

import brdfcl

dfg = brdfcl.lut("ggx-dfg", size=64)  # float32 (64, 64, 2)
np.save("ggx_dfg.npy", dfg)
sheen = brdfcl.lut("sheen-e", size=64, sheen_visibility="ashikhmin")  # float32 (64, 64)
print("DFG at N.V = 1, roughness 0:", dfg[0, -1], "  sheen E range:", sheen.min(), sheen.max())
