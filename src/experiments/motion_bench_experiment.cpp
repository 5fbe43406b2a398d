#include "fastron/experiments/motion_bench_experiment.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "fastron/geometry/control_points.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/geometry/urdf.h"
#include "plan_rows.h"

namespace fastron {

using experiments::columnsWith;
using experiments::joined;
using experiments::MethodPlan;
using experiments::planCells;
using experiments::plannerOptions;
using experiments::planTable;
using experiments::planWithEachChecker;
using experiments::progressLine;
using experiments::speedups;

namespace {

struct Problem {
  std::string id;
  std::filesystem::path scene, request;
};

/// The sceneNNNN.yaml files of `folder` that have a requestNNNN.yaml beside them, in order.
std::vector<Problem> problemsIn(const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder)) {
    throw FileError(folder.string() + ": not a folder of sceneNNNN.yaml / requestNNNN.yaml files");
  }
  std::vector<Problem> problems;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("scene") || entry.path().extension() != ".yaml") continue;
    const std::string id = name.substr(5, name.size() - 10);
    const auto request = folder / ("request" + id + ".yaml");
    if (std::filesystem::exists(request)) problems.push_back({id, entry.path(), request});
  }
  std::sort(problems.begin(), problems.end(),
            [](const Problem& a, const Problem& b) { return a.id < b.id; });
  if (problems.empty()) {
    throw FileError(folder.string() + ": no sceneNNNN.yaml with a matching requestNNNN.yaml");
  }
  return problems;
}

/// When the goal touches obstacles with the hand only (a grasp), allows those hand-object pairs
/// in the scene and returns a note naming them; returns a note saying why otherwise.
std::string allowGrasp(const Robot& robot, Scene& scene, const Eigen::VectorXd& goal) {
  const auto span = std::span<const double>(goal.data(), static_cast<std::size_t>(goal.size()));
  std::string note;
  for (int round = 0; round < 4; ++round) {
    const auto contact = FclChecker(robot, scene).firstContact(span);
    if (!contact) return note;
    const bool hand = contact->robotLink.find("hand") != std::string::npos ||
                      contact->robotLink.find("finger") != std::string::npos;
    if (contact->selfCollision || !hand) {
      return note + (note.empty() ? "" : "; ") + "goal collides: " + contact->robotLink +
             " touches " + contact->other;
    }
    for (const Link& link : robot.links()) {
      if (link.name.find("hand") != std::string::npos ||
          link.name.find("finger") != std::string::npos)
        scene.allowedCollisions.allow(link.name, contact->other);
    }
    note += (note.empty() ? "grasp: hand may touch " : ", ") + contact->other;
  }
  return note;
}

}  // namespace

Table runMotionBench(const MotionBenchOptions& o, const Progress& progress) {
  Table table{columnsWith({"problem", "planner", "method", "note"}, {"support", "train_s"}), {}};
  std::vector<Problem> problems = problemsIn(o.problems);
  if (o.quick && problems.size() > 2) problems.resize(2);
  Robot robot = loadRobot(o.robot, UrdfOptions{.searchPaths = o.packagePaths}, o.srdf);
  const JointLimits limits = robot.limits();
  const FeatureMap features = robotFeatures(robot, o.features);
  const CheckerOptions checking{.selfCollision = o.selfCollision};
  for (std::size_t p = 0; p < problems.size(); ++p) {
    const Problem& problem = problems[p];
    if (progress)
      progress("motion-bench: " + progressLine("problem", p, problems.size()) + " (" +
               problem.scene.filename().string() + ")");
    Scene scene = loadScene(problem.scene);
    const PlanRequest request = loadMoveItRequest(problem.request);
    const auto toVector = [](const std::vector<double>& v) {
      return Eigen::VectorXd(
          Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
    };
    const Eigen::VectorXd start =
        toVector(actuatedConfiguration(robot, request.start, problem.request.string() + ": start"));
    const Eigen::VectorXd goal =
        toVector(actuatedConfiguration(robot, request.goal, problem.request.string() + ": goal"));
    const std::string note = allowGrasp(robot, scene, goal);
    auto fcl = std::make_shared<FclChecker>(robot, scene, checking);
    const FclChecker audit(robot, scene, checking);

    ProxyCollisionDetector proxy(fcl, features,
                                 experimentProxyParams(o.features, 5, 500, o.seed + p));
    const auto began = std::chrono::steady_clock::now();
    proxy.initialize(o.quick ? 1500 : o.trainingPoints);
    for (std::size_t u = 0; u < (o.quick ? 1 : o.updates); ++u) proxy.step();
    const double trainSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    const CalibratedModel calibrated = proxy.calibratedModel();
    const auto& model = calibrated.model;

    const PlannerOptions options = plannerOptions(o, PlannerType::RrtConnect);
    for (const MethodPlan& each :
         planWithEachChecker(calibrated, nullptr, fcl, limits, start, goal, options)) {
      const auto& [method, plan, exactShare] = each;
      table.add(joined({problem.id, "RRTConnect", method, note},
                       joined(planCells(each, audit, o.resolution),
                              {std::to_string(model->supportCount()), cell(trainSeconds)})));
    }
  }
  return table;
}

std::string motionBenchReport(const Table& r, const MotionBenchOptions& o) {
  std::ostringstream md;
  md << "# MoveIt benchmark problems (" << o.problems.string() << ")\n\n"
     << featureSentence(o.features) << " Robot " << o.robot
     << (o.srdf.empty() ? "" : " with the disabled collisions of " + o.srdf.string())
     << (o.selfCollision ? ", self-collision checked by FCL" : ", self-collision not checked")
     << "; for each problem Fastron is trained on the scene ("
     << (o.quick ? 1500 : o.trainingPoints) << " samples, then " << (o.quick ? 1 : o.updates)
     << " active-learning updates) and RRT-Connect plans with Fastron (verified and repaired with "
        "FCL) and with FCL. Edges checked every "
     << o.resolution << " rad, time limit " << o.timeLimit << " s, seed " << o.seed
     << (o.quick ? ", quick mode" : "") << ". " << simplificationSentence(o.simplifyTime) << "\n\n"
     << "| Problem | Method | Status | Plan | Verify | Repair | Total | Path length | Collides "
        "(FCL) | Training | Note |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  const std::size_t status = r.index("status"), plan = r.index("plan_s"),
                    verify = r.index("verify_s"), repair = r.index("repair_s"),
                    total = r.index("total_s"), length = r.index("path_length"),
                    collides = r.index("collides_fcl"), train = r.index("train_s"),
                    note = r.index("note");
  const auto ms = [](const std::string& text) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f ms", std::stod(text) * 1e3);
    return std::string(buffer);
  };
  for (const auto& row : r.rows) {
    const bool fastron = row[r.index("method")] == "Fastron";
    md << "| " << row[r.index("problem")] << " | " << row[r.index("method")] << " | " << row[status]
       << " | " << ms(row[plan]) << " | " << ms(row[verify]) << " | " << ms(row[repair]) << " | "
       << ms(row[total]) << " | " << row[length].substr(0, 5) << " | " << row[collides] << " | "
       << (fastron ? ms(row[train]) : "—") << " | " << row[note] << " |\n";
  }
  md << "\n## Summary\n\n" << planTable(r, {}, {"RRTConnect"}) << speedups(r, {}, {"RRTConnect"});
  return md.str();
}

}  // namespace fastron
