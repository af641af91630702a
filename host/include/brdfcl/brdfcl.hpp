// brdfcl's public C++ API in one include: materials and their options, the devices, batch and
// streamed evaluation, the look-up tables, the readers and writers of brdfcl's files, glTF assets
// and rendering. No header here names an OpenCL type (scripts/check-layers enforces it).
#pragma once

#include "brdfcl/error.hpp"     // brdfcl::Error, its kind and exit status
#include "brdfcl/material.hpp"  // MaterialParams, EvalOptions and the spellings of their options
#include "brdfcl/runtime.hpp"   // Runtime (one device, by index or name), listDevices

#include "brdfcl/albedo.hpp"     // directional albedo by quadrature
#include "brdfcl/arrays.hpp"     // evaluation of directions held in memory (numpy arrays)
#include "brdfcl/evaluator.hpp"  // Evaluator and SoaBatch: batch evaluation on a device
#include "brdfcl/lut.hpp"        // the LUT bakes engines use
#include "brdfcl/stream.hpp"     // evaluation of sample files of any size

#include "brdfcl/gbuffer.hpp"  // the G-buffer format
#include "brdfcl/image.hpp"    // EXR, PNG and Radiance HDR images
#include "brdfcl/io.hpp"       // materials, samples and results files
#include "brdfcl/sampling_io.hpp"  // the views and sampled-direction files of brdfcl sample
#include "brdfcl/scene.hpp"    // the scene file that goes with a G-buffer

#include "brdfcl/frame_budget.hpp"  // the memory a frame needs, checked before any work
#include "brdfcl/gltf.hpp"          // glTF assets as brdfcl loads them
#include "brdfcl/gltf_render.hpp"   // cameras and ray casting of a loaded asset
#include "brdfcl/render.hpp"        // environments and the deferred shader
#include "brdfcl/render_job.hpp"    // one render from an asset or the built-in scene to an image
