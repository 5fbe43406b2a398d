#pragma once
// The exact check of a straight joint motion that skips what clearance proves (Schwarzer, Saha
// and Latombe, "Adaptive dynamic collision checking for single and multiple articulated robots in
// complex environments", T-RO 2005), on the states a dense check would look at: for every pair of
// a robot shape and an obstacle (or of two robot shapes) that must not touch, a lower bound on
// their distance at two checked states, d_a and d_b, proves the pair apart at every state between
// when d_a + d_b exceeds the most that motion can bring them closer (clearance_bounds.h's levers).
// Where no bound proves a pair apart, the exact checker decides it. The answer is the dense
// check's, exactly: only states proven free are skipped. The same bounds decide most pairs of a
// single configuration's check (certifiedStateCheck).

#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/clearance_bounds.h"
#include "fastron/geometry/self_pair_table.h"

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
  /// A self pair's table of distances (held by ClearanceModel::selfTables), or null: its bound
  /// is read before the balls'.
  const SelfPairTable* table = nullptr;

  /// The bound of the pair's table at q (the caller takes its margin off), or -infinity when it
  /// has none.
  double tableBound(const double* q) const {
    return table ? table->lowerBound(q) : -std::numeric_limits<double>::infinity();
  }
};

/// A robot against one scene, as the certificate sees it.
struct ClearanceModel {
  /// Per robot shape, in the shape's frame: the robot's, shared by every scene's model.
  std::shared_ptr<const std::vector<BallCover>> balls;
  std::vector<EnclosingVolume> obstacles;  ///< per obstacle
  std::vector<ClearancePair> pairs;
  /// The robot's self-pair tables (CheckerOptions::selfPairTables or selfPairSlack) that pairs
  /// point to, shared by every scene's model; null for none.
  std::shared_ptr<const std::vector<SelfPairTable>> selfTables;
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

/// The robot's balls placed in the world at one configuration, each shape's (and each ball's
/// children) placed on first use, as columns, and the lower bounds on a pair's distance that they
/// give. Kept from one configuration to the next, as a thread's scratch: once every shape has been
/// placed it allocates nothing. Not safe to share between threads.
class PlacedBalls {
 public:
  /// For the robot's covers (ClearanceModel::balls, one per robot shape).
  explicit PlacedBalls(std::shared_ptr<const std::vector<BallCover>> covers);

  /// Places the robot at q (exact.place); the balls follow on first use.
  void place(const ExactPairCheck& exact, const double* q);

  /// A lower bound on the pair's distance at the configuration last placed: from the shapes'
  /// enclosing balls when that keeps them apart, else from their balls (and the children of
  /// balls that overlap), the larger of the valid bounds. `obstacles` are the scene's, as the
  /// pair indexes them.
  double lowerBound(const ClearancePair& pair, const std::vector<EnclosingVolume>& obstacles);

 private:
  struct Shape {
    std::size_t wholeStamp = 0;
    Eigen::Vector3d whole;
    std::size_t stamp = 0;
    BallColumns centres;
    std::vector<std::size_t> childStamp;
    std::vector<BallColumns> children;
  };

  double obstacleBound(const ClearancePair& pair, const EnclosingVolume& obstacle, double floor);
  double selfBound(const ClearancePair& pair, double floor, double wanted);
  double childBound(std::size_t shapeA, std::size_t ballA, std::size_t shapeB, std::size_t ballB);
  const Eigen::Vector3d& wholeCentre(std::size_t shape);
  const BallColumns& centres(std::size_t shape);
  const BallColumns& childCentres(std::size_t shape, std::size_t ball);

  std::shared_ptr<const std::vector<BallCover>> covers_;
  std::vector<Eigen::Isometry3d> poses_;
  std::vector<Shape> shapes_;
  std::size_t now_ = 0;
  BallColumns near_;  // selfBound's balls of the other shape near the first
  std::vector<std::size_t> nearIndex_;
};

/// True when a pair of `model` touches at q, as a check of every pair with `exact` decides, that
/// asks `exact` only about the pairs no bound keeps apart. `balls` is the caller's scratch, made
/// for model.balls.
bool certifiedStateCheck(const ClearanceModel& model, const ExactPairCheck& exact,
                         PlacedBalls& balls, const double* q);

/// The answer of certifiedMotionCheck.
struct CertifiedMotion {
  /// A state in collision, i in 1..segments (not necessarily the first), or 0 when none is.
  std::size_t collidingState = 0;
  /// Configurations placed (forward kinematics and the bounds; `from` counts).
  std::size_t statesPlaced = 0;
};

/// The bounds a motion check found at its end, kept by the caller for the next motion that starts
/// there (a path's next edge): certifiedMotionCheck reads them instead of placing that start
/// again, and writes its own end's. Valid for one ClearanceModel: the caller empties `q` when
/// the model changes.
struct MotionEndBounds {
  std::vector<double> q;       ///< the end; empty: none kept
  std::vector<double> bounds;  ///< per pair of the model: a lower bound on its distance, or 0
};

/// Checks the states from + (i / segments) (to - from), i = 1..segments (`to` itself for
/// i = segments), as a dense check would, and answers as it: looks at `to` first, then bisects,
/// proving stretches free pair by pair and asking `exact` only about pairs at states no bound
/// proves apart. `from` is placed for its bounds, never checked (unless `carried` holds them: a
/// start equal to its `q`, value for value); `carried`, when given, then keeps `to`'s bounds when
/// `to` is free, and nothing when it collides. Every configuration between the two must be one
/// that the levers hold for (prismatic joints within their limits).
CertifiedMotion certifiedMotionCheck(const ClearanceModel& model, const ExactPairCheck& exact,
                                     const double* from, const double* to, std::size_t dim,
                                     std::size_t segments, MotionEndBounds* carried = nullptr);

}  // namespace fastron
