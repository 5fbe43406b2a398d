#pragma once
// The keys and files of the caches kept per robot (the self-collision model, the self-pair
// tables): what a robot's collision answers depend on, hashed.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "fastron/geometry/robot.h"

namespace fastron::pipeline {

/// 64-bit FNV-1a, fed field by field.
class Hash {
 public:
  void bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      h_ ^= p[i];
      h_ *= 1099511628211ULL;
    }
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  void doubles(const double* v, std::size_t n) { bytes(v, n * sizeof(double)); }
  std::uint64_t digest() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ULL;
};

/// Feeds `h` the robot's kinematics (kinematicsChecksum: links, joints, held positions, actuated
/// joints, mimics), its collision shapes on their links, and the link pairs its description
/// allows (an SRDF's disabled collisions, a catalogue's pairs): a changed URDF or SRDF changes it.
void hashRobotCollisions(Hash& h, const Robot& robot);

/// NAME-KEY.EXTENSION (KEY in 16 hex digits) in `directory`, or in defaultCacheDirectory() when it
/// is empty.
std::filesystem::path cacheFile(const std::filesystem::path& directory, const Robot& robot,
                                std::uint64_t key, std::string_view extension);

}  // namespace fastron::pipeline
