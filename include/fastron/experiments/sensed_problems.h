#pragma once
// Planning problems as a depth sensor would give their scenes: every obstacle's surface sampled
// into a point cloud, so that any MoveIt scene can be tried as a sensed one.

#include <cstdint>
#include <filesystem>

#include "fastron/core/export.h"

namespace fastron::experiments {

struct SensedProblemOptions {
  double spacing = 0.01;   ///< metres between surface points (scene_sensing.h, surfacePoints)
  double radius = 0;       ///< of each point's ball; 0: the spacing (the balls then close the gaps)
  std::uint64_t seed = 1;  ///< of the samples on mesh triangles
};

/// Rewrites the problems of `from` (MotionBenchMaker's sceneNNNN.yaml and requestNNNN.yaml, or
/// any scene files named scene*.yaml) into `to` (created; may be `from`): each scene's obstacles
/// become one point cloud "sensed", written beside it as sceneNNNN.npy and named by the scene's
/// `point_clouds` list; everything else the scene says (robot_state, allowed collisions) and the
/// requests are kept. Returns the number of scenes written. Throws FileError naming a file that
/// cannot be read or written, InvalidArgument for bad options.
std::size_t writeSensedProblems(const std::filesystem::path& from, const std::filesystem::path& to,
                                const SensedProblemOptions& options);

}  // namespace fastron::experiments
