"""Exact (first-order-hold) solution of linear time-invariant systems, restartable.

``x' = A x + B w``, ``y = C x + D w`` with inputs ``w`` linear between samples ``dt``
apart (first-order hold, :func:`scipy.signal.cont2discrete` with ``method="foh"``). The
discrete system is diagonalised once (:func:`discretise`) and each mode run with
:func:`scipy.signal.lfilter` (:meth:`FohSystem.run`), from rest or from any state, so a caller can solve a record in
segments (the tractor's switch between this exact path and RK4 across tyre lift-off,
:func:`tyrelab.vehicle.tractor.simulate_tractor`). SI units are the caller's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import signal

__all__ = ["FohSystem", "discretise"]


@dataclass(frozen=True)
class FohSystem:
    """A continuous LTI system discretised exactly for piecewise-linear inputs, in modal form.

    Attributes
    ----------
    mu : ndarray, shape (n,)
        Eigenvalues of the discrete state matrix ``A_d``.
    vecs, inv : ndarray, shape (n, n)
        Its eigenvectors and their inverse.
    g_in : ndarray, shape (n, m)
        Modal input matrix ``V^-1 B_d`` of the first-order-hold state ``xi_k = x_k - Γ2 w_k``.
    gamma2 : ndarray, shape (n, m)
        ``Γ2`` of the first-order hold.
    cv : ndarray, shape (p, n)
        ``C V``.
    dd : ndarray, shape (p, m)
        ``D + C Γ2``.
    dt_s : float
        Sample step, s.
    """

    mu: np.ndarray
    vecs: np.ndarray
    inv: np.ndarray
    g_in: np.ndarray
    gamma2: np.ndarray
    cv: np.ndarray
    dd: np.ndarray
    dt_s: float

    @property
    def n_states(self) -> int:
        """Number of states."""
        return int(self.mu.size)

    def run(self, w, x0=None, keep_modes: bool = False):
        """Outputs at the samples of ``w`` (shape ``(m, N)``), from state ``x0`` (default rest).

        With ``keep_modes`` also the modal trajectories, from which :meth:`state_at` gives
        the state at any sample without computing every state at every sample.

        Examples
        --------
        Unit step into ``x' = -x``, ``y = x``, restarted half-way from the state reached:

        >>> s = discretise([[-1.0]], [[1.0]], [[1.0]], [[0.0]], 1e-3)
        >>> first = s.run(np.ones((1, 501)))
        >>> second = s.run(np.ones((1, 501)), x0=first[:, -1])
        >>> round(float(second[0, -1]), 6), round(1 - float(np.exp(-1)), 6)
        (0.632121, 0.632121)
        """
        kept = self.modes(w, x0)
        y = self.outputs(kept, range(self.cv.shape[0]))
        return (y, kept) if keep_modes else y

    def modes(self, w, x0=None):
        """The modal trajectories of :meth:`run` (its second return value with ``keep_modes``), from
        which :meth:`outputs` gives any outputs at any samples and :meth:`state_at` the state.

        Examples
        --------
        >>> s = discretise([[-1.0]], [[1.0]], [[1.0]], [[0.0]], 1e-3)
        >>> kept = s.modes(np.ones((1, 1001)))
        >>> bool(np.array_equal(s.outputs(kept, [0], step=10), s.run(np.ones((1, 1001)))[:, ::10]))
        True
        """
        w = np.atleast_2d(np.asarray(w, float))
        if w.shape[0] != self.g_in.shape[1]:
            raise ValueError(f"w: expected {self.g_in.shape[1]} input rows, got {w.shape[0]}")
        if x0 is None:
            q0 = self.inv @ (-self.gamma2 @ w[:, 0])
        else:
            x0 = np.asarray(x0, float)
            if x0.shape != (self.n_states,):
                raise ValueError(f"x0: expected shape ({self.n_states},), got {x0.shape}")
            q0 = self.inv @ (x0 - self.gamma2 @ w[:, 0])
        # the modal inputs g_k = (V^-1 B_d) w_k of every mode at once, real and imaginary parts in
        # real arithmetic; a real mode (real eigenvalue and input row) runs a real filter; a
        # conjugate pair is run once and counted twice
        keep = [i for i in range(self.n_states) if self.mu[i].imag >= 0]
        wk = w[:, :-1]
        g_re = self.g_in[keep].real @ wk
        g_im = self.g_in[keep].imag @ wk
        real = [self.mu[i].imag == 0 and q0[i].imag == 0 and not self.g_in[i].imag.any() for i in keep]
        # the trajectories as real rows (Re q of every mode, then Im q of the complex ones): an
        # output is one real matrix-vector product over them
        cplx = [j for j, r in enumerate(real) if not r]
        q = np.empty((len(keep) + len(cplx), w.shape[1]))
        for j, i in enumerate(keep):  # modal recursion q_{k+1} = mu q_k + g_k
            mu = self.mu[i]
            if real[j]:
                q[j, 0] = q0[i].real
                q[j, 1:] = signal.lfilter([1.0], [1.0, -mu.real], g_re[j], zi=[mu.real * q0[i].real])[0]
            else:
                g = np.empty(g_re.shape[1], dtype=complex)
                g.real, g.imag = g_re[j], g_im[j]
                qc = signal.lfilter([1.0], [1.0, -mu], g, zi=[mu * q0[i]])[0]
                r = len(keep) + cplx.index(j)
                q[j, 0], q[r, 0] = q0[i].real, q0[i].imag
                q[j, 1:], q[r, 1:] = qc.real, qc.imag
        factor = np.array([2.0 if self.mu[i].imag > 0 else 1.0 for i in keep])
        return _Kept(keep, cplx, factor, q, w, self.dd @ w)

    def outputs(self, kept, rows, stop: int | None = None, step: int = 1, start: int = 0) -> np.ndarray:
        """Outputs ``rows`` at samples ``start:stop:step`` of the :meth:`modes` ``kept``, those of
        :meth:`run` (the same operations on fewer elements): a caller that needs some outputs
        everywhere and others only on part of the record computes no more."""
        rows = list(rows)
        at = slice(start, stop, step)
        y = kept.direct[rows, at]
        if not kept.keep:
            return y
        # y += sum over modes of factor (Re c Re q - Im c Im q): per output row one real
        # matrix-vector product over the rows of Re q and Im q
        cv = self.cv[np.ix_(rows, kept.keep)] * kept.factor
        coef = np.hstack([cv.real, -cv[:, kept.cplx].imag])
        q = kept.q[:, at]
        for r in range(len(rows)):  # row by row: a row's numbers do not depend on the other rows asked for
            y[r] += coef[r] @ q
        return y

    def state_at(self, kept, k: int) -> np.ndarray:
        """State ``x_k = V q_k + Γ2 w_k`` at sample ``k`` of a :meth:`run` with ``keep_modes``
        (``kept`` its second return value).

        Examples
        --------
        >>> s = discretise([[-1.0]], [[1.0]], [[1.0]], [[0.0]], 1e-3)
        >>> y, kept = s.run(np.ones((1, 1001)), keep_modes=True)
        >>> bool(abs(s.state_at(kept, 1000)[0] - y[0, 1000]) < 1e-15)
        True
        """
        x = self.gamma2 @ kept.w[:, k]
        n_keep = len(kept.keep)
        for j, i in enumerate(kept.keep):
            im = kept.q[n_keep + kept.cplx.index(j), k] if j in kept.cplx else 0.0
            x = x + kept.factor[j] * (self.vecs[:, i].real * kept.q[j, k] - self.vecs[:, i].imag * im)
        return x


@dataclass(frozen=True)
class _Kept:
    """Modal trajectories of one :meth:`FohSystem.modes` call: the kept modes (a conjugate pair
    once, ``factor`` 2) and which of them are complex (``cplx``, positions in ``keep``), their
    trajectories ``q`` (rows: Re q of each kept mode, then Im q of each complex one; columns: the
    samples), the inputs and ``D_d w``."""

    keep: list
    cplx: list
    factor: np.ndarray
    q: np.ndarray
    w: np.ndarray
    direct: np.ndarray


def discretise(a, b, c, d, dt_s: float) -> FohSystem:
    """First-order-hold discretisation of ``(A, B, C, D)`` at step ``dt_s``, in modal form.

    ``xi_{k+1} = A_d xi_k + B_d w_k``, ``y_k = C xi_k + (D + C Γ2) w_k`` with
    ``xi_k = x_k - Γ2 w_k`` (:func:`scipy.signal.cont2discrete`, ``method="foh"``).
    ``A_d`` must be diagonalisable (distinct eigenvalues; true of damped vehicle models).

    Parameters
    ----------
    a, b, c, d : array_like
        Continuous state space (n×n, n×m, p×n, p×m).
    dt_s : float
        Step, s (> 0).

    Returns
    -------
    FohSystem

    See Also
    --------
    tyrelab.vehicle.run.pitch_plane.state_space : a model it runs (the pitch-plane tractor).

    Examples
    --------
    >>> s = discretise([[-1.0]], [[1.0]], [[1.0]], [[0.0]], 1e-3)
    >>> round(float(s.mu[0].real), 9) == round(float(np.exp(-1e-3)), 9)
    True
    """
    if not dt_s > 0:
        raise ValueError(f"dt_s must be positive, got {dt_s}")
    a, b, c, d = (np.atleast_2d(np.asarray(v, float)) for v in (a, b, c, d))
    n, m = b.shape
    # with C = I and D = 0 the discrete D is Γ2 itself (scipy: D_d = D + C Γ2)
    ad, bd, _, gamma2, _ = signal.cont2discrete((a, b, np.eye(n), np.zeros((n, m))), dt_s, method="foh")
    mu, vecs = np.linalg.eig(ad)
    inv = np.linalg.inv(vecs)
    return FohSystem(mu=mu, vecs=vecs, inv=inv, g_in=inv @ bd, gamma2=gamma2, cv=c @ vecs, dd=d + c @ gamma2,
                     dt_s=float(dt_s))
