// brdfcl::gltf::load: .gltf/.glb through tinygltf into world-space triangle lists (gltf.hpp).
// brdfcl checks what tinygltf trusts (the GLB header, buffer view ranges, the node graph) before
// tinygltf or the walk relies on it, and owns file reading and image decoding through tinygltf's
// callbacks, so that every failure is one line naming the file and the JSON path.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf.hpp"
#include "gltf/accessors.hpp"
#include "gltf/document.hpp"
#include "gltf/draco.hpp"
#include "gltf/images.hpp"
#include "gltf/meshopt.hpp"
#include "gltf/tangents.hpp"
#include "io/confined_open.hpp"
#include "io/files.hpp"
#include "io/glb.hpp"
#include "io/input_limits.hpp"
#include "io/messages.hpp"
#include "io/option_style.hpp"

namespace brdfcl::gltf {
namespace {

using json = nlohmann::json;
using brdfcl::detail::printable;

using brdfcl::detail::kGlbMagic;
using brdfcl::detail::le32;

std::string at(const char* kind, std::size_t i) { return std::string(kind) + "[" + std::to_string(i) + "]"; }

// A buffer or image URI, as tinygltf will ask for it.
struct External {
  std::string label;  // "buffers[0]", "images[0] ('wood.png')": what cannot-read messages name
  std::string field;  // "buffers[0].uri": what refusals name
  std::string uri;    // as written
  std::string name;   // percent-decoded, relative to the asset's folder
  bool buffer = false;
  std::uint64_t length = 0;  // a buffer's byteLength
};

// The largest image file read (stb_image takes an int size).
constexpr std::uint64_t kMaxImageFileBytes = 0x7FFFFFFF;

// What the tinygltf callbacks share with the loader.
struct Context {
  std::string source;   // the file name as messages show it
  std::string baseDir;
  LoadOptions options;
  std::map<std::string, External> files;  // the path tinygltf builds for a URI -> the URI
  std::vector<bool> imageUsed;                   // by a texture: only those are decoded
  std::vector<Image> images;
  std::string error;  // the first failure seen in a callback; it wins over tinygltf's own text

  [[noreturn]] void fail(const std::string& where, const std::string& message) const {
    throw Error(source + ": " + where + ": " + message);
  }
};

// The GLB `b` (checked by glbJsonChunk) with its JSON chunk replaced by `text`, the BIN chunk kept.
std::string withJsonChunk(const std::string& b, std::string text) {
  while (text.size() % 4) text += ' ';
  const std::string rest = b.substr(20 + std::size_t(le32(b, 12)));
  auto le = [](std::size_t v) {
    return std::string{char(v & 255), char((v >> 8) & 255), char((v >> 16) & 255), char((v >> 24) & 255)};
  };
  return "glTF" + le(2) + le(20 + text.size() + rest.size()) + le(text.size()) + "JSON" + text + rest;
}

// tinygltf copies "extras" and "extensions" recursively: a hostile file nesting arrays a million
// deep would overflow the stack there, so the depth is checked here, without recursion.
constexpr std::size_t kMaxDepth = 128;

std::size_t nestingDepth(const json& root) {
  std::size_t deepest = 0;
  std::vector<std::pair<const json*, std::size_t>> stack{{&root, 1}};
  while (!stack.empty()) {
    const auto [v, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    if (depth > kMaxDepth) break;
    if (v->is_structured())
      for (const json& child : *v) stack.emplace_back(&child, depth + 1);
  }
  return deepest;
}

json parseJson(const std::string& text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(source + ": invalid JSON: " + printable(brdfcl::detail::withoutJsonTag(e.what()), 300) +
                "; the file is not glTF 2.0 or is corrupt");
  }
  if (!doc.is_object()) throw Error(source + ": expected a glTF JSON object at the top level, got " + brdfcl::detail::describeJson(doc));
  if (nestingDepth(doc) > kMaxDepth)
    throw Error(source + ": the JSON nests deeper than " + std::to_string(kMaxDepth) +
                " levels (in extras?); glTF needs far fewer: re-export the file");
  return doc;
}

// The path tinygltf builds for a URI (its decoding, joined to baseDir), so that its file callbacks
// can be mapped back to buffers[i]/images[i].
std::string resolved(const std::string& baseDir, const std::string& uri) {
  const std::string f = brdfcl::detail::uriDecoded(uri);
  if (baseDir.empty()) return f;
  return baseDir.back() == '/' ? baseDir + f : baseDir + "/" + f;
}

bool isDataUri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

std::string quoted(const std::string& uri) { return "'" + printable(uri, 200) + "'"; }

// "m.gltf: buffers[0].uri '../x.bin' <what>": a refusal that names the URI as written.
std::string refusal(const Context& ctx, const External& e, const std::string& what) {
  return ctx.source + ": " + e.field + " " + quoted(e.uri) + " " + what;
}

[[noreturn]] void refuse(const Context& ctx, const External& e, const std::string& what) {
  throw Error(refusal(ctx, e, what));
}

std::string outsideRefusal() {
  return "points outside the asset's folder; move the file into the folder, or pass " + flagName("--allow-outside-uris");
}

// A URI's own refusals, before any file is looked at: what lies outside the folder is not
// stat'ed, so a refusal says nothing about it. Registers the URI for readFile.
void registerUri(Context& ctx, const std::string& label, const std::string& field, const std::string& uri, bool buffer,
                 std::uint64_t length) {
  External e{label, field, uri, brdfcl::detail::uriDecoded(uri), buffer, length};
  if (!isDataUri(uri)) {
    if (const std::string scheme = brdfcl::detail::uriScheme(uri); !scheme.empty())
      refuse(ctx, e, "has the URI scheme '" + printable(scheme, 40) +
                         ":'; brdfcl reads files in the asset's folder and data: URIs only: save the file next to the "
                         "asset and name it by a relative path");
    if (e.name.find('\0') != std::string::npos)
      refuse(ctx, e, "holds a NUL character (%00) once percent-decoded; re-export the file");
    if (!ctx.options.allowOutsideUris && !brdfcl::detail::staysInside(e.name))
      refuse(ctx, e, outsideRefusal());
  }
  ctx.files[resolved(ctx.baseDir, uri)] = std::move(e);
}

std::uint64_t unsignedAt(const Context& ctx, const json& obj, const char* key, const std::string& path, bool required) {
  const auto it = obj.find(key);
  if (it == obj.end()) {
    if (required) ctx.fail(path, std::string("missing \"") + key + "\"; re-export the file");
    return 0;
  }
  if (!it->is_number_unsigned() && !(it->is_number_integer() && it->get<long long>() >= 0))
    ctx.fail(path + "." + key, "expected an integer >= 0, got " + brdfcl::detail::describeJson(*it));
  return it->get<std::uint64_t>();
}

// Buffers and buffer views as the JSON declares them, checked before tinygltf slices buffers by
// them (it does not check image buffer views), and the external files named, for messages.
void checkBuffers(const json& doc, Context& ctx, bool glb, std::size_t binSize, const std::vector<bool>& fallbacks) {
  std::vector<std::uint64_t> lengths;
  if (const auto it = doc.find("buffers"); it != doc.end() && it->is_array()) {
    for (std::size_t i = 0; i < it->size(); ++i) {
      const json& b = (*it)[i];
      const std::string path = at("buffers", i);
      if (!b.is_object()) ctx.fail(path, "expected an object, got " + brdfcl::detail::describeJson(b));
      const std::uint64_t length = unsignedAt(ctx, b, "byteLength", path, true);
      lengths.push_back(length);
      const auto uri = b.find("uri");
      if (i < fallbacks.size() && fallbacks[i]) continue;  // no bytes: only compressed views decode into it
      if (uri == b.end() || !uri->is_string()) {
        if (!glb || i != 0) ctx.fail(path, "no \"uri\" (only the first buffer of a .glb may omit it); re-export the file");
        if (length > binSize)
          ctx.fail(path + ".byteLength", std::to_string(length) + " is more than the " + std::to_string(binSize) +
                                             " bytes of the GLB's BIN chunk; re-export the file");
        continue;
      }
      const std::string u = uri->get<std::string>();
      if (!isDataUri(u)) registerUri(ctx, path, path + ".uri", u, true, length);
    }
  }
  if (const auto it = doc.find("bufferViews"); it != doc.end() && it->is_array()) {
    for (std::size_t i = 0; i < it->size(); ++i) {
      const json& v = (*it)[i];
      const std::string path = at("bufferViews", i);
      if (!v.is_object()) ctx.fail(path, "expected an object, got " + brdfcl::detail::describeJson(v));
      const std::uint64_t buffer = unsignedAt(ctx, v, "buffer", path, true);
      if (buffer >= lengths.size())
        ctx.fail(path + ".buffer", "buffer " + std::to_string(buffer) + " does not exist (the file has " +
                                       std::to_string(lengths.size()) + "); re-export the file");
      const std::uint64_t offset = unsignedAt(ctx, v, "byteOffset", path, false);
      const std::uint64_t length = unsignedAt(ctx, v, "byteLength", path, true);
      if (length == 0) ctx.fail(path + ".byteLength", "expected at least 1, got 0; re-export the file");
      if (offset > lengths[buffer] || length > lengths[buffer] - offset)
        ctx.fail(path, "bytes " + std::to_string(offset) + " + " + std::to_string(length) + " lie outside buffers[" +
                           std::to_string(buffer) + "] of " + std::to_string(lengths[buffer]) + " bytes; re-export the file");
    }
  }
}

std::string imageLabel(const json& img, std::size_t i) {
  std::string name;
  if (const auto u = img.find("uri"); u != img.end() && u->is_string() && !isDataUri(u->get<std::string>()))
    name = u->get<std::string>();
  else if (const auto n = img.find("name"); n != img.end() && n->is_string())
    name = n->get<std::string>();
  return name.empty() ? at("images", i) : at("images", i) + " ('" + printable(name, 120) + "')";
}

void registerImages(const json& doc, Context& ctx) {
  const auto images = doc.find("images");
  const std::size_t count = images != doc.end() && images->is_array() ? images->size() : 0;
  ctx.imageUsed.assign(count, false);
  ctx.images.assign(count, Image{});
  for (std::size_t i = 0; i < count; ++i) {
    const json& img = (*images)[i];
    if (!img.is_object()) continue;
    ctx.images[i].name = at("images", i);
    if (const auto u = img.find("uri"); u != img.end() && u->is_string()) {
      const std::string uri = u->get<std::string>();
      if (!isDataUri(uri)) {
        ctx.images[i].name = uri;
        registerUri(ctx, imageLabel(img, i), at("images", i) + ".uri", uri, false, 0);
      }
    }
  }
  if (const auto tex = doc.find("textures"); tex != doc.end() && tex->is_array())
    for (const json& t : *tex)
      if (const auto s = t.is_object() ? t.find("source") : t.end(); t.is_object() && s != t.end() && s->is_number_integer())
        if (s->get<long long>() >= 0 && std::size_t(s->get<long long>()) < count) ctx.imageUsed[std::size_t(s->get<long long>())] = true;
}

// --- tinygltf callbacks ---------------------------------------------------------------------

bool fileExists(const std::string&, void*) { return true; }  // so that a missing file reaches readFile
std::string expandPath(const std::string& p, void*) { return p; }  // no shell-style expansion of file names
bool writeFile(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// Opens only what registerUri let through, inside the asset's folder (openInside), regular files
// only, a buffer's first byteLength bytes (a longer file is padding).
bool readFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  Context& ctx = *static_cast<Context*>(user);
  auto failed = [&](const std::string& message) {
    if (ctx.error.empty()) ctx.error = message;
    if (err) *err = "refused";
    return false;
  };
  const auto found = ctx.files.find(path);
  if (found == ctx.files.end())  // a data: URI tinygltf does not decode itself
    return failed(ctx.source + ": a buffer or image URI names '" + printable(path, 200) +
                  "', which brdfcl does not read; use a file in the asset's folder or a base64 data: URI");
  const External& e = found->second;
  brdfcl::detail::OpenRules rules;
  rules.allowOutside = ctx.options.allowOutsideUris;
  if (e.buffer) rules.atLeast = rules.readAtMost = e.length;
  else rules.sizeAtMost = kMaxImageFileBytes;
  std::string data;
  using Outcome = brdfcl::detail::Opened::Outcome;
  const brdfcl::detail::Opened r = brdfcl::detail::readInside(ctx.baseDir, e.name, rules, data);
  const std::string where = e.label + ": ";
  switch (r.outcome) {
    case Outcome::Ok:
      out->assign(data.begin(), data.end());
      return true;
    case Outcome::Outside:
      return failed(refusal(ctx, e, outsideRefusal()));
    case Outcome::Link:
      return failed(refusal(ctx, e, "is or passes through a symbolic link, which brdfcl does not follow from an "
                                    "asset's folder; copy the file in, or pass " + flagName("--allow-outside-uris")));
    case Outcome::NotRegular:
      return failed(refusal(ctx, e, "is not a regular file (a directory, FIFO or device); name a file"));
    case Outcome::TooSmall:
      return failed(ctx.source + ": " + where + quoted(e.uri) + " has " + std::to_string(r.size) +
                    " bytes, but byteLength says " + std::to_string(e.length) + "; re-export the file");
    case Outcome::TooLarge:
      return failed(refusal(ctx, e, "has " + std::to_string(r.size) + " bytes, more than the " +
                                        std::to_string(kMaxImageFileBytes) +
                                        " brdfcl reads for an image; save it smaller"));
    case Outcome::Unreadable:
      break;
  }
  return failed(ctx.source + ": " + where + "cannot read " + quoted(e.uri) + ": " + std::strerror(r.error));
}

bool decodeImage(tinygltf::Image*, const int index, std::string*, std::string*, int, int, const unsigned char* bytes,
                 int size, void* user) {
  Context& ctx = *static_cast<Context*>(user);
  if (index < 0 || std::size_t(index) >= ctx.images.size() || !ctx.imageUsed[std::size_t(index)]) return true;
  Image& img = ctx.images[std::size_t(index)];
  std::string reason;
  if (size <= 0 || !detail::decodeImage(bytes, std::size_t(size), ctx.options.maxImagePixels, img, reason)) {
    const std::string label = at("images", std::size_t(index)) +
                              (img.name.rfind("images[", 0) == 0 ? "" : " ('" + printable(img.name, 120) + "')");
    if (ctx.error.empty() && reason.rfind("declares ", 0) == 0)
      ctx.error = ctx.source + ": " + label + " " + reason;
    else if (ctx.error.empty())
      ctx.error = ctx.source + ": " + label + ": cannot decode the image (" +
                  printable(reason.empty() ? "no data" : reason, 120) + "); save it as PNG or JPEG";
    return false;
  }
  return true;
}

// tinygltf's error text, several lines sometimes, as one line.
std::string oneLine(const std::string& text) {
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '.')) line.pop_back();
    if (!line.empty()) out += (out.empty() ? "" : "; ") + line;
    start = end + 1;
  }
  return printable(out.empty() ? "unknown error" : out, 300);
}

}  // namespace

namespace detail {
// Implemented in scene_walk.cpp: the node walk and primitive assembly.
void buildScene(const tinygltf::Model& model, const Document& doc, const LoadOptions& options, Asset& asset);
}  // namespace detail

Asset loadFromMemory(const std::string& bytes, const std::string& name, const std::string& baseDir,
                     const LoadOptions& options) {
  Context ctx;
  ctx.source = printable(name, 300);
  ctx.baseDir = baseDir;
  ctx.options = options;
  if (bytes.size() > 0xFFFFFFF0u) throw Error(ctx.source + ": the file is larger than 4 GiB; brdfcl reads glTF files up to 4 GiB");
  const bool glb = bytes.size() >= 4 && le32(bytes, 0) == kGlbMagic;
  std::size_t binSize = 0;
  const json doc = parseJson(glb ? brdfcl::detail::glbJsonChunk(bytes, ctx.source, binSize) : bytes, ctx.source);
  Asset asset;
  asset.path = name;
  const detail::Document document(doc, ctx.source);
  document.checkExtensions(asset.warnings);  // before tinygltf meets images it cannot decode (KTX2)
  const std::vector<bool> fallbacks = detail::meshoptFallbacks(doc, ctx.source);
  checkBuffers(doc, ctx, glb, binSize, fallbacks);
  registerImages(doc, ctx);
  // tinygltf needs bytes for every buffer and a bufferView for every indices accessor: fallback
  // buffers get a byte and Draco primitives lose "indices", in a rewritten document.
  std::string rewritten;
  const bool hasFallbacks = std::find(fallbacks.begin(), fallbacks.end(), true) != fallbacks.end();
  const bool hasDraco = detail::hasDracoPrimitives(doc);
  if (hasFallbacks) detail::checkFallbackUse(doc, fallbacks, ctx.source);
  if (hasFallbacks || hasDraco) {
    json forTinygltf = hasFallbacks ? detail::withoutFallbackBuffers(doc, fallbacks) : doc;
    if (hasDraco) detail::withoutDracoIndices(forTinygltf);
    const std::string text = forTinygltf.dump();
    rewritten = glb ? withJsonChunk(bytes, text) : text;
  }
  const std::string& input = rewritten.empty() ? bytes : rewritten;
  if (input.size() > 0xFFFFFFF0u) throw Error(ctx.source + ": the file is larger than 4 GiB; brdfcl reads glTF files up to 4 GiB");

  tinygltf::TinyGLTF reader;
  reader.SetImageLoader(&decodeImage, &ctx);
  reader.SetFsCallbacks(tinygltf::FsCallbacks{&fileExists, &expandPath, &readFile, &writeFile, &ctx});
  tinygltf::Model model;
  std::string err, warn;
  const auto* data = reinterpret_cast<const unsigned char*>(input.data());
  const bool ok = glb ? reader.LoadBinaryFromMemory(&model, &err, &warn, data, unsigned(input.size()), baseDir)
                      : reader.LoadASCIIFromString(&model, &err, &warn, input.data(), unsigned(input.size()), baseDir);
  if (!ctx.error.empty()) throw Error(ctx.error);
  if (!ok) throw Error(ctx.source + ": " + oneLine(err) + "; the file is not valid glTF 2.0: re-export it");
  detail::decodeMeshopt(doc, model, fallbacks, ctx.source, options);
  detail::decodeDraco(doc, model, ctx.source, options);  // after meshopt: its view may be one of those

  asset.samplers = document.samplers();
  asset.images = std::move(ctx.images);
  asset.textures = document.textures(asset.images.size(), asset.samplers.size());
  asset.materials = document.materials(asset.textures.size(), asset.warnings, options.strict);
  asset.variants = document.variants();
  detail::buildScene(model, document, options, asset);
  return asset;
}

Asset load(const std::string& path, const LoadOptions& options) {
  const brdfcl::detail::ReadingInput reading(printable(path, 300));
  std::string bytes;
  brdfcl::detail::readInputFile(path, printable(path, 300), "", bytes, brdfcl::detail::maxInputFileBytes(path));
  const std::size_t slash = path.find_last_of('/');
  const std::string base = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const bool glbName = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  if (glbName && (bytes.size() < 4 || le32(bytes, 0) != kGlbMagic))
    throw Error(printable(path, 300) + ": not a GLB file (no glTF magic number); a .glb must start with 'glTF'");
  return loadFromMemory(bytes, path, base, options);
}

}  // namespace brdfcl::gltf
