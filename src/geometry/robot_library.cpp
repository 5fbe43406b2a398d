#include "fastron/geometry/robot_library.h"

#include <cstdlib>

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "fastron/core/install_location.h"
#include "fastron/geometry/srdf.h"
#include "yaml_reader.h"

namespace fastron {

std::filesystem::path dataDirectory() {
  const char* overridden = std::getenv("FASTRON_DATA_DIR");
  if (overridden != nullptr && overridden[0] != '\0') return overridden;
  if (auto installed = installedShareDirectory()) return *installed;
  throw FileError(
      "Fastron's data folder (robots, scenes) was not found: no share/fastron/robots/robots.yaml "
      "above the program or library, and FASTRON_DATA_DIR is not set; install Fastron "
      "(cmake --install) or set FASTRON_DATA_DIR to a folder with robots/ and scenes/");
}

std::vector<RobotEntry> parseRobotCatalogue(const std::string& yaml, const std::string& source,
                                            const std::filesystem::path& directory) {
  return detail::namingYamlErrors(source, [&] {
    const detail::Reader r(source);
    const YAML::Node root = detail::parseYaml(yaml, source);
    if (!root.IsMap()) r.fail(root, "the robot catalogue is a map of robots");
    std::vector<RobotEntry> robots;
    for (const auto& entry : root) {
      RobotEntry robot;
      robot.name = r.text(entry.first, "robot name");
      const std::string what = "robot '" + robot.name + "'";
      const YAML::Node e = entry.second;
      r.onlyKeys(e, {"urdf", "srdf", "description", "joints", "held", "allowed_collisions"}, what);
      if (e["description"]) robot.description = r.text(e["description"], what + " description");
      robot.urdf = directory / r.text(r.required(e, "urdf", what), what + " urdf");
      if (e["srdf"]) robot.srdf = directory / r.text(e["srdf"], what + " srdf");
      for (const auto& j : r.list(r.required(e, "joints", what), what + " joints"))
        robot.joints.push_back(r.text(j, what + " joint"));
      if (e["held"]) {
        if (!e["held"].IsMap()) r.fail(e["held"], what + " held must be a map of joint: position");
        for (const auto& h : e["held"])
          robot.held.emplace_back(r.text(h.first, what + " held joint"),
                                  r.number(h.second, what + " held position"));
      }
      if (e["allowed_collisions"]) {
        for (const auto& p : r.list(e["allowed_collisions"], what + " allowed_collisions")) {
          if (!p.IsSequence() || p.size() != 2)
            r.fail(p, what + " allowed_collisions entries are [link, link] pairs");
          robot.allowedCollisions.emplace_back(r.text(p[0], what + " link"),
                                               r.text(p[1], what + " link"));
        }
      }
      robots.push_back(std::move(robot));
    }
    return robots;
  });
}

std::vector<RobotEntry> shippedRobots() {
  const std::filesystem::path catalogue = dataDirectory() / "robots" / "robots.yaml";
  return parseRobotCatalogue(readFile(catalogue, "robot catalogue"), catalogue.string(),
                             catalogue.parent_path());
}

namespace {

/// The SRDF's disabled collisions added to the robot, its groups and warnings to `into`.
void applySrdf(const std::filesystem::path& file, RobotDescription& into) {
  Srdf srdf = loadSrdf(file, into.robot);
  into.robot.allowedCollisions().merge(srdf.disabledCollisions);
  into.srdf.disabledCollisions.merge(srdf.disabledCollisions);
  for (SrdfGroup& group : srdf.groups) {  // a later SRDF's group replaces one of the same name
    std::erase_if(into.srdf.groups, [&](const SrdfGroup& g) { return g.name == group.name; });
    into.srdf.groups.push_back(std::move(group));
  }
  into.srdf.warnings.insert(into.srdf.warnings.end(), srdf.warnings.begin(), srdf.warnings.end());
}

Robot loadShipped(const RobotEntry& entry, const UrdfOptions& options) {
  UrdfOptions shipped = options;
  shipped.searchPaths.push_back(entry.urdf.parent_path());  // its package:// meshes
  Robot robot = loadUrdf(entry.urdf, shipped);
  robot.setActuatedJoints(entry.joints);
  for (const auto& [joint, value] : entry.held) robot.setHeldPosition(joint, value);
  for (const auto& [a, b] : entry.allowedCollisions) {
    robot.linkIndex(a);  // both links must exist
    robot.linkIndex(b);
    robot.allowedCollisions().allow(a, b);
  }
  return robot;
}

/// One warning per joint of `robot` that its URDF `urdf` made fixed (Joint::heldMultiDof).
std::vector<std::string> heldJointWarnings(const Robot& robot, const std::filesystem::path& urdf) {
  std::vector<std::string> warnings;
  for (const Joint& joint : robot.joints()) {
    if (joint.heldMultiDof.empty()) continue;
    warnings.push_back(urdf.string() + ": joint '" + joint.name + "' is " + joint.heldMultiDof +
                       ": held at its origin (Fastron plans joints of one coordinate; a "
                       "scene's multi_dof_joint_state places the robot's root)");
  }
  return warnings;
}

}  // namespace

RobotDescription loadRobotDescription(const std::string& nameOrPath, const UrdfOptions& options,
                                      const std::filesystem::path& srdf) {
  const auto described = [&](RobotDescription description, const std::filesystem::path& urdf) {
    if (!srdf.empty()) applySrdf(srdf, description);
    description.warnings = heldJointWarnings(description.robot, urdf);
    description.warnings.insert(description.warnings.end(), description.srdf.warnings.begin(),
                                description.srdf.warnings.end());
    return description;
  };
  const std::filesystem::path asPath(nameOrPath);
  if (asPath.extension() == ".urdf" || std::filesystem::is_regular_file(asPath)) {
    if (!std::filesystem::is_regular_file(asPath))
      throw FileNotFound(nameOrPath + ": URDF file not found");
    return described({loadUrdf(asPath, options), {}, {}}, asPath);
  }
  std::string names;
  for (const RobotEntry& entry : shippedRobots()) {
    names += (names.empty() ? "" : ", ") + entry.name;
    if (entry.name != nameOrPath) continue;
    RobotDescription description{loadShipped(entry, options), {}, {}};
    if (!entry.srdf.empty()) applySrdf(entry.srdf, description);
    return described(std::move(description), entry.urdf);
  }
  throw FileError("'" + nameOrPath + "' is neither a shipped robot (" + names +
                  ") nor a URDF file");
}

Robot loadRobot(const std::string& nameOrPath, const UrdfOptions& options,
                const std::filesystem::path& srdf) {
  return loadRobotDescription(nameOrPath, options, srdf).robot;
}

}  // namespace fastron
