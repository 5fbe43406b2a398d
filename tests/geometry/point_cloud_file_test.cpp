// Point-cloud and OctoMap files: hand-made files of each format read back, and every malformed
// file refused with a message naming it.

#include "fastron/geometry/point_cloud_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <cstring>
#include <sstream>

#include "fastron/core/error.h"
#include "fastron/core/npy.h"
#include "fastron/geometry/point_cloud.h"
#include "fastron/geometry/scene_file.h"
#include "temp_dir.h"

namespace fastron {
namespace cloud_file_test {

using ::testing::HasSubstr;

const std::vector<Eigen::Vector3d> kPoints = {{0.5, -0.25, 1.0}, {0.0, 0.125, -2.0}, {3, 4, 5}};

template <class T>
std::string binary(std::initializer_list<T> values) {
  std::string out;
  for (const T v : values) out.append(reinterpret_cast<const char*>(&v), sizeof v);
  return out;
}

std::string messageOf(std::string_view bytes, CloudFormat format) {
  try {
    (void)parseCloudFile(bytes, format, "c.file");
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

void expectPoints(const CloudFile& file) {
  ASSERT_EQ(file.points.points.size(), kPoints.size());
  for (std::size_t i = 0; i < kPoints.size(); ++i)
    EXPECT_TRUE(file.points.points[i].isApprox(kPoints[i])) << i;
}

TEST(CloudFiles, NpyOfDoublesAndOfFloats) {
  std::vector<double> values;
  for (const auto& p : kPoints) values.insert(values.end(), p.data(), p.data() + 3);
  expectPoints(parseCloudFile(npyBytes(values.data(), 3, 3), CloudFormat::Npy, "c.npy"));
  std::string floats = npyBytes(values.data(), 3, 3);
  // The same header with <f4 and the values as floats.
  const std::size_t descr = floats.find("<f8");
  floats.replace(descr, 3, "<f4");
  const std::size_t dataStart = floats.size() - 9 * sizeof(double);
  floats.resize(dataStart);
  for (const double v : values) floats += binary<float>({static_cast<float>(v)});
  expectPoints(parseCloudFile(floats, CloudFormat::Npy, "c.npy"));
}

TEST(CloudFiles, AnEmptyNpyIsAnEmptyCloud) {
  const CloudFile file = parseCloudFile(npyBytes(nullptr, 0, 3), CloudFormat::Npy, "c.npy");
  EXPECT_TRUE(file.points.points.empty());
}

TEST(CloudFiles, PlyAsciiAndBinary) {
  const std::string ascii =
      "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nproperty uchar red\nelement face 0\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0.5 -0.25 1 255\n0 0.125 -2 0\n3 4 5 7\n";
  expectPoints(parseCloudFile(ascii, CloudFormat::Ply, "c.ply"));
  std::string bin =
      "ply\r\nformat binary_little_endian 1.0\r\nelement camera 1\r\nproperty int id\r\n"
      "element vertex 3\r\nproperty double x\r\nproperty float y\r\nproperty float z\r\n"
      "end_header\r\n";
  bin += binary<std::int32_t>({42});
  for (const auto& p : kPoints)
    bin += binary<double>({p.x()}) +
           binary<float>({static_cast<float>(p.y()), static_cast<float>(p.z())});
  expectPoints(parseCloudFile(bin, CloudFormat::Ply, "c.ply"));
}

TEST(CloudFiles, PcdAsciiBinaryAndOrganised) {
  const std::string header =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\n"
      "COUNT 1 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\n";
  expectPoints(parseCloudFile(header + "DATA ascii\n0.5 -0.25 1 9\n0 0.125 -2 9\n3 4 5 9\n",
                              CloudFormat::Pcd, "c.pcd"));
  std::string bin = header + "DATA binary\n";
  for (const auto& p : kPoints)
    bin += binary<float>(
        {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()), 1.0F});
  expectPoints(parseCloudFile(bin, CloudFormat::Pcd, "c.pcd"));
  // An organised cloud: NaN marks a pixel without a return, and is skipped.
  const std::string organised =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 2\nPOINTS 4\nDATA ascii\n"
      "0.5 -0.25 1\nnan nan nan\n0 0.125 -2\n3 4 5\n";
  expectPoints(parseCloudFile(organised, CloudFormat::Pcd, "c.pcd"));
}

std::string octomapFile(bool binaryFormat) {
  octomap::OcTree tree(0.1);
  tree.updateNode(octomap::point3d(0.05F, 0.05F, 0.05F), true);
  tree.updateNode(octomap::point3d(0.55F, -0.25F, 0.35F), true);
  tree.updateNode(octomap::point3d(-0.45F, 0.15F, 0.25F), false);  // free: no point
  std::ostringstream out;
  if (binaryFormat) {
    tree.writeBinary(out);
  } else {
    tree.write(out);
  }
  return out.str();
}

TEST(CloudFiles, OctomapsGiveTheirOccupiedVoxelCentres) {
  for (const bool binaryFormat : {true, false}) {
    const CloudFile file =
        parseCloudFile(octomapFile(binaryFormat),
                       binaryFormat ? CloudFormat::OctomapBinary : CloudFormat::OctomapFull, "m");
    EXPECT_DOUBLE_EQ(file.voxelSize, 0.1);
    ASSERT_EQ(file.points.points.size(), 2u) << binaryFormat;
    for (const auto& p : file.points.points) {
      const bool first = p.isApprox(Eigen::Vector3d(0.05, 0.05, 0.05), 1e-6);
      const bool second = p.isApprox(Eigen::Vector3d(0.55, -0.25, 0.35), 1e-6);
      EXPECT_TRUE(first || second) << p.transpose();
    }
  }
}

TEST(CloudFiles, TruncatedOrCorruptOctomapsAreRefused) {
  const std::string whole = octomapFile(true);
  EXPECT_THAT(messageOf(whole.substr(0, whole.size() - 3), CloudFormat::OctomapBinary),
              HasSubstr("truncated OctoMap data"));
  std::string deep = whole.substr(0, whole.find("data\n") + 5);
  for (int i = 0; i < 40; ++i) deep += std::string("\xff\xff", 2);  // inner nodes without end
  EXPECT_THAT(messageOf(deep, CloudFormat::OctomapBinary), HasSubstr("deeper than the tree"));
  EXPECT_THAT(messageOf("# Octomap OcTree binary file\nid ColorOcTree\nres 0.1\ndata\n",
                        CloudFormat::OctomapBinary),
              HasSubstr("'ColorOcTree' is not supported"));
  EXPECT_THAT(messageOf("not a map", CloudFormat::OctomapFull), HasSubstr("not an OctoMap"));
}

TEST(CloudFiles, BadCloudsGetOneLineErrors) {
  const double nanRow[] = {0, 0, 0, std::nan(""), 1, 2};
  EXPECT_THAT(messageOf(npyBytes(nanRow, 2, 3), CloudFormat::Npy),
              HasSubstr("c.file: point 1 is not finite"));
  EXPECT_THAT(messageOf(npyBytes(nanRow, 3, 2), CloudFormat::Npy),
              HasSubstr("expected an (n, 3) array of points, got shape (3, 2)"));
  const std::string plyHeader =
      "ply\nformat binary_little_endian 1.0\nelement vertex 100000000\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  EXPECT_THAT(messageOf(plyHeader + std::string(1000, '\0'), CloudFormat::Ply),
              HasSubstr("truncated PLY data"));
  EXPECT_THAT(messageOf("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty "
                        "float y\nproperty float z\nend_header\n1 2 3\n",
                        CloudFormat::Ply),
              HasSubstr("truncated PLY data: 1 of 2 vertices"));
  EXPECT_THAT(messageOf("ply\nformat binary_big_endian 1.0\nend_header\n", CloudFormat::Ply),
              HasSubstr("c.file:2: PLY format 'binary_big_endian' is not supported"));
  EXPECT_THAT(
      messageOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n",
                CloudFormat::Ply),
      HasSubstr("no 'y' property"));
  const std::string pcdHeader =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 100000000\nHEIGHT 1\nPOINTS 100000000\n";
  EXPECT_THAT(messageOf(pcdHeader + "DATA binary\n" + std::string(1000, '\0'), CloudFormat::Pcd),
              HasSubstr("truncated PCD data"));
  EXPECT_THAT(messageOf(pcdHeader + "DATA binary_compressed\n", CloudFormat::Pcd),
              HasSubstr("PCD DATA 'binary_compressed' is not supported"));
  EXPECT_THAT(messageOf("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
                        "DATA ascii\n1 nan 2\n",
                        CloudFormat::Pcd),
              HasSubstr("c.file:8: point 0 is not finite"));
  EXPECT_THAT(messageOf("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 two 2\n",
                        CloudFormat::Pcd),
              HasSubstr("c.file:6: 'two' is not a number"));
  EXPECT_THAT(messageOf("FIELDS x y\nSIZE 4 4\nTYPE F F\nPOINTS 0\nDATA ascii\n", CloudFormat::Pcd),
              HasSubstr("no 'z' field"));
  EXPECT_THROW((void)cloudFormatOf("cloud.xyz"), FileError);
}

TEST(VoxelDownsample, EveryPointLiesNearAKeptPoint) {
  CloudPoints cloud;
  Rng rng(4);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int i = 0; i < 5000; ++i) cloud.points.emplace_back(u(rng), u(rng), 0.1 * u(rng));
  const double voxel = 0.05;
  const CloudPoints kept = voxelDownsample(cloud, voxel);
  EXPECT_LT(kept.points.size(), 20u * 20u * 3u + 1);
  EXPECT_GT(kept.points.size(), 100u);
  for (const auto& p : cloud.points) {
    double nearest = 1e9;
    for (const auto& k : kept.points) nearest = std::min(nearest, (p - k).norm());
    ASSERT_LE(nearest, voxel * std::sqrt(3.0) + 1e-12);
  }
  EXPECT_EQ(voxelDownsample(cloud, 0).points.size(), cloud.points.size());
  EXPECT_THROW((void)voxelDownsample(cloud, -1), InvalidArgument);
  EXPECT_THROW((void)voxelDownsample(cloud, 1e-9), InvalidArgument);  // 2^20 voxels away
  cloud.points[7].y() = std::nan("");
  EXPECT_THAT([&] { (void)voxelDownsample(cloud, voxel); },
              ::testing::ThrowsMessage<InvalidArgument>(HasSubstr("point 7")));
}

class SensedSceneFiles : public test::TempDir {};

TEST_F(SensedSceneFiles, BothSceneFormatsTakePointCloudsAndOctomaps) {
  std::vector<double> values;
  for (const auto& p : kPoints) values.insert(values.end(), p.data(), p.data() + 3);
  write("cloud.npy", npyBytes(values.data(), 3, 3));
  write("map.bt", octomapFile(true));
  const std::string sensed =
      "point_clouds:\n  - {id: camera, file: cloud.npy, radius: 0.01, position: [1, 0, 0]}\n"
      "octomaps:\n  - {id: map, file: map.bt}\n";
  const Scene own = loadScene(write("own.yaml", "obstacles: []\n" + sensed));
  const Scene moveit =
      loadScene(write("moveit.yaml", "world:\n  collision_objects: []\n" + sensed));
  for (const Scene* scene : {&own, &moveit}) {
    ASSERT_EQ(scene->size(), 2u);
    const auto& camera = std::get<PointCloud>(scene->obstacle("camera").shape);
    EXPECT_EQ(camera.cloud->points.size(), 3u);
    EXPECT_DOUBLE_EQ(camera.radius, 0.01);
    EXPECT_DOUBLE_EQ(scene->obstacle("camera").pose.translation().x(), 1.0);
    const auto& map = std::get<PointCloud>(scene->obstacle("map").shape);
    EXPECT_EQ(map.cloud->points.size(), 2u);
    EXPECT_NEAR(map.radius, 0.1 * std::sqrt(3.0) / 2, 1e-12);  // covers each voxel
  }
  try {
    (void)loadScene(
        write("bad.yaml", "point_clouds:\n  - {id: c, file: missing.npy, radius: 1}\n"));
    FAIL();
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.yaml:2"));
    EXPECT_THAT(e.what(), HasSubstr("point cloud 'c'"));
  }
}

}  // namespace cloud_file_test
}  // namespace fastron
