// Driver for three.js's WebGPU lighting model (PhysicalLightingModel.js and the BSDF files it
// imports, run as they are through the TSL stand-in): sets the material state as GLTFLoader and
// MeshPhysicalNodeMaterial set it for a glTF material, runs one directional light of intensity 1.
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import { join } from 'node:path';

export const LOBES = ['all', 'diffuse', 'specular', 'sheen', 'clearcoat'];

// The engine's modules the drivers run, from the checkout the harness names.
export async function loadEngine() {
  const src = process.env.EC_THREEJS_SRC;
  const load = async (p) => (await import(pathToFileURL(join(src, p)).href)).default;
  return {
    PhysicalLightingModel: await load('src/nodes/functions/PhysicalLightingModel.js'),
    getRoughness: await load('src/nodes/functions/material/getRoughness.js'),
    sheenClamp: JSON.parse(process.env.EC_THREEJS_SHEEN_CLAMP),
  };
}

// Materials (one line each) and pairs (material index, L, V, ...) as the harness writes them.
export function readInputs() {
  const rows = (f) => readFileSync(f, 'utf8').trim().split('\n').map((l) => l.trim().split(/\s+/).map(Number));
  return { mats: rows(process.env.EC_MATERIALS), pairs: rows(process.env.EC_PAIRS) };
}

export const formatRow = (row) => row.map((x) => (Number.isNaN(x) ? 'nan' : x === Infinity ? 'inf' : x === -Infinity ? '-inf' : x.toPrecision(9))).join(' ');

// The per-fragment state for material line m seen from V, and the lighting model
// MeshPhysicalNodeMaterial.setupLightingModel makes for it.
export function setupMaterial(tsl, engine, m, V) {
  const { PhysicalLightingModel, getRoughness, sheenClamp } = engine;
  const f = (x) => tsl.float(x);
  const set = (node, v) => { node.v = Array.isArray(v.v) ? v.v.slice() : v.v; };
  const [hasSheen, hasCoat, hasAniso, hasIor, b0, b1, b2, metallic, rough, c0, c1, c2, rs, cc, rc, s, ac, as, iorF] = m;
  // GLTFLoader: MeshPhysicalMaterial where an extension asks for it (sheen = 1 with
  // KHR_materials_sheen; clearcoat, anisotropy, ior from the extensions; specular 1, colour 1).
  const physical = hasSheen || hasCoat || hasAniso || hasIor;
  const material = { sheen: hasSheen ? 1 : 0, clearcoat: hasCoat ? cc : 0, anisotropy: hasAniso ? s : 0 };
  // NodeMaterial.setupDiffuseColor, MeshStandardNodeMaterial.setupVariants and the physical
  // material's setupSpecular / setupVariants, reading MaterialNode's uniforms.
  set(tsl.diffuseColor, tsl.vec4(b0, b1, b2, 1));
  set(tsl.metalness, f(metallic));
  set(tsl.roughness, getRoughness({ roughness: f(rough) }));
  if (physical) {
    set(tsl.ior, f(iorF));
    set(tsl.specularColor, tsl.min(tsl.pow2(tsl.ior.sub(1.0).div(tsl.ior.add(1.0))).mul(tsl.vec3(1)), tsl.vec3(1.0)).mul(f(1)));
    set(tsl.specularF90, tsl.mix(f(1), 1.0, tsl.metalness));
  } else {
    set(tsl.specularColor, tsl.vec3(0.04));
    set(tsl.specularF90, f(1.0));
  }
  set(tsl.specularColorBlended, tsl.mix(physical ? tsl.specularColor : tsl.vec3(0.04), tsl.diffuseColor.rgb, tsl.metalness));
  set(tsl.diffuseContribution, tsl.diffuseColor.rgb.mul(tsl.metalness.oneMinus()));
  if (material.clearcoat > 0) {
    set(tsl.clearcoat, f(cc));
    set(tsl.clearcoatRoughness, getRoughness({ roughness: f(rc) }));
  }
  if (material.sheen > 0) {
    set(tsl.sheen, tsl.vec3(c0, c1, c2).mul(f(1)));
    set(tsl.sheenRoughness, sheenClamp ? f(rs).clamp(sheenClamp[0], sheenClamp[1]) : f(rs));
  }
  if (material.anisotropy > 0) {
    // MaterialNode's anisotropy vector: (s cos θ, s sin θ), computed on the CPU.
    const aV = tsl.vec2(Math.fround(s * ac), Math.fround(s * as)).toVar();
    set(tsl.anisotropy, aV.length());
    tsl.If(tsl.anisotropy.equal(0.0), () => { aV.assign(tsl.vec2(1.0, 0.0)); }).Else(() => {
      aV.divAssign(tsl.vec2(tsl.anisotropy));
      set(tsl.anisotropy, tsl.anisotropy.saturate());
    });
    set(tsl.alphaT, tsl.anisotropy.pow2().mix(tsl.roughness.pow2(), 1.0));
    // TBNViewMatrix of a flat quad: T = +X, B = +Y.
    const T = tsl.vec3(1, 0, 0), B = tsl.vec3(0, 1, 0);
    set(tsl.anisotropyT, T.mul(aV.x).add(B.mul(aV.y)));
    set(tsl.anisotropyB, B.mul(aV.x).sub(T.mul(aV.y)));
  }
  set(tsl.normalView, tsl.vec3(0, 0, 1));
  set(tsl.clearcoatNormalView, tsl.vec3(0, 0, 1));
  set(tsl.positionViewDirection, V);

  // MeshPhysicalNodeMaterial.setupLightingModel.
  return physical
    ? new PhysicalLightingModel(material.clearcoat > 0, material.sheen > 0, false, material.anisotropy > 0, false, false)
    : new PhysicalLightingModel();
}

// Sets every lobe's accumulator (lobe name -> node, absent where the material lacks it) but
// `lobe`'s to 0 ('all' keeps them all).
export function keepLobe(tsl, lobe, accumulators) {
  for (const [name, node] of Object.entries(accumulators)) {
    if (node && lobe !== 'all' && lobe !== name) node.assign(tsl.vec3(0));
  }
}

export async function main(tsl) {
  const engine = await loadEngine();
  const { mats, pairs } = readInputs();
  const out = [];
  for (const p of pairs) {
    // L and V as brdfcl normalizes them (in float).
    const unit = (x, y, z) => tsl.normalize(tsl.vec3(x, y, z));
    const L = unit(p[1], p[2], p[3]), V = unit(p[4], p[5], p[6]);
    const row = [];
    for (const lobe of LOBES) {
      // The light loop: start() (its super.start() runs the lights' direct() and the indirect
      // light, which is none here), finish().
      const model = setupMaterial(tsl, engine, mats[p[0]], V);
      model.indirect = () => {};
      const reflectedLight = { directDiffuse: tsl.vec3().toVar(), directSpecular: tsl.vec3().toVar() };
      const builder = {
        context: {},
        lightsNode: { getLightsNode: () => null, setupLights: () => model.direct({ lightDirection: L, lightColor: tsl.vec3(1), reflectedLight }) },
      };
      model.start(builder);
      // Lobes: each lobe's accumulator enters finish() alone, the others 0; finish() then layers
      // the coat over diffuse + specular and adds the sheen, as for the whole.
      keepLobe(tsl, lobe, { diffuse: reflectedLight.directDiffuse, specular: reflectedLight.directSpecular,
        sheen: model.sheenSpecularDirect, clearcoat: model.clearcoatSpecularDirect });
      // LightingNode: outgoing light = direct diffuse + direct specular (+ indirect, 0 here).
      const outgoingLight = reflectedLight.directDiffuse.add(reflectedLight.directSpecular).toVar();
      model.finish({ context: { outgoingLight } });
      const dotNL = tsl.normalView.dot(L).clamp();
      row.push(...outgoingLight.div(dotNL).v);
    }
    out.push(formatRow(row));
  }
  process.stdout.write(out.join('\n') + '\n');
}
