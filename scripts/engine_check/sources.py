# The engine checkouts' files: each engine's evaluator built from its checkout, the git commit each
# file last changed in (or its blob hash), and the `file@commit` pins of the profile's section of
# docs/profiles.md.
import os
import re
import subprocess
from .common import REPO


def git_info(src, files):
    def git(*a):
        r = subprocess.run(["git", "-C", src] + list(a), capture_output=True, text=True)
        return r.stdout.strip() if r.returncode == 0 else None
    head = git("rev-parse", "HEAD")
    per_file = {}
    for p in files:
        per_file[p] = git("log", "-1", "--format=%h", "--", p) if head else None
        if per_file[p] is None:
            fp = os.path.join(src, p)
            if os.path.exists(fp):
                with open(fp, "rb") as f:
                    data = f.read()
                import hashlib
                per_file[p] = "blob " + hashlib.sha1(b"blob %d\0" % len(data) + data).hexdigest()[:10]
            else:
                per_file[p] = "missing"
    desc = git("describe", "--tags", "--always") if head else None
    return head, desc, per_file


def pins(profile):
    """`file@commit` pins of the profile's section of docs/profiles.md."""
    try:
        with open(os.path.join(REPO, "docs", "profiles.md"), encoding="utf-8") as f:
            doc = f.read()
    except OSError:
        return {}
    m = re.search(r"^## `%s`.*?(?=^## )" % re.escape(profile), doc, re.S | re.M)
    if not m:
        return {}
    sec = m.group(0).split("\n\n")[1] if "\n\n" in m.group(0) else m.group(0)
    return {os.path.basename(a): b for a, b in re.findall(r"`?([\w./]+)@([0-9a-f]{7,40})", sec)}


def build_engine(a, work, prof, folder, builder, label):
    """The evaluator of one engine built from its checkout under --sources, the checkout's commit
    printed after label: (exes, files, per_file), or None (said in a line) where there is no checkout."""
    src = os.path.join(a.sources, folder)
    if not os.path.isdir(src):
        print("%s: no %s/ under %s, skipped" % (prof, folder, a.sources))
        return None
    exes, files = builder(src, work, a.float64)
    head, desc, per_file = git_info(src, files)
    print("%s: %s at %s" % (label, folder, ("%s (%s)" % (head[:12], desc)) if head else "no git commit"))
    return exes, files, per_file
