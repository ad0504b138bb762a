// Recording the player's view to a movie in real time: each shown frame is written as many times
// as the movie's frame rate needs to keep the wall-clock time, and stopping pads the last frame up
// to the moment of the stop, so a movie lasts as long as the recording did. Window-free (library
// tspscript), so the timing rule is tested without a display.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "jobs/movie.h"
#include "tsp/report/image.h"

namespace tspplayer {

/// Frames a real-time movie at fps should hold at now_s when it started at start_s: one for
/// the start, then one every 1/fps s (at least 1; times before the start count as the start).
/// Never throws.
std::int64_t frames_due(double start_s, double now_s, int fps);

/// One recording. Use from one thread.
class Recorder {
 public:
  /// Starts ffmpeg writing path from width × height frames at fps; start_s is the clock reading
  /// of the first frame. Throws like tspgl::MovieWriter (bad name or size, no ffmpeg).
  Recorder(const std::filesystem::path& path, int width, int height, int fps, double start_s);
  /// Appends the frame shown at now_s as often as the wall clock asks (none when the movie is
  /// ahead; at most kMaxRepeatSeconds of copies after a stall). Throws tsp::UsageError when
  /// the frame's size differs, tsp::IoError when ffmpeg failed.
  void frame(const tsp::Image& image, double now_s);
  /// Holds the last frame written (a shown frame not fit for the movie) up to now_s: the
  /// movie keeps the wall-clock time; nothing before the first frame. Throws like frame().
  void hold(double now_s);
  /// Movie frames written from the frame shown (frame()), and movie frames repeating an earlier
  /// one because the frame shown was not fit for the movie (hold()).
  std::int64_t frames_shown() const { return shown_; }
  /// See frames_shown().
  std::int64_t frames_held() const { return held_; }
  /// Pads the last frame up to now_s and ends the movie (waits for ffmpeg); returns the line
  /// that says what was written. Throws tsp::IoError when ffmpeg failed (no file is left).
  std::string finish(double now_s);
  /// Seconds of movie written so far.
  double seconds() const { return double(movie_.frames()) / fps_; }
  /// The movie's path.
  const std::filesystem::path& path() const { return movie_.path(); }

  /// Longest stretch one frame is repeated for (a stalled window does not write minutes).
  static constexpr double kMaxRepeatSeconds = 10;

 private:
  tspgl::MovieWriter movie_;
  int fps_;
  double start_s_;
  std::optional<tsp::Image> last_;
  std::int64_t shown_ = 0, held_ = 0;
  // Appends image until the movie holds `total` frames (at most kMaxRepeatSeconds of copies).
  void pad_to(const tsp::Image& image, std::int64_t total);
};

}  // namespace tspplayer
