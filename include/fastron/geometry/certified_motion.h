#pragma once
// The exact check of a straight joint motion that skips what clearance proves (Schwarzer, Saha
// and Latombe, "Adaptive dynamic collision checking for single and multiple articulated robots in
// complex environments", T-RO 2005), on the states a dense check would look at: for every pair of
// a robot shape and an obstacle (or of two robot shapes) that must not touch, a lower bound on
// their distance at two checked states, d_a and d_b, proves the pair apart at every state between
// when d_a + d_b exceeds the most that motion can bring them closer (clearance_bounds.h's levers).
// Where no bound proves a pair apart, the exact checker decides it. The answer is the dense
// check's, exactly: only states proven free are skipped.

#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/clearance_bounds.h"

namespace FASTRON_API fastron {

/// A pair that must not touch: a robot shape and an obstacle, or two robot shapes.
struct ClearancePair {
  std::size_t shape = 0;  ///< a robot shape
  std::size_t other = 0;  ///< an obstacle (selfPair false) or a robot shape
  bool selfPair = false;
  /// How fast their distance can shrink, per unit of each configuration coordinate.
  Eigen::VectorXd levers;
  /// ExactPairCheck::distance may be asked about the pair (the checker's distance is cheap for
  /// it: FCL's between primitives, not a mesh's, which cost 20-50 collision checks).
  bool askDistance = false;
};

/// A robot against one scene, as the certificate sees it.
struct ClearanceModel {
  /// Per robot shape, in the shape's frame: the robot's, shared by every scene's model.
  std::shared_ptr<const std::vector<BallCover>> balls;
  std::vector<EnclosingVolume> obstacles;  ///< per obstacle
  std::vector<ClearancePair> pairs;
};

/// What the certificate asks of an exact checker, about the configuration it last placed.
struct ExactPairCheck {
  /// Places the robot at a configuration; writes each robot shape's world pose.
  std::function<void(const double* q, std::vector<Eigen::Isometry3d>& shapePoses)> place;
  /// True when the pair touches at the configuration last placed, as the exact checker decides.
  std::function<bool(const ClearancePair& pair)> touches;
  /// Optional: the pair's exact distance at the configuration last placed. Asked instead of
  /// `touches` about a pair (with askDistance) that no bound keeps apart where a long stretch of
  /// the motion depends on it: a distance above 0.1 mm is the pair's bound there (and the pair is
  /// free); below, `touches` decides.
  std::function<double(const ClearancePair& pair)> distance;
};

/// The answer of certifiedMotionCheck.
struct CertifiedMotion {
  /// A state in collision, i in 1..segments (not necessarily the first), or 0 when none is.
  std::size_t collidingState = 0;
  /// Configurations placed (forward kinematics and the bounds; `from` counts).
  std::size_t statesPlaced = 0;
};

/// Checks the states from + (i / segments) (to - from), i = 1..segments (`to` itself for
/// i = segments), as a dense check would, and answers as it: looks at `to` first, then bisects,
/// proving stretches free pair by pair and asking `exact` only about pairs at states no bound
/// proves apart. `from` is placed for its bounds, never checked. Every configuration between the
/// two must be one that the levers hold for (prismatic joints within their limits).
CertifiedMotion certifiedMotionCheck(const ClearanceModel& model, const ExactPairCheck& exact,
                                     const double* from, const double* to, std::size_t dim,
                                     std::size_t segments);

}  // namespace fastron
