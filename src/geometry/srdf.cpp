#include "fastron/geometry/srdf.h"

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "xml_reader.h"

namespace fastron {

AllowedCollisionMatrix parseSrdfDisabledCollisions(const std::string& xml,
                                                   const std::string& source, const Robot& robot) {
  TiXmlDocument document;
  const TiXmlElement* root = detail::parseRobotXml(xml, source, "an SRDF file", document);
  const char* name = root->Attribute("name");
  if (name != nullptr && std::string(name) != robot.name()) {
    throw FileError(source + ":" + std::to_string(root->Row()) + ": the SRDF is for robot '" +
                    name + "', not '" + robot.name() + "'");
  }
  AllowedCollisionMatrix disabled;
  for (const TiXmlElement* e = root->FirstChildElement("disable_collisions"); e != nullptr;
       e = e->NextSiblingElement("disable_collisions")) {
    const std::string at = source + ":" + std::to_string(e->Row()) + ": <disable_collisions>";
    const char* a = e->Attribute("link1");
    const char* b = e->Attribute("link2");
    if (a == nullptr || b == nullptr) {
      throw FileError(at + " needs both link1 and link2");
    }
    for (const char* link : {a, b}) {
      try {
        robot.linkIndex(link);
      } catch (const InvalidArgument&) {
        throw FileError(at + ": robot '" + robot.name() + "' has no link '" + link + "'");
      }
    }
    disabled.allow(a, b);
  }
  return disabled;
}

AllowedCollisionMatrix loadSrdfDisabledCollisions(const std::filesystem::path& file,
                                                  const Robot& robot) {
  return parseSrdfDisabledCollisions(readFile(file, "SRDF file"), file.string(), robot);
}

}  // namespace fastron
