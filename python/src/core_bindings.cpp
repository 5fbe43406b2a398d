// fastron.Model, training, evaluation, datasets and the oracle interface.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>

#include "arrays.h"
#include "bindings.h"
#include "fastron/core/collision_checker.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model.h"
#include "fastron/core/model_checker.h"
#include "fastron/core/model_file.h"
#include "fastron/core/simd.h"
#include "fastron/core/support_reduction.h"
#include "fastron/core/trainer.h"
#include "python_checker.h"

namespace fastron::python {

namespace {

/// f for one configuration (a float) or for each row of an (n, d) array.
py::object scores(const Model& model, py::handle q) {
  const ConfigurationRows rows = configurations(q, model.dim(), "q");
  if (rows.single) return py::float_(model.score(rows.row(0)));
  py::array_t<double> out = newArray(rows.rows);
  double* data = out.mutable_data();
  {
    py::gil_scoped_release released;
    model.scoreBatch(rows.data, rows.rows, data);
  }
  return out;
}

/// (score, gradient) of one configuration (d,), or (scores (n,), gradients (n, d)) of each row.
py::tuple scoreGradients(const Model& model, py::handle q) {
  const ConfigurationRows rows = configurations(q, model.dim(), "q");
  if (rows.single) {
    Model::ScoreGradient one;
    {
      py::gil_scoped_release released;
      one = model.scoreGradient(rows.row(0));
    }
    return py::make_tuple(one.score, toArray(one.gradient));
  }
  Model::ScoreGradients many;
  {
    py::gil_scoped_release released;
    many = model.scoreGradients(rows.matrix());
  }
  return py::make_tuple(toArray(many.scores), toArray(many.gradients));
}

py::object inCollision(const Model& model, py::handle q) {
  const ConfigurationRows rows = configurations(q, model.dim(), "q");
  if (rows.single) return py::bool_(model.inCollision(rows.row(0)));
  py::array_t<bool> out(static_cast<py::ssize_t>(rows.rows));
  bool* hits = out.mutable_data();
  py::gil_scoped_release released;
  if (model.pointField()) {  // the grids answer one configuration at a time
    for (std::size_t i = 0; i < rows.rows; ++i)
      hits[i] = model.inCollision(rows.data + i * rows.cols);
    return out;
  }
  std::vector<double> f(rows.rows);
  model.scoreBatch(rows.data, rows.rows, f.data());
  std::transform(f.begin(), f.end(), hits, [](double v) { return v > 0; });
  return out;
}

py::tuple train(py::handle x, py::handle y, std::optional<FeatureMap> features,
                std::optional<JointLimits> limits, std::optional<double> gamma,
                std::optional<double> beta, const std::string& kernel,
                std::optional<std::uint32_t> kernelBlock, std::optional<double> wholeShare,
                bool selfCollisionLabels, std::optional<std::size_t> maxIterations,
                std::optional<std::size_t> maxSupport, unsigned threads) {
  if (features && limits) throw InvalidArgument("give features= or limits=, not both");
  const std::size_t dim = features ? features->configurationDim() : limits ? limits->dim() : 0;
  const ConfigurationRows rows = configurations(x, dim, "X", false);
  const Labels labelled = labels(y, rows.rows, "y");
  const FeatureMap map =
      features
          ? *features
          : FeatureMap::jointScaling(limits ? *limits : rangeOf(rows.matrix(), "give limits="));
  // With a robot's features, the settings tuned for them; on bare data, the paper's defaults.
  TrainParams params =
      features ? defaultTrainParams(map.kind(), selfCollisionLabels) : TrainParams{};
  params.kernel.type = parseKernelType(kernel);
  if (gamma) params.kernel.gamma = *gamma;
  if (kernelBlock) params.kernel.block = *kernelBlock;
  if (wholeShare) params.kernel.wholeShare = *wholeShare;
  if (beta) params.beta = *beta;
  if (maxIterations) params.maxIterations = *maxIterations;
  if (maxSupport) params.maxSupportPoints = *maxSupport;
  std::shared_ptr<const Model> model;
  UpdateReport report;
  {
    py::gil_scoped_release released;
    Trainer trainer(map, params);
    trainer.addPoints(rows.matrix(), labelled);
    report = trainer.update(threads);
    model = trainer.model();
  }
  return py::make_tuple(std::const_pointer_cast<Model>(model), report);
}

/// JointLimits and FeatureMap.
void bindLimitsAndFeatures(py::module_& m) {
  py::class_<JointLimits>(m, "JointLimits",
                          "Lower and upper limit of each joint; joint scaling maps them to "
                          "[-1, 1].")
      .def(py::init([](py::handle lower, py::handle upper) {
             const Eigen::VectorXd l = vector(lower, 0, "lower");
             return JointLimits(l, vector(upper, static_cast<std::size_t>(l.size()), "upper"));
           }),
           py::arg("lower"), py::arg("upper"))
      .def_property_readonly("dim", &JointLimits::dim)
      .def_property_readonly("lower", [](const JointLimits& l) { return toArray(l.lower()); })
      .def_property_readonly("upper", [](const JointLimits& l) { return toArray(l.upper()); })
      .def("__repr__",
           [](const JointLimits& l) { return "JointLimits(dim=" + std::to_string(l.dim()) + ")"; });

  py::class_<FeatureMap>(m, "FeatureMap",
                         "What the model's kernel compares: joint values scaled to [-1, 1] "
                         "('joints'), or the world positions of control points on a robot "
                         "('fk'; see robot_features).")
      .def_static("joint_scaling", &FeatureMap::jointScaling, py::arg("limits"))
      .def_property_readonly("kind",
                             [](const FeatureMap& f) { return std::string(toString(f.kind())); })
      .def_property_readonly("configuration_dim", &FeatureMap::configurationDim)
      .def_property_readonly("feature_dim", &FeatureMap::featureDim)
      .def_property_readonly("limits", &FeatureMap::limits)
      .def(
          "map",
          [](const FeatureMap& f, py::handle q) -> py::object {
            const ConfigurationRows rows = configurations(q, f.configurationDim(), "q");
            Eigen::MatrixXd x = f.map(Configurations(rows.matrix()));
            if (rows.single) return toArray(x.row(0).transpose());
            return toArray(x);
          },
          py::arg("q"), "Features of one configuration (d,) or of each row of (n, d).")
      .def("__repr__", [](const FeatureMap& f) { return "FeatureMap(" + f.summary() + ")"; });
}

/// UpdateReport and Model.
void bindModel(py::module_& m) {
  py::class_<UpdateReport>(m, "UpdateReport", "What one run of Algorithm 1 did.")
      .def_readonly("iterations", &UpdateReport::iterations)
      .def_property_readonly(
          "stop_reason", [](const UpdateReport& r) { return std::string(toString(r.stopReason)); })
      .def_readonly("training_points", &UpdateReport::trainingPoints)
      .def_readonly("misclassified", &UpdateReport::misclassified)
      .def_readonly("support_count", &UpdateReport::supportCount)
      .def_readonly("reverted", &UpdateReport::reverted)
      .def_readonly("shared_iterations", &UpdateReport::sharedIterations)
      .def_property_readonly("seconds", [](const UpdateReport& r) { return inSeconds(r.elapsed); })
      .def("__repr__", [](const UpdateReport& r) {
        return "UpdateReport(support_count=" + std::to_string(r.supportCount) +
               ", iterations=" + std::to_string(r.iterations) + ", stop_reason='" +
               std::string(toString(r.stopReason)) + "')";
      });

  py::class_<Model, std::shared_ptr<Model>>(
      m, "Model",
      "A trained Fastron model: f(q) = sum_i w_i k(s_i, q), in collision when f(q) > 0. "
      "Immutable: query it from any number of threads.")
      .def_property_readonly("dim", &Model::dim, "Joint values per configuration.")
      .def_property_readonly("feature_dim", &Model::featureDim, "Features per configuration.")
      .def_property_readonly("support_count", &Model::supportCount)
      .def_property_readonly("checksum", &Model::checksum,
                             "Of the support set and weights, taken when the model was built.")
      .def_property_readonly("features", &Model::features)
      .def_property_readonly("limits", &Model::limits)
      .def_property_readonly("gamma", [](const Model& model) { return model.kernel().gamma; })
      .def_property_readonly(
          "kernel", [](const Model& model) { return std::string(toString(model.kernel().type)); })
      .def_property_readonly(
          "kernel_block", [](const Model& model) { return model.kernel().block; },
          "Features per point term of the kernel; 0: one term over all features.")
      .def_property_readonly(
          "kernel_whole_share", [](const Model& model) { return model.kernel().wholeShare; },
          "With point terms: the whole feature vector's share of the kernel.")
      .def_property_readonly(
          "support_points",
          [](py::handle self) {
            return readOnlyView(self.cast<const Model&>().supportConfigurations(), self);
          },
          "Support configurations (joint values), shape (|S|, dim); a read-only view.")
      .def_property_readonly(
          "support_features",
          [](py::handle self) {
            return readOnlyView(self.cast<const Model&>().supportFeatures(), self);
          },
          "Their features, shape (|S|, feature_dim); a read-only view.")
      .def_property_readonly(
          "weights",
          [](py::handle self) { return readOnlyView(self.cast<const Model&>().weights(), self); },
          "The support points' weights, shape (|S|,); a read-only view.")
      .def("score", &scores, py::arg("q"),
           "f(q) for one configuration (d,) -> float, or for each row of (n, d) -> (n,).")
      .def("score_gradient", &scoreGradients, py::arg("q"),
           "f(q) (summed in float, as score) and its analytic gradient with respect to the joint "
           "values: (float, (d,)) for one configuration (d,), ((n,), (n, d)) for each row of "
           "(n, d).")
      .def("in_collision", &inCollision, py::arg("q"),
           "f(q) > 0 for one configuration (d,) -> bool, or for each row of (n, d) -> (n,) bool.")
      .def(
          "first_in_collision",
          [](const Model& model, py::handle q) -> std::optional<std::size_t> {
            const ConfigurationRows rows = configurations(q, model.dim(), "q", false);
            std::size_t first = 0;
            {
              py::gil_scoped_release released;
              first = model.firstInCollision(rows.data, rows.rows);
            }
            if (first == rows.rows) return std::nullopt;
            return first;
          },
          py::arg("q"),
          "Index of the first row of (n, d) predicted in collision, or None when all are free.")
      .def_property_readonly("has_only_point_terms", &Model::hasOnlyPointTerms,
                             "Whether with_point_field can tabulate the model: point terms of 3 "
                             "features and no whole-vector term.")
      .def(
          "with_point_field",
          [](const Model& model, double spacing, std::size_t samples, std::uint64_t seed,
             double errorFactor, std::uint32_t refinement, std::size_t maxFineNodes,
             double fineFrom, const std::string& answers) {
            PointFieldOptions options;
            options.answers = parseFieldAnswers(answers);
            options.spacing = spacing;
            options.samples = samples;
            options.seed = seed;
            options.errorFactor = errorFactor;
            options.refinement = refinement;
            options.maxFineNodes = maxFineNodes;
            options.fineFrom = fineFrom;
            py::gil_scoped_release released;
            return std::const_pointer_cast<Model>(model.withPointField(options));
          },
          py::kw_only(), py::arg("spacing") = PointFieldOptions{}.spacing,
          py::arg("samples") = PointFieldOptions{}.samples,
          py::arg("seed") = PointFieldOptions{}.seed,
          py::arg("error_factor") = PointFieldOptions{}.errorFactor,
          py::arg("refinement") = PointFieldOptions{}.refinement,
          py::arg("max_fine_nodes") = PointFieldOptions{}.maxFineNodes,
          py::arg("fine_from") = PointFieldOptions{}.fineFrom,
          py::arg("answers") = std::string(toString(PointFieldOptions{}.answers)),
          "A copy whose collision answers (in_collision, first_in_collision) read the point terms "
          "from grids of `spacing` metres where they decide the sign, and sum every term where "
          "not: the same answers, faster for large support sets (docs/performance.md). Where the "
          "grids leave more than `fine_from` of their samples undecided, the least certain "
          "cells get fine blocks (`refinement` fine cells per edge, at most `max_fine_nodes` "
          "nodes). answers='estimate': the sign of the grids' estimate everywhere inside them, "
          "faster still, differing from the full sum only on the model's boundary (no fine "
          "blocks). score still sums every term. Raises ValueError unless has_only_point_terms "
          "or on bad options.")
      .def_property_readonly(
          "point_field",
          [](const Model& model) -> py::object {
            const PointField* field = model.pointField();
            if (!field) return py::none();
            py::dict d;
            d["grids"] = field->grids().size();
            d["spacing"] = field->spacing();
            d["nodes"] = field->nodeCount();
            d["memory_bytes"] = field->memoryBytes();
            d["fine_blocks"] = field->fineBlockCount();
            d["answers"] = std::string(toString(field->answers()));
            return d;
          },
          "None, or the grids of with_point_field: {'grids', 'spacing', 'nodes', "
          "'memory_bytes', 'fine_blocks', 'answers'}.")
      .def(
          "save",
          [](const Model& model, const std::filesystem::path& path) { saveModel(model, path); },
          py::arg("path"))
      .def("__repr__", [](const Model& model) {
        return "Model(dim=" + std::to_string(model.dim()) + ", features='" +
               model.features().summary() +
               "', support_count=" + std::to_string(model.supportCount()) + ")";
      });
}

/// train, and smaller support sets (prune_support, merge_support).
void bindTraining(py::module_& m) {
  m.def("train", &train, py::arg("X"), py::arg("y"), py::kw_only(),
        py::arg("features") = py::none(), py::arg("limits") = py::none(),
        py::arg("gamma") = py::none(), py::arg("beta") = py::none(), py::arg("kernel") = "rq",
        py::arg("kernel_block") = py::none(), py::arg("kernel_whole_share") = py::none(),
        py::arg("self_collision_labels") = false, py::arg("max_iterations") = py::none(),
        py::arg("max_support_points") = py::none(), py::arg("threads") = 0,
        "Algorithm 1 on labelled configurations X (n, d) and labels y (n,) (+1 / -1 or bool). "
        "Features: `features`, else joint scaling by `limits`, else by the data's range. With a "
        "robot's features the kernel and beta default to those tuned for them (for labels that "
        "include self-collisions when self_collision_labels=True); kernel_block (features per "
        "point term, 0: one term) and kernel_whole_share override the kernel's point terms. "
        "threads=1 trains on the calling thread alone; any other value also on a second core "
        "from 4096 rows of X on (the same model either way). Returns (Model, UpdateReport). The "
        "GIL is released while it trains.");

  m.def(
      "prune_support",
      [](const Model& model, py::handle x) {
        const ConfigurationRows rows = configurations(x, model.dim(), "X", false);
        py::gil_scoped_release released;
        return std::const_pointer_cast<Model>(pruneSupport(model, Configurations(rows.matrix())));
      },
      py::arg("model"), py::arg("X"),
      "A model without the support points that no answer on the configurations X (n, d) needs: "
      "tried smallest |weight| first, dropped while every row of X keeps its answer. No labels "
      "needed; X should be fresh configurations spread as the queries will be.");
  m.def(
      "merge_support",
      [](const Model& model, double radius) {
        return std::const_pointer_cast<Model>(mergeSupport(model, radius));
      },
      py::arg("model"), py::arg("radius"),
      "A model whose support points of one sign closer than radius in feature space are merged "
      "into the heaviest one near them (D-Fastron's clustering), which takes their weight.");
}

/// ConfusionCounts and evaluate, the SIMD paths, dataset files.
void bindMetricsAndData(py::module_& m) {
  py::class_<ConfusionCounts>(m, "ConfusionCounts",
                              "Predictions against labels, 'positive' meaning in collision.")
      .def_readonly("true_positives", &ConfusionCounts::truePositives)
      .def_readonly("true_negatives", &ConfusionCounts::trueNegatives)
      .def_readonly("false_positives", &ConfusionCounts::falsePositives)
      .def_readonly("false_negatives", &ConfusionCounts::falseNegatives)
      .def_property_readonly("total", &ConfusionCounts::total)
      .def_property_readonly("accuracy", &ConfusionCounts::accuracy)
      .def_property_readonly("tpr", &ConfusionCounts::tpr)
      .def_property_readonly("tnr", &ConfusionCounts::tnr)
      .def("__repr__", [](const ConfusionCounts& c) {
        return "ConfusionCounts(accuracy=" + std::to_string(c.accuracy()) +
               ", tpr=" + std::to_string(c.tpr()) + ", tnr=" + std::to_string(c.tnr()) +
               ", total=" + std::to_string(c.total()) + ")";
      });
  m.def(
      "evaluate",
      [](const Model& model, py::handle x, py::handle y) {
        const ConfigurationRows rows = configurations(x, model.dim(), "X", false);
        const Labels labelled = labels(y, rows.rows, "y");
        py::gil_scoped_release released;
        return evaluate(model, Configurations(rows.matrix()), labelled);
      },
      py::arg("model"), py::arg("X"), py::arg("y"),
      "The model's predictions on X (n, d) against labels y: accuracy, TPR, TNR.");

  m.def(
      "simd_paths",
      [] {
        std::vector<std::string> names;
        for (const SimdPath path : supportedSimdPaths()) names.emplace_back(toString(path));
        return names;
      },
      "The SIMD paths of the kernel sums this processor runs, narrowest first ('portable', "
      "'avx2', 'avx512').");
  m.def(
      "active_simd_path", [] { return std::string(toString(activeSimdPath())); },
      "The SIMD path queries use now.");
  m.def(
      "use_simd_path", [](const std::string& name) { useSimdPath(parseSimdPath(name)); },
      py::arg("name"), "Makes every query of the process use this SIMD path from now on.");

  m.def(
      "read_dataset",
      [](const std::filesystem::path& path) {
        const Dataset data = readDataset(path);
        return py::make_tuple(toArray(data.points), toArray(data.labels));
      },
      py::arg("path"), "A .csv or .npy dataset as (X (n, d) float64, y (n,) int8 of +1 / -1).");
  m.def(
      "write_dataset",
      [](const std::filesystem::path& path, py::handle x, py::handle y) {
        const ConfigurationRows rows = configurations(x, 0, "X", false);
        writeDataset(Dataset{Configurations(rows.matrix()), labels(y, rows.rows, "y"), {}}, path);
      },
      py::arg("path"), py::arg("X"), py::arg("y"), "Writes a .csv or .npy dataset.");
}

/// CollisionChecker, the interface of every oracle.
void bindCollisionChecker(py::module_& m) {
  py::class_<CollisionChecker, std::shared_ptr<CollisionChecker>>(
      m, "CollisionChecker", "An exact collision checker (the oracle Fastron learns from).")
      .def_property_readonly("name", &CollisionChecker::name)
      .def_property_readonly("dof", &CollisionChecker::dof)
      .def_property_readonly("call_count", &CollisionChecker::callCount)
      .def(
          "in_collision",
          [](const CollisionChecker& checker, py::handle q) -> py::object {
            const ConfigurationRows rows = configurations(q, checker.dof(), "q");
            if (rows.single) return py::bool_(checker.inCollision(rows.row(0)));
            std::vector<std::uint8_t> hits;
            {
              py::gil_scoped_release released;
              hits = checker.inCollisionBatch(Configurations(rows.matrix()));
            }
            py::array_t<bool> out(static_cast<py::ssize_t>(hits.size()));
            std::copy(hits.begin(), hits.end(), out.mutable_data());
            return out;
          },
          py::arg("q"),
          "The exact answer for one configuration (d,) -> bool, or each row of (n, d) -> (n,) "
          "bool (on the calling thread, GIL released).")
      .def_property_readonly(
          "proves_motions_free",
          [](const CollisionChecker& checker) { return checker.provesMotionsFree(); },
          "True when motion_collision skips the states it proves free.")
      .def(
          "motion_collision",
          [](const CollisionChecker& checker, py::handle from, py::handle to,
             std::size_t segments) {
            const Eigen::VectorXd a = vector(from, checker.dof(), "start");
            const Eigen::VectorXd b = vector(to, checker.dof(), "end");
            if (segments == 0) throw InvalidArgument("segments must be at least 1, got 0");
            CollisionChecker::MotionCheck answer;
            {
              py::gil_scoped_release released;
              answer = checker.motionCollision(a.data(), b.data(), segments);
            }
            return py::make_tuple(answer.collidingState == 0 ? py::object(py::none())
                                                             : py::int_(answer.collidingState),
                                  answer.looked);
          },
          py::arg("start"), py::arg("end"), py::arg("segments"),
          "The straight motion looked at in `segments` equal steps (states i = 1..segments, `end` "
          "last): (i of a state in collision, or None, configurations looked at).");
}

/// Checkers made of a callable, a model, or other checkers.
void bindCheckerWrappers(py::module_& m) {
  py::class_<PythonChecker, CollisionChecker, std::shared_ptr<PythonChecker>>(
      m, "FunctionChecker",
      "An exact checker written in Python: fn(q) -> bool for a (dof,) array. Fastron calls it "
      "from one thread at a time, holding the GIL.")
      .def(py::init<py::function, std::size_t, std::string>(), py::arg("fn"), py::arg("dof"),
           py::arg("name") = "python");

  py::class_<ModelChecker, CollisionChecker, std::shared_ptr<ModelChecker>>(
      m, "ModelChecker",
      "A model answering as a checker (score > 0: in collision), to combine with others in an "
      "AnyOfChecker.")
      .def(py::init([](const std::shared_ptr<Model>& model, std::string name) {
             return std::make_shared<ModelChecker>(model, std::move(name));
           }),
           py::arg("model"), py::arg("name") = "Fastron");

  py::class_<AnyOfChecker, CollisionChecker, std::shared_ptr<AnyOfChecker>>(
      m, "AnyOfChecker",
      "In collision when any of its checkers says so: e.g. a scene's obstacle model beside the "
      "robot's self-collision model, learned once (ModelChecker of each), as a planning source.")
      .def(py::init([](const std::vector<std::shared_ptr<CollisionChecker>>& checkers) {
             return std::make_shared<AnyOfChecker>(
                 std::vector<std::shared_ptr<const CollisionChecker>>(checkers.begin(),
                                                                      checkers.end()));
           }),
           py::arg("checkers"));

  py::class_<AllOfChecker, CollisionChecker, std::shared_ptr<AllOfChecker>>(
      m, "AllOfChecker",
      "In collision only when all of its checkers say so, a later one asked only about what the "
      "earlier ones call colliding: with a model first and an exact checker last, an optimistic "
      "hybrid (the model's 'free' trusted, its 'collides' confirmed).")
      .def(py::init([](const std::vector<std::shared_ptr<CollisionChecker>>& checkers) {
             return std::make_shared<AllOfChecker>(
                 std::vector<std::shared_ptr<const CollisionChecker>>(checkers.begin(),
                                                                      checkers.end()));
           }),
           py::arg("checkers"));
}

}  // namespace

void bindCore(py::module_& m) {
  bindLimitsAndFeatures(m);
  bindModel(m);
  bindTraining(m);
  bindMetricsAndData(m);
  bindCollisionChecker(m);
  bindCheckerWrappers(m);
}

}  // namespace fastron::python
