// OpenCL device selection, context/queue setup and the program cache. Kernel sources come from
// the embedded copy of kernels/, with #include "..." lines expanded here (OpenCL has no virtual FS).
#include "runtime/opencl.hpp"

#include <cstdlib>
#include <mutex>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "io/disk_cache.hpp"
#include "io/option_style.hpp"
#include "runtime/pocl_cache_dir.hpp"

namespace brdfcl {
namespace detail {
const std::map<std::string, std::string>& embeddedKernels();
}

const char* clErrorName(int code) {
  switch (code) {
#define BRDFCL_CL_ERR(x) case x: return #x;
    BRDFCL_CL_ERR(CL_SUCCESS) BRDFCL_CL_ERR(CL_DEVICE_NOT_FOUND) BRDFCL_CL_ERR(CL_DEVICE_NOT_AVAILABLE)
    BRDFCL_CL_ERR(CL_COMPILER_NOT_AVAILABLE) BRDFCL_CL_ERR(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    BRDFCL_CL_ERR(CL_OUT_OF_RESOURCES) BRDFCL_CL_ERR(CL_OUT_OF_HOST_MEMORY)
    BRDFCL_CL_ERR(CL_PROFILING_INFO_NOT_AVAILABLE) BRDFCL_CL_ERR(CL_MEM_COPY_OVERLAP)
    BRDFCL_CL_ERR(CL_IMAGE_FORMAT_MISMATCH) BRDFCL_CL_ERR(CL_IMAGE_FORMAT_NOT_SUPPORTED)
    BRDFCL_CL_ERR(CL_BUILD_PROGRAM_FAILURE) BRDFCL_CL_ERR(CL_MAP_FAILURE)
    BRDFCL_CL_ERR(CL_MISALIGNED_SUB_BUFFER_OFFSET) BRDFCL_CL_ERR(CL_COMPILE_PROGRAM_FAILURE)
    BRDFCL_CL_ERR(CL_LINKER_NOT_AVAILABLE) BRDFCL_CL_ERR(CL_LINK_PROGRAM_FAILURE)
    BRDFCL_CL_ERR(CL_INVALID_VALUE) BRDFCL_CL_ERR(CL_INVALID_DEVICE_TYPE) BRDFCL_CL_ERR(CL_INVALID_PLATFORM)
    BRDFCL_CL_ERR(CL_INVALID_DEVICE) BRDFCL_CL_ERR(CL_INVALID_CONTEXT) BRDFCL_CL_ERR(CL_INVALID_QUEUE_PROPERTIES)
    BRDFCL_CL_ERR(CL_INVALID_COMMAND_QUEUE) BRDFCL_CL_ERR(CL_INVALID_HOST_PTR) BRDFCL_CL_ERR(CL_INVALID_MEM_OBJECT)
    BRDFCL_CL_ERR(CL_INVALID_BINARY) BRDFCL_CL_ERR(CL_INVALID_BUILD_OPTIONS) BRDFCL_CL_ERR(CL_INVALID_PROGRAM)
    BRDFCL_CL_ERR(CL_INVALID_PROGRAM_EXECUTABLE) BRDFCL_CL_ERR(CL_INVALID_KERNEL_NAME)
    BRDFCL_CL_ERR(CL_INVALID_KERNEL_DEFINITION) BRDFCL_CL_ERR(CL_INVALID_KERNEL) BRDFCL_CL_ERR(CL_INVALID_ARG_INDEX)
    BRDFCL_CL_ERR(CL_INVALID_ARG_VALUE) BRDFCL_CL_ERR(CL_INVALID_ARG_SIZE) BRDFCL_CL_ERR(CL_INVALID_KERNEL_ARGS)
    BRDFCL_CL_ERR(CL_INVALID_WORK_DIMENSION) BRDFCL_CL_ERR(CL_INVALID_WORK_GROUP_SIZE)
    BRDFCL_CL_ERR(CL_INVALID_WORK_ITEM_SIZE) BRDFCL_CL_ERR(CL_INVALID_GLOBAL_OFFSET)
    BRDFCL_CL_ERR(CL_INVALID_EVENT_WAIT_LIST) BRDFCL_CL_ERR(CL_INVALID_EVENT) BRDFCL_CL_ERR(CL_INVALID_OPERATION)
    BRDFCL_CL_ERR(CL_INVALID_BUFFER_SIZE) BRDFCL_CL_ERR(CL_INVALID_GLOBAL_WORK_SIZE)
    BRDFCL_CL_ERR(CL_INVALID_PROPERTY) BRDFCL_CL_ERR(CL_INVALID_COMPILER_OPTIONS)
    BRDFCL_CL_ERR(CL_INVALID_LINKER_OPTIONS)
#undef BRDFCL_CL_ERR
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";
    default: return "unknown OpenCL error";
  }
}

namespace {

// Where a caller lists the devices.
const char* devicesHint() { return optionStyle() == OptionStyle::Python ? "brdfcl.devices()" : "'brdfcl devices'"; }

constexpr const char* kNoPlatform = "no OpenCL platform found; install pocl-opencl-icd (make deps)";

// PoCL's CPU device runs one worker thread a core, unpinned by default. Linux then now and then
// leaves two of them on one core for a whole launch, which runs at half speed: launches of the
// same kernel took either t or 2t (docs/performance.md, "Run-to-run spread"). Pinned, they do not.
// Set before PoCL reads its environment (the first OpenCL call), and never over the user's value.
// PoCL's kernel cache folder is checked then too (runtime/pocl_cache_dir.hpp).
void pinPoclWorkers() {
  static std::once_flag once;
  std::call_once(once, [] {
    ::setenv("POCL_AFFINITY", "1", 0);
    detail::preparePoclCacheFolder();
  });
}

std::vector<cl::Platform> platformsOrThrow() {
  pinPoclWorkers();
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    platforms.clear();  // the ICD loader reports "no platform" as CL_PLATFORM_NOT_FOUND_KHR
  }
  if (platforms.empty()) throw Error(ErrorKind::Environment, kNoPlatform);
  return platforms;
}

std::vector<std::pair<cl::Device, cl::Platform>> allDevices() {
  std::vector<std::pair<cl::Device, cl::Platform>> out;
  for (auto& p : platformsOrThrow()) {
    std::vector<cl::Device> devices;
    try {
      p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform without devices answers CL_DEVICE_NOT_FOUND
    }
    for (auto& d : devices) out.emplace_back(d, p);
  }
  if (out.empty()) throw Error(ErrorKind::Environment, "no OpenCL device found; install pocl-opencl-icd (make deps)");
  return out;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
  return s;
}

DeviceInfo describe(std::size_t index, const cl::Device& d, const cl::Platform& p) {
  DeviceInfo info;
  info.index = index;
  info.name = trim(d.getInfo<CL_DEVICE_NAME>());
  info.platform = trim(p.getInfo<CL_PLATFORM_NAME>());
  auto type = d.getInfo<CL_DEVICE_TYPE>();
  info.type = (type & CL_DEVICE_TYPE_GPU) ? "GPU" : (type & CL_DEVICE_TYPE_CPU) ? "CPU"
              : (type & CL_DEVICE_TYPE_ACCELERATOR) ? "ACCELERATOR" : "OTHER";
  info.computeUnits = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
  info.openclC = trim(d.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
  info.maxAlloc = d.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  info.globalMem = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  return info;
}

// "OpenCL C 1.2 PoCL" -> -cl-std=CL1.2; devices that speak 3.0 still get the 1.2 dialect's
// guarantees unless they report 2.x/3.x, in which case CL3.0/CL2.0 is asked for explicitly.
std::string pickStd(const std::string& openclC) {
  int major = 1, minor = 2;
  if (std::sscanf(openclC.c_str(), "OpenCL C %d.%d", &major, &minor) != 2) return "-cl-std=CL1.2";
  if (major >= 3) return "-cl-std=CL3.0";
  if (major == 2) return "-cl-std=CL2.0";
  return fmt::format("-cl-std=CL{}.{}", major, minor);
}

void expandIncludes(const std::string& name, std::set<std::string>& seen, std::string& out);

// Appends `text` to `out` with each #include "..." line replaced by that embedded file, expanded.
void expandText(const std::string& text, std::set<std::string>& seen, std::string& out) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    auto pos = line.find("#include \"");
    if (pos != std::string::npos && line.find_first_not_of(" \t") == pos) {
      auto end = line.find('"', pos + 10);
      expandIncludes(line.substr(pos + 10, end - pos - 10), seen, out);
      continue;
    }
    out += line;
    out += '\n';
  }
}

void expandIncludes(const std::string& name, std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(name).second) return;  // every header has guards; skip the work as well
  const auto& files = detail::embeddedKernels();
  auto it = files.find(name);
  if (it == files.end()) throw Error(fmt::format("internal: kernel file '{}' is not embedded", name), 3);
  expandText(it->second, seen, out);
}

}  // namespace

void rethrowOpenCL(const std::string& what) {
  try {
    throw;
  } catch (const cl::BuildError& e) {
    std::string log;
    for (const auto& [dev, text] : e.getBuildLog()) log += text;
    throw Error(ErrorKind::Device, fmt::format("{}: OpenCL kernel build failed ({}); build log:\n{}", what, e.what(), log));
  } catch (const cl::Error& e) {
    const bool memory = e.err() == CL_OUT_OF_HOST_MEMORY || e.err() == CL_MEM_OBJECT_ALLOCATION_FAILURE;
    throw Error(memory ? ErrorKind::Memory : ErrorKind::Device,
                fmt::format("{}: OpenCL call {} failed: {} ({})", what, e.what(), clErrorName(e.err()), e.err()));
  }
}

std::vector<DeviceInfo> listDevices() {
  try {
    std::vector<DeviceInfo> out;
    auto devices = allDevices();
    for (std::size_t i = 0; i < devices.size(); ++i) out.push_back(describe(i, devices[i].first, devices[i].second));
    return out;
  } catch (const cl::Error&) {
    rethrowOpenCL("listing OpenCL devices");
  }
}

std::string kernelSource(const std::string& kernelFile) {
  std::set<std::string> seen;
  std::string out;
  expandIncludes(kernelFile, seen, out);
  return out;
}

Runtime::Runtime(const std::string& selector) : cl_(std::make_unique<OpenCL>(selector)) {}
Runtime::~Runtime() = default;
const DeviceInfo& Runtime::info() const { return cl_->info_; }
std::size_t Runtime::programsFromDiskCache() const { return cl_->fromDisk_; }
const std::string& Runtime::standardOption() const { return cl_->clStd_; }

Runtime::OpenCL::OpenCL(const std::string& selectorArg) {
  std::string selector = selectorArg;
  // The message names where the selector came from: a stale BRDFCL_DEVICE in a shell profile
  // is otherwise hard to spot.
  std::string source = optionName("--device");
  if (selector.empty()) {
    if (const char* env = std::getenv("BRDFCL_DEVICE")) {
      selector = env;
      source = "BRDFCL_DEVICE";
    }
  }
  try {
    auto devices = allDevices();
    std::size_t chosen = devices.size();
    if (selector.empty()) {
      chosen = 0;
    } else if (selector.find_first_not_of("0123456789") == std::string::npos) {
      // Digits only, so the one failure mode of stoull is overflow: report it as out of range.
      chosen = selector.size() > 9 ? devices.size() : std::size_t(std::stoull(selector));
      if (chosen >= devices.size())
        throw Error(fmt::format("{}{}{}: device index out of range: {} device(s) found; see {}", source,
                                source.back() == '=' ? "" : " ", selector, devices.size(), devicesHint()));
    } else {
      for (std::size_t i = 0; i < devices.size() && chosen == devices.size(); ++i) {
        if (describe(i, devices[i].first, devices[i].second).name.find(selector) != std::string::npos) chosen = i;
      }
      if (chosen == devices.size())
        throw Error(fmt::format("{}{}'{}': no OpenCL device matches; see {}", source, source.back() == '=' ? "" : " ",
                                selector, devicesHint()));
    }
    device_ = devices[chosen].first;
    info_ = describe(chosen, device_, devices[chosen].second);
    clStd_ = pickStd(info_.openclC);
    // OpenCL lets single-precision division be off by 2.5 ulp and sqrt by 3 (NVIDIA's are). The
    // row kernels normalize directions exactly as the host's readers do, to the bit, and every
    // result is then the same on any device that rounds these correctly; ask for it where offered,
    // except in the batch kernels on a GPU (mathOptions, Arithmetic::Batch).
    if (device_.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT)
      mathOptions_ = " -cl-fp32-correctly-rounded-divide-sqrt";
    fp64_ = device_.getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() != 0;
    context_ = cl::Context(device_);
    // Profiling costs nothing measurable on PoCL or NVIDIA, and lets the bench time the kernel
    // alone on devices whose result has to travel back to the host (SoaBatch::lastKernelSeconds).
    queue_ = cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE);
  } catch (const cl::Error&) {
    rethrowOpenCL("opening OpenCL device");
  }
}

namespace {
// Each evaluation path has a program of its own (eval/batch.hpp), so one set of materials and
// options takes up to four entries, a tenth to a twentieth of the size of one holding every kernel
// (mostly 0.1-0.5 MB against 3-4 MB with PoCL's binaries); the byte budget (BRDFCL_CACHE_MAX) bounds them too.
constexpr std::size_t kCachedPrograms = 512;
}  // namespace

std::string Runtime::OpenCL::mathOptions(Arithmetic arithmetic) const {
  std::string extra;
  if (const char* e = std::getenv("BRDFCL_BUILD_OPTIONS"); e && *e) extra = std::string(" ") + e;
  bool fast = info_.type != "CPU";
  if (const char* e = std::getenv("BRDFCL_BATCH_MATH")) {
    const std::string v = e;
    if (v != "exact" && v != "fast")
      throw Error(fmt::format("BRDFCL_BATCH_MATH={} is not supported; use exact or fast", v));
    fast = v == "fast";
  }
  if (arithmetic == Arithmetic::Exact || !fast) return mathOptions_ + extra;
  return (fp64_ ? std::string(" -DBRDFCL_ROWS_FP64=1") : mathOptions_) + " -DBRDFCL_NATIVE_MATH=1" + extra;
}

cl::Program Runtime::OpenCL::program(const std::string& kernelFile, const std::string& defines,
                                     Arithmetic arithmetic) {
  return buildExpanded(kernelFile, kernelSource(kernelFile), defines, arithmetic);
}

cl::Program Runtime::OpenCL::programFromSource(const std::string& tag, const std::string& source,
                                               const std::string& defines) {
  std::set<std::string> seen;
  std::string expanded;
  expandText(source, seen, expanded);
  return buildExpanded(tag, expanded, defines, Arithmetic::Exact);
}

cl::Program Runtime::OpenCL::buildExpanded(const std::string& tag, const std::string& source,
                                           const std::string& defines, Arithmetic arithmetic) {
  // -w: PoCL prints clang warnings (e.g. the float16 ABI note on AVX2) to stderr; real
  // problems are errors and reach the user through the build log.
  std::string options = clStd_ + mathOptions(arithmetic) + " -w " + defines;
  std::lock_guard<std::mutex> lock(cacheMutex_);
  auto key = std::make_pair(options, source);
  if (auto it = cache_.find(key); it != cache_.end()) return it->second;
  // A binary this device built before, from brdfcl's disk cache: PoCL's own cache still
  // preprocesses the source (its opencl-c.h included) on every process start to find its entry,
  // about 17 ms a program. The name's hash covers the source, the options and the device and
  // driver versions; a binary the device refuses is rebuilt from source.
  const std::string binaryName = fmt::format(
      "program_{:016x}.bin",
      detail::contentHash(source, detail::contentHash(options + '\n' + info_.name + '\n' + info_.platform + '\n' +
                                                      device_.getInfo<CL_DEVICE_VERSION>() + '\n' +
                                                      device_.getInfo<CL_DRIVER_VERSION>())));
  cl::Program program;
  if (const std::string binary = detail::loadCachedPayload(binaryName); !binary.empty()) {
    try {
      // The C call takes the bytes where they were read (cl::Program::Binaries would copy them).
      const std::size_t size = binary.size();
      const auto* bytes = reinterpret_cast<const unsigned char*>(binary.data());
      cl_device_id device = device_();
      cl_int status = CL_SUCCESS, error = CL_SUCCESS;
      cl_program raw = clCreateProgramWithBinary(context_(), 1, &device, &size, &bytes, &status, &error);
      if (error != CL_SUCCESS) throw cl::Error(error, "clCreateProgramWithBinary");
      program = cl::Program(raw);
      program.build(std::vector<cl::Device>{device_}, options.c_str());
      ++fromDisk_;
    } catch (const cl::Error&) {
      program = cl::Program();
    }
  }
  if (program() == nullptr) {
    try {
      program = cl::Program(context_, source);
      program.build(std::vector<cl::Device>{device_}, options.c_str());
    } catch (const cl::Error&) {
      rethrowOpenCL(fmt::format("building {} with '{}'", tag, options));
    }
    try {
      const auto binaries = program.getInfo<CL_PROGRAM_BINARIES>();
      if (binaries.size() == 1 && !binaries[0].empty()) {
        detail::storeCachedBytes(binaryName, binaries[0]);
        // Every kernel change and option set makes a new entry: keep the most recently used.
        detail::pruneCached("program_", kCachedPrograms);
      }
    } catch (const cl::Error&) {
      // A device that cannot hand out its binary just builds from source next time.
    }
  }
  cache_.emplace(std::move(key), program);
  return program;
}

}  // namespace brdfcl
