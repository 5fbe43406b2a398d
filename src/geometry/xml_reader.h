#pragma once
// Internal to the geometry layer: reading the XML robot descriptions (URDF, SRDF) with errors that
// name the file and the line.

#include <tinyxml.h>

#include <string>

#include "fastron/core/error.h"

namespace fastron::detail {

/// `xml` made safe for TinyXML: refused (FileError naming `source`) when it holds a NUL byte,
/// which no text file has, and followed by four NUL bytes. TinyXML steps over a UTF-8 sequence
/// by the length its first byte announces: a text that ends inside one made it read past the end
/// of the buffer (found by fuzz/urdf_fuzzer).
inline std::string paddedXml(const std::string& xml, const std::string& source) {
  if (xml.find('\0') != std::string::npos)
    throw FileError(source + ": a NUL byte at offset " + std::to_string(xml.find('\0')) +
                    ": not a text file");
  std::string padded = xml;
  padded.append(4, '\0');
  return padded;
}

/// Parses `xml` (paddedXml) into `document` and returns its <robot> root; throws FileError naming
/// `source` (and the line where TinyXML knows it) on malformed XML, or saying that it is not `what`
/// (e.g. "a URDF file") when the root is not <robot>.
inline const TiXmlElement* parseRobotXml(const std::string& xml, const std::string& source,
                                         const char* what, TiXmlDocument& document) {
  const std::string padded = paddedXml(xml, source);
  document.Parse(padded.c_str());
  if (document.Error()) {
    std::string where = source;
    if (const int row = document.ErrorRow(); row > 0) {  // 0 when the text is not XML at all
      where += ':';
      where += std::to_string(row);
    }
    throw FileError(where + ": malformed XML: " + document.ErrorDesc());
  }
  const TiXmlElement* root = document.RootElement();
  if (root == nullptr || root->ValueStr() != "robot") {
    throw FileError(source + ": not " + what + " (the root element is not <robot>)");
  }
  return root;
}

}  // namespace fastron::detail
