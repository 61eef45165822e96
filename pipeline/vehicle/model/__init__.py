"""The tractor as parts that assemble themselves (issues 23, 35).

A tractor is a list of parts (:class:`Chassis`, two :class:`Axle`, optional :class:`Cab`,
:class:`Implement` and :class:`Ballast`, the seat :class:`SeatPoint`), in the shape of
Project Chrono's vehicle module (chassis, axles with a suspension and left/right wheels,
tyres, attachments, each subsystem initialising itself). :func:`assemble` hands every part
a :class:`Builder` twice: :meth:`Part.declare` asks for the coordinates the part moves on,
:meth:`Part.contribute` adds its bodies (mass and inertia on rows of the coordinates), its
force elements (:mod:`tyrelab.vehicle.elements`: each a row ``g`` over the coordinates, its
deformation ``δ = g·q (+ u)``) and its outputs. The result is one :class:`Assembly` with one
state layout (:class:`tyrelab.vehicle.elements.StateLayout`), which every solution path reads:

* :meth:`Assembly.linear` — ``x' = A x + B w``, ``y = C x + D w`` with named states,
  inputs and outputs (the exact first-order-hold path, the frequency domain);
* :meth:`Assembly.undamped` — stiffness and mass matrices of the undamped eigenproblem
  (the bounce/pitch frequencies of thesis ch. 8, the roll modes);
* the nonlinear right-hand side of :mod:`tyrelab.vehicle.tractor` (RK4 across lift-off), on
  the same states, from the same element rows.

How to add a part kind
----------------------
Write one frozen dataclass with ``declare(builder)`` and ``contribute(builder)`` (and
``check(three_d)`` for its rules) and hand it to :func:`assemble` in ``Parts.extra``; no
solver changes. A front-linkage implement on a spring, say::

    @dataclass(frozen=True)
    class FrontWeight(Part):
        mass_kg: float
        ahead_of_cg_m: float
        stiffness_N_per_m: float
        damping_N_s_per_m: float

        def declare(self, b):
            b.coordinate("front_weight_z")

        def contribute(self, b):
            at = b.chassis_point(self.ahead_of_cg_m, 0.0, 0.0)
            own = {"z": b.row({"front_weight_z": 1.0}), "x": at["x"], "y": at["y"]}
            b.body(self.mass_kg, 0.0, 0.0, own, None, b.pitch_row)
            b.element(SpringDamper("front_weight", own["z"] - at["z"], self.stiffness_N_per_m,
                                   self.damping_N_s_per_m))

A new element kind (a lateral tyre element) is a subclass of
:class:`tyrelab.vehicle.elements.Element` (see that module); a new chassis freedom (lateral
``y``, yaw) is a name added to :data:`CHASSIS_FREEDOMS` (after the existing ones, so the
existing models keep their coordinates' order and their numbers to the bit).

Kinematics (small angles, SI): ``x`` forward, ``y`` left, ``z`` up from the tractor's centre
of gravity (CG); pitch ``θ`` nose up, roll ``φ`` left side up. A point ``(p_x, p_y, p_z)``
of the chassis moves by ``dz = z + p_x θ + p_y φ``, ``dx = x - p_z θ``, ``dy = -p_z φ``.

Coordinates: chassis ``z``, ``th``, ``x`` (with a longitudinal element), ``phi`` (with a
roll inertia: the 3-D model); a pivot axle ``<axle>_axle_roll``; a suspended axle
``<axle>_axle_z`` (and its roll in 3-D); a suspended cab ``cab_z``, ``cab_th`` (``cab_phi``);
an implement on a hitch spring ``implement_th``. States are the positions the springs
see, then all velocities (``v`` + name), then the elements' own states (a Maxwell element's
spring extension, ``q``, or ``q_<element>`` for more than one): a coordinate no spring sees
carries only its velocity (the fore-aft ``x`` with a Maxwell element or a damper alone).

Mass: ``Chassis`` mass and inertias are the whole tractor's (rigid cab and axles
included); a suspended axle or cab is taken out of it where it sits (its own mass and
inertia moving on its own coordinates instead), so switching a part from rigid to
suspended keeps the tractor's mass, CG and inertia. An implement and a front ballast are
added to the tractor.

The seat suspension (:class:`SeatSuspension`, on :class:`SeatPoint`) is base-excited with no
feedback on the tractor (thesis ch. 7): a linear filter the seat point's vertical output
passes through, :attr:`Assembly.output_filters`, which the time and frequency domains apply.

The package (issue 45): :mod:`~tyrelab.vehicle.model.parts` (the part kinds and the fields each
needs), :mod:`~tyrelab.vehicle.model.assembly` (:class:`Builder`, :class:`Assembly`,
:func:`assemble`), :mod:`~tyrelab.vehicle.model.linear` (:class:`LinearModel`); the force elements
are :mod:`tyrelab.vehicle.elements`, one layer below. Every name is importable from here, as
before the split.
"""

from ..elements import Element
from ..units import STANDARD_GRAVITY_M_S2  # noqa: F401  (the model's gravity, as before the split)
from ..units import STANDARD_GRAVITY_M_S2 as GRAVITY_M_S2  # noqa: F401  (the name of issue 35)
from .assembly import Assembly, Builder, assemble, coordinate_output
from .linear import LinearModel
from .parts import (AXLE_LONGITUDINAL_MODELS, AXLE_MOUNTS, CHASSIS_FREEDOMS, LATERAL_MODELS, LONGITUDINAL_MODELS, Axle, Ballast, Cab,
                    Chassis, Implement, Part, Parts, SeatPoint, SeatSuspension, cab_mount_problems, needs,
                    pivot_problem, scenario_key)

__all__ = ["Chassis", "Axle", "Cab", "Implement", "Ballast", "SeatPoint", "SeatSuspension", "Parts", "Part",
           "Builder", "Element", "Assembly", "LinearModel", "assemble", "coordinate_output", "AXLE_MOUNTS",
           "AXLE_LONGITUDINAL_MODELS", "LATERAL_MODELS", "CHASSIS_FREEDOMS", "needs", "scenario_key", "pivot_problem",
           "cab_mount_problems"]
