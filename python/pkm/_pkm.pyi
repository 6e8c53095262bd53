"""Type stubs of the compiled core pkm._pkm (docs/python.md). Units: mm, rad, s, N unless a name says otherwise."""

from __future__ import annotations

import os
from typing import Any, Literal, Optional, Sequence, TypedDict, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

__version__: str  # pkm --version's (CMake's project version)

# --- machine and kinematics ------------------------------------------------------------------------------------
# (python/src/machine.cpp, machine_dict.cpp, batch_*.cpp)
# Poses: rows [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] in the machine's angle convention, shape (N, 6) or (6,);
# angles="deg" (python/pkm/_angles.py) takes and returns them in degrees instead.
_Angles = Literal["rad", "deg"]
# Actuator values: mm, or rad for angular actuators (Machine.actuator_unit), shape (N, n) or (n,).

_Errors = Literal["raise", "nan"]
_Array = NDArray[np.float64]


class ActuatorLimits(TypedDict):
    min: Optional[float]
    max: Optional[float]
    speed: Optional[float]
    accel: Optional[float]
    force_N: Optional[float]


class FkInfo(TypedDict):
    iterations: NDArray[np.int32]
    residual_mm: _Array
    branch: NDArray[np.int32]


class FkSolutionDict(TypedDict):
    pose: _Array
    branch: int
    iterations: int
    residual_mm: float


class Machine:
    """A parallel-kinematic machine from a machine file: its mechanism, limits and settings."""

    @staticmethod
    def load(path: str | os.PathLike[str]) -> Machine: ...
    @staticmethod
    def from_yaml(text: str, source: str = "<text>") -> Machine: ...
    @staticmethod
    def from_dict(data: dict[str, Any], source: str = "<dict>") -> Machine: ...

    @property
    def name(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def type(self) -> str: ...
    @property
    def actuator_count(self) -> int: ...
    @property
    def angle_convention(self) -> str: ...
    @property
    def controlled_axes(self) -> tuple[bool, bool, bool, bool, bool, bool]: ...
    @property
    def coordinate_names(self) -> tuple[str, str, str, str, str, str]: ...
    @property
    def controlled_names(self) -> list[str]: ...
    @property
    def is_planar(self) -> bool: ...
    @property
    def home(self) -> _Array: ...
    @property
    def tool_mm(self) -> Optional[_Array]: ...
    @property
    def actuator_limits(self) -> ActuatorLimits: ...
    @property
    def actuator_unit(self) -> Literal["mm", "rad"]: ...
    @property
    def platform_size_mm(self) -> float: ...

    def ik(self, poses: ArrayLike, *, errors: _Errors = "raise", check_limits: bool = True,
           out: Optional[_Array] = None, angles: _Angles = "rad") -> _Array:
        """Actuator values (N, n) of poses (N, 6) [x, y, z mm, a, b, c rad]; (n,) for one pose (6,)."""

    @overload
    def fk(self, actuators: ArrayLike, guess: Optional[ArrayLike] = None, *, warm: bool = True,
           extrapolate: bool = False, errors: _Errors = "raise", check_limits: bool = True, tolerance_mm: float = 1e-10,
           max_iterations: int = 60, same_branch: bool = True, info: Literal[False] = False,
           angles: _Angles = "rad") -> _Array: ...
    @overload
    def fk(self, actuators: ArrayLike, guess: Optional[ArrayLike] = None, *, warm: bool = True,
           extrapolate: bool = False, errors: _Errors = "raise", check_limits: bool = True, tolerance_mm: float = 1e-10,
           max_iterations: int = 60, same_branch: bool = True, info: Literal[True],
           angles: _Angles = "rad") -> tuple[_Array, FkInfo]: ...

    def fk_all(self, actuators: ArrayLike, *, check_limits: bool = True, tolerance_mm: float = 1e-10,
               max_iterations: int = 60) -> list[FkSolutionDict]:
        """Every assembly mode of one row (n,) of actuator values, nearest to home first."""

    def pose_from_abc(self, poses: ArrayLike, *, angles: _Angles = "rad") -> _Array:
        """Poses (N, 6) with G-code's A B C (rad, R = Rz(C)·Ry(B)·Rx(A)) in the machine's own convention."""

    def abc_from_pose(self, poses: ArrayLike, *, angles: _Angles = "rad") -> _Array:
        """The machine's own poses (N, 6) with G-code's A B C (rad, R = Rz(C)·Ry(B)·Rx(A))."""

    def jacobian(self, poses: ArrayLike, *, errors: _Errors = "raise", check_limits: bool = True,
                 angles: _Angles = "rad") -> _Array:
        """d(actuators)/d(controlled coordinates): (N, n, m), or (n, m) for one pose."""

    def conditioning(self, poses: ArrayLike, *, errors: _Errors = "nan",
                     check_limits: bool = True, angles: _Angles = "rad") -> dict[str, Any]:
        """det, condition_number, min_singular_value, delta_rho (mm/mm), s_x, s_y, s_z: (N,) arrays."""

    def __getstate__(self) -> tuple[str, str]: ...
    def __setstate__(self, state: tuple[str, str]) -> None: ...


def read_machine_dict(path: str | os.PathLike[str]) -> dict[str, Any]:
    """The machine file as plain data (dicts, lists, numbers, texts) for Machine.from_dict."""

def set_threads(threads: Optional[int]) -> None:
    """Limit pkm's batch calls to `threads` TBB threads (0 or None: all cores)."""

def get_threads() -> int: ...

def _ik_loop_seconds(machine: Machine, poses: ArrayLike, check_limits: bool = True) -> float: ...

# --- end of machine and kinematics -----------------------------------------------------------------------------

# --- pipeline and analyses (python/src/pipeline_*.cpp, analysis_*.cpp) ---------------------------------------
# Poses: [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] in the machine's angle convention. Keys carry their units;
# actuator values are actuators_mm (actuators_rad for angular actuators), drive forces force_N (force_Nmm).

def interpret(program_path: str | os.PathLike[str], machine: Optional[Machine] = None,
              tool_table: Optional[str | os.PathLike[str]] = None,
              subroutine_path: Optional[str | os.PathLike[str] | Sequence[str | os.PathLike[str]]] = None,
              parameter_file: Optional[str | os.PathLike[str]] = None,
              format: Literal["auto", "gcode", "apt", "nx", "creo", "catia", "solidworks"] = "auto",
              transform: bool = True) -> dict[str, Any]:
    """The canonical moves of a part program as arrays (line, kind, end_mm, end_abc_deg, center_mm, ...)."""

def plan(machine: Machine, program_path: str | os.PathLike[str], *, servo_period_ms: Optional[float] = None,
         feed_override_pct: float = 100.0, blend_tolerance_mm: Optional[float] = None, law: Optional[str] = None,
         free: str = "spin", bounds_deg: Optional[tuple[float, float] | Sequence[tuple[float, float]]] = None, law_step_mm: float = 1.0,
         solver: str = "greedy", energy_accounting: str = "no-recovery", force_model: str = "statics",
         force_limit_N: Optional[float] = None, max_rate_deg_per_mm: Optional[float] = None, load: str = "",
         dynamics: bool = False, elastic: bool = False, path_error: bool = True,
         tool_table: Optional[str | os.PathLike[str]] = None,
         subroutine_path: Optional[str | os.PathLike[str] | Sequence[str | os.PathLike[str]]] = None,
         parameter_file: Optional[str | os.PathLike[str]] = None,
         out_dir: Optional[str | os.PathLike[str]] = None, tables: str = "hdf5",
         lookahead_mm: float = 5000.0, lookahead_moves: int = 10000) -> dict[str, Any]:
    """The planned servo-rate motion: summary (as summary.json), time_s, line, actuators_mm (T, n), pose_machine (T, 6)
    (base frame, Machine.angle_convention), xyz_program_mm (T, 3) and abc_deg (T, 3) (program coordinates, G-code A B C),
    and with dynamics=True a dynamics dict (force_N, static_force_N, dynamic_force_N, power_W ...); with
    elastic=True also elastic (response.csv's columns: time_s, line, deviation_mm (T, 3), rotation_deg,
    tool_error_mm) and the elastic keys in summary['dynamics']."""

def interpolate(machine: Machine, program_path: str | os.PathLike[str], *, method: str = "carrier-corrected",
                servo_period_ms: Optional[float] = None, step_mm: Optional[float] = None,
                max_step_rate_hz: Optional[float] = None, rho_max_mm: float = 1e-3,
                delta_rho_max: Optional[float] = None, feed_override_pct: float = 100.0, override_at: str = "",
                accel: str = "s-curve", error_samples: int = 5, chord_check: bool = True,
                orientation_criterion: bool = False, linearise: bool = True, deviation_mm: Optional[float] = None,
                candidates: str = "all-six", tool_table: Optional[str | os.PathLike[str]] = None,
                subroutine_path: Optional[str | os.PathLike[str] | Sequence[str | os.PathLike[str]]] = None,
                parameter_file: Optional[str | os.PathLike[str]] = None,
                out_dir: Optional[str | os.PathLike[str]] = None) -> dict[str, Any]:
    """Whole drive steps per servo period: summary, time_s, line, steps (P, n) int32, position_steps (P, n) int64,
    contour_error_mm, tool_mm (P, 3), path_mm (P, 3)."""

def optimize(machine: Machine, program_path: str | os.PathLike[str], law: str, *, free: str = "spin",
             bounds_deg: Optional[tuple[float, float] | Sequence[tuple[float, float]]] = None, step_mm: float = 1.0, solver: str = "greedy",
             energy_accounting: str = "no-recovery", force_model: str = "statics",
             force_limit_N: Optional[float] = None, max_rate_deg_per_mm: Optional[float] = None, load: str = "",
             parts: str = "fixed", improvement: float = 0.01, min_part_mm: float = 1.0, patience: int = 3,
             tool_table: Optional[str | os.PathLike[str]] = None,
             subroutine_path: Optional[str | os.PathLike[str] | Sequence[str | os.PathLike[str]]] = None,
             parameter_file: Optional[str | os.PathLike[str]] = None,
             out_path: Optional[str | os.PathLike[str]] = None) -> dict[str, Any]:
    """The free coordinates chosen by a drive control law: summary (as `pkm optimize --json`), free_rad (K, F),
    line, position_mm, actuators_mm, chosen / constant metrics, the rewritten program."""

def modes(machine: Machine, pose: ArrayLike, *, angles: _Angles = "rad") -> dict[str, Any]:
    """Natural frequencies (frequencies_Hz) and mode shapes (shapes, columns) of the elastic struts at a pose."""

def compliance(machine: Machine, pose: ArrayLike, *, angles: _Angles = "rad") -> dict[str, Any]:
    """The tool's 6 × 6 compliance at a pose and its principal stiffness (translational_stiffness_N_um ...)."""

def workspace(machine: Machine, *, plane: str = "xy", centre: Optional[ArrayLike] = None, range_mm: float = 200.0,
              step_mm: float = 20.0, axes: Optional[Sequence[tuple[int, float, float]]] = None,
              stiffness: bool = False, frequencies: bool = False, threads: int = 0,
              out_dir: Optional[str | os.PathLike[str]] = None) -> dict[str, Any]:
    """The workspace map: summary (as summary.json), pose (C, 6), status (C,), limit, det_sign, condition_number,
    delta_rho, sensitivity (C, 3), optional lowest_stiffness_N_um / lowest_frequency_Hz."""


# --- calibration and dynamics ----------------------------------------------------------------------------------
# (python/src/analysis_calibration.cpp, analysis_dynamics.cpp; docs/calibration.md, docs/dynamics.md)

_PlanMethod = Literal["seven-pose", "random", "d-optimal"]
_Path = str | os.PathLike[str]


def calibrate_plan(machine: Machine, *, method: _PlanMethod = "d-optimal", poses: Optional[int] = None,
                   box_mm: float = 50.0, box_deg: float = 10.0, strut_change_mm: float = 10.0,
                   candidates: int = 400, held_out: int = 50, seed: int = 1, fixture_path: Optional[_Path] = None,
                   plate_radius_mm: float = 100.0, ballbar_centre_mm: Optional[tuple[float, float, float]] = None,
                   sigma_mm: float = 0.01, strict: bool = False, out_dir: Optional[_Path] = None) -> dict[str, Any]:
    """The poses to measure and their predicted accuracy, as `pkm calibrate plan`: summary, plan (plan.csv's
    columns), poses (P, 6), parameter_names (k,), predicted_sigma (k,), predicted_tool_error_mm (held_out,)."""

def calibrate_simulate(machine: Machine, *, method: _PlanMethod = "d-optimal", poses: Optional[int] = None,
                       box_mm: float = 50.0, box_deg: float = 10.0, strut_change_mm: float = 10.0,
                       candidates: int = 400, held_out: int = 50, seed: int = 1,
                       fixture_path: Optional[_Path] = None, plate_radius_mm: float = 100.0,
                       ballbar_centre_mm: Optional[tuple[float, float, float]] = None, sigma_mm: float = 0.01,
                       trials: int = 20, joint_error_mm: float = 0.1, offset_error_mm: float = 0.1,
                       write_measurements: Optional[_Path] = None, noise_free: bool = False,
                       out_dir: Optional[_Path] = None) -> dict[str, Any]:
    """Monte-Carlo calibration trials, as `pkm calibrate simulate`: summary, trials (trials.csv's columns), and with
    write_measurements true_parameters (true_parameters.csv's columns)."""

def calibrate_identify(machine: Machine, measurements_path: _Path, *, fixture_path: Optional[_Path] = None,
                       holdout: int = 0, strict: bool = False, calibrated_path: Optional[_Path] = None,
                       report_path: Optional[_Path] = None, out_dir: Optional[_Path] = None) -> dict[str, Any]:
    """Geometry and drive offsets from a measurement file, as `pkm calibrate identify`: summary, parameter_names,
    parameter_units, nominal, identified, sigma, identifiable (k,), residuals_before_mm, residuals_after_mm (r,),
    residuals / poses (the CSVs' columns), calibrated_text, calibrated_machine (a Machine)."""

def inverse_dynamics(machine: Machine, poses: ArrayLike, velocities: ArrayLike, accelerations: ArrayLike, *,
                     rates: Literal["twist", "coordinates"] = "twist",
                     load_N_Nmm: Optional[Sequence[float]] = None, errors: _Errors = "raise",
                     check_limits: bool = True) -> dict[str, _Array]:
    """Rigid-body drive forces for (N, 6) poses and twists [v mm/s, ω rad/s] (rates='twist') or coordinate rates:
    force_N, static_force_N, dynamic_force_N, actuator_rates_mm_s, power_W, each (N, n)."""
