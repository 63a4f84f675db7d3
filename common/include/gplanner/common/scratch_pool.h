#pragma once
// Scratch objects for calls that may run on many threads at once: a call takes one for
// as long as it needs it, a free one or, when none is free, a new one, and gives it back
// when its lease ends. Only the free list is under a lock, held for a push or a pop, so
// calls using their scratch run in parallel. The pool grows to the most leases ever held
// at once and keeps what it made until it dies.

#include <functional>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace gplanner {

template <typename T>
class ScratchPool {
 public:
  // make: a new scratch object, called without the lock held.
  explicit ScratchPool(std::function<std::unique_ptr<T>()> make) : make_(std::move(make)) {}
  ScratchPool(const ScratchPool&) = delete;
  ScratchPool& operator=(const ScratchPool&) = delete;

  class Lease {
   public:
    Lease(ScratchPool* pool, std::unique_ptr<T> object) : pool_(pool), object_(std::move(object)) {}
    Lease(Lease&&) = default;
    Lease& operator=(Lease&&) = delete;
    ~Lease() {
      if (object_) pool_->give_back(std::move(object_));
    }
    T& operator*() const { return *object_; }
    T* operator->() const { return object_.get(); }

   private:
    ScratchPool* pool_;
    std::unique_ptr<T> object_;
  };

  Lease take() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!free_.empty()) {
        std::unique_ptr<T> object = std::move(free_.back());
        free_.pop_back();
        return Lease(this, std::move(object));
      }
    }
    return Lease(this, make_());
  }

 private:
  void give_back(std::unique_ptr<T> object) {
    const std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(object));
  }

  std::function<std::unique_ptr<T>()> make_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<T>> free_;
};

}  // namespace gplanner
