#include "apps/hostile/roadmap_edits.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "gplanner/planner/output/roadmap_file.h"
#include "gplanner/planner/planning/roadmap.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner::hostile {
namespace {

// The layout save_roadmap writes (planner/src/planning/roadmap.cpp).
constexpr std::size_t kMagicBytes = 19;  // "gplanner-roadmap 1\n"
constexpr std::size_t kFingerprintAt = kMagicBytes;
constexpr std::size_t kWidthAt = kFingerprintAt + 8;
constexpr std::size_t kVertexCountAt = kWidthAt + 4;
constexpr std::size_t kEdgeCountAt = kVertexCountAt + 8;
constexpr std::size_t kVerticesAt = kEdgeCountAt + 8;

std::uint64_t fnv1a(const std::string& bytes, std::size_t n) {
  std::uint64_t value = 1469598103934665603ull;
  for (std::size_t i = 0; i < n; ++i) {
    value ^= static_cast<unsigned char>(bytes[i]);
    value *= 1099511628211ull;
  }
  return value;
}

void fix_checksum(std::string* bytes) {
  const std::size_t body = bytes->size() - 8;
  const std::uint64_t sum = fnv1a(*bytes, body);
  std::memcpy(&(*bytes)[body], &sum, 8);
}

template <typename T>
void set(std::string* bytes, std::size_t at, T value) {
  if (at + sizeof(T) > bytes->size()) throw std::runtime_error("roadmap edit past the end");
  std::memcpy(&(*bytes)[at], &value, sizeof(T));
}

double number(const YAML::Node& value) {
  return std::strtod(value.as<std::string>().c_str(), nullptr);
}

std::string saved_roadmap(const Scene& scene, const std::string& folder) {
  const int w = scene.space.width();
  Roadmap roadmap(w);
  std::vector<float> q(scene.start.begin(), scene.start.end());
  roadmap.add_vertex(q.data());
  roadmap.add_vertex(scene.goal.data());
  // Two more: the start raised and the goal raised (the tiny scenes' first value is x or
  // a joint angle; any finite row within the scene's own rows will do).
  roadmap.add_vertex(q.data());
  roadmap.add_vertex(scene.goal.data());
  roadmap.add_edge(0, 2, 0.5f);
  roadmap.add_edge(1, 3, 0.5f);
  roadmap.add_edge(2, 3, 1.5f);
  const std::string path = folder + "/.roadmap-being-made";
  save_roadmap(roadmap, scene, path);
  std::string bytes = testing::read_file(path);
  std::filesystem::remove(path);
  return bytes;
}

}  // namespace

std::string roadmap_file(const std::string& folder, const YAML::Node& spec) {
  const std::string scene_name = spec["scene"] ? spec["scene"].as<std::string>() : "scene.yaml";
  const Scene scene = load_scene(folder + "/" + scene_name);
  std::string bytes = saved_roadmap(scene, folder);
  const std::size_t width = static_cast<std::size_t>(scene.space.width());
  const std::size_t edges_at = kVerticesAt + 4 * width * 4;
  for (const auto& edit : spec) {
    const std::string kind = edit.first.as<std::string>();
    const YAML::Node& value = edit.second;
    if (kind == "scene" || kind == "valid") continue;
    if (kind == "truncate") {
      bytes.resize(bytes.size() - std::min<std::size_t>(bytes.size(), value.as<std::size_t>()));
      continue;
    }
    if (kind == "magic") {
      const std::string text = value.as<std::string>();
      bytes.replace(0, std::min(text.size(), bytes.size()), text);
      continue;
    }
    if (kind == "flip") {
      bytes.at(value.as<std::size_t>()) ^= static_cast<char>(0xff);
      continue;
    }
    if (kind == "fingerprint") {
      std::uint64_t fingerprint;
      std::memcpy(&fingerprint, &bytes[kFingerprintAt], 8);
      set<std::uint64_t>(&bytes, kFingerprintAt, fingerprint + 1);
    } else if (kind == "width") {
      set<std::int32_t>(&bytes, kWidthAt, static_cast<std::int32_t>(number(value)));
    } else if (kind == "vertex_count") {
      set<std::uint64_t>(&bytes, kVertexCountAt,
                         std::strtoull(value.as<std::string>().c_str(), nullptr, 10));
    } else if (kind == "edge_count") {
      set<std::uint64_t>(&bytes, kEdgeCountAt,
                         std::strtoull(value.as<std::string>().c_str(), nullptr, 10));
    } else if (kind == "vertex_value") {
      set<float>(&bytes, kVerticesAt, static_cast<float>(number(value)));
    } else if (kind == "edge_a") {
      set<std::uint32_t>(&bytes, edges_at, static_cast<std::uint32_t>(number(value)));
    } else if (kind == "edge_b") {
      set<std::uint32_t>(&bytes, edges_at + 4, static_cast<std::uint32_t>(number(value)));
    } else if (kind == "edge_length") {
      set<float>(&bytes, edges_at + 8, static_cast<float>(number(value)));
    } else if (kind == "edge_state") {
      set<std::uint8_t>(&bytes, edges_at + 12, static_cast<std::uint8_t>(number(value)));
    } else if (kind == "grow") {
      bytes.insert(bytes.size() - 8, std::string(value.as<std::size_t>(), '\0'));
    } else {
      throw std::runtime_error("unknown roadmap edit '" + kind + "'");
    }
    fix_checksum(&bytes);
  }
  return bytes;
}

}  // namespace gplanner::hostile
