// Model files (fastron::parseModel). A mutated file almost always fails its CRC-32 first, so the
// target writes the right size and checksum into version-2 inputs and reaches the parser behind
// them; inputs without that fix-up still test the checks themselves.
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <string>

#include "fastron/core/model_file.h"
#include "fuzz_reader.h"

namespace {

constexpr std::size_t kSizeOffset = 16;  // after magic, version and dimension

/// The input with its size field and trailing CRC-32 made consistent, when it is long enough.
std::string withValidFraming(std::string bytes) {
  if (bytes.size() < kSizeOffset + 8 + 4 || bytes.compare(0, 8, std::string("FASTRON\0", 8)) != 0)
    return bytes;
  const std::uint64_t size = bytes.size();
  std::memcpy(bytes.data() + kSizeOffset, &size, sizeof size);
  const auto crc = static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size() - 4)));
  std::memcpy(bytes.data() + bytes.size() - 4, &crc, sizeof crc);
  return bytes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  const std::string raw = fuzz::textOf(data, size);
  // The first byte chooses whether the framing is repaired, so the corpus keeps both kinds.
  const std::string bytes = size > 0 && (data[0] & 1) ? withValidFraming(raw.substr(1)) : raw;
  fuzz::readOrRefuse("fuzz.fastron", [&] {
    const ModelFileHeader header = parseModelHeader(bytes, "fuzz.fastron");
    const Model model = parseModel(bytes, "fuzz.fastron");  // no kinematics: joint-space only
    if (model.dim() != header.dim) fuzz::finding("the header and the model disagree", "");
    // A model that loads answers queries.
    const Eigen::VectorXd middle = (model.limits().lower() + model.limits().upper()) / 2;
    const double score = model.score(middle.data());
    if (std::isnan(score)) fuzz::finding("a loaded model scores NaN", "");
  });
  return 0;
}
