"""Mason: plan and rehearse missions for robot construction crews.

Walls (``Wall``), build orders (``plan_order``), team schedules (``plan_schedule``),
missions (``simulate``, ``monte_carlo``), crews and MAPF (``mason.crew``), and the
validators for plans made elsewhere (``validate_order``, ``validate_schedule``,
``check_trace``). Long calls release the GIL, honour their time limit and stop on Ctrl-C.
"""

from ._errors import InputError, MasonError, NoSolutionError, ValidationError
from ._mason import (
    Plan,
    Schedule,
    Trace,
    Wall,
    __version__,
    builtin_walls,
    check_trace,
    monte_carlo,
    plan_order,
    plan_schedule,
    simulate,
    summarise,
    validate_order,
    validate_schedule,
)
from . import crew

__all__ = [
    "InputError",
    "MasonError",
    "NoSolutionError",
    "ValidationError",
    "Plan",
    "Schedule",
    "Trace",
    "Wall",
    "__version__",
    "builtin_walls",
    "check_trace",
    "crew",
    "monte_carlo",
    "plan_order",
    "plan_schedule",
    "simulate",
    "summarise",
    "validate_order",
    "validate_schedule",
]
