// The TF editor's histogram as the player keeps it (tf_histogram.h counts it): counted again only
// when the domain, the file or the bars change, its errors in the status area, its last count for
// `stats` — the panel draws it and writes nothing.
#include <algorithm>

#include "player/player_app.h"
#include "tsp/core/error.h"

namespace tspplayer {

const EditorHistogram& PlayerApp::editor_histogram(const tsp::ValueRange& d, int bins) {
  EditorHistogram& h = editor_histogram_;
  if (editor_histogram_file_ == &viewer().file() && h.over.lo == d.lo && h.over.hi == d.hi &&
      int(h.counts.size()) == bins)
    return h;
  try {
    h = tspplayer::editor_histogram(viewer().file(), state_.step, d, bins);
  } catch (const tsp::Error& e) {
    h = {d, std::vector<double>(std::size_t(bins), 0.0), -1};
    status = std::string("histogram: ") + e.what();
  }
  editor_histogram_file_ = &viewer().file();
  editor_histogram_bins_ =
      int(std::count_if(h.counts.begin(), h.counts.end(), [](double c) { return c > 0; }));
  return h;
}

}  // namespace tspplayer
