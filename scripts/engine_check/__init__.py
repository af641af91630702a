# The engine check's code (scripts/engine-check is its entry): cli, direct and ibl run the checks;
# glsl and the engine modules (khronos, filament, threejs, materialx, babylon; engines lists them)
# build the evaluators; sets, brdfcl, compare, sources and selftest do the rest.
