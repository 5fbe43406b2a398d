#include "fastron/geometry/urdf.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "fastron/geometry/mesh_loader.h"
#include "xml_reader.h"

namespace fastron {
namespace {

// urdfdom reports problems through console_bridge, a process-wide logger: collect them for the
// exception message instead of letting them reach stderr.
class MessageCollector : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN)
      messages += (messages.empty() ? "" : "; ") + text;
  }
  std::string messages;
};
std::mutex urdfdomMutex;

std::string at(const std::string& source, const TiXmlElement* e) {
  return source + ":" + std::to_string(e->Row());
}

std::vector<double> numbers(const char* text) {
  std::vector<double> values;
  if (text == nullptr) return values;
  std::istringstream in(text);
  std::string token;
  while (in >> token) {
    try {
      std::size_t used = 0;
      values.push_back(std::stod(token, &used));
      if (used != token.size()) values.push_back(std::nan(""));
    } catch (const std::exception&) {
      values.push_back(std::nan(""));
    }
  }
  return values;
}

void requireFinite(const TiXmlElement* e, const char* attribute, std::size_t count,
                   const std::string& where) {
  const char* text = e->Attribute(attribute);
  if (text == nullptr) return;
  const std::vector<double> v = numbers(text);
  bool ok = v.size() == count;
  for (const double x : v) ok = ok && std::isfinite(x);
  if (!ok) {
    throw FileError(where + ": <" + e->ValueStr() + "> " + attribute + "=\"" + text + "\" needs " +
                    std::to_string(count) + " finite number" + (count > 1 ? "s" : ""));
  }
}

void requirePositive(const TiXmlElement* e, const char* attribute, std::size_t count,
                     const std::string& where) {
  const char* text = e->Attribute(attribute);
  if (text == nullptr)
    throw FileError(where + ": <" + e->ValueStr() + "> has no '" + attribute + "' attribute");
  requireFinite(e, attribute, count, where);
  for (const double x : numbers(text)) {
    if (x <= 0) {
      throw FileError(where + ": <" + e->ValueStr() + "> " + attribute + "=\"" + text +
                      "\" must be positive");
    }
  }
}

// What urdfdom does not check, or drops silently, checked with line numbers. Returns the
// number of <collision> elements of every link.
std::map<std::string, std::size_t> validateXml(const TiXmlElement* robot,
                                               const std::string& source) {
  std::map<std::string, std::size_t> collisions;
  for (const TiXmlElement* link = robot->FirstChildElement("link"); link;
       link = link->NextSiblingElement("link")) {
    const char* name = link->Attribute("name");
    const std::string linkName = name ? name : "";
    std::size_t count = 0;
    for (const TiXmlElement* c = link->FirstChildElement("collision"); c;
         c = c->NextSiblingElement("collision")) {
      ++count;
      const std::string where = at(source, c) + ": link '" + linkName + "'";
      if (const TiXmlElement* origin = c->FirstChildElement("origin")) {
        requireFinite(origin, "xyz", 3, at(source, origin));
        requireFinite(origin, "rpy", 3, at(source, origin));
      }
      const TiXmlElement* geometry = c->FirstChildElement("geometry");
      const TiXmlElement* shape = geometry ? geometry->FirstChildElement() : nullptr;
      if (shape == nullptr) throw FileError(where + ": <collision> without a geometry");
      const std::string type = shape->ValueStr();
      const std::string shapeAt = at(source, shape) + ": link '" + linkName + "'";
      if (type == "box") {
        requirePositive(shape, "size", 3, shapeAt);
      } else if (type == "sphere") {
        requirePositive(shape, "radius", 1, shapeAt);
      } else if (type == "cylinder") {
        requirePositive(shape, "radius", 1, shapeAt);
        requirePositive(shape, "length", 1, shapeAt);
      } else if (type == "mesh") {
        if (!shape->Attribute("filename")) throw FileError(shapeAt + ": <mesh> has no filename");
        if (shape->Attribute("scale")) requirePositive(shape, "scale", 3, shapeAt);
      } else {
        throw FileError(shapeAt + ": unknown collision geometry <" + type +
                        "> (URDF has box, cylinder, sphere and mesh; write a capsule as a cylinder "
                        "plus a sphere on each end)");
      }
    }
    collisions[linkName] = count;
  }
  for (const TiXmlElement* joint = robot->FirstChildElement("joint"); joint;
       joint = joint->NextSiblingElement("joint")) {
    const char* name = joint->Attribute("name");
    const char* type = joint->Attribute("type");
    const std::string t = type ? type : "";
    if (const TiXmlElement* origin = joint->FirstChildElement("origin")) {
      requireFinite(origin, "xyz", 3, at(source, origin));
      requireFinite(origin, "rpy", 3, at(source, origin));
    }
    if (const TiXmlElement* axis = joint->FirstChildElement("axis"))
      requireFinite(axis, "xyz", 3, at(source, axis));
    if (const TiXmlElement* mimic = joint->FirstChildElement("mimic")) {
      if (mimic->Attribute("joint") == nullptr)
        throw FileError(at(source, mimic) + ": <mimic> of joint '" + (name ? name : "") +
                        "' has no joint attribute");
      requireFinite(mimic, "multiplier", 1, at(source, mimic));
      requireFinite(mimic, "offset", 1, at(source, mimic));
    }
    if (const TiXmlElement* limit = joint->FirstChildElement("limit")) {
      requireFinite(limit, "lower", 1, at(source, limit));
      requireFinite(limit, "upper", 1, at(source, limit));
      const auto lower = numbers(limit->Attribute("lower")),
                 upper = numbers(limit->Attribute("upper"));
      const double lo = lower.empty() ? 0 : lower[0], hi = upper.empty() ? 0 : upper[0];
      if (lo > hi && t != "continuous") {
        throw FileError(at(source, limit) + ": joint '" + (name ? name : "") + "': lower limit " +
                        std::to_string(lo) + " is above the upper limit " + std::to_string(hi));
      }
    }
  }
  return collisions;
}

Eigen::Isometry3d toIsometry(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return t;
}

/// The folders of a colon-separated list (an environment variable's; none when unset).
std::vector<std::filesystem::path> pathList(const char* list) {
  std::vector<std::filesystem::path> dirs;
  std::istringstream entries(list == nullptr ? "" : list);
  for (std::string dir; std::getline(entries, dir, ':');) {
    if (!dir.empty()) dirs.emplace_back(dir);
  }
  return dirs;
}

std::filesystem::path resolveMesh(const std::string& uri, const UrdfOptions& options,
                                  const std::filesystem::path& baseDirectory,
                                  const std::string& where) {
  std::vector<std::filesystem::path> candidates;
  if (uri.rfind("package://", 0) == 0) {
    const std::string rest = uri.substr(10);
    const std::size_t slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    const auto packageIn = [&](const std::filesystem::path& dir) {
      candidates.push_back(dir / package / inside);
      if (dir.filename() == package) candidates.push_back(dir / inside);
    };
    for (const auto& dir : options.searchPaths) packageIn(dir);
    // As ROS finds packages when no folder is given: the URDF's folder and its ancestors (a
    // description package's urdf/ beside its meshes/), then the ROS 1 and ROS 2 package paths.
    if (!baseDirectory.empty()) {
      for (std::filesystem::path dir = std::filesystem::absolute(baseDirectory);;
           dir = dir.parent_path()) {
        packageIn(dir);
        if (dir == dir.parent_path()) break;
      }
    }
    for (const auto& dir : pathList(std::getenv("ROS_PACKAGE_PATH"))) packageIn(dir);
    for (const auto& dir : pathList(std::getenv("AMENT_PREFIX_PATH"))) packageIn(dir / "share");
  } else {
    const std::string path = uri.rfind("file://", 0) == 0 ? uri.substr(7) : uri;
    if (std::filesystem::path(path).is_absolute()) {
      candidates.emplace_back(path);
    } else {
      candidates.push_back(baseDirectory / path);
      for (const auto& dir : options.searchPaths) candidates.push_back(dir / path);
    }
  }
  for (const auto& c : candidates) {
    if (std::filesystem::is_regular_file(c)) return c;
  }
  std::string tried;
  for (const auto& c : candidates) tried += (tried.empty() ? "" : ", ") + c.string();
  throw FileError(where + ": mesh '" + uri + "' not found" +
                  (tried.empty() ? " (no search paths given)" : " (tried " + tried + ")"));
}

// A cylinder (r, l) whose two end centres carry spheres of radius r becomes Capsule(r, l).
void mergeCapsules(std::vector<LinkShape>& shapes) {
  auto sphereAt = [&](int link, double r, const Eigen::Vector3d& p, const std::vector<bool>& used) {
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      const auto* s = std::get_if<Sphere>(&shapes[i].shape);
      if (!used[i] && s && shapes[i].link == link && std::abs(s->radius - r) < 1e-9 &&
          (shapes[i].origin.translation() - p).norm() < 1e-6) {
        return static_cast<int>(i);
      }
    }
    return -1;
  };
  std::vector<bool> used(shapes.size(), false);
  std::vector<LinkShape> merged;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const auto* c = std::get_if<Cylinder>(&shapes[i].shape);
    if (!c || used[i]) continue;
    const Eigen::Vector3d axis = shapes[i].origin.linear().col(2) * (c->length / 2);
    const Eigen::Vector3d centre = shapes[i].origin.translation();
    used[i] = true;
    const int a = sphereAt(shapes[i].link, c->radius, centre + axis, used);
    if (a >= 0) used[static_cast<std::size_t>(a)] = true;
    const int b = sphereAt(shapes[i].link, c->radius, centre - axis, used);
    if (a >= 0 && b >= 0) {
      used[static_cast<std::size_t>(b)] = true;
      merged.push_back({shapes[i].link, shapes[i].origin, Capsule{c->radius, c->length}});
    } else {
      if (a >= 0) used[static_cast<std::size_t>(a)] = false;
      used[i] = false;
    }
  }
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    if (!used[i]) merged.push_back(shapes[i]);
  }
  shapes = std::move(merged);
}

/// A collision element's shape: a box, sphere or cylinder, or a mesh loaded from its file.
Shape collisionShape(const urdf::Geometry& geometry, const UrdfOptions& options,
                     const std::filesystem::path& baseDirectory, const std::string& where) {
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& b = static_cast<const urdf::Box&>(geometry);
      return Box{Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z)};
    }
    case urdf::Geometry::SPHERE:
      return Sphere{static_cast<const urdf::Sphere&>(geometry).radius};
    case urdf::Geometry::CYLINDER: {
      const auto& cy = static_cast<const urdf::Cylinder&>(geometry);
      return Cylinder{cy.radius, cy.length};
    }
    case urdf::Geometry::MESH: {
      const auto& m = static_cast<const urdf::Mesh&>(geometry);
      const auto path = resolveMesh(m.filename, options, baseDirectory, where);
      return Mesh{loadMesh(path, Eigen::Vector3d(m.scale.x, m.scale.y, m.scale.z))};
    }
  }
  throw FileError(where + ": unknown collision geometry");
}

/// A urdfdom joint as ours (a floating or planar joint fixed at its origin, Joint::heldMultiDof);
/// throws FileError naming `source` and the joint for a revolute or prismatic joint without
/// limits.
Joint toJoint(const std::string& name, const urdf::Joint& j,
              const std::map<std::string, int>& linkIndex, const std::string& source) {
  Joint joint;
  joint.name = name;
  joint.parent = linkIndex.at(j.parent_link_name);
  joint.child = linkIndex.at(j.child_link_name);
  joint.origin = toIsometry(j.parent_to_joint_origin_transform);
  joint.axis = Eigen::Vector3d(j.axis.x, j.axis.y, j.axis.z);
  switch (j.type) {
    case urdf::Joint::REVOLUTE:
      joint.type = JointType::Revolute;
      break;
    case urdf::Joint::CONTINUOUS:
      joint.type = JointType::Continuous;
      break;
    case urdf::Joint::PRISMATIC:
      joint.type = JointType::Prismatic;
      break;
    case urdf::Joint::FIXED:
      joint.type = JointType::Fixed;
      break;
    case urdf::Joint::FLOATING:
      joint.type = JointType::Fixed;
      joint.heldMultiDof = "floating";
      break;
    case urdf::Joint::PLANAR:
      joint.type = JointType::Fixed;
      joint.heldMultiDof = "planar";
      break;
    default:
      throw FileError(source + ": joint '" + name + "': unsupported joint type");
  }
  if (joint.type == JointType::Revolute || joint.type == JointType::Prismatic) {
    if (!j.limits) throw FileError(source + ": joint '" + name + "' has no <limit>");
    joint.lower = j.limits->lower;
    joint.upper = j.limits->upper;
  }
  if (j.mimic) {
    joint.mimic = Mimic{j.mimic->joint_name, j.mimic->multiplier, j.mimic->offset};
  }
  return joint;
}

}  // namespace

Robot parseUrdf(const std::string& xml, const std::string& source, const UrdfOptions& options,
                const std::filesystem::path& baseDirectory) {
  TiXmlDocument document;
  const TiXmlElement* robotElement = detail::parseRobotXml(xml, source, "a URDF file", document);
  const std::map<std::string, std::size_t> collisionCounts = validateXml(robotElement, source);

  urdf::ModelInterfaceSharedPtr model;
  {
    const std::lock_guard lock(urdfdomMutex);
    MessageCollector collector;
    console_bridge::useOutputHandler(&collector);
    model = urdf::parseURDF(detail::paddedXml(xml, source));
    console_bridge::restorePreviousOutputHandler();
    if (!model) throw FileError(source + ": invalid URDF: " + collector.messages);
  }

  std::vector<Link> links;
  std::map<std::string, int> linkIndex;
  std::vector<urdf::LinkSharedPtr> urdfLinks;
  model->getLinks(urdfLinks);
  for (const auto& l : urdfLinks) {
    linkIndex[l->name] = static_cast<int>(links.size());
    links.push_back({l->name, -1});
  }

  std::vector<LinkShape> shapes;
  for (const auto& l : urdfLinks) {
    const auto expected = collisionCounts.find(l->name);
    if (expected != collisionCounts.end() && expected->second != l->collision_array.size()) {
      throw FileError(source + ": link '" + l->name + "': urdfdom read " +
                      std::to_string(l->collision_array.size()) + " of its " +
                      std::to_string(expected->second) + " collision elements");
    }
    for (const auto& c : l->collision_array) {
      const std::string where = source + ": link '" + l->name + "'";
      shapes.push_back({linkIndex[l->name], toIsometry(c->origin),
                        collisionShape(*c->geometry, options, baseDirectory, where)});
    }
  }
  if (options.mergeCapsules) mergeCapsules(shapes);

  std::vector<Joint> joints;
  for (const auto& [name, j] : model->joints_) {
    joints.push_back(toJoint(name, *j, linkIndex, source));
  }
  try {
    return Robot(model->getName(), std::move(links), std::move(joints), std::move(shapes));
  } catch (const InvalidArgument& e) {
    throw FileError(source + ": " + e.what());
  }
}

Robot loadUrdf(const std::filesystem::path& file, const UrdfOptions& options) {
  return parseUrdf(readFile(file, "URDF file"), file.string(), options, file.parent_path());
}

}  // namespace fastron
