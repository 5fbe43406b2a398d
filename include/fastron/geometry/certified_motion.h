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
#include <cstdint>
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
  /// How many of the first movers of `shape` and of `other` (a self pair's; ClearanceModel::
  /// movers) move the two relative to each other: the pair's speed at a configuration, which
  /// `levers` bound over every configuration.
  std::uint32_t shapeMovers = 0, otherMovers = 0;

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
  /// Per robot shape, its movers relative to the root (shapeMovers with its balls), shared by
  /// every scene's model.
  std::shared_ptr<const std::vector<std::vector<ShapeMover>>> movers;
};

/// A joint's axis in the world at one configuration: through `origin`, along `direction` (unit).
struct JointAxis {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
};

/// What the certificate asks of an exact checker, about the configuration it last placed.
struct ExactPairCheck {
  /// Places the robot at a configuration; writes each robot shape's world pose.
  std::function<void(const double* q, std::vector<Eigen::Isometry3d>& shapePoses)> place;
  /// Writes each joint's axis (robot.joints() order) at the configuration last placed: asked by
  /// a motion's speeds alone (PlacedBalls::speed), not by a state's check.
  std::function<void(std::vector<JointAxis>& jointAxes)> axes;
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

  /// True when a ball inside the pair's robot shape (BallCover::inside) reaches into its
  /// obstacle at the configuration last placed, deeper than the exact checker's tolerance: the
  /// pair touches, as the exact checker would find, without asking it. False for self pairs and
  /// obstacles known only by a volume around them (meshes, clouds).
  bool touchProven(const ClearancePair& pair, const std::vector<EnclosingVolume>& obstacles);

  /// A buffer of pairs for the caller (certifiedStateCheck's pairs left to the exact checker).
  std::vector<const ClearancePair*>& openPairs() { return open_; }

  /// How far one step of `stride` (per configuration coordinate, non-negative) can bring the
  /// pair's shapes closer at the configuration last placed: the sum over the pair's movers of
  /// stride times multiplier times the distance of the shape's enclosing ball from the joint's
  /// axis (1 for a prismatic joint). `movers` are the model's; `exact` is the check that placed
  /// the configuration, asked for the joints' axes once per configuration.
  double speed(const ExactPairCheck& exact, const ClearancePair& pair,
               const std::vector<std::vector<ShapeMover>>& movers,
               const std::vector<double>& stride);

 private:
  struct Shape {
    std::size_t wholeStamp = 0;
    Eigen::Vector3d whole;
    std::size_t stamp = 0;
    BallColumns centres;
    std::vector<std::size_t> childStamp;
    std::vector<BallColumns> children;
    std::size_t speedStamp = 0;
    std::vector<double> speeds;  // sums of the speeds of the first k movers, k = 0..movers
    std::size_t insideStamp = 0;
    BallColumns inside;
  };

  double obstacleBound(const ClearancePair& pair, const EnclosingVolume& obstacle, double floor);
  double selfBound(const ClearancePair& pair, double floor, double wanted);
  double childBound(std::size_t shapeA, std::size_t ballA, std::size_t shapeB, std::size_t ballB);
  const Eigen::Vector3d& wholeCentre(std::size_t shape);
  const BallColumns& centres(std::size_t shape);
  const BallColumns& childCentres(std::size_t shape, std::size_t ball);
  const std::vector<double>& shapeSpeeds(const ExactPairCheck& exact, std::size_t shape,
                                         const std::vector<ShapeMover>& movers,
                                         const std::vector<double>& stride);

  std::shared_ptr<const std::vector<BallCover>> covers_;
  std::vector<Eigen::Isometry3d> poses_;
  std::vector<JointAxis> axes_;
  std::vector<Shape> shapes_;
  std::size_t now_ = 0;
  std::size_t axesStamp_ = 0;  // the placement axes_ are of
  BallColumns near_;           // selfBound's balls of the other shape near the first
  std::vector<std::size_t> nearIndex_;
  std::vector<const ClearancePair*> open_;
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

/// What certifiedMotionCheck keeps from one motion to the next, as a thread's scratch (made for a
/// model's balls, ClearanceModel::balls): the balls placed, the bounds found at the last motion's
/// end (a path's next edge starts there), and the bisection's buffers. Once warm, a check
/// allocates nothing (each motion made its own balls and buffers before). Not safe to share
/// between threads.
struct MotionScratch {
  explicit MotionScratch(std::shared_ptr<const std::vector<BallCover>> covers);
  /// Forgets the last motion's end: the caller's model changed.
  void forgetEnd();

  PlacedBalls balls;
  /// The last motion's end, when it was free, and a lower bound per pair of the model there (0
  /// where none proves it apart); empty `endQ`: none kept.
  std::vector<double> endQ, endBounds;

  // The bisection's buffers, reused by every motion.
  /// States lo < i < hi, between two looked at (rows atLo, atHi of `bounds`), that the pairs
  /// active[activeBegin, activeEnd) are not yet proven apart over.
  struct Stretch {
    std::size_t lo, hi, atLo, atHi, activeBegin, activeEnd;
  };
  std::vector<Stretch> stretches;
  std::vector<std::uint32_t> active;
  /// Per state looked at, a bound per pair, then a speed per pair; `used` rows in use.
  std::vector<std::vector<double>> bounds;
  std::size_t used = 0;
  std::vector<double> q, stride, perStep, perStepGrowth;
  std::vector<std::vector<double>> growth;  ///< per robot shape, summed over its first movers
};

/// Checks the states from + (i / segments) (to - from), i = 1..segments (`to` itself for
/// i = segments), as a dense check would, and answers as it: looks at `to` first, then bisects,
/// proving stretches free pair by pair and asking `exact` only about pairs at states no bound
/// proves apart. `from` is placed for its bounds, never checked, unless the scratch kept them (a
/// start equal to its `endQ`, value for value); the scratch then keeps `to`'s bounds when `to`
/// is free, and nothing when it collides. Every configuration between the two must be one that
/// the levers hold for (prismatic joints within their limits).
CertifiedMotion certifiedMotionCheck(const ClearanceModel& model, const ExactPairCheck& exact,
                                     const double* from, const double* to, std::size_t dim,
                                     std::size_t segments, MotionScratch& scratch);

}  // namespace fastron
