# --self-test: the harness on snippets written for it (no engine code involved): GLSL -> C++,
# the metric, the EXR files, the IBL machinery and the TSL stand-in in node.
import math
import os
import shutil
import subprocess
import tempfile
from .common import CXX_FLAGS, GLUE, f32
from .glsl import glsl_to_cpp, hook
from .babylon import babylon_cpp
from .sets import Mat
from .compare import rel_err, worst_pair
from .ibl import exr_read, exr_write, write_gbuffer


# ---------------------------------------------------------------------------------------------
# Self-test: the machinery on snippets written for it (no engine code involved).

SELF_GLSL = """
precision highp float;
const float M_PI = 3.141592653589793;
uniform float u_Rough;
in vec3 v_Position;
out vec4 g_finalColor;
float D(float NdotH, float a) { float a2 = a * a; float f = NdotH * NdotH * (a2 - 1.0) + 1.0; return a2 / (M_PI * f * f); }
void split(in vec3 c, out float r, inout float g) { r = c.r; g += c.g; }
vec3 diffuseTerm(vec3 c) { return c / M_PI; }
vec3 specTerm(float a, float NdotH) { return vec3(D(NdotH, a)); }
void main() {
    vec4 base = vec4(0.5, 0.25, 1.0e-1, 1.0);
    float r = 0.0; float g = 1.0;
    split(base.rgb, r, g);
    g_finalColor = vec4(diffuseTerm(base.rgb) + specTerm(u_Rough * u_Rough, 0.75) * vec3(r, g, 1.0), 1.0);
}
"""


def self_test():
    ok = True

    def expect(cond, what):
        nonlocal ok
        print("%s %s" % ("ok  " if cond else "FAIL", what))
        ok = ok and cond

    cpp = glsl_to_cpp(SELF_GLSL)
    expect("0.5f" in cpp and "1.0e-1f" in cpp and "3.141592653589793f" in cpp, "float literals keep an f")
    expect(".rgb()" in cpp, "swizzles become GLM calls")
    expect("float& r" in cpp and "float& g" in cpp, "out/inout parameters become references")
    expect("void engine_main()" in cpp, "main() is renamed")
    bab = babylon_cpp("void sample(\n    in float a,\n    out vec4 radiance\n)\n{radiance=vec4(a);}", False)
    expect("vec4& radiance" in bab, "an out parameter on a line of its own (Babylon) becomes a reference")
    cpp, h1 = hook(cpp, "diffuseTerm", "ec::DIFFUSE")
    cpp, h2 = hook(cpp, "specTerm", "ec::SPECULAR")
    expect(h1 and h2 and "diffuseTerm__engine(vec3 c)" in cpp, "lobe hooks rename and wrap definitions")
    with tempfile.TemporaryDirectory(prefix="engine-check-self-") as d:
        src = os.path.join(d, "t.cpp")
        with open(src, "w") as f:
            f.write('#include "glsl.hpp"\n#undef M_PI\nnamespace t {\n' + cpp + "\n}\n"
                    "int main() { for (int lobe = 0; lobe < 3; ++lobe) { ec::g_lobe = lobe; t::u_Rough = 0.5f;\n"
                    "  t::engine_main(); std::printf(\"%.9g %.9g %.9g\\n\", t::g_finalColor.r, t::g_finalColor.g,"
                    " t::g_finalColor.b); } }\n")
        r = subprocess.run(["g++"] + CXX_FLAGS + ["-I", GLUE, src, "-o", os.path.join(d, "t")],
                           capture_output=True, text=True)
        expect(r.returncode == 0, "the converted GLSL compiles with GLM" + ("" if r.returncode == 0 else
                                                                            ":\n" + r.stderr[-3000:]))
        if r.returncode == 0:
            out = subprocess.run([os.path.join(d, "t")], capture_output=True, text=True).stdout.split("\n")
            rows = [[f32(float(x)) for x in line.split()] for line in out if line.strip()]
            pi = f32(math.pi)
            a = f32(0.5 * 0.5)
            a2 = f32(a * a)
            ff = f32(f32(f32(f32(0.75 * 0.75) * f32(a2 - 1.0))) + 1.0)
            dd = f32(a2 / f32(f32(pi * ff) * ff))
            diff = [f32(0.5 / pi), f32(0.25 / pi), f32(f32(0.1) / pi)]
            spec = [f32(dd * 0.5), f32(dd * 1.25), dd]
            expect(rows[1] == diff, "diffuse lobe alone, in float: %s" % rows[1])
            expect(rows[2] == spec, "specular lobe alone, in float: %s" % rows[2])
            expect(rows[0] == [f32(x + y) for x, y in zip(diff, spec)], "all lobes: %s" % rows[0])
    metric_self_test(expect)
    exr_self_test(expect)
    ibl_self_test(expect)
    tsl_ok = tsl_self_test(expect)
    return 0 if ok and tsl_ok else 1


def metric_self_test(expect):
    """The comparison's metric |a - b| / max(|a|, |b|, floor): relative above the floor, in units
    of the floor below it; subnormals flushed; NaN and infinity."""
    expect(rel_err(1e-38, 0.0) == 0.0 and rel_err(1e-38, 0.0, 0.0) == 0.0, "a subnormal-sized value counts as 0")
    expect(rel_err(1e-30, 0.0) == 1e-26 and rel_err(1e-30, 0.0, 0.0) == 1.0,
           "a tiny value against 0: %g under the floor, 1 with --floor 0" % rel_err(1e-30, 0.0))
    expect(rel_err(2e-5, 1e-5) == 0.1 and rel_err(2e-5, 1e-5, 1e-3) == 1e-2 and rel_err(2e-5, 1e-5, 0.0) == 0.5,
           "below the floor the difference is divided by the floor: %g" % rel_err(2e-5, 1e-5))
    expect(rel_err(2.0, 1.0) == 0.5 and rel_err(-2.0, 1.0) == 1.5 and rel_err(1.0, 1.0 + 2e-4, 1e-2) ==
           rel_err(1.0, 1.0 + 2e-4, 0.0), "above the floor it is the relative difference")
    expect(rel_err(math.nan, math.nan) == 0.0 and rel_err(math.nan, 0.0) == math.inf and
           rel_err(math.inf, 1.0) == math.inf and rel_err(math.inf, math.inf) == 0.0, "NaN and infinity")
    pairs = [(0, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0)), (1, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0)),
             (0, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0)), (1, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0))]
    engine = [(1.0, 1.0, 1.0), (2.0, 1.0, 1.0), (math.nan, 1.0, 1.0), (1.0, 4.0, 1.0)]
    ours = [(1.0, 1.0, 1.0), (1.0, 1.0, 1.0), (1.0, 1.0, 1.0), (1.0, 1.0, math.inf)]
    expect(worst_pair(pairs, engine, ours, 1e-4) == (0.5, (1, engine[1], ours[1]), 2, (2, engine[2], ours[2])),
           "the worst pair is the largest finite difference; NaN or infinity on one side are counted apart")
    expect(worst_pair(pairs, engine, ours, 1e-4, lambda i: i == 0) == (0.0, (0, engine[0], ours[0]), 1,
                                                                       (2, engine[2], ours[2])),
           "the worst pair looks only at the materials it is asked about")


def exr_self_test(expect):
    """The image-based-light check's EXR writer and reader (uncompressed, ZIPS and ZIP, blocks
    that end short of 16 lines) and the G-buffer it writes, read back."""
    with tempfile.TemporaryDirectory(prefix="engine-check-exr-") as d:
        w, h = 5, 37
        ch = {"R": [k * 0.25 for k in range(w * h)], "G": [-k / 3.0 for k in range(w * h)],
              "B": [f32(1e-30 * k) for k in range(w * h)]}
        want = {n: [f32(v) for v in vals] for n, vals in ch.items()}
        for comp, name in [(0, "uncompressed"), (2, "ZIPS"), (3, "ZIP")]:
            path = os.path.join(d, "t%d.exr" % comp)
            exr_write(path, w, h, ch, compression=comp)
            rw, rh, got = exr_read(path)
            expect((rw, rh) == (w, h) and got == want, "EXR %s round trip" % name)
        mats = [Mat(base=[0.25, 0.5, 0.75], metallic=0.0, roughness=0.5, clearcoat=(0.5, 0.25))]
        pairs = [(0, (0.0, 0.0, 1.0), (0.6, 0.0, 0.8)), (0, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0))]
        g = os.path.join(d, "g.exr")
        write_gbuffer(g, mats, pairs)
        _, _, ch = exr_read(g)
        expect(ch["V.X"] == [f32(0.6), 0.0] and ch["baseColor.B"] == [0.75, 0.75] and
               ch["clearcoatRoughness"] == [0.25, 0.25] and ch["mask"] == [1.0, 1.0] and
               ch["sheenRoughness"] == [0.0, 0.0], "the image-based-light G-buffer reads back")


SELF_IBL_GLSL = """
float shade(float a) { return a * 2.0; }
vec3 tint(vec3 c,
        const in float k) {
    float shade = shade(k);
    vec4 t = vec4(c, 1.0);
    t.rgb *= shade;
    t.xy += vec2(0.5);
    return t.rgb;
}
"""


def ibl_self_test(expect):
    """Machinery of the image-based-light check: swizzles written to, locals named after their
    function, parameter lists across lines, the two-run table look-ups."""
    cpp = glsl_to_cpp(SELF_IBL_GLSL)
    expect("ec::swz<3>(t, 0, 1, 2) *= shade" in cpp and "ec::swz<2>(t, 0, 1) +=" in cpp,
           "swizzles written to become ec::swz")
    expect("shade__fn" in cpp and "const in" not in cpp, "a local named after its function; `const in` on its own line")
    with tempfile.TemporaryDirectory(prefix="engine-check-ibl-") as d:
        src = os.path.join(d, "t.cpp")
        with open(src, "w") as f:
            f.write('#include "glsl.hpp"\n#include "driver.hpp"\nnamespace t {\n' + cpp + "\n}\n"
                    "int main() { ec::open_lookups(); vec3 r = t::tint(vec3(1, 2, 3), 0.5f);\n"
                    "  std::printf(\"%.9g %.9g %.9g %.9g\\n\", r.x, r.y, r.z, ec::table_lookup(ec::E_CN, 0.25f, 0.5f));\n"
                    "  if (ec::g_lookups_out) std::fclose(ec::g_lookups_out); }\n")
        exe = os.path.join(d, "t")
        r = subprocess.run(["g++"] + CXX_FLAGS + ["-I", GLUE, src, "-o", exe], capture_output=True, text=True)
        expect(r.returncode == 0, "the IBL snippet compiles" + ("" if r.returncode == 0 else ":\n" + r.stderr[-3000:]))
        if r.returncode == 0:
            rec, ans = os.path.join(d, "rec.txt"), os.path.join(d, "ans.txt")
            first = subprocess.run([exe], capture_output=True, text=True, env=dict(os.environ, EC_LOOKUPS_OUT=rec))
            with open(rec) as f:
                asked = f.read().split()
            expect(first.stdout.split() == ["1.5", "2.5", "3", "0.5"] and asked == ["1", "0x1p-2", "0x1p-1"],
                   "swizzle writes land; the first run records (table, u, v): %s %s" % (first.stdout.split(), asked))
            with open(ans, "w") as f:
                f.write("1 0x1p-2 0x1p-1 0x1.8p-1\n")
            second = subprocess.run([exe], capture_output=True, text=True, env=dict(os.environ, EC_LOOKUPS=ans))
            expect(second.stdout.split()[-1:] == ["0.75"], "the second run reads the answer: %s" % second.stdout.split())


SELF_TSL = {
    "helper.js": "import { Fn } from './TSLBase.js';\nconst sq = Fn( ( [ x ] ) => x.mul( x ) );\nexport default sq;\n",
    "bsdf.js": """import { Fn, float, If, PI } from './TSLBase.js';
import { notInTheStandIn } from './Other.js';
import sq from './helper.js';
const D = Fn( ( { a, NdotH } ) => {
	const a2 = sq( a );
	const f = NdotH.mul( NdotH ).mul( a2.sub( 1.0 ) ).add( 1.0 ).toVar();
	If( f.lessThan( 0 ), () => { f.assign( notInTheStandIn ); } );
	return a2.div( PI.mul( f ).mul( f ) );
} );
export default D;
""",
    "driver.mjs": """import D from './bsdf.js';
export async function main( tsl ) {
	const v = D( { a: tsl.float( 0.25 ), NdotH: tsl.float( 0.75 ) } );
	console.log( String( v.v ) );
}
""",
}


def node_run(mode, driver, files, stdin=""):
    cmd = ["node", os.path.join(GLUE, "tsl-run.mjs"), mode, driver] + files
    return subprocess.run(cmd, input=stdin, capture_output=True, text=True)


def tsl_self_test(expect):
    if not shutil.which("node"):
        expect(False, "node is installed (scripts/install-deps installs nodejs)")
        return False
    with tempfile.TemporaryDirectory(prefix="engine-check-tsl-") as d:
        for name, text in SELF_TSL.items():
            with open(os.path.join(d, name), "w") as f:
                f.write(text)
        files = [os.path.join(d, "bsdf.js"), os.path.join(d, "helper.js")]
        r32 = node_run("f32", os.path.join(d, "driver.mjs"), files)
        r64 = node_run("f64", os.path.join(d, "driver.mjs"), files)
        ok = r32.returncode == 0 and r64.returncode == 0
        expect(ok, "TSL files run in node through the stand-in" + ("" if ok else ":\n" + r32.stderr[-2000:]))
        if not ok:
            return False
        v32, v64 = float(r32.stdout), float(r64.stdout)
        pi = f32(math.pi)
        a2 = f32(0.25 * 0.25)
        ff = f32(f32(f32(f32(0.75 * 0.75) * f32(a2 - 1.0))) + 1.0)
        want32 = f32(a2 / f32(f32(pi * ff) * ff))
        a2 = 0.0625
        ff = 0.75 * 0.75 * (a2 - 1.0) + 1.0
        want64 = a2 / (math.pi * ff * ff)
        expect(v32 == want32, "TSL in float32, rounded after every operation: %r" % v32)
        expect(v64 == want64, "TSL in float64 (--float64): %r" % v64)
        return v32 == want32 and v64 == want64
