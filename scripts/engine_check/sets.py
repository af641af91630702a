# The materials and direction pairs the check runs: the Mat class, the random set and the edge set
# (grazing angles, roughness 0 and 1, each extension alone).
import math
from .common import f32, fmt


# ---------------------------------------------------------------------------------------------
# Materials and direction pairs.

class Mat:
    def __init__(self, **kw):
        self.base = [1.0, 1.0, 1.0]
        self.metallic = 1.0
        self.roughness = 1.0
        self.sheen = None  # (color, roughness)
        self.clearcoat = None  # (factor, roughness)
        self.anisotropy = None  # (strength, rotation)
        self.ior = None
        for k, v in kw.items():
            setattr(self, k, v)

    def gltf(self):
        m = {"pbrMetallicRoughness": {"baseColorFactor": [fmt(c) for c in self.base] + ["1"],
                                      "metallicFactor": fmt(self.metallic),
                                      "roughnessFactor": fmt(self.roughness)}}
        ext = {}
        if self.sheen is not None:
            ext["KHR_materials_sheen"] = {"sheenColorFactor": [fmt(c) for c in self.sheen[0]],
                                          "sheenRoughnessFactor": fmt(self.sheen[1])}
        if self.clearcoat is not None:
            ext["KHR_materials_clearcoat"] = {"clearcoatFactor": fmt(self.clearcoat[0]),
                                              "clearcoatRoughnessFactor": fmt(self.clearcoat[1])}
        if self.anisotropy is not None:
            ext["KHR_materials_anisotropy"] = {"anisotropyStrength": fmt(self.anisotropy[0]),
                                               "anisotropyRotation": fmt(self.anisotropy[1])}
        if self.ior is not None:
            ext["KHR_materials_ior"] = {"ior": fmt(self.ior)}
        if ext:
            m["extensions"] = ext
        return m

    def line(self):
        sh = self.sheen or ([0.0, 0.0, 0.0], 0.0)
        cc = self.clearcoat or (0.0, 0.0)
        an = self.anisotropy or (0.0, 0.0)
        vals = [int(self.sheen is not None), int(self.clearcoat is not None), int(self.anisotropy is not None),
                int(self.ior is not None)] + self.base + [self.metallic, self.roughness] + list(sh[0]) + \
            [sh[1], cc[0], cc[1], an[0], math.cos(an[1]), math.sin(an[1]), 1.5 if self.ior is None else self.ior]
        return " ".join(str(v) if isinstance(v, int) else fmt(f32(v)) for v in vals)

    def short(self):
        s = "b=(%s) m=%s r=%s" % (",".join("%.3g" % c for c in self.base), "%.3g" % self.metallic,
                                  "%.3g" % self.roughness)
        if self.sheen is not None:
            s += " sheen=(%s;%.3g)" % (",".join("%.3g" % c for c in self.sheen[0]), self.sheen[1])
        if self.clearcoat is not None:
            s += " cc=(%.3g;%.3g)" % self.clearcoat
        if self.anisotropy is not None:
            s += " aniso=(%.3g;%.3g)" % self.anisotropy
        if self.ior is not None:
            s += " ior=%.4g" % self.ior
        return s


def rf(rng, lo=0.0, hi=1.0):
    return f32(rng.uniform(lo, hi))


def random_set(rng, nmat, per):
    mats, pairs = [], []
    for i in range(nmat):
        m = Mat(base=[rf(rng) for _ in range(3)], metallic=rng.choice([0.0, 1.0, rf(rng)]), roughness=rf(rng))
        if rng.random() < 0.5:
            m.sheen = ([rf(rng) for _ in range(3)], rf(rng))
        if rng.random() < 0.5:
            m.clearcoat = (rf(rng), rf(rng))
        if rng.random() < 0.35:
            m.anisotropy = (rf(rng), rf(rng, 0.0, 2 * math.pi))
        if rng.random() < 0.5:
            m.ior = rf(rng, 1.0, 2.5)
        mats.append(m)
        for _ in range(per):
            pairs.append((i, hemisphere(rng), hemisphere(rng)))
    return mats, pairs


def hemisphere(rng, z=None):
    if z is None:
        z = rng.uniform(0.02, 1.0)
    phi = rng.uniform(0.0, 2 * math.pi)
    s = math.sqrt(max(0.0, 1.0 - z * z))
    return (f32(s * math.cos(phi)), f32(s * math.sin(phi)), f32(z))


def edge_set(rng):
    """Roughness 0 to 0.02, cosines down to 1e-6, strength 0 with the extension present, sheen
    roughness below 0.07, IOR 1.0 to 2.5."""
    mats = []
    for r in [0.0, 1e-4, 0.005, 0.01, 0.02]:
        for metal in [0.0, 1.0]:
            mats.append(Mat(base=[0.8, 0.5, 0.2], metallic=metal, roughness=r))
            mats.append(Mat(base=[0.8, 0.5, 0.2], metallic=metal, roughness=r, anisotropy=(0.0, 0.0)))
            mats.append(Mat(base=[0.8, 0.5, 0.2], metallic=metal, roughness=r, anisotropy=(1.0, 0.7)))
            mats.append(Mat(base=[0.8, 0.5, 0.2], metallic=metal, roughness=r, clearcoat=(1.0, r)))
    for rs in [0.0, 1e-3, 0.01, 0.03, 0.0699]:
        mats.append(Mat(base=[0.3, 0.6, 0.9], metallic=0.0, roughness=0.5, sheen=([1.0, 0.8, 0.6], rs)))
    mats.append(Mat(base=[0.3, 0.6, 0.9], metallic=0.0, roughness=0.5, sheen=([0.0, 0.0, 0.0], 0.5)))
    mats.append(Mat(base=[0.3, 0.6, 0.9], metallic=0.0, roughness=0.5, clearcoat=(0.0, 0.3)))
    mats.append(Mat(base=[0.3, 0.6, 0.9], metallic=0.0, roughness=0.5, clearcoat=(0.0, 0.0),
                    sheen=([0.0, 0.0, 0.0], 0.0), anisotropy=(0.0, 0.0), ior=1.5))
    for ior in [1.0, 1.001, 1.33, 1.5, 2.0, 2.5]:
        mats.append(Mat(base=[0.5, 0.5, 0.5], metallic=0.0, roughness=0.3, ior=ior))
        mats.append(Mat(base=[0.5, 0.5, 0.5], metallic=0.0, roughness=0.3, ior=ior, clearcoat=(0.7, 0.2)))
    for m in mats:
        m.base = [f32(c) for c in m.base]
    cosines = [1e-6, 1e-4, 1e-2, 0.5, 1.0]
    pairs = []
    for i in range(len(mats)):
        pairs.append((i, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0)))  # N·H = 1
        for zl in cosines:
            for zv in cosines:
                L = hemisphere(rng, zl)
                pairs.append((i, L, hemisphere(rng, zv)))
            V = (-L[0], -L[1], L[2])  # mirror: N·H = 1 up to rounding
            pairs.append((i, L, V))
    return mats, pairs
