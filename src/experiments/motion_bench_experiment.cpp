#include "fastron/experiments/motion_bench_experiment.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "fastron/core/model_checker.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/geometry/urdf.h"
#include "fastron/planning/verify_repair.h"
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
using experiments::sampleFree;
using experiments::speedups;
using experiments::uniformIn;

namespace {

struct Problem {
  std::string family, id;
  std::filesystem::path scene, request;
};

/// The sceneNNNN.yaml files of `folder` that have a requestNNNN.yaml beside them, in order, as
/// problems of `family`.
std::vector<Problem> pairsIn(const std::filesystem::path& folder, const std::string& family) {
  std::vector<Problem> problems;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("scene") || entry.path().extension() != ".yaml") continue;
    const std::string id = name.substr(5, name.size() - 10);
    const auto request = folder / ("request" + id + ".yaml");
    if (std::filesystem::exists(request)) problems.push_back({family, id, entry.path(), request});
  }
  std::sort(problems.begin(), problems.end(),
            [](const Problem& a, const Problem& b) { return a.id < b.id; });
  return problems;
}

/// The problems of `folder`: its own scene/request pairs (one family, named after the folder), or
/// else those of each sub-folder (a family each, in name order).
std::vector<Problem> problemsIn(const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder)) {
    throw FileError(folder.string() + ": not a folder of sceneNNNN.yaml / requestNNNN.yaml files");
  }
  const std::filesystem::path absolute = std::filesystem::absolute(folder).lexically_normal();
  const std::string name =
      (absolute.has_filename() ? absolute : absolute.parent_path()).filename().string();
  std::vector<Problem> problems = pairsIn(folder, name);
  if (!problems.empty()) return problems;
  std::vector<std::filesystem::path> families;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.is_directory()) families.push_back(entry.path());
  }
  std::sort(families.begin(), families.end());
  for (const auto& family : families) {
    const std::vector<Problem> more = pairsIn(family, family.filename().string());
    problems.insert(problems.end(), more.begin(), more.end());
  }
  if (problems.empty()) {
    throw FileError(folder.string() +
                    ": no sceneNNNN.yaml with a matching requestNNNN.yaml, in it or in a folder "
                    "in it");
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

/// initialize(samples) then `updates` steps; the seconds they took.
double train(ProxyCollisionDetector& proxy, std::size_t samples, std::size_t updates) {
  const auto began = std::chrono::steady_clock::now();
  proxy.initialize(samples);
  for (std::size_t u = 0; u < updates; ++u) proxy.step();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
}

}  // namespace

Table runMotionBench(const MotionBenchOptions& o, const Progress& progress) {
  if (o.queriesPerScene == 0) throw InvalidArgument("motion-bench: queries per scene must be >= 1");
  Table table{columnsWith({"family", "problem", "query", "planner", "method", "note"},
                          {"support", "train_s", "self_train_s", "learn_s"}),
              {}};
  std::vector<Problem> problems = problemsIn(o.problems);
  if (o.quick) {  // two problems of each family
    std::map<std::string, std::size_t> kept;
    std::erase_if(problems, [&](const Problem& p) { return ++kept[p.family] > 2; });
  }
  Robot robot = loadRobot(o.robot, UrdfOptions{.searchPaths = o.packagePaths}, o.srdf);
  const JointLimits limits = robot.limits();
  const FeatureMap features = robotFeatures(robot, o.features);
  const CheckerOptions checking{.selfCollision = o.selfCollision};
  if (o.selfModel && !o.selfCollision) {
    throw InvalidArgument("motion-bench: a self-collision model needs self-collision checked");
  }
  // The robot's self-collision model, learned once: self-collision does not depend on the scene.
  const std::size_t samples = o.quick ? 1500 : o.trainingPoints;
  const std::size_t updates = o.quick ? 1 : o.updates;
  std::shared_ptr<const CollisionChecker> selfModel;
  double selfTrainSeconds = 0;
  if (o.selfModel) {
    if (progress) progress("motion-bench: learning the robot's self-collisions");
    ProxyCollisionDetector self(
        std::make_shared<FclChecker>(robot, Scene{}, checking),
        robotFeatures(robot, FeatureKind::JointScaling),
        withoutBand(experimentProxyParams(FeatureKind::JointScaling, 5, 500, o.seed)));
    selfTrainSeconds = train(self, o.quick ? 2000 : o.selfTrainingPoints, updates);
    selfModel = std::make_shared<ModelChecker>(self.model(), "Fastron self");
  }
  for (std::size_t p = 0; p < problems.size(); ++p) {
    const Problem& problem = problems[p];
    if (progress)
      progress("motion-bench: " + progressLine("problem", p, problems.size()) + " (" +
               problem.family + "/" + problem.scene.filename().string() + ")");
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

    const ProxyParams params = experimentProxyParams(o.features, 5, 500, o.seed + p);
    ProxyCollisionDetector proxy(fcl, features, params);
    const double trainSeconds = train(proxy, samples, updates);
    CalibratedModel calibrated = proxy.calibratedModel();
    std::string support = std::to_string(calibrated.model->supportCount());
    // The split source: this scene's obstacles (a model whose oracle ignores self-collision) and
    // the robot's self-collision model.
    std::shared_ptr<const CollisionChecker> split;
    std::string splitSupport, splitTrain;
    if (selfModel) {
      ProxyCollisionDetector obstacles(std::make_shared<FclChecker>(robot, scene), features,
                                       withoutBand(params));
      splitTrain = cell(train(obstacles, samples, updates));
      splitSupport = std::to_string(obstacles.model()->supportCount());
      split = std::make_shared<AnyOfChecker>(std::vector<std::shared_ptr<const CollisionChecker>>{
          std::make_shared<ModelChecker>(obstacles.model()), selfModel});
    }

    Rng rng(o.seed * 7919 + p);
    const PlannerOptions options = plannerOptions(o, PlannerType::RrtConnect);
    for (std::size_t query = 0; query < o.queriesPerScene; ++query) {
      // Query 0 is the request; the others join two configurations free under FCL.
      const auto freeConfiguration = [&] {
        return sampleFree(
            *fcl, [&] { return uniformIn(limits, rng); }, "configuration");
      };
      const Eigen::VectorXd from = query == 0 ? start : freeConfiguration();
      const Eigen::VectorXd to = query == 0 ? goal : freeConfiguration();
      double learnSeconds = 0;
      if (o.learnFromVerification && query > 0) {  // what the last query's plan taught it
        learnSeconds = std::chrono::duration<double>(proxy.learnObservations().total).count();
        calibrated = proxy.calibratedModel();
        support = std::to_string(calibrated.model->supportCount());
      }
      for (const MethodPlan& each : planWithEachChecker(calibrated, nullptr, fcl, limits, from, to,
                                                        options, p * o.queriesPerScene + query)) {
        if (o.learnFromVerification && each.method == "Fastron") {
          proxy.addObservations(answersMissedBy(*calibrated.model, each.plan.exactAnswers));
        }
        table.add(joined(
            {problem.family, problem.id, std::to_string(query), "RRTConnect", each.method,
             query == 0 ? note : ""},
            joined(planCells(each, audit, o.resolution),
                   {support, cell(trainSeconds), cell(selfTrainSeconds), cell(learnSeconds)})));
      }
      if (split) {
        const MethodPlan each{"Fastron split", planVerified(split, fcl, limits, from, to, options),
                              0};
        table.add(joined({problem.family, problem.id, std::to_string(query), "RRTConnect",
                          each.method, query == 0 ? note : ""},
                         joined(planCells(each, audit, o.resolution),
                                {splitSupport, splitTrain, cell(selfTrainSeconds), "0"})));
      }
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
     << " active-learning updates) and RRT-Connect plans with Fastron and Hybrid (verified and "
        "repaired with FCL) and with FCL, "
     << o.queriesPerScene << " quer" << (o.queriesPerScene == 1 ? "y" : "ies")
     << " per scene (the request, then start/goal pairs drawn free under FCL). Edges checked "
        "every "
     << o.resolution << " rad, time limit " << o.timeLimit << " s, seed " << o.seed
     << (o.quick ? ", quick mode" : "") << ". " << simplificationSentence(o.simplifyTime)
     << " Training is reported beside the plans, not in them; the end-to-end time adds each "
        "scene's training, shared by its queries."
     << (o.learnFromVerification
             ? " Before each query after a scene's first, Fastron's model learns the exact answers "
               "of the last plan's verification and repair that it got wrong (no oracle call; "
               "learn_s in results.csv, not in the totals)."
             : "")
     << "\n";

  const auto statistic = [&](const Table::Filter& where, const char* column, bool median) {
    const Summary s = summarize(r.numbers(column, where));
    return median ? s.median : s.mean;
  };
  // Per family, and over all: medians and means of the total time per valid plan, training per
  // scene, and Fastron's end-to-end time (total + training / queries per scene).
  const auto summary = [&](const Table::Filter& where) {
    std::ostringstream out;
    out << planTable(r, where, {"RRTConnect"}) << speedups(r, where, {"RRTConnect"});
    Table::Filter fastron = where;
    fastron.emplace_back("method", "Fastron");
    fastron.emplace_back("query", "0");
    const double train = statistic(fastron, "train_s", true);
    Table::Filter solved = where;
    solved.emplace_back("solved", "1");
    const auto total = [&](const char* method, bool median) {
      Table::Filter f = solved;
      f.emplace_back("method", method);
      return statistic(f, "total_s", median);
    };
    const double share = train / static_cast<double>(o.queriesPerScene);
    char line[512];
    std::snprintf(line, sizeof line,
                  "Training per scene: median %s (|S| median %.0f). End-to-end per query with %zu "
                  "quer%s per scene, median total + training / queries: Fastron %s, Hybrid %s, "
                  "FCL %s (FCL / Fastron %.2fx).\n",
                  durationText(train).c_str(), statistic(fastron, "support", true),
                  o.queriesPerScene, o.queriesPerScene == 1 ? "y" : "ies",
                  durationText(total("Fastron", true) + share).c_str(),
                  durationText(total("Hybrid", true) + share).c_str(),
                  durationText(total("FCL", true)).c_str(),
                  total("FCL", true) / (total("Fastron", true) + share));
    out << '\n' << line;
    Table::Filter split = where;
    split.emplace_back("method", "Fastron split");
    split.emplace_back("query", "0");
    if (!r.numbers("train_s", split).empty()) {
      const double splitTrain = statistic(split, "train_s", true);
      const double splitTotal = total("Fastron split", true);
      std::snprintf(
          line, sizeof line,
          "Fastron split: obstacle model per scene median %s (|S| median %.0f), the "
          "robot's self-collision model %s once; end-to-end per query %s without the "
          "self-collision model (FCL / Fastron split %.2fx).\n",
          durationText(splitTrain).c_str(), statistic(split, "support", true),
          durationText(statistic(split, "self_train_s", true)).c_str(),
          durationText(splitTotal + splitTrain / static_cast<double>(o.queriesPerScene)).c_str(),
          total("FCL", true) / (splitTotal + splitTrain / static_cast<double>(o.queriesPerScene)));
      out << line;
    }
    return out.str();
  };
  for (const std::string& family : r.distinct("family", {})) {
    md << "\n## " << family << "\n\n" << summary({{"family", family}});
  }
  md << "\n## All families\n\n" << summary({});

  md << "\n## The requests\n\n"
     << "| Family | Problem | Method | Status | Plan | Verify | Repair | Total | Path length | "
        "Collides (FCL) | Training | Note |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  const auto ms = [](double seconds) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f ms", seconds * 1e3);
    return std::string(buffer);
  };
  const auto text = [&](const std::vector<std::string>& row, const char* column) {
    return row[r.index(column)];
  };
  const auto number = [&](const std::vector<std::string>& row, const char* column) {
    return std::stod(text(row, column));
  };
  for (const auto& row : r.rows) {
    if (text(row, "query") != "0") continue;
    const bool fastron = text(row, "method") == "Fastron";
    char length[32];
    std::snprintf(length, sizeof length, "%.3f", number(row, "path_length"));
    md << "| " << text(row, "family") << " | " << text(row, "problem") << " | "
       << text(row, "method") << " | " << text(row, "status") << " | " << ms(number(row, "plan_s"))
       << " | " << ms(number(row, "verify_s")) << " | " << ms(number(row, "repair_s")) << " | "
       << ms(number(row, "total_s")) << " | " << length << " | " << text(row, "collides_fcl")
       << " | " << (fastron ? ms(number(row, "train_s")) : "—") << " | " << text(row, "note")
       << " |\n";
  }
  return md.str();
}

}  // namespace fastron
