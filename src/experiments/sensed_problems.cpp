#include "fastron/experiments/sensed_problems.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "fastron/core/npy.h"
#include "fastron/core/types.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/geometry/scene_sensing.h"

namespace fastron::experiments {
namespace {

std::vector<std::filesystem::path> sceneFiles(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> scenes;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("scene") && entry.path().extension() == ".yaml")
      scenes.push_back(entry.path());
  }
  if (error)
    throw FileError(folder.string() + ": cannot list the folder (" + error.message() + ")");
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

/// The scene file's YAML with its obstacles replaced by the cloud in `cloudFile`.
std::string sensedSceneYaml(const std::filesystem::path& scene, const std::string& cloudFile,
                            double radius) {
  YAML::Node root;
  try {
    root = YAML::Load(readFile(scene, "scene file"));
  } catch (const YAML::Exception& e) {
    throw FileError(scene.string() + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  if (root["world"]) {
    root["world"]["collision_objects"] = YAML::Node(YAML::NodeType::Sequence);
  } else {
    root["obstacles"] = YAML::Node(YAML::NodeType::Sequence);
  }
  YAML::Node cloud;
  cloud["id"] = "sensed";
  cloud["file"] = cloudFile;
  cloud["radius"] = radius;
  cloud["voxel"] = 0;  // sampled at the spacing already
  root["point_clouds"] = YAML::Node(YAML::NodeType::Sequence);
  root["point_clouds"].push_back(cloud);
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace

std::size_t writeSensedProblems(const std::filesystem::path& from, const std::filesystem::path& to,
                                const SensedProblemOptions& options) {
  if (!(options.spacing > 0) || !std::isfinite(options.spacing))
    throw InvalidArgument("sensed problems: the spacing must be positive");
  if (!(options.radius >= 0) || !std::isfinite(options.radius))
    throw InvalidArgument("sensed problems: the radius must be finite and >= 0");
  const double radius = options.radius > 0 ? options.radius : options.spacing;
  const std::vector<std::filesystem::path> scenes = sceneFiles(from);
  if (scenes.empty()) throw FileError(from.string() + ": no scene*.yaml files");
  std::error_code error;
  std::filesystem::create_directories(to, error);
  if (error) throw FileError(to.string() + ": cannot create the folder (" + error.message() + ")");
  Rng rng(options.seed);
  for (const std::filesystem::path& scene : scenes) {
    const CloudPoints cloud = surfacePoints(loadScene(scene), options.spacing, rng);
    const std::string cloudFile = scene.stem().string() + ".npy";
    writeFileAtomically(to / cloudFile,
                        npyBytes(cloud.points.empty() ? nullptr : cloud.points.front().data(),
                                 cloud.points.size(), 3),
                        "point cloud file");
    writeFileAtomically(to / scene.filename(), sensedSceneYaml(scene, cloudFile, radius),
                        "scene file");
  }
  if (!std::filesystem::equivalent(from, to)) {
    for (const auto& entry : std::filesystem::directory_iterator(from)) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with("request") && entry.path().extension() == ".yaml")
        std::filesystem::copy_file(entry.path(), to / name,
                                   std::filesystem::copy_options::overwrite_existing);
    }
  }
  return scenes.size();
}

}  // namespace fastron::experiments
