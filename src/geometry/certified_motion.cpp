#include "fastron/geometry/certified_motion.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <span>
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
/// A ball inside a robot shape that reaches this far into an obstacle proves the pair touching:
/// far beyond the exact checker's tolerance (1e-6 for FCL's GJK), so that it cannot find
/// them apart: 0.1 mm.
constexpr double kTouchDepth = 1e-4;

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

double PlacedBalls::speed(const ExactPairCheck& exact, const ClearancePair& pair,
                          const std::vector<std::vector<ShapeMover>>& movers,
                          const std::vector<double>& stride) {
  double sum = shapeSpeeds(exact, pair.shape, movers[pair.shape], stride)[pair.shapeMovers];
  if (pair.selfPair)
    sum += shapeSpeeds(exact, pair.other, movers[pair.other], stride)[pair.otherMovers];
  return sum;
}

/// Per k, the summed speed of the shape's first k movers: a joint moves the shape's enclosing
/// ball's points at most by their distance from its axis per unit (revolute), or by 1
/// (prismatic), times its multiplier.
const std::vector<double>& PlacedBalls::shapeSpeeds(const ExactPairCheck& exact, std::size_t shape,
                                                    const std::vector<ShapeMover>& movers,
                                                    const std::vector<double>& stride) {
  Shape& s = shapes_[shape];
  if (s.speedStamp == now_) return s.speeds;
  if (axesStamp_ != now_) {
    exact.axes(axes_);
    axesStamp_ = now_;
  }
  const Eigen::Vector3d& centre = wholeCentre(shape);
  const double radius = (*covers_)[shape].whole.radius;
  s.speeds.resize(movers.size() + 1);
  s.speeds[0] = 0;
  for (std::size_t m = 0; m < movers.size(); ++m) {
    const ShapeMover& mover = movers[m];
    double arm = 1;
    if (!mover.prismatic) {
      const JointAxis& axis = axes_[static_cast<std::size_t>(mover.joint)];
      const Eigen::Vector3d away = centre - axis.origin;
      arm = (away - away.dot(axis.direction) * axis.direction).norm() + radius;
    }
    s.speeds[m + 1] = s.speeds[m] + stride[mover.coordinate] * mover.multiplier * arm;
  }
  s.speedStamp = now_;
  return s.speeds;
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

bool PlacedBalls::touchProven(const ClearancePair& pair,
                              const std::vector<EnclosingVolume>& obstacles) {
  if (pair.selfPair) return false;
  Shape& s = shapes_[pair.shape];
  if (s.insideStamp != now_) {
    s.inside.place(poses_[pair.shape], (*covers_)[pair.shape].inside);
    s.insideStamp = now_;
  }
  return obstacles[pair.other].reachedBy(s.inside, kTouchDepth);
}

bool certifiedStateCheck(const ClearanceModel& model, const ExactPairCheck& exact,
                         PlacedBalls& balls, const double* q) {
  balls.place(exact, q);
  // Every pair's bounds and proofs of a touch first, then the exact checker on the pairs left
  // open: a colliding state asked FCL about the near pairs before the touching one.
  std::vector<const ClearancePair*>& open = balls.openPairs();
  open.clear();
  for (const ClearancePair& pair : model.pairs) {
    if (pair.tableBound(q) - kMargin > 0) continue;
    if (balls.lowerBound(pair, model.obstacles) - kMargin > 0) continue;
    if (balls.touchProven(pair, model.obstacles)) return true;
    open.push_back(&pair);
  }
  return std::ranges::any_of(open, [&](const ClearancePair* pair) { return exact.touches(*pair); });
}

MotionScratch::MotionScratch(std::shared_ptr<const std::vector<BallCover>> covers)
    : balls(std::move(covers)) {}

void MotionScratch::forgetEnd() {
  endQ.clear();
}

namespace {

/// The looks of one motion at its states: each places the robot at a state, bounds the pairs
/// still open and, when told to decide, asks the exact checker about the pairs no bound keeps
/// apart. Its buffers are the scratch's.
class MotionLooks {
 public:
  MotionLooks(const ClearanceModel& model, const ExactPairCheck& exact, MotionScratch& scratch,
              const double* from, const double* to, std::size_t dim, std::size_t segments,
              std::size_t& placed)
      : model_(model),
        exact_(exact),
        scratch_(scratch),
        from_(from),
        to_(to),
        dim_(dim),
        segments_(segments),
        placed_(placed) {
    scratch.q.resize(dim);
    scratch.stride.resize(dim);
    for (std::size_t j = 0; j < dim; ++j)
      scratch.stride[j] = std::abs(to[j] - from[j]) / static_cast<double>(segments);
    const Eigen::Map<const Eigen::VectorXd> stride(scratch.stride.data(),
                                                   static_cast<Eigen::Index>(dim));
    // Per shape, the summed growth of its first k movers' speeds per step (their levers' growth
    // times their stride), as shapeSpeeds sums the speeds.
    const std::vector<std::vector<ShapeMover>>& movers = *model.movers;
    scratch.growth.resize(movers.size());
    for (std::size_t shape = 0; shape < movers.size(); ++shape) {
      std::vector<double>& sums = scratch.growth[shape];
      sums.resize(movers[shape].size() + 1);
      sums[0] = 0;
      for (std::size_t m = 0; m < movers[shape].size(); ++m) {
        const ShapeMover& mover = movers[shape][m];
        sums[m + 1] = sums[m] + (mover.prismatic ? 0.0
                                                 : scratch.stride[mover.coordinate] *
                                                       mover.multiplier * mover.growth.dot(stride));
      }
    }
    scratch.perStep.resize(model.pairs.size());
    scratch.perStepGrowth.resize(model.pairs.size());
    for (std::size_t p = 0; p < model.pairs.size(); ++p) {
      const ClearancePair& pair = model.pairs[p];
      scratch.perStep[p] = pair.levers.dot(stride);
      scratch.perStepGrowth[p] =
          scratch.growth[pair.shape][pair.shapeMovers] +
          (pair.selfPair ? scratch.growth[pair.other][pair.otherMovers] : 0.0);
    }
    scratch.used = 0;
  }

  /// How much one step of the motion can bring pair p closer, anywhere on the motion (its
  /// levers).
  double perStep(std::size_t p) const { return scratch_.perStep[p]; }

  /// How much one step can bring pair p closer within `steps` steps of a state where its speed
  /// (PlacedBalls::speed) is `speed`: the speed grows by at most perStepGrowth a step.
  double perStepNear(std::size_t p, double speed, double steps) const {
    return std::min(scratch_.perStep[p], speed + steps * scratch_.perStepGrowth[p]);
  }

  /// A new row: a bound per pair (0), then a speed per pair (infinite: not known), kept until
  /// the next motion; its index.
  std::size_t newBounds() {
    if (scratch_.used == scratch_.bounds.size()) scratch_.bounds.emplace_back();
    std::vector<double>& row = scratch_.bounds[scratch_.used];
    row.assign(2 * model_.pairs.size(), 0.0);
    std::fill(row.begin() + static_cast<std::ptrdiff_t>(model_.pairs.size()), row.end(),
              std::numeric_limits<double>::infinity());
    return scratch_.used++;
  }
  std::vector<double>& bounds(std::size_t row) { return scratch_.bounds[row]; }

  /// Places state i; writes each active pair's bound into row `row` (0 where none proves it
  /// apart); with `decide`, asks the exact checker about those pairs and returns true at a
  /// contact. `steps`: how many steps of the motion the state's bounds are to cover, where an
  /// exact distance pays. A pair without a bound at both ends of the stretch (`close`) goes to the
  /// exact checker without one: its bound was not positive there, and a bound costs as much as
  /// the check on the mesh Panda's pairs that sit millimetres apart.
  template <class Active, class Close>
  bool look(std::size_t i, const Active& active, std::size_t row, bool decide, double steps,
            const Close& close) {
    motionState(from_, to_, dim_, i, segments_, scratch_.q.data());
    scratch_.balls.place(exact_, scratch_.q.data());
    ++placed_;
    std::vector<double>& out = scratch_.bounds[row];
    const std::size_t pairs = model_.pairs.size();
    // A row's speeds are read only by the stretches of two steps or more that it ends, at most
    // `steps` + 1/2 long: none when `steps` is 1 (half of a motion's looks). A speed not computed
    // stays infinite (newBounds), so a stretch that did read it would take its other end's.
    const bool speeds = steps > 1;
    for (const std::uint32_t p : active) {
      const ClearancePair& pair = model_.pairs[p];
      if (speeds)
        out[pairs + p] = scratch_.balls.speed(exact_, pair, *model_.movers, scratch_.stride);
      // A table's bound is a lookup: read it first, and the balls' only where it proves nothing.
      double bound = pair.tableBound(scratch_.q.data()) - kMargin;
      if (!(bound > 0))
        bound = close(p) ? 0 : scratch_.balls.lowerBound(pair, model_.obstacles) - kMargin;
      out[p] = bound > 0 ? bound : 0;
      if (bound > 0) continue;
      // A touch proven by a ball inside the shape needs neither a distance nor FCL.
      if (scratch_.balls.touchProven(pair, model_.obstacles)) {
        if (decide) return true;
        continue;
      }
      if (pair.askDistance && exact_.distance && steps >= kDistanceSteps) {
        const double distance = exact_.distance(pair);
        if (distance > kDistanceFloor) {
          out[p] = distance - kMargin;
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
  MotionScratch& scratch_;
  const double *from_, *to_;
  std::size_t dim_, segments_;
  std::size_t& placed_;  // the states placed, counted into the caller's answer
};

/// Every pair, 0..n-1, as a range of indices (std::views::iota does not compile with clang 14
/// and libstdc++ 12, the sanitizer build's pair).
struct AllPairs {
  std::uint32_t n;
  struct Iterator {
    std::uint32_t p;
    std::uint32_t operator*() const { return p; }
    Iterator& operator++() {
      ++p;
      return *this;
    }
    bool operator!=(const Iterator& other) const { return p != other.p; }
  };
  Iterator begin() const { return {0}; }
  Iterator end() const { return {n}; }
};

}  // namespace

CertifiedMotion certifiedMotionCheck(const ClearanceModel& model, const ExactPairCheck& exact,
                                     const double* from, const double* to, std::size_t dim,
                                     std::size_t segments, MotionScratch& scratch) {
  CertifiedMotion answer;
  if (segments == 0) return answer;
  // The start's bounds are known when the last motion ended here (a path's edges share their
  // waypoints).
  const bool startKnown = scratch.endQ.size() == dim &&
                          scratch.endBounds.size() == model.pairs.size() &&
                          std::equal(from, from + dim, scratch.endQ.begin());
  MotionLooks looks(model, exact, scratch, from, to, dim, segments, answer.statesPlaced);
  std::size_t atFrom = 0;
  const std::size_t pairs = model.pairs.size();
  if (startKnown) {  // its bounds; its speeds were for the last motion's stride
    atFrom = looks.newBounds();
    std::copy(scratch.endBounds.begin(), scratch.endBounds.end(), looks.bounds(atFrom).begin());
  }
  scratch.forgetEnd();
  const auto never = [](std::uint32_t) { return false; };
  const double all = static_cast<double>(segments);
  const AllPairs every{static_cast<std::uint32_t>(pairs)};

  const std::size_t atTo = looks.newBounds();
  if (looks.look(segments, every, atTo, true, all, never)) {  // into an obstacle: found at once
    answer.collidingState = segments;
    return answer;
  }
  scratch.endQ.assign(to, to + dim);
  scratch.endBounds.assign(looks.bounds(atTo).begin(),
                           looks.bounds(atTo).begin() + static_cast<std::ptrdiff_t>(pairs));
  if (segments == 1) return answer;
  // The midpoint next, before `from` is placed for its bounds: a motion that collides (most of a
  // planner's extensions) is found after the looks of the dense check's order, and pays for
  // `from` only when it survives them.
  const std::size_t half = segments / 2;
  const std::size_t atHalf = looks.newBounds();
  if (looks.look(half, every, atHalf, true, all / 2, never)) {
    answer.collidingState = half;
    return answer;
  }
  if (!startKnown) {
    atFrom = looks.newBounds();
    looks.look(0, every, atFrom, false, all / 2, never);
  }

  // Breadth first, as the dense check's bisection order: a collision anywhere on the motion is met
  // after a few looks (depth first walked the first half's every unproven state before the
  // second half's midpoint, and doubled the looks of RRT-Connect's mostly colliding extensions).
  // A stretch's active pairs are a range of scratch.active.
  std::vector<MotionScratch::Stretch>& queue = scratch.stretches;
  std::vector<std::uint32_t>& active = scratch.active;
  queue.clear();
  active.clear();
  for (const std::uint32_t p : every) active.push_back(p);
  queue.push_back({0, half, atFrom, atHalf, 0, active.size()});
  queue.push_back({half, segments, atHalf, atTo, 0, active.size()});
  for (std::size_t next = 0; next < queue.size(); ++next) {
    const MotionScratch::Stretch s = queue[next];
    if (s.hi - s.lo < 2) continue;
    const double steps = static_cast<double>(s.hi - s.lo);
    const std::vector<double>& atLo = looks.bounds(s.atLo);
    const std::vector<double>& atHi = looks.bounds(s.atHi);
    const std::size_t openBegin = active.size();
    for (std::size_t k = s.activeBegin; k < s.activeEnd; ++k) {
      const std::uint32_t p = active[k];
      const double speed = std::min(atLo[pairs + p], atHi[pairs + p]);
      if (!(atLo[p] + atHi[p] > steps * looks.perStepNear(p, speed, steps))) active.push_back(p);
    }
    const std::size_t openEnd = active.size();
    if (openBegin == openEnd) continue;
    const std::size_t mid = s.lo + (s.hi - s.lo) / 2;
    const std::size_t atMid = looks.newBounds();
    // newBounds may have moved the rows: read the ends' bounds by row again.
    const auto closeAtBothEnds = [&](std::uint32_t p) {
      return looks.bounds(s.atLo)[p] == 0 && looks.bounds(s.atHi)[p] == 0;
    };
    const std::span<const std::uint32_t> open(active.data() + openBegin, openEnd - openBegin);
    if (looks.look(mid, open, atMid, true, steps / 2, closeAtBothEnds)) {
      answer.collidingState = mid;
      return answer;
    }
    queue.push_back({s.lo, mid, s.atLo, atMid, openBegin, openEnd});
    queue.push_back({mid, s.hi, atMid, s.atHi, openBegin, openEnd});
  }
  return answer;
}

}  // namespace fastron
