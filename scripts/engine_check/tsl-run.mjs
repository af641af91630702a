// Runs engine TSL files in node through the stand-in: `node tsl-run.mjs f32|f64 DRIVER FILE...`
// registers the module hooks for FILE... (the engine files run as they are) and then runs
// DRIVER's main(), which reads its inputs from stdin and writes results to stdout.
import { register } from 'node:module';
import { pathToFileURL } from 'node:url';
import { resolve } from 'node:path';

const [mode, driver, ...files] = process.argv.slice(2);
const keep = [driver, ...files].map((f) => resolve(f));
register('./tsl-hooks.mjs', { parentURL: import.meta.url, data: { keep } });
const tsl = await import('./tsl.mjs');
tsl.setFloat64(mode === 'f64');
const d = await import(pathToFileURL(resolve(driver)).href);
await d.main(tsl);
