#pragma once
// Storage for an array of a trivial type that is not value-initialised: for arrays that
// the host's threads fill entry by entry (placement new), each thread touching its part
// of the memory first. Zeroing it on one thread first cost more than the fill (a page's
// first write costs about 2 us on the H200's host). Shared by GoalDistances' rows and
// the roadmap planner's new edges.

#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>

namespace gplanner::detail {

template <typename T>
struct FreeStorage {
  void operator()(T* p) const { ::operator delete(p); }
};

template <typename T>
using UninitializedArray = std::unique_ptr<T[], FreeStorage<T>>;

// Room for `count` T (at least one), none constructed.
template <typename T>
UninitializedArray<T> uninitialized_array(std::size_t count) {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
  return UninitializedArray<T>(
      static_cast<T*>(::operator new(std::max<std::size_t>(count, 1) * sizeof(T))));
}

}  // namespace gplanner::detail
