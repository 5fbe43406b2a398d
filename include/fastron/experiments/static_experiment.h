#pragma once
// The paper's static-environment experiments (Sec. IV-A): the 2-DOF and 4-DOF rods among up to
// four random cubes, FCL labels; Fastron against ISVM, SSVM, LIBSVM and the exact checkers
// (Fig. 5 and its tables), and Fastron's beta and gamma sweeps (Figs. 4 and 6).

#include <string>
#include <vector>

#include "fastron/experiments/progress.h"
#include "fastron/experiments/table.h"

namespace fastron::experiments {

struct StaticOptions {
  std::size_t trials = 10;
  std::uint64_t seed = 1;
  bool quick = false;  ///< small N and test sets: for the test suite
  std::vector<int> dofs{2, 4};
  double beta = 1;  ///< Fastron's conditional bias in the method comparison
};

/// One row per (dof, trial, method): accuracy, tpr, tnr, support, query_s, train_s (including
/// labelling), obstacles, cobs_fraction.
Table runStatic(const StaticOptions& options, const Progress& progress);

/// Fastron only, one row per (dof, trial, value) of `parameter` ("beta" or "gamma"): accuracy,
/// tpr, tnr, support_ratio (|S| / N).
Table runStaticSweep(const StaticOptions& options, const std::string& parameter,
                     const Progress& progress);

/// The Markdown report: the paper's tables with our mean ± std beside the paper's values.
std::string staticReport(const Table& results, const StaticOptions& options);
std::string staticSweepReport(const Table& results, const std::string& parameter,
                              const StaticOptions& options);

}  // namespace fastron::experiments
