# GLSL -> C++ on GLM: the rewriting that lets an engine's own shader text compile as C++, finding
# and hooking its functions, resolving its #includes, and compiling one evaluator per define variant.
import os
import re
import subprocess
from .common import CXX_FLAGS, CheckError, GLUE, progress


# ---------------------------------------------------------------------------------------------
# GLSL -> C++ (GLM). The text stays the engine's; only the spelling GLSL and C++ disagree on moves.

FLOAT_LITERAL = re.compile(r"(?<![\w.])((?:\d+\.\d*|\.\d+)(?:[eE][+-]?\d+)?|\d+[eE][+-]?\d+)(?![\w.])")
SWIZZLE = re.compile(r"\.([xyzw]{2,4}|[rgba]{2,4}|[stpq]{2,4})\b(?!\s*\()")
LHS_SWIZZLE = re.compile(r"\b([A-Za-z_]\w*(?:\[[^\]]*\])?(?:\.[A-Za-z_]\w*)*?)\.([xyzw]{2,4}|[rgba]{2,4}|[stpq]{2,4})"
                         r"\s*([-+*/]?=)(?!=)")


def lhs_swizzle(m):
    idx = ["xyzw".find(c) if c in "xyzw" else "rgba".find(c) if c in "rgba" else "stpq".find(c) for c in m.group(2)]
    return "ec::swz<%d>(%s, %s) %s" % (len(idx), m.group(1), ", ".join(map(str, idx)), m.group(3))


def glsl_to_cpp(text, float64=False):
    """float64: literals keep no `f` (the text is then compiled with float spelled double)."""
    out = []
    for line in text.split("\n"):
        s = line.strip()
        if s.startswith("#version") or re.match(r"precision\s+\w+\s+\w+\s*;", s):
            out.append("")
            continue
        if s.startswith("#"):
            out.append(line)  # preprocessor lines: C++'s own preprocessor reads them
            continue
        line = re.sub(r"\blayout\s*\([^)]*\)\s*", "", line)
        line = re.sub(r"^(\s*)(?:flat\s+)?(?:uniform|in|out|varying|attribute)\s+(?=\w+\s+\w+)", r"\1", line)
        line = re.sub(r"\buniform\s+", "", line)
        line = re.sub(r"\b(?:highp|mediump|lowp)\s+", "", line)
        line = re.sub(r"\b(?:const\s+)?(?:inout|out)\s+(\w+)\s+(\w+)", r"\1& \2", line)
        line = re.sub(r"([(,]\s*)(?:const\s+)?in\s+(?=\w+\s+\w+)", r"\1", line)
        # a parameter list continued on its own line: `    const in T name, ...)`
        line = re.sub(r"^(\s*)(?:const\s+)?in\s+(?=\w+\s+\w+\s*[,)])", r"\1", line)
        # GLSL lets a local take the name of the function whose call initializes it
        # (`float specularAO = specularAO(...)`); in C++ the name is the new variable at once.
        line = re.sub(r"^(\s*)(?:const\s+)?(\w+)\s+(\w+)\s*=\s*\3\s*\(",
                      r"\1auto \3__fn = [&](auto&&... ec_a) { return \3(ec_a...); }; \2 \3 = \3__fn(", line)
        if not float64:
            line = FLOAT_LITERAL.sub(lambda m: m.group(1) + "f", line)
        line = LHS_SWIZZLE.sub(lhs_swizzle, line)
        line = SWIZZLE.sub(lambda m: "." + m.group(1) + "()", line)
        line = re.sub(r"\bdiscard\s*;", "return;", line)
        out.append(line)
    text = "\n".join(out)
    return re.sub(r"\bvoid\s+main\s*\(\s*\)", "void engine_main()", text)


def find_function(text, name, start=0):
    """(header_start, name_start, body_end) of the next definition of `name`, or None."""
    pat = re.compile(r"(?m)^[ \t]*(?:inline\s+)?[\w:<>]+[ \t]+(" + re.escape(name) + r")\s*\([^;{]*\)\s*\{")
    m = pat.search(text, start)
    if not m:
        return None
    depth, i = 0, m.end() - 1
    while i < len(text):
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return m.start(), m.start(1), i + 1
        i += 1
    raise CheckError("unbalanced braces after the definition of %s" % name)


def hook(text, name, lobe, macro="EC_LOBE_HOOK"):
    """Renames every definition of `name` to name__engine and wraps it as lobe `lobe`'s entry."""
    pos, last_end, found = 0, None, False
    while True:
        f = find_function(text, name, pos)
        if not f:
            break
        _, ns, end = f
        text = text[:ns] + name + "__engine" + text[ns + len(name):]
        end += len("__engine")
        last_end, pos, found = end, end, True
    if not found:
        return text, False
    wrapper = "\n%s(%s, %s)\n" % (macro, name, lobe)
    return text[:last_end] + wrapper + text[last_end:], True


def resolve_includes(path, skip, seen=None):
    """The file's text with `#include <x>` / `#include "x"` replaced by x (once), skipping `skip`."""
    seen = set() if seen is None else seen
    base = os.path.dirname(path)
    with open(path, encoding="utf-8") as f:
        text = f.read()

    def repl(m):
        name = m.group(1)
        if name in skip or name in seen:
            return "// (%s not compiled)" % name if name in skip else ""
        p = os.path.join(base, name)
        if not os.path.exists(p):
            raise CheckError("%s includes %s, which the checkout lacks" % (path, name))
        seen.add(name)
        return resolve_includes(p, skip, seen)

    return re.sub(r'(?m)^[ \t]*#include\s*[<"]([^>"]+)[>"].*$', repl, text)


def compile_variants(name, engine_text, prefix_inc, glue_inc, defines_for, macro_names, workdir, extra="",
                     float64=False):
    """Pastes the engine text into 16 namespaces (one per set of extensions present), then g++.
    float64: GLM in double and the engine's `float` spelled double."""
    parts = ["#define EC_FLOAT64" if float64 else "", '#include "glsl.hpp"', '#include "driver.hpp"', extra]
    for v in range(16):
        parts.append("namespace v%d {" % v)
        parts.append("#undef M_PI\n#undef M_PI_2\n#undef M_1_PI\n#undef M_2_PI")
        defs = defines_for(v)
        parts += ["#define %s %s" % (k, val) for k, val in defs]
        parts.append('#include "%s"' % prefix_inc)
        parts.append("#define float double" if float64 else "")
        parts.append(engine_text)
        parts.append("#undef float" if float64 else "")
        parts.append('#define EC_%s_AFTER\n#include "%s"\n#undef EC_%s_AFTER' % (name.upper(), glue_inc, name.upper()))
        parts += ["#undef %s" % k for k in sorted(set(macro_names) | {k for k, _ in defs})]
        parts.append("}  // namespace v%d" % v)
    parts.append("static ec::RunFn const ec_variants[16] = {%s};" % ", ".join("v%d::ec_run" % v for v in range(16)))
    parts.append("int main(int argc, char** argv) { return ec::run(ec_variants, argc, argv); }")
    src = os.path.join(workdir, name + ".cpp")
    with open(src, "w") as f:
        f.write("\n".join(parts) + "\n")
    exe = os.path.join(workdir, name)
    cmd = ["g++"] + CXX_FLAGS + ["-I", GLUE, src, "-o", exe]
    progress("compiling %s" % name)
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise CheckError("g++ failed on %s's code (%s):\n%s" % (name, src, r.stderr[-4000:]))
    return exe
