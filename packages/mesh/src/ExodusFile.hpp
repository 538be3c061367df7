#pragma once
// Internal to mesh/: what the Exodus reader and writer share: the file handle that closes on
// every path out, name arrays for the C API, and the checks that turn its statuses and a
// corrupt file's counts into input errors naming the file.
#include <exodusII.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/Mesh.hpp"

namespace tribos::mesh::exodus {

/// One Exodus element block: elements of one type (Exodus has one topology per block) and of
/// one body. A body of several element types is written as one block per type, each under
/// the body's name; the reader joins consecutive blocks of one name back into one body.
struct BlockPart {
  int id;
  int body;  ///< index into Mesh::blocks
  ElementType type;
  LO first, count;
};

/// The parts of every body: its runs of elements of one type. The first part of a body
/// keeps the body's id; further parts take ids above every body's.
inline std::vector<BlockPart> blockParts(const Mesh& mesh) {
  int nextId = 0;
  for (const auto& b : mesh.blocks) nextId = std::max(nextId, b.id + 1);
  std::vector<BlockPart> parts;
  for (int b = 0; b < mesh.numBlocks(); ++b) {
    const ElementBlock& block = mesh.blocks[b];
    if (block.count == 0) parts.push_back({block.id, b, ElementType::Tet4, block.first, 0});  // the reader refuses it
    for (LO e = block.first; e < block.first + block.count; ++e) {
      if (e > block.first && mesh.elementType(e) == mesh.elementType(e - 1)) {
        parts.back().count++;
        continue;
      }
      parts.push_back({e == block.first ? block.id : nextId++, b, mesh.elementType(e), e, 1});
    }
  }
  return parts;
}

/// Names of at least this length survive a round trip; the library's default (32) would cut
/// descriptive set names such as "contact_upper_brick_bottom_face".
constexpr int kNameLength = 64;
/// netCDF stores names in a dimension of NC_MAX_NAME (256) characters including the NUL.
constexpr int kMaxNameLength = 255;

/// Closes the file on every path out of a reader/writer. The writer closes explicitly via
/// close() so that a failed final flush is reported instead of lost in a destructor.
class ExodusFile {
 public:
  explicit ExodusFile(int id) : id_(id) {}
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;
  ~ExodusFile() {
    if (id_ >= 0) ex_close(id_);
  }
  int id() const { return id_; }
  int close() {
    const int status = ex_close(id_);
    id_ = -1;
    return status;
  }

 private:
  int id_;
};

/// Owns a char*[] for the name APIs (which take non-const char**), each entry `length` + 1
/// characters, zero-filled so unset names read back as empty strings.
class NameArray {
 public:
  NameArray(size_t count, int length)
      : storage_(count, std::string(static_cast<size_t>(length) + 1, '\0')), pointers_(count), length_(length) {
    for (size_t i = 0; i < count; ++i) pointers_[i] = storage_[i].data();
  }
  NameArray(const std::vector<std::string>& names, int length) : NameArray(names.size(), length) {
    for (size_t i = 0; i < names.size(); ++i)
      names[i].copy(pointers_[i], std::min<size_t>(names[i].size(), static_cast<size_t>(length_)));
  }
  char** data() { return pointers_.data(); }
  std::string operator[](size_t i) const { return std::string(pointers_[i]); }

 private:
  std::vector<std::string> storage_;
  std::vector<char*> pointers_;
  int length_;
};

/// Counts from the file size allocations: each is checked first against what the rest of
/// the file allows, so that a corrupt header is an input error and not std::bad_alloc.
/// Blocks, sets, variables, steps and info lines beyond this many are not a mesh Tribos reads.
constexpr int64_t kMaxEntities = 1'000'000;
/// A node set may list a node once per face corner it belongs to (other writers do).
constexpr int64_t kMaxNodeRepeats = 64;

inline void requireCount(int64_t count, int64_t limit, const std::string& path, const std::string& what,
                  const std::string& limitText) {
  if (count < 0 || count > limit)
    throw core::InputError(path + ": the file claims " + std::to_string(count) + " " + what + ", outside 0.." +
                           std::to_string(limit) + " (" + limitText + "): a corrupt file?");
}

inline void check(int status, const std::string& path, const std::string& what) {
  if (status < 0) throw core::InputError(path + ": Exodus error while " + what + " (status " + std::to_string(status) + ")");
}

}  // namespace tribos::mesh::exodus
