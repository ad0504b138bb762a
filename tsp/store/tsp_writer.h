// Writes a .tsp file (layout: docs/formats.md). Used by the builder; the caller writes to a
// temporary name and renames it when finish() returned.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tsp/store/tsp_file.h"
#include "tsp/tree/tsp_tree.h"

namespace tsp {

/// How several processes write one .tsp file together with parallel HDF5; implemented where
/// MPI is (src/mpi), so this library needs none. Each method is called on every process at the
/// same point.
class CollectiveIo {
 public:
  virtual ~CollectiveIo() = default;
  /// Makes the file-access property list fapl open the file on every process (MPI-IO).
  /// Throws Error.
  virtual void set_file_access(std::int64_t fapl) = 0;
  /// Makes the transfer property list dxpl write collectively. Throws Error.
  virtual void set_collective_transfer(std::int64_t dxpl) = 0;
  /// Waits until every process is here (collective). Throws Error.
  virtual void barrier() = 0;
};

/// An open .tsp file being written. Every method holds hdf5_mutex() while it calls HDF5, so
/// bricks may be written from several threads.
class TspWriter {
 public:
  /// Creates (truncates) path with room for the bricks of tree's shape (field_index 0: the
  /// file's first field, at its root), or reopens the file the first field was written to and
  /// adds field field_index ≥ 1 in its group fields/K. deflate 1–9 compresses every brick
  /// chunk (byte shuffle, then deflate at that level; 0: stored as is). Throws IoError.
  /// With io, every process of io opens the file together (collectively; field_index ≥ 1:
  /// after a barrier), every brick write is collective (each process calls write_brick_series or
  /// write_no_brick the same number of times) and end_collective() must run before finish().
  TspWriter(const std::string& path, const TspTree& tree, int field_index = 0, int deflate = 0,
            CollectiveIo* io = nullptr);
  ~TspWriter();
  TspWriter(const TspWriter&) = delete;
  TspWriter& operator=(const TspWriter&) = delete;
  /// Writes brick b at every step: codes is [T][Bz][By][Bx] (stored_brick_shape, padded).
  /// Throws IoError.
  void write_brick_series(int brick, std::span<const std::uint16_t> codes);
  /// Writes brick b's stencil at every step (trees with a stencil only), laid out like codes.
  /// Throws IoError.
  void write_inside_series(int brick, std::span<const std::uint8_t> inside);
  /// With io: this process's part of a collective brick write when it has no brick to write
  /// (and of the stencil's, with one). Throws IoError.
  void write_no_brick();
  /// With io: closes the file on every process (collective); with finisher, reopens it on this
  /// process alone for finish(). Throws IoError.
  void end_collective(bool finisher);
  /// Writes the tree (shape and statistics), the ranges and the metadata, then closes the file.
  /// Throws IoError.
  void finish(const TspTree& tree, const TspMetadata& metadata);
  /// After every field is finished: lists their names, in order, in the root attribute `fields`
  /// (files with several fields). Throws IoError.
  static void write_field_list(const std::string& path, const std::vector<std::string>& names);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tsp
