// Files that an asset or a scene file names inside itself: glTF buffer and image URIs and a
// scene's environment path stay inside the naming file's folder and open regular files only; a
// refusal names the URI as written and nothing about what lies outside; --allow-outside-uris opts in.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/scene.hpp"
#include "gltf_builder.hpp"
#include "process.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const std::vector<float> kP = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<float> kN = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
const std::vector<float> kUv = {0, 1, 1, 1, 1, 0, 0, 0};
const std::vector<std::uint32_t> kI = {0, 1, 2, 0, 2, 3};

// A textured quad: buffers[0] is m.bin, images[0] is t.png.
GltfBuilder texturedQuad() {
  GltfBuilder b;
  const int tex = b.addTexture(b.addImage(encodePng8(1, 1, 3, {200, 100, 50}), "image/png", "t.png"));
  const int mat = b.addMaterial({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", tex}}}}}});
  b.addScene({b.addMeshNode(b.addTriangles(kP, kI, mat, kN, kUv))});
  return b;
}

class GltfConfinement : public ::testing::Test {
 protected:
  ScratchDir scratch{"gltf-confinement"};

  void SetUp() override {
    fs::create_directories(scratch.path("asset"));
    fs::create_directories(scratch.path("secret"));
  }

  // asset/m.gltf with its external files; `edit` rewrites its JSON. Returns the .gltf path.
  std::string asset(const std::function<void(json&)>& edit = {}) {
    const std::string p = texturedQuad().write(scratch.path("asset"), "m.gltf", Storage::ExternalFiles);
    if (edit) {
      json d = json::parse(slurp(p));
      edit(d);
      GltfBuilder::writeFile(p, d.dump(1));
    }
    return p;
  }

  // asset/m.gltf whose buffers[0].uri is `uri`, with its bytes moved to secret/x.bin.
  std::string bufferAt(const std::string& uri) {
    const std::string p = asset([&](json& d) { d["buffers"][0]["uri"] = uri; });
    fs::rename(scratch.path("asset/m.bin"), scratch.path("secret/x.bin"));
    return p;
  }

  std::string loadError(const std::string& path, bool allowOutside = false) {
    gltf::LoadOptions o;
    o.allowOutsideUris = allowOutside;
    return errorOf([&] { gltf::load(path, o); });
  }

  RunResult gbuffer(const std::string& gltfPath, std::vector<std::string> extra = {}) {
    std::vector<std::string> argv{BRDFCL_CLI_PATH, "gbuffer", "--gltf", gltfPath, "--size", "8x8", "--out",
                                  scratch.path("g.exr")};
    argv.insert(argv.end(), extra.begin(), extra.end());
    ProcessOptions o;
    o.timeout = std::chrono::seconds(60);  // a FIFO opened for reading would block forever
    if (!kAddressSanitizer) o.addressSpaceMiB = 4096;  // /dev/zero read to the end would not stop sooner
    fs::create_directories(scratch.path("run"));
    return runProcess(argv, scratch.path("run"), o);
  }

  // One error line, exit 2, no output file.
  void expectRefused(const RunResult& r, const std::string& message) {
    EXPECT_EQ(r.status, 2) << r.describe();
    ASSERT_EQ(r.errorLines().size(), 1u) << r.describe();
    EXPECT_EQ(r.errorLines()[0], "brdfcl: " + message);
    EXPECT_FALSE(fs::exists(scratch.path("g.exr")));
  }
};

constexpr const char* kOutside =
    "points outside the asset's folder; move the file into the folder, or pass --allow-outside-uris";
constexpr const char* kLink =
    "is or passes through a symbolic link, which brdfcl does not follow from an asset's folder; copy the file in, or "
    "pass --allow-outside-uris";
constexpr const char* kNotRegular = "is not a regular file (a directory, FIFO or device); name a file";

TEST_F(GltfConfinement, DotDotBufferIsRefusedAndAllowedOnRequest) {
  const std::string p = bufferAt("../secret/x.bin");
  EXPECT_EQ(loadError(p), p + ": buffers[0].uri '../secret/x.bin' " + kOutside);
  expectRefused(gbuffer(p), p + ": buffers[0].uri '../secret/x.bin' " + kOutside);
  const RunResult r = gbuffer(p, {"--allow-outside-uris"});
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(fs::exists(scratch.path("g.exr")));
  EXPECT_EQ(gltf::load(p, [] {
              gltf::LoadOptions o;
              o.allowOutsideUris = true;
              return o;
            }()).primitives.size(),
            1u);
}

TEST_F(GltfConfinement, PercentEncodedDotDotIsRefused) {
  const std::string p = bufferAt("%2e%2e%2fsecret%2Fx.bin");
  EXPECT_EQ(loadError(p), p + ": buffers[0].uri '%2e%2e%2fsecret%2Fx.bin' " + kOutside);
}

TEST_F(GltfConfinement, AbsolutePathSaysNothingAboutTheTarget) {
  const std::string p = asset([](json& d) {
    d["buffers"][0]["uri"] = "/etc/passwd";
    d["buffers"][0]["byteLength"] = 1;
    d["bufferViews"] = json::array({{{"buffer", 0}, {"byteLength", 1}}});
  });
  const std::string e = loadError(p);
  EXPECT_EQ(e, p + ": buffers[0].uri '/etc/passwd' " + kOutside);
  EXPECT_EQ(e.find("bytes"), std::string::npos) << e;
  const std::string traversal = asset([](json& d) { d["buffers"][0]["uri"] = "../../../../../../../../etc/passwd"; });
  EXPECT_EQ(loadError(traversal), traversal + ": buffers[0].uri '../../../../../../../../etc/passwd' " + kOutside);
}

TEST_F(GltfConfinement, DevZeroIsRefusedBeforeReading) {
  const std::string p = asset([](json& d) { d["buffers"][0]["uri"] = "/dev/zero"; });
  expectRefused(gbuffer(p), p + ": buffers[0].uri '/dev/zero' " + kOutside);
  expectRefused(gbuffer(p, {"--allow-outside-uris"}), p + ": buffers[0].uri '/dev/zero' " + kNotRegular);
}

TEST_F(GltfConfinement, FifoInsideTheFolderDoesNotHang) {
  const std::string p = asset([](json& d) { d["buffers"][0]["uri"] = "pipe.bin"; });
  ASSERT_EQ(::mkfifo(scratch.path("asset/pipe.bin").c_str(), 0600), 0);
  expectRefused(gbuffer(p), p + ": buffers[0].uri 'pipe.bin' " + kNotRegular);
  expectRefused(gbuffer(p, {"--allow-outside-uris"}), p + ": buffers[0].uri 'pipe.bin' " + kNotRegular);
}

TEST_F(GltfConfinement, SymbolicLinksInsideDoNotLeadOut) {
  const std::string p = bufferAt("link.bin");
  ASSERT_EQ(::symlink("../secret/x.bin", scratch.path("asset/link.bin").c_str()), 0);
  EXPECT_EQ(loadError(p), p + ": buffers[0].uri 'link.bin' " + kLink);
  // A linked folder on the way.
  const std::string q = asset([](json& d) { d["buffers"][0]["uri"] = "sub/x.bin"; });
  ASSERT_EQ(::symlink("../secret", scratch.path("asset/sub").c_str()), 0);
  EXPECT_EQ(loadError(q), q + ": buffers[0].uri 'sub/x.bin' " + kLink);
  const RunResult r = gbuffer(q, {"--allow-outside-uris"});
  EXPECT_EQ(r.status, 0) << r.describe();
}

TEST_F(GltfConfinement, ImageUriIsConfinedToo) {
  const std::string p = asset([](json& d) { d["images"][0]["uri"] = "../secret/t.png"; });
  fs::rename(scratch.path("asset/t.png"), scratch.path("secret/t.png"));
  EXPECT_EQ(loadError(p), p + ": images[0].uri '../secret/t.png' " + kOutside);
  expectRefused(gbuffer(p), p + ": images[0].uri '../secret/t.png' " + kOutside);
  EXPECT_EQ(gbuffer(p, {"--allow-outside-uris"}).status, 0);
  ASSERT_EQ(::symlink("../secret/t.png", scratch.path("asset/t.png").c_str()), 0);
  const std::string q = asset();
  EXPECT_EQ(loadError(q), q + ": images[0].uri 't.png' " + kLink);
}

TEST_F(GltfConfinement, GlbExternalBufferIsConfined) {
  GltfBuilder b = texturedQuad();
  b.extraBuffers.push_back({{"byteLength", 4}, {"uri", "../secret/x.bin"}});
  GltfBuilder::writeFile(scratch.path("secret/x.bin"), "abcd");
  const std::string p = b.write(scratch.path("asset"), "m.glb", Storage::Glb);
  EXPECT_EQ(loadError(p), p + ": buffers[1].uri '../secret/x.bin' " + kOutside);
  EXPECT_EQ(gbuffer(p, {"--allow-outside-uris"}).status, 0);
}

TEST_F(GltfConfinement, SchemesAndNulAreRefused) {
  const std::string p = asset([](json& d) { d["buffers"][0]["uri"] = "file:///etc/passwd"; });
  EXPECT_EQ(loadError(p, true),
            p + ": buffers[0].uri 'file:///etc/passwd' has the URI scheme 'file:'; brdfcl reads files in the asset's "
                "folder and data: URIs only: save the file next to the asset and name it by a relative path");
  const std::string h = asset([](json& d) { d["images"][0]["uri"] = "https://example.com/t.png"; });
  EXPECT_CONTAINS(loadError(h), ": images[0].uri 'https://example.com/t.png' has the URI scheme 'https:'");
  const std::string n = asset([](json& d) { d["buffers"][0]["uri"] = "m.bin%00.png"; });
  EXPECT_EQ(loadError(n), n + ": buffers[0].uri 'm.bin%00.png' holds a NUL character (%00) once percent-decoded; "
                              "re-export the file");
}

TEST_F(GltfConfinement, InsideNamesStillLoad) {
  fs::create_directories(scratch.path("asset/sub"));
  const std::string p = asset([](json& d) {
    d["buffers"][0]["uri"] = "sub/../m.bin";
    d["images"][0]["uri"] = "./sub/%2E%2E/t.png";
  });
  const gltf::Asset a = gltf::load(p);
  EXPECT_EQ(a.primitives.size(), 1u);
  ASSERT_EQ(a.images.size(), 1u);
  EXPECT_EQ(a.images[0].width, 1);
  // A backslash is an ordinary character of a file name, as on POSIX: "..\" is no step up.
  const std::string q = asset([](json& d) { d["buffers"][0]["uri"] = "a\\b.bin"; });
  fs::rename(scratch.path("asset/m.bin"), scratch.path("asset/a\\b.bin"));
  EXPECT_EQ(gltf::load(q).primitives.size(), 1u);
  const std::string r = asset([](json& d) { d["buffers"][0]["uri"] = "..\\secret\\x.bin"; });
  EXPECT_EQ(loadError(r), r + ": buffers[0]: cannot read '..\\secret\\x.bin': No such file or directory");
}

TEST_F(GltfConfinement, LongerBufferFileIsPadding) {
  const std::string p = asset();
  std::ofstream(scratch.path("asset/m.bin"), std::ios::binary | std::ios::app) << std::string(8, '\0');
  EXPECT_EQ(gltf::load(p).primitives.size(), 1u);
  fs::resize_file(scratch.path("asset/m.bin"), 4);
  EXPECT_CONTAINS(loadError(p), ": buffers[0]: 'm.bin' has 4 bytes, but byteLength says");
}

TEST_F(GltfConfinement, DirectoryIsNotARegularFile) {
  const std::string p = asset([](json& d) { d["images"][0]["uri"] = "sub"; });
  fs::create_directories(scratch.path("asset/sub"));
  EXPECT_EQ(loadError(p), p + ": images[0].uri 'sub' " + kNotRegular);
}

TEST_F(GltfConfinement, ImageFileSizeIsBoundedBeforeReading) {
  const std::string p = asset();
  fs::resize_file(scratch.path("asset/t.png"), std::uintmax_t(1) << 31);  // sparse: no disk, nothing read
  EXPECT_EQ(loadError(p), p + ": images[0].uri 't.png' has 2147483648 bytes, more than the 2147483647 brdfcl reads "
                              "for an image; save it smaller");
}

TEST_F(GltfConfinement, DataUriTinygltfCannotDecodeIsNotAFileName) {
  const std::string p = asset([](json& d) { d["buffers"][0]["uri"] = "data:text/plain,abc"; });
  EXPECT_CONTAINS(loadError(p), ": a buffer or image URI names '");
  EXPECT_CONTAINS(loadError(p), "', which brdfcl does not read; use a file in the asset's folder or a base64 data: URI");
}

// --- a scene file's environment path ------------------------------------------------------------

class SceneConfinement : public GltfConfinement {
 protected:
  std::string sceneError(const std::string& path, bool allowOutside = false) {
    return errorOf([&] { parseScene(R"({"environment": {"path": ")" + path + R"("}})", "s.json", scratch.path("asset"), allowOutside); });
  }
};

TEST_F(SceneConfinement, EnvironmentPathStaysInTheScenesFolder) {
  GltfBuilder::writeFile(scratch.path("secret/env.hdr"), "#?RADIANCE\n");
  const std::string outside =
      "points outside the scene file's folder; move the file into the folder, or pass --allow-outside-uris";
  EXPECT_EQ(sceneError("../secret/env.hdr"), "s.json: environment.path '../secret/env.hdr' " + outside);
  EXPECT_EQ(sceneError(scratch.path("secret/env.hdr")),
            "s.json: environment.path '" + scratch.path("secret/env.hdr") + "' " + outside);
  EXPECT_EQ(sceneError("/dev/zero"), "s.json: environment.path '/dev/zero' " + outside);
  EXPECT_EQ(sceneError("/dev/zero", true),
            "s.json: environment.path '/dev/zero' is not a regular file (a directory, FIFO or device); name a file");
  ASSERT_EQ(::mkfifo(scratch.path("asset/pipe.hdr").c_str(), 0600), 0);
  EXPECT_EQ(sceneError("pipe.hdr"),
            "s.json: environment.path 'pipe.hdr' is not a regular file (a directory, FIFO or device); name a file");
  ASSERT_EQ(::symlink("../secret/env.hdr", scratch.path("asset/env.hdr").c_str()), 0);
  EXPECT_CONTAINS(sceneError("env.hdr"), "s.json: environment.path 'env.hdr' is or passes through a symbolic link");
  EXPECT_CONTAINS(sceneError("a\\u0000b.hdr"), "' holds a NUL character; name a file");
  const Scene s = parseScene(R"({"environment": {"path": "../secret/env.hdr"}})", "s.json", scratch.path("asset"), true);
  EXPECT_EQ(fs::path(s.environment.path), fs::path(scratch.path("asset")) / "../secret/env.hdr");
}

}  // namespace
}  // namespace brdfcl::test
