# Each brdfcl error is a subclass of brdfcl.Error by its kind, and also the built-in exception a
# Python caller expects of that kind (docs/python.md): input errors stay ValueErrors.
import os
import resource
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import brdfcl

M = {"pbrMetallicRoughness": {"roughnessFactor": 0.5}}

KINDS = [
    (brdfcl.InputError, "input", ValueError),
    (brdfcl.EnvironmentError, "environment", OSError),
    (brdfcl.DeviceError, "device", RuntimeError),
    (brdfcl.OutOfMemoryError, "memory", MemoryError),
    (brdfcl.InternalError, "internal", RuntimeError),
]


@pytest.mark.parametrize("cls, kind, builtin", KINDS)
def test_classes(cls, kind, builtin):
    assert issubclass(cls, brdfcl.Error) and issubclass(cls, builtin) and cls.kind == kind
    assert not issubclass(brdfcl.Error, ValueError)


def test_input_errors_are_value_errors():
    with pytest.raises(brdfcl.InputError, match=r"^L must have shape \(N, 3\), got \(2, 4\)$") as e:
        brdfcl.evaluate(M, np.zeros((2, 4)), np.zeros((2, 3)))
    assert isinstance(e.value, ValueError) and e.value.kind == "input"
    with pytest.raises(ValueError, match="no OpenCL device matches"):
        brdfcl.evaluate(M, [[0, 0, 1]], [[0, 0, 1]], device="no-such-device-name")
    # Raised by the pure-Python checks too.
    with pytest.raises(brdfcl.InputError, match="material_index must have shape"):
        brdfcl.evaluate([M, M], [[0, 0, 1]], [[0, 0, 1]], material_index=np.zeros((1, 1), np.int64))


def run_child(code, env=None, preexec_fn=None):
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          env={**os.environ, **(env or {})}, preexec_fn=preexec_fn, timeout=120)


def test_no_platform_is_an_environment_error(tmp_path):
    """No OpenCL platform (an empty ICD vendor folder): an OSError, in a child process so that
    this one keeps its devices."""
    r = run_child("""
        import brdfcl
        try:
            brdfcl.devices()
        except brdfcl.EnvironmentError as e:
            assert isinstance(e, OSError) and isinstance(e, brdfcl.Error) and e.kind == "environment"
            print("OK", e)
        """, env={"OCL_ICD_VENDORS": str(tmp_path)})
    assert r.returncode == 0 and r.stdout.startswith("OK no OpenCL platform found"), r.stdout + r.stderr


def test_frame_too_large_is_a_memory_error():
    """A render larger than the address space allows: a MemoryError naming a size that fits."""
    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (16 << 30, 16 << 30))
    r = run_child("""
        import brdfcl
        try:
            brdfcl.render(scene="spheres", size=(16384, 16384))
        except MemoryError as e:
            assert isinstance(e, brdfcl.OutOfMemoryError) and e.kind == "memory"
            print("OK", e)
        """, preexec_fn=limit)
    assert r.returncode == 0 and r.stdout.startswith("OK size=16384x16384 needs about"), r.stdout + r.stderr
