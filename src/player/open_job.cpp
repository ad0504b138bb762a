#include "player/open_job.h"

#include <cstdio>
#include <vector>

#include "jobs/play_input.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"

namespace tspplayer {

OpenJob::OpenJob(std::string input, tspgl::PlayInputOptions o, std::string cache_dir)
    : input_(std::move(input)), field_(o.field) {
  worker_.submit([this, o = std::move(o), cache_dir = std::move(cache_dir)](std::stop_token stop) {
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
    const auto report = [this, stop](const std::string& phase, std::int64_t done,
                                     std::int64_t total) {
      if (stop.stop_requested()) throw tsp::Error("cancelled; no file written");
      std::lock_guard lock(mu_);
      progress_.phase = phase;
      progress_.done = done;
      progress_.total = total;
    };
    hooks.build = [report](tsp::VolumeSource& source, const std::string& out,
                           tsp::BuildOptions b) {
      b.progress = report;
      return tsp::build_tsp_file(source, out, b);
    };
    hooks.build_fields = [report](const tsp::FieldSourceFn& open_field,
                                  const std::vector<std::string>& fields, const std::string& out,
                                  tsp::BuildOptions b) {
      b.progress = report;
      tsp::build_tsp_fields(open_field, fields, out, b);
    };
    hooks.build_adaptive = [report](tsp::MeshSource& mesh, const std::string& out,
                                    tsp::AdaptiveOptions a) {
      a.build.progress = report;
      tsp::build_adaptive_tsp(mesh, out, a);
    };
    std::string out = tspgl::prepare_play_input(input_, o, cache_dir, hooks);
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
