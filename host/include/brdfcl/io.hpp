// Readers and writers for the user's files: glTF material JSON, sample CSV/NPY, result CSV/NPY.
// Every reader throws brdfcl::Error with one line naming the file and the line, row or key.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "brdfcl/material.hpp"

namespace brdfcl {

// Materials of a glTF 2.0 document (.gltf JSON, or a .glb, whose JSON chunk is read after its
// header is checked), or of any JSON object with a top-level "materials" array.
// KHR_materials_sheen is the draft when it has intensityFactor, colorFactor or
// colorIntensityTexture, the ratified extension otherwise; mixing the two key families is an
// error. Values are checked against the glTF schema ranges; errors name the file and the JSON
// path ("m.json: materials[2].pbrMetallicRoughness.roughnessFactor: ..."). Texture references
// are ignored with one warning per material, passed to `warn` (if set).
// A typo must not silently leave a factor at its default, so these get one warning each, with
// the JSON path and "did you mean <key>?" when a known key is near: unknown keys of a material,
// of pbrMetallicRoughness, of KHR_materials_{sheen,clearcoat,anisotropy} and of their
// textureInfo objects; unknown KHR_/EXT_ extension names; and the ratified KHR_materials_*
// extensions f leaves out (ior, specular, transmission, ...), each naming what is ignored
// ("m.json: materials[0].extensions.KHR_materials_ior: ignored: ..."). "extras", vendor
// extensions and real non-material extensions (KHR_texture_transform) are silent.
struct MaterialReadOptions {
  std::function<void(const std::string&)> warn;  // receives each warning line; may be empty
  bool strict = false;  // the first of those typo warnings is thrown as the Error instead (texture notes stay warnings)
};
std::vector<MaterialParams> readMaterials(const std::string& path, const MaterialReadOptions& options);
std::vector<MaterialParams> parseMaterials(const std::string& jsonText, const std::string& sourceName,
                                           const MaterialReadOptions& options);
// The same, not strict.
std::vector<MaterialParams> readMaterials(const std::string& path,
                                          const std::function<void(const std::string&)>& warn = {});
std::vector<MaterialParams> parseMaterials(const std::string& jsonText, const std::string& sourceName,
                                           const std::function<void(const std::string&)>& warn = {});

// Memory for a chunk of rows that is filled before it is read: elements are left uninitialized
// (a 28 MB chunk zero-filled and then overwritten by a read cost a pass over it and a fault per
// page), and blocks of 2 MiB or more are mapped 2 MiB-aligned and offered to transparent huge
// pages, so that a first touch faults a few large pages rather than thousands of small ones.
namespace detail {
void* allocateChunk(std::size_t bytes);
void freeChunk(void* p, std::size_t bytes) noexcept;
}  // namespace detail
template <typename T>
struct ChunkAllocator {
  using value_type = T;
  ChunkAllocator() = default;
  template <typename U>
  ChunkAllocator(const ChunkAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(detail::allocateChunk(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { detail::freeChunk(p, n * sizeof(T)); }
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;  // default-initialized: indeterminate until written
  }
  template <typename U, typename... A>
  void construct(U* p, A&&... a) {
    ::new (static_cast<void*>(p)) U(std::forward<A>(a)...);
  }
  template <typename U>
  bool operator==(const ChunkAllocator<U>&) const noexcept { return true; }
  template <typename U>
  bool operator!=(const ChunkAllocator<U>&) const noexcept { return false; }
};
template <typename T>
using ChunkVector = std::vector<T, ChunkAllocator<T>>;

// Samples in the shading frame N = +Z, T = +X, B = +Y. L points to the light, V to the viewer.
struct Samples {
  std::vector<std::uint32_t> material;  // empty when the file has no material column (grid mode)
  std::vector<float> L;                 // 3 per sample, normalized by the reader
  std::vector<float> V;                 // 3 per sample, normalized by the reader
  std::size_t size() const { return L.size() / 3; }
};

// How every reader of directions normalizes one (the samples files, evaluateArrays): each
// component rounded to float, then x / sqrt((x*x + y*y) + z*z) with every operation in float
// (within 3 ulp of the exact unit vector); a vector whose squared length would leave float's
// range is first scaled by a power of two in double (exact), so every finite non-zero vector
// normalizes. Returns false (leaving dst alone) for zero length. The inputs must be finite.
// io/directions.hpp has the vectorized form, which gives the same bits.
bool normalizeDirection(const double* d, float* dst);

// CSV whose header names the columns material,Lx,Ly,Lz,Vx,Vy,Vz in any order (material may be
// absent when materialColumnOptional), or .npy float32/float64 of shape (N,7) or (N,6) in that
// column order, chosen by the extension (.npy, any case). Path "-" is stdin ("<stdin>" in
// messages), NPY when it starts with NPY's magic and CSV otherwise. The header's column order
// becomes one permutation for the whole file; a missing, unknown (with "did you mean") or
// repeated column is an error naming it ("s.csv: header: missing column Vz"), and a missing
// material column without materialColumnOptional suggests --grid. Rejects short or non-numeric
// rows, NaN/Inf, zero-length directions, non-integer material indices and, when
// materialCount != 0, indices >= it. Errors say "s.csv:17: ..." (1-based file lines, the
// header is line 1) or "s.npy: row 12: ..." (0-based rows, as numpy indexes them). Large files
// are parsed on several threads.
Samples readSamples(const std::string& path, std::size_t materialCount, bool materialColumnOptional);

// The same files read a chunk at a time, so a file of any size takes bounded memory: the chunk's
// rows plus one read buffer. Checks, normalization and messages (line and row numbers included)
// are exactly readSamples's, which is this stream read in one chunk. The header is read and
// checked by the constructor. Regular files (stdin redirected from one included) are read with
// pread and never mapped, so the page cache is not charged to the process; pipes are read whole
// first (NPY needs to seek, and --grid re-reads).
// Not thread-safe: one thread reads a stream (it parses each chunk on several threads itself).
class SampleStream {
 public:
  SampleStream(const std::string& path, std::size_t materialCount, bool materialColumnOptional);
  ~SampleStream();
  SampleStream(const SampleStream&) = delete;
  SampleStream& operator=(const SampleStream&) = delete;

  bool hasMaterialColumn() const;
  // Replaces `out` with the next 1..maxRows rows (fewer only at the end of a CSV chunk of
  // blank lines or of the file); false, with `out` empty, once the file is exhausted. Throws the
  // reader's Error for the first bad row, and "no samples" if the file holds none at all.
  bool next(std::size_t maxRows, Samples& out);
  // Starts again from the first row (the grid re-reads directions once per material).
  void rewind();

  // The rows as the file holds them, for the device to check and normalize where they lie
  // (Evaluator::evaluateTableRows): served for float32 C-order NPY files of 7 columns read
  // against a material count; hasRawRows() says whether. nextRows replaces `out` with the next
  // 1..maxRows rows, unchecked, and returns false once the file is exhausted; throwRowError
  // throws what next() would have thrown for row i of `rows` (e.g. "s.npy: row 12: field 'Lx'
  // is not finite: nan"). next() and nextRows share one position.
  struct RawRows {
    ChunkVector<float> data;  // count rows of 7 floats: material, Lx Ly Lz Vx Vy Vz
    std::size_t count = 0, firstRow = 0;
  };
  bool hasRawRows() const;
  bool nextRows(std::size_t maxRows, RawRows& out);
  // Starts reading the next maxRows raw rows on a thread of its own (where hasRawRows(); else it
  // does nothing), so that the read overlaps what the caller does next, such as opening the
  // device. The next nextRows(maxRows) returns them, or throws the read's error; any other call
  // first waits for the read and drops it.
  void readAhead(std::size_t maxRows);
  [[noreturn]] void throwRowError(const RawRows& rows, std::size_t i) const;

  // The file's rows without parsing them: NPY's N; for a CSV, the lines after the header up to
  // the last one that is not blank (one pass over the file, a block at a time).
  std::size_t countRows();
  // Narrows the stream to rows [first, first + count) of countRows()'s (count >= 1), so that
  // ranks of an mpirun job read disjoint parts of one file: next() returns only those, rewind()
  // goes back to `first`, and messages keep the whole file's line and row numbers. A blank CSV
  // line in the range is the error it is in the whole file.
  void selectRows(std::size_t first, std::size_t count);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Outputs. Every writer of brdfcl (results, PNG/EXR images, G-buffers, LUTs, the demo .glb)
// writes through the same layer, whose rules are:
//  - "-" is stdout. Formats that need to seek (OpenEXR, NPY) are spooled to a temporary file
//    in the system temp directory first, then copied.
//  - An existing symlink is followed (chains and relative targets included) and the target is
//    written; the link stays a link. /dev/stdout and other /proc links are written in place.
//  - A FIFO, character device or other non-regular file is written in place, without temporary.
//  - A regular file (or a new one) is written to a temporary beside it
//    (".brdfcl.tmp.<host>.<pid namespace>.<pid>.<random>") that is renamed into place on success
//    and removed on failure: no half-written outputs. A replaced file's permission bits and owner
//    (where the process may set it) carry over to the new one; a new file gets 0666 less the
//    umask, as open() gives. Temporaries are removed on SIGINT/SIGTERM/SIGHUP/SIGPIPE
//    (installSignalCleanup, cleanup.hpp), and those of dead processes of this host, an hour old,
//    by the next write to their directory.
//  - A directory is refused: "cannot write 'out': it is a directory; name a file inside it".
// A missing or unwritable directory fails before any data is written:
// "cannot write 'out/x.csv': No such file or directory".

// Writes N rows of r,g,b: CSV with header and 9 significant digits (%.9g), or float32 .npy
// (N,3) v1.0, chosen by the extension (any case); "-", and a FIFO or device whose name has no
// extension (/dev/stdout), get CSV. Any other extension is refused before anything is written:
// "cannot write 'o.exr': unknown extension; use .csv or .npy (- writes CSV to stdout)".
// rgb.size() must be a multiple of 3 (std::invalid_argument otherwise: a caller bug).
void writeResults(const std::string& path, const std::vector<float>& rgb);

// writeResults a chunk at a time: rows go to the output as they come (a file's temporary, or
// straight to stdout or a FIFO for CSV), and commit() completes it (for .npy after writing the
// final row count into the header, whose length is fixed at 128 bytes). Destroyed without
// commit(), e.g. by an exception, it removes the temporary: no half-written file. The bytes
// equal writeResults's of all rows. The constructor throws the path and extension errors.
class ResultWriter {
 public:
  explicit ResultWriter(const std::string& path);
  // The rows alone, without the CSV header line or the NPY header, in `format` (".csv" or
  // ".npy") whatever `path` is called: an mpirun rank's part of the one output file.
  ResultWriter(const std::string& path, const std::string& format, bool header);
  ~ResultWriter();
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;

  void append(const float* rgb, std::size_t rows);  // 3 floats a row
  // append() from memory the writer may also use as scratch: it may overwrite the
  // kInPlaceHeadroom bytes before rgb (and rgb's rows). An NPY file written with O_DIRECT then
  // goes to the disk from rgb itself, without a copy, when rgb's address and its offset in the
  // file are congruent modulo kInPlaceHeadroom; otherwise this is append(). appendOffset() is
  // the file offset the next append starts at (header included), for placing rgb.
  static constexpr std::size_t kInPlaceHeadroom = 4096;
  void appendInPlace(float* rgb, std::size_t rows);
  std::size_t appendOffset() const;
  std::size_t rows() const;
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Runs `write` on a path it must fill (an empty file, already created) and puts the result at
// `path` by the rules above: for a regular file `write` gets the temporary beside it, renamed
// into place on success; for "-" or a stream it gets a spool that is then copied there. On any
// exception the temporary is removed and the exception propagates.
void writeAtomically(const std::string& path, const std::function<void(const std::string& tmpPath)>& write);

// `size` bytes to `path` by the same rules, streamed directly to "-" and FIFOs.
void writeOutput(const std::string& path, const void* data, std::size_t size);

// Checks, before any work starts, that `path` can be written as the output named by `option`
// (e.g. "--png") by the rules above: "-" is accepted, symlinks are followed, FIFOs and devices
// are accepted if writable, a directory is refused, a file's directory must exist and be
// writable. Throws the Error the write would throw later, in the option's words:
// "--png '/nonexistent/o.png': cannot write: No such file or directory",
// "--out 'out': cannot write: it is a directory; name a file inside it".
void checkOutputPath(const std::string& option, const std::string& path);

// checkOutputPath plus an extension rule for the commands whose writer does not check one itself
// (PNG, EXR): the extension must be one of `extensions` (lower case with the dot, compared in
// any case); "-" and an extensionless FIFO or device are accepted. For --out img.jpg:
// "--out 'img.jpg': cannot write: unknown extension; use .png or -".
void checkOutputPath(const std::string& option, const std::string& path, const std::vector<std::string>& extensions);

// checkOutputPath plus the results writers' extension rule (.csv, .npy, "-"):
// "--out 'o.exr': cannot write: unknown extension; use .csv or .npy (- writes CSV to stdout)".
void checkResultsPath(const std::string& option, const std::string& path);

// A file a command line names: the option ("--out", or "A" for an operand), its path, and
// whether the command writes it.
struct FileArgument {
  std::string option, path;
  bool output = false;
};

// Refuses, before any work, an output that is the same file as an input or as another output,
// which the run would destroy or overwrite with half of itself. Existing files are the same when
// device and inode agree (after symlinks: a link or a hard link to an input is that input); an
// output that does not exist yet is compared by where it would be written (the end of its links,
// in the real path of its directory). Empty paths, "-", and FIFOs and devices (/dev/null twice)
// are not compared. Throws Error naming both options:
// "--out 's.csv' is the same file as --samples 's.csv'; write the output elsewhere",
// "--gbuffer 'g.exr' is the same file as --out 'g.exr'; give each output its own file".
void checkDistinctFiles(const std::vector<FileArgument>& files);

}  // namespace brdfcl
