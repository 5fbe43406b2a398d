#include "fastron/geometry/srdf.h"

#include <algorithm>
#include <map>

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "xml_reader.h"

namespace fastron {
namespace {

/// Reading one SRDF: where an element is, and the warnings about what is skipped.
class SrdfReader {
 public:
  SrdfReader(std::string source, const Robot& robot, const TiXmlElement* root,
             std::vector<std::string>& warnings)
      : source_(std::move(source)), robot_(robot), warnings_(warnings) {
    for (const TiXmlElement* e = root->FirstChildElement("virtual_joint"); e != nullptr;
         e = e->NextSiblingElement("virtual_joint")) {
      virtualJoints_.push_back(attribute(e, "name"));
    }
  }

  std::string at(const TiXmlElement* e) const {
    return source_ + ":" + std::to_string(e->Row()) + ": <" + e->ValueStr() + ">";
  }
  /// The attribute, or "" when it is absent.
  static std::string attribute(const TiXmlElement* e, const char* name) {
    const char* value = e->Attribute(name);
    return value == nullptr ? "" : value;
  }
  std::string required(const TiXmlElement* e, const char* name) const {
    const std::string value = attribute(e, name);
    if (value.empty()) throw FileError(at(e) + " needs a " + name + " attribute");
    return value;
  }
  /// The index of the link (or joint) `name`, or -1 after a warning that the element is skipped.
  int link(const TiXmlElement* e, const std::string& name) const {
    return lookUp(e, name, "link", [&] { return robot_.linkIndex(name); });
  }
  /// The same for a joint; -1 without a warning for one of the SRDF's virtual joints (the
  /// robot's base in the world, which MoveIt's model has and the URDF does not).
  int joint(const TiXmlElement* e, const std::string& name) const {
    if (std::find(virtualJoints_.begin(), virtualJoints_.end(), name) != virtualJoints_.end())
      return -1;
    return lookUp(e, name, "joint", [&] { return robot_.jointIndex(name); });
  }
  /// Warns that the element is skipped because of `why`.
  void skip(const TiXmlElement* e, const std::string& why) const {
    warn(e, why + ": skipped, as MoveIt does");
  }
  void warn(const TiXmlElement* e, const std::string& what) const {
    warnings_.push_back(at(e) + " " + what);
  }

  /// One warning per absent name, however many entries name it: MoveIt configurations written
  /// for a fuller URDF name the same few links in dozens of entries.
  void finish() const {
    for (const Absent& a : absent_) {
      warnings_.push_back(source_ + ":" + std::to_string(a.firstLine) + ": " + a.kind + " '" +
                          a.name + "', which robot '" + robot_.name() +
                          "' does not have, is named by " + std::to_string(a.entries) + " entr" +
                          (a.entries == 1 ? "y" : "ies") + " (the first a <" + a.element +
                          ">): skipped, as MoveIt does");
    }
  }

 private:
  struct Absent {
    std::string kind, name, element;
    int firstLine = 0;
    std::size_t entries = 0;
  };

  template <class Find>
  int lookUp(const TiXmlElement* e, const std::string& name, const char* kind, Find find) const {
    try {
      return find();
    } catch (const InvalidArgument&) {
      auto it = std::find_if(absent_.begin(), absent_.end(),
                             [&](const Absent& a) { return a.kind == kind && a.name == name; });
      if (it == absent_.end())
        it = absent_.insert(absent_.end(), {kind, name, e->ValueStr(), e->Row(), 0});
      ++it->entries;
      return -1;
    }
  }

  std::string source_;
  const Robot& robot_;
  std::vector<std::string>& warnings_;
  std::vector<std::string> virtualJoints_;
  mutable std::vector<Absent> absent_;
};

/// Adds the joint if it moves and mimics none, and is not there yet.
void addJoint(const Robot& robot, int joint, std::vector<std::string>& joints) {
  const Joint& j = robot.joints()[static_cast<std::size_t>(joint)];
  if (!j.movable() || j.mimic) return;
  if (std::find(joints.begin(), joints.end(), j.name) == joints.end()) joints.push_back(j.name);
}

/// The links from `link` up to the root, `link` first.
std::vector<int> pathToRoot(const Robot& robot, int link) {
  std::vector<int> path{link};
  for (int joint = robot.links()[static_cast<std::size_t>(link)].parentJoint; joint >= 0;
       joint = robot.links()[static_cast<std::size_t>(path.back())].parentJoint) {
    path.push_back(robot.joints()[static_cast<std::size_t>(joint)].parent);
  }
  return path;
}

/// The joints between two links, from `base` to `tip`: up from the base to their nearest common
/// ancestor, then down to the tip (MoveIt's chains between two end effectors pass the root).
std::vector<int> chainJoints(const Robot& robot, int base, int tip) {
  const std::vector<int> up = pathToRoot(robot, base), down = pathToRoot(robot, tip);
  std::vector<int> joints;
  std::size_t common = 0;  // index in `down` of the nearest common ancestor
  while (std::find(up.begin(), up.end(), down[common]) == up.end()) ++common;
  for (const int link : up) {
    if (link == down[common]) break;
    joints.push_back(robot.links()[static_cast<std::size_t>(link)].parentJoint);
  }
  for (std::size_t i = common; i-- > 0;)
    joints.push_back(robot.links()[static_cast<std::size_t>(down[i])].parentJoint);
  return joints;
}

/// The joints of one group element, resolving subgroups through `groupJoints`.
template <class Subgroup>
void addElement(const SrdfReader& r, const Robot& robot, const TiXmlElement* e,
                std::vector<std::string>& joints, Subgroup groupJoints) {
  const std::string kind = e->ValueStr();
  if (kind == "joint") {
    if (const int j = r.joint(e, r.required(e, "name")); j >= 0) addJoint(robot, j, joints);
  } else if (kind == "link") {
    const int l = r.link(e, r.required(e, "name"));
    if (l < 0) return;
    if (const int j = robot.links()[static_cast<std::size_t>(l)].parentJoint; j >= 0)
      addJoint(robot, j, joints);
  } else if (kind == "chain") {
    const int base = r.link(e, r.required(e, "base_link"));
    const int tip = r.link(e, r.required(e, "tip_link"));
    if (base < 0 || tip < 0) return;
    for (const int j : chainJoints(robot, base, tip)) addJoint(robot, j, joints);
  } else if (kind == "group") {
    for (const std::string& j : groupJoints(e, r.required(e, "name"))) {
      if (std::find(joints.begin(), joints.end(), j) == joints.end()) joints.push_back(j);
    }
  }
}

/// Every <group>, its subgroups resolved wherever they are defined in the file.
std::vector<SrdfGroup> readGroups(const TiXmlElement* root, const SrdfReader& r,
                                  const Robot& robot) {
  std::map<std::string, const TiXmlElement*> byName;
  std::vector<std::string> order;
  for (const TiXmlElement* g = root->FirstChildElement("group"); g != nullptr;
       g = g->NextSiblingElement("group")) {
    const std::string name = r.required(g, "name");
    if (!byName.emplace(name, g).second)
      throw FileError(r.at(g) + " '" + name + "' is defined twice");
    order.push_back(name);
  }
  std::map<std::string, std::vector<std::string>> resolved;
  std::vector<std::string> resolving;  // the groups being resolved, outermost first
  const auto resolve = [&](const auto& self, const std::string& name) -> std::vector<std::string> {
    if (const auto done = resolved.find(name); done != resolved.end()) return done->second;
    const TiXmlElement* g = byName.at(name);
    if (std::find(resolving.begin(), resolving.end(), name) != resolving.end())
      throw FileError(r.at(g) + " '" + name + "' contains itself through its subgroups");
    constexpr std::size_t kDeepest = 64;  // real groups nest two or three deep
    if (resolving.size() >= kDeepest)
      throw FileError(r.at(g) + " '" + name + "': subgroups nest deeper than " +
                      std::to_string(kDeepest));
    resolving.push_back(name);
    std::vector<std::string> joints;
    for (const TiXmlElement* e = g->FirstChildElement(); e != nullptr;
         e = e->NextSiblingElement()) {
      addElement(
          r, robot, e, joints, [&](const TiXmlElement* element, const std::string& subgroup) {
            if (byName.count(subgroup) == 0) {
              r.skip(element, "names group '" + subgroup + "', which the SRDF does not define");
              return std::vector<std::string>{};
            }
            return self(self, subgroup);
          });
    }
    resolving.pop_back();
    return resolved[name] = joints;
  };
  std::vector<SrdfGroup> groups;
  for (const std::string& name : order) groups.push_back({name, resolve(resolve, name)});
  return groups;
}

/// End effectors, virtual and passive joints: only their names are checked.
void checkOtherElements(const TiXmlElement* root, const SrdfReader& r,
                        const std::vector<SrdfGroup>& groups) {
  const auto hasGroup = [&](const std::string& name) {
    return std::any_of(groups.begin(), groups.end(),
                       [&](const SrdfGroup& g) { return g.name == name; });
  };
  for (const TiXmlElement* e = root->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string kind = e->ValueStr();
    if (kind == "end_effector") {
      r.link(e, SrdfReader::attribute(e, "parent_link"));
      for (const char* key : {"group", "parent_group"}) {
        const std::string group = SrdfReader::attribute(e, key);
        if (!group.empty() && !hasGroup(group))
          r.skip(e, "names group '" + group + "', which the SRDF does not define");
      }
    } else if (kind == "virtual_joint") {
      r.link(e, SrdfReader::attribute(e, "child_link"));
    } else if (kind == "passive_joint") {
      r.joint(e, SrdfReader::attribute(e, "name"));
    }
  }
}

}  // namespace

const SrdfGroup& Srdf::group(std::string_view name) const {
  std::string known;
  for (const SrdfGroup& g : groups) {
    if (g.name == name) return g;
    known += (known.empty() ? "" : ", ") + g.name;
  }
  throw InvalidArgument("the SRDF has no group '" + std::string(name) +
                        "' (it has: " + (known.empty() ? "none" : known) + ")");
}

Srdf parseSrdf(const std::string& xml, const std::string& source, const Robot& robot) {
  TiXmlDocument document;
  const TiXmlElement* root = detail::parseRobotXml(xml, source, "an SRDF file", document);
  Srdf srdf;
  const SrdfReader r(source, robot, root, srdf.warnings);
  const std::string name = SrdfReader::attribute(root, "name");
  if (!name.empty() && name != robot.name())
    r.warn(root, "is for robot '" + name + "', not '" + robot.name() +
                     "': read all the same, as MoveIt does");
  for (const TiXmlElement* e = root->FirstChildElement("disable_collisions"); e != nullptr;
       e = e->NextSiblingElement("disable_collisions")) {
    const char* a = e->Attribute("link1");
    const char* b = e->Attribute("link2");
    if (a == nullptr || b == nullptr) throw FileError(r.at(e) + " needs both link1 and link2");
    if (r.link(e, a) >= 0 && r.link(e, b) >= 0) srdf.disabledCollisions.allow(a, b);
  }
  srdf.groups = readGroups(root, r, robot);
  checkOtherElements(root, r, srdf.groups);
  r.finish();
  return srdf;
}

Srdf loadSrdf(const std::filesystem::path& file, const Robot& robot) {
  return parseSrdf(readFile(file, "SRDF file"), file.string(), robot);
}

}  // namespace fastron
