#include "octomap_file.h"

#include <octomap/OcTree.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>

#include "fastron/core/error.h"

namespace fastron {
namespace {

constexpr int kTreeDepth = 16;  // every OcTree's

struct OctomapHeader {
  std::string id;
  double resolution = 0;
  std::size_t dataStart = 0;
};

OctomapHeader octomapHeader(std::string_view bytes, bool binary, const std::string& source) {
  const std::string_view magic = binary ? "# Octomap OcTree binary file" : "# Octomap OcTree file";
  if (!bytes.starts_with(magic))
    throw FileError(source + ": not an OctoMap " + (binary ? ".bt" : ".ot") +
                    " file (its first line is not '" + std::string(magic) + "')");
  OctomapHeader header;
  std::size_t position = 0, line = 0;
  while (position < bytes.size()) {
    const std::size_t end = bytes.find('\n', position);
    if (end == std::string_view::npos) break;
    std::string_view text = bytes.substr(position, end - position);
    position = end + 1;
    ++line;
    if (text.ends_with('\r')) text.remove_suffix(1);
    const std::string where = source + ":" + std::to_string(line);
    if (text.empty() || text.starts_with('#')) continue;
    if (text == "data") {
      if (header.id.empty()) throw FileError(where + ": the OctoMap header has no 'id' line");
      if (!(header.resolution > 0))
        throw FileError(where + ": the OctoMap header has no positive 'res'");
      header.dataStart = position;
      return header;
    }
    const std::size_t space = text.find(' ');
    const std::string_view key = text.substr(0, space);
    const std::string_view value =
        space == std::string_view::npos ? std::string_view() : text.substr(space + 1);
    if (key == "id") {
      header.id = std::string(value);
      if (header.id != "OcTree")
        throw FileError(where + ": OctoMap tree type '" + header.id +
                        "' is not supported (OcTree)");
    } else if (key == "res") {
      const auto [ptr, error] =
          std::from_chars(value.data(), value.data() + value.size(), header.resolution);
      if (error != std::errc() || !std::isfinite(header.resolution) || header.resolution <= 0)
        throw FileError(where + ": 'res " + std::string(value) + "' is not a positive number");
    } else if (key != "size") {
      throw FileError(where + ": unknown OctoMap header line '" + std::string(text) + "'");
    }
  }
  throw FileError(source + ": the OctoMap header has no 'data' line");
}

/// Walks the node data as octomap will read it, without building anything: every node within
/// the bytes and the tree's depth. Counts the voxels its occupied leaves cover.
class StructureCheck {
 public:
  StructureCheck(std::string_view data, bool binary, std::string source, std::size_t maxVoxels)
      : data_(data), binary_(binary), source_(std::move(source)), maxVoxels_(maxVoxels) {}

  std::size_t voxels() {
    if (binary_) {
      binaryNode(0);
    } else {
      fullNode(0);
    }
    return voxels_;
  }

 private:
  unsigned char byte() {
    if (position_ >= data_.size()) throw FileError(source_ + ": truncated OctoMap data");
    return static_cast<unsigned char>(data_[position_++]);
  }
  void addVoxels(int depth) {
    const std::size_t n = std::size_t{1} << (3 * (kTreeDepth - depth));
    if (n > maxVoxels_ || voxels_ > maxVoxels_ - n)
      throw FileError(source_ + ": the OctoMap's occupied space holds more than " +
                      std::to_string(maxVoxels_) + " voxels of its resolution");
    voxels_ += n;
  }
  // A .bt inner node at `depth`: two bits per child (01 occupied leaf, 10 free leaf, 11 inner).
  void binaryNode(int depth) {
    if (depth >= kTreeDepth) throw FileError(source_ + ": OctoMap data deeper than the tree");
    const unsigned bits = byte() | static_cast<unsigned>(byte()) << 8;
    // octomap reads every inner node as occupied, and then gives it its children's largest
    // occupancy: all but the root, which without children stays an occupied leaf.
    if (bits == 0 && depth == 0) addVoxels(0);
    for (int child = 0; child < 8; ++child) {
      const unsigned code = bits >> (2 * child) & 3U;
      if (code == 2) addVoxels(depth + 1);  // bit 2c clear, bit 2c+1 set: occupied
    }
    for (int child = 0; child < 8; ++child) {
      if ((bits >> (2 * child) & 3U) == 3) binaryNode(depth + 1);
    }
  }
  // A .ot node at `depth`: its log-odds (float), then one bit per child that follows.
  void fullNode(int depth) {
    if (depth > kTreeDepth) throw FileError(source_ + ": OctoMap data deeper than the tree");
    unsigned char value[sizeof(float)];
    for (unsigned char& b : value) b = byte();
    float logOdds = 0;
    std::memcpy(&logOdds, value, sizeof logOdds);
    const unsigned children = byte();
    if (children != 0 && depth == kTreeDepth)
      throw FileError(source_ + ": OctoMap data deeper than the tree");
    if (children == 0 && logOdds >= 0) addVoxels(depth);
    for (int child = 0; child < 8; ++child) {
      if ((children >> child & 1U) != 0) fullNode(depth + 1);
    }
  }

  std::string_view data_;
  bool binary_;
  std::string source_;
  std::size_t maxVoxels_;
  std::size_t position_ = 0, voxels_ = 0;
};

}  // namespace

OctomapVoxels octomapVoxels(std::string_view bytes, bool binary, const std::string& source,
                            std::size_t maxVoxels) {
  const OctomapHeader header = octomapHeader(bytes, binary, source);
  const std::string_view data = bytes.substr(header.dataStart);
  OctomapVoxels out;
  out.resolution = header.resolution;
  if (data.empty()) return out;  // octomap writes no node for an empty tree
  const std::size_t voxels = StructureCheck(data, binary, source, maxVoxels).voxels();
  octomap::OcTree tree(header.resolution);
  std::istringstream stream{std::string(data)};
  if (binary) {
    tree.readBinaryData(stream);
  } else {
    tree.readData(stream);
  }
  out.centres.reserve(voxels);
  for (auto leaf = tree.begin_leafs(), end = tree.end_leafs(); leaf != end; ++leaf) {
    if (!tree.isNodeOccupied(*leaf)) continue;
    // A pruned leaf stands for all the voxels of its cube.
    const double size = leaf.getSize();
    const auto n = static_cast<int>(std::lround(size / header.resolution));
    const Eigen::Vector3d corner = Eigen::Vector3d(leaf.getX(), leaf.getY(), leaf.getZ()).array() -
                                   size / 2 + header.resolution / 2;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k)
          out.centres.push_back(corner + header.resolution * Eigen::Vector3d(i, j, k));
  }
  return out;
}

}  // namespace fastron
