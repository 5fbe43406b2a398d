#include "fastron/geometry/robot_library.h"

#include <yaml-cpp/yaml.h>

#include <cstdlib>

#include "fastron/core/error.h"

namespace fastron {

std::filesystem::path dataDirectory() {
  const char* overridden = std::getenv("FASTRON_DATA_DIR");
  return overridden != nullptr ? std::filesystem::path(overridden)
                               : std::filesystem::path(FASTRON_DATA_DIR);
}

std::vector<RobotEntry> shippedRobots() {
  const std::filesystem::path catalogue = dataDirectory() / "robots" / "robots.yaml";
  YAML::Node root;
  try {
    root = YAML::LoadFile(catalogue.string());
  } catch (const YAML::Exception& e) {
    throw FileError(catalogue.string() + ": " + e.what());
  }
  std::vector<RobotEntry> robots;
  YAML::Mark where;  // of the entry being read, for errors that carry no position
  try {
    for (const auto& entry : root) {
      where = entry.first.Mark();
      RobotEntry r;
      r.name = entry.first.as<std::string>();
      r.description = entry.second["description"].as<std::string>("");
      if (!entry.second["urdf"])
        throw FileError(catalogue.string() + ": robot '" + r.name + "' has no 'urdf'");
      r.urdf = catalogue.parent_path() / entry.second["urdf"].as<std::string>();
      for (const auto& j : entry.second["joints"]) r.joints.push_back(j.as<std::string>());
      for (const auto& h : entry.second["held"])
        r.held.emplace_back(h.first.as<std::string>(), h.second.as<double>());
      for (const auto& p : entry.second["allowed_collisions"]) {
        if (!p.IsSequence() || p.size() != 2)
          throw YAML::Exception(p.Mark(), "allowed_collisions entries are [link, link] pairs");
        r.allowedCollisions.emplace_back(p[0].as<std::string>(), p[1].as<std::string>());
      }
      robots.push_back(std::move(r));
    }
  } catch (const YAML::Exception& e) {
    const YAML::Mark mark = e.mark.is_null() ? where : e.mark;
    throw FileError(catalogue.string() + ":" + std::to_string(mark.line + 1) + ": " + e.msg);
  }
  return robots;
}

Robot loadRobot(const std::string& nameOrPath, const UrdfOptions& options) {
  const std::filesystem::path asPath(nameOrPath);
  if (asPath.extension() == ".urdf" || std::filesystem::is_regular_file(asPath)) {
    if (!std::filesystem::is_regular_file(asPath))
      throw FileError(nameOrPath + ": URDF file not found");
    return loadUrdf(asPath, options);
  }
  std::string names;
  for (const RobotEntry& entry : shippedRobots()) {
    names += (names.empty() ? "" : ", ") + entry.name;
    if (entry.name != nameOrPath) continue;
    Robot robot = loadUrdf(entry.urdf, options);
    robot.setActuatedJoints(entry.joints);
    for (const auto& [joint, value] : entry.held) robot.setHeldPosition(joint, value);
    for (const auto& [a, b] : entry.allowedCollisions) {
      robot.linkIndex(a);  // both links must exist
      robot.linkIndex(b);
      robot.allowedCollisions().allow(a, b);
    }
    return robot;
  }
  throw FileError("'" + nameOrPath + "' is neither a shipped robot (" + names +
                  ") nor a URDF file");
}

}  // namespace fastron
