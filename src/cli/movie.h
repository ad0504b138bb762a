// Encoding a directory of step PNGs into a short movie with ffmpeg, when it is installed.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

namespace tspcli {

/// Frames per second of the demo movie.
inline constexpr int kMovieFps = 8;

/// The first executable named `name` on $PATH, if any.
std::optional<std::filesystem::path> find_on_path(const std::string& name);

/// Encodes frames_dir/step_%04d.png (numbered from first_step) into out (.mp4: H.264 or
/// ffmpeg's default MP4 codec; .gif: a GIF) through an ffmpeg subprocess writing a temporary
/// name beside out, renamed when it succeeded. Returns false (out untouched) when there is no
/// ffmpeg on $PATH. Throws tsp::IoError when ffmpeg fails.
bool encode_movie(const std::filesystem::path& frames_dir, int first_step,
                  const std::filesystem::path& out);

}  // namespace tspcli
