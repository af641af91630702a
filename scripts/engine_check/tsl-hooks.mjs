// Module hooks for running an engine's TSL files in node: an import of a file outside the list
// the check runs (TSL's node system, renderer state) is answered by the eager stand-in (tsl.mjs),
// with a stub that throws on use for any name the stand-in lacks.
import { readFileSync } from 'node:fs';
import { fileURLToPath, pathToFileURL } from 'node:url';

let keep = new Set();
const standin = new URL('./tsl.mjs', import.meta.url).href;

export async function initialize(data) { keep = new Set(data.keep.map((p) => pathToFileURL(p).href)); }

export async function resolve(spec, ctx, next) {
  const parent = ctx.parentURL || '';
  if (parent.startsWith('file:') && keep.has(parent) && (spec.startsWith('.') || spec.startsWith('/'))) {
    const url = new URL(spec, parent).href;
    if (!keep.has(url)) return { url: 'engine-check-standin:' + encodeURIComponent(url) + '?from=' + encodeURIComponent(parent), shortCircuit: true };
  }
  return next(spec, ctx);
}

export async function load(url, ctx, next) {
  if (url.startsWith('engine-check-standin:')) {
    const [target, q] = url.slice('engine-check-standin:'.length).split('?from=');
    const parent = fileURLToPath(decodeURIComponent(q));
    const want = decodeURIComponent(target);
    const std = await import(standin);
    const names = new Set();
    const src = readFileSync(parent, 'utf8');
    for (const m of src.matchAll(/import\s*(?:(\w+)\s*,?\s*)?(?:\{([^}]*)\})?\s*from\s*['"]([^'"]+)['"]/g)) {
      if (new URL(m[3], decodeURIComponent(q)).href !== want) continue;
      if (m[1]) names.add('default');
      for (const n of (m[2] || '').split(',')) { const k = n.trim().split(/\s+as\s+/)[0]; if (k) names.add(k); }
    }
    let body = `import * as S from ${JSON.stringify(standin)};\n`;
    for (const n of names) {
      if (n === 'default') { body += 'export default S.missing("default of ' + want + '");\n'; continue; }
      body += n in std ? `export const ${n} = S.${n};\n` : `export const ${n} = S.missing(${JSON.stringify(n)});\n`;
    }
    return { format: 'module', source: body, shortCircuit: true };
  }
  if (url.startsWith('file:') && keep.has(url)) {
    return { format: 'module', source: readFileSync(fileURLToPath(url), 'utf8'), shortCircuit: true };
  }
  return next(url, ctx);
}
