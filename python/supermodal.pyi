# Type stubs of the supermodal extension module (docs/python.md). Units are SI; arrays are float64.
import os
from typing import Literal, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

Vec3 = Sequence[float]
Quat = Sequence[float]  # (w, x, y, z)
Path = Union[str, os.PathLike[str]]
Motion = Literal["dynamic", "static", "kinematic"]
Solver = Literal["penalty", "soft"]

class ArgumentError(ValueError):
    argument: str
    def __init__(self, message: str, argument: str = "") -> None: ...

class ArgumentTypeError(TypeError):
    argument: str
    def __init__(self, message: str, argument: str = "") -> None: ...

class SceneError(ValueError):
    pointer: str
    file: str
    def __init__(self, message: str, pointer: str = "", file: str = "") -> None: ...

class StateError(ValueError): ...

class Material:
    def __init__(
        self,
        *,
        name: str = "",
        density: float = 1000.0,
        young: float = 1e9,
        poisson: float = 0.3,
        friction: float = 0.5,
        restitution: float = 0.2,
        rolling_resistance: float = 0.0,
        damping_ratio: float = 0.01,
        yield_stress: float = ...,
        hardening: float = 0.0,
        max_plastic_strain: float = ...,
    ) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def density(self) -> float: ...
    @property
    def young(self) -> float: ...
    @property
    def poisson(self) -> float: ...
    @property
    def friction(self) -> float: ...
    @property
    def restitution(self) -> float: ...
    @property
    def rolling_resistance(self) -> float: ...
    @property
    def damping_ratio(self) -> float: ...
    @property
    def yield_stress(self) -> float: ...
    @property
    def hardening(self) -> float: ...
    @property
    def max_plastic_strain(self) -> float: ...

class Body:
    @property
    def name(self) -> str: ...
    @property
    def index(self) -> int: ...
    @property
    def valid(self) -> bool: ...
    @property
    def motion(self) -> Motion: ...
    @property
    def mass(self) -> float: ...
    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    linear_velocity: tuple[float, float, float]
    angular_velocity: tuple[float, float, float]
    @property
    def center_of_mass(self) -> tuple[float, float, float]: ...
    @property
    def kinetic_energy(self) -> float: ...
    @property
    def potential_energy(self) -> float: ...
    @property
    def awake(self) -> bool: ...
    def wake(self) -> None: ...
    @property
    def interpolated_position(self) -> tuple[float, float, float]: ...
    @property
    def interpolated_orientation(self) -> tuple[float, float, float, float]: ...
    @property
    def mode_count(self) -> int: ...
    @property
    def modal_amplitudes(self) -> npt.NDArray[np.float64]: ...
    @property
    def modal_velocities(self) -> npt.NDArray[np.float64]: ...
    def mode_shapes(self, points: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
    def apply_force(self, force: Vec3, point: Vec3 | None = None) -> None: ...
    def apply_torque(self, torque: Vec3) -> None: ...
    def apply_impulse(self, impulse: Vec3, point: Vec3 | None = None) -> None: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class Constraint:
    @property
    def name(self) -> str: ...
    @property
    def valid(self) -> bool: ...
    @property
    def broken(self) -> bool: ...
    @property
    def force(self) -> tuple[float, float, float]: ...
    @property
    def error(self) -> tuple[float, float]: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class ContactEvent:
    @property
    def kind(self) -> Literal["begin", "persist", "end"]: ...
    @property
    def a(self) -> Body: ...
    @property
    def b(self) -> Body: ...
    @property
    def point(self) -> tuple[float, float, float]: ...
    @property
    def normal(self) -> tuple[float, float, float]: ...
    @property
    def impulse_on_a(self) -> tuple[float, float, float]: ...
    @property
    def normal_impulse(self) -> float: ...
    @property
    def depth(self) -> float: ...

class Contact:
    @property
    def a(self) -> Body: ...
    @property
    def b(self) -> Body: ...
    @property
    def point(self) -> tuple[float, float, float]: ...
    @property
    def normal(self) -> tuple[float, float, float]: ...
    @property
    def force_on_a(self) -> tuple[float, float, float]: ...
    @property
    def depth(self) -> float: ...
    @property
    def point_count(self) -> int: ...

class FaultEvent:
    @property
    def kind(self) -> Literal["body_non_finite", "modal_non_finite"]: ...
    @property
    def body(self) -> Body: ...
    @property
    def stage(self) -> str: ...
    @property
    def step(self) -> int: ...
    @property
    def substep(self) -> int: ...

class Anchor(TypedDict, total=False):
    point: Vec3
    direction: Vec3
    eta: float
    omega: float

class ExportInfo(TypedDict):
    frames: int
    bodies: int

class FitResult(TypedDict):
    body: dict[str, object]
    rms_m: float
    max_m: float
    rms_relative: float
    size_m: float
    iterations: int
    acceptable: bool

class World:
    def __init__(
        self,
        *,
        dt: float = 0.002,
        substep_count: int = 1,
        gravity: Vec3 = (0.0, -9.81, 0.0),
        max_steps_per_advance: int = 64,
        constraint_iterations: int = 4,
        thread_count: int = 1,
        contact_enabled: bool = True,
        contact_solver: Solver = "penalty",
        contact_iterations: int = 10,
        solver_substeps: int = 1,
        soft_frequency_hz: float = 0.0,
        soft_damping_ratio: float = 10.0,
        contact_path: Literal["auto", "sampling", "support_map"] = "auto",
        contact_stiffness: Literal["frequency", "material"] = "frequency",
        contact_frequency_hz: float = 0.0,
        contact_damping_ratio: float = -1.0,
        sample_spacing: float = 0.0,
        sleep_enabled: bool = True,
    ) -> None: ...
    def configure(self, **settings: object) -> None: ...
    def settings(self) -> dict[str, object]: ...
    dt: float
    substep_count: int
    contact_solver: str
    contact_iterations: int
    constraint_iterations: int
    def step(self, count: int = 1) -> None: ...
    def advance(self, seconds: float) -> int: ...
    @property
    def interpolation_alpha(self) -> float: ...
    @property
    def time(self) -> float: ...
    @property
    def step_count(self) -> int: ...
    def state_hash(self) -> int: ...
    def snapshot(self) -> bytes: ...
    def restore(self, snapshot: bytes) -> None: ...
    @property
    def duration(self) -> float | None: ...
    @property
    def source(self) -> str: ...
    def warnings(self) -> dict[str, int]: ...
    def last_step_ms(self) -> float: ...
    def max_penetration(self) -> float: ...
    def create_body(
        self,
        *,
        material: Material | None = None,
        name: str = "",
        motion: Motion = "dynamic",
        shape: Literal["superquadric", "plane"] = "superquadric",
        radii: Vec3 = (0.5, 0.5, 0.5),
        epsilon1: float = 1.0,
        epsilon2: float = 1.0,
        taper: Sequence[float] = (0.0, 0.0),
        bend: Sequence[float] = (0.0, 0.0),
        plane_normal: Vec3 = (0.0, 1.0, 0.0),
        plane_offset: float = 0.0,
        density: float = 1000.0,
        position: Vec3 = (0.0, 0.0, 0.0),
        orientation: Quat = (1.0, 0.0, 0.0, 0.0),
        linear_velocity: Vec3 = (0.0, 0.0, 0.0),
        angular_velocity: Vec3 = (0.0, 0.0, 0.0),
        gravity_scale: float = 1.0,
        friction: float = 0.5,
        restitution: float = 0.2,
        young: float = 1e9,
        poisson: float = 0.3,
        rolling_resistance: float = 0.0,
        allow_sleep: bool = True,
        modal: bool = False,
        mode_count: int = 12,
        lattice: Sequence[int] = (0, 0, 0),
        modal_integrator: Literal["exact", "central_difference"] = "exact",
        damping_ratio: float = 0.01,
        yield_stress: float = ...,
        hardening: float = 0.0,
        max_plastic_strain: float = ...,
        adaptive_tolerance: float = 0.0,
    ) -> Body: ...
    def destroy_body(self, body: Body) -> None: ...
    @property
    def bodies(self) -> list[Body]: ...
    def find_body(self, name: str) -> Body | None: ...
    def create_constraint(
        self,
        *,
        a: Body,
        b: Body | None = None,
        type: Literal["point", "distance", "weld"] = "point",
        name: str = "",
        anchor_a: Vec3 | Anchor = (0.0, 0.0, 0.0),
        anchor_b: Vec3 | Anchor = (0.0, 0.0, 0.0),
        frequency_hz: float = 30.0,
        damping_ratio: float = 0.7,
        rest_length: float = -1.0,
        swing_limit: float = -1.0,
        twist_limit: float = -1.0,
        axis_a: Vec3 = (0.0, 0.0, 0.0),
        angular_damping: float = 0.0,
        break_force: float = ...,
        collide_connected: bool = False,
    ) -> Constraint: ...
    def destroy_constraint(self, constraint: Constraint) -> None: ...
    @property
    def constraints(self) -> list[Constraint]: ...
    def positions(self, interpolated: bool = False) -> npt.NDArray[np.float64]: ...
    def orientations(self, interpolated: bool = False) -> npt.NDArray[np.float64]: ...
    def linear_velocities(self) -> npt.NDArray[np.float64]: ...
    def angular_velocities(self) -> npt.NDArray[np.float64]: ...
    def contact_events(self) -> list[ContactEvent]: ...
    def contacts(self) -> list[Contact]: ...
    def fault_events(self) -> list[FaultEvent]: ...
    def export_glb(
        self, path: Path, *, seconds: float = 1.0, fps: float = 30.0, tessellation: int = 32, morph_targets: bool = True
    ) -> ExportInfo: ...

def load_scene(source: Path | dict[str, object], overrides: dict[str, object] | None = None) -> World: ...
def parse_scene(text: str, overrides: dict[str, object] | None = None) -> World: ...
def sweep(
    scene: Path | dict[str, object],
    grid: dict[str, Sequence[object]],
    client: object | None = None,
    *,
    n_workers: int = 2,
    seconds: float | None = None,
) -> list[dict[str, object]]: ...
def fit(
    points: npt.ArrayLike,
    *,
    taper: bool = False,
    bend: bool = False,
    epsilon_min: float = 0.1,
    epsilon_max: float = 2.0,
    max_iterations: int = 200,
    max_points: int = 4000,
    acceptable_rms_relative: float = 0.02,
) -> FitResult: ...
