"""Robots, scenes, exact checkers, the proxy pipeline and planning from Python."""
import os
import pathlib
import threading
import time

import numpy as np
import pytest

import fastron
from conftest import uniform


def test_robot_and_forward_kinematics(baxter):
    assert baxter.dof == 7 and len(baxter.joint_names) == 7
    assert baxter.limits.lower.shape == (7,)
    one = baxter.link_positions(np.zeros(7))
    assert one.shape == (len(baxter.link_names), 3)
    many = baxter.link_positions(np.zeros((4, 7)))
    assert many.shape == (4, len(baxter.link_names), 3) and np.array_equal(many[2], one)
    # The base link sits at the origin; a joint moves the links after it.
    assert np.allclose(one[baxter.link_names.index("base")], 0)
    moved = baxter.link_positions(np.array([0.5, 0, 0, 0, 0, 0, 0]))
    assert np.abs(moved - one).max() > 0.1


def test_automatic_control_points_follow_their_limits(baxter):
    assert fastron.robot_features(baxter).feature_dim == 12  # 4 points by default
    assert fastron.robot_features(baxter, max_points=2).feature_dim == 6
    assert fastron.robot_features(baxter, max_points=0).feature_dim > 12
    assert fastron.robot_features(baxter, "joints", max_points=2).feature_dim == 7
    # The cover rule spreads the points along the chain: other points, as many.
    cover = fastron.robot_features(baxter, rule="cover")
    assert cover.feature_dim == 12
    q = np.array([0.3, -0.2, 0.1, 1.0, 0.2, 0.5, 0.0])
    assert not np.allclose(cover.map(q), fastron.robot_features(baxter).map(q))
    mesh = fastron.load_robot("panda-mesh")
    # Three points at most on the hand's rigid body; without the limit it takes all four.
    a = fastron.robot_features(mesh).map(np.zeros(7))
    b = fastron.robot_features(mesh, max_per_body=0).map(np.zeros(7))
    assert a.shape == b.shape == (12,) and not np.array_equal(a, b)
    with pytest.raises(fastron.InvalidArgument, match="spacing"):
        fastron.robot_features(baxter, min_spacing=-1)


def test_task_space_kernels_by_default_and_on_request(baxter, baxter_fcl):
    features = fastron.robot_features(baxter)
    x = np.random.default_rng(5).uniform(baxter.limits.lower, baxter.limits.upper, (600, 7))
    y = baxter_fcl.in_collision(x)
    model, _ = fastron.train(x, y, features=features)
    assert (model.kernel_block, model.kernel_whole_share) == (3, 0.5)
    assert (model.gamma, model.kernel) == (40, "rq")
    self_model, _ = fastron.train(x, y, features=features, self_collision_labels=True)
    assert (self_model.kernel_block, self_model.gamma) == (0, 40)  # one term, beta 10
    chosen, _ = fastron.train(x, y, features=features, kernel_block=6, kernel_whole_share=0.5)
    assert (chosen.kernel_block, chosen.kernel_whole_share) == (6, 0.5)
    assert np.all(np.sign(chosen.score(x)) == np.where(y, 1, -1))  # Claim 1
    with pytest.raises(fastron.InvalidArgument, match="kernel block 5 does not divide"):
        fastron.train(x, y, features=features, kernel_block=5)


def test_checkers_agree_with_the_command_labels(tmp_path, fastron_command, baxter, baxter_fcl):
    import subprocess
    data = tmp_path / "s.csv"
    scene = fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml"
    subprocess.run([fastron_command, "sample", "--robot", "baxter", "--scene", scene, "-n", "500",
                    "-o", data], check=True, capture_output=True)
    x, y = fastron.read_dataset(data)
    assert np.array_equal(baxter_fcl.in_collision(x), y > 0)
    gjk = fastron.GjkChecker(baxter, fastron.load_scene(scene))
    assert np.mean(gjk.in_collision(x) == (y > 0)) > 0.97  # convex hulls of the same shapes


def test_contacts_distance_and_moving_scenes(baxter):
    scene = fastron.Scene()
    scene.add_box("wall", [0.1, 2, 2], [0.6, 0, 0.3])
    fcl = fastron.FclChecker(baxter, scene)
    x = uniform(baxter.limits, 400, seed=3)
    hits = fcl.in_collision(x)
    assert 0 < hits.sum() < len(x)
    contact = fcl.first_contact(x[np.argmax(hits)])
    assert contact.other == "wall" and contact.robot_link in baxter.link_names
    free = x[np.argmin(hits)]
    assert fcl.first_contact(free) is None and fcl.distance(free) > 0
    scene.set_pose("wall", [5, 0, 0])
    fcl.set_scene(scene)
    assert not fcl.in_collision(x).any()
    assert np.allclose(scene.position("wall"), [5, 0, 0])


def test_scene_checkers_by_name_share_one_interface(tmp_path, fastron_command, baxter,
                                                   three_boxes):
    import subprocess
    assert fastron.scene_checker_names()[0] == "fcl"
    assert set(fastron.scene_checker_names()) >= {"fcl", "gjk"}
    x = uniform(baxter.limits, 300, seed=6)
    for name in fastron.scene_checker_names():
        checker = fastron.scene_checker(name, baxter, three_boxes, self_collision=True)
        assert isinstance(checker, fastron.SceneChecker) and checker.robot.name == "baxter"
        hits = checker.in_collision(x)
        assert 0 < hits.sum() < len(x)
        assert checker.first_contact(x[np.argmax(hits)]) is not None
        assert checker.first_contact(x[np.argmin(hits)]) is None
        if checker.measures_distance:
            assert checker.distance(x[np.argmin(hits)]) > 0
        else:
            with pytest.raises(fastron.Unsupported, match="does not measure distances"):
                checker.distance(x[0])
            with pytest.raises(NotImplementedError):
                checker.distance(x[0])
        # A plan's limits come from the checker's robot, whichever backend it is.
        assert fastron.check_path(checker, x[np.argmin(hits)][None, :], 0.05)
    assert isinstance(fastron.scene_checker("gjk", baxter, three_boxes), fastron.GjkChecker)
    with pytest.raises(fastron.InvalidArgument, match="unknown checker 'bullet' \\(known: fcl"):
        fastron.scene_checker("bullet", baxter, three_boxes)
    # The command's --checker labels as the checker of that name does.
    data = tmp_path / "gjk.csv"
    scene = fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml"
    subprocess.run([fastron_command, "sample", "--robot", "baxter", "--scene", scene, "-n", "300",
                    "--checker", "gjk", "-o", data], check=True, capture_output=True)
    q, y = fastron.read_dataset(data)
    assert np.array_equal(fastron.scene_checker("gjk", baxter, three_boxes).in_collision(q), y > 0)


def test_motions_checked_whole_answer_as_every_state(baxter, three_boxes):
    certified = fastron.FclChecker(baxter, three_boxes, self_collision=True)
    dense = fastron.FclChecker(baxter, three_boxes, self_collision=True, prove_motions_free=False)
    assert certified.proves_motions_free and not dense.proves_motions_free
    starts = uniform(baxter.limits, 400, seed=4)
    starts = starts[~dense.in_collision(starts)][:100]
    steps = np.random.default_rng(5).normal(size=starts.shape)
    ends = np.clip(starts + 0.8 * steps / np.linalg.norm(steps, axis=1)[:, None],
                   baxter.limits.lower, baxter.limits.upper)
    looked_certified = looked_dense = colliding = 0
    for start, end in zip(starts, ends):
        state, looked = certified.motion_collision(start, end, 60)
        dense_state, dense_looked = dense.motion_collision(start, end, 60)
        assert (state is None) == (dense_state is None)
        if state is not None:  # the state named collides
            assert dense.in_collision(start + (end - start) * state / 60)
            colliding += 1
        looked_certified += looked
        looked_dense += dense_looked
    assert 0 < colliding < len(starts)
    assert looked_certified < looked_dense
    with pytest.raises(fastron.InvalidArgument, match="start"):
        certified.motion_collision(starts[0][:3], ends[0], 10)
    with pytest.raises(fastron.InvalidArgument, match="segments"):
        certified.motion_collision(starts[0], ends[0], 0)


def test_python_oracle_and_gil(tmp_path):
    calls = []
    threads = set()

    def disc(q):
        calls.append(1)
        threads.add(threading.get_ident())
        return bool(np.hypot(q[0] - 0.2, q[1]) < 0.5)

    features = fastron.FeatureMap.joint_scaling(fastron.JointLimits([-2, -2], [2, 2]))
    detector = fastron.ProxyCollisionDetector(disc, features, gamma=30, beta=5)
    report = detector.initialize(1500)
    assert report.labelled == len(calls) and len(threads) == 1
    model = detector.model()
    assert model.in_collision(np.array([0.2, 0])) and not model.in_collision(np.array([1.5, 1.5]))

    def failing(q):
        raise RuntimeError("oracle broke")

    with pytest.raises(RuntimeError, match="oracle broke"):
        fastron.ProxyCollisionDetector(failing, features).initialize(10)


def test_updates_from_zero_weights_or_the_last_ones():
    # cold_start chooses how each step() runs Algorithm 1; both keep a disc that moves learnt.
    centre = {"x": 0.0}

    def disc(q):
        return bool(np.hypot(q[0] - centre["x"], q[1]) < 0.5)

    features = fastron.FeatureMap.joint_scaling(fastron.JointLimits([-2, -2], [2, 2]))
    for cold in (True, False):
        centre["x"] = 0.0
        detector = fastron.ProxyCollisionDetector(disc, features, gamma=30, beta=5,
                                                  active_samples=800, cold_start=cold,
                                                  calibration_samples=0)
        detector.initialize(1500)
        for _ in range(5):
            centre["x"] += 0.1
            report = detector.step()
            assert report.added == 800
        model = detector.model()
        assert model.in_collision(np.array([0.5, 0])), cold
        assert not model.in_collision(np.array([-0.4, 0])), cold  # the disc left it


def test_a_world_that_stands_still_needs_no_relabelling():
    # The same model with as many fewer oracle calls per step as the support set has points.
    def disc(q):
        return bool(np.hypot(q[0], q[1]) < 0.5)

    features = fastron.FeatureMap.joint_scaling(fastron.JointLimits([-2, -2], [2, 2]))
    made = []
    for relabel in (True, False):
        detector = fastron.ProxyCollisionDetector(disc, features, gamma=30, beta=5,
                                                  active_samples=400, cold_start=False,
                                                  calibration_samples=0, relabel_support=relabel)
        detector.initialize(1500)
        support = detector.model().support_count
        made.append((support, detector.step().labelled, detector.model()))
    (support, relabelling, a), (_, still, b) = made
    assert relabelling == still + support
    np.testing.assert_array_equal(a.weights, b.weights)


def test_oracle_faults_keep_the_last_good_model():
    broken = {"on": False}

    def disc(q):
        if broken["on"]:
            raise RuntimeError("sensor offline")
        return bool(np.hypot(q[0], q[1]) < 0.5)

    features = fastron.FeatureMap.joint_scaling(fastron.JointLimits([-1, -1], [1, 1]))
    detector = fastron.ProxyCollisionDetector(disc, features, gamma=30, beta=5,
                                              calibration_samples=100)
    detector.initialize(500)
    version, checksum = detector.model_version, detector.model().checksum
    broken["on"] = True
    with pytest.raises(fastron.OracleFault, match="oracle 'python' failed: .*sensor offline"):
        detector.step()
    assert detector.model_version == version and detector.model().checksum == checksum

    # In the background: faults are counted and reported, and the detector recovers.
    detector.start_background()
    deadline = time.time() + 10
    while detector.background_health().faults < 2 and time.time() < deadline:
        time.sleep(0.01)
    health = detector.background_health()
    assert health.faults >= 2 and health.steps == 0 and "sensor offline" in health.last_fault
    broken["on"] = False
    while detector.background_health().steps < 1 and time.time() < deadline:
        time.sleep(0.01)
    detector.stop_background()
    health = detector.background_health()
    assert health.steps >= 1 and health.consecutive_faults == 0
    assert detector.model_version > version


def test_long_calls_release_the_gil(baxter, baxter_fcl):
    """A Python thread keeps running while C++ labels and trains."""
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    detector = fastron.ProxyCollisionDetector(baxter_fcl, fastron.robot_features(baxter))
    thread = threading.Thread(target=tick)
    thread.start()
    start = time.perf_counter()
    detector.initialize(40000)
    elapsed = time.perf_counter() - start
    done.set()
    thread.join()
    during = [t for t in ticks if start < t < start + elapsed]
    assert len(during) >= max(3, 0.2 * elapsed / 0.001), (elapsed, len(during))


def test_train_scene_measures_each_round_on_fresh_configurations(baxter, baxter_fcl):
    features = fastron.robot_features(baxter)
    model, rounds, kept = fastron.train_scene(baxter_fcl, features, 1000, accuracy=1.0,
                                              held_out=1000, max_samples=3000, seed=2)
    assert [r[0] for r in rounds] == [1000, 2000, 3000]
    assert rounds[kept][1] == model.support_count
    assert all(r[2].total == 1000 for r in rounds)
    # The kept round comes closest to the targets (accuracy 1, TPR 0.96).
    lacking = [1.0 - r[2].accuracy + max(0.0, 0.96 - r[2].tpr) for r in rounds]
    assert lacking[kept] == min(lacking)
    # Each round's counts are of configurations its model never learned, so a fresh sample of
    # the scene agrees with them within sampling noise.
    q = uniform(baxter.limits, 4000, seed=9)
    fresh = fastron.evaluate(model, q, baxter_fcl.in_collision(q))
    assert abs(fresh.accuracy - rounds[kept][2].accuracy) < 0.03

    _, one, first = fastron.train_scene(baxter_fcl, features, 1000, accuracy=0.5, tpr=0.5,
                                        held_out=500)
    assert len(one) == 1 and one[0][0] == 1000 and first == 0
    with pytest.raises(fastron.InvalidArgument, match="target accuracy must be in"):
        fastron.train_scene(baxter_fcl, features, 100, accuracy=2.0)


def test_train_scene_trains_an_alternative_in_each_round_that_misses(baxter, baxter_fcl):
    features = fastron.robot_features(baxter)
    five = fastron.robot_features(baxter, max_points=5)
    model, rounds, kept = fastron.train_scene(baxter_fcl, features, 1000, accuracy=1.0,
                                              held_out=1000, max_samples=2000,
                                              alternatives=[(five, 10.0)])
    # Every round misses accuracy 1: both candidates learn the same samples, in turn.
    assert [(r[0], r[4]) for r in rounds] == [(1000, 0), (1000, 1), (2000, 0), (2000, 1)]
    assert all(r[2].total == 1000 for r in rounds)
    assert rounds[kept][1] == model.support_count
    assert model.feature_dim == (five if rounds[kept][4] == 1 else features).feature_dim
    lacking = [1.0 - r[2].accuracy + max(0.0, 0.96 - r[2].tpr) for r in rounds]
    assert lacking[kept] == min(lacking)
    with pytest.raises(fastron.InvalidArgument, match="reads 4 joint values, the first 7"):
        four_joints = fastron.FeatureMap.joint_scaling(fastron.JointLimits([0] * 4, [1] * 4))
        fastron.train_scene(baxter_fcl, features, 100, alternatives=[(four_joints, None)])


def test_train_scene_learns_a_grown_oracles_labels_when_only_the_tpr_misses(
        baxter, three_boxes, baxter_fcl):
    features = fastron.robot_features(baxter)
    roomy = fastron.FclChecker(baxter, three_boxes.grown(0.03))
    _, rounds, _ = fastron.train_scene(baxter_fcl, features, 1000, accuracy=0.0, tpr=1.0,
                                       held_out=1000, max_samples=3000, grown_oracles=[roomy])
    assert [r[3] for r in rounds] == [0, 1, 1][:len(rounds)] and len(rounds) >= 2
    # A Python oracle works too; calling everything a collision meets TPR 1 on the exact labels,
    # where the free configurations are its false positives.
    _, rounds, kept = fastron.train_scene(baxter_fcl, features, 1000, accuracy=0.0, tpr=1.0,
                                          held_out=1000, grown_oracles=(lambda q: True,))
    assert [r[3] for r in rounds] == [0, 1] and kept == 1
    assert rounds[1][2].tpr == 1.0 and rounds[1][2].true_negatives == 0
    assert rounds[1][2].false_positives > 0
    with pytest.raises(fastron.InvalidArgument, match="margin must be finite"):
        three_boxes.grown(-0.01)


def test_background_updates_and_snapshots(baxter, three_boxes):
    scene = three_boxes
    fcl = fastron.FclChecker(baxter, scene)
    detector = fastron.ProxyCollisionDetector(fcl, fastron.robot_features(baxter), seed=4)
    detector.initialize(3000)
    first = detector.model()
    q = uniform(baxter.limits, 200, seed=8)
    before = first.score(q)
    detector.start_background(min_period=0.01)
    for _ in range(5):
        scene.step()
        fcl.set_scene(scene)
        time.sleep(0.02)
        detector.model().score(q)  # snapshots stay queryable during updates
    detector.stop_background()
    assert not detector.background_running
    assert detector.model() is not first  # the first background step finishes before stopping
    assert np.array_equal(first.score(q), before)  # an old snapshot never changes


def test_planning_verified_paths_never_collide(baxter):
    scene = fastron.load_scene(fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml")
    fcl = fastron.FclChecker(baxter, scene)
    inner = fastron.Scene()
    for name in ("box1", "box2", "box3"):  # the scene's 0.2 m boxes, 1 cm smaller on every side
        inner.add_box(name, [0.18] * 3, scene.position(name))
    shrunk = fastron.FclChecker(baxter, inner)
    detector = fastron.ProxyCollisionDetector(fcl, fastron.robot_features(baxter), seed=2)
    detector.initialize(6000)
    x = uniform(baxter.limits, 400, seed=11)
    free = x[~fcl.in_collision(x)]
    solved = 0
    for i in range(4):
        start, goal = free[2 * i], free[2 * i + 1]
        plan = fastron.plan_verified(detector, fcl, start, goal, resolution=0.05, time_limit=5)
        if plan.solved:
            solved += 1
            assert np.array_equal(plan.path[0], start) and np.array_equal(plan.path[-1], goal)
            # Verification guarantees what discrete checking does: every state at the planning
            # resolution is free...
            assert fastron.check_path(fcl, plan.path, 0.05), plan
            # ...so at a finer resolution the path is free of the boxes shrunk by how far the
            # robot moves within half a step: in the worst case 0.025 rad times a lever of up to
            # a metre per joint, centimetres. The corners simplified paths cut measured under
            # 5 mm deep (2 of 160 paths cut one, none against boxes 5 mm smaller), so 1 cm keeps
            # the independent check strict.
            assert fastron.check_path(shrunk, plan.path, 0.01), plan
            answers_x, answers_y = plan.exact_answers
            assert answers_x.shape[1] == 7 and answers_y.shape == (answers_x.shape[0],)
        exact = fastron.plan(fcl, start, goal, resolution=0.05, time_limit=5)
        if exact.solved:
            assert plan.solved, plan  # verify and repair fall back to the exact checker
    assert solved >= 3
    on_model = fastron.plan(detector.model(), free[0], free[1], resolution=0.05)
    assert on_model.path.shape[1] == 7


def test_the_planners_range_is_halved_on_a_schedule_unless_told_to_stay():
    square = fastron.JointLimits([-1, -1], [1, 1])
    ompls = 0.2 * np.sqrt(8.0)  # OMPL's default: a fifth of the square's diagonal
    start, goal = np.array([-0.8, -0.8]), np.array([0.8, -0.8])
    open_square = fastron.FunctionChecker(lambda q: False, 2, "open")
    easy = fastron.plan(open_square, start, goal, limits=square, simplify_time=0)
    assert easy.solved and easy.range == pytest.approx(ompls)
    # A goal walled in by a ring: no path, so the range goes down the schedule (to 1/8 of
    # OMPL's), and the goal's tree, in a pocket, grows at 1/16.
    ring = fastron.FunctionChecker(
        lambda q: bool(0.1 < np.hypot(q[0] - 0.8, q[1] + 0.8) < 0.2), 2, "ring")
    walled = fastron.plan(ring, start, goal, limits=square, time_limit=0.3)
    assert not walled.solved
    assert any(walled.range == pytest.approx(ompls / 2**k) for k in range(5)), walled.range
    stays = fastron.plan(ring, start, goal, limits=square, time_limit=0.3, range=0.3,
                         range_stage=0)
    assert stays.range == pytest.approx(0.3)


def test_plan_verified_in_a_static_scene_on_a_relaxed_oracle(baxter):
    # static_scene: the model's plan, then a hybrid asking the detector's oracle (FCL without
    # self-collision, a relaxation of the exact checker) about the model's "collides", then the
    # exact checker; final paths are checked with self-collision whatever the oracle said.
    scene = fastron.load_scene(fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml")
    obstacles = fastron.FclChecker(baxter, scene)
    exact = fastron.FclChecker(baxter, scene, self_collision=True)
    detector = fastron.ProxyCollisionDetector(obstacles, fastron.robot_features(baxter), seed=4,
                                              calibration_samples=0)
    detector.initialize(3000)
    version = detector.model_version
    x = uniform(baxter.limits, 400, seed=14)
    free = x[~exact.in_collision(x)]
    solved = 0
    for i, simplification in enumerate(("full", "shortcuts", "shortcuts")):
        start, goal = free[2 * i], free[2 * i + 1]
        plan = fastron.plan_verified(detector, exact, start, goal, resolution=0.05, time_limit=5,
                                     static_scene=True, oracle_relaxes_exact=True,
                                     simplification=simplification, hybrid_range=0.6,
                                     model_share=0.02)
        if plan.solved:
            solved += 1
            assert np.array_equal(plan.path[0], start) and np.array_equal(plan.path[-1], goal)
            assert fastron.check_path(exact, plan.path, 0.05), plan
            assert plan.planned_on in ("Fastron", "Fastron+FCL", "FCL"), plan.planned_on
            # Where the time went: the verified path's plan last, each attempt within the time.
            # (a repair that plans the whole motion again is no attempt: it is repair time)
            assert plan.attempts and plan.attempts[-1][1] == "solved", plan.attempts
            assert plan.whole_path_replanned or plan.attempts[-1][0] == plan.planned_on
            assert sum(a[2] for a in plan.attempts) <= plan.plan_seconds + 1e-9
            assert all(a[3] > 0 for a in plan.attempts)  # each asked its source something
            assert all(0 < a[4] <= a[2] for a in plan.attempts)  # and took time answering
            assert plan.exact_checks > 0  # verification at least
        assert plan.relearned == 0
    assert solved >= 2
    assert detector.model_version == version  # without learning_rounds the model stays


def test_static_scene_plans_on_the_hybrid_that_asks_the_relaxed_oracle():
    # A wall with a gap: the detector learned it while the gap was shut, so its model closes the
    # way. static_scene plans next on the hybrid that asks about the model's "collides" (the
    # detector's own oracle with oracle_relaxes_exact, else the exact checker); without it an
    # uncalibrated detector goes straight to the exact checker.
    gap = {"open": False}
    asked = []

    def oracle(q):
        asked.append(1)
        return bool(abs(q[0]) < 0.1 and (q[1] < 0.5 or not gap["open"]))

    exact = fastron.FunctionChecker(lambda q: bool(abs(q[0]) < 0.1 and q[1] < 0.5), 2, "wall")
    features = fastron.FeatureMap.joint_scaling(fastron.JointLimits([-1, -1], [1, 1]))
    start, goal = np.array([-0.8, -0.8]), np.array([0.8, -0.8])
    planned_on = {}
    for static_scene, relaxed in ((False, False), (True, False), (True, True)):
        gap["open"] = False
        detector = fastron.ProxyCollisionDetector(oracle, features, gamma=30, beta=5, seed=3,
                                                  calibration_samples=0)
        detector.initialize(1500)
        gap["open"] = True
        asked.clear()
        settings = {"oracle_relaxes_exact": True} if relaxed else {}
        plan = fastron.plan_verified(detector, exact, start, goal, resolution=0.01, time_limit=4,
                                     approximate_share=0.25, static_scene=static_scene,
                                     model_share=0.025 if static_scene else None, **settings)
        assert plan.solved, plan
        assert fastron.check_path(exact, plan.path, 0.01)
        planned_on[(static_scene, relaxed)] = plan.planned_on
        assert (len(asked) > 0) == relaxed, (static_scene, relaxed, len(asked))
    assert planned_on == {(False, False): "wall", (True, False): "Fastron+wall",
                          (True, True): "Fastron+python"}, planned_on


def test_plans_on_two_models_at_once(baxter):
    # Two models, each of a part of the scene (as a scene's obstacles beside a robot's
    # self-collisions), answer together through an AnyOfChecker; FCL on the whole scene verifies.
    scene = fastron.load_scene(fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml")
    parts = [fastron.Scene(), fastron.Scene()]
    for part, name in zip((0, 1, 1), ("box1", "box2", "box3")):
        parts[part].add_box(name, [0.2] * 3, scene.position(name))
    models = []
    for part in parts:
        detector = fastron.ProxyCollisionDetector(fastron.FclChecker(baxter, part),
                                                  fastron.robot_features(baxter), seed=3)
        detector.initialize(3000)
        models.append(detector.model())
    checkers = [fastron.ModelChecker(models[0]), fastron.ModelChecker(models[1], "other boxes")]
    both = fastron.AnyOfChecker(checkers)
    assert both.dof == 7 and both.name == "Fastron+other boxes"
    x = uniform(baxter.limits, 500, seed=12)
    assert np.array_equal(checkers[0].in_collision(x), models[0].in_collision(x))
    assert np.array_equal(both.in_collision(x),
                          checkers[0].in_collision(x) | checkers[1].in_collision(x))
    fcl = fastron.FclChecker(baxter, scene)
    free = x[~fcl.in_collision(x)]
    plan = fastron.plan_verified(both, fcl, free[0], free[1], limits=baxter.limits,
                                 resolution=0.05, time_limit=5)
    assert plan.solved, plan
    assert fastron.check_path(fcl, plan.path, 0.05), plan
    with pytest.raises(fastron.InvalidArgument, match="no checkers"):
        fastron.AnyOfChecker([])
    with pytest.raises(fastron.InvalidArgument, match="has 2 dof"):
        fastron.AnyOfChecker([both, fastron.FunctionChecker(lambda q: False, 2)])
    # All of the models and FCL: their "collides" confirmed by FCL, an optimistic hybrid.
    confirmed = fastron.AllOfChecker([both, fcl])
    assert confirmed.name == "Fastron+other boxes&FCL"
    assert np.array_equal(confirmed.in_collision(x), both.in_collision(x) & fcl.in_collision(x))
    plan = fastron.plan_verified(confirmed, fcl, free[0], free[1], limits=baxter.limits,
                                 resolution=0.05, time_limit=5)
    assert plan.solved and fastron.check_path(fcl, plan.path, 0.05), plan
    with pytest.raises(fastron.InvalidArgument, match="AllOfChecker: no checkers"):
        fastron.AllOfChecker([])


def test_moveit_files():
    shared = os.environ.get("FASTRON_SHARED_DIR")
    if not shared or not pathlib.Path(shared, "data/motion-bench-sample").is_dir():
        pytest.skip("no MotionBenchMaker sample (FASTRON_SHARED_DIR)")
    folder = pathlib.Path(shared, "data/motion-bench-sample")
    panda = fastron.load_robot("panda-mesh")
    scene = fastron.load_scene(folder / "scene0001.yaml")
    start, goal = fastron.load_moveit_request(folder / "request0001.yaml", panda)
    assert start.shape == goal.shape == (7,) and len(scene) > 0
    fcl = fastron.FclChecker(panda, scene)
    assert not fcl.in_collision(start) and not fcl.in_collision(goal)


def test_self_pair_tables_answer_as_fcl_alone(tmp_path, monkeypatch):
    # The mesh Panda's tables, built once into the cache that `fastron plan` reads them from.
    monkeypatch.setenv("FASTRON_CACHE_DIR", str(tmp_path))
    panda = fastron.load_robot("panda-mesh")
    scene = fastron.Scene()
    scene.add_box("shelf", [0.3, 0.6, 0.04], [0.6, 0.0, 0.5])
    tables = fastron.FclChecker(panda, scene, self_collision=True, self_pair_tables=True)
    plain = fastron.FclChecker(panda, scene, self_collision=True)
    assert tables.self_pair_table_count == 4 and plain.self_pair_table_count == 0
    assert len(list(tmp_path.glob("panda-*.self-pairs"))) == 1
    q = uniform(panda.limits, 500, seed=3)
    expected = plain.in_collision(q)
    assert 0 < expected.sum() < len(q)
    assert np.array_equal(tables.in_collision(q), expected)
    again = fastron.scene_checker("fcl", panda, scene, self_collision=True, self_pair_tables=True)
    assert again.self_pair_table_count == 4  # read back from the cache


def test_moveit_configuration_as_moveit_reads_it():
    shared = os.environ.get("FASTRON_SHARED_DIR")
    if not shared or not pathlib.Path(shared, "data/baxter-moveit").is_dir():
        pytest.skip("no Baxter MoveIt configuration (FASTRON_SHARED_DIR)")
    folder = pathlib.Path(shared, "data/baxter-moveit")
    robot, groups, warnings = fastron.load_robot_description(
        str(folder / "baxter.urdf"), srdf=folder / "baxter.srdf")
    assert len(groups["both_arms"]) == 14 and groups["left_hand"] == []
    assert any("collision_head_link" in w and "skipped, as MoveIt does" in w for w in warnings)
    left = fastron.load_robot(str(folder / "baxter.urdf"), srdf=folder / "baxter.srdf",
                              group="left_arm")
    assert left.dof == 7
    problem = folder / "problems-easy"
    scene = fastron.load_scene(problem / "scene0001.yaml")
    planned, start, goal, warning = fastron.robot_for_request(
        robot, problem / "request0001.yaml", scene, groups)
    assert planned.dof == 14 and start.shape == goal.shape == (14,) and warning == ""
    fcl = fastron.FclChecker(planned, scene)
    assert not fcl.in_collision(start) and not fcl.in_collision(goal)
    _, _, _, warning = fastron.robot_for_request(robot, problem / "request0001.yaml", scene,
                                                 {"arms": groups["both_arms"]})
    assert "no group 'both_arms'" in warning
    with pytest.raises(fastron.InvalidArgument, match="no group 'arms'"):
        fastron.load_robot(str(folder / "baxter.urdf"), srdf=folder / "baxter.srdf", group="arms")


def test_the_default_method_is_the_commands(baxter, fastron_command):
    """Python's train_scene_model is the function `fastron plan` trains with: the same seed gives
    the same model, and planning on it as the command does gives a path free under FCL."""
    import re
    import subprocess
    scene_file = fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml"
    three_boxes = fastron.load_scene(scene_file)  # as the command reads it (others move theirs)
    out = subprocess.run([str(fastron_command), "plan", "--robot", "baxter", "--scene",
                          str(scene_file), "--start=-1.2,0.3,0,1.2,0,0.5,0",
                          "--goal=1.2,0.3,0,1.2,0,0.5,0", "--samples", "1200", "--seed", "3"],
                         capture_output=True, text=True, check=False).stdout
    cli_support = int(re.search(r"^model +trained on 1200 [^\n]*?, (\d+) support points", out,
                                re.MULTILINE).group(1))
    detector = fastron.train_scene_model(baxter, three_boxes, samples=1200, seed=3)
    assert detector.model().support_count == cli_support
    again = fastron.train_scene_model(baxter, three_boxes, samples=1200, seed=3)
    q = uniform(baxter.limits, 300, 1)
    assert np.array_equal(detector.model().score(q), again.model().score(q))
    fcl = fastron.FclChecker(baxter, three_boxes)
    plan = fastron.plan_verified(detector, fcl, np.array([-1.2, 0.3, 0, 1.2, 0, 0.5, 0]),
                                 np.array([1.2, 0.3, 0, 1.2, 0, 0.5, 0]), resolution=0.03,
                                 static_scene=True, oracle_relaxes_exact=True)
    assert plan.solved and fastron.check_path(fcl, plan.path, 0.01)
    with pytest.raises(fastron.InvalidArgument):
        fastron.train_scene_model(baxter, three_boxes, fastron.robot_features(
            fastron.load_robot("ur3")))


def test_the_held_out_recipe_is_the_commands(baxter, fastron_command, tmp_path):
    """train_held_out_model is the function `fastron train --robot --scene` calls: the same seed
    gives the same model (rounds, candidates and all)."""
    import subprocess
    scene_file = fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml"
    out = tmp_path / "held-out.fastron"
    subprocess.run([str(fastron_command), "train", "--robot", "baxter", "--scene", str(scene_file),
                    "--samples", "1000", "--held-out", "1000", "--target-accuracy", "1",
                    "--max-samples", "2000", "--seed", "3", "-o", str(out)],
                   capture_output=True, check=True)
    cli = fastron.load_model(out, baxter)
    model, rounds, kept = fastron.train_held_out_model(
        baxter, fastron.load_scene(scene_file), samples=1000, held_out=1000, target_accuracy=1,
        max_samples=2000, seed=3)
    assert model.checksum == cli.checksum
    assert rounds[kept]["support_count"] == model.support_count
    # The rounds missed: the other candidate tried (the spread rule's 9 points along Baxter's
    # geometry are all it gives, so only the cover rule's make one).
    assert {r["candidate"] for r in rounds} == {0, 1}
    assert model.has_only_point_terms
    assert all(0 <= r["accuracy"] <= 1 and r["training_samples"] in (1000, 2000) for r in rounds)
    with pytest.raises(fastron.InvalidArgument, match="margins must increase"):
        fastron.train_held_out_model(baxter, fastron.load_scene(scene_file), samples=100,
                                     margins=[0.02, 0.01])
    with pytest.raises(fastron.InvalidArgument, match="target accuracy"):
        fastron.train_held_out_model(baxter, fastron.load_scene(scene_file), samples=100,
                                     target_accuracy=1.5)


def test_help_shows_the_api():
    assert "f(q)" in fastron.Model.__doc__
    assert "numpy" in fastron.__doc__ or "array" in fastron.__doc__
    assert "Algorithm 1" in fastron.train.__doc__


def test_type_stubs_cover_the_module():
    import ast
    stubs = pathlib.Path(fastron.__file__).with_name("_fastron.pyi")
    tree = ast.parse(stubs.read_text())
    stubbed = {node.name for node in tree.body if isinstance(node, (ast.ClassDef, ast.FunctionDef))}
    public = {name for name in dir(fastron._fastron) if not name.startswith("_")}
    assert public == stubbed


def test_paths_written_read_and_cut_as_the_checks_cut_them(tmp_path, baxter, baxter_fcl):
    path = np.array([[0.0] * 7, [0.3, 0.4, 0, 0, 0, 0, 0], [0.3, 0.4, 0, 0, 0, 0, -0.5]])
    fastron.write_path(tmp_path / "p.csv", path, baxter)
    assert (tmp_path / "p.csv").read_text().startswith(",".join(baxter.joint_names) + "\n")
    back = fastron.read_path(tmp_path / "p.csv", baxter)
    assert back.shape == (3, 7) and np.array_equal(back, path)
    states = fastron.states_along_path(path, 0.09)
    assert states.shape == (1 + 6 + 6, 7)  # ceil(0.5 / 0.09) = 6 segments per edge
    assert np.array_equal(states[0], path[0]) and np.array_equal(states[-1], path[-1])
    assert np.all(np.linalg.norm(np.diff(states, axis=0), axis=1) <= 0.09 + 1e-12)
    # The states check_path looks at: the path is free exactly when all of them are.
    assert fastron.check_path(baxter_fcl, path, 0.09) == (not baxter_fcl.in_collision(states).any())
    (tmp_path / "panda.csv").write_text("panda_joint1\n0\n")
    with pytest.raises(fastron.FileError, match=r"panda.csv:1: column 1 is 'panda_joint1'"):
        fastron.read_path(tmp_path / "panda.csv", baxter)
    with pytest.raises(fastron.InvalidArgument, match="path"):
        fastron.states_along_path(np.zeros(7), 0.1)
    with pytest.raises(fastron.InvalidArgument, match="resolution"):
        fastron.states_along_path(path, 0)
    with pytest.raises(fastron.InvalidArgument, match="model resolution must be 0"):
        fastron.plan(baxter_fcl, path[0], path[1], model_resolution=-1)


def test_a_detector_learns_the_answers_its_model_got_wrong(baxter):
    # The loop of docs/log/2026-11-23-motion-bench-panda-meshes-and-srdf.md, "Learning from verification in one scene": keep the exact
    # answers the model got wrong and learn them without asking the oracle.
    scene = fastron.load_scene(fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml")
    fcl = fastron.FclChecker(baxter, scene)
    detector = fastron.ProxyCollisionDetector(fcl, fastron.robot_features(baxter), seed=5,
                                              relabel_support=False, calibration_samples=0)
    detector.initialize(400)  # a small model, wrong about some of the answers below
    model = detector.model()
    all_x = uniform(baxter.limits, 2000, seed=13)
    all_y = np.where(fcl.in_collision(all_x), 1, -1).astype(np.int8)
    missed_x, missed_y = fastron.answers_missed_by(model, all_x, all_y)
    wrong = model.in_collision(all_x) != (all_y > 0)
    assert len(missed_y) == int(wrong.sum()) > 0
    assert np.array_equal(missed_x, all_x[wrong]) and np.array_equal(missed_y, all_y[wrong])

    version = detector.model_version
    detector.add_observations(missed_x, missed_y)
    report = detector.learn_observations()
    assert report.observed == len(missed_y) and report.labelled == 0  # no oracle call
    assert detector.model_version == version + 1
    # Claim 1 over the support set and the observations: every one is learned.
    assert report.update.stop_reason == "converged" and report.update.misclassified == 0
    learned = detector.model().in_collision(missed_x) == (missed_y > 0)
    assert learned.mean() >= 0.95, learned.mean()
    assert detector.dropped_observations == 0
    nothing = detector.learn_observations()  # nothing waiting: no new model
    assert nothing.observed == 0 and detector.model_version == version + 1

    with pytest.raises(fastron.InvalidArgument, match="X"):
        fastron.answers_missed_by(model, np.zeros((3, 6)), np.ones(3))


def test_plan_verified_learns_within_a_query(baxter):
    # learning_rounds: the detector learns what verification found wrong before repairing. Its
    # model knows one of the three boxes; each query's straight line, free on the model, crosses
    # another.
    scene = fastron.load_scene(fastron.data_directory() / "scenes" / "baxter_three_boxes.yaml")
    fcl = fastron.FclChecker(baxter, scene)
    one_box = fastron.Scene()
    one_box.add_box("box1", [0.2] * 3, scene.position("box1"))
    detector = fastron.ProxyCollisionDetector(fastron.FclChecker(baxter, one_box),
                                              fastron.robot_features(baxter), seed=5,
                                              relabel_support=False, calibration_samples=0)
    detector.initialize(2000)
    x = uniform(baxter.limits, 600, seed=13)
    free = x[~fcl.in_collision(x)]
    queries = [(a, b) for a, b in zip(free[0::2], free[1::2])
               if not fastron.check_path(fcl, np.array([a, b]), 0.05)
               and not detector.model().in_collision(np.linspace(a, b, 50)).any()][:4]
    assert len(queries) == 4
    relearned = 0
    for start, goal in queries:
        version = detector.model_version
        plan = fastron.plan_verified(detector, fcl, start, goal, resolution=0.05, time_limit=5,
                                     learning_rounds=2)
        assert plan.solved, plan
        assert fastron.check_path(fcl, plan.path, 0.05)
        assert 0 <= plan.relearned <= 2
        assert detector.model_version == version + plan.relearned
        relearned += plan.relearned
    assert relearned > 0, "the model's paths must meet the boxes it does not know"
    with pytest.raises(fastron.InvalidArgument, match="only a ProxyCollisionDetector learns"):
        fastron.plan_verified(detector.model(), fcl, free[0], free[1], learning_rounds=1)
