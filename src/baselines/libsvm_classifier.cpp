#include "fastron/baselines/libsvm_classifier.h"

#include <libsvm/svm.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "fastron/core/error.h"

namespace fastron {
namespace {

void quiet(const char*) {}  // LIBSVM prints progress to stdout unless told otherwise

}  // namespace

LibsvmClassifier::LibsvmClassifier(JointLimits limits, double gamma, double C, double tolerance)
    : limits_(std::move(limits)), gamma_(gamma), C_(C), tolerance_(tolerance) {
  validate(Kernel{KernelType::Gaussian, gamma_});
  if (!(C_ > 0) || !(tolerance_ > 0))
    throw InvalidArgument("LIBSVM: C and the tolerance must be positive");
  model_.terms = jointSpaceModel(limits_, Kernel{KernelType::Gaussian, gamma_},
                                 Eigen::MatrixXd(0, limits_.dim()), Eigen::VectorXd(0));
}

void LibsvmClassifier::train(const Configurations& q, std::span<const std::int8_t> labels) {
  const Eigen::Index n = q.rows();
  if (static_cast<std::size_t>(n) != labels.size())
    throw InvalidArgument("LIBSVM: one label per configuration");
  const Configurations x = limits_.toInput(q);
  const auto d = static_cast<int>(limits_.dim());

  // Dense rows in LIBSVM's sparse format: index 1..d, then the terminator -1.
  std::vector<svm_node> nodes(static_cast<std::size_t>(n) * static_cast<std::size_t>(d + 1));
  std::vector<svm_node*> rows(static_cast<std::size_t>(n));
  std::vector<double> targets(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    svm_node* row = &nodes[static_cast<std::size_t>(i) * static_cast<std::size_t>(d + 1)];
    for (int j = 0; j < d; ++j) row[j] = {j + 1, x(i, j)};
    row[d] = {-1, 0};
    rows[static_cast<std::size_t>(i)] = row;
    targets[static_cast<std::size_t>(i)] = labels[static_cast<std::size_t>(i)];
  }
  svm_problem problem{static_cast<int>(n), targets.data(), rows.data()};
  svm_parameter param{};
  param.svm_type = C_SVC;
  param.kernel_type = RBF;
  param.gamma = gamma_;
  param.C = C_;
  param.eps = tolerance_;
  param.cache_size = 200;
  param.shrinking = 1;
  if (const char* problemText = svm_check_parameter(&problem, &param)) {
    throw InvalidArgument(std::string("LIBSVM: ") + problemText);
  }
  static std::mutex printMutex;  // the print hook is process-wide
  svm_model* trained = nullptr;
  {
    const std::lock_guard lock(printMutex);
    svm_set_print_string_function(quiet);
    trained = svm_train(&problem, &param);
  }
  std::unique_ptr<svm_model, void (*)(svm_model*)> model(
      trained, [](svm_model* m) { svm_free_and_destroy_model(&m); });

  // decision = sum_i coef_i k(sv_i, x) - rho, positive for model->label[0].
  const double sign = model->nr_class == 2 && model->label[0] == -1 ? -1.0 : 1.0;
  const int count = model->nr_class == 2 ? model->l : 0;
  Eigen::MatrixXd points = Eigen::MatrixXd::Zero(count, d);  // LIBSVM rows are sparse
  Eigen::VectorXd weights(count);
  for (int i = 0; i < count; ++i) {
    for (const svm_node* node = model->SV[i]; node->index != -1; ++node)
      points(i, node->index - 1) = node->value;
    weights[i] = sign * model->sv_coef[0][i];
  }
  const double bias =
      model->nr_class == 2 ? -sign * model->rho[0] : (labels.empty() ? -1.0 : labels[0]);
  model_ = {jointSpaceModel(limits_, Kernel{KernelType::Gaussian, gamma_}, std::move(points),
                            std::move(weights)),
            bias};
}

}  // namespace fastron
