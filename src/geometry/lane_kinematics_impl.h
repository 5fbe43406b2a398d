// The batched positions of control points, written once and compiled once per SimdPath: each
// lane_kinematics_*.cpp defines FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH and includes this
// file with its own -march flags. One configuration per lane, so the frames of a joint are
// computed for a register of configurations at once. (Vector helpers, and why not Eigen:
// core/simd_lanes.h.)
//
// No include guard: included once per translation unit.

#if !defined(FASTRON_SIMD_NAMESPACE) || !defined(FASTRON_SIMD_WIDTH)
#error \
    "define FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH before including lane_kinematics_impl.h"
#endif

#include <cstddef>

#include "internal/simd_lanes.h"
#include "lane_kinematics.h"

namespace fastron::detail {
namespace {

/// A frame per lane: the rotation row by row, then the translation.
struct LaneFrame {
  Floats m[12];
};

/// Positions of up to kWidth configurations, one per lane.
void placeRegister(const LaneChain& c, const double* q, std::size_t count, float* out) {
  LaneFrame frames[kMaxLaneSteps];
  for (std::size_t s = 0; s < c.stepCount; ++s) {
    const LaneStep& step = c.steps[s];
    Floats value = {};  // lanes past `count` turn by 0 and are never written out
    for (std::size_t l = 0; l < count; ++l) {
      value[l] =
          step.scale * static_cast<float>(q[l * c.dof + static_cast<std::size_t>(step.joint)]) +
          step.offset;
    }
    Floats* f = frames[s].m;
    const float* b = step.fixed;
    if (step.parent >= 0) {  // parent (per lane) times the constant transform (broadcast)
      const Floats* a = frames[step.parent].m;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          f[3 * i + j] =
              mulAdd(a[3 * i + 2], b[8 + j], mulAdd(a[3 * i + 1], b[4 + j], a[3 * i] * b[j]));
        }
        f[9 + i] = mulAdd(a[3 * i + 2], b[11],
                          mulAdd(a[3 * i + 1], b[7], mulAdd(a[3 * i], b[3], a[9 + i])));
      }
    } else {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) f[3 * i + j] = splat(b[4 * i + j]);
        f[9 + i] = splat(b[4 * i + 3]);
      }
    }
    if (step.prismatic != 0) {
      for (int i = 0; i < 3; ++i) f[9 + i] = mulAdd(value, f[3 * i + 2], f[9 + i]);
    } else {  // f * Rz(value): only the x and y columns turn
      Floats si, co;
      sinCos(value, si, co);
      for (int i = 0; i < 3; ++i) {
        const Floats x = f[3 * i], y = f[3 * i + 1];
        f[3 * i] = mulAdd(co, x, si * y);
        f[3 * i + 1] = mulAdd(co, y, -(si * x));
      }
    }
  }
  const std::size_t coordinates = 3 * c.pointCount;
  for (std::size_t k = 0; k < c.pointCount; ++k) {
    const LanePoint& p = c.points[k];
    const float* local = p.local;
    for (int i = 0; i < 3; ++i) {
      Floats position;
      if (p.step < 0) {
        position = splat(local[i]);
      } else {
        const Floats* f = frames[p.step].m;
        position =
            f[3 * i] * local[0] + f[3 * i + 1] * local[1] + f[3 * i + 2] * local[2] + f[9 + i];
      }
      for (std::size_t l = 0; l < count; ++l) {
        out[l * coordinates + 3 * k + static_cast<std::size_t>(i)] = position[l];
      }
    }
  }
}

void placeLanes(const LaneChain& c, const double* q, std::size_t count, float* out) {
  for (std::size_t first = 0; first < count; first += kWidth) {
    const std::size_t lanes = count - first < kWidth ? count - first : kWidth;
    placeRegister(c, q + first * c.dof, lanes, out + first * 3 * c.pointCount);
  }
}

}  // namespace

namespace FASTRON_SIMD_NAMESPACE {
const PlaceLanes kPlaceLanes = &placeLanes;
}

}  // namespace fastron::detail
