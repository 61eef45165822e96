"""Natural modes of an assembled tractor: named by what moves, followed by their shapes (issues 23, 37).

:func:`mode_set` solves the undamped eigenproblem ``K φ = ω² M φ`` of an assembly
(:meth:`tyrelab.vehicle.model.Assembly.undamped`) and names each mode by the coordinate that moves
most (:data:`MODE_NAMES`; the body's bounce and pitch by thesis §8.2's rule). Names by shape alone
can change when a parameter moves two modes past each other (the lower body mode is "pitch" on one
side and "bounce" on the other), so wherever two models' modes must be compared the modes are
**followed by shape**: :meth:`ModeSet.follow` pairs each mode of a reference with the mode of the
other model whose shape it resembles most, by the mass-weighted modal assurance criterion

    MAC(a, b) = (aᵀ M b)² / ((aᵀ M a)(bᵀ M b))

(Allemang & Brown 1982; ``M`` the reference's mass matrix over the coordinates the two share),
one to one (:func:`scipy.optimize.linear_sum_assignment`). A pair below :data:`FOLLOW_MAC` is a
mode that cannot be followed: it gets no number.

Two places follow modes: :func:`frequency_intervals` (the 95 % intervals from the tyre stiffness
uncertainty, where each perturbed model's modes are followed from the nominal one, so an interval
is always on the frequency of one mode) and :func:`follow_names` (a sweep's variants take the mode
names of its first variant, so a sweep's ``bounce_Hz`` column holds one mode). Further freedoms
(lateral, yaw: issue 33) add their coordinate's name to :data:`MODE_NAMES`; the following is
the same for every mode.

Examples
--------
>>> from tyrelab.vehicle.model import assemble
>>> from tyrelab.vehicle.tractor import Tractor, tractor_parts
>>> asm = assemble(tractor_parts(Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 0.0, 0.0)))
>>> m = mode_set(asm)
>>> {k: round(v, 4) for k, v in m.frequencies().items()}
{'bounce': 2.2508, 'pitch': 4.5016}
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy import linalg, optimize

from ... import _validate
from . import beam
from ..model import Assembly, assemble
from ..units import from_kilo, to_kilo

__all__ = ["MODE_NAMES", "LATERAL_ROLL_SHARE", "FOLLOW_MAC", "ModeSet", "mode_set", "mac_matrix", "frequency_intervals", "follow_names"]

#: Mode names by the coordinate that moves most (the body's ``z`` and ``th`` by thesis §8.2's rule;
#: ``y`` and ``psi``: the body's lateral and yaw freedoms of issue 33's lateral tyre elements).
MODE_NAMES = {"lateral_roll": "lateral_roll", "z": "bounce", "th": "pitch", "phi": "roll", "y": "lateral", "psi": "yaw",
              "front_axle_roll": "front_axle_roll",
              "rear_axle_roll": "rear_axle_roll", "front_axle_z": "front_axle_bounce", "rear_axle_z": "rear_axle_bounce",
              "cab_z": "cab_bounce", "cab_th": "cab_pitch", "cab_phi": "cab_roll", "implement_th": "implement_pitch"}
#: The lowest mode led by the body's lateral or roll motion is named ``lateral_roll`` when the lesser of
#: the two holds at least this share of its kinetic energy (issue 33; a documented choice), else by
#: what moves most (``lateral``, ``roll``).
LATERAL_ROLL_SHARE = 0.05
#: Least MAC at which a mode is the same mode as the reference's: more than half of the reference
#: shape's mass-weighted motion lies in it, so no other mode (they are M-orthogonal) can claim it.
FOLLOW_MAC = 0.5


@dataclass(frozen=True)
class ModeSet:
    """The undamped modes of one assembly.

    Attributes
    ----------
    names : tuple of str
        One per mode, in ascending frequency.
    frequencies_Hz : tuple of float
    coordinates : tuple of str
        The coordinates of the shapes' rows.
    shapes : ndarray
        Mass-normalised mode shapes, one column per mode.
    mass : ndarray
        The mass matrix over ``coordinates``.
    nodal_points_m : tuple of float
        Per mode, the point ahead of the CG that the body's bounce and pitch leave still
        (``-z/θ``; inf without pitch).
    """

    names: tuple
    frequencies_Hz: tuple
    coordinates: tuple
    shapes: np.ndarray
    mass: np.ndarray
    nodal_points_m: tuple

    def frequencies(self) -> dict:
        """``{name: frequency_Hz}``."""
        return dict(zip(self.names, self.frequencies_Hz))

    def nodal(self) -> dict:
        """``{"bounce": m, "pitch": m}``: the nodal points of the body's bounce and pitch ahead of the CG."""
        return {n: x for n, x in zip(self.names, self.nodal_points_m) if n in ("bounce", "pitch")}

    def follow(self, other: "ModeSet", threshold: float = FOLLOW_MAC) -> dict:
        """``{name: (index of the same mode in other, MAC)}`` per mode of this set; the index is None
        where the best one-to-one match is below ``threshold`` (the mode cannot be followed)."""
        _validate.instance("other", other, ModeSet)
        mac = mac_matrix(self, other)
        rows, cols = optimize.linear_sum_assignment(-mac)
        out = {n: (None, 0.0) for n in self.names}
        for i, j in zip(rows, cols):
            out[self.names[i]] = (int(j) if mac[i, j] >= threshold else None, float(mac[i, j]))
        return out


def mac_matrix(reference: ModeSet, other: ModeSet) -> np.ndarray:
    """Mass-weighted MAC of every mode of ``reference`` (rows) with every mode of ``other``
    (columns), over their common coordinates with the reference's mass matrix.

    Examples
    --------
    >>> from tyrelab.vehicle.model import assemble
    >>> from tyrelab.vehicle.tractor import Tractor, tractor_parts
    >>> m = mode_set(assemble(tractor_parts(Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 0.0, 0.0))))
    >>> mac_matrix(m, m).round(6).tolist()
    [[1.0, 0.0], [0.0, 1.0]]
    """
    _validate.instance("reference", reference, ModeSet)
    _validate.instance("other", other, ModeSet)
    common = [c for c in reference.coordinates if c in other.coordinates]
    ia = [reference.coordinates.index(c) for c in common]
    ib = [other.coordinates.index(c) for c in common]
    m = reference.mass[np.ix_(ia, ia)]
    a, b = reference.shapes[ia, :], other.shapes[ib, :]
    cross = a.T @ m @ b
    na, nb = np.einsum("ij,ik,kj->j", a, m, a), np.einsum("ij,ik,kj->j", b, m, b)
    den = np.outer(na, nb)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(den > 0, cross**2 / np.where(den > 0, den, 1.0), 0.0)


def _is_beam(asm: Assembly) -> bool:
    """The thesis' §8.2 beam on two springs (the undamped model has z and θ only)."""
    return asm.undamped()[2] == ("z", "th")


def mode_set(asm: Assembly) -> ModeSet:
    """The undamped modes of an assembled tractor, named.

    Each mode is named by the coordinate that moves most (kinetic-energy share; :data:`MODE_NAMES`,
    a second mode of the same name ``_2``); of the modes led by the body's ``z`` or ``θ`` the one with
    the larger ``|z|/|θ|`` share is bounce, the other pitch (thesis §8.2). The pitch-plane tractor on
    rigid axles is thesis §8.2's beam on two springs: its frequencies are
    :func:`tyrelab.vehicle.solvers.beam.mode_shapes`' (the same eigenproblem).
    """
    _validate.instance("asm", asm, Assembly)
    k, m, coords = asm.undamped()
    if np.array_equal(k, k.T):
        w2, vecs = linalg.eigh(k, m)
    else:  # the static loads' moment (issue 33) makes K unsymmetric: real modes of the undamped system
        w2, vecs = linalg.eig(k, m)
        order = np.argsort(w2.real)
        w2, vecs = w2.real[order], vecs[:, order].real
    freqs = [math.sqrt(max(float(x), 0.0)) / (2 * math.pi) for x in w2]
    iz, ith = coords.index("z"), coords.index("th")
    shares = [vecs[:, i] * (m @ vecs[:, i]) for i in range(len(w2))]
    dominant = [coords[int(np.argmax(np.abs(sh)))] for sh in shares]
    if "y" in coords:  # issue 33: the lowest mode led by the body's lateral or roll motion, with both in it,
        iy, iphi = coords.index("y"), coords.index("phi")  # is the coupled lateral-roll mode
        for i, sh in enumerate(shares):
            ey, ephi, total = abs(sh[iy]), abs(sh[iphi]), float(np.sum(np.abs(sh)))
            if dominant[i] in ("y", "phi"):
                if min(ey, ephi) >= LATERAL_ROLL_SHARE * total:
                    dominant[i] = "lateral_roll"
                break
    label = {i: MODE_NAMES.get(dominant[i], dominant[i]) for i in range(len(w2))}
    if _is_beam(asm):
        p = asm.parts
        ms = beam.mode_shapes(p.chassis.mass_kg, p.chassis.pitch_inertia_kg_m2, p.front.ahead_of_cg_m,
                                      -p.rear.ahead_of_cg_m, 2 * p.front.tyre_stiffness_N_per_m,
                                      2 * p.rear.tyre_stiffness_N_per_m)
        # thesis §8.2's names and frequencies; each to the eigenvector of the nearer frequency
        order = sorted(("bounce", "pitch"), key=lambda n: ms[n]["frequency_Hz"])
        label = dict(enumerate(order))
        freqs = [ms[n]["frequency_Hz"] for n in order]
    else:
        # the body's bounce and pitch (modes led by z or θ): by thesis §8.2's rule, the larger
        # |z|/(r |θ|) is bounce (a tie to the lower frequency), the other pitch
        body = [i for i in range(len(w2)) if dominant[i] in ("z", "th")]
        ranked = sorted(body, key=lambda i: -abs(shares[i][iz]) / max(abs(shares[i][ith]), 1e-300))
        for j, i in enumerate(ranked[:2]):
            label[i] = ("bounce", "pitch")[j] if len(ranked) > 1 else MODE_NAMES[dominant[i]]
    names, nodal = [], []
    for i in range(len(w2)):
        name = label[i]
        while name in names:
            name = f"{name}_2" if not name[-1].isdigit() else f"{name[:-1]}{int(name[-1]) + 1}"
        names.append(name)
        z, th = vecs[iz, i], vecs[ith, i]
        nodal.append(float(-z / th) + 0.0 if abs(th) > 1e-12 * abs(z) else math.inf)
    return ModeSet(tuple(names), tuple(freqs), tuple(coords), vecs, m, tuple(nodal))


def _scaled(asm: Assembly, axle: str, factor: float) -> Assembly:
    p = asm.parts
    part = getattr(p, axle)
    return assemble(dataclasses.replace(p, **{axle: dataclasses.replace(
        part, tyre_stiffness_N_per_m=factor * part.tyre_stiffness_N_per_m)}))


def frequency_intervals(asm: Assembly, u_front_tyre_kN_per_m: float, u_rear_tyre_kN_per_m: float) -> tuple[dict, list]:
    """95 % intervals of the natural frequencies from the tyre stiffness uncertainties.

    First order (GUM 5.1.2), central differences (±1 % of each axle's tyre stiffness),
    independent axles, ``f ± 1.96 u`` (:func:`tyrelab.vehicle.solvers.beam.frequency_uncertainty`
    for thesis §8.2's beam, the same method on the assembled model otherwise), each perturbed model's
    modes followed from the nominal ones by shape (:meth:`ModeSet.follow`).

    Returns
    -------
    intervals : dict
        ``{name: [low, high]}`` per mode of :func:`mode_set`; None where the mode cannot be followed
        through the perturbation or the first-order interval would reach below 0 Hz.
    notes : list of str
        Why each None.

    Examples
    --------
    >>> from tyrelab.vehicle.model import assemble
    >>> from tyrelab.vehicle.tractor import Tractor, tractor_parts
    >>> asm = assemble(tractor_parts(Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 0.0, 0.0)))
    >>> ci, notes = frequency_intervals(asm, 5.0, 5.0)
    >>> [round(x, 3) for x in ci["bounce"]], notes
    ([2.095, 2.407], [])
    """
    _validate.instance("asm", asm, Assembly)
    base = mode_set(asm)
    freqs = base.frequencies()
    p = asm.parts
    lost: dict = {}
    if _is_beam(asm):
        _, intervals = beam.frequency_uncertainty(
            p.chassis.mass_kg, p.chassis.pitch_inertia_kg_m2, p.front.ahead_of_cg_m, -p.rear.ahead_of_cg_m,
            to_kilo(p.front.tyre_stiffness_N_per_m), to_kilo(p.rear.tyre_stiffness_N_per_m),
            u_front_tyre_kN_per_m, u_rear_tyre_kN_per_m)
        # the beam's two frequencies come in ascending order, as the set's
        raw = {n: list(iv) for n, iv in zip(sorted(freqs, key=freqs.get), intervals)}
    else:
        var = dict.fromkeys(freqs, 0.0)
        for axle, u in (("front", u_front_tyre_kN_per_m), ("rear", u_rear_tyre_kN_per_m)):
            if not u > 0:
                continue
            k = getattr(p, axle).tyre_stiffness_N_per_m
            up, down = mode_set(_scaled(asm, axle, 1.01)), mode_set(_scaled(asm, axle, 0.99))
            fu, fd = base.follow(up), base.follow(down)
            for n in freqs:
                (j_up, mac_up), (j_down, mac_down) = fu[n], fd[n]
                if j_up is None or j_down is None:
                    lost[n] = (axle, min(mac_up, mac_down))
                    continue
                var[n] += ((up.frequencies_Hz[j_up] - down.frequencies_Hz[j_down]) / (0.02 * k) * from_kilo(u)) ** 2
        raw = {n: [f - 1.96 * math.sqrt(var[n]), f + 1.96 * math.sqrt(var[n])] for n, f in freqs.items()}
    out, notes = {}, []
    for n in freqs:
        if n in lost:
            axle, mac = lost[n]
            out[n] = None
            notes.append(f"{n}: no 95 % interval: the mode cannot be followed when the {axle} tyre stiffness "
                         f"changes by 1 % (its shape's MAC {mac:.2f} < {FOLLOW_MAC:g}: it trades places with another mode)")
        elif raw[n][0] < 0:
            out[n] = None
            notes.append(f"{n}: no 95 % interval: the first-order interval would reach below 0 Hz "
                         f"({raw[n][0]:.3g} Hz; the tyre stiffness uncertainty moves this mode too far to be linear)")
        else:
            out[n] = raw[n]
    return out, notes


def follow_names(reference: ModeSet, other: ModeSet) -> tuple[dict, list]:
    """``other``'s modes under ``reference``'s names: ``{other's name: reference's name}`` for every
    mode followed (:meth:`ModeSet.follow`), and a note per reference mode that cannot be followed."""
    _validate.instance("reference", reference, ModeSet)
    _validate.instance("other", other, ModeSet)
    mapping, notes = {}, []
    for name, (j, mac) in reference.follow(other).items():
        if j is None:
            notes.append(f"{name}: not followed from the first variant (best MAC {mac:.2f} < {FOLLOW_MAC:g}): no number")
        else:
            mapping[other.names[j]] = name
    return mapping, notes
