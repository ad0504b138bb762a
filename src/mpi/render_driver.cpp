#include "mpi/render_driver.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "jobs/frame_set.h"
#include "jobs/movie.h"
#include "mpi/child_process.h"
#include "tsp/core/error.h"
#include "tsp/core/input_file.h"
#include "tsp/core/json_read.h"
#include "tsp/core/json_text.h"
#include "tsp/core/output_folder.h"
#include "tsp/core/temp_output.h"

namespace tspmpi {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Waiting ranks poll instead of blocking: Open MPI's blocking collectives spin on a core, which
// the other ranks' renders need (a rank whose part is done would slow the rest down).
constexpr auto kPollInterval = std::chrono::milliseconds(2);
// Largest part frames.json read back (a frame's record is about 1 KB).
constexpr std::int64_t kMaxFramesJson = std::int64_t(1) << 30;

void wait(MPI_Request& request) {
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(kPollInterval);
  }
}

// Rank 0's code and text, on every rank.
void share(MPI_Comm comm, int& code, std::string& text) {
  int head[2] = {code, int(text.size())};
  MPI_Request r;
  MPI_Ibcast(head, 2, MPI_INT, 0, comm, &r);
  wait(r);
  code = head[0];
  text.resize(std::size_t(head[1]));
  MPI_Ibcast(text.data(), head[1], MPI_CHAR, 0, comm, &r);
  wait(r);
}

// Every rank's code and text, on rank 0 (in rank order; empty elsewhere).
std::vector<std::pair<int, std::string>> gather(MPI_Comm comm, int code, const std::string& text) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  int mine[2] = {code, int(text.size())};
  std::vector<int> heads(rank == 0 ? std::size_t(2 * ranks) : 0);
  MPI_Request r;
  MPI_Igather(mine, 2, MPI_INT, heads.data(), 2, MPI_INT, 0, comm, &r);
  wait(r);
  std::vector<int> sizes, offsets;
  std::size_t total = 0;
  for (int i = 0; rank == 0 && i < ranks; ++i) {
    sizes.push_back(heads[std::size_t(2 * i + 1)]);
    offsets.push_back(int(total));
    total += std::size_t(sizes.back());
  }
  std::string all(total, '\0');
  MPI_Igatherv(text.data(), int(text.size()), MPI_CHAR, all.data(), sizes.data(), offsets.data(),
               MPI_CHAR, 0, comm, &r);
  wait(r);
  std::vector<std::pair<int, std::string>> out;
  for (int i = 0; rank == 0 && i < ranks; ++i)
    out.emplace_back(heads[std::size_t(2 * i)],
                     all.substr(std::size_t(offsets[std::size_t(i)]), std::size_t(sizes[std::size_t(i)])));
  return out;
}

// What `tspplay render --mpi-check` answered: the outputs rank 0 makes.
struct Check {
  std::string out, movie, save_tf;
  int fps = 8, passes = 1;
  std::vector<std::string> inputs;
};

Check parse_check(const std::string& text) {
  const json j = tsp::parse_json(text, "tspplay render --mpi-check");
  Check c;
  try {
    c.out = j.at("out").get<std::string>();
    c.movie = j.at("movie").get<std::string>();
    c.save_tf = j.at("save_tf").get<std::string>();
    c.fps = j.at("fps").get<int>();
    c.passes = j.at("passes").get<int>();
    for (const json& i : j.at("inputs")) c.inputs.push_back(i.get<std::string>());
  } catch (const json::exception& e) {
    throw tsp::FormatError(std::string("tspplay render --mpi-check: unexpected answer: ") + e.what());
  }
  return c;
}

// Rank 0's outputs, checked and reserved before any rank renders (the serial render's order):
// the frames' folder, --save-tf and --movie, each replaced only when the whole job succeeded.
struct Outputs {
  explicit Outputs(Check c) : check(std::move(c)), inputs(check.inputs) {
    folder.emplace(check.out, tspgl::is_frame_set_name);
    if (!check.save_tf.empty()) saved_tf.emplace(check.save_tf);
    if (!check.movie.empty()) movie.emplace(check.movie);
  }
  Check check;
  tsp::InputGuard inputs;
  std::optional<tsp::OutputFolder> folder;
  std::optional<tsp::TempOutput> saved_tf, movie;
};

// The folder rank r renders into, inside rank 0's temporary output folder.
fs::path part_dir(const std::string& shared, int rank) {
  return fs::path(shared) / (".rank-" + std::to_string(rank));
}

std::vector<std::string> with(std::vector<std::string> args, std::initializer_list<std::string> more) {
  args.insert(args.begin(), "render");
  args.insert(args.end(), more);
  return args;
}

// Rank 0's first step: the serial command checks everything (the same errors, said once), then
// the outputs are reserved. Returns the exit status (0: go on) and fills outputs.
int check_and_reserve(const std::vector<std::string>& args, std::unique_ptr<Outputs>& outputs) {
  try {
    const ChildResult r = run_child(serial_tspplay(), with(args, {"--mpi-check"}), {}, true);
    if (r.exit_code != 0) {  // its words, under our name
      std::istringstream in(r.err);
      for (std::string line; std::getline(in, line);)
        std::fprintf(stderr, "%s\n", (line.rfind("tspplay: ", 0) == 0 ? "tspplay-mpi: " + line.substr(9)
                                                                       : line).c_str());
      return r.exit_code;
    }
    outputs = std::make_unique<Outputs>(parse_check(r.out));
    return 0;
  } catch (const tsp::UsageError& e) {
    std::fprintf(stderr, "tspplay-mpi: usage error: %s\n", e.what());
    return 2;
  } catch (const tsp::Error& e) {
    std::fprintf(stderr, "tspplay-mpi: error: %s\n", e.what());
    return 1;
  }
}

// Renders this rank's part; returns its status and what it said (tspplay's prefixes removed).
std::pair<int, std::string> render_part(const std::vector<std::string>& args, const std::string& shared,
                                        int rank, int ranks, int threads, int node_rank) {
  const std::string t = std::to_string(threads);
  // Its share of the node's cores, and of its GPUs (EGL: GPU node_rank mod GPUs, unless --gpu
  // or TSPPLAY_EGL_DEVICE names one).
  std::vector<std::string> env = {"TSPPLAY_THREADS=" + t,
                                  "TSPPLAY_EGL_DEVICE_SLOT=" + std::to_string(node_rank)};
  if (!std::getenv("LP_NUM_THREADS")) env.push_back("LP_NUM_THREADS=" + t);  // llvmpipe's
  try {
    const ChildResult r = run_child(
        serial_tspplay(),
        with(args, {"--mpi-part", std::to_string(rank) + "/" + std::to_string(ranks), "--mpi-dir",
                    part_dir(shared, rank).string()}),
        env);
    std::string said;
    for (const std::string& line : child_lines(r.err)) said += line + "\n";
    if (r.exit_code != 0 && said.empty())
      said = "error: tspplay render ended with status " + std::to_string(r.exit_code) + "\n";
    return {r.exit_code, said};
  } catch (const tsp::Error& e) {
    return {1, std::string("error: ") + e.what() + "\n"};
  }
}

// Moves rank r's PNGs up into the shared folder and returns its frames.json.
json take_part(const std::string& shared, int r) {
  const fs::path dir = part_dir(shared, r);
  const json j = tsp::parse_json(
      tsp::read_input_file((dir / "frames.json").string(), "frames.json", kMaxFramesJson),
      (dir / "frames.json").string());
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "frames.json" || !tspgl::is_frame_set_name(name)) continue;
    std::error_code ec;
    fs::rename(e.path(), fs::path(shared) / name, ec);
    if (ec) throw tsp::IoError(e.path().string() + ": cannot move into the output (" + ec.message() + ")");
  }
  fs::remove_all(dir);
  return j;
}

// Rank 0, every part done: the serial render's frame set, frames.json, --save-tf and movie,
// committed in its order. Prints the summary. Throws tsp::Error (nothing is committed then).
void join(Outputs& o, int ranks) {
  const std::string shared = fs::absolute(o.folder->tmp()).string();
  std::vector<json> parts;
  for (int r = 0; r < ranks; ++r) parts.push_back(take_part(shared, r));
  const json merged = tspgl::merge_part_frames(parts);
  try {
    tsp::write_file_atomically((fs::path(shared) / "frames.json").string(),
                               tsp::json_text(merged, 2) + "\n");
  } catch (const tsp::IoError& e) {
    throw tsp::IoError(o.folder->as_shown(e.what()));
  }
  std::vector<fs::path> frames;
  int last_pass = 0;
  for (const json& f : merged["frames"]) last_pass = std::max(last_pass, f["pass"].get<int>());
  for (const json& f : merged["frames"])
    if (f["pass"].get<int>() == last_pass)
      frames.push_back(tspgl::step_png(shared, f.at("step").get<int>()));
  const fs::path tf_part = part_dir(shared, 0).string() + ".tf.json";
  if (o.saved_tf) {
    const std::string text = tsp::read_input_file(tf_part.string(), "--save-tf");
    std::ofstream(o.saved_tf->tmp(), std::ios::binary | std::ios::trunc) << text;
    fs::remove(tf_part);
  }
  if (o.movie) tspgl::encode_movie_into(frames, *o.movie, o.check.movie, o.check.fps);
  if (o.saved_tf) o.saved_tf->commit();
  o.folder->commit();
  if (o.movie) o.movie->commit();
  std::printf("rendered %zu frames (%zu steps x %d passes) on %d ranks with %s\n",
              merged["frames"].size(), frames.size(), last_pass, ranks,
              merged.value("renderer", "").c_str());
  std::printf("median frame %.2f ms (last pass)\n", merged.value("median_ms", 0.0));
  std::printf("wrote %s/frames.json\n", o.check.out.c_str());
  if (o.movie)
    std::printf("wrote %s (%zu frames, %d a second)\n", o.check.movie.c_str(), frames.size(),
                o.check.fps);
}

// Rank 0: says what every failed rank said, or joins the parts. Returns the exit status.
int finish(const std::vector<std::pair<int, std::string>>& parts, Outputs& outputs) {
  const int ranks = int(parts.size());
  int code = 0;
  std::set<std::string> warnings;
  for (int r = 0; r < ranks; ++r) {
    for (const std::string& line : child_lines(parts[std::size_t(r)].second)) {
      if (line.rfind("warning: ", 0) == 0) {
        warnings.insert(line);
      } else if (parts[std::size_t(r)].first != 0) {
        std::fprintf(stderr, "tspplay-mpi: rank %d of %d: %s\n", r, ranks, line.c_str());
      }
    }
    if (parts[std::size_t(r)].first != 0 && code == 0) code = parts[std::size_t(r)].first;
  }
  for (const std::string& w : warnings) std::fprintf(stderr, "tspplay-mpi: %s\n", w.c_str());
  if (code != 0) {
    std::fprintf(stderr, "tspplay-mpi: nothing written: %s left as it was\n",
                 outputs.check.out.c_str());
    return code >= 1 && code <= 3 ? code : 1;
  }
  try {
    join(outputs, ranks);
    return 0;
  } catch (const tsp::Error& e) {
    std::fprintf(stderr, "tspplay-mpi: rank 0 of %d: error: %s\n", ranks, e.what());
    return 1;
  }
}

// This rank's index among the ranks of comm on its node (0 when MPI cannot tell).
int node_rank(MPI_Comm comm) {
  int rank = 0, on_node = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm node;
  if (MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node) != MPI_SUCCESS)
    return 0;
  MPI_Comm_rank(node, &on_node);
  MPI_Comm_free(&node);
  return on_node;
}

void print_help() {
  std::printf(
      "tspplay-mpi render: `tspplay render` with its steps split over MPI ranks\n"
      "  mpirun -np N tspplay-mpi render FILE -o frames/ [render's options] [--movie out.mp4]\n\n"
      "Each rank renders a block of consecutive frames with the serial tspplay (beside this\n"
      "executable or on PATH) on its share of the node's cores; rank 0 writes the serial\n"
      "render's step PNGs and frames.json (each frame with its \"rank\") and encodes --movie.\n"
      "A failing rank is named and nothing is written. docs/mpi.md has the details.\n"
      "render's options:\n\n");
  std::fflush(stdout);
  try {
    const ChildResult r = run_child(serial_tspplay(), {"render", "--help"}, {}, true);
    std::fputs(r.out.c_str(), stdout);
  } catch (const tsp::Error& e) {
    std::fprintf(stderr, "tspplay-mpi: error: %s\n", e.what());
  }
}

}  // namespace

int run_render(MPI_Comm comm, int threads, const std::vector<std::string>& args) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") {
      if (rank == 0) print_help();
      return 0;
    }
  std::unique_ptr<Outputs> outputs;  // rank 0's
  int code = rank == 0 ? check_and_reserve(args, outputs) : 0;
  // Absolute: every rank (on any node, over a shared file system) renders into it.
  std::string shared = outputs ? fs::absolute(outputs->folder->tmp()).string() : std::string();
  std::fflush(stderr);
  share(comm, code, shared);
  if (code != 0) return code;
  const auto [status, said] = render_part(args, shared, rank, ranks, threads, node_rank(comm));
  const auto parts = gather(comm, status, said);
  if (rank == 0) code = finish(parts, *outputs);
  std::fflush(stdout);
  std::fflush(stderr);
  std::string none;
  share(comm, code, none);  // every rank ends with rank 0's status
  return code;
}

}  // namespace tspmpi
