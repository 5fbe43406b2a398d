#include "fastron/experiments/plan_results.h"

#include <algorithm>

#include "fastron/core/error.h"

namespace fastron::experiments {
namespace {

template <class Value>
const Value& valueOf(const std::vector<std::pair<std::string, Value>>& pairs,
                     std::string_view column, const char* what) {
  const auto found = std::find_if(pairs.begin(), pairs.end(),
                                  [&](const auto& pair) { return pair.first == column; });
  if (found == pairs.end()) {
    throw InvalidArgument(std::string("a plan row has no ") + what + " '" + std::string(column) +
                          "'");
  }
  return found->second;
}

template <class Value>
std::vector<std::string> namesOf(const std::vector<std::pair<std::string, Value>>& pairs) {
  std::vector<std::string> names;
  for (const auto& [name, value] : pairs) names.push_back(name);
  return names;
}

}  // namespace

const std::string& PlanRow::queryValue(std::string_view column) const {
  return valueOf(query, column, "query column");
}

double PlanRow::figure(std::string_view column) const {
  return valueOf(figures, column, "figure");
}

Table PlanRows::table() const {
  Table table;
  if (rows.empty() && skipped.empty()) return table;
  const std::vector<std::string> queryColumns =
      namesOf(rows.empty() ? skipped.front().query : rows.front().query);
  const std::vector<std::string> figureColumns =
      rows.empty() ? std::vector<std::string>{} : namesOf(rows.front().figures);
  table.columns = queryColumns;
  // clang-format off
  for (const char* column :
       {"planner", "method", "solved", "status", "plan_s", "simplify_s", "verify_s", "repair_s",
        "total_s", "path_length", "waypoints", "stretches", "gradient_repairs", "relearned", "relearn_s", "fallback",
        "exact_ends", "collides_fcl", "exact_share", "attempts", "failed_plan_s", "plan_checks",
        "plan_check_s", "plan_check_share", "model_plan_s", "model_checks", "model_check_s",
        "exact_checks", "relaxed_checks", "planned_on"}) {
    table.columns.emplace_back(column);
  }
  // clang-format on
  table.columns.insert(table.columns.end(), figureColumns.begin(), figureColumns.end());
  const auto flag = [](bool b) { return std::string(b ? "1" : "0"); };
  for (const PlanRow& row : rows) {
    if (namesOf(row.query) != queryColumns || namesOf(row.figures) != figureColumns) {
      throw InvalidArgument("plan rows of one table must share their columns; row of " +
                            row.method + " differs");
    }
    std::vector<std::string> cells;
    for (const auto& [name, value] : row.query) cells.push_back(value);
    const PlanOutcome& o = row.outcome;
    const std::vector<std::string> plan{
        row.planner,
        row.method,
        flag(o.solved),
        o.status,
        cell(o.planSeconds),
        cell(o.simplifySeconds),
        cell(o.verifySeconds),
        cell(o.repairSeconds),
        cell(o.totalSeconds),
        cell(o.pathLength),
        std::to_string(o.waypoints),
        std::to_string(o.repairedStretches),
        std::to_string(o.gradientRepairs),
        std::to_string(o.relearned),
        cell(o.learnSeconds),
        flag(o.wholeMotionReplanned),
        flag(o.substituteEnds),
        o.collidesUnderAudit ? cell(*o.collidesUnderAudit ? 1.0 : 0.0) : cell(std::nan("")),
        cell(o.exactShare),
        std::to_string(o.attempts),
        cell(o.failedPlanSeconds),
        std::to_string(o.planChecks),
        cell(o.planCheckSeconds),
        cell(o.planCheckShare),
        cell(o.modelPlanSeconds),
        std::to_string(o.modelChecks),
        cell(o.modelCheckSeconds),
        std::to_string(o.exactChecks),
        std::to_string(o.relaxedChecks),
        o.plannedOn};
    cells.insert(cells.end(), plan.begin(), plan.end());
    for (const auto& [name, value] : row.figures) cells.push_back(cell(value));
    table.add(std::move(cells));
  }
  for (const SkippedQuery& query : skipped) {
    if (namesOf(query.query) != queryColumns)
      throw InvalidArgument("a skipped query's columns differ from the plan rows'");
    std::vector<std::string> cells;
    for (const auto& [name, value] : query.query) cells.push_back(value);
    const std::string nan = cell(std::nan(""));
    cells.insert(cells.end(), {"", "", "0", "skipped: " + query.error});
    cells.resize(table.columns.size() - 1, nan);  // plan columns, then the figures; planned_on
    cells.insert(cells.end() - static_cast<std::ptrdiff_t>(figureColumns.size()), "");
    table.add(std::move(cells));
  }
  return table;
}

}  // namespace fastron::experiments
