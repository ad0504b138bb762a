// The fields a player put aside when it switched to another field of the same file: each keeps
// its open file, its renderer (textures resident, bricks in RAM) and its TF, so switching back
// shows it at once, as it was.
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "render/volume_renderer.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/store/tsp_file.h"

namespace tspplayer {

/// Parked fields by name. Use from the GL thread (the renderers hold GL objects).
class FieldShelf {
 public:
  /// One parked field: what it is drawn from and with.
  struct Field {
    std::unique_ptr<tsp::TspFile> file;
    std::unique_ptr<tspgl::VolumeRenderer> renderer;  ///< null: made anew when shown
    tsp::TransferFunction tf;
  };
  /// Puts f aside under name (replacing a field parked there). Never throws.
  void park(const std::string& name, Field f) { fields_[name] = std::move(f); }
  /// The field parked under name, taken off the shelf; none when there is none. Never throws.
  std::optional<Field> take(const std::string& name) {
    auto it = fields_.find(name);
    if (it == fields_.end()) return std::nullopt;
    Field f = std::move(it->second);
    fields_.erase(it);
    return f;
  }
  /// Drops every parked field (their renderers' GL objects: the context must be current).
  void clear() { fields_.clear(); }
  /// Number of parked fields.
  std::size_t size() const { return fields_.size(); }

 private:
  std::map<std::string, Field> fields_;
};

}  // namespace tspplayer
