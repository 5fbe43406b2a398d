#include "fastron/planning/ompl_adapters.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <chrono>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fastron/core/error.h"
#include "fastron/planning/motion.h"

namespace fastron {
namespace {

// Joint space without projections: none of our planners projects states, and OMPL's default for
// more than two dimensions is a random projection whose bounds it estimates by sampling states,
// most of the cost of setting up a space for every query.
class JointSpace final : public ompl::base::RealVectorStateSpace {
 public:
  using RealVectorStateSpace::RealVectorStateSpace;
  void registerProjections() override {}
};

const double* valuesOf(const ompl::base::State* state) {
  return state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
}

}  // namespace

std::size_t firstCollision(const CollisionSource& source, const double* states, std::size_t n,
                           std::size_t dim) {
  if (const auto* model = std::get_if<std::shared_ptr<const Model>>(&source)) {
    return (*model)->firstInCollision(states, n);
  }
  const auto& checker = *std::get<std::shared_ptr<const CollisionChecker>>(source);
  if (checker.dof() != dim) {
    throw InvalidArgument("checker '" + checker.name() + "' has " + std::to_string(checker.dof()) +
                          " dof, the states " + std::to_string(dim));
  }
  return checker.firstInCollision(states, n);
}

std::string sourceName(const CollisionSource& source) {
  if (std::holds_alternative<std::shared_ptr<const Model>>(source)) return "Fastron";
  const auto& checker = std::get<std::shared_ptr<const CollisionChecker>>(source);
  return checker ? checker->name() : "none";
}

std::size_t sourceDof(const CollisionSource& source) {
  return std::visit(
      [](const auto& pointer) -> std::size_t {
        if (!pointer) throw InvalidArgument("the collision source is a null pointer");
        if constexpr (std::is_same_v<std::decay_t<decltype(pointer)>,
                                     std::shared_ptr<const Model>>) {
          return pointer->dim();
        } else {
          return pointer->dof();
        }
      },
      source);
}

namespace {

SharedSourceUse orNew(SharedSourceUse use) {
  return use ? std::move(use) : std::make_shared<SourceUseCounter>();
}

}  // namespace

std::size_t firstCollision(const CollisionSource& source, const double* states, std::size_t n,
                           std::size_t dim, SourceUseCounter& use) {
  const auto began = std::chrono::steady_clock::now();
  const std::size_t first = firstCollision(source, states, n, dim);
  use.add(first < n ? first + 1 : n, std::chrono::steady_clock::now() - began);
  return first;
}

void SourceUseCounter::add(std::uint64_t answered, std::chrono::nanoseconds time) {
  answered_.fetch_add(answered, std::memory_order_relaxed);
  nanoseconds_.fetch_add(time.count(), std::memory_order_relaxed);
}

SourceUse SourceUseCounter::total() const {
  return {answered_.load(std::memory_order_relaxed),
          std::chrono::nanoseconds(nanoseconds_.load(std::memory_order_relaxed))};
}

CollisionValidityChecker::CollisionValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                                   CollisionSource source, SharedSourceUse use)
    : ompl::base::StateValidityChecker(si),
      source_(std::move(source)),
      use_(orNew(std::move(use))) {}

bool CollisionValidityChecker::isValid(const ompl::base::State* state) const {
  return firstCollision(source_, valuesOf(state), 1, si_->getStateDimension(), *use_) == 1;
}

ResolutionMotionValidator::ResolutionMotionValidator(const ompl::base::SpaceInformationPtr& si,
                                                     CollisionSource source, double resolution,
                                                     SharedSourceUse use)
    : ompl::base::MotionValidator(si),
      source_(std::move(source)),
      resolution_(resolution),
      use_(orNew(std::move(use))),
      ends_(si->getStateDimension()) {}

std::size_t ResolutionMotionValidator::ask(const double* states, std::size_t n,
                                           std::size_t dim) const {
  return firstCollision(source_, states, n, dim, *use_);
}

bool ResolutionMotionValidator::checkMotion(const ompl::base::State* s1,
                                            const ompl::base::State* s2) const {
  const std::size_t dim = si_->getStateDimension();
  const double* a = valuesOf(s1);
  const double* b = valuesOf(s2);
  const std::size_t n = segmentCount(a, b, dim, resolution_);
  if (const auto* checker = std::get_if<std::shared_ptr<const CollisionChecker>>(&source_);
      checker != nullptr && (*checker)->provesMotionsFree()) {
    const std::optional<bool> endCollides = ends_.find(b);
    bool valid = false;
    if (!endCollides || !*endCollides) {  // the whole motion at once (`b` looked at again)
      const auto began = std::chrono::steady_clock::now();
      const CollisionChecker::MotionCheck answer = (*checker)->motionCollision(a, b, n);
      use_->add(answer.looked, std::chrono::steady_clock::now() - began);
      if (answer.collidingState == 0 || answer.collidingState == n)
        ends_.remember(b, answer.collidingState == n);
      valid = answer.collidingState == 0;
    }
    (valid ? valid_ : invalid_)++;
    return valid;
  }
  thread_local std::vector<double> states;  // planners call this millions of times: no allocation
  motionStates(a, b, dim, n, states);       // row 0 is b itself
  bool valid = false;
  if (const std::optional<bool> endCollides = ends_.find(b)) {
    // Known: only the interior states (rows 1..n-1) are asked about.
    valid = !*endCollides && (n == 1 || ask(states.data() + dim, n - 1, dim) == n - 1);
  } else {
    const std::size_t first = ask(states.data(), n, dim);
    ends_.remember(b, first == 0);
    valid = first == n;
  }
  (valid ? valid_ : invalid_)++;
  return valid;
}

bool ResolutionMotionValidator::checkMotion(
    const ompl::base::State* s1, const ompl::base::State* s2,
    std::pair<ompl::base::State*, double>& lastValid) const {
  const std::size_t dim = si_->getStateDimension();
  const double* a = valuesOf(s1);
  const double* b = valuesOf(s2);
  const std::size_t n = segmentCount(a, b, dim, resolution_);
  const std::optional<bool> endCollides = ends_.find(b);
  // In order from s1, so the first collision found is the first along the motion.
  thread_local std::vector<double> state;
  state.resize(dim);
  for (std::size_t i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(n);
    for (std::size_t j = 0; j < dim; ++j) state[j] = i == n ? b[j] : a[j] + t * (b[j] - a[j]);
    bool collides = false;
    if (i == n && endCollides) {
      collides = *endCollides;
    } else {
      collides = ask(state.data(), 1, dim) == 0;
      if (i == n) ends_.remember(b, collides);
    }
    if (collides) {
      lastValid.second = static_cast<double>(i - 1) / static_cast<double>(n);
      if (lastValid.first != nullptr) {
        si_->getStateSpace()->interpolate(s1, s2, lastValid.second, lastValid.first);
      }
      invalid_++;
      return false;
    }
  }
  valid_++;
  return true;
}

ompl::base::SpaceInformationPtr makeSpaceInformation(const CollisionSource& source,
                                                     const JointLimits& limits, double resolution) {
  const std::size_t dim = sourceDof(source);
  if (dim != limits.dim()) {
    throw InvalidArgument(sourceName(source) + " checks " + std::to_string(dim) +
                          " joints but the joint limits have " + std::to_string(limits.dim()));
  }
  if (!(resolution > 0) || !std::isfinite(resolution)) {
    throw InvalidArgument("motion resolution must be positive, got " + std::to_string(resolution));
  }
  auto space = std::make_shared<JointSpace>(static_cast<unsigned>(dim));
  ompl::base::RealVectorBounds bounds(static_cast<unsigned>(dim));
  for (std::size_t j = 0; j < dim; ++j) {
    bounds.setLow(static_cast<unsigned>(j), limits.lower()[static_cast<Eigen::Index>(j)]);
    bounds.setHigh(static_cast<unsigned>(j), limits.upper()[static_cast<Eigen::Index>(j)]);
  }
  space->setBounds(bounds);
  auto si = std::make_shared<ompl::base::SpaceInformation>(space);
  const auto use = std::make_shared<SourceUseCounter>();
  si->setStateValidityChecker(std::make_shared<CollisionValidityChecker>(si, source, use));
  si->setMotionValidator(std::make_shared<ResolutionMotionValidator>(si, source, resolution, use));
  si->setup();
  return si;
}

SourceUse sourceUse(const ompl::base::SpaceInformationPtr& si) {
  const auto* checker =
      dynamic_cast<const CollisionValidityChecker*>(si->getStateValidityChecker().get());
  return checker != nullptr ? checker->use()->total() : SourceUse{};
}

}  // namespace fastron
