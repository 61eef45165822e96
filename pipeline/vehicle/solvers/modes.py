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
from .roots import (SENSITIVITY_SHAPE_SHARE, ZERO_ROOT, DampedMode, _release_path, _released, _released_by, _roots,
                    root_sensitivities)
from ..units import from_kilo, to_kilo

__all__ = ["MODE_NAMES", "LATERAL_ROLL_SHARE", "FOLLOW_MAC", "ZERO_ROOT", "ModeSet", "mode_set", "mac_matrix",
           "frequency_intervals", "follow_names", "DampedMode", "damped_modes", "follow_damped", "follow_renamed", "FOLLOW_STEPS",
           "root_sensitivities", "SENSITIVITY_SHAPE_SHARE"]

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

    See Also
    --------
    follow_names : names modes by it.

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


def _shape_names(shares, coords, one_to_one: bool = False) -> list[str]:
    """Names of modes (ascending in frequency) from their kinetic-energy shares over ``coords``
    (:func:`mode_set`'s rules: what moves most, :data:`MODE_NAMES`; the lowest mode led by the body's
    lateral or roll motion with both in it ``lateral_roll``; of the modes led by ``z`` or ``θ`` the
    larger ``|z|/|θ|`` share is bounce, the other pitch, thesis §8.2; a second of a name ``_2``).
    ``one_to_one``: each mode leads by a coordinate of its own, the assignment of modes to coordinates
    with the largest total share (:func:`scipy.optimize.linear_sum_assignment`; the damped modes of
    issue 42, where a heavily damped pair can share its leader)."""
    coords = list(coords)
    iz, ith = coords.index("z"), coords.index("th")
    dominant = [coords[int(np.argmax(np.abs(sh)))] for sh in shares]
    if one_to_one and len(shares) <= len(coords):
        rows, cols = optimize.linear_sum_assignment(-np.abs(np.array(shares, float)))
        for i, j in zip(rows, cols):
            dominant[int(i)] = coords[int(j)]
    if "y" in coords:  # issue 33: the lowest mode led by the body's lateral or roll motion, with both in it,
        iy, iphi = coords.index("y"), coords.index("phi")  # is the coupled lateral-roll mode
        for i, sh in enumerate(shares):
            ey, ephi, total = abs(sh[iy]), abs(sh[iphi]), float(np.sum(np.abs(sh)))
            if dominant[i] in ("y", "phi"):
                if min(ey, ephi) >= LATERAL_ROLL_SHARE * total:
                    dominant[i] = "lateral_roll"
                break
    label = {i: MODE_NAMES.get(dominant[i], dominant[i]) for i in range(len(shares))}
    # the body's bounce and pitch (modes led by z or θ): by thesis §8.2's rule, the larger
    # |z|/(r |θ|) is bounce (a tie to the lower frequency), the other pitch
    body = [i for i in range(len(shares)) if dominant[i] in ("z", "th")]
    ranked = sorted(body, key=lambda i: -abs(shares[i][iz]) / max(abs(shares[i][ith]), 1e-300))
    for j, i in enumerate(ranked[:2]):
        label[i] = ("bounce", "pitch")[j] if len(ranked) > 1 else MODE_NAMES[dominant[i]]
    names: list[str] = []
    for i in range(len(shares)):
        name = label[i]
        while name in names:
            name = f"{name}_2" if not name[-1].isdigit() else f"{name[:-1]}{int(name[-1]) + 1}"
        names.append(name)
    return names


def mode_set(asm: Assembly) -> ModeSet:
    """The undamped modes of an assembled tractor, named.

    Each mode is named by the coordinate that moves most (kinetic-energy share; :data:`MODE_NAMES`,
    a second mode of the same name ``_2``); of the modes led by the body's ``z`` or ``θ`` the one with
    the larger ``|z|/|θ|`` share is bounce, the other pitch (thesis §8.2). The pitch-plane tractor on
    rigid axles is thesis §8.2's beam on two springs: its frequencies are
    :func:`tyrelab.vehicle.solvers.beam.mode_shapes`' (the same eigenproblem).

    See Also
    --------
    follow_names : follows them into a variant.
    frequency_intervals : their 95 % intervals.

    Examples
    --------
    >>> from tyrelab.vehicle.model import Axle, Chassis, Parts, assemble
    >>> asm = assemble(Parts(Chassis(5120.0, 6210.0, 0.838), Axle("front", 1.54, 4.25e5, 1.5e3),
    ...                      Axle("rear", -0.896, 3.3e5, 1e3)))
    >>> m = mode_set(asm)
    >>> m.names, [round(f, 3) for f in m.frequencies_Hz]
    (('bounce', 'pitch'), [2.322, 3.531])
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
    if _is_beam(asm):
        p = asm.parts
        ms = beam.mode_shapes(p.chassis.mass_kg, p.chassis.pitch_inertia_kg_m2, p.front.ahead_of_cg_m,
                                      -p.rear.ahead_of_cg_m, 2 * p.front.tyre_stiffness_N_per_m,
                                      2 * p.rear.tyre_stiffness_N_per_m)
        # thesis §8.2's names and frequencies; each to the eigenvector of the nearer frequency
        order = sorted(("bounce", "pitch"), key=lambda n: ms[n]["frequency_Hz"])
        names = order
        freqs = [ms[n]["frequency_Hz"] for n in order]
    else:
        names = _shape_names(shares, coords)
    nodal = []
    for i in range(len(w2)):
        z, th = vecs[iz, i], vecs[ith, i]
        nodal.append(float(-z / th) + 0.0 if abs(th) > 1e-12 * abs(z) else math.inf)
    return ModeSet(tuple(names), tuple(freqs), tuple(coords), vecs, m, tuple(nodal))


def _scaled(asm: Assembly, axle: str, factor: float) -> Assembly:
    p = asm.parts
    part = getattr(p, axle)
    return assemble(dataclasses.replace(p, **{axle: dataclasses.replace(
        part, tyre_stiffness_N_per_m=factor * part.tyre_stiffness_N_per_m)}))


def frequency_intervals(asm: Assembly, u_front_tyre_kN_per_m: float, u_rear_tyre_kN_per_m: float,
                        modes: ModeSet | None = None) -> tuple[dict, list]:
    """95 % intervals of the natural frequencies from the tyre stiffness uncertainties.

    First order (GUM 5.1.2), central differences (±1 % of each axle's tyre stiffness),
    independent axles, ``f ± 1.96 u`` (:func:`tyrelab.vehicle.solvers.beam.frequency_uncertainty`
    for thesis §8.2's beam, the same method on the assembled model otherwise), each perturbed model's
    modes followed from the nominal ones by shape (:meth:`ModeSet.follow`).

    Parameters
    ----------
    asm : Assembly
    u_front_tyre_kN_per_m, u_rear_tyre_kN_per_m : float
        Standard uncertainty of one front and one rear tyre's vertical stiffness, kN/m.
    modes : ModeSet, optional
        ``mode_set(asm)`` where the caller has it already (a ride's :func:`~tyrelab.vehicle.run.plan.finish`),
        else computed here.

    Returns
    -------
    intervals : dict
        ``{name: [low, high]}`` per mode of :func:`mode_set`; None where the mode cannot be followed
        through the perturbation or the first-order interval would reach below 0 Hz.
    notes : list of str
        Why each None.

    See Also
    --------
    mode_set : the modes whose frequencies it brackets.

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
    base = mode_set(asm) if modes is None else _validate.instance("modes", modes, ModeSet)
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
                         f"changes by 1 % (its shape's MAC {_validate.compared(mac, '<', FOLLOW_MAC, 2)}: it trades places with another mode)")
        elif raw[n][0] < 0:
            out[n] = None
            notes.append(f"{n}: no 95 % interval: the first-order interval would reach below 0 Hz "
                         f"({raw[n][0]:.3g} Hz; the tyre stiffness uncertainty moves this mode too far to be linear)")
        else:
            out[n] = raw[n]
    return out, notes


def follow_names(reference: ModeSet, other: ModeSet) -> tuple[dict, list]:
    """``other``'s modes under ``reference``'s names: ``{other's name: reference's name}`` for every
    mode followed (:meth:`ModeSet.follow`), and a note per reference mode that cannot be followed.

    See Also
    --------
    mac_matrix : the MAC it follows modes by.
    mode_set : the modes it names.

    Examples
    --------
    >>> from tyrelab.vehicle.model import Axle, Chassis, Parts, assemble
    >>> asm = assemble(Parts(Chassis(5120.0, 6210.0, 0.838), Axle("front", 1.54, 4.25e5, 1.5e3),
    ...                      Axle("rear", -0.896, 3.3e5, 1e3)))
    >>> stiffer = assemble(Parts(Chassis(5120.0, 6210.0, 0.838), Axle("front", 1.54, 5e5, 1.5e3),
    ...                          Axle("rear", -0.896, 3.3e5, 1e3)))
    >>> follow_names(mode_set(asm), mode_set(stiffer))
    ({'bounce': 'bounce', 'pitch': 'pitch'}, [])
    """
    _validate.instance("reference", reference, ModeSet)
    _validate.instance("other", other, ModeSet)
    mapping, notes = {}, []
    for name, (j, mac) in reference.follow(other).items():
        if j is None:
            notes.append(f"{name}: not followed from the first variant (best MAC {_validate.compared(mac, '<', FOLLOW_MAC, 2)}): no number")
        else:
            mapping[other.names[j]] = name
    return mapping, notes




#: The series dampers are released along ``1/c₂ = share / c₂`` with ``share`` from 0 (locked) through
#: :data:`FOLLOW_STEPS` steps, equal in ``log share`` from :data:`FOLLOW_FROM` to 1 (a Maxwell element
#: with a small damper goes through its change near ``share`` ~ its ``c``/``k``-time's, far below 1);
#: a step whose best match is below :data:`FOLLOW_SURE` is halved (in ``log share``), up to
#: :data:`FOLLOW_SPLITS` times.
FOLLOW_STEPS = 8
FOLLOW_FROM = 1e-4
FOLLOW_SURE = 0.9
FOLLOW_SPLITS = 6


def _complex_mac(m: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Mass-weighted MAC of the columns of ``a`` (rows) with those of ``b`` (columns), complex shapes."""
    cross = np.abs(a.conj().T @ m @ b) ** 2
    na = np.real(np.einsum("ij,ik,kj->j", a.conj(), m, a))
    nb = np.real(np.einsum("ij,ik,kj->j", b.conj(), m, b))
    den = np.outer(na, nb)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(den > 0, cross / np.where(den > 0, den, 1.0), 0.0)


def damped_modes(asm: Assembly, gravity_m_s2: float | None = None, reference: ModeSet | None = None,
                 steps: int = FOLLOW_STEPS) -> dict:
    """The damped modes of an assembled tractor from the complex roots of its linear model (issue 42).

    The roots are the eigenvalues of the model in contact (:meth:`~tyrelab.vehicle.model.Assembly.linear`:
    every element kind's own states, a rolling tyre's contact points among them); zero roots
    (:data:`ZERO_ROOT`: a series damper's drift) are left out. Names follow the shapes: with the
    rolling elements' series dampers locked (the model of :func:`mode_set`'s undamped modes,
    ``reference``, damped), each undamped mode takes the root whose shape over the coordinates (the
    velocity part of the eigenvector) it resembles most by the mass-weighted MAC, one to one
    (:func:`scipy.optimize.linear_sum_assignment`); then the series dampers are released to their
    values in ``steps`` equal steps of ``1/c₂`` (of speed; a Maxwell element's damper likewise) and each mode is followed from step to
    step by its shape (the reference model's own following, ``tests/vehicle/reference_lateral.py``).
    A mode that stops oscillating is a real root (``overdamped``); a mode whose shape no root
    resembles (MAC below :data:`FOLLOW_MAC`) is left out.

    Returns
    -------
    dict
        ``{name: DampedMode}`` in the reference's order.

    See Also
    --------
    mode_set : the undamped modes whose shapes name the damped ones.
    follow_damped : the same modes followed into a perturbed model.

    Examples
    --------
    A mass on a Kelvin-Voigt spring: ``ζ = c / (2 √(k m))``.

    >>> from tyrelab.vehicle.model import assemble
    >>> from tyrelab.vehicle.tractor import Tractor, tractor_parts
    >>> asm = assemble(tractor_parts(Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 2e3, 2e3)))
    >>> d = damped_modes(asm)
    >>> round(d["bounce"].damping_ratio, 4), round(4e3 / (2 * math.sqrt(2e5 * 1000)), 4)
    (0.1414, 0.1414)
    """
    _validate.instance("asm", asm, Assembly)
    steps = _validate.positive_int("steps", steps)
    ref = reference if reference is not None else mode_set(_released(asm, 0.0))
    _validate.instance("reference", ref, ModeSet)
    m = ref.mass
    roots, shapes = _roots(_released(asm, 0.0), gravity_m_s2, ref.coordinates)
    mac = _complex_mac(m, ref.shapes.astype(complex), shapes)
    rows, cols = optimize.linear_sum_assignment(-mac)
    current = {int(i): int(j) for i, j in zip(rows, cols) if mac[i, j] >= FOLLOW_MAC}
    quality = {i: float(mac[i, j]) for i, j in current.items()}
    state = {"current": current, "roots": roots, "shapes": shapes}
    if _released_by(asm):
        roots_at = _release_path(asm, gravity_m_s2, ref.coordinates)

        def advance(share: float) -> list:
            """The step to ``share``: the followed modes' MAC, the new state (not yet taken)."""
            new_roots, new_shapes = roots_at(share)
            order = sorted(state["current"])
            mac = _complex_mac(m, state["shapes"][:, [state["current"][i] for i in order]], new_shapes)
            rows, cols = optimize.linear_sum_assignment(-mac)
            return [(order[r], int(c), float(mac[r, c])) for r, c in zip(rows, cols)], new_roots, new_shapes

        def go(lo: float, hi: float, depth: int) -> None:
            pairs, new_roots, new_shapes = advance(hi)
            if depth < FOLLOW_SPLITS and pairs and min(q for _, _, q in pairs) < FOLLOW_SURE:
                mid = math.sqrt(lo * hi) if lo > 0 else hi * FOLLOW_FROM
                go(lo, mid, depth + 1)
                go(mid, hi, depth + 1)
                return
            nxt = {}
            for i, c, q in pairs:
                if q >= FOLLOW_MAC:
                    nxt[i] = c
                    quality[i] = min(quality[i], q)
            state.update(current=nxt, roots=new_roots, shapes=new_shapes)

        grid = np.concatenate([[0.0], np.geomspace(FOLLOW_FROM, 1.0, steps + 1)])
        for lo, hi in zip(grid[:-1], grid[1:]):
            go(float(lo), float(hi), 0)
        current, roots = state["current"], state["roots"]
    # the modes: every oscillating root (a complex pair, followed or not: a pair can form from a followed
    # mode's real roots and a contact point's as the dampers are released, issue 43) and the real roots
    # the following reached. Each named by its own shape (the rules of mode_set), the oscillating ones
    # first: a mode followed through a veering takes the name of what it has become, and a real root
    # (reported overdamped) takes a name only where no oscillating mode has it (else ``_2``)
    final = state["shapes"]
    quality_of = {j: quality[i] for i, j in current.items()}
    oscillating = [j for j in range(len(roots)) if abs(roots[j].imag) > 1e-9 * abs(roots[j])]
    chosen = sorted(set(oscillating), key=lambda j: abs(roots[j]))
    real = sorted((j for j in current.values() if j not in oscillating), key=lambda j: abs(roots[j]))
    ref_shapes = ref.shapes.astype(complex)
    for j in chosen:
        if j not in quality_of:  # not followed: its match to the undamped mode it resembles most
            quality_of[j] = float(np.max(_complex_mac(m, ref_shapes, final[:, [j]]))) if ref_shapes.size else 0.0

    def shares_of(js):
        return [np.real(final[:, j].conj() * (m @ final[:, j])) for j in js]

    named = list(zip(_shape_names(shares_of(chosen), ref.coordinates, one_to_one=True), chosen))
    taken = {n for n, _ in named}
    for j in real:
        base = name = _shape_names(shares_of([j]), ref.coordinates)[0]
        k = 1
        while name in taken:
            k += 1
            name = f"{base}_{k}"
        taken.add(name)
        named.append((name, j))
    out = {}
    for name, j in sorted(named, key=lambda t: abs(roots[t[1]])):
        lam = complex(roots[j])
        size = abs(lam)
        overdamped = abs(lam.imag) <= 1e-9 * size
        out[name] = DampedMode(name, lam, size / (2 * math.pi), 0.0 if overdamped else lam.imag / (2 * math.pi),
                               1.0 if overdamped else -lam.real / size, bool(overdamped), quality_of[j],
                               final[:, j], tuple(ref.coordinates), m)
    return out


def follow_damped(reference: dict, other: dict, threshold: float = FOLLOW_MAC) -> dict:
    """``{reference name: other's DampedMode, or None}``: each damped mode of ``reference``
    (:func:`damped_modes`) paired one to one with the mode of ``other`` whose shape it resembles most
    (mass-weighted MAC of the complex shapes over the coordinates they share, the reference's mass);
    None below ``threshold`` (the mode cannot be followed). Names then stay the reference's across a
    scenario's intervals, speeds and a sweep.

    See Also
    --------
    damped_modes : the damped modes it follows.
    follow_names : the undamped modes' following.

    Examples
    --------
    >>> from tyrelab.vehicle.model import assemble
    >>> from tyrelab.vehicle.tractor import Tractor, tractor_parts
    >>> d = damped_modes(assemble(tractor_parts(Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 2e3, 2e3))))
    >>> {k: v.name for k, v in follow_damped(d, d).items()}
    {'bounce': 'bounce', 'pitch': 'pitch'}
    """
    if not isinstance(reference, dict) or not isinstance(other, dict):
        raise ValueError("reference, other: dicts of DampedMode (damped_modes)")
    out = dict.fromkeys(reference)
    if not reference or not other:
        return out
    first = next(iter(reference.values()))
    names_o = list(other)
    o0 = other[names_o[0]]
    common = [c for c in first.coordinates if c in o0.coordinates]
    ia = [first.coordinates.index(c) for c in common]
    ib = [o0.coordinates.index(c) for c in common]
    m = first.mass[np.ix_(ia, ia)]
    a = np.stack([d.shape[ia] for d in reference.values()], axis=1)
    b = np.stack([other[n].shape[ib] for n in names_o], axis=1)
    mac = _complex_mac(m, a, b)
    rows, cols = optimize.linear_sum_assignment(-mac)
    names_r = list(reference)
    for i, j in zip(rows, cols):
        if mac[i, j] >= threshold:
            out[names_r[i]] = other[names_o[j]]
    return out


def follow_renamed(reference: dict, other: dict, threshold: float = FOLLOW_MAC) -> tuple[dict, dict]:
    """``other``'s damped modes under ``reference``'s names (issue 42): each mode of ``other`` that one of
    ``reference`` follows by shape (:func:`follow_damped`) takes that mode's name; the others keep their
    own name (``_2``, ``_3``, ... where the reference's names took it), so no root is dropped. How a
    sweep's variants' modes are named from its first variant's at the same speed: a mode keeps its
    name across the sweep's pressures as its character changes (a ``lateral_roll`` that turns into
    mostly ``lateral`` motion stays ``lateral_roll``).

    Returns
    -------
    modes : dict
        ``{name: DampedMode}`` (its ``name`` the new one), in ascending undamped frequency.
    renamed : dict
        ``{other's name: its name here}`` for every mode of ``other``.

    See Also
    --------
    follow_damped : the pairing by shape.

    Examples
    --------
    >>> from tyrelab.vehicle.model import assemble
    >>> from tyrelab.vehicle.tractor import Tractor, tractor_parts
    >>> d = damped_modes(assemble(tractor_parts(Tractor(1000, 250, 1.0, 1.0, 0.5, 1e5, 1e5, 2e3, 2e3))))
    >>> swapped = {"pitch": dataclasses.replace(d["bounce"], name="pitch"),
    ...            "bounce": dataclasses.replace(d["pitch"], name="bounce")}
    >>> modes, renamed = follow_renamed(d, swapped)
    >>> renamed, [round(m.undamped_Hz, 3) for m in modes.values()]
    ({'pitch': 'bounce', 'bounce': 'pitch'}, [2.251, 4.502])
    """
    if not isinstance(reference, dict) or not isinstance(other, dict):
        raise ValueError("reference, other: dicts of DampedMode (damped_modes)")
    ref = {n: d for n, d in reference.items() if d is not None}
    own = {n: d for n, d in other.items() if d is not None}
    followed = follow_damped(ref, own, threshold) if ref and own else {}
    renamed = {}
    for name, d in followed.items():
        if d is not None:
            renamed[next(n for n, o in own.items() if o is d)] = name
    taken = set(renamed.values())
    for n in own:
        if n in renamed:
            continue
        new, k = n, 1
        while new in taken:
            k += 1
            new = f"{n}_{k}"
        renamed[n] = new
        taken.add(new)
    modes = {renamed[n]: dataclasses.replace(d, name=renamed[n]) for n, d in own.items()}
    return dict(sorted(modes.items(), key=lambda kv: kv[1].undamped_Hz)), renamed
