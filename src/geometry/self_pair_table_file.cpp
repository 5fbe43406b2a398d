#include "fastron/geometry/self_pair_table_file.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"

namespace fastron {
namespace {

constexpr std::string_view kFirstLine = "fastron self-pair tables 1";
constexpr std::size_t kMaxTables = 1 << 16;

void putHex(std::string& out, double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", value);
  out += text;
}

/// Reads the file line by line; every error names the file and the line.
class Lines {
 public:
  Lines(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw FileError(file_ + ":" + std::to_string(line_) + ": " + what);
  }

  /// The next line; fails as cut short at the end of the file.
  std::string_view next(const char* expected) {
    if (at_ >= text_.size()) {
      ++line_;
      fail(std::string("the file ends where ") + expected + " should be");
    }
    const std::size_t end = std::min(text_.find('\n', at_), text_.size());
    const std::string_view line = text_.substr(at_, end - at_);
    at_ = end + 1;
    ++line_;
    return line;
  }

  /// The words of the next line, which must start with `keyword` and have `count` more.
  std::vector<std::string_view> fields(std::string_view keyword, std::size_t count) {
    const std::string_view line = next(std::string(keyword).c_str());
    std::vector<std::string_view> words;
    for (std::size_t i = 0; i < line.size();) {
      const std::size_t end = std::min(line.find(' ', i), line.size());
      if (end > i) words.push_back(line.substr(i, end - i));
      i = end + 1;
    }
    if (words.empty() || words[0] != keyword || words.size() != count + 1) {
      fail("expected '" + std::string(keyword) + "' and " + std::to_string(count) +
           " values, found '" + std::string(line.substr(0, 80)) + "'");
    }
    words.erase(words.begin());
    return words;
  }

  double number(std::string_view word, const char* field) const {
    const std::string text(word);
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE ||
        !std::isfinite(value))
      fail(std::string(field) + " '" + text.substr(0, 40) + "' is not a finite number");
    return value;
  }

  std::uint64_t integer(std::string_view word, const char* field, int base = 10) const {
    const std::string text(word);
    char* end = nullptr;
    errno = 0;
    const unsigned long long value = std::strtoull(text.c_str(), &end, base);
    if (text.empty() || text[0] == '-' || end != text.c_str() + text.size() || errno == ERANGE)
      fail(std::string(field) + " '" + text.substr(0, 40) + "' is not a whole number");
    return value;
  }

  bool done() const { return at_ >= text_.size(); }

 private:
  std::string_view text_;
  std::string file_;
  std::size_t at_ = 0;
  std::size_t line_ = 0;
};

}  // namespace

void saveSelfPairTables(const SelfPairTableFile& file, const std::filesystem::path& path) {
  std::string out(kFirstLine);
  char key[32];
  std::snprintf(key, sizeof key, "\nkey %016llx\n", static_cast<unsigned long long>(file.key));
  out += key;
  out += "tables " + std::to_string(file.tables.size()) + "\n";
  for (const SelfPairTable& t : file.tables) {
    out += "table " + std::to_string(t.shapeA) + " " + std::to_string(t.shapeB) + " " +
           std::to_string(t.axes) + "\n";
    for (std::size_t k = 0; k < t.axes; ++k) {
      out += "axis " + std::to_string(t.coordinate[k]) + " ";
      putHex(out, t.lower[k]);
      out += ' ';
      putHex(out, t.spacing[k]);
      out += ' ';
      putHex(out, t.lever[k]);
      out += " " + std::to_string(t.nodes[k]) + "\n";
    }
    for (const float d : t.distance) {
      putHex(out, static_cast<double>(d));  // exact: a float is a double
      out += '\n';
    }
  }
  out += "end\n";
  writeFileAtomically(path, out, "self-pair tables");
}

SelfPairTableFile loadSelfPairTables(const std::filesystem::path& path) {
  return parseSelfPairTables(readFile(path, "self-pair tables"), path.string());
}

SelfPairTableFile parseSelfPairTables(std::string_view text, const std::string& source) {
  Lines lines(text, source);
  if (lines.next("the first line") != kFirstLine)
    lines.fail("not a self-pair table file of version 1 (the first line must be '" +
               std::string(kFirstLine) + "')");
  SelfPairTableFile file;
  file.key = lines.integer(lines.fields("key", 1)[0], "key", 16);
  const std::uint64_t count = lines.integer(lines.fields("tables", 1)[0], "table count");
  if (count > kMaxTables) lines.fail("table count " + std::to_string(count) + " is too large");
  for (std::uint64_t i = 0; i < count; ++i) {
    SelfPairTable t;
    const auto head = lines.fields("table", 3);
    t.shapeA = lines.integer(head[0], "shape");
    t.shapeB = lines.integer(head[1], "shape");
    t.axes = lines.integer(head[2], "axes");
    if (t.axes < 1 || t.axes > 2) lines.fail("axes must be 1 or 2");
    std::size_t nodes = 1;
    for (std::size_t k = 0; k < t.axes; ++k) {
      const auto axis = lines.fields("axis", 5);
      t.coordinate[k] = lines.integer(axis[0], "coordinate");
      t.lower[k] = lines.number(axis[1], "first node");
      t.spacing[k] = lines.number(axis[2], "spacing");
      t.lever[k] = lines.number(axis[3], "lever");
      t.nodes[k] = lines.integer(axis[4], "nodes");
      if (t.nodes[k] == 0 || t.nodes[k] > (std::size_t{1} << 24) / nodes)
        lines.fail("node count " + std::to_string(t.nodes[k]) + " is out of range");
      nodes *= t.nodes[k];
    }
    t.distance.resize(nodes);
    for (float& d : t.distance) {
      const double value = lines.number(lines.next("a distance"), "distance");
      d = static_cast<float>(value);
      if (static_cast<double>(d) != value) lines.fail("a distance is not a float");
    }
    try {
      checkSelfPairTable(t, std::numeric_limits<std::size_t>::max(),
                         std::numeric_limits<std::size_t>::max(), source);
    } catch (const InvalidArgument& e) {
      throw FileError(e.what());
    }
    file.tables.push_back(std::move(t));
  }
  if (lines.next("'end'") != "end") lines.fail("expected 'end' after the tables");
  if (!lines.done()) lines.fail("text after 'end'");
  return file;
}

}  // namespace fastron
