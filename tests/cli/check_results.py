#!/usr/bin/python3
"""Checks the results of `fastron bench NAME --quick` for shape and sane values.

Usage: check_results.py NAME OUTPUT_DIR [--no-timing]; exits non-zero with a message naming the
problem. --no-timing skips the speed comparisons, for sanitizer builds whose instrumentation slows
the vectorised model far more than FCL's code, which is not instrumented.
"""
import csv
import math
import re
import sys
from pathlib import Path


TIMING = "--no-timing" not in sys.argv


def fail(message):
    sys.exit(f"check_results: {message}")


def rows_of(out):
    with open(out / "results.csv", newline="") as f:
        # A batch run's problems it could not run are rows of their own, with no method.
        rows = [r for r in csv.DictReader(f) if not r.get("status", "").startswith("skipped: ")]
    if not rows:
        fail("results.csv has no rows")
    return rows


def value(row, key):
    text = row[key]
    return math.nan if text == "nan" else float(text)


def rate_columns(rows, keys):
    for row in rows:
        for key in keys:
            v = value(row, key)
            if not math.isnan(v) and not 0.0 <= v <= 1.0:
                fail(f"{key} = {v} is not a rate in [0, 1]: {row}")


def check_static(rows):
    rate_columns(rows, ["accuracy", "tpr", "tnr", "cobs_fraction"])
    for row in rows:
        if row["qp_stopped"] not in ("0", "1") or (row["qp_stopped"] == "1" and row["method"] != "SSVM"):
            fail(f"qp_stopped must be 0 or 1, and 1 only for SSVM: {row}")
    methods = {r["method"] for r in rows}
    expected = {"Fastron", "ISVM", "SSVM", "LIBSVM", "FK+GJK", "FK+FCL"}
    if methods != expected:
        fail(f"methods {sorted(methods)}, expected {sorted(expected)}")
    for dof in {r["dof"] for r in rows}:
        def mean(method, key):
            values = [value(r, key) for r in rows if r["dof"] == dof and r["method"] == method]
            return sum(values) / len(values)
        if mean("FK+FCL", "accuracy") != 1.0:
            fail("FCL disagrees with its own labels")
        if TIMING and not mean("Fastron", "train_s") < mean("SSVM", "train_s"):
            fail(f"{dof} DOF: Fastron trained slower than SSVM")
        if TIMING and not mean("Fastron", "query_s") < mean("FK+FCL", "query_s"):
            fail(f"{dof} DOF: Fastron queried slower than FK+FCL")
        if mean("Fastron", "accuracy") < 0.75:
            fail(f"{dof} DOF: Fastron accuracy {mean('Fastron', 'accuracy')}")


def check_sweep(rows, parameter):
    rate_columns(rows, ["accuracy", "tpr", "tnr"])
    values = sorted({float(r[parameter]) for r in rows})
    if len(values) < 5:
        fail(f"only {len(values)} values of {parameter}")
    for row in rows:
        if not 0 < value(row, "support_ratio") <= 1:
            fail(f"support_ratio out of (0, 1]: {row}")


def check_plans(rows, methods, every_method_solves=True, paper="Fastron"):
    """Planning experiments: every final path is free under FCL, times add up, and (unless the
    queries are hard enough that any planner may time out, as the UR3 shelf's) each method solves
    something. `paper` names the paper's model-only method (its plans ask FCL nothing)."""
    found = {r["method"] for r in rows}
    if found != set(methods):
        fail(f"methods {sorted(found)}, expected {sorted(methods)}")
    for row in rows:
        if row["solved"] not in ("0", "1"):
            fail(f"solved must be 0 or 1: {row}")
        share = value(row, "exact_share")
        expected_share = {paper: 0, "GJK": 0, "FCL": 1}.get(row["method"])
        if not 0 <= share <= 1 or (expected_share is not None and share != expected_share):
            fail(f"share of plan queries FCL answered out of place: {row}")
        if row["solved"] == "1":
            if value(row, "collides_fcl") != 0:
                fail(f"a final path collides under FCL: {row}")
            times = [value(row, k) for k in ("plan_s", "verify_s", "repair_s", "total_s")]
            if any(t < 0 for t in times) or abs(sum(times[:3]) - times[3]) > 1e-6 * max(1.0, times[3]):
                fail(f"plan + verify + repair != total: {row}")
            if row["method"] == "FCL" and (value(row, "verify_s") != 0 or value(row, "repair_s") != 0):
                fail(f"FCL plans need no verify or repair: {row}")
            # Where the time went: at least the plan that was verified; failed attempts within
            # the plan's time; an exact check at least for verification (or the plan itself).
            if value(row, "attempts") < 1 or not 0 <= value(row, "failed_plan_s") <= times[0] + 1e-9:
                fail(f"attempts or failed_plan_s out of place: {row}")
            if value(row, "exact_checks") < 1 or value(row, "plan_checks") < 1:
                fail(f"a solved plan with no exact check or none on its own source: {row}")
            if row["method"] == "FCL" and value(row, "plan_checks") != value(row, "exact_checks"):
                fail(f"FCL's plan is all its exact checks: {row}")
            if row["method"] in ("FCL", "GJK", paper) and value(row, "relaxed_checks") != 0:
                fail(f"only the default method asks a relaxed oracle: {row}")
            # The checks' time within the attempts' (the clock read around each one is counted
            # in both): the plan's, and the repair's when the whole motion was planned exactly;
            # the bare model's attempts within all of them.
            if not 0 < value(row, "plan_check_s") <= times[0] + times[2] + 1e-9:
                fail(f"plan_check_s out of place: {row}")
            if not 0 < value(row, "plan_check_share") <= 1:
                fail(f"plan_check_share out of place: {row}")
            model = [value(row, k) for k in ("model_plan_s", "model_checks", "model_check_s")]
            if not (0 <= model[2] <= model[0] <= times[0] + 1e-9 and model[1] <= value(row, "plan_checks")):
                fail(f"the bare model's attempts out of place: {row}")
            if row["method"] == "FCL" and model != [0, 0, 0]:
                fail(f"FCL's plan asks no model: {row}")
        elif row["status"] == "solved":
            fail(f"status 'solved' on an unsolved row: {row}")
    # The source whose path was verified: the exact checker's after a whole-motion fallback, and
    # for Fastron otherwise the model or (after its time box) its hybrid.
    exact_names = {r["planned_on"] for r in rows if r["method"] == "FCL"}
    if len(exact_names) != 1 or "" in exact_names:
        fail(f"FCL rows must name one exact checker in planned_on, found {sorted(exact_names)}")
    exact = exact_names.pop()
    for row in rows:
        if row["solved"] != "1":
            continue
        if row["fallback"] == "1" and row["planned_on"] != exact:
            fail(f"a whole-motion fallback planned on {row['planned_on']!r}, not {exact!r}: {row}")
        if row["method"] == paper and row["fallback"] == "0" and row["planned_on"] not in (
                "Fastron", "Fastron+" + exact):
            fail(f"a Fastron path planned on {row['planned_on']!r}: {row}")
    for method in methods if every_method_solves else []:
        if not any(r["solved"] == "1" for r in rows if r["method"] == method):
            fail(f"{method} solved no query")


def main():
    name, out = sys.argv[1], Path(sys.argv[2])
    rows = rows_of(out)
    report = (out / "report.md").read_text()
    if "|---|" not in report:
        fail("report.md has no table")
    if name == "static":
        check_static(rows)
    elif name == "changing":
        rate_columns(rows, ["accuracy", "tpr", "tnr"])
        for case in {r["case"] for r in rows}:
            def mean(method, key):
                values = [value(r, key) for r in rows if r["case"] == case and r["method"] == method]
                return sum(values) / len(values)
            if TIMING and not mean("Fastron (FCL)", "query_s") < mean("FK+FCL", "query_s"):
                fail(f"{case}: Fastron queried slower than FK+FCL")
            if mean("Fastron (FCL)", "accuracy") < 0.6:
                fail(f"{case}: Fastron accuracy {mean('Fastron (FCL)', 'accuracy')}")
            if not all(value(r, "update_s") > 0 for r in rows if r["method"].startswith("Fastron")):
                fail("an update took no time")
        for r in rows:
            if not r["method"].startswith("Fastron"):
                continue
            parts = [value(r, k) for k in ("sample_s", "label_s", "train_s")]
            if any(p < 0 for p in parts) or sum(parts) > value(r, "update_s") * (1 + 1e-9):
                fail(f"sampling + labelling + training exceed the update: {r}")
    elif name == "sweep":
        rate_columns(rows, ["cobs_fraction"])
        counts = sorted({int(r["obstacles"]) for r in rows})
        def gjk(count):
            return [value(r, "query_s") for r in rows if r["method"] == "FK+GJK" and int(r["obstacles"]) == count][0]
        if TIMING and not gjk(counts[-1]) > gjk(counts[0]):
            fail("GJK did not get slower with more obstacles")
    elif name == "cspace":
        rate_columns(rows, ["grid_accuracy"])
        for row in rows:
            if value(row, "grid_accuracy") < 0.8:
                fail(f"{row['method']} grid accuracy {row['grid_accuracy']}")
    elif name in ("plan", "shelf", "surgical"):
        check_plans(rows, ["Fastron", "Hybrid", "GJK", "FCL"], every_method_solves=name != "shelf")
        if name == "plan" and {r["planner"] for r in rows} != {"RRT", "RRTConnect", "RRT*", "BIT*"}:
            fail(f"planners {sorted({r['planner'] for r in rows})}")
    elif name == "motion-bench":
        # The split model plans only with --self-model, whose run reports its training.
        split = "- Fastron split: trained in" in report
        if "Default method: Fastron (what `fastron plan` does)" not in report:
            fail("report.md does not name the default method")
        if not re.search(r"Median end-to-end time of FCL / of each method, training included "
                         r"\(one query per scene\): RRTConnect: Fastron [0-9.]+x", report):
            fail("report.md has no end-to-end line with training for the default method")
        check_plans(rows, ["Fastron", "Fastron (paper)", "Hybrid (paper)", "FCL"] +
                    (["Fastron split"] if split else []), paper="Fastron (paper)")
        if split != any(r["method"] == "Fastron split" for r in rows):
            fail("report.md and results.csv disagree about the split model")
        for row in rows:
            relearned = value(row, "relearned")
            if row["method"] != "Fastron" and (relearned != 0 or value(row, "relearn_s") != 0):
                fail(f"only the default method learns within a query: {row}")
            if relearned > 3 or (relearned > 0 and not 0 < value(row, "relearn_s") <= value(row, "plan_s")):
                fail(f"learning rounds out of place: {row}")
        # Every model's accuracy and TPR beside its speed, scored against FCL per scene.
        rate_columns([r for r in rows if r["method"] != "FCL"], ["accuracy", "tpr"])
        for row in rows:
            if row["method"] != "FCL" and math.isnan(value(row, "accuracy")):
                fail(f"no accuracy for a model: {row}")
        if "Models per scene:\n- Fastron: trained in" not in report:
            fail("report.md does not give the trained models' accuracy")
        # The default method's control points: one rule per robot, the same in every scene.
        chosen = {r["cover_rule"] for r in rows if r["method"] == "Fastron"}
        if not chosen <= {"0", "1"} or len(chosen) != 1:
            fail(f"the default method's control points are not one rule for the robot: {chosen}")
        if any(r["cover_rule"] != "0" for r in rows if r["method"] != "Fastron"):
            fail("only the default method chooses its control points")
        if not re.search(r"the spread rule's in [0-9]+ scenes, the cover rule's in [0-9]+\)", report):
            fail("report.md does not say which control points the default method kept")
        # Along FCL's own path of each request: rates, measured wherever FCL solved the request.
        rate_columns(rows, ["fcl_path_near_walls", "fcl_path_called_colliding"])
        for row in rows:
            measured = not math.isnan(value(row, "fcl_path_near_walls"))
            fcl_solved = any(r["method"] == "FCL" and r["solved"] == "1" for r in rows
                             if (r["family"], r["problem"], r["query"]) ==
                             (row["family"], row["problem"], row["query"]))
            if measured != (row["query"] == "0" and fcl_solved):
                fail(f"the path figures are measured on the solved requests only: {row}")
        if "Along FCL's own path of each request" not in report:
            fail("report.md does not say where the model stands along FCL's paths")
    elif name == "sensed":
        rate_columns(rows, ["accuracy_cloud", "tpr_cloud", "accuracy_truth", "tpr_truth", "cloud_truth"])
        for r in rows:
            if not value(r, "raw_points") >= value(r, "kept_points") >= value(r, "reach_points") > 1000:
                fail(f"the cloud does not shrink from raw to kept to in reach, or is nearly empty: {r}")
            if not value(r, "ingest_s") > 0 or not value(r, "update_s") >= value(r, "label_s") + value(r, "train_s") * 0.999:
                fail(f"ingest or update times do not add up: {r}")
            if value(r, "cloud_truth") < 0.9:
                fail(f"FCL on the cloud and on the boxes disagree on {1 - value(r, 'cloud_truth')} of the configurations")
        if sum(value(r, "accuracy_cloud") for r in rows) / len(rows) < 0.85:
            fail("the model's accuracy against FCL on the cloud is below 0.85")
        plans = list(csv.DictReader(open(out / "plans.csv", newline="")))
        if {p["method"] for p in plans} != {"Fastron", "FCL"}:
            fail(f"methods {sorted({p['method'] for p in plans})}")
        if not any(p["solved"] == "1" for p in plans):
            fail("no plan was solved")
        scene = list(csv.DictReader(open(out / "scene.csv", newline="")))
        if len(scene) < 1000:
            fail("scene.csv holds too few of the cloud's points for a picture")
    elif name == "optimize":
        rate_columns(rows, ["accuracy", "tpr"])
        if {r["method"] for r in rows} != {"Optimizer", "FCL", "Fastron"}:
            fail(f"methods {sorted({r['method'] for r in rows})}")
        for r in rows:
            # Verified every 0.03 rad, a path may graze between those states: the audit at a
            # third of the step reports it, for every method alike.
            if r["colliding"] not in ("0", "1") or (r["colliding"] == "1" and r["solved"] != "1"):
                fail(f"colliding must be 0 or 1, and 1 only for a solved path: {r}")
            if r["method"] == "Optimizer" and not value(r, "rounds") >= 1:
                fail(f"the optimiser ran no round: {r}")
        optimised = [r for r in rows if r["method"] == "Optimizer"]
        if not any(r["solved"] == "1" for r in optimised):
            fail("the optimiser solved no query")
        scores = list(csv.DictReader(open(out / "scores.csv", newline="")))
        for trial in {r["trial"] for r in optimised if r["solved"] == "1"}:
            before = [value(s, "score") for s in scores if s["trial"] == trial and s["path"] == "before"]
            if not before or max(before) <= 0:
                fail(f"query {trial}: the straight line must cross the model's collisions")
    elif name.startswith("static-"):
        check_sweep(rows, name.split("-")[1])
    else:
        fail(f"no checks for '{name}'")
    print(f"{name}: {len(rows)} result rows look sane")


if __name__ == "__main__":
    main()
