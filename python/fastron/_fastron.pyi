"""Type stubs of the fastron extension module (see docs/python.md)."""
import os
from typing import Callable, Dict, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Path = Union[str, os.PathLike]

class Error(RuntimeError): ...
class InvalidArgument(Error, ValueError): ...
class FileError(Error, OSError): ...
class FileNotFound(FileError, FileNotFoundError): ...
class OracleFault(Error): ...
class Unsupported(Error, NotImplementedError): ...

class JointLimits:
    def __init__(self, lower: ArrayLike, upper: ArrayLike) -> None: ...
    @property
    def dim(self) -> int: ...
    @property
    def lower(self) -> npt.NDArray[np.float64]: ...
    @property
    def upper(self) -> npt.NDArray[np.float64]: ...

class FeatureMap:
    @staticmethod
    def joint_scaling(limits: JointLimits) -> FeatureMap: ...
    @property
    def kind(self) -> str: ...
    @property
    def configuration_dim(self) -> int: ...
    @property
    def feature_dim(self) -> int: ...
    @property
    def limits(self) -> JointLimits: ...
    def map(self, q: ArrayLike) -> npt.NDArray[np.float64]: ...

class UpdateReport:
    iterations: int
    stop_reason: str
    training_points: int
    misclassified: int
    support_count: int
    reverted: bool
    seconds: float

class Model:
    dim: int
    feature_dim: int
    support_count: int
    checksum: int
    features: FeatureMap
    limits: JointLimits
    gamma: float
    kernel: str
    kernel_block: int
    kernel_whole_share: float
    has_only_point_terms: bool
    point_field: Optional[Dict[str, Union[int, float]]]
    support_points: npt.NDArray[np.float64]
    support_features: npt.NDArray[np.float64]
    weights: npt.NDArray[np.float64]
    @overload
    def score(self, q: Sequence[float]) -> float: ...
    @overload
    def score(self, q: ArrayLike) -> Union[float, npt.NDArray[np.float64]]: ...
    @overload
    def score_gradient(self, q: Sequence[float]) -> Tuple[float, npt.NDArray[np.float64]]: ...
    @overload
    def score_gradient(self, q: ArrayLike) -> Tuple[Union[float, npt.NDArray[np.float64]], npt.NDArray[np.float64]]: ...
    def in_collision(self, q: ArrayLike) -> Union[bool, npt.NDArray[np.bool_]]: ...
    def first_in_collision(self, q: ArrayLike) -> Optional[int]: ...
    def with_point_field(self, *, spacing: float = 0.04, samples: int = 20000, seed: int = 1,
                         error_factor: float = 2.0, refinement: int = 2,
                         max_fine_nodes: int = 524288, fine_from: float = 0.15) -> Model: ...
    def save(self, path: Path) -> None: ...

def train(X: ArrayLike, y: ArrayLike, *, features: Optional[FeatureMap] = None,
          limits: Optional[JointLimits] = None, gamma: Optional[float] = None,
          beta: Optional[float] = None, kernel: str = "rq", kernel_block: Optional[int] = None,
          kernel_whole_share: Optional[float] = None, self_collision_labels: bool = False,
          max_iterations: Optional[int] = None,
          max_support_points: Optional[int] = None) -> tuple[Model, UpdateReport]: ...

class ConfusionCounts:
    true_positives: int
    true_negatives: int
    false_positives: int
    false_negatives: int
    total: int
    accuracy: float
    tpr: float
    tnr: float

def evaluate(model: Model, X: ArrayLike, y: ArrayLike) -> ConfusionCounts: ...
def prune_support(model: Model, X: ArrayLike) -> Model: ...
def merge_support(model: Model, radius: float) -> Model: ...
def simd_paths() -> list[str]: ...
def active_simd_path() -> str: ...
def use_simd_path(name: str) -> None: ...
def read_dataset(path: Path) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int8]]: ...
def write_dataset(path: Path, X: ArrayLike, y: ArrayLike) -> None: ...

class CollisionChecker:
    name: str
    dof: int
    call_count: int
    def in_collision(self, q: ArrayLike) -> Union[bool, npt.NDArray[np.bool_]]: ...

class FunctionChecker(CollisionChecker):
    def __init__(self, fn: Callable[[npt.NDArray[np.float64]], bool], dof: int,
                 name: str = "python") -> None: ...

class ModelChecker(CollisionChecker):
    def __init__(self, model: Model, name: str = "Fastron") -> None: ...

class AnyOfChecker(CollisionChecker):
    def __init__(self, checkers: Sequence[CollisionChecker]) -> None: ...

class AllOfChecker(CollisionChecker):
    def __init__(self, checkers: Sequence[CollisionChecker]) -> None: ...

class Robot:
    name: str
    dof: int
    joint_names: list[str]
    link_names: list[str]
    limits: JointLimits
    def link_positions(self, q: ArrayLike) -> npt.NDArray[np.float64]: ...

def load_robot(name_or_path: str, *, srdf: Optional[Path] = None,
               package_paths: Sequence[Path] = (), group: Optional[str] = None) -> Robot: ...
def load_robot_description(name_or_path: str, *, srdf: Optional[Path] = None,
                           package_paths: Sequence[Path] = (), group: Optional[str] = None
                           ) -> tuple[Robot, dict[str, list[str]], list[str]]: ...
def shipped_robots() -> list[str]: ...
def data_directory() -> os.PathLike: ...

class Scene:
    def __init__(self) -> None: ...
    obstacle_names: list[str]
    time: float
    def __len__(self) -> int: ...
    def step(self, steps: int = 1) -> None: ...
    def add_box(self, name: str, size: ArrayLike, position: ArrayLike,
                rpy: Optional[ArrayLike] = None) -> None: ...
    def add_sphere(self, name: str, radius: float, position: ArrayLike) -> None: ...
    def add_cylinder(self, name: str, radius: float, length: float, position: ArrayLike,
                     rpy: Optional[ArrayLike] = None) -> None: ...
    def add_point_cloud(self, name: str, points: ArrayLike, radius: float, *,
                        voxel: Optional[float] = None, position: Optional[ArrayLike] = None,
                        rpy: Optional[ArrayLike] = None) -> None: ...
    def set_point_cloud(self, name: str, points: ArrayLike, radius: float, *,
                        voxel: Optional[float] = None) -> None: ...
    def remove(self, name: str) -> None: ...
    def set_pose(self, name: str, position: ArrayLike, rpy: Optional[ArrayLike] = None) -> None: ...
    def position(self, name: str) -> npt.NDArray[np.float64]: ...
    def grown(self, margin: float) -> Scene: ...

def load_scene(path: Path) -> Scene: ...
def load_moveit_request(path: Path, robot: Robot) -> tuple[npt.NDArray[np.float64],
                                                          npt.NDArray[np.float64]]: ...
def robot_for_request(robot: Robot, request: Path, scene: Scene,
                      groups: Mapping[str, Sequence[str]] = ...
                      ) -> tuple[Robot, npt.NDArray[np.float64], npt.NDArray[np.float64], str]: ...
def robot_features(robot: Robot, kind: str = "fk",
                   control_points: Sequence[str] = (), *, max_points: int = 4,
                   min_spacing: float = 0.1, max_per_body: int = 3,
                   rule: str = "spread", along_geometry: bool = False) -> FeatureMap: ...
def load_model(path: Path, robot: Optional[Robot] = None) -> Model: ...

class Contact:
    robot_link: str
    other: str
    self_collision: bool

class SceneChecker(CollisionChecker):
    robot: Robot
    def set_scene(self, scene: Scene) -> None: ...
    def first_contact(self, q: ArrayLike) -> Optional[Contact]: ...
    @property
    def measures_distance(self) -> bool: ...
    def distance(self, q: ArrayLike) -> float: ...

class FclChecker(SceneChecker):
    def __init__(self, robot: Robot, scene: Scene, *, self_collision: bool = False,
                 padding: float = 0.0, prove_motions_free: bool = True,
                 self_pair_tables: bool = False) -> None: ...
    @property
    def self_pair_table_count(self) -> int: ...

class GjkChecker(SceneChecker):
    def __init__(self, robot: Robot, scene: Scene, *, self_collision: bool = False,
                 padding: float = 0.0) -> None: ...

def scene_checker_names() -> list[str]: ...
def scene_checker(name: str, robot: Robot, scene: Scene, *, self_collision: bool = False,
                  padding: float = 0.0, prove_motions_free: bool = True,
                  self_pair_tables: bool = False) -> SceneChecker: ...

class StepReport:
    update: UpdateReport
    labelled: int
    added: int
    observed: int
    model_version: int
    seconds: float
    label_seconds: float

class BackgroundHealth:
    steps: int
    faults: int
    consecutive_faults: int
    last_fault: str
    model_version: int

def answers_missed_by(model: Model, X: ArrayLike, y: ArrayLike
                      ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int8]]: ...

def train_scene(oracle: Union[CollisionChecker, Callable[[npt.NDArray[np.float64]], bool]],
                features: FeatureMap, samples: int = 16000, *, accuracy: float = 0.975,
                tpr: float = 0.96, held_out: int = 8000, max_samples: int = 64000, seed: int = 1,
                self_collision_labels: bool = False, gamma: Optional[float] = None,
                beta: Optional[float] = None,
                grown_oracles: Sequence[Union[CollisionChecker,
                                              Callable[[npt.NDArray[np.float64]], bool]]] = (),
                alternatives: Sequence[tuple[FeatureMap, Optional[float]]] = ()
                ) -> tuple[Model, list[tuple[int, int, ConfusionCounts, int, int]], int]: ...

class ProxyCollisionDetector:
    def __init__(self, oracle: Union[CollisionChecker, Callable[[npt.NDArray[np.float64]], bool]],
                 features: FeatureMap, *, seed: int = 1, gamma: Optional[float] = None,
                 beta: Optional[float] = None, kernel_block: Optional[int] = None,
                 kernel_whole_share: Optional[float] = None, self_collision_labels: bool = False,
                 max_support_points: int = 3000, active_samples: Optional[int] = None,
                 cold_start: Optional[bool] = None, label_threads: int = 0,
                 calibration_samples: int = 1000, relabel_support: bool = True) -> None: ...
    def initialize(self, samples: int) -> StepReport: ...
    def step(self) -> StepReport: ...
    def train_static(self, samples: int, updates: int = 0) -> StepReport: ...
    def model(self) -> Model: ...
    model_version: int
    def background_health(self) -> BackgroundHealth: ...
    def add_observations(self, X: ArrayLike, y: ArrayLike) -> None: ...
    def learn_observations(self) -> StepReport: ...
    dropped_observations: int
    def start_background(self, min_period: float = 0.0) -> None: ...
    def stop_background(self) -> None: ...
    background_running: bool
    features: FeatureMap
    limits: JointLimits

class PlanResult:
    status: str
    solved: bool
    path: npt.NDArray[np.float64]
    seconds: float
    simplify_seconds: float
    range: float

class VerifiedPlan:
    status: str
    solved: bool
    path: npt.NDArray[np.float64]
    failure: str
    planned_on: str
    plan_seconds: float
    verify_seconds: float
    repair_seconds: float
    total_seconds: float
    invalid_stretches: int
    gradient_repairs: int
    relearned: int
    whole_path_replanned: bool
    attempts: list[tuple[str, str, float, int, float]]
    exact_checks: int
    relaxed_checks: int
    exact_answers: tuple[npt.NDArray[np.float64], npt.NDArray[np.int8]]

Source = Union[Model, CollisionChecker]

def plan(source: Source, start: ArrayLike, goal: ArrayLike, *,
         limits: Optional[JointLimits] = None, planner: str = "RRTConnect", range: float = 0.0,
         range_stage: int = 100, resolution: float = 0.02, model_resolution: float = 0.0,
         time_limit: float = 10.0, simplify_time: float = 0.1,
         simplification: str = "full") -> PlanResult: ...
def plan_verified(approximate: Union[Source, ProxyCollisionDetector], exact: CollisionChecker,
                  start: ArrayLike, goal: ArrayLike, *, limits: Optional[JointLimits] = None,
                  planner: str = "RRTConnect", range: float = 0.0, range_stage: int = 100,
                  resolution: float = 0.02, model_resolution: float = 0.0, time_limit: float = 10.0,
                  simplify_time: float = 0.1, simplification: str = "full",
                  learning_rounds: int = 0, static_scene: bool = False,
                  approximate_share: float = 0.1, model_share: Optional[float] = None,
                  substitute_share: float = 0.002, stretch_share: float = 0.02,
                  bridge_margin: float = 1.0,
                  enclosed_after: int = 256, hybrid_range: Optional[float] = None,
                  oracle_relaxes_exact: bool = False,
                  gradient_repair: bool = False) -> VerifiedPlan: ...

class OptimizedTrajectory:
    path: npt.NDArray[np.float64]
    free_on_model: bool
    iterations: int
    costs: list[float]
    seconds: float

class VerifiedTrajectory:
    status: str
    solved: bool
    failure: str
    path: npt.NDArray[np.float64]
    rounds: int
    iterations: int
    optimize_seconds: float
    verify_seconds: float
    learn_seconds: float
    costs: list[float]

def path_collision_cost(model: Model, path: ArrayLike, *, margin: float = 1.0
                        ) -> tuple[float, npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
def straight_path(start: ArrayLike, goal: ArrayLike, *, spacing: float = 0.05
                  ) -> npt.NDArray[np.float64]: ...
def optimize_trajectory(model: Model, path: ArrayLike, *, margin: float = 1.0,
                        max_step: float = 0.03, smoothing: float = 0.005,
                        max_iterations: int = 400, model_resolution: float = 0.06,
                        time_limit: float = 0.0) -> OptimizedTrajectory: ...
def optimize_verified(detector: ProxyCollisionDetector, exact: CollisionChecker, start: ArrayLike,
                      goal: ArrayLike, *, resolution: float = 0.02, spacing: float = 0.05,
                      margin: float = 1.0, max_step: float = 0.03, smoothing: float = 0.005,
                      max_iterations: int = 400, model_resolution: float = 0.06,
                      time_limit: float = 0.0, rounds: int = 4) -> VerifiedTrajectory: ...
def train_scene_model(robot: Robot, scene: Scene, features: Optional[FeatureMap] = None, *,
                      samples: int = 1000, updates: int = 0, seed: int = 1,
                      gamma: Optional[float] = None, beta: Optional[float] = None,
                      self_collision: bool = False, padding: float = 0.0,
                      checker: str = "fcl") -> ProxyCollisionDetector: ...
def train_held_out_model(robot: Robot, scene: Scene, *, features: str = "fk",
                         samples: int = 16000, held_out: int = 8000,
                         target_accuracy: float = 0.975, target_tpr: float = 0.96,
                         max_samples: int = 64000, margins: Sequence[float] = (0.005, 0.01),
                         self_collision: bool = False, gamma: Optional[float] = None,
                         beta: Optional[float] = None, other_candidates: bool = True,
                         seed: int = 1, checker: str = "fcl"
                         ) -> tuple[Model, list[dict[str, float]], int]: ...
def check_path(checker: CollisionChecker, path: ArrayLike, resolution: float) -> bool: ...
def states_along_path(path: ArrayLike, resolution: float) -> npt.NDArray[np.float64]: ...
def write_path(file: Path, path: ArrayLike, robot: Robot) -> None: ...
def read_path(file: Path, robot: Robot) -> npt.NDArray[np.float64]: ...
