// The OpenCL runtime, now private to the library: host/src/runtime/opencl.hpp.
#pragma once
#include "host/src/runtime/opencl.hpp"
