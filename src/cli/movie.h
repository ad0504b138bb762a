// Encoding a directory of step PNGs into a short movie with ffmpeg, when it is installed.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tspcli {

/// Frames per second of the demo movie.
inline constexpr int kMovieFps = 8;

/// The first executable named `name` on $PATH, if any.
std::optional<std::filesystem::path> find_on_path(const std::string& name);

/// Encodes the PNG frames, in order, into out (.mp4: H.264 or ffmpeg's default MP4 codec; .gif:
/// a GIF) at fps frames a second through an ffmpeg subprocess: the frames are linked as
/// frame_%05d.png into a temporary folder beside out, the movie written to a temporary name
/// renamed when it succeeded. Returns false (out untouched) when there is no ffmpeg on $PATH.
/// Throws tsp::IoError when ffmpeg fails or the folder cannot be made.
bool encode_movie(const std::vector<std::filesystem::path>& frames,
                  const std::filesystem::path& out, int fps = kMovieFps);

}  // namespace tspcli
