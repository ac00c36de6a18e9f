"""``VehicleConfig`` presets of real 1:10 cars identified on track by ForzaETH.

ForzaETH's On-Track-SysID (MIT licence; Dikici et al., "Learning-Based On-Track System
Identification for Scaled Autonomous Racing in Under a Minute", arXiv 2411.17508, 2024)
publishes single-track models of their cars with Pacejka lateral tyre fits
``F_y = F_z D sin(C atan(B a - E (B a - atan(B a))))`` per axle (``F_z`` the axle's static
load, ``a`` the slip angle). A preset takes from a car's model its mass, yaw inertia, axle
distances and CoM height, and maps its tyres onto ours by the fits' slope at zero slip
(cornering stiffness per unit load ``B C D``, front and rear) and their friction: the
model's ``mu`` where it has one (NUC6, NUC7), else the lower axle peak ``min(D_f, D_r)``.
Everything else (motor, servo, suspension, chassis box) stays the Traxxas defaults, so a
preset drives in both engines (ours and the PhysX car ``build --car`` authors).

:func:`read_forzaeth_model` reads a model file (``models/<NAME>/<NAME>_pacejka.txt``) and
:func:`preset_from_model` maps any such model; :func:`forzaeth_preset` gives the four real
cars and the authors' simulator car without the files (the numbers below, with their source).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from ..errors import ConfigError
from .sim import VehicleConfig

#: Per car: m (kg), I_z (kg m^2), l_f, l_r, h_cg (m), mu (None: not in the model), and the
#: Pacejka [B, C, D, E] of the front and rear axles, from ForzaETH On-Track-SysID commit
#: 7b2b712, ``models/<NAME>/<NAME>_pacejka.txt`` (MIT).
FORZAETH_MODELS: dict[str, dict[str, Any]] = {
    "NUC2": {
        "m": 4.5, "I_z": 0.0627, "l_f": 0.17, "l_r": 0.155, "h_cg": 0.02, "mu": None,
        "C_Pf": [7.6671, 1.2628, 1.2307, 0.3821], "C_Pr": [7.1036, 1.7356, 1.0252, 1.2875],
    },
    "NUC5": {
        "m": 3.5, "I_z": 0.0627, "l_f": 0.165, "l_r": 0.155, "h_cg": 0.02, "mu": None,
        "C_Pf": [6.4196, 0.9826, 0.4044, 0.5073], "C_Pr": [7.5624, 1.3006, 0.3237, 0.6478],
    },
    "NUC6": {
        "m": 3.75, "I_z": 0.056, "l_f": 0.176, "l_r": 0.149, "h_cg": 0.014, "mu": 0.9514,
        "C_Pf": [6.7948, 1.3492, 0.8768, 0.6186], "C_Pr": [6.9876, 2.6412, 0.9679, 0.1296],
    },
    "NUC7": {
        "m": 3.75, "I_z": 0.056, "l_f": 0.176, "l_r": 0.149, "h_cg": 0.014, "mu": 0.9514,
        "C_Pf": [11.1259, 1.2333, 0.8809, 0.7587], "C_Pr": [7.5143, 4.2815, 0.7418, 0.8582],
    },
    "SIM": {
        "m": 3.54, "I_z": 0.05797, "l_f": 0.162, "l_r": 0.145, "h_cg": 0.02, "mu": None,
        "C_Pf": [6.6185, 1.6102, 0.652, 0.7826], "C_Pr": [7.9507, 3.692, 0.6691, 0.5595],
    },
}  # fmt: skip


def pacejka(alpha: Any, params: list[float]) -> Any:
    """ForzaETH's lateral force per unit load, ``D sin(C atan(B a - E (B a - atan(B a))))``."""
    import numpy as np

    b, c, d, e = params
    ba = b * np.asarray(alpha, dtype=float)
    return d * np.sin(c * np.arctan(ba - e * (ba - np.arctan(ba))))


def read_forzaeth_model(path: str | Path) -> dict[str, Any]:
    """A ForzaETH model file (YAML: ``m``, ``I_z``, ``l_f``, ``l_r``, ``C_Pf``, ...) as a dict."""
    import yaml

    p = Path(path)
    try:
        data = yaml.safe_load(p.read_text())
    except (OSError, yaml.YAMLError) as e:
        raise ConfigError(f"{p}: not a readable ForzaETH model file ({e})") from e
    missing = {"m", "I_z", "l_f", "l_r", "C_Pf", "C_Pr"} - set(data or {})
    if missing:
        raise ConfigError(f"{p}: a ForzaETH model needs {sorted(missing)}")
    return dict(data)


def preset_from_model(model: dict[str, Any], base: VehicleConfig | None = None) -> VehicleConfig:
    """``base`` (default: the paper's car) with a ForzaETH model's mass, inertia, geometry and tyres."""
    b = base or VehicleConfig()
    bcd = [p[0] * p[1] * p[2] for p in (model["C_Pf"], model["C_Pr"])]
    mu = model.get("mu") or min(model["C_Pf"][2], model["C_Pr"][2])
    lf, lr = float(model["l_f"]), float(model["l_r"])
    update = {
        "mass": float(model["m"]),
        "yaw_inertia": float(model["I_z"]),
        "com_to_front": lf,
        "com_to_rear": lr,
        "wheelbase": lf + lr,
        "tyre_friction": float(mu),
        "cornering_stiffness_front": float(bcd[0]),
        "cornering_stiffness_rear": float(bcd[1]),
    }
    if model.get("h_cg"):
        update["com_height"] = float(model["h_cg"])
    return VehicleConfig(**{**b.model_dump(), **update})


def forzaeth_preset(name: str, base: VehicleConfig | None = None) -> VehicleConfig:
    """The ``VehicleConfig`` of ForzaETH's car ``name`` (NUC2, NUC5, NUC6, NUC7, SIM)."""
    key = name.upper()
    if key not in FORZAETH_MODELS:
        raise ConfigError(f"no ForzaETH car {name!r}; choose one of {', '.join(FORZAETH_MODELS)}")
    return preset_from_model(FORZAETH_MODELS[key], base)


def static_axle_loads(model: dict[str, Any], g: float = 9.81) -> tuple[float, float]:
    """Static front and rear axle loads (N) of a ForzaETH model, as its fits use them."""
    lf, lr, m = float(model["l_f"]), float(model["l_r"]), float(model["m"])
    return m * g * lr / (lf + lr), m * g * lf / (lf + lr)


def single_track_yaw_rate(model: dict[str, Any], v: float, steer: float, g: float = 9.81) -> float:
    """Steady yaw rate (rad/s) of ForzaETH's single-track model with its Pacejka tyres at
    static loads, at constant forward speed ``v`` and ``steer`` (integrated to rest)."""
    fzf, fzr = static_axle_loads(model, g)
    lf, lr, m, iz = float(model["l_f"]), float(model["l_r"]), float(model["m"]), float(model["I_z"])
    vy = r = 0.0
    dt = 1e-3
    for _ in range(20000):
        af = steer - math.atan2(vy + lf * r, v)
        ar = -math.atan2(vy - lr * r, v)
        fyf = fzf * float(pacejka(af, model["C_Pf"]))
        fyr = fzr * float(pacejka(ar, model["C_Pr"]))
        dvy = (fyf * math.cos(steer) + fyr) / m - v * r
        dr = (lf * fyf * math.cos(steer) - lr * fyr) / iz
        vy, r = vy + dt * dvy, r + dt * dr
    return r
