#include "fastron/geometry/robot.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <unordered_set>

#include "fastron/core/error.h"

namespace fastron {
namespace {

template <class T>
int indexByName(const std::vector<T>& items, std::string_view name, const char* kind,
                const std::string& robot) {
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].name == name) return static_cast<int>(i);
  }
  std::string known;
  for (const auto& item : items) known += (known.empty() ? "" : ", ") + item.name;
  throw InvalidArgument("robot '" + robot + "' has no " + kind + " '" + std::string(name) +
                        "' (it has: " + known + ")");
}

}  // namespace

namespace {

/// Checks each joint (names, links, limits, axis, origin) and settles what it leaves open (a
/// continuous joint's range, a unit axis); returns each link's parent joint (-1: none). Throws
/// InvalidArgument naming the robot (`where`) and the joint.
std::vector<int> checkJoints(const std::string& where, const std::vector<Link>& links,
                             std::vector<Joint>& joints) {
  std::unordered_set<std::string> names;
  const int linkCount = static_cast<int>(links.size());
  std::vector<int> parentJointOf(links.size(), -1);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    Joint& joint = joints[j];
    const std::string at = where + ", joint '" + joint.name + "'";
    if (!names.insert(joint.name).second)
      throw InvalidArgument(where + ": two joints named '" + joint.name + "'");
    if (joint.parent < 0 || joint.parent >= linkCount || joint.child < 0 ||
        joint.child >= linkCount) {
      throw InvalidArgument(at + ": parent or child link does not exist");
    }
    if (parentJointOf[static_cast<std::size_t>(joint.child)] >= 0) {
      throw InvalidArgument(at + ": link '" + links[static_cast<std::size_t>(joint.child)].name +
                            "' already has a parent joint");
    }
    parentJointOf[static_cast<std::size_t>(joint.child)] = static_cast<int>(j);
    if (joint.type == JointType::Continuous) {
      joint.lower = -std::numbers::pi;
      joint.upper = std::numbers::pi;
    }
    if (joint.movable()) {
      if (!std::isfinite(joint.lower) || !std::isfinite(joint.upper) || joint.lower > joint.upper) {
        throw InvalidArgument(at + ": limits need finite lower <= upper, got [" +
                              std::to_string(joint.lower) + ", " + std::to_string(joint.upper) +
                              "]");
      }
      if (!joint.axis.allFinite() || joint.axis.norm() < 1e-12)
        throw InvalidArgument(at + ": axis is zero");
      joint.axis.normalize();
    }
    if (!joint.origin.matrix().allFinite()) throw InvalidArgument(at + ": origin is not finite");
  }
  return parentJointOf;
}

}  // namespace

/// The joints in breadth-first order from the single root (parents before children), each link's
/// parent joint set. Throws InvalidArgument on several roots or a cycle.
void Robot::orderJoints(const std::string& where, const std::vector<int>& parentJointOf,
                        const std::vector<Joint>& joints) {
  const int linkCount = static_cast<int>(links_.size());
  // One root; order the joints breadth-first from it so parents come before children.
  std::vector<int> roots;
  for (int l = 0; l < linkCount; ++l) {
    if (parentJointOf[static_cast<std::size_t>(l)] < 0) roots.push_back(l);
  }
  if (roots.size() != 1) {
    throw InvalidArgument(where + " must have exactly one root link, found " +
                          std::to_string(roots.size()));
  }
  root_ = roots.front();
  std::vector<std::vector<int>> childJoints(links_.size());
  for (std::size_t j = 0; j < joints.size(); ++j) {
    childJoints[static_cast<std::size_t>(joints[j].parent)].push_back(static_cast<int>(j));
  }
  std::queue<int> frontier;
  frontier.push(root_);
  while (!frontier.empty()) {
    const int link = frontier.front();
    frontier.pop();
    for (const int j : childJoints[static_cast<std::size_t>(link)]) {
      joints_.push_back(joints[static_cast<std::size_t>(j)]);
      frontier.push(joints[static_cast<std::size_t>(j)].child);
    }
  }
  if (joints_.size() != joints.size()) throw InvalidArgument(where + ": the joints form a cycle");
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    links_[static_cast<std::size_t>(joints_[j].child)].parentJoint = static_cast<int>(j);
  }
  links_[static_cast<std::size_t>(root_)].parentJoint = -1;
}

Robot::Robot(std::string name, std::vector<Link> links, std::vector<Joint> joints,
             std::vector<LinkShape> shapes)
    : name_(std::move(name)), links_(std::move(links)), shapes_(std::move(shapes)) {
  const std::string where = "robot '" + name_ + "'";
  if (links_.empty()) throw InvalidArgument(where + " has no links");
  std::unordered_set<std::string> names;
  for (const Link& l : links_) {
    if (!names.insert(l.name).second)
      throw InvalidArgument(where + ": two links named '" + l.name + "'");
  }
  const std::vector<int> parentJointOf = checkJoints(where, links_, joints);
  orderJoints(where, parentJointOf, joints);
  const int linkCount = static_cast<int>(links_.size());
  for (const LinkShape& s : shapes_) {
    if (s.link < 0 || s.link >= linkCount)
      throw InvalidArgument(where + ": a shape's link does not exist");
    validate(s.shape, where + ", link '" + links_[static_cast<std::size_t>(s.link)].name + "'");
  }

  resolveMimics();
  held_.resize(joints_.size(), 0.0);
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    held_[j] = std::clamp(0.0, joints_[j].lower, joints_[j].upper);
    if (joints_[j].movable() && !joints_[j].mimic && joints_[j].lower < joints_[j].upper)
      actuated_.push_back(static_cast<int>(j));
  }
  for (const MimicJoint& m : mimics_) {
    held_[static_cast<std::size_t>(m.joint)] =
        m.multiplier * held_[static_cast<std::size_t>(m.source)] + m.offset;
  }
}

void Robot::resolveMimics() {
  // A mimic of a mimic follows the end of the chain: multipliers multiply, offsets carry.
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    if (!joints_[j].movable()) joints_[j].mimic.reset();  // nothing to follow with: as MoveIt
    if (!joints_[j].mimic) continue;
    const std::string at = "robot '" + name_ + "', joint '" + joints_[j].name + "'";
    MimicJoint resolved{static_cast<int>(j), -1, 1, 0};
    std::string followed = joints_[j].mimic->joint;
    resolved.multiplier = joints_[j].mimic->multiplier;
    resolved.offset = joints_[j].mimic->offset;
    for (std::size_t hops = 0;; ++hops) {
      const auto it = std::find_if(joints_.begin(), joints_.end(),
                                   [&](const Joint& other) { return other.name == followed; });
      if (it == joints_.end())
        throw InvalidArgument(at + " mimics joint '" + followed + "', which the robot lacks");
      if (!it->movable())
        throw InvalidArgument(at + " mimics joint '" + followed + "', which is fixed");
      if (hops > joints_.size()) throw InvalidArgument(at + ": its mimics form a cycle");
      if (!it->mimic) {
        resolved.source = static_cast<int>(it - joints_.begin());
        break;
      }
      resolved.offset = resolved.multiplier * it->mimic->offset + resolved.offset;
      resolved.multiplier *= it->mimic->multiplier;
      followed = it->mimic->joint;
    }
    if (!std::isfinite(resolved.multiplier) || !std::isfinite(resolved.offset))
      throw InvalidArgument(at + ": its mimic multiplier and offset must be finite");
    mimics_.push_back(resolved);
  }
  for (const MimicJoint& m : mimics_) {
    joints_[static_cast<std::size_t>(m.joint)].mimic =
        Mimic{joints_[static_cast<std::size_t>(m.source)].name, m.multiplier, m.offset};
  }
}

bool Robot::followsConfiguration(int joint) const {
  const auto actuated = [&](int j) {
    return std::find(actuated_.begin(), actuated_.end(), j) != actuated_.end();
  };
  if (actuated(joint)) return true;
  const auto m = std::find_if(mimics_.begin(), mimics_.end(),
                              [&](const MimicJoint& each) { return each.joint == joint; });
  return m != mimics_.end() && actuated(m->source);
}

int Robot::linkIndex(std::string_view name) const {
  return indexByName(links_, name, "link", name_);
}
int Robot::jointIndex(std::string_view name) const {
  return indexByName(joints_, name, "joint", name_);
}

std::vector<std::string> Robot::actuatedJointNames() const {
  std::vector<std::string> names;
  for (const int j : actuated_) names.push_back(joints_[static_cast<std::size_t>(j)].name);
  return names;
}

std::vector<std::string> Robot::movableJointNames() const {
  std::vector<std::string> names;
  for (const Joint& j : joints_) {
    if (j.movable() && !j.mimic) names.push_back(j.name);
  }
  return names;
}

void Robot::setActuatedJoints(const std::vector<std::string>& names) {
  if (names.empty()) throw InvalidArgument("robot '" + name_ + "': no actuated joints given");
  std::vector<int> actuated;
  for (const std::string& n : names) {
    const int j = jointIndex(n);
    const Joint& joint = joints_[static_cast<std::size_t>(j)];
    if (!joint.movable())
      throw InvalidArgument("robot '" + name_ + "': joint '" + n + "' is fixed");
    if (joint.mimic) {
      throw InvalidArgument("robot '" + name_ + "': joint '" + n + "' mimics joint '" +
                            joint.mimic->joint + "' (actuate that one)");
    }
    if (!(joint.lower < joint.upper)) {
      throw InvalidArgument("robot '" + name_ + "': joint '" + n + "' has no range to move in");
    }
    if (std::find(actuated.begin(), actuated.end(), j) != actuated.end()) {
      throw InvalidArgument("robot '" + name_ + "': joint '" + n + "' is listed twice");
    }
    actuated.push_back(j);
  }
  actuated_ = std::move(actuated);
}

void Robot::setHeldPosition(std::string_view joint, double value) {
  const int j = jointIndex(joint);
  const Joint& jt = joints_[static_cast<std::size_t>(j)];
  if (jt.mimic) {
    throw InvalidArgument("robot '" + name_ + "': joint '" + jt.name + "' mimics joint '" +
                          jt.mimic->joint + "' and follows it");
  }
  if (!std::isfinite(value) || value < jt.lower - 1e-9 || value > jt.upper + 1e-9) {
    throw InvalidArgument("robot '" + name_ + "': held position " + std::to_string(value) +
                          " of joint '" + jt.name + "' is outside its limits [" +
                          std::to_string(jt.lower) + ", " + std::to_string(jt.upper) + "]");
  }
  held_[static_cast<std::size_t>(j)] = value;
  for (const MimicJoint& m : mimics_) {
    if (m.source == j) held_[static_cast<std::size_t>(m.joint)] = m.multiplier * value + m.offset;
  }
}

JointLimits Robot::limits() const {
  Eigen::VectorXd lower(static_cast<Eigen::Index>(dof())), upper(static_cast<Eigen::Index>(dof()));
  for (std::size_t i = 0; i < actuated_.size(); ++i) {
    lower[static_cast<Eigen::Index>(i)] = joints_[static_cast<std::size_t>(actuated_[i])].lower;
    upper[static_cast<Eigen::Index>(i)] = joints_[static_cast<std::size_t>(actuated_[i])].upper;
  }
  return {lower, upper};
}

AllowedCollisionMatrix Robot::adjacentLinks() const {
  // Links joined by fixed joints form rigid groups. A group may touch itself and its geometric
  // parent: the nearest ancestor group that has collision geometry (links without geometry,
  // such as the frames between two coincident joints, are skipped).
  const std::size_t n = links_.size();
  std::vector<int> group(n);
  for (std::size_t l = 0; l < n; ++l) group[l] = static_cast<int>(l);
  for (const Joint& j : joints_) {  // parent before child, so the parent's group is final
    if (!j.movable())
      group[static_cast<std::size_t>(j.child)] = group[static_cast<std::size_t>(j.parent)];
  }
  std::vector<bool> hasGeometry(n, false);
  for (const LinkShape& s : shapes_)
    hasGeometry[static_cast<std::size_t>(group[static_cast<std::size_t>(s.link)])] = true;
  auto parentGroup = [&](int g) {
    const int joint = links_[static_cast<std::size_t>(g)].parentJoint;
    return joint < 0
               ? -1
               : group[static_cast<std::size_t>(joints_[static_cast<std::size_t>(joint)].parent)];
  };
  std::vector<int> geometricParent(n, -1);
  for (std::size_t g = 0; g < n; ++g) {
    int p = parentGroup(static_cast<int>(g));
    while (p >= 0 && !hasGeometry[static_cast<std::size_t>(p)]) p = parentGroup(p);
    geometricParent[g] = p;
  }
  AllowedCollisionMatrix acm;
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      const int ga = group[a], gb = group[b];
      if (ga == gb || geometricParent[static_cast<std::size_t>(ga)] == gb ||
          geometricParent[static_cast<std::size_t>(gb)] == ga) {
        acm.allow(links_[a].name, links_[b].name);
      }
    }
  }
  return acm;
}

std::vector<std::pair<std::size_t, std::size_t>> Robot::selfCollisionPairs(
    const AllowedCollisionMatrix& extra) const {
  AllowedCollisionMatrix allowed = adjacentLinks();
  allowed.merge(allowed_);
  allowed.merge(extra);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < shapes_.size(); ++a) {
    for (std::size_t b = a + 1; b < shapes_.size(); ++b) {
      const int la = shapes_[a].link, lb = shapes_[b].link;
      if (la != lb && !allowed.allowed(links_[static_cast<std::size_t>(la)].name,
                                       links_[static_cast<std::size_t>(lb)].name)) {
        pairs.emplace_back(a, b);
      }
    }
  }
  return pairs;
}

std::vector<std::size_t> coordinatesOfMoreThanATurn(const Robot& robot) {
  const JointLimits limits = robot.limits();
  std::vector<std::size_t> coordinates;
  for (std::size_t i = 0; i < robot.dof(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    const Joint& joint = robot.joints()[static_cast<std::size_t>(robot.actuatedJoints()[i])];
    if (joint.type == JointType::Revolute &&
        limits.upper()[k] - limits.lower()[k] > 2 * std::numbers::pi)
      coordinates.push_back(i);
  }
  return coordinates;
}

}  // namespace fastron
