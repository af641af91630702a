// Workload generation: materials per lobe and in-domain directions (N.L, N.V in [0.01, 1]) from
// a fast counter-based generator, since 64M samples must not take longer to make than to run.
#include "eval/workload.hpp"

#include "brdfcl/error.hpp"
#include "eval/splitmix64.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace brdfcl::bench {

namespace {
// Uniform floats in [0, 1) and in [a, b) from SplitMix64.
struct Rng {
  detail::SplitMix64 bits;
  float uniform() { return bits.uniformFloat(); }
  float in(float a, float b) { return a + (b - a) * uniform(); }
};
}  // namespace

const std::vector<std::string>& workloadNames() {
  static const std::vector<std::string> names = {"sheen", "specular", "clearcoat", "all"};
  return names;
}

Workload makeWorkload(const std::string& name, std::uint64_t seed, std::size_t materials) {
  const auto& names = workloadNames();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw Error("unknown --lobe value '" + name + "'; use sheen, specular, clearcoat or all");
  Workload w;
  w.name = name;
  w.options.lobe = name == "sheen" ? Lobe::Sheen : name == "specular" ? Lobe::Specular
                   : name == "clearcoat" ? Lobe::Clearcoat : Lobe::All;
  Rng rng{{seed * 0x2545f4914f6cdd1dull}};
  const bool sheen = name == "sheen" || name == "all";
  const bool coat = name == "clearcoat" || name == "all";
  const bool aniso = name == "specular" || name == "all";
  for (std::size_t i = 0; i < materials; ++i) {
    MaterialParams m;
    m.baseColor = {rng.uniform(), rng.uniform(), rng.uniform()};
    m.metallic = rng.uniform();
    m.roughness = rng.in(0.05f, 1.0f);
    if (sheen) {
      m.sheenColor = {rng.in(0.01f, 1.0f), rng.in(0.01f, 1.0f), rng.in(0.01f, 1.0f)};
      m.sheenRoughness = rng.in(0.05f, 1.0f);
    }
    if (coat) {
      m.clearcoat = rng.in(0.01f, 1.0f);
      m.clearcoatRoughness = rng.in(0.05f, 1.0f);
    }
    if (aniso) {
      m.anisotropyStrength = rng.in(0.01f, 1.0f);
      m.anisotropyRotation = rng.in(-3.14159f, 3.14159f);
    }
    w.materials.push_back(m);
  }
  return w;
}

Bench::Bench(Runtime& rt, const std::string& workload, std::size_t n, std::uint64_t seed, std::size_t materials,
             Profile profile)
    : workload_(makeWorkload(workload, seed, materials)), n_(n) {
  if (profile != Profile::Spec) {
    // An engine's own sheen: the spec's sheen variants of the workload do not apply.
    const Lobe lobe = workload_.options.lobe;
    workload_.options = EvalOptions{};
    workload_.options.lobe = lobe;
    workload_.options.profile = profile;
  }
  evaluator_ = std::make_unique<Evaluator>(rt, workload_.options);
  batch_ = std::make_unique<SoaBatch>(*evaluator_, workload_.materials, n);
  Rng rng{seed};
  float* dir[6];
  for (int k = 0; k < 6; ++k) dir[k] = batch_->direction(k);
  std::uint32_t* index = batch_->materialIndex();
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 2; ++d) {
      const float z = rng.in(0.01f, 1.0f), phi = rng.in(0.0f, 6.2831853f), s = std::sqrt(1.0f - z * z);
      dir[3 * d][i] = s * std::cos(phi);
      dir[3 * d + 1][i] = s * std::sin(phi);
      dir[3 * d + 2][i] = z;
    }
    // A modulo, not a mask, for any K.
    index[i] = std::uint32_t(rng.bits.next() % materials);
  }
  for (auto& p : peerOut_) p.assign(batch_->capacity(), 0.0f);
  for (int k = 0; k < 6; ++k) peerInput_.dir[k] = batch_->directionPlane(k);
  peerInput_.material = batch_->materialIndexPlane();
  peerInput_.materials = batch_->packedMaterials().data();
  peerInput_.sheenE = batch_->sheenAlbedoValues().data();
  peerInput_.sheenESize = batch_->sheenAlbedoSize();
  for (int c = 0; c < 3; ++c) peerInput_.out[c] = peerOut_[c].data();
  peerInput_.count = n;
}

Bench::~Bench() = default;

void Bench::setDirections(const std::vector<float>& planes) {
  if (planes.size() != 6 * n_) throw Error("direction planes hold " + std::to_string(planes.size()) + " floats; expected 6 x " + std::to_string(n_));
  for (int k = 0; k < 6; ++k) std::copy(planes.begin() + k * n_, planes.begin() + (k + 1) * n_, batch_->direction(k));
}

void Bench::setMaterialIndices(const std::vector<std::uint32_t>& index) {
  if (index.size() != n_) throw Error("material indices hold " + std::to_string(index.size()) + " values; expected " + std::to_string(n_));
  for (std::uint32_t k : index)
    if (k >= workload_.materials.size())
      throw Error("material index " + std::to_string(k) + " is not below the material count " +
                  std::to_string(workload_.materials.size()));
  std::copy(index.begin(), index.end(), batch_->materialIndex());
}

double Bench::peerDeviation() const {
  double worst = 0;
  for (int c = 0; c < 3; ++c) {
    const float* k = batch_->result(c);
    for (std::size_t i = 0; i < n_; ++i)
      worst = std::max(worst, double(std::fabs(k[i] - peerOut_[c][i]) / (std::fabs(k[i]) + 1e-3f)));
  }
  return worst;
}

}  // namespace brdfcl::bench
