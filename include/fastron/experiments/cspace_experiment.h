#pragma once
// The paper's Fig. 7: for random 2-DOF environments, the exact C-space (FCL) beside the C-spaces
// that Fastron, ISVM and SSVM learn, with their support points.

#include "fastron/experiments/progress.h"
#include "fastron/experiments/table.h"

namespace fastron::experiments {

struct CspaceOptions {
  std::size_t environments = 3;
  std::uint64_t seed = 1;
  bool quick = false;
};

struct CspaceResults {
  Table summary;  ///< environment, method, grid_accuracy, support
  Table grid;     ///< environment, x1, x2 (input space), truth, fastron, isvm, ssvm (scores)
  Table support;  ///< environment, method, x1, x2, weight
  Table cubes;    ///< environment, x, y, z, side, yaw
};

CspaceResults runCspace(const CspaceOptions& options, const Progress& progress);
std::string cspaceReport(const CspaceResults& results, const CspaceOptions& options);

}  // namespace fastron::experiments
