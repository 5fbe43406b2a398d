#include "fastron/core/model_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include "fastron/core/error.h"
#include "fastron/core/trainer.h"
#include "temp_dir.h"
#include "test_worlds.h"

namespace fastron {
namespace {

using test::messageOf;
using ::testing::HasSubstr;

class ModelFile : public test::TempDir {
 protected:
  Model sampleModel() const {
    const Configurations q = test::uniformPoints(600, 3, 1);
    const JointLimits limits(Eigen::Vector3d(-1, 0, -3), Eigen::Vector3d(2, 1, 3));
    Trainer trainer(limits, TrainParams{.kernel = {KernelType::Gaussian, 12}, .beta = 3});
    trainer.addPoints(limits.toJoint(q), test::BallWorld::random(3, 3, 0.5, 2).label(q));
    trainer.update();
    return *trainer.model();
  }
};

TEST_F(ModelFile, RoundTripKeepsEveryValue) {
  const Model model = sampleModel();
  ASSERT_GT(model.supportCount(), 10u);
  saveModel(model, path("m.fastron"));
  const Model loaded = loadModel(path("m.fastron"), 3);
  EXPECT_EQ(loaded.kernel().type, KernelType::Gaussian);
  EXPECT_EQ(loaded.kernel().gamma, 12);
  EXPECT_TRUE(loaded.limits() == model.limits());
  EXPECT_EQ(loaded.supportConfigurations(), model.supportConfigurations());
  EXPECT_EQ(loaded.weights(), model.weights());
  const std::vector<double> q{0.3, 0.2, 1};
  EXPECT_EQ(loaded.score(q), model.score(q));
}

TEST_F(ModelFile, EmptyModelRoundTrips) {
  const Model empty(FeatureMap::jointScaling(JointLimits::unitBox(2)), Kernel{},
                    Configurations(0, 2), Eigen::VectorXd(0));
  saveModel(empty, path("e.fastron"));
  EXPECT_EQ(loadModel(path("e.fastron")).supportCount(), 0u);
}

TEST_F(ModelFile, MissingFileIsNamed) {
  EXPECT_THAT(messageOf<FileError>([&] { loadModel(path("absent.fastron")); }),
              HasSubstr("absent.fastron: cannot open"));
}

TEST_F(ModelFile, EveryTruncationIsRefused) {
  saveModel(sampleModel(), path("m.fastron"));
  const std::string bytes = read(path("m.fastron"));
  for (std::size_t size = 0; size < bytes.size(); size += (size < 200 ? 1 : 97)) {
    write("t.fastron", bytes.substr(0, size));
    const std::string message = messageOf<FileError>([&] { loadModel(path("t.fastron")); });
    EXPECT_THAT(message, HasSubstr("t.fastron")) << "size " << size;
  }
  write("t.fastron", bytes.substr(0, bytes.size() - 1));
  EXPECT_THAT(messageOf<FileError>([&] { loadModel(path("t.fastron")); }), HasSubstr("truncated"));
}

TEST_F(ModelFile, CorruptBytesFailTheChecksum) {
  saveModel(sampleModel(), path("m.fastron"));
  std::string bytes = read(path("m.fastron"));
  for (const std::size_t at : {std::size_t{40}, bytes.size() / 2, bytes.size() - 9}) {
    std::string corrupt = bytes;
    corrupt[at] = static_cast<char>(corrupt[at] ^ 0x10);
    write("c.fastron", corrupt);
    EXPECT_THAT(messageOf<FileError>([&] { loadModel(path("c.fastron")); }), HasSubstr("checksum"))
        << "byte " << at;
  }
  bytes.push_back('x');
  write("c.fastron", bytes);
  EXPECT_THAT(messageOf<FileError>([&] { loadModel(path("c.fastron")); }), HasSubstr("trailing"));
}

TEST_F(ModelFile, WrongMagicVersionAndDimensionAreNamed) {
  write("text.fastron", "x1,x2,label\n0,0,1\n");
  EXPECT_THAT(messageOf<FileError>([&] { loadModel(path("text.fastron")); }), HasSubstr("magic"));

  saveModel(sampleModel(), path("m.fastron"));
  std::string bytes = read(path("m.fastron"));
  bytes[8] = 7;  // version
  write("v.fastron", bytes);
  EXPECT_THAT(messageOf<FileError>([&] { loadModel(path("v.fastron")); }),
              HasSubstr("unsupported model file version 7"));

  EXPECT_THAT(messageOf<FileError>([&] { loadModel(path("m.fastron"), 7); }),
              HasSubstr("model has dimension 3 but 7 was expected"));
}

// Version 1 files (support points in input space [-1, 1]^d, no feature block) still load, as
// joint-space models: the bytes are written here by hand, as version 1 laid them out.
TEST_F(ModelFile, VersionOneStillLoads) {
  std::string bytes("FASTRON\0", 8);
  auto put = [&bytes](const auto value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof(value));
  };
  put(std::uint32_t{1});  // version
  put(std::uint32_t{2});  // dimension
  put(std::uint32_t{0});  // rational quadratic
  put(std::uint32_t{0});  // reserved
  put(2.0);               // gamma
  put(0.0), put(-2.0);    // lower limits
  put(4.0), put(2.0);     // upper limits
  put(std::uint64_t{2});
  put(0.5), put(0.0);    // support point 1, input space: joint values (3, 0)
  put(-1.0), put(1.0);   // support point 2: joint values (0, 2)
  put(1.5), put(-0.25);  // weights
  put(static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size()))));
  write("v1.fastron", bytes);

  EXPECT_EQ(readModelHeader(path("v1.fastron")).version, 1u);
  const Model model = loadModel(path("v1.fastron"), 2);
  EXPECT_EQ(model.features().kind(), FeatureKind::JointScaling);
  ASSERT_EQ(model.supportCount(), 2u);
  EXPECT_NEAR(model.supportConfigurations()(0, 0), 3, 1e-12);
  EXPECT_NEAR(model.supportConfigurations()(1, 1), 2, 1e-12);
  const std::vector<double> q{3, 0};  // on the first support point, r2 = 2.25 + 1 to the second
  const double expected = 1.5 - 0.25 / ((1 + 3.25) * (1 + 3.25));
  EXPECT_NEAR(model.scoreExact(q.data()), expected, 1e-12);

  // Saved again, it becomes version 3 with the same contents.
  saveModel(model, path("v3.fastron"));
  EXPECT_EQ(readModelHeader(path("v3.fastron")).version, 3u);
  EXPECT_EQ(loadModel(path("v3.fastron")).scoreExact(q.data()), model.scoreExact(q.data()));
}

// Version 2 is version 3 without the kernel's point terms (block and share, 12 bytes after
// gamma): made here from a version 3 file by removing them, it loads with a one-term kernel.
TEST_F(ModelFile, VersionTwoStillLoads) {
  const Model model = sampleModel();
  saveModel(model, path("m.fastron"));
  std::string bytes = read(path("m.fastron"));
  constexpr std::size_t kGammaEnd = 8 + 4 + 4 + 8 + 4 + 4 + 8;
  bytes.erase(kGammaEnd, 12);
  bytes[8] = 2;
  const std::uint64_t size = bytes.size();
  bytes.replace(16, 8, reinterpret_cast<const char*>(&size), 8);
  const auto crc = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size() - 4)));
  bytes.replace(bytes.size() - 4, 4, reinterpret_cast<const char*>(&crc), 4);
  write("v2.fastron", bytes);

  EXPECT_EQ(readModelHeader(path("v2.fastron")).version, 2u);
  const Model loaded = loadModel(path("v2.fastron"), 3);
  EXPECT_EQ(loaded.kernel().block, 0u);
  EXPECT_EQ(loaded.weights(), model.weights());
  const std::vector<double> q{0.3, 0.2, 1};
  EXPECT_EQ(loaded.score(q), model.score(q));
}

TEST_F(ModelFile, KernelPointTermsRoundTripAndABadBlockIsRefused) {
  // Six features, two blocks of three (any features may have point terms).
  const Configurations q = test::uniformPoints(800, 6, 4);
  const Kernel kernel{KernelType::RationalQuadratic, 20, 3, 0.25};
  Trainer trainer(JointLimits::unitBox(6), TrainParams{.kernel = kernel, .beta = 2});
  trainer.addPoints(q, test::randomLabels(800, 5));
  trainer.update();
  ASSERT_GT(trainer.supportCount(), 10u);
  saveModel(*trainer.model(), path("k.fastron"));
  const Model loaded = loadModel(path("k.fastron"), 6);
  EXPECT_EQ(loaded.kernel().block, 3u);
  EXPECT_EQ(loaded.kernel().wholeShare, 0.25);
  const std::vector<double> x{0.3, -0.2, 0.6, 0.1, 0, -0.9};
  EXPECT_EQ(loaded.score(x), trainer.model()->score(x));

  // A block of 4 does not divide 6 features: the file is invalid, and says why.
  std::string bytes = read(path("k.fastron"));
  constexpr std::size_t kBlockAt = 8 + 4 + 4 + 8 + 4 + 4 + 8;
  bytes[kBlockAt] = 4;
  const auto crc = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size() - 4)));
  bytes.replace(bytes.size() - 4, 4, reinterpret_cast<const char*>(&crc), 4);
  write("b.fastron", bytes);
  EXPECT_THAT(messageOf<FileError>([&] { loadModel(path("b.fastron")); }),
              HasSubstr("kernel block 4 does not divide the feature dimension 6"));
}

TEST_F(ModelFile, UnwritablePathIsNamed) {
  EXPECT_THAT(
      messageOf<FileError>([&] { saveModel(sampleModel(), path("no/such/dir/m.fastron")); }),
      HasSubstr("dir/m.fastron: cannot write model file"));
}

// Saving goes through a temporary file and a rename: a writer killed at any moment leaves the
// old model or the new one, whole, where the model was (with the non-atomic writer this test saw
// truncated files).
TEST_F(ModelFile, AWriterKilledWhileSavingLeavesAWholeModel) {
  const Model small = sampleModel();
  // Big enough that a save takes milliseconds, so the kills land inside writes.
  const Eigen::Index n = 100000;
  const JointLimits limits = JointLimits::unitBox(7);
  const Model big(FeatureMap::jointScaling(limits), Kernel{}, Configurations::Random(n, 7),
                  Eigen::VectorXd::Constant(n, 0.5));
  const auto file = path("m.fastron");
  saveModel(small, file);
  Rng rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    const pid_t writer = ::fork();
    ASSERT_GE(writer, 0);
    if (writer == 0) {
      for (int i = 0;; ++i) saveModel(i % 2 == 0 ? big : small, file);
    }
    ::usleep(static_cast<useconds_t>(std::uniform_int_distribution<int>(2000, 40000)(rng)));
    ::kill(writer, SIGKILL);
    ::waitpid(writer, nullptr, 0);
    const Model loaded = loadModel(file);
    EXPECT_TRUE(loaded.supportCount() == small.supportCount() ||
                loaded.supportCount() == big.supportCount())
        << loaded.supportCount();
  }
}

}  // namespace
}  // namespace fastron
