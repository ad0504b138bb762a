#include "player/session.h"

#include <cmath>
#include <filesystem>

#include "jobs/cache_key.h"
#include "jobs/calibration.h"
#include "tsp/core/error.h"
#include "tsp/core/input_file.h"
#include "tsp/core/json_read.h"
#include "tsp/core/json_text.h"
#include "tsp/core/temp_output.h"

namespace tspplayer {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A member of j (optional: a session written by an older build of this version may lack it),
// of type T; a value of the wrong type is a FormatError naming it.
template <class T>
void take(const json& j, const char* key, T& out, const std::string& origin) {
  const auto it = j.find(key);
  if (it == j.end()) return;
  try {
    out = it->get<T>();
  } catch (const json::exception& e) {
    throw tsp::FormatError(origin + ": session key '" + key + "': " + e.what());
  }
}

void finite(double v, const char* key, const std::string& origin) {
  if (!std::isfinite(v))
    throw tsp::FormatError(origin + ": session key '" + std::string(key) + "' is not finite");
}

json rgba(const tsp::Rgba& c) { return {c.r, c.g, c.b, c.a}; }

tsp::Rgba rgba_of(const json& j, const std::string& origin) {
  if (!j.is_array() || j.size() != 4)
    throw tsp::FormatError(origin + ": session key 'tf': a colour is [r, g, b, a]");
  tsp::Rgba c{j[0].get<float>(), j[1].get<float>(), j[2].get<float>(), j[3].get<float>()};
  for (float v : {c.r, c.g, c.b, c.a})
    if (!(v >= 0 && v <= 1))
      throw tsp::FormatError(origin + ": session key 'tf': colour components lie in [0, 1]");
  return c;
}

void read_tf(const json& t, Session& s, const std::string& origin) {
  if (!t.is_object()) throw tsp::FormatError(origin + ": session key 'tf' is not an object");
  std::array<double, 2> d{0, 1};
  take(t, "domain", d, origin);
  finite(d[0], "tf.domain", origin);
  finite(d[1], "tf.domain", origin);
  if (!(d[0] < d[1])) throw tsp::FormatError(origin + ": session key 'tf.domain': expected lo < hi");
  s.tf_domain = {d[0], d[1]};
  try {
    for (const json& e : t.value("entries", json::array())) s.tf_entries.push_back(rgba_of(e, origin));
    for (const json& p : t.value("points", json::array())) {
      if (!p.is_array() || p.size() != 2)
        throw tsp::FormatError(origin + ": session key 'tf.points': a point is [x, [r, g, b, a]]");
      s.tf_points.push_back({p[0].get<double>(), rgba_of(p[1], origin)});
      finite(s.tf_points.back().x, "tf.points", origin);
    }
  } catch (const json::exception& e) {
    throw tsp::FormatError(origin + ": session key 'tf': " + e.what());
  }
  if (s.tf_entries.size() == 1)
    throw tsp::FormatError(origin + ": session key 'tf.entries': at least two entries");
  take(t, "label", s.tf_label, origin);
  take(t, "log_opacity", s.log_opacity, origin);
}

void read_camera(const json& c, Session& s, const std::string& origin) {
  if (!c.is_object()) throw tsp::FormatError(origin + ": session key 'camera' is not an object");
  take(c, "azimuth_deg", s.azimuth_deg, origin);
  take(c, "elevation_deg", s.elevation_deg, origin);
  take(c, "zoom", s.zoom, origin);
  take(c, "fov_deg", s.fov_deg, origin);
  take(c, "perspective", s.perspective, origin);
  take(c, "pan", s.pan, origin);
  if (c.contains("eye") && !c["eye"].is_null()) {
    std::array<double, 3> eye{};
    take(c, "eye", eye, origin);
    for (double v : eye) finite(v, "camera.eye", origin);
    s.eye = eye;
  }
  for (double v : {s.azimuth_deg, s.pan[0], s.pan[1]}) finite(v, "camera", origin);
  if (!(s.elevation_deg > -90 && s.elevation_deg < 90))
    throw tsp::FormatError(origin + ": session key 'camera.elevation_deg': expected (-90, 90)");
  if (!(s.zoom > 0) || !std::isfinite(s.zoom))
    throw tsp::FormatError(origin + ": session key 'camera.zoom': expected a positive number");
  if (!(s.fov_deg > 0 && s.fov_deg < 180))
    throw tsp::FormatError(origin + ": session key 'camera.fov_deg': expected (0, 180)");
}

}  // namespace

bool Session::operator==(const Session& o) const {
  auto same_points = [](const std::vector<tsp::TfPoint>& a, const std::vector<tsp::TfPoint>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (a[i].x != b[i].x || !(a[i].c == b[i].c)) return false;
    return true;
  };
  return input == o.input && field == o.field && tf_domain.lo == o.tf_domain.lo &&
         tf_domain.hi == o.tf_domain.hi && tf_entries == o.tf_entries &&
         same_points(tf_points, o.tf_points) && tf_label == o.tf_label &&
         log_opacity == o.log_opacity && azimuth_deg == o.azimuth_deg &&
         elevation_deg == o.elevation_deg && zoom == o.zoom && fov_deg == o.fov_deg &&
         perspective == o.perspective && pan == o.pan && eye == o.eye && scale == o.scale &&
         step == o.step && speed == o.speed && loop == o.loop && every_step == o.every_step &&
         probes == o.probes && probe_op == o.probe_op && probe_surface == o.probe_surface &&
         surface == o.surface && panels == o.panels && annotations == o.annotations &&
         ui_ini == o.ui_ini && ui_open == o.ui_open;
}

json to_json(const Session& s) {
  json entries = json::array(), points = json::array();
  for (const tsp::Rgba& c : s.tf_entries) entries.push_back(rgba(c));
  for (const tsp::TfPoint& p : s.tf_points) points.push_back({p.x, rgba(p.c)});
  json camera = {{"azimuth_deg", s.azimuth_deg}, {"elevation_deg", s.elevation_deg},
                 {"zoom", s.zoom},               {"fov_deg", s.fov_deg},
                 {"perspective", s.perspective}, {"pan", s.pan}};
  camera["eye"] = s.eye ? json(*s.eye) : json();
  return {{"version", kSessionVersion},
          {"input", s.input},
          {"field", s.field},
          {"tf",
           {{"domain", {s.tf_domain.lo, s.tf_domain.hi}},
            {"label", s.tf_label},
            {"log_opacity", s.log_opacity},
            {"points", points},
            {"entries", entries}}},
          {"camera", camera},
          {"scale", s.scale},
          {"step", s.step},
          {"speed", s.speed},
          {"loop", s.loop},
          {"every_step", s.every_step},
          {"probes", s.probes},
          {"probe_op", s.probe_op},
          {"probe_surface", s.probe_surface},
          {"surface", s.surface},
          {"panels",
           {{"shown", s.panels},
            {"annotations", s.annotations},
            {"imgui_ini", s.ui_ini},
            {"open", s.ui_open}}}};
}

Session session_from_json(const json& j, const std::string& origin) {
  if (!j.is_object()) throw tsp::FormatError(origin + ": not a tspplay session (not a JSON object)");
  if (!j.contains("version") || !j["version"].is_number_integer())
    throw tsp::FormatError(origin + ": not a tspplay session (no version)");
  if (const int v = j["version"].get<int>(); v != kSessionVersion)
    throw tsp::FormatError(origin + ": session version " + std::to_string(v) +
                           ", this tspplay reads version " + std::to_string(kSessionVersion));
  Session s;
  take(j, "input", s.input, origin);
  take(j, "field", s.field, origin);
  if (j.contains("tf")) read_tf(j["tf"], s, origin);
  if (j.contains("camera")) read_camera(j["camera"], s, origin);
  take(j, "scale", s.scale, origin);
  for (double k : s.scale)
    if (!(k > 0) || !std::isfinite(k))
      throw tsp::FormatError(origin + ": session key 'scale': expected three positive factors");
  take(j, "step", s.step, origin);
  if (s.step < 0) throw tsp::FormatError(origin + ": session key 'step' is negative");
  take(j, "speed", s.speed, origin);
  if (!(s.speed >= 0) || !std::isfinite(s.speed))
    throw tsp::FormatError(origin + ": session key 'speed': expected 0 or steps per second");
  take(j, "loop", s.loop, origin);
  take(j, "every_step", s.every_step, origin);
  take(j, "probes", s.probes, origin);
  take(j, "probe_op", s.probe_op, origin);
  take(j, "probe_surface", s.probe_surface, origin);
  take(j, "surface", s.surface, origin);
  if (j.contains("panels")) {
    const json& p = j["panels"];
    if (!p.is_object()) throw tsp::FormatError(origin + ": session key 'panels' is not an object");
    take(p, "shown", s.panels, origin);
    take(p, "annotations", s.annotations, origin);
    take(p, "imgui_ini", s.ui_ini, origin);
    if (p.contains("open")) {
      if (!p["open"].is_object())
        throw tsp::FormatError(origin + ": session key 'panels.open' is not an object");
      for (const auto& [window, ids] : p["open"].items()) {
        std::vector<std::array<std::int64_t, 2>> pairs;
        take(p["open"], window.c_str(), pairs, origin);
        for (const auto& [id, open] : pairs)
          if (id < 0 || id > 0xffffffffll || (open != 0 && open != 1))
            throw tsp::FormatError(origin + ": session key 'panels.open': expected [id, 0|1]");
      }
      s.ui_open = p["open"];
    }
  }
  return s;
}

Session read_session(const std::string& path) {
  const std::string text = tsp::read_input_file(path, "session", kMaxSessionBytes);
  return session_from_json(tsp::parse_json(text, path), path);
}

void write_session(const std::string& path, const Session& s, bool cache_entry) {
  if (cache_entry) {
    std::error_code ec;
    fs::create_directories(fs::path(path).parent_path(), ec);
    if (ec)
      throw tsp::IoError(fs::path(path).parent_path().string() +
                         ": cannot create the session folder: " + ec.message());
  }
  tsp::write_file_atomically(path, tsp::json_text(to_json(s), 1) + "\n",
                             cache_entry ? tsp::OutputLinks::replace : tsp::OutputLinks::follow);
}

std::string session_cache_path(const std::string& input, const std::string& field,
                               const std::string& dir) {
  const std::string root = dir.empty() ? tspgl::default_calibration_dir() : dir;
  if (root.empty() || root == "-") return "";
  std::error_code ec;
  fs::path named = fs::absolute(fs::path(input), ec);
  if (ec) named = fs::path(input);
  const json key = {{"input", named.lexically_normal().string()}, {"field", field}};
  return (fs::path(root) / "sessions" / ("session-" + tspgl::key_hash(tsp::json_text(key)) + ".json"))
      .string();
}

}  // namespace tspplayer
