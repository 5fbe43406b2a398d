#include "fastron/geometry/robot_features.h"

#include "fastron/core/error.h"
#include "fastron/core/model_file.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/point_kinematics.h"

namespace fastron {

FeatureMap robotFeatures(const Robot& robot, FeatureKind kind, std::vector<ControlPoint> points) {
  return robotFeatures(robot, kind, robot.limits(), std::move(points));
}

FeatureMap robotFeatures(const Robot& robot, FeatureKind kind, JointLimits limits,
                         std::vector<ControlPoint> points) {
  if (kind == FeatureKind::JointScaling) return FeatureMap::jointScaling(std::move(limits));
  if (points.empty()) points = defaultControlPoints(robot);
  return FeatureMap::kinematic(std::move(limits),
                               std::make_shared<RobotPointKinematics>(robot, std::move(points)));
}

Model loadModelFor(const std::filesystem::path& path, const Robot& robot) {
  const ModelFileHeader header = readModelHeader(path);
  std::shared_ptr<const PointKinematics> kinematics;
  if (header.features == FeatureKind::Kinematic) {
    if (header.kinematics.robot != robot.name()) {
      throw FileError(path.string() + ": the model was trained for robot '" +
                      header.kinematics.robot + "', not '" + robot.name() + "'");
    }
    try {
      kinematics = std::make_shared<RobotPointKinematics>(robot, header.kinematics.points);
    } catch (const InvalidArgument& e) {
      throw FileError(path.string() + ": the model's control points do not fit robot '" +
                      robot.name() + "': " + e.what());
    }
  }
  return loadModel(path, robot.dof(), std::move(kinematics));
}

}  // namespace fastron
