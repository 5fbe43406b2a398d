#pragma once
// Tests that run every SIMD path (simd.h) put the process's path back when they end, however they
// end (a failed ASSERT returns early).

#include "fastron/core/simd.h"

namespace fastron::test {

class SimdPathGuard {
 public:
  SimdPathGuard() : saved_(activeSimdPath()) {}
  ~SimdPathGuard() { useSimdPath(saved_); }
  SimdPathGuard(const SimdPathGuard&) = delete;
  SimdPathGuard& operator=(const SimdPathGuard&) = delete;

 private:
  SimdPath saved_;
};

}  // namespace fastron::test
