#pragma once
// Internal to the geometry layer: reading YAML files (scenes, MoveIt files, the robot catalogue)
// with errors that name the file, the line and the field.

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "fastron/core/error.h"
#include "fastron/geometry/scene.h"  // makePose

namespace fastron::detail {

// Reads YAML nodes and reports problems as "file:line: message".
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    const int line = node.IsDefined() ? node.Mark().line + 1 : 0;
    throw FileError(source_ + (line > 0 ? ":" + std::to_string(line) : "") + ": " + message);
  }

  YAML::Node required(const YAML::Node& map, const char* key, const std::string& what) const {
    const YAML::Node value = map[key];
    if (!value) fail(map, what + " has no '" + key + "'");
    return value;
  }

  double number(const YAML::Node& node, const std::string& what) const {
    double v = 0;
    try {
      v = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(node, what + " must be a number");
    }
    if (!std::isfinite(v)) fail(node, what + " is not finite");
    return v;
  }

  /// The node itself, after checking that it is a list. A copy (nodes are handles), so that a
  /// range-for over list(required(...)) does not iterate over a destroyed temporary.
  YAML::Node list(const YAML::Node& node, const std::string& what) const {
    if (!node.IsSequence()) fail(node, what + " must be a list");
    return node;
  }

  std::string text(const YAML::Node& node, const std::string& what) const {
    if (!node.IsScalar()) fail(node, what + " must be a string");
    return node.Scalar();
  }

  bool flag(const YAML::Node& node, const std::string& what) const {
    try {
      return node.as<bool>();
    } catch (const YAML::Exception&) {
      fail(node, what + " must be true or false");
    }
  }

  std::uint64_t count(const YAML::Node& node, const std::string& what) const {
    try {
      return node.as<std::uint64_t>();
    } catch (const YAML::Exception&) {
      fail(node, what + " must be a non-negative integer");
    }
  }

  std::vector<double> numbers(const YAML::Node& node, std::size_t count,
                              const std::string& what) const {
    if (!node.IsSequence() || (count > 0 && node.size() != count)) {
      fail(node, what + " must be a list of " + std::to_string(count) + " numbers");
    }
    std::vector<double> v;
    for (const auto& item : node) v.push_back(number(item, what));
    return v;
  }

  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& what) const {
    const auto v = numbers(node, 3, what);
    return {v[0], v[1], v[2]};
  }

  /// `position` plus `rpy` or `orientation` (quaternion x, y, z, w) of a map.
  Eigen::Isometry3d pose(const YAML::Node& map, const std::string& what) const {
    const Eigen::Vector3d position =
        map["position"] ? vector3(map["position"], what + " position") : Eigen::Vector3d::Zero();
    if (map["rpy"] && map["orientation"]) fail(map, what + ": give rpy or orientation, not both");
    if (map["orientation"]) {
      const auto q = numbers(map["orientation"], 4, what + " orientation [x, y, z, w]");
      const Eigen::Quaterniond quaternion(q[3], q[0], q[1], q[2]);
      if (quaternion.norm() < 1e-9)
        fail(map["orientation"], what + " orientation is a zero quaternion");
      Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
      p.translation() = position;
      p.linear() = quaternion.normalized().toRotationMatrix();
      return p;
    }
    return makePose(position,
                    map["rpy"] ? vector3(map["rpy"], what + " rpy") : Eigen::Vector3d::Zero());
  }

  void onlyKeys(const YAML::Node& map, const std::set<std::string>& allowed,
                const std::string& what) const {
    if (!map.IsMap()) fail(map, what + " must be a map");
    for (const auto& entry : map) {
      const std::string key = text(entry.first, what + " key");
      if (!allowed.count(key)) {
        std::string list;
        for (const auto& k : allowed) list += (list.empty() ? "" : ", ") + k;
        fail(entry.first, what + ": unknown key '" + key + "' (expected " + list + ")");
      }
    }
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

inline YAML::Node parseYaml(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw FileError(source + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
}

/// Runs `read`; a yaml-cpp error it did not foresee (a map where a list belongs, ...) becomes a
/// FileError naming the file and the line.
template <class Read>
auto namingYamlErrors(const std::string& source, Read read) {
  try {
    return read();
  } catch (const YAML::Exception& e) {
    throw FileError(source + (e.mark.is_null() ? "" : ":" + std::to_string(e.mark.line + 1)) +
                    ": " + e.msg);
  }
}

/// A MoveIt joint_state map (`name` and `position` lists of one length) inside `what`.
inline NamedPositions jointState(const Reader& r, const YAML::Node& state,
                                 const std::string& what) {
  const std::string at = what + ".joint_state";
  const YAML::Node names = r.list(r.required(state, "name", at), at + ".name");
  const YAML::Node positions = r.list(r.required(state, "position", at), at + ".position");
  if (names.size() != positions.size()) r.fail(state, at + ": one position per name is needed");
  NamedPositions read;
  for (std::size_t i = 0; i < names.size(); ++i) {
    read.names.push_back(r.text(names[i], what + " joint name"));
    read.positions.push_back(r.number(positions[i], what + " position of " + read.names.back()));
  }
  return read;
}

}  // namespace fastron::detail
