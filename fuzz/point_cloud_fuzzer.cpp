// Point-cloud and OctoMap files (fastron::parseCloudFile): the first byte picks the format
// (.npy, .ply, .pcd, .bt, .ot), the rest is the file.
#include <cmath>

#include "fastron/geometry/point_cloud_file.h"
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  if (size == 0) return 0;
  const auto format = static_cast<CloudFormat>(data[0] % 5);
  fuzz::readOrRefuse("fuzz.cloud", [&] {
    // A small cap: an OctoMap of a few bytes may describe millions of voxels, legitimately.
    const CloudFile file =
        parseCloudFile(fuzz::textOf(data + 1, size - 1), format, "fuzz.cloud", 100'000);
    for (const auto& p : file.points.points) {
      if (!p.allFinite()) fuzz::finding("a point is not finite", "");
    }
    if (format == CloudFormat::OctomapBinary || format == CloudFormat::OctomapFull) {
      if (!(file.voxelSize > 0) && !file.points.points.empty())
        fuzz::finding("an OctoMap without a resolution", "");
    }
  });
  return 0;
}
