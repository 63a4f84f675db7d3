// Roadmaps: edges without duplicates, and files that come back whole for their own
// scene and are refused, with a clear reason, for another scene or when damaged.

#include "gplanner/planner/planning/roadmap.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <random>

#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

Scene load(const std::string& name) {
  return load_scene(testing::project_root() + "/scenes/" + name);
}

Roadmap random_roadmap(const Scene& scene, std::size_t n, unsigned seed) {
  Roadmap roadmap(scene.space.width());
  const std::vector<float> q = testing::sample_configurations(scene, n, seed);
  for (std::size_t i = 0; i < n; ++i) roadmap.add_vertex(&q[i * scene.space.width()]);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> pick(0, n - 1);
  for (std::size_t e = 0; e < 3 * n; ++e) {
    roadmap.add_edge(pick(rng), pick(rng), static_cast<float>(e) * 0.5f,
                     static_cast<EdgeState>(e % 3));
  }
  return roadmap;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string load_error(const Scene& scene, const std::string& path) {
  try {
    load_roadmap(scene, path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(Roadmap, AddsEachEdgeOnceEitherWayRound) {
  Roadmap roadmap(2);
  const float a[] = {0, 0}, b[] = {1, 0}, c[] = {0, 1};
  roadmap.add_vertex(a);
  roadmap.add_vertex(b);
  roadmap.add_vertex(c);
  EXPECT_EQ(roadmap.add_edge(0, 1, 1.0f), 0);
  EXPECT_EQ(roadmap.add_edge(1, 0, 1.0f), -1);
  EXPECT_EQ(roadmap.add_edge(2, 2, 0.0f), -1);
  EXPECT_EQ(roadmap.add_edge(2, 1, 1.4f), 1);
  EXPECT_EQ(roadmap.edge_count(), 2u);
  EXPECT_EQ(roadmap.find_edge(0, 1), 0);
  EXPECT_EQ(roadmap.find_edge(1, 2), 1);
  EXPECT_EQ(roadmap.find_edge(0, 2), -1);
  EXPECT_EQ(roadmap.edge(1).a, 1u);
  EXPECT_EQ(roadmap.edge(1).b, 2u);
  EXPECT_EQ(roadmap.edges_at(1).size(), 2u);
}

TEST(Roadmap, SavedAndLoadedWhole) {
  const Scene scene = load("piano.yaml");
  const Roadmap saved = random_roadmap(scene, 500, 4);
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/piano.roadmap";
  save_roadmap(saved, scene, path);
  const Roadmap loaded = load_roadmap(scene, path);
  EXPECT_EQ(loaded.vertices(), saved.vertices());
  ASSERT_EQ(loaded.edge_count(), saved.edge_count());
  for (std::size_t e = 0; e < saved.edge_count(); ++e) {
    EXPECT_EQ(loaded.edge(e).a, saved.edge(e).a);
    EXPECT_EQ(loaded.edge(e).b, saved.edge(e).b);
    EXPECT_EQ(loaded.edge(e).length, saved.edge(e).length);
    EXPECT_EQ(loaded.edge(e).state, saved.edge(e).state);
  }
}

TEST(Roadmap, RefusedForAnotherSceneOrOtherSettings) {
  const Scene piano = load("piano.yaml");
  const Scene detailed = load("piano_detailed.yaml");  // same robot and bounds, more furniture
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/piano.roadmap";
  save_roadmap(random_roadmap(piano, 50, 1), piano, path);
  EXPECT_NE(load_error(detailed, path).find("belongs to another scene"), std::string::npos)
      << load_error(detailed, path);
  Scene finer = piano;
  finer.planner.numbers["edge_resolution"] = 0.005;
  EXPECT_NE(load_error(finer, path).find("build it again"), std::string::npos);
  Scene reweighted = piano;
  reweighted.planner.numbers["distance_weights.rotation"] = 2.0;
  EXPECT_NE(load_error(reweighted, path).find("another scene"), std::string::npos);
  // Settings that do not decide validity leave it usable.
  Scene other_seed = piano;
  other_seed.planner.numbers["seed"] = 99;
  other_seed.planner.numbers["roadmap.milestones"] = 10;
  EXPECT_EQ(load_error(other_seed, path), "");
}

TEST(Roadmap, DamagedFilesAreRefusedNamingTheFile) {
  const Scene scene = load("piano.yaml");
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/piano.roadmap";
  save_roadmap(random_roadmap(scene, 100, 2), scene, path);
  const std::string good = read_bytes(path);

  const std::string truncated = scratch.path() + "/truncated.roadmap";
  write_bytes(truncated, good.substr(0, good.size() / 2));
  EXPECT_NE(load_error(scene, truncated).find(truncated + ": roadmap file is damaged"),
            std::string::npos)
      << load_error(scene, truncated);

  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  const std::string corrupt = scratch.path() + "/corrupt.roadmap";
  write_bytes(corrupt, flipped);
  EXPECT_NE(load_error(scene, corrupt).find("damaged"), std::string::npos)
      << load_error(scene, corrupt);

  const std::string text = scratch.write("notes.txt", "hello\n");
  EXPECT_NE(load_error(scene, text).find("not a gplanner roadmap"), std::string::npos);
  EXPECT_NE(load_error(scene, scratch.path() + "/missing").find("cannot open"), std::string::npos);
}

TEST(Roadmap, FailedSaveKeepsTheOldFile) {
  const Scene scene = load("piano.yaml");
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/piano.roadmap";
  save_roadmap(random_roadmap(scene, 30, 3), scene, path);
  const std::string before = read_bytes(path);
  EXPECT_THROW(save_roadmap(random_roadmap(scene, 30, 4), scene,
                            scratch.path() + "/no/such/folder/x.roadmap"),
               std::runtime_error);
  EXPECT_EQ(read_bytes(path), before);
}

}  // namespace
}  // namespace gplanner
