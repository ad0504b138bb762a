#include "cli/movie.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/core/temp_output.h"

extern char** environ;

namespace tspcli {

namespace fs = std::filesystem;

std::optional<fs::path> find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::string dirs = path;
  std::size_t p = 0;
  while (p <= dirs.size()) {
    std::size_t c = dirs.find(':', p);
    if (c == std::string::npos) c = dirs.size();
    const fs::path candidate = fs::path(c > p ? dirs.substr(p, c - p) : ".") / name;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0)
      return candidate;
    p = c + 1;
  }
  return std::nullopt;
}

bool encode_movie(const std::vector<fs::path>& frames, const fs::path& out, int fps) {
  const auto ffmpeg = find_on_path("ffmpeg");
  if (!ffmpeg) return false;
  if (frames.empty()) throw tsp::IoError(out.string() + ": no frames to encode");
  const bool gif = out.extension() == ".gif";
  tsp::TempOutput tmp(out.string());
  // The frames under consecutive names (strided steps, any file names): symbolic links in a
  // private folder beside the movie, removed however this ends.
  std::string pattern = (fs::path(tmp.dir()) / ".frames.XXXXXX").string();
  if (!mkdtemp(pattern.data()))
    throw tsp::IoError(out.string() + ": cannot make a temporary folder for the frames");
  const fs::path links = pattern;
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{links};
  for (std::size_t i = 0; i < frames.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05zu.png", i);
    std::error_code ec;
    fs::create_symlink(fs::absolute(frames[i]), links / name, ec);
    if (ec) throw tsp::IoError(out.string() + ": cannot link frame " + frames[i].string());
  }
  // Even sizes: H.264 in yuv420p needs them; the temp name has no usable extension, hence -f.
  std::vector<std::string> args = {ffmpeg->string(), "-nostdin", "-loglevel", "error", "-y",
                                   "-framerate", std::to_string(fps), "-start_number", "0", "-i",
                                   (links / "frame_%05d.png").string()};
  if (gif) {
    args.insert(args.end(), {"-f", "gif"});
  } else {
    args.insert(args.end(), {"-vf", "scale=trunc(iw/2)*2:trunc(ih/2)*2", "-pix_fmt", "yuv420p",
                             "-movflags", "+faststart", "-f", "mp4"});
  }
  args.push_back(tmp.tmp());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0)
    throw tsp::IoError(ffmpeg->string() + ": cannot start the movie encoder");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw tsp::IoError(ffmpeg->string() + ": lost the movie encoder");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw tsp::IoError(out.string() + ": ffmpeg failed to encode " +
                       std::to_string(frames.size()) + " frames from " +
                       frames.front().parent_path().string() + " (exit status " +
                       std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  tmp.commit();
  return true;
}

}  // namespace tspcli
