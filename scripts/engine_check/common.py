# Shared by the engine check's modules: where the glue files and the repository are, the lobes,
# the C++ flags the engines' GLSL compiles with, the error type and the small formatting helpers.
import os
import struct
import sys

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # scripts/
GLUE = os.path.join(HERE, "engine_check")
REPO = os.path.dirname(HERE)
LOBES = ["all", "diffuse", "specular", "sheen", "clearcoat"]
CXX_FLAGS = ["-std=c++17", "-O1", "-ffp-contract=off", "-fno-fast-math", "-w"]


class CheckError(Exception):
    pass


def progress(msg):
    if sys.stderr.isatty():
        sys.stderr.write("engine-check: " + msg + "\n")
        sys.stderr.flush()


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def fmt(x):
    return "%.9g" % x
