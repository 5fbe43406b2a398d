// URDF robots (fastron::parseUrdf). Meshes named by the input are looked up from the working
// folder and not found there: the target reaches the mesh checks without reading other files.
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/urdf.h"
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  fuzz::readOrRefuse("fuzz.urdf", [&] {
    const Robot robot = parseUrdf(fuzz::textOf(data, size), "fuzz.urdf");
    // A robot that loads has sane limits and poses every link finitely in the middle of them.
    std::vector<double> q;
    for (const int j : robot.actuatedJoints()) {
      const Joint& joint = robot.joints()[static_cast<std::size_t>(j)];
      if (!(joint.lower <= joint.upper) || !std::isfinite(joint.lower) ||
          !std::isfinite(joint.upper))
        fuzz::finding("a joint without finite lower <= upper was accepted", joint.name);
      q.push_back((joint.lower + joint.upper) / 2);
    }
    KinematicsData kinematics = makeKinematicsData(robot);
    forwardKinematics(robot, q.data(), kinematics);
    for (const auto& pose : kinematics.linkPoses)
      if (!pose.matrix().allFinite()) fuzz::finding("a link pose is not finite", robot.name());
  });
  return 0;
}
