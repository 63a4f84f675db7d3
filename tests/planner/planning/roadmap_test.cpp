// Roadmaps: edges without duplicates, and files that come back whole for their own
// scene and are refused, with a clear reason, for another scene or when damaged.

#include "gplanner/planner/planning/roadmap.h"
#include "gplanner/planner/output/roadmap_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>

#include "gplanner/planner/scene/input_error.h"
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

// Edges appended in bulk (on the host's threads past 16,384) make the roadmap that adding
// them one by one makes: the same edges in the same order, each vertex's list in index
// order, ends swapped so that a < b.
TEST(Roadmap, AppendedEdgesAreThoseAddedOneByOne) {
  for (const std::size_t count : {std::size_t(50), std::size_t(40000)}) {
    const std::uint32_t n = 3000;
    Roadmap one_by_one(1), bulk(1), single(1);
    for (std::uint32_t v = 0; v < n; ++v) {
      const float q = static_cast<float>(v);
      one_by_one.add_vertex(&q);
      bulk.add_vertex(&q);
      single.add_vertex(&q);
    }
    std::mt19937 rng(static_cast<unsigned>(count));
    std::uniform_int_distribution<std::uint32_t> pick(0, n - 1);
    std::vector<RoadmapEdge> edges;
    one_by_one.add_edge(0, 1, 1.0f);  // one already there: the bulk's indices follow it
    bulk.add_edge(0, 1, 1.0f);
    single.add_edge(0, 1, 1.0f);
    while (edges.size() < count) {
      const std::uint32_t a = pick(rng), b = pick(rng);
      const float length = static_cast<float>(edges.size());
      if (one_by_one.add_edge(a, b, length, EdgeState::kValid) < 0) continue;
      edges.push_back({a, b, length, EdgeState::kValid});
      single.append_edge(a, b, length, EdgeState::kValid);
    }
    EXPECT_EQ(bulk.append_edges(edges.data(), edges.size()), 1u);
    for (const Roadmap* r : {&bulk, &single}) {
      ASSERT_EQ(r->edge_count(), one_by_one.edge_count());
      for (std::size_t e = 0; e < r->edge_count(); ++e) {
        EXPECT_EQ(r->edge(e).a, one_by_one.edge(e).a);
        EXPECT_EQ(r->edge(e).b, one_by_one.edge(e).b);
        EXPECT_LT(r->edge(e).a, r->edge(e).b);
        EXPECT_EQ(r->edge(e).length, one_by_one.edge(e).length);
        EXPECT_EQ(r->edge(e).state, one_by_one.edge(e).state);
      }
      for (std::uint32_t v = 0; v < n; ++v) ASSERT_EQ(r->edges_at(v), one_by_one.edges_at(v));
    }
  }
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
  finer.planner.edge_resolution = 0.005;
  EXPECT_NE(load_error(finer, path).find("build it again"), std::string::npos);
  Scene reweighted = piano;
  reweighted.planner.distance_weights.rotation = 2.0;
  EXPECT_NE(load_error(reweighted, path).find("another scene"), std::string::npos);
  // Settings that do not decide validity leave it usable.
  Scene other_seed = piano;
  other_seed.planner.seed = 99;
  other_seed.planner.roadmap.milestones = 10;
  EXPECT_EQ(load_error(other_seed, path), "");
}

TEST(Roadmap, DamagedFilesAreRefusedNamingTheFile) {
  const Scene scene = load("piano.yaml");
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/piano.roadmap";
  save_roadmap(random_roadmap(scene, 100, 2), scene, path);
  const std::string good = testing::read_file(path);

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

  // The right magic, then garbage (issue 32: it was called another scene's roadmap).
  std::string garbage = good.substr(0, 19);
  for (int i = 0; i < 500; ++i) garbage += static_cast<char>((i * 7919) & 0xff);
  const std::string forged_header = scratch.path() + "/garbage.roadmap";
  write_bytes(forged_header, garbage);
  EXPECT_NE(load_error(scene, forged_header).find(forged_header + ": roadmap file is damaged"),
            std::string::npos)
      << load_error(scene, forged_header);
  EXPECT_EQ(load_error(scene, forged_header).find("another scene"), std::string::npos);

  const std::string text = scratch.write("notes.txt", "hello\n");
  EXPECT_NE(load_error(scene, text).find("not a gplanner roadmap"), std::string::npos);
  EXPECT_NE(load_error(scene, scratch.path() + "/missing").find("does not exist"),
            std::string::npos);
}

// `bytes` (a roadmap file's) with its checksum made right again, as a careful forger
// would.
std::string with_checksum(std::string bytes) {
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a, 64 bit, as roadmap.cpp
  for (std::size_t i = 0; i < bytes.size() - 8; ++i) {
    hash ^= static_cast<unsigned char>(bytes[i]);
    hash *= 1099511628211ull;
  }
  std::memcpy(bytes.data() + bytes.size() - 8, &hash, 8);
  return bytes;
}

constexpr std::size_t kHeaderBytes = 19 + 8 + 4 + 8 + 8;  // magic, fingerprint, width, counts

TEST(Roadmap, ContentWithAValidChecksumIsStillChecked) {
  const Scene scene = load("piano.yaml");
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/piano.roadmap";
  const std::size_t n = 20;
  const Roadmap roadmap = random_roadmap(scene, n, 5);
  save_roadmap(roadmap, scene, path);
  const std::string good = testing::read_file(path);
  ASSERT_EQ(with_checksum(good), good);
  const std::size_t width = scene.space.width();
  const std::size_t first_edge = kHeaderBytes + n * width * sizeof(float);
  auto refused = [&](const std::string& bytes) {
    const std::string forged = scratch.path() + "/forged.roadmap";
    write_bytes(forged, with_checksum(bytes));
    try {
      load_roadmap(scene, forged);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  for (const float length : {std::nanf(""), -1.0f, std::numeric_limits<float>::infinity()}) {
    std::string bytes = good;
    std::memcpy(bytes.data() + first_edge + 8, &length, sizeof(float));
    const std::string message = refused(bytes);
    EXPECT_NE(message.find("edge 0: roadmap file is damaged (its length is"), std::string::npos)
        << message;
  }
  for (const float value : {std::nanf(""), 1e30f}) {
    std::string bytes = good;
    std::memcpy(bytes.data() + kHeaderBytes + width * sizeof(float), &value, sizeof(float));
    const std::string message = refused(bytes);
    EXPECT_NE(message.find("milestone 1: roadmap file is damaged"), std::string::npos) << message;
  }
  // Counts that claim more than the file holds: refused before it is read whole.
  std::string bytes = good;
  const std::uint64_t huge = 4000000000ull;
  std::memcpy(bytes.data() + 19 + 8 + 4, &huge, sizeof(huge));
  EXPECT_NE(refused(bytes).find("do not give its size"), std::string::npos) << refused(bytes);
}

TEST(Roadmap, FileKindsAreNamed) {
  const Scene scene = load("piano.yaml");
  testing::ScratchFolder scratch;
  EXPECT_THROW(load_roadmap(scene, scratch.path()), InputError);
  EXPECT_NE(load_error(scene, scratch.path()).find("is a folder"), std::string::npos);
  EXPECT_NE(load_error(scene, "/dev/null").find("is a device"), std::string::npos);
}

TEST(Roadmap, FailedSaveKeepsTheOldFile) {
  const Scene scene = load("piano.yaml");
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/piano.roadmap";
  save_roadmap(random_roadmap(scene, 30, 3), scene, path);
  const std::string before = testing::read_file(path);
  EXPECT_THROW(save_roadmap(random_roadmap(scene, 30, 4), scene,
                            scratch.path() + "/no/such/folder/x.roadmap"),
               std::runtime_error);
  EXPECT_EQ(testing::read_file(path), before);
}

}  // namespace
}  // namespace gplanner
