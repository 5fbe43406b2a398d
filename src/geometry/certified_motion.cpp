#include "fastron/geometry/certified_motion.h"

#include <algorithm>
#include <deque>
#include <limits>
#include <memory>
#include <numeric>
#include <utility>

#include "fastron/core/motion_states.h"

namespace fastron {
namespace {

/// Taken off every lower bound, so that rounding (of the states, of the poses) and the exact
/// checker's own tolerance cannot turn a touch into a proof: 10 micrometres.
constexpr double kMargin = 1e-5;
/// An exact distance is asked for where the stretch a state bounds is at least this many steps
/// long: it costs several collision checks, and pays only where it proves many states free.
constexpr double kDistanceSteps = 4;
/// An exact distance below this leaves the verdict to the collision check (FCL's distance and
/// collision tolerances differ at contact).
constexpr double kDistanceFloor = 1e-4;

Eigen::Vector3d centre(const BallColumns& columns, std::size_t i) {
  return {columns.x[i], columns.y[i], columns.z[i]};
}

}  // namespace

PlacedBalls::PlacedBalls(std::shared_ptr<const std::vector<BallCover>> covers)
    : covers_(std::move(covers)), poses_(covers_->size()), shapes_(covers_->size()) {
  for (std::size_t s = 0; s < shapes_.size(); ++s) {
    shapes_[s].children.resize((*covers_)[s].children.size());
    shapes_[s].childStamp.assign((*covers_)[s].children.size(), 0);
  }
}

void PlacedBalls::place(const ExactPairCheck& exact, const double* q) {
  exact.place(q, poses_);
  ++now_;
}

double PlacedBalls::lowerBound(const ClearancePair& pair,
                               const std::vector<EnclosingVolume>& obstacles) {
  // The finer bound only where the coarse one proves nothing: finer bounds that would prove a
  // pair apart over more steps of a motion cost more than the looks they saved (the mesh Panda's
  // paths verified 1.2 times faster without them, with 24% more looks;
  // docs/log/2026-12-01-cheap-looks-and-shared-ends.md).
  const double wanted = kMargin;
  const std::vector<BallCover>& covers = *covers_;
  const double radius = covers[pair.shape].whole.radius;
  const Eigen::Vector3d& whole = wholeCentre(pair.shape);
  const double coarse = pair.selfPair ? (whole - wholeCentre(pair.other)).norm() - radius -
                                            covers[pair.other].whole.radius
                                      : obstacles[pair.other].distanceFrom(whole) - radius;
  if (coarse > wanted) return coarse;
  // The finer bound matters only above the coarse one (and above 0): its search stops once it is
  // no higher.
  const double floor = std::max(coarse, 0.0);
  return std::max(coarse, pair.selfPair ? selfBound(pair, floor, wanted)
                                        : obstacleBound(pair, obstacles[pair.other], floor));
}

/// The smallest bound over the shape's balls (a ball that meets the volume: the larger of its own
/// and its children's), or the first at most `floor`.
double PlacedBalls::obstacleBound(const ClearancePair& pair, const EnclosingVolume& obstacle,
                                  double floor) {
  const BallColumns& at = centres(pair.shape);
  const double best = obstacle.smallestGap(at);
  if (best > 0 || (*covers_)[pair.shape].children.empty()) return best;
  double finer = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < at.size(); ++b) {
    double bound = obstacle.distanceFrom(centre(at, b)) - at.radius[b];
    if (bound <= 0) bound = std::max(bound, obstacle.smallestGap(childCentres(pair.shape, b)));
    finer = std::min(finer, bound);
    if (finer <= floor) return finer;
  }
  return finer;
}

/// The smallest bound over pairs of the shapes' balls (their children where they overlap), or the
/// first at most `floor`. A ball farther than `wanted` from the other shape's enclosing ball keeps
/// that bound, precise enough: only the balls near the other shape are paired (all pairs of two
/// 12-ball covers were most of the certificate's time on robots of primitives).
double PlacedBalls::selfBound(const ClearancePair& pair, double floor, double wanted) {
  const std::vector<BallCover>& covers = *covers_;
  const BallColumns& at = centres(pair.shape);
  const BallColumns& otherAt = centres(pair.other);
  const Eigen::Vector3d& wholeAt = wholeCentre(pair.shape);
  const Eigen::Vector3d& otherWholeAt = wholeCentre(pair.other);
  const double wholeRadius = covers[pair.shape].whole.radius;
  const double otherWholeRadius = covers[pair.other].whole.radius;
  double best = std::numeric_limits<double>::infinity();
  near_.clear();
  nearIndex_.clear();
  for (std::size_t o = 0; o < otherAt.size(); ++o) {
    const Eigen::Vector3d c = centre(otherAt, o);
    const double gap = (c - wholeAt).norm() - otherAt.radius[o] - wholeRadius;
    if (gap > wanted) {
      best = std::min(best, gap);
    } else {
      near_.push(c, otherAt.radius[o]);
      nearIndex_.push_back(o);
    }
  }
  if (near_.size() == 0) return best;
  const bool children =
      !covers[pair.shape].children.empty() || !covers[pair.other].children.empty();
  for (std::size_t b = 0; b < at.size(); ++b) {
    const Eigen::Vector3d c = centre(at, b);
    double bound = (c - otherWholeAt).norm() - at.radius[b] - otherWholeRadius;
    if (bound <= wanted) bound = smallestGap(near_, c, at.radius[b]);
    if (bound <= 0 && children) {
      // Ball by ball, the children of each pair that overlaps.
      bound = std::numeric_limits<double>::infinity();
      for (std::size_t n = 0; n < near_.size(); ++n) {
        const std::size_t o = nearIndex_[n];
        double pairBound = (c - centre(otherAt, o)).norm() - at.radius[b] - otherAt.radius[o];
        if (pairBound <= 0)
          pairBound = std::max(pairBound, childBound(pair.shape, b, pair.other, o));
        bound = std::min(bound, pairBound);
        if (bound <= floor) break;
      }
    }
    best = std::min(best, bound);
    if (best <= floor) return best;
  }
  return best;
}

/// The bound between two overlapping balls from their children (the ball itself for a shape
/// without children; one of the two has them).
double PlacedBalls::childBound(std::size_t shapeA, std::size_t ballA, std::size_t shapeB,
                               std::size_t ballB) {
  const std::vector<BallCover>& covers = *covers_;
  const bool aSplits = !covers[shapeA].children.empty();
  const bool bSplits = !covers[shapeB].children.empty();
  if (!aSplits) {
    const BallColumns& a = centres(shapeA);
    return smallestGap(childCentres(shapeB, ballB), centre(a, ballA), a.radius[ballA]);
  }
  const BallColumns& a = childCentres(shapeA, ballA);
  const BallColumns& other = bSplits ? childCentres(shapeB, ballB) : centres(shapeB);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (bSplits) {
      best = std::min(best, smallestGap(other, centre(a, i), a.radius[i]));
    } else {
      best = std::min(
          best, (centre(a, i) - centre(other, ballB)).norm() - a.radius[i] - other.radius[ballB]);
    }
  }
  return best;
}

const Eigen::Vector3d& PlacedBalls::wholeCentre(std::size_t shape) {
  Shape& s = shapes_[shape];
  if (s.wholeStamp != now_) {
    s.whole = poses_[shape] * (*covers_)[shape].whole.centre;
    s.wholeStamp = now_;
  }
  return s.whole;
}

const BallColumns& PlacedBalls::centres(std::size_t shape) {
  Shape& s = shapes_[shape];
  if (s.stamp != now_) {
    s.centres.place(poses_[shape], (*covers_)[shape].balls);
    s.stamp = now_;
  }
  return s.centres;
}

const BallColumns& PlacedBalls::childCentres(std::size_t shape, std::size_t ball) {
  Shape& s = shapes_[shape];
  if (s.childStamp[ball] != now_) {
    s.children[ball].place(poses_[shape], (*covers_)[shape].children[ball]);
    s.childStamp[ball] = now_;
  }
  return s.children[ball];
}

bool certifiedStateCheck(const ClearanceModel& model, const ExactPairCheck& exact,
                         PlacedBalls& balls, const double* q) {
  balls.place(exact, q);
  for (const ClearancePair& pair : model.pairs) {
    if (pair.tableBound(q) - kMargin > 0) continue;
    if (balls.lowerBound(pair, model.obstacles) - kMargin > 0) continue;
    if (exact.touches(pair)) return true;
  }
  return false;
}

namespace {

using Bounds = std::shared_ptr<const std::vector<double>>;  // per pair, at one checked state

/// States lo < i < hi, between two checked ones, that the pairs in `active` are not yet proven
/// apart over.
struct Stretch {
  std::size_t lo, hi;
  Bounds atLo, atHi;
  std::vector<std::uint32_t> active;
};

/// The looks of one motion at its states: each places the robot at a state, bounds the pairs
/// still open and, when told to decide, asks the exact checker about the pairs no bound keeps
/// apart.
class MotionLooks {
 public:
  MotionLooks(const ClearanceModel& model, const ExactPairCheck& exact, const double* from,
              const double* to, std::size_t dim, std::size_t segments, std::size_t& placed)
      : model_(model),
        exact_(exact),
        from_(from),
        to_(to),
        dim_(dim),
        segments_(segments),
        balls_(model.balls),
        q_(dim),
        perStep_(model.pairs.size()),
        placed_(placed) {
    Eigen::VectorXd stride(static_cast<Eigen::Index>(dim));
    for (std::size_t j = 0; j < dim; ++j)
      stride[static_cast<Eigen::Index>(j)] =
          std::abs(to[j] - from[j]) / static_cast<double>(segments);
    for (std::size_t p = 0; p < perStep_.size(); ++p)
      perStep_[p] = model.pairs[p].levers.dot(stride);
  }

  /// How much one step of the motion can bring pair p closer.
  double perStep(std::size_t p) const { return perStep_[p]; }

  /// Places state i; writes each active pair's bound (0 where none proves it apart); with
  /// `decide`, asks the exact checker about those pairs and returns true at a contact. `steps`:
  /// how many steps of the motion the state's bounds are to cover, where an exact distance pays.
  /// A pair without a bound at both ends of the stretch (`close`) goes to the exact checker
  /// without one: its bound was not positive there, and a bound costs as much as the check on
  /// the mesh Panda's pairs that sit millimetres apart.
  template <class Close>
  bool look(std::size_t i, const std::vector<std::uint32_t>& active, std::vector<double>& bounds,
            bool decide, double steps, const Close& close) {
    motionState(from_, to_, dim_, i, segments_, q_.data());
    balls_.place(exact_, q_.data());
    ++placed_;
    for (const std::uint32_t p : active) {
      const ClearancePair& pair = model_.pairs[p];
      // A table's bound is a lookup: read it first, and the balls' only where it proves nothing.
      double bound = pair.tableBound(q_.data()) - kMargin;
      if (!(bound > 0)) bound = close(p) ? 0 : balls_.lowerBound(pair, model_.obstacles) - kMargin;
      bounds[p] = bound > 0 ? bound : 0;
      if (bound > 0) continue;
      if (pair.askDistance && exact_.distance && steps >= kDistanceSteps) {
        const double distance = exact_.distance(pair);
        if (distance > kDistanceFloor) {
          bounds[p] = distance - kMargin;
          continue;
        }
      }
      if (decide && exact_.touches(pair)) return true;
    }
    return false;
  }

 private:
  const ClearanceModel& model_;
  const ExactPairCheck& exact_;
  const double *from_, *to_;
  std::size_t dim_, segments_;
  PlacedBalls balls_;
  std::vector<double> q_;
  std::vector<double> perStep_;
  std::size_t& placed_;  // the states placed, counted into the caller's answer
};

}  // namespace

CertifiedMotion certifiedMotionCheck(const ClearanceModel& model, const ExactPairCheck& exact,
                                     const double* from, const double* to, std::size_t dim,
                                     std::size_t segments, MotionEndBounds* carried) {
  CertifiedMotion answer;
  if (segments == 0) return answer;
  // The start's bounds, when the last motion ended here (a path's edges share their waypoints).
  Bounds known;
  if (carried != nullptr) {
    if (carried->q.size() == dim && carried->bounds.size() == model.pairs.size() &&
        std::equal(from, from + dim, carried->q.begin())) {
      known = std::make_shared<const std::vector<double>>(std::move(carried->bounds));
    }
    carried->q.clear();
  }
  const std::size_t pairs = model.pairs.size();
  MotionLooks looks(model, exact, from, to, dim, segments, answer.statesPlaced);
  const auto never = [](std::uint32_t) { return false; };
  const double all = static_cast<double>(segments);

  std::vector<std::uint32_t> every(pairs);
  std::iota(every.begin(), every.end(), 0U);
  auto atTo = std::make_shared<std::vector<double>>(pairs, 0.0);
  if (looks.look(segments, every, *atTo, true, all, never)) {  // into an obstacle: found at once
    answer.collidingState = segments;
    return answer;
  }
  if (carried != nullptr) {
    carried->q.assign(to, to + dim);
    carried->bounds = *atTo;
  }
  if (segments == 1) return answer;
  // The midpoint next, before `from` is placed for its bounds: a motion that collides (most of a
  // planner's extensions) is found after the looks of the dense check's order, and pays for
  // `from` only when it survives them.
  const std::size_t half = segments / 2;
  auto atHalf = std::make_shared<std::vector<double>>(pairs, 0.0);
  if (looks.look(half, every, *atHalf, true, all / 2, never)) {
    answer.collidingState = half;
    return answer;
  }
  Bounds atFrom = known;
  if (!atFrom) {
    auto placed = std::make_shared<std::vector<double>>(pairs, 0.0);
    looks.look(0, every, *placed, false, all / 2, never);
    atFrom = std::move(placed);
  }

  // Breadth first, as the dense check's bisection order: a collision anywhere on the motion is met
  // after a few looks (depth first walked the first half's every unproven state before the
  // second half's midpoint, and doubled the looks of RRT-Connect's mostly colliding extensions).
  std::deque<Stretch> queue;
  queue.push_back({0, half, atFrom, atHalf, every});
  queue.push_back({half, segments, atHalf, atTo, std::move(every)});
  while (!queue.empty()) {
    Stretch s = std::move(queue.front());
    queue.pop_front();
    if (s.hi - s.lo < 2) continue;
    std::vector<std::uint32_t> open;
    const double steps = static_cast<double>(s.hi - s.lo);
    for (const std::uint32_t p : s.active) {
      if (!((*s.atLo)[p] + (*s.atHi)[p] > steps * looks.perStep(p))) open.push_back(p);
    }
    if (open.empty()) continue;
    const std::size_t mid = s.lo + (s.hi - s.lo) / 2;
    auto atMid = std::make_shared<std::vector<double>>(pairs, 0.0);
    const auto closeAtBothEnds = [&](std::uint32_t p) {
      return (*s.atLo)[p] == 0 && (*s.atHi)[p] == 0;
    };
    if (looks.look(mid, open, *atMid, true, steps / 2, closeAtBothEnds)) {
      answer.collidingState = mid;
      return answer;
    }
    queue.push_back({s.lo, mid, s.atLo, atMid, open});
    queue.push_back({mid, s.hi, atMid, s.atHi, std::move(open)});
  }
  return answer;
}

}  // namespace fastron
