#include "teleop/sim/model_additions.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "xml_mutex.h"

namespace teleop::sim {
namespace {

// a scratch file name that no other process or thread uses
std::string scratch_path(const char* tag) {
  static std::atomic<int> counter{0};
  const auto dir = std::filesystem::temp_directory_path();
  return (dir / ("teleop_" + std::string(tag) + "_" + std::to_string(getpid()) + "_" + std::to_string(counter++) + ".xml"))
      .string();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// MuJoCo writes the whole model, includes resolved, into one file
std::string flatten(const std::string& path) {
  const std::string flat = scratch_path("flat");
  std::array<char, 1024> error{};
  {
    const std::lock_guard lock(xml_mutex());
    mjModel* model = mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
    if (model == nullptr) throw std::runtime_error("cannot load MuJoCo model '" + path + "': " + error.data());
    const int saved = mj_saveLastXML(flat.c_str(), model, error.data(), static_cast<int>(error.size()));
    mj_deleteModel(model);
    if (saved == 0) throw std::runtime_error("cannot flatten MuJoCo model '" + path + "': " + error.data());
  }
  std::string text = read_text(flat);
  std::filesystem::remove(flat);
  return text;
}

// position just after the start tag of the body (or the worldbody)
size_t insertion_point(const std::string& text, const std::string& body, const std::string& path) {
  const std::string tag = body.empty() ? "<worldbody" : "<body name=\"" + body + "\"";
  const size_t start = text.find(tag);
  const size_t end = start == std::string::npos ? start : text.find('>', start);
  if (end == std::string::npos || text[end - 1] == '/') {
    throw std::runtime_error("MuJoCo model '" + path + "' has no body named '" + body + "' to add geometry to");
  }
  return end + 1;
}

}  // namespace

std::string flatten_with_additions(const std::string& path, const std::vector<ModelAddition>& additions) {
  std::string text = flatten(path);
  for (const ModelAddition& a : additions) {
    text.insert(insertion_point(text, a.body, path), "\n" + a.element_xml + "\n");
  }
  return text;
}

MujocoModel load_with_additions(const std::string& path, const std::vector<ModelAddition>& additions) {
  if (additions.empty()) return MujocoModel::load(path);
  const std::string text = flatten_with_additions(path, additions);
  const std::string scratch = scratch_path("overlay");
  {
    std::ofstream out(scratch);
    out << text;
    if (!out) throw std::runtime_error("cannot write scratch model '" + scratch + "'");
  }
  try {
    MujocoModel model = MujocoModel::load(scratch);
    std::filesystem::remove(scratch);
    return model;
  } catch (const std::runtime_error& e) {
    std::filesystem::remove(scratch);
    throw std::runtime_error("MuJoCo model '" + path + "' with the added geometry: " + e.what());
  }
}

}  // namespace teleop::sim
