#pragma once
// The current version of a checker's world (its obstacles, placed), which many threads read while
// setScene replaces it: a reader holds a shared_ptr to one consistent version for as long as its
// check takes. One lock per read; a batch of checks (checkFirst) reads once.

#include <memory>
#include <mutex>
#include <utility>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

template <class T>
class Snapshot {
 public:
  std::shared_ptr<const T> get() const {
    const std::lock_guard lock(mutex_);
    return value_;
  }

  void set(std::shared_ptr<const T> next) {
    {
      const std::lock_guard lock(mutex_);
      value_.swap(next);
    }  // the old version is released outside the lock (readers may still hold it)
  }

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const T> value_;
};

}  // namespace fastron
