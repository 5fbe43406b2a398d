#include "fastron/geometry/srdf.h"

#include <tinyxml.h>

#include <fstream>
#include <sstream>

#include "fastron/core/error.h"

namespace fastron {

AllowedCollisionMatrix parseSrdfDisabledCollisions(const std::string& xml,
                                                   const std::string& source, const Robot& robot) {
  TiXmlDocument document;
  document.Parse(xml.c_str());
  if (document.Error()) {
    const int row = document.ErrorRow();  // 0 when the text is not XML at all
    throw FileError(source + (row > 0 ? ":" + std::to_string(row) : "") +
                    ": malformed XML: " + document.ErrorDesc());
  }
  const TiXmlElement* root = document.RootElement();
  if (root == nullptr || root->ValueStr() != "robot") {
    throw FileError(source + ": not an SRDF file (the root element is not <robot>)");
  }
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
  std::ifstream in(file);
  if (!in) throw FileError(file.string() + ": cannot open SRDF file");
  std::stringstream text;
  text << in.rdbuf();
  return parseSrdfDisabledCollisions(text.str(), file.string(), robot);
}

}  // namespace fastron
