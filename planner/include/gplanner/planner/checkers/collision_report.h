#pragma once
// What collides at a configuration, said by FCL in double: the pair of bodies (a link
// and an obstacle, or two checked links) whose surfaces meet (solid primitives as FCL's
// primitives), for messages and for `gplan check --pairs`. Where none meet, a verdict of
// collision rests on containment in a closed body or on the tolerance band, and the
// closest pair is named.

#include <memory>
#include <string>

namespace gplanner {

struct Scene;

struct CollisionPair {
  bool found = false;   // false: no pair collides (and a and b name the closest pair)
  std::string a;        // "link 'NAME'"
  std::string b;        // "obstacle 'NAME' (obstacles[I])" or "link 'NAME'"
  std::string a_key;    // the link's name
  std::string b_key;    // "obstacles[I]" or the link's name
  double distance = 0;  // 0 when found; otherwise the closest pair's distance (metres)

  // "link 'A' and obstacle 'B' (obstacles[2])" or, when none collides, the closest pair
  // and its distance.
  std::string describe() const;
};

// FCL models of every link and of every obstacle on its own, built once; single thread.
class CollisionReporter {
 public:
  // `scene` must outlive the reporter.
  explicit CollisionReporter(const Scene& scene);
  ~CollisionReporter();

  // The first colliding pair at row q (shape: [width]), links against obstacles first,
  // then the checked link pairs; when none collides, the closest pair.
  CollisionPair first_pair(const float* q);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gplanner
