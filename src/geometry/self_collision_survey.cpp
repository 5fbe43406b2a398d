#include "fastron/geometry/self_collision_survey.h"

#include <algorithm>
#include <map>
#include <utility>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"

namespace fastron {

std::string_view toString(PairVerdict verdict) {
  switch (verdict) {
    case PairVerdict::Default:
      return "default";
    case PairVerdict::Always:
      return "always";
    case PairVerdict::Never:
      return "never";
    case PairVerdict::Enabled:
      return "enabled";
  }
  return "unknown";
}

SelfCollisionSurvey surveySelfCollisions(const Robot& robot, const SelfCollisionOptions& options) {
  if (options.samples == 0) throw InvalidArgument("self-collision survey: samples must be >= 1");
  if (!(options.alwaysShare > 0 && options.alwaysShare <= 1)) {
    throw InvalidArgument("self-collision survey: alwaysShare must be in (0, 1], got " +
                          std::to_string(options.alwaysShare));
  }
  const FclChecker checker(robot, Scene{}, {.selfCollision = true});

  // Every candidate pair, keyed by link names (the earlier link of robot.links() first, as
  // FclChecker::selfContacts names them), starting at zero collisions.
  std::map<std::pair<std::string, std::string>, LinkPairSurvey> pairs;
  for (const auto& [a, b] : robot.selfCollisionPairs({})) {
    const auto [first, second] = std::minmax(robot.shapes()[a].link, robot.shapes()[b].link);
    const std::string& la = robot.links()[static_cast<std::size_t>(first)].name;
    const std::string& lb = robot.links()[static_cast<std::size_t>(second)].name;
    pairs.try_emplace({la, lb}, LinkPairSurvey{la, lb});
  }

  const JointLimits limits = robot.limits();
  std::vector<double> home(robot.dof());
  for (std::size_t j = 0; j < home.size(); ++j) {
    const auto i = static_cast<Eigen::Index>(j);
    home[j] = std::clamp(0.0, limits.lower()[i], limits.upper()[i]);
  }
  for (const Contact& c : checker.selfContacts(home))
    pairs.at({c.robotLink, c.other}).atHome = true;

  SelfCollisionSurvey survey;
  survey.samples = options.samples;
  Rng rng(options.seed);
  const Configurations q = uniformConfigurations(limits, options.samples, rng);
  // Per sample, the pairs touching (map nodes stay put): verdicts are known only at the end.
  std::vector<std::vector<const LinkPairSurvey*>> touching(options.samples);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    for (const Contact& c : checker.selfContacts({q.row(i).data(), robot.dof()})) {
      LinkPairSurvey& pair = pairs.at({c.robotLink, c.other});
      ++pair.collisions;
      touching[static_cast<std::size_t>(i)].push_back(&pair);
    }
  }

  const auto always = static_cast<double>(options.samples) * options.alwaysShare;
  for (auto& [key, pair] : pairs) {
    if (pair.atHome)
      pair.verdict = PairVerdict::Default;
    else if (static_cast<double>(pair.collisions) >= always)
      pair.verdict = PairVerdict::Always;
    else if (pair.collisions == 0)
      pair.verdict = PairVerdict::Never;
  }
  for (const auto& contacts : touching) {
    survey.configurationsBefore += !contacts.empty();
    survey.configurationsInCollision +=
        std::any_of(contacts.begin(), contacts.end(),
                    [](const LinkPairSurvey* p) { return p->verdict == PairVerdict::Enabled; });
  }
  for (auto& [key, pair] : pairs) survey.pairs.push_back(std::move(pair));
  std::stable_sort(survey.pairs.begin(), survey.pairs.end(),
                   [](const auto& a, const auto& b) { return a.collisions > b.collisions; });
  return survey;
}

}  // namespace fastron
