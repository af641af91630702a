# brdfcl.Options, the one model-options object of every function and Evaluator method, and the
# library's messages in a Python caller's words: keywords (lobe=), never the CLI's options (--lobe).
import re

import numpy as np
import pytest

import brdfcl

M = {"pbrMetallicRoughness": {"roughnessFactor": 0.4},
     "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 0.5}}}
L = np.array([[0.3, 0.1, 0.9], [-0.5, 0.2, 0.7]], np.float32)
V = np.array([[0.0, 0.0, 1.0], [0.4, -0.1, 0.8]], np.float32)


def test_options_are_checked_when_made_and_name_the_keyword():
    with pytest.raises(brdfcl.InputError, match=r"^unknown lobe= value 'speculr'; use all, diffuse, specular, sheen or clearcoat$"):
        brdfcl.Options(lobe="speculr")
    with pytest.raises(brdfcl.InputError, match=r"^unknown sheen_visibility= value 'x'; use charlie or ashikhmin$"):
        brdfcl.Options(sheen_visibility="x")
    with pytest.raises(brdfcl.InputError, match=r"^sheen_scaling= applies to profile='spec' only; profile='filament' uses"):
        brdfcl.Options(profile="filament", sheen_scaling="view")
    with pytest.raises(brdfcl.InputError, match=r"^lobe= must be a str, got int$"):
        brdfcl.Options(lobe=3)
    with pytest.raises(TypeError):
        brdfcl.Options("all")  # keywords only


def test_options_value_semantics():
    a = brdfcl.Options(profile="threejs")
    assert a == brdfcl.Options(profile="threejs") and hash(a) == hash(brdfcl.Options(profile="threejs"))
    assert a.replace(lobe="specular") == brdfcl.Options(profile="threejs", lobe="specular")
    assert a.lobe == "all"  # replace made a copy
    with pytest.raises(AttributeError, match="immutable"):
        a.lobe = "sheen"
    with pytest.raises(TypeError, match="unknown option 'lobes'"):
        a.replace(lobes="sheen")
    assert repr(brdfcl.Options()) == ("brdfcl.Options(lobe='all', profile='spec', sheen_visibility='charlie', "
                                      "sheen_distribution='charlie', sheen_scaling='min')")


def test_one_options_object_for_functions_and_evaluator():
    o = brdfcl.Options(lobe="sheen", sheen_visibility="ashikhmin")
    want = brdfcl.evaluate(M, L, V, lobe="sheen", sheen_visibility="ashikhmin")
    assert np.array_equal(brdfcl.evaluate(M, L, V, options=o), want)
    ev = brdfcl.Evaluator()
    assert np.array_equal(ev.evaluate(M, L, V, options=o), want)
    assert np.array_equal(brdfcl.evaluate_grid([M], L, V, options=o)[0], want)
    # An Evaluator's options are the default of its calls; keywords override them.
    sheen = brdfcl.Evaluator(options=o)
    assert sheen.options == o
    assert np.array_equal(sheen.evaluate(M, L, V), want)
    assert np.array_equal(sheen.evaluate(M, L, V, lobe="all"), brdfcl.evaluate(M, L, V, sheen_visibility="ashikhmin"))
    # albedo integrates every lobe whatever the options' lobe.
    a = brdfcl.albedo(M, 0.5, options=o)
    assert np.array_equal(a["all"], brdfcl.albedo(M, 0.5, sheen_visibility="ashikhmin")["all"])
    with pytest.raises(brdfcl.InputError, match=r"^options= must be a brdfcl.Options, got dict$"):
        brdfcl.evaluate(M, L, V, options={"lobe": "sheen"})


def test_render_and_shade_take_the_options_profile():
    o = brdfcl.Options(profile="filament")
    assert np.array_equal(brdfcl.render(size=(16, 12), options=o), brdfcl.render(size=(16, 12), profile="filament"))
    with pytest.raises(brdfcl.InputError, match=r"^ibl='exact' integrates the spec's BRDF only; an engine profile"):
        brdfcl.render(size=(16, 12), options=o, ibl="exact")


@pytest.mark.parametrize("call, message", [
    (lambda: brdfcl.render(size=(8, 8), camera="0"), r"^camera= applies to glTF assets; add gltf=FILE$"),
    (lambda: brdfcl.render(size=(8, 8), strict=True), r"^strict= applies to glTF assets; add gltf=FILE$"),
    (lambda: brdfcl.render(size=(8, 8), ibl="fast"), r"^ibl='fast' is not an image-based light mode; use split-sum or exact$"),
    (lambda: brdfcl.render(size=(8, 8), ibl_samples=0, ibl="exact"), r"^ibl_samples=0 is out of range; use 1 to 65536$"),
    (lambda: brdfcl.render(size=(8, 8), ibl_samples=8), r"^ibl_samples= applies to ibl='exact'; add ibl='exact'$"),
    (lambda: brdfcl.render(size=(8, 8), env_intensity=-1.0), r"^env_intensity=-1 is not a finite number >= 0"),
    (lambda: brdfcl.render(size=(8, 8), environment="nowhere.hdr"), r"^environment='nowhere.hdr'"),
    (lambda: brdfcl.render(size=(8, 8), lights="none.json"), r"^lights='none.json': cannot read"),
    (lambda: brdfcl.evaluate(M, L, V, device="no such device"), r"^device='no such device': no OpenCL device matches; "
                                                                 r"see brdfcl.devices\(\)$"),
])
def test_library_messages_name_python_keywords(call, message):
    with pytest.raises(brdfcl.Error, match=message) as e:
        call()
    assert not re.search(r"(^|\W)--[a-z]", str(e.value)), str(e.value)
