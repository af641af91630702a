// Driver for three.js's image-based light (PhysicalLightingModel's indirect(): indirectDiffuse,
// indirectSpecular, ambientOcclusion, then finish()) under a uniform environment of radiance 1,
// with the material state set as threejs.mjs sets it for the direct light.
import { LOBES, loadEngine, readInputs, formatRow, setupMaterial, keepLobe } from './threejs.mjs';

export async function main(tsl) {
  const engine = await loadEngine();
  const { mats, pairs } = readInputs();
  const out = [];
  for (const p of pairs) {
    const V = tsl.normalize(tsl.vec3(p[4], p[5], p[6]));
    const row = [];
    for (const lobe of LOBES) {
      const model = setupMaterial(tsl, engine, mats[p[0]], V);
      // LightingContextNode's context: no ambient, hemisphere or probe light (irradiance 0), no
      // ambient-occlusion map (ambientOcclusion 1).
      const reflectedLight = { directDiffuse: tsl.vec3().toVar(), directSpecular: tsl.vec3().toVar(),
        indirectDiffuse: tsl.vec3().toVar(), indirectSpecular: tsl.vec3().toVar() };
      const context = { radiance: tsl.vec3().toVar(), irradiance: tsl.vec3().toVar(), iblIrradiance: tsl.vec3().toVar(),
        ambientOcclusion: tsl.float(1).toVar(), reflectedLight };
      // EnvironmentNode.setup, run among the lights: a texture read of a uniform environment is 1
      // at every direction and level, so radiance = 1 × intensity, iblIrradiance = 1 × π × intensity,
      // and the coat's radiance (about the coat normal, at the coat roughness) = 1 × intensity.
      const environment = () => {
        const intensity = tsl.float(1);
        context.radiance.addAssign(tsl.vec3(1).mul(intensity));
        context.iblIrradiance.addAssign(tsl.vec3(1).mul(Math.PI).mul(intensity));
        if (model.clearcoatRadiance) model.clearcoatRadiance.addAssign(tsl.vec3(1).mul(intensity));
      };
      // The light loop: start() runs the lights, then indirect() (called here with the context
      // whatever arguments LightingModel.start passes), then finish().
      const indirect = engine.PhysicalLightingModel.prototype.indirect;
      model.indirect = () => indirect.call(model, { context });
      model.start({ context, lightsNode: { getLightsNode: () => null, setupLights: environment } });
      // Lobes: each indirect accumulator enters finish() alone, the others 0.
      keepLobe(tsl, lobe, { diffuse: reflectedLight.indirectDiffuse, specular: reflectedLight.indirectSpecular,
        sheen: model.sheenSpecularIndirect, clearcoat: model.clearcoatSpecularIndirect });
      // LightsNode: outgoing light = (direct + indirect diffuse) + (direct + indirect specular).
      const outgoingLight = reflectedLight.directDiffuse.add(reflectedLight.indirectDiffuse)
        .add(reflectedLight.directSpecular.add(reflectedLight.indirectSpecular)).toVar();
      model.finish({ context: { outgoingLight } });
      row.push(...outgoingLight.v);
    }
    out.push(formatRow(row));
  }
  process.stdout.write(out.join('\n') + '\n');
}
