// Movies through an ffmpeg subprocess, when it is installed: a folder's step PNGs encoded at once
// (render --movie, the demo) or frames streamed as they are drawn (the player's record button).
// Both write under a temporary name renamed when ffmpeg succeeded, so no half-written movie
// remains.
#pragma once
#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tsp/report/image.h"

namespace tsp {
class TempOutput;
}

namespace tspgl {

/// Frames per second of the demo movie and of render --movie by default.
inline constexpr int kMovieFps = 8;

/// The first executable named `name` on $PATH, if any. Never throws.
std::optional<std::filesystem::path> find_on_path(const std::string& name);

/// Throws tsp::UsageError unless out ends in .mp4 or .gif (`what` names the option).
void check_movie_name(const std::filesystem::path& out, const std::string& what);

/// Encodes the PNG frames, in order, into out's temporary file (out.tmp(); `name` is the movie's
/// name, .mp4: H.264 or ffmpeg's default MP4 codec; .gif: a GIF) at fps frames a second through an
/// ffmpeg subprocess; the caller commits out. The frames are linked as frame_%05d.png into a
/// temporary folder beside out. ffmpeg failed when it exits non-zero, reports any error (it runs
/// at -loglevel error; disk full is one it reports yet exits 0 for) or writes nothing. Throws
/// tsp::IoError when there is no ffmpeg on $PATH, ffmpeg failed (its first error line quoted) or
/// the folder cannot be made, tsp::Interrupted when SIGINT/SIGTERM stopped it.
void encode_movie_into(const std::vector<std::filesystem::path>& frames, tsp::TempOutput& out,
                       const std::filesystem::path& name, int fps = kMovieFps);

/// encode_movie_into a TempOutput of out, committed when it succeeded. Returns false (out
/// untouched) when there is no ffmpeg on $PATH. Throws what encode_movie_into and
/// tsp::TempOutput throw.
bool encode_movie(const std::vector<std::filesystem::path>& frames,
                  const std::filesystem::path& out, int fps = kMovieFps);

/// A movie written frame by frame: ffmpeg reads raw RGBA frames of one size from a pipe. Use from
/// one thread; not copyable.
class MovieWriter {
 public:
  /// Starts ffmpeg writing out (.mp4 or .gif) from width × height frames at fps. Throws
  /// tsp::UsageError for a bad name or size, tsp::IoError when there is no ffmpeg on $PATH, the
  /// folder cannot take the output or ffmpeg cannot be started.
  MovieWriter(const std::filesystem::path& out, int width, int height, int fps);
  /// Without finish(): stops ffmpeg and removes its temporary output (out untouched).
  ~MovieWriter();
  MovieWriter(const MovieWriter&) = delete;
  MovieWriter& operator=(const MovieWriter&) = delete;

  /// Appends frame (the size given at construction) `repeat` times. Throws tsp::UsageError for
  /// another size, tsp::IoError when ffmpeg has stopped reading (it failed).
  void write(const tsp::Image& frame, int repeat = 1);
  /// Ends the movie: closes the pipe, waits for ffmpeg and renames the output into place.
  /// Throws tsp::IoError when ffmpeg failed as encode_movie_into says (nothing is left behind
  /// then), tsp::Interrupted after SIGINT/SIGTERM.
  void finish();
  /// Frames written so far.
  std::int64_t frames() const { return frames_; }
  /// The movie's path.
  const std::filesystem::path& path() const { return out_; }

 private:
  std::filesystem::path out_;
  int width_ = 0, height_ = 0;
  std::unique_ptr<tsp::TempOutput> tmp_;
  int pipe_ = -1;
  int errors_ = -1;  ///< ffmpeg's standard error (an anonymous memory file)
  pid_t pid_ = -1;
  std::int64_t frames_ = 0;
};

}  // namespace tspgl
