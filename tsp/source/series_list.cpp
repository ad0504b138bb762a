#include "tsp/source/series_list.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/core/input_file.h"
#include "tsp/core/json_read.h"

namespace tsp::io {
namespace {

namespace fs = std::filesystem;

pugi::xml_node load_vtk_xml(pugi::xml_document& doc, const std::string& path,
                            const std::string& type) {
  const std::string text = read_input_file(path, "list file");
  pugi::xml_parse_result res = doc.load_buffer(text.data(), text.size());
  if (!res)
    throw FormatError(path + ": not well-formed XML (" + res.description() + " at byte " +
                      std::to_string(res.offset) + ")");
  pugi::xml_node root = doc.child("VTKFile");
  if (!root || std::string(root.attribute("type").value()) != type)
    throw FormatError(path + ": expected <VTKFile type=\"" + type + "\">");
  return root;
}

}  // namespace

bool has_suffix(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  return std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) ==
           std::tolower(static_cast<unsigned char>(b));
  });
}

std::string resolve_relative(const std::string& list_file, const std::string& name) {
  fs::path p(name);
  if (p.is_absolute()) return p.string();
  return (fs::path(list_file).parent_path() / p).string();
}

std::vector<StepFile> read_pvd(const std::string& path) {
  pugi::xml_document doc;
  pugi::xml_node root = load_vtk_xml(doc, path, "Collection");
  pugi::xml_node collection = root.child("Collection");
  if (!collection) throw FormatError(path + ": no <Collection> element");
  std::vector<StepFile> steps;
  int index = 0;
  for (pugi::xml_node ds : collection.children("DataSet")) {
    const std::string dwhere = path + ", DataSet " + std::to_string(index++);
    if (!ds.attribute("file")) throw FormatError(dwhere + ": has no file attribute");
    if (!ds.attribute("timestep"))
      throw FormatError(dwhere + ": has no timestep attribute, expected one per step");
    std::string text = ds.attribute("timestep").value();
    std::size_t used = 0;
    double time = 0;
    try {
      time = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size())
      throw FormatError(dwhere + ": timestep \"" + text + "\" is not a number");
    if (!std::isfinite(time))
      throw FormatError(dwhere + ": timestep \"" + text + "\" is not a finite number");
    steps.push_back({resolve_relative(path, ds.attribute("file").value()), time});
  }
  return steps;
}

std::vector<StepFile> read_file_series(const std::string& path) {
  const std::string text = read_input_file(path, "list file");
  nlohmann::json j = parse_json(text, path);
  if (!j.is_object() || !j.contains("file-series-version") || !j["file-series-version"].is_string())
    throw FormatError(path + ": no \"file-series-version\" string, expected \"1.0\"");
  std::string version = j["file-series-version"];
  if (version.rfind("1.", 0) != 0)
    throw FormatError(path + ": file-series-version \"" + version + "\", expected 1.x");
  if (!j.contains("files") || !j["files"].is_array())
    throw FormatError(path + ": no \"files\" array");
  std::vector<StepFile> steps;
  int index = 0;
  for (const auto& f : j["files"]) {
    const std::string fwhere = path + ", files[" + std::to_string(index++) + "]";
    if (!f.is_object() || !f.contains("name") || !f["name"].is_string())
      throw FormatError(fwhere + ": expected an object with a \"name\" string");
    if (!f.contains("time") || !f["time"].is_number())
      throw FormatError(fwhere + ": expected a numeric \"time\"");
    steps.push_back(
        {resolve_relative(path, f["name"].get<std::string>()), f["time"].get<double>()});
  }
  return steps;
}

void order_steps(const std::string& list, std::vector<StepFile>& steps) {
  if (steps.empty()) throw FormatError(list + ": lists no data files, expected at least one");
  std::stable_sort(steps.begin(), steps.end(),
                   [](const StepFile& a, const StepFile& b) { return a.time < b.time; });
  for (std::size_t i = 1; i < steps.size(); ++i)
    if (steps[i].time == steps[i - 1].time)
      throw FormatError(list + ": " + steps[i - 1].file + " and " + steps[i].file +
                        " share time " + std::to_string(steps[i].time) +
                        "; several parts per time step are not supported");
}

std::string vtm_volume_block(const std::string& path) {
  pugi::xml_document doc;
  pugi::xml_node root = load_vtk_xml(doc, path, "vtkMultiBlockDataSet");
  std::vector<std::string> names, volumes;
  std::string internal;
  // Every DataSet at any depth, without recursion.
  for (pugi::xpath_node x : root.select_nodes("//DataSet")) {
    pugi::xml_node ds = x.node();
    const std::string name = ds.attribute("name").value();
    const std::string file = ds.attribute("file").value();
    names.push_back(name.empty() ? file : name);
    if (name == "internal" && !file.empty()) internal = file;
    if (has_suffix(file, ".vtu") || has_suffix(file, ".vts")) volumes.push_back(file);
  }
  // The block is read later through the input gate; checked here too, so that the error names
  // the .vtm that points at it.
  const auto checked = [&](const std::string& block) {
    const std::string file = resolve_relative(path, block);
    try {
      require_regular_file(file, "volume block");
    } catch (const IoError& e) {
      throw IoError(path + ": " + e.what());
    }
    return file;
  };
  if (!internal.empty()) return checked(internal);
  if (volumes.size() == 1) return checked(volumes[0]);
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) list += (i ? ", " : "") + names[i];
  throw FormatError(path + ": no DataSet named \"internal\" and " +
                    std::to_string(volumes.size()) + " .vtu/.vts blocks (blocks: " +
                    (list.empty() ? "none" : list) +
                    "); expected the volume mesh as one .vtu or .vts");
}

}  // namespace tsp::io
