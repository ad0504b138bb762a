#include "player/open_job.h"

#include <cstdio>

#include "jobs/play_input.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"

namespace tspplayer {

OpenJob::OpenJob(std::string input, std::string field, std::string cache_dir,
                 bool allow_external)
    : input_(std::move(input)), field_(std::move(field)) {
  worker_.submit([this, cache_dir = std::move(cache_dir), allow_external](std::stop_token stop) {
    struct Done {  // marks the job ended however it ends
      std::atomic<bool>& done;
      ~Done() { done = true; }
    } mark{done_};
    tspgl::PlayBuildHooks hooks;
    hooks.say = [this](const std::string& line) {
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
      std::lock_guard lock(mu_);
      progress_.line = line;
    };
    hooks.build = [this, stop](tsp::VolumeSource& source, const std::string& out,
                               tsp::BuildOptions o) {
      o.progress = [this, stop](const std::string& phase, std::int64_t done, std::int64_t total) {
        if (stop.stop_requested()) throw tsp::Error("cancelled; no file written");
        std::lock_guard lock(mu_);
        progress_.phase = phase;
        progress_.done = done;
        progress_.total = total;
      };
      return tsp::build_tsp_file(source, out, o);
    };
    std::string out = tspgl::prepare_play_input(input_, field_, cache_dir, hooks, allow_external);
    std::lock_guard lock(mu_);
    result_ = std::move(out);
  });
}

OpenJob::~OpenJob() { worker_.request_stop(); }

OpenJob::Progress OpenJob::progress() const {
  std::lock_guard lock(mu_);
  return progress_;
}

std::string OpenJob::result() {
  worker_.wait();  // rethrows the build's exception
  std::lock_guard lock(mu_);
  return result_;
}

}  // namespace tspplayer
