#pragma once
// The results of the planning experiments (plan, shelf, surgical, demo, motion-bench), typed: one
// row per planned query and method. They become text in one place: PlanRows::table() for
// results.csv, and the Markdown tables the reports share.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fastron/experiments/table.h"

namespace fastron::experiments {

/// How one method's plan of one query went.
struct PlanOutcome {
  bool solved = false;
  std::string status;          ///< "solved", or why not
  double planSeconds = 0;      ///< the plan itself, simplification included
  double simplifySeconds = 0;  ///< of which shortening the path
  double verifySeconds = 0;
  double repairSeconds = 0;
  double totalSeconds = 0;           ///< plan + verify + repair
  double pathLength = std::nan("");  ///< joint space; NaN unless solved
  std::size_t waypoints = 0;
  std::size_t repairedStretches = 0;
  std::size_t gradientRepairs = 0;  ///< of those, freed by gradient repair (no replanning)
  /// plans on the model that verification found colliding and the model learned from before
  /// planning again (planVerifiedLearning)
  std::size_t relearned = 0;
  double learnSeconds = 0;            ///< of planSeconds: that learning
  bool wholeMotionReplanned = false;  ///< the motion was planned again on the exact checker
  bool substituteEnds = false;        ///< planned between substitutes of start and goal
  /// The final path re-checked by an FCL checker the planner never used; empty unless solved.
  std::optional<bool> collidesUnderAudit;
  double exactShare = 0;         ///< of the plan's own collision queries, the share FCL answered
  std::size_t attempts = 0;      ///< plans before verification (VerifiedPlan::attempts)
  double failedPlanSeconds = 0;  ///< of planSeconds: the attempts that found no path
  std::uint64_t exactChecks = 0, relaxedChecks = 0;  ///< as in VerifiedPlan
  /// Configurations the attempts' sources answered (a model's, a hybrid's, FCL's own plan).
  std::uint64_t planChecks = 0;
  /// Those sources answering them (PlanAttempt::checkTime): within planSeconds, and within
  /// repairSeconds for a whole motion planned on the exact checker (wholeMotionReplanned), whose
  /// plan is an attempt too. The rest of the attempts' time is the planner's own work (sampling,
  /// nearest neighbours, simplification's bookkeeping).
  double planCheckSeconds = 0;
  double planCheckShare = 0;  ///< planCheckSeconds over the attempts' whole time
  /// Of those: the attempts on a bare model (PlanAttempt::onModel), their time, their checks
  /// (model queries) and the checks' time.
  double modelPlanSeconds = 0, modelCheckSeconds = 0;
  std::uint64_t modelChecks = 0;
  std::string plannedOn;  ///< the source whose path was verified (VerifiedPlan::plannedOn)
};

/// One plan of one query by one method.
struct PlanRow {
  /// What was planned, as (column, value) in column order: e.g. case and trial, or family,
  /// problem, query and note.
  std::vector<std::pair<std::string, std::string>> query;
  std::string planner;
  std::string method;
  PlanOutcome outcome;
  /// The experiment's own figures beside the plan, (column, value): e.g. the model's support
  /// count, accuracy and TPR, or the scene's training seconds.
  std::vector<std::pair<std::string, double>> figures;

  /// The value of a query column; throws InvalidArgument naming a column the row does not have.
  const std::string& queryValue(std::string_view column) const;
  /// The value of a figure; throws InvalidArgument naming a figure the row does not have.
  double figure(std::string_view column) const;
};

/// A query that could not be run, and why (e.g. a problem file that cannot be read).
struct SkippedQuery {
  std::vector<std::pair<std::string, std::string>> query;  ///< as PlanRow::query
  std::string error;
};

struct PlanRows {
  std::vector<PlanRow> rows;
  /// The queries a batch run went on past: a row each in table(), in no summary.
  std::vector<SkippedQuery> skipped;
  /// What the run noticed and went on past, for the report (e.g. SRDF entries naming links the
  /// robot lacks).
  std::vector<std::string> warnings;
  /// What the run built or read once for a robot, for the report (e.g. its self-pair tables).
  std::vector<std::string> notes;

  /// results.csv: the query columns, planner, method, the plan's columns (solved, status,
  /// plan_s, simplify_s, verify_s, repair_s, total_s, path_length, waypoints, stretches,
  /// relearned, relearn_s, fallback, exact_ends, collides_fcl, exact_share, attempts,
  /// failed_plan_s, plan_checks, plan_check_s, plan_check_share, model_plan_s, model_checks,
  /// model_check_s, exact_checks, relaxed_checks, planned_on), then the figures; then a row per
  /// skipped query (status "skipped: " and the error, no method, NaN figures). Throws
  /// InvalidArgument when the rows do not share their query and figure columns.
  Table table() const;
};

}  // namespace fastron::experiments
