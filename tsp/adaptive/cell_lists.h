// tsp/adaptive: Leven's adaptive voxel octree (paper 000 §4.2, issue 31): a mesh series built
// top-down into a .tsp whose octree stops where the mesh's cells are no smaller than a node's
// voxels or its field is homogeneous; may include core/, source/, voxelize/, tree/, store/,
// build/. This file: the octree nodes' cell lists, kept on disk so memory stays bounded.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tsp {

/// Numbered lists of T in an anonymous file (created and unlinked at once: nothing is left
/// behind); only their offsets and lengths stay in memory. Used for the octree nodes' cell lists
/// and the per-step cell summaries.
template <class T>
class DiskLists {
 public:
  /// `keys` empty lists in a file in dir; what names them in messages. Throws IoError when dir
  /// is not writable.
  DiskLists(const std::string& dir, std::int64_t keys, const std::string& what);
  ~DiskLists();
  DiskLists(const DiskLists&) = delete;
  DiskLists& operator=(const DiskLists&) = delete;
  /// Stores list `key` (appended to the file; a later put of the same key replaces it, the old
  /// bytes stay). Not thread-safe with put(). Throws IoError (disk full).
  void put(std::int64_t key, std::span<const T> items);
  /// List `key`, empty when none was stored; thread-safe with get(). Throws IoError.
  std::vector<T> get(std::int64_t key) const;
  /// Length of list `key` (0 when none was stored). Never throws.
  std::int64_t count(std::int64_t key) const { return count_[std::size_t(key)]; }
  /// Bytes written to the file. Never throws.
  std::int64_t bytes() const { return end_; }

 private:
  int fd_ = -1;
  std::string dir_, what_;
  std::vector<std::int64_t> offset_, count_;  // per key, in bytes and items
  std::int64_t end_ = 0;
};

/// Cell indices per (octree node, list step).
using CellLists = DiskLists<std::int64_t>;

}  // namespace tsp
