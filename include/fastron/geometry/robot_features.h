#pragma once
// A model's features for a robot (joint scaling or control points' positions), and a model file
// read for a robot: its task-space features rebuilt from the robot's kinematics.

#include <filesystem>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/core/model.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {

/// The model's features for `robot`: joint scaling by its limits, or the world positions of
/// `points` (defaultControlPoints when empty).
FeatureMap robotFeatures(const Robot& robot, FeatureKind kind,
                         std::vector<ControlPoint> points = {});
/// The same with other joint limits than the robot's (e.g. a narrower range to sample).
FeatureMap robotFeatures(const Robot& robot, FeatureKind kind, JointLimits limits,
                         std::vector<ControlPoint> points = {});

/// Loads a model file for `robot`: a task-space model gets kinematics built from `robot` and the
/// control points the file records, and is refused (FileError naming the difference) when the
/// robot's name, actuated joints or kinematics differ from those it was trained on.
Model loadModelFor(const std::filesystem::path& path, const Robot& robot);

}  // namespace fastron
