// The benchmark workloads shared by build/bin/brdfcl-bench and `brdfcl bench`: per lobe, K
// random materials (256 by default) carrying exactly that lobe's layers, and N random in-domain samples written
// straight into a SoaBatch so that the kernel and the C++ peers (bench/peers) read the same arrays.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "host/src/eval/peer_input.hpp"

namespace brdfcl::bench {

// "sheen": ratified sheen only, sheenColor D_Charlie V_Charlie (the --lobe sheen contract);
// "specular": anisotropic base specular; "clearcoat": clearcoat only; "all": every layer with
// min albedo scaling from the E table.
const std::vector<std::string>& workloadNames();

struct Workload {
  std::string name;
  EvalOptions options;
  std::vector<MaterialParams> materials;
};
// The first materials of a count-K workload are the same for any K (one generator, drawn in order).
constexpr std::size_t kDefaultMaterials = 256;
Workload makeWorkload(const std::string& name, std::uint64_t seed = 1, std::size_t materials = kDefaultMaterials);

// Bytes a sample moves: L and V (24), the material index (4) and RGB out (12).
constexpr double kBytesPerSample = 40.0;

// A workload's batch of n samples on the device, plus separate output planes for the peers.
class Bench {
 public:
  // `profile` evaluates the workload's materials and pairs under an engine profile
  // (docs/profiles.md); the C++ peers compute the spec, so they only pair with Profile::Spec.
  Bench(Runtime& rt, const std::string& workload, std::size_t n, std::uint64_t seed = 1,
        std::size_t materials = kDefaultMaterials, Profile profile = Profile::Spec);
  ~Bench();
  std::size_t size() const { return n_; }
  const Workload& workload() const { return workload_; }
  void runKernel() { batch_->run(); }
  Evaluator& evaluator() { return *evaluator_; }
  const SoaBatch& batch() const { return *batch_; }
  // The batch's planes as the peers read them, with output planes of their own.
  const peers::Input& peerInput() const { return peerInput_; }
  // Largest |kernel - peer| / (|kernel| + 1e-3) over the batch, after both ran.
  double peerDeviation() const;
  // Replaces the random directions with given ones, six planes of size() floats (L.xyz, V.xyz),
  // so that an outside peer (bench/peers/mitsuba_peer.py) and the kernel evaluate the same pairs.
  void setDirections(const std::vector<float>& planes);
  // Replaces the random material indices with given ones, size() values below the material count.
  void setMaterialIndices(const std::vector<std::uint32_t>& index);

 private:
  Workload workload_;
  std::size_t n_;
  std::unique_ptr<Evaluator> evaluator_;
  std::unique_ptr<SoaBatch> batch_;
  std::vector<float> peerOut_[3];
  peers::Input peerInput_{};
};

}  // namespace brdfcl::bench
