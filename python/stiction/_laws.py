"""The laws on numpy arrays: SI adhesion laws of a sphere, the elasto-plastic asperity, the
rough surface's pressure, and the tabulated contact law for FE codes.

Every method takes arrays of any shape (or scalars, or lists) and returns arrays of the
same shape (a float for a scalar); the GIL is released while the library computes, and
points are evaluated in parallel where each is expensive (asperity forces, surface
pressures).
"""

from __future__ import annotations

import os
from typing import Any, NamedTuple, Optional, Union

import numpy as np

from . import _stiction as _native
from ._results import LawEvaluation, PlasticState, PullOut

ArrayLike = Union[float, "np.ndarray", list]
Path = str  #: "approach" | "retract"

__all__ = ["AdhesionLaw", "Asperity", "Surface", "ContactLaw", "Jumps", "PullOff", "PressureEstimate"]


class Jumps(NamedTuple):
    """Interferences (m) at which contact jumps: in on approach, out on retraction."""

    jump_in: float
    jump_out: float


class PullOff(NamedTuple):
    """An asperity's pull-off: the most tensile force on unloading."""

    force: Any  #: N (negative when adhesive)
    delta: Any  #: interference where it occurs (m)


class PressureEstimate(NamedTuple):
    """A surface pressure with the quadrature's estimate of its error."""

    pressure: Any  #: Pa
    error: Any  #: Pa


class AdhesionLaw:
    """An adhesion law of one elastic sphere against a flat, SI units: force F (N,
    compressive positive) at interference delta (m) for a sphere of radius R (m).

    K = 4/3 E* is Maugis' elastic constant (Pa), with 1/E* = (1 - nu1^2)/E1 +
    (1 - nu2^2)/E2; w the work of adhesion (J/m^2); z0 the Dugdale range (m), so that the
    Dugdale stress is sigma0 = w/z0. Maugis' transition parameter is
    lambda = 2 sigma0 (R / (pi w K^2))^(1/3) (paper eq 6).

    Make one with :meth:`maugis_kim`, :meth:`jkr`, :meth:`dmt`, :meth:`hertz`, or
    :meth:`of_scene` (the law a scene names).
    """

    __slots__ = ("_law",)

    def __init__(self, native: Any) -> None:
        self._law = native

    @classmethod
    def maugis_kim(cls, k: float, work_of_adhesion: float, z0: float) -> "AdhesionLaw":
        """Maugis-Dugdale with the Kim extension (paper eqs 6-11): every branch, the
        jump-in on approach and the jump-out on retraction."""
        return cls(_native.AdhesionLaw.maugis_kim(k, work_of_adhesion, z0))

    @classmethod
    def jkr(cls, k: float, work_of_adhesion: float) -> "AdhesionLaw":
        """JKR, the lambda -> infinity limit: in the units of eq 7 (A = a / (pi w R^2 /
        K)^(1/3)) Fbar = A^3 - sqrt(6) A^(3/2), Delta = A^2 - (2/3) sqrt(6 A), stable for
        A >= 6^(-1/3); pull-off -3/2 pi w R under load control, -5/6 pi w R at the
        jump-out (displacement control); jump-in at delta = 0."""
        return cls(_native.AdhesionLaw.jkr(k, work_of_adhesion))

    @classmethod
    def dmt(cls, k: float, work_of_adhesion: float, z0: float) -> "AdhesionLaw":
        """DMT with a Dugdale interaction of range z0, the lambda -> 0 limit: in contact
        F = K sqrt(R) delta^(3/2) - 2 pi w R; out of contact F = -2 pi w R (1 + delta/z0)
        for -z0 < delta < 0 and 0 below; no hysteresis; pull-off -2 pi w R."""
        return cls(_native.AdhesionLaw.dmt(k, work_of_adhesion, z0))

    @classmethod
    def hertz(cls, k: float) -> "AdhesionLaw":
        """Hertz: F = K sqrt(R) delta^(3/2) for delta > 0, zero otherwise."""
        return cls(_native.AdhesionLaw.hertz(k))

    @classmethod
    def of_scene(cls, scene: Any) -> "AdhesionLaw":
        """The adhesion law a scene names (``contact.adhesion_law``), with the pair's K and
        the scene's w and z0."""
        return cls(_native.AdhesionLaw.of_scene(scene))

    @property
    def name(self) -> str:
        """The law's registered name."""
        return self._law.name

    def force(self, delta: ArrayLike, radius: ArrayLike, path: Path = "approach", from_: Optional[float] = None) -> Any:
        """Force F (N) at each interference of `delta` (m) for a sphere of `radius` (m;
        one value or one per point) on `path`: "approach" (coming from far), or "retract"
        after the largest interference `from_` (m)."""
        return self._law.force(delta, radius, path, from_)

    def jumps(self, radius: float) -> Jumps:
        """(jump_in, jump_out) interferences (m) for a sphere of `radius` (m)."""
        return Jumps(*self._law.jumps(radius))

    def __repr__(self) -> str:
        return repr(self._law)


class Asperity:
    """One elasto-plastic adhesive asperity of a scene's contact section (paper Fig 2):
    yield onset delta_CP (eq 1), loading force (eqs 2-3), residual height and radius after
    unloading (eqs 4-5), effective radius on unloading R_eff (eqs 12-13) seen by the
    adhesion law. SI: interference delta (m), force (N, compressive positive).

    ``elastic=True``: the same asperity with a plasticity law that never yields.
    """

    __slots__ = ("_a",)

    def __init__(self, scene: Any, elastic: bool = False) -> None:
        self._a = _native.Asperity(scene, elastic)

    @property
    def delta_cp(self) -> float:
        """Yield onset delta_CP (m), eq 1 (inf if it never yields)."""
        return self._a.delta_cp

    @property
    def radius(self) -> float:
        """Initial tip radius R (m)."""
        return self._a.radius

    def force(
        self,
        delta: ArrayLike,
        delta_max: Optional[ArrayLike] = None,
        path: Path = "approach",
        from_: Optional[float] = None,
    ) -> Any:
        """Force F (N) at each interference of `delta` (m), the asperity having been
        loaded to `delta_max` (m; one value or one per point; None: virgin), on `path`:
        "approach" (loading or reloading) or "retract" from `from_` (m; default
        delta_max)."""
        return self._a.force(delta, delta_max, path, from_)

    def pull_off(self, delta_max: ArrayLike) -> PullOff:
        """The pull-off after loading to each `delta_max` (m): (force N, interference m)."""
        return PullOff(*self._a.pull_off(delta_max))

    def state(self, delta_max: ArrayLike) -> PlasticState:
        """The plastic state after loading to each `delta_max` (m): delta_res (eq 4),
        r_res (eq 5), extrapolated."""
        return PlasticState(self._a.state(delta_max))

    def jumps(self, delta_max: Optional[float] = None) -> Jumps:
        """(jump_in, jump_out) interferences (m) after loading to `delta_max`."""
        return Jumps(*self._a.jumps(delta_max))

    def __repr__(self) -> str:
        return repr(self._a)


class Surface:
    """The Greenwood-Williamson rough surface of a surface or switch scene against a rigid
    flat (paper eqs 14-16), as ``stiction surface`` builds it:

        p(d) = N int_d^inf F(h - d; h - d_min, path) phi(h) dh

    with N the asperity density (1/m^2), phi the Gaussian density of asperity heights of
    RMS sigma_s, F the asperity force. d (m) is the separation of the flat from the mean
    plane of the heights; the history is d_min (m), the deepest separation reached (inf:
    a virgin surface). Pressures in Pa, compressive positive; each point is an adaptive,
    error-controlled quadrature (``accuracy``), points in parallel.
    """

    __slots__ = ("_s",)

    def __init__(self, scene: Any, accuracy: Optional[str] = None, elastic: bool = False) -> None:
        self._s = _native.Surface(scene, accuracy, elastic)

    @property
    def sigma_s(self) -> float:
        """RMS of the asperity heights sigma_s (m)."""
        return self._s.sigma_s

    @property
    def accuracy(self) -> str:
        """The accuracy mode of the quadrature."""
        return self._s.accuracy

    def pressure(
        self,
        d: ArrayLike,
        d_min: Optional[ArrayLike] = None,
        path: Path = "approach",
        from_: Optional[float] = None,
    ) -> Any:
        """Nominal pressure p (Pa) at each separation of `d` (m) with history `d_min` (m;
        one value or one per point; None: virgin) on `path`: "approach" (first loading, or
        reloading after d_min) or "retract" (from `from_`, m; default d_min)."""
        return self._s.pressure(d, d_min, path, from_)

    def pressure_estimate(
        self,
        d: ArrayLike,
        d_min: Optional[ArrayLike] = None,
        path: Path = "approach",
        from_: Optional[float] = None,
    ) -> PressureEstimate:
        """(pressure, error estimate), Pa, as :meth:`pressure` computes them."""
        return PressureEstimate(*self._s.pressure_estimate(d, d_min, path, from_))

    def reach(self, d_min: Optional[float] = None, path: Path = "approach", from_: Optional[float] = None) -> float:
        """The separation (m) beyond which the pressure is zero on `path` with history
        `d_min`."""
        return self._s.reach(d_min, path, from_)

    def pull_out(self, d_min: float) -> PullOut:
        """The pull-out after the surface was pressed to `d_min` (m) and retracts."""
        return PullOut(self._s.pull_out(d_min))

    def __repr__(self) -> str:
        return repr(self._s)


class ContactLaw:
    """A tabulated contact law p(d; d_min, path) of a rough surface for FE codes (a
    law.json of ``stiction law``): pressure p (Pa, compressive positive) at separation d
    (m) with history d_min (m, the deepest separation reached) on the approach or retract
    branch, with its tangent dp/dd (Pa/m). Monotone (Steffen) interpolation in d on each
    tabulated history, blended between histories; the virgin envelope where the history
    deepens.

    ``ContactLaw.load(path)`` reads a file; ``evaluate`` is vectorised.
    """

    __slots__ = ("_law",)

    def __init__(self, native: Any) -> None:
        self._law = native

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "ContactLaw":
        """Reads a law file (law.json)."""
        return cls(_native.ContactLaw.load(os.fspath(path)))

    @classmethod
    def from_json(cls, text: str) -> "ContactLaw":
        """A law from the text of a law.json."""
        return cls(_native.ContactLaw.from_json(text))

    def evaluate(self, d: ArrayLike, d_min: Optional[ArrayLike] = None, path: Any = "approach") -> LawEvaluation:
        """Stateless evaluation at each separation of `d` (m) with history `d_min` (m; one
        value or one per point; None or inf: virgin) on `path` ("approach" | "retract", one
        word or one per point), as ``stiction law eval --d D --d-min DMIN --path PATH``:
        where d < d_min the history deepens (the virgin envelope's value; d_min becomes d,
        the path approach)."""
        p, t, m, r = self._law.evaluate(d, d_min, path)
        return LawEvaluation._of({"pressure": p, "tangent": t, "d_min": m, "retract": r})

    def follow(self, d: ArrayLike, state: Optional[dict] = None) -> tuple:
        """Follows separations `d` (m) in order as an FE code would, the history updated
        by each (from a virgin surface, or `state` as returned). Returns (LawEvaluation,
        final state dict)."""
        p, t, m, r, st = self._law.follow(d, state)
        return LawEvaluation._of({"pressure": p, "tangent": t, "d_min": m, "retract": r}), st

    def virgin_pressure(self, d: ArrayLike) -> tuple:
        """The virgin envelope p_V(d) (Pa) and its slope (Pa/m) at each separation (m)."""
        return self._law.virgin_pressure(d)

    def reach(self, d_min: float, path: Path = "approach") -> float:
        """The separation (m) beyond which the branch `path` of history `d_min` is zero."""
        return self._law.reach(d_min, path)

    @property
    def d_min_range(self) -> tuple:
        """(deepest, shallowest) tabulated history (m)."""
        return self._law.d_min_range

    @property
    def d_min_grid(self) -> np.ndarray:
        """The tabulated histories (m), increasing."""
        return self._law.d_min_grid

    @property
    def length_scale(self) -> Optional[float]:
        """The surface's sigma_s (m), if recorded."""
        return self._law.length_scale

    @property
    def scene(self) -> dict:
        """The scene the law was tabulated from."""
        return self._law.scene

    @property
    def measured_error(self) -> Optional[dict]:
        """The interpolation error measured against the surface, if recorded."""
        return self._law.measured_error

    def to_json(self) -> str:
        """law.json as text."""
        return self._law.to_json()

    def to_csv(self) -> str:
        """law.csv as text."""
        return self._law.to_csv()

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes law.json to `path`."""
        self._law.save(os.fspath(path))

    def __reduce__(self) -> tuple:
        return (ContactLaw.from_json, (self.to_json(),))

    def __repr__(self) -> str:
        return repr(self._law)
