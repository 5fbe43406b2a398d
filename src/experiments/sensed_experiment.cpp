#include "fastron/experiments/sensed_experiment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "baxter_cases.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/metrics.h"
#include "fastron/core/trainer.h"
#include "fastron/experiments/report_text.h"
#include "fastron/experiments/statistics.h"
#include "fastron/experiments/timing.h"
#include "fastron/geometry/clearance_bounds.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/point_cloud.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/geometry/scene_sensing.h"
#include "fastron/planning/motion.h"
#include "fastron/proxy/labelling.h"
#include "plan_rows.h"

namespace fastron::experiments {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// A RealSense-like camera above the arm's shoulder, looking over the table at the wall.
DepthCamera sensedCamera(const SensedOptions& o) {
  DepthCamera camera;
  camera.pose = cameraLookingAt({0.0, -0.55, 1.1}, {1.0, -0.55, -0.1});
  camera.width = o.width;
  camera.height = o.height;
  camera.horizontalFieldOfView = 1.52;  // 87 degrees
  camera.maxRange = 4;
  camera.depthNoise = o.depthNoise;
  return camera;
}

/// The points of `cloud` within the arm's reach of the robot's base.
std::size_t pointsInReach(const PointCloud& cloud, const Scene& scene, double reach) {
  const Eigen::Vector3d base = scene.robotBase.translation();
  const double within = reach + cloud.radius;
  return static_cast<std::size_t>(
      std::count_if(cloud.cloud->points.begin(), cloud.cloud->points.end(),
                    [&](const Eigen::Vector3d& p) { return (p - base).norm() <= within; }));
}

const std::vector<std::string> kFrameColumns{
    "trial",         "frame",          "raw_points", "kept_points",    "reach_points",
    "camera_s",      "ingest_s",       "update_s",   "label_s",        "train_s",
    "updates_per_s", "accuracy_cloud", "tpr_cloud",  "accuracy_truth", "tpr_truth",
    "cloud_truth",   "support",        "query_s",    "fcl_query_s"};

/// The arm's link origins from the first that moves to the child of its last joint, at q.
std::vector<Eigen::Vector3d> armPolyline(const Robot& robot, const Eigen::VectorXd& q,
                                         const Scene& scene) {
  KinematicsData data = makeKinematicsData(robot);
  forwardKinematics(robot, q.data(), data, scene.robotBase);
  const auto& lastJoint = robot.joints()[static_cast<std::size_t>(robot.actuatedJoints().back())];
  std::vector<Eigen::Vector3d> chain;
  for (int link = lastJoint.child; link >= 0;) {
    chain.insert(chain.begin(), data.linkPoses[static_cast<std::size_t>(link)].translation());
    const int joint = robot.links()[static_cast<std::size_t>(link)].parentJoint;
    if (joint < 0 || !robot.joints()[static_cast<std::size_t>(joint)].movable()) break;
    link = robot.joints()[static_cast<std::size_t>(joint)].parent;
  }
  return chain;
}

/// The picture's tables: the cloud (every k-th point, at most 20000) and the plan.
void keepPicture(const PointCloud& cloud, const Robot& robot, const Scene& scene,
                 const JointPath& path, double resolution, SensedResults& results) {
  results.scene = {{"x", "y", "z"}, {}};
  const auto& points = cloud.cloud->points;
  const std::size_t every = points.size() / 20000 + 1;
  for (std::size_t i = 0; i < points.size(); i += every)
    results.scene.add({cell(points[i].x()), cell(points[i].y()), cell(points[i].z())});
  results.path = {{"kind", "x", "y", "z"}, {}};
  const auto add = [&](const char* kind, const Eigen::Vector3d& p) {
    results.path.add({kind, cell(p.x()), cell(p.y()), cell(p.z())});
  };
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const std::size_t n = segmentCount(path[k], path[k + 1], resolution);
    for (std::size_t i = 0; i <= n; ++i) {
      const Eigen::VectorXd q =
          path[k] + (path[k + 1] - path[k]) * (static_cast<double>(i) / static_cast<double>(n));
      add("path", armPolyline(robot, q, scene).back());
    }
  }
  for (const Eigen::Vector3d& p : armPolyline(robot, path.front(), scene)) add("start", p);
  for (const Eigen::Vector3d& p : armPolyline(robot, path.back(), scene)) add("goal", p);
}

/// One planning query: start and goal free of the cloud and of the true boxes; Fastron on the
/// model (verified and repaired on the cloud) and FCL on the cloud, audited against both.
/// Returns Fastron's plan.
VerifiedPlan planQuery(const SensedOptions& o, const ProxyCollisionDetector& proxy,
                       const std::shared_ptr<const SceneChecker>& onCloud,
                       const SceneChecker& onTruth, const JointLimits& limits, std::size_t trial,
                       std::size_t frame, Rng& rng, PlanRows& plans) {
  const auto freeOfBoth = [&] {
    return sampleFree(
        *onCloud,
        [&] {
          return sampleFree(
              onTruth, [&] { return uniformIn(limits, rng); }, "end");
        },
        "end free of the boxes and of the cloud");
  };
  const Eigen::VectorXd start = freeOfBoth(), goal = freeOfBoth();
  const PlannerOptions options = plannerOptions(o, PlannerType::RrtConnect);
  const auto methods = planWithEachChecker(proxy.calibratedModel(), nullptr, onCloud, limits, start,
                                           goal, options, o.seed, frame);
  const double audit = o.resolution / 3;
  for (const MethodPlan& m : methods) {
    const bool collidesCloud = m.plan.solved() && !checkPath(*onCloud, m.plan.path, audit).valid();
    plans.rows.push_back({{{"trial", std::to_string(trial)}, {"frame", std::to_string(frame)}},
                          "RRTConnect",
                          m.method,
                          outcomeOf(m, onTruth, audit),
                          {{"collides_cloud", collidesCloud ? 1.0 : 0.0},
                           {"support", static_cast<double>(proxy.model()->supportCount())}}});
  }
  return methods.front().plan;
}

}  // namespace

SensedResults runSensed(const SensedOptions& o, const Progress& progress) {
  SensedResults results{{kFrameColumns, {}}, {}};
  const Case c = caseFor("7dof-3boxes");
  const Robot robot = baxterWithJoints(c.joints);
  const JointLimits limits = robot.limits();
  const FeatureMap features = robotFeatures(robot, o.features);
  const double reach = reachBound(robot);
  const std::size_t frames = o.quick ? 4 : o.frames, tests = o.quick ? 300 : 1000;
  for (std::size_t trial = 0; trial < o.trials; ++trial) {
    const std::uint64_t seed = o.seed * 1000 + trial;
    Scene truth = sceneForTrial("baxter_sensed.yaml", seed);
    const DepthCamera camera = sensedCamera(o);
    Rng noise(seed + 17), rng(seed);
    Scene sensed;
    sensed.robotBase = truth.robotBase;
    sensed.add({"camera", sensedCloud(renderDepth(camera, truth, noise), o.radius, o.radius),
                Eigen::Isometry3d::Identity(), std::nullopt});
    const auto onCloud = makeSceneChecker("fcl", robot, sensed);
    const auto onTruth = makeSceneChecker("fcl", robot, truth);
    // The width and bias of the models of a scene's obstacles (sceneTrainParams): a cloud is
    // just that. The terms stay the pipeline's (a whole-vector term beside the points'): point
    // terms alone need points along the links' geometry, which would cost these updates' rate.
    ProxyParams params = pipeline::withoutBand(proxyParams(c, seed, o.features));
    const TrainParams ofScenes = sceneTrainParams(o.features, false);
    params.train.kernel.gamma = ofScenes.kernel.gamma;
    params.train.beta = ofScenes.beta;
    if (o.gamma > 0) params.train.kernel.gamma = o.gamma;
    if (o.beta > 0) params.train.beta = o.beta;
    if (o.activeSamples > 0) params.activeLearning.maxSamples = o.activeSamples;
    ProxyCollisionDetector proxy(onCloud, features, params);
    proxy.initialize(o.quick ? 500 : 3000);
    for (std::size_t frame = 1; frame <= frames; ++frame) {
      if (progress && (frame == 1 || frame % 10 == 0))
        progress("sensed: trial " + std::to_string(trial + 1) + "/" + std::to_string(o.trials) +
                 ", " + progressLine("frame", frame, frames));
      truth.step();
      onTruth->setScene(truth);
      const auto seeing = Clock::now();
      const CloudPoints raw = renderDepth(camera, truth, noise);
      const double cameraSeconds = secondsSince(seeing);
      const auto ingesting = Clock::now();
      PointCloud cloud = sensedCloud(raw, o.radius, o.radius);
      sensed.setShape("camera", cloud);
      onCloud->setScene(sensed);
      const double ingestSeconds = secondsSince(ingesting);
      const StepReport update = proxy.step();
      const double updateSeconds = std::chrono::duration<double>(update.total).count();

      const Configurations test = uniformConfigurations(limits, tests, rng);
      const Labels onCloudLabels = labelConfigurations(*onCloud, test);
      const Labels onTruthLabels = labelConfigurations(*onTruth, test);
      const std::shared_ptr<const Model> model = proxy.model();
      const Eigen::VectorXd scores = model->scoreBatch(test);
      const auto predicted = [&](std::size_t i) {
        return scores[static_cast<Eigen::Index>(i)] > 0;
      };
      const ConfusionCounts cloudCounts = confusionOf(onCloudLabels, predicted);
      const ConfusionCounts truthCounts = confusionOf(onTruthLabels, predicted);
      const ConfusionCounts agreement =
          confusionOf(onTruthLabels, [&](std::size_t i) { return onCloudLabels[i] > 0; });
      results.frames.add({std::to_string(trial), std::to_string(frame),
                          cell(static_cast<double>(raw.points.size())),
                          cell(static_cast<double>(cloud.cloud->points.size())),
                          cell(static_cast<double>(pointsInReach(cloud, sensed, reach))),
                          cell(cameraSeconds), cell(ingestSeconds), cell(updateSeconds),
                          cell(std::chrono::duration<double>(update.labelTime).count()),
                          cell(std::chrono::duration<double>(update.update.elapsed).count()),
                          cell(1 / (ingestSeconds + updateSeconds)), cell(cloudCounts.accuracy()),
                          cell(cloudCounts.tpr()), cell(truthCounts.accuracy()),
                          cell(truthCounts.tpr()), cell(agreement.accuracy()),
                          cell(static_cast<double>(model->supportCount())),
                          cell(meanSecondsPerCall(
                              test, [&](const double* q) { return model->inCollision(q); }, 0.01)),
                          cell(meanSecondsPerCheck(test, *onCloud, 0.01))});
      if (frame % (o.quick ? 2 : o.planEvery) != 0) continue;
      const VerifiedPlan plan =
          planQuery(o, proxy, onCloud, *onTruth, limits, trial, frame, rng, results.plans);
      if (plan.solved()) keepPicture(cloud, robot, sensed, plan.path, o.resolution, results);
    }
  }
  return results;
}

namespace {

std::string fixed(double value, int digits) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(digits);
  text << value;
  return text.str();
}

/// The frames' table: medians over frames, accuracies as means.
void framesSection(std::ostream& md, const Table& f, const SensedOptions& o) {
  const auto median = [&](const char* column, int digits = 0) {
    return fixed(summarize(f.numbers(column)).median, digits);
  };
  const auto seconds = [&](const char* column) {
    return durationText(summarize(f.numbers(column)).median);
  };
  const auto mean = [&](const char* column) { return fixed(summarize(f.numbers(column)).mean, 3); };
  md << "# Sensed scenes: Baxter among moving boxes seen through a depth camera\n\n"
     << "Baxter's right arm (7 joints) over a table, before a wall, with three 0.2 m boxes on "
        "random walks of 1 to 4 cm per frame (data/scenes/baxter_sensed.yaml), seen only through a "
        "simulated depth camera ("
     << o.width << " x " << o.height << " pixels, 87 degrees, depth noise " << o.depthNoise * 1000
     << " mm) above the shoulder. Every frame the cloud is down-sampled at " << o.radius
     << " m, each point a ball of that radius, handed to FCL's cloud check (cropped to the arm's "
        "reach), and the model ("
     << featureSentence(o.features) << ") updates from it: " << o.trials << " trial(s) of "
     << (o.quick ? 4 : o.frames) << " frames, seed " << o.seed << (o.quick ? ", quick mode" : "")
     << ". Accuracy and TPR on fresh uniform configurations every frame, against FCL on the cloud "
        "and on the true boxes.\n\n";
  md << "| cloud: raw | kept | in reach | ingest | update | updates/s | accuracy (cloud) | TPR "
        "(cloud) | accuracy (boxes) | TPR (boxes) | FCL cloud = boxes | \\|S\\| | query | FCL "
        "on the cloud |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n"
     << "| " << median("raw_points") << " | " << median("kept_points") << " | "
     << median("reach_points") << " | " << seconds("ingest_s") << " | " << seconds("update_s")
     << " | " << median("updates_per_s", 1) << " | " << mean("accuracy_cloud") << " | "
     << mean("tpr_cloud") << " | " << mean("accuracy_truth") << " | " << mean("tpr_truth") << " | "
     << mean("cloud_truth") << " | " << median("support") << " | " << seconds("query_s") << " | "
     << seconds("fcl_query_s") << " |\n\n"
     << "Medians over frames (accuracies: means). Ingest: down-sampling and the checker's grid; "
        "update: labelling on the cloud and training (Algorithms 1 and 2); updates/s: 1 / (ingest "
        "+ update), on this machine's 2 cores. The camera's rendering ("
     << seconds("camera_s") << " a frame) is the simulator's, not counted.\n\n";
}

/// The median total time of `method`'s solved plans.
double medianSolvedTotal(const Table& plans, const std::string& method) {
  const Table::Filter where{{"method", method}};
  const auto solved = plans.numbers("solved", where);
  const auto total = plans.numbers("total_s", where);
  std::vector<double> totals;
  for (std::size_t i = 0; i < total.size(); ++i)
    if (solved[i] > 0) totals.push_back(total[i]);
  return summarize(totals).median;
}

void plansSection(std::ostream& md, const PlanRows& rows, const SensedOptions& o) {
  md << "## Plans\n\nA query every " << o.planEvery
     << " frames (start and goal free of the cloud and of the boxes): Fastron on the frame's "
        "model, verified and repaired on the cloud, and FCL on the cloud; RRT-Connect, "
     << o.timeLimit << " s, edges every " << edgeSteps(o, "rad") << ". "
     << simplificationSentence(o.simplifyTime, o.simplification)
     << " Every solved path audited every " << o.resolution / 3
     << " rad (a third of the edge step) against the cloud and against the true boxes.\n\n"
     << "| method | solved | median total | colliding with the cloud | colliding with the boxes "
        "|\n|---|---|---|---|---|\n";
  const Table plans = rows.table();
  for (const std::string& method : plans.distinct("method")) {
    const Table::Filter where{{"method", method}};
    const auto solved = plans.numbers("solved", where);
    double solvedCount = 0, cloudHits = 0, boxHits = 0;
    for (const double v : solved) solvedCount += v;
    for (const double v : plans.numbers("collides_cloud", where)) cloudHits += v;
    for (const double v : plans.numbers("collides_fcl", where))
      if (!std::isnan(v)) boxHits += v;
    md << "| " << method << " | " << cell(solvedCount) << "/" << solved.size() << " | "
       << durationText(medianSolvedTotal(plans, method)) << " | " << cell(cloudHits) << " | "
       << cell(boxHits) << " |\n";
  }
  md << "\nMedian total time of FCL / of Fastron: "
     << fixed(medianSolvedTotal(plans, "FCL") / medianSolvedTotal(plans, "Fastron"), 1)
     << "x.\n\nColliding with the boxes: a path free of the cloud can still touch a box where the "
        "camera does not see it (a box's far side, or behind another). Colliding with the cloud: "
        "a touch between the states the plan's checks looked at, which the finer audit finds.\n";
}

}  // namespace

std::string sensedReport(const SensedResults& r, const SensedOptions& o) {
  std::ostringstream md;
  framesSection(md, r.frames, o);
  if (!r.plans.rows.empty()) plansSection(md, r.plans, o);
  return md.str();
}

}  // namespace fastron::experiments
