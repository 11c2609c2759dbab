"""stiction: adhesive contact of elasto-plastic rough surfaces and in-use stiction of MEMS
micro-switches, from Python.

The model library of the ``stiction`` command line (a reference implementation of the
multiscale model of Wu, Rochus, Noels and Golinval) as a Python package: the same scenes,
the same validation and messages, the same numbers.

    >>> import stiction
    >>> scene = stiction.load_scene({"kind": "switch", ...})   # or a TOML/JSON path
    >>> r = stiction.run(stiction.Scene.paper("switch"), accuracy="fast")
    >>> r.cycles[0].pull_out_pressure, r.stiction                  # Pa, bool

Units are SI everywhere (m, N, Pa, J/m^2, V), except :func:`maugis_kim_force` and
:func:`md_curve`, in the nondimensional units of ``stiction md``. Bad input raises
:class:`InputError`, a numerical failure :class:`NumericalError` (both
:class:`StictionError`), with the library's message. Every computation releases the GIL.

A tutorial: docs/python.md.
"""

from __future__ import annotations

import os
from typing import Any, Callable, List, Mapping, Optional, Sequence, Union

import numpy as np

from . import _stiction
from ._errors import InputError, NumericalError, StictionError
from ._laws import (
    AdhesionLaw,
    Asperity,
    ContactLaw,
    Jumps,
    PressureEstimate,
    PullOff,
    Surface,
)
from ._results import (
    AsperityResult,
    CalibrationResult,
    ContactState,
    Cycle,
    CycleTable,
    DesignMap,
    LawEvaluation,
    LawResult,
    MapPoint,
    MdResult,
    ModelFormReport,
    ModelWarning,
    ProbabilityResult,
    ProbabilitySample,
    Record,
    SurfaceResult,
    SwitchResult,
    Table,
    ThresholdResult,
    TopographyResult,
)
from ._stiction import Scene


# the largest integer the library takes: a count (usize, i64) or a seed (u64) beyond it
# would overflow on the way in (an OverflowError) instead of being refused by name
_I64_MAX = 2**63 - 1
_U64_MAX = 2**64 - 1


def _count(name: str, value: Any, least: int, most: int = _I64_MAX) -> int:
    """An integer argument (not a bool, not a float) in [`least`, `most`], or InputError."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not least <= value <= most:
        shown = repr(value)
        if len(shown) > 40:  # 10**400: its length, not its 401 digits
            if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
                shown = f"an integer of {int(value).bit_length()} bits"
            else:
                shown = shown[:40] + "..."
        raise InputError(f"invalid {name} = {shown}: must be an integer in [{least}, {most}]")
    return int(value)


def _client(client: Any) -> Any:
    """A `client` argument: None, a dask.distributed.Client or a concurrent.futures.Executor
    (anything with a callable ``submit``), or InputError naming it."""
    if client is not None and not callable(getattr(client, "submit", None)):
        raise InputError(
            f"invalid client = {type(client).__name__}: must be a dask.distributed.Client, a "
            "concurrent.futures.Executor (an object with submit) or None"
        )
    return client


_Progress = Optional[Callable[[int, int], None]]


def _progress(value: Any) -> _Progress:
    """A `progress` argument: None or a callable, or InputError naming it."""
    if value is not None and not callable(value):
        raise InputError(
            f"invalid progress = {type(value).__name__}: must be a callable(done, total) or None"
        )
    return value


_PROGRESS_DOC = """`progress`, a callable ``progress(done, total)`` (two ints), is called as the work
    advances, at most ten times a second, and once more with ``done == total`` when the call
    succeeds; ``done`` never decreases and never exceeds ``total`` (which grows when a
    further stage starts, such as the model-form combinations of ``model_form =
    "check"``). An exception it raises stops the computation and propagates to the caller.
    Ctrl-C (SIGINT) stops the computation within a fraction of a second and raises
    ``KeyboardInterrupt``, with or without `progress`; no partial result is returned."""


def _word(name: str, value: Any) -> Optional[str]:
    """A word argument (or None), or InputError naming it."""
    if value is not None and not isinstance(value, str):
        raise InputError(f"invalid {name} = {value!r}: must be a word (a str) or None")
    return value

__version__: str = _stiction.__version__

__all__ = [
    "Scene",
    "load_scene",
    "scene_keys",
    "variable_fields",
    "run",
    "maugis_kim_force",
    "md_curve",
    "AdhesionLaw",
    "Asperity",
    "Surface",
    "ContactLaw",
    "tabulate_law",
    "design_threshold",
    "design_map",
    "design_merge",
    "read_map",
    "design_probability",
    "read_probability",
    "calibrate",
    "StictionError",
    "InputError",
    "NumericalError",
    "Record",
    "Table",
    "CycleTable",
    "SwitchResult",
    "ModelFormReport",
    "topography",
    "TopographyResult",
    "ContactState",
    "Cycle",
    "SurfaceResult",
    "AsperityResult",
    "MdResult",
    "ThresholdResult",
    "DesignMap",
    "MapPoint",
    "ProbabilityResult",
    "ProbabilitySample",
    "LawResult",
    "LawEvaluation",
    "CalibrationResult",
    "ModelWarning",
    "Jumps",
    "PullOff",
    "PressureEstimate",
]

PathLike = Union[str, "os.PathLike[str]"]
SceneLike = Union[Scene, PathLike, Mapping[str, Any]]


def load_scene(path_or_dict: SceneLike) -> Scene:
    """A scene from a TOML or JSON file (JSON when the name ends in ``.json`` or the text
    starts with ``{``), a dict of the same keys and sections (``{"kind": "switch",
    "contact": {...}, "surface": {...}, "switch": {...}}``; an infinite yield stress as
    ``float("inf")`` or ``"inf"``), or a :class:`Scene`.

    Every key is validated by the library, with its key and law registries: an unknown,
    missing or out-of-domain key raises :class:`InputError` whose message names the file
    (``<dict>`` for a dict), the key, the value and what is allowed (``err.key`` is the
    key)."""
    return _stiction.load_scene(path_or_dict)


def scene_keys(kind: Optional[str] = None) -> List[dict]:
    """Every scene key (of `kind`: "asperity" | "surface" | "switch", or all) with its
    unit, what it accepts, its default and its meaning: the library's key registry."""
    return _stiction.scene_keys(kind)


def variable_fields() -> List[str]:
    """The scene fields a design map or threshold may vary (``section.key``)."""
    return _stiction.variable_fields()


_RESULTS = {"switch": SwitchResult, "surface": SurfaceResult, "asperity": AsperityResult}


def run(
    scene: SceneLike,
    accuracy: Optional[str] = None,
    progress: _Progress = None,
) -> Union[SwitchResult, SurfaceResult, AsperityResult]:
    """Runs a scene of any kind and returns the result of its kind, the same as the
    command of that kind (``stiction switch | surface | asperity --scene FILE``):

    * a switch scene: :class:`SwitchResult` (``.cycles[i].d_e`` in m,
      ``.cycles[i].pull_out_pressure`` in Pa, ``.cycles[i].sticks``, ``.stiction``);
    * a surface scene: :class:`SurfaceResult`;
    * an asperity scene: :class:`AsperityResult`.

    `accuracy` ("accurate" | "balanced" | "fast" | "reference") replaces the scene's, as
    ``--accuracy`` does. `progress(done, total)` counts the cycles of a switch scene (an
    asperity or surface run is one step); see "Progress and Ctrl-C" in docs/python.md."""
    kind, data = _stiction.run(scene, _word("accuracy", accuracy), progress=_progress(progress))
    return _RESULTS[kind](data)


def maugis_kim_force(
    lam: float,
    delta: Any,
    path: str = "approach",
    from_: Optional[float] = None,
    *,
    delta_max: Optional[float] = None,
) -> Any:
    """The Maugis-Kim force Fbar = F / (pi w R) at each interference Delta = delta /
    (pi^2 w^2 R / K^2)^(1/3) of `delta` (any shape; a float for a scalar), for the
    transition parameter ``lam`` = lambda in [1e-6, 1e6] (paper eqs 7-11 with the Kim
    extension; the units of ``stiction md --lambda LAM --delta D``).

    `path`: "approach" (coming from far: zero until the jump-in Delta_in = -2/(pi lambda))
    or "retract" after the largest interference `from_` (``--from``; `delta_max` is
    another name for it), on the stable branch down to the jump-out. Limits: the pull-off
    under load control is -2 (DMT, lambda -> 0) and -3/2 (JKR, lambda -> inf)."""
    if delta_max is not None:
        if from_ is not None and from_ != delta_max:
            raise InputError(f"from_ = {from_!r} and delta_max = {delta_max!r}: give one (they name the same value)")
        from_ = delta_max
    return _stiction.maugis_kim_force(lam, delta, path, from_)


def md_curve(lam: float, points: int = 200, delta_end: float = 5.0) -> MdResult:
    """The whole nondimensional Maugis-Kim curve of lambda = `lam` with `points` points up
    to Delta = `delta_end`, and its landmarks (jump-in, turning point, both pull-offs),
    as ``stiction md --lambda LAM``."""
    return MdResult(_stiction.md_curve(lam, _count("points", points, 0), delta_end))


def design_threshold(
    scene: SceneLike,
    vary: str,
    from_: float,
    to: float,
    accuracy: Optional[str] = None,
    require: Optional[str] = None,
    progress: _Progress = None,
) -> ThresholdResult:
    """The critical value of the scene field `vary` (``section.key``, e.g.
    ``"surface.sigma_s"``) in [`from_`, `to`] (its SI unit) at which the pull-out ratio
    after accommodation (phi x largest pull-out / K_s d0) crosses 1, as ``stiction design
    threshold --vary FIELD --from A --to B``. `require` (``"contact_resistance<1"``, ohm;
    or ``"real_contact_fraction>0.01"``) adds a second requirement, as ``--require``: the
    result's ``requirement`` has its crossings and the ``window`` of values where the
    switch is free of stiction and meets it. `progress(done, total)` counts the design
    points evaluated (``total``: the scan and a typical refinement; a search that needs
    more holds at ``total - 1`` until it ends)."""
    return ThresholdResult(
        _stiction.design_threshold(
            scene, vary, from_, to, _word("accuracy", accuracy), _word("require", require),
            progress=_progress(progress),
        )
    )


def _design_map(native: Any) -> DesignMap:
    return DesignMap(native.data(), native)


def design_map(
    scene: SceneLike,
    vary: Union[str, Sequence[str]],
    accuracy: Optional[str] = None,
    client: Any = None,
    shard: Optional[str] = None,
    require: Optional[str] = None,
    progress: _Progress = None,
) -> DesignMap:
    """A 1-D or 2-D map of the pull-out ratio after accommodation (phi x largest pull-out
    in Pa / K_s d0 in Pa; above 1 the switch sticks) over the grid of `vary`,
    a list of the CLI's ``--vary`` strings: ``"FIELD=FROM:TO:lin|log:N"`` for a number
    (e.g. ``["switch.k_s=1e9:1e11:log:8"]``; the first varies slowest), or
    ``"FIELD=WORD,WORD,..."`` for a law name or a choice (e.g.
    ``"contact.plasticity_law=etsion_kadin,kogut_etsion"``: each point's ``values`` then
    holds the word). The points are those of
    ``stiction design map --vary ... --accuracy ...`` on the same scene, exactly: each
    point with ``.pull_out_ratio``, ``.sticks``, ``.closes``, ``.status``; ``to_json()``
    is the command's map.json.

    Without `client` the points run here, in parallel threads. With a
    ``dask.distributed.Client`` (or any ``concurrent.futures.Executor``) each point is a
    task on the cluster, evaluated by this package on the workers, and the answers are
    assembled into the same map (docs/python.md, "Design maps on a Dask cluster").
    `shard` ("K/N") runs part K of N of the grid, as ``--shard``; join the parts with
    :func:`design_merge`. `require` (``"contact_resistance<1"``) marks each point's
    ``meets_requirement`` and ``in_window`` (free of stiction and meeting it), as
    ``--require``. `progress(done, total)` counts the design points done (with `client`,
    the tasks completed)."""
    vary_list = [vary] if isinstance(vary, str) else list(vary)
    report = _progress(progress)
    if _client(client) is None:
        return _design_map(
            _stiction.design_map(
                scene, vary_list, _word("accuracy", accuracy), _word("shard", shard), _word("require", require),
                progress=report,
            )
        )
    from ._dask import Stages, map_on_client

    stages = Stages(report)
    native = map_on_client(client, scene, vary_list, accuracy, shard, require, stages)
    forms = _stiction.model_form_scenes(scene, _word("accuracy", accuracy))
    if forms is not None:
        # the same map under every other combination of the credible published model
        # forms, on the cluster too (each without the requirement: only its verdicts count)
        mode, scenes, excluded = forms
        maps = [
            (form, map_on_client(client, form_scene, vary_list, mode, shard, None, stages))
            for form, form_scene in scenes
        ]
        native = _stiction.with_map_model_form(native, mode, maps, excluded)
    stages.end()
    return _design_map(native)


def design_merge(
    parts: Sequence[Union[DesignMap, ProbabilityResult, PathLike]],
) -> Union[DesignMap, ProbabilityResult]:
    """Joins the shards of one map (DesignMaps or paths of their map.json) into exactly
    the map of an unsharded run, or the shards of one probability run (ProbabilityResults
    or paths of their probability.json) into exactly the unsharded run, as ``stiction
    design merge``. The parts must be all of one kind."""
    def is_probability(p: Any) -> bool:
        if isinstance(p, ProbabilityResult):
            return True
        if isinstance(p, DesignMap):
            return False
        # a file's kind from its content (its name may be anything), as the command reads it
        path = os.fspath(p)
        if os.path.isdir(path):
            return os.path.exists(os.path.join(path, "probability.json"))
        try:
            with open(path, "rb") as f:
                head = f.read(4096)
        except OSError:
            return os.path.basename(path) == "probability.json"
        # the "format" tag comes first in both files
        return b'"format": "stiction-design-probability"' in head

    kinds = {is_probability(p) for p in parts}
    if len(kinds) > 1:
        raise InputError(
            "parts: map parts and probability parts do not merge (give the shards of one map, "
            "or of one probability run)"
        )
    if kinds == {True}:
        natives = [p._native if isinstance(p, ProbabilityResult) else os.fspath(p) for p in parts]
        return _probability(_stiction.design_merge_probability(natives))
    natives = [p._native if isinstance(p, DesignMap) else os.fspath(p) for p in parts]
    return _design_map(_stiction.design_merge(natives))


def read_map(path: PathLike) -> DesignMap:
    """Reads a map.json of ``stiction design map`` (whole, merged or a shard)."""
    return _design_map(_stiction.read_map(os.fspath(path)))


def _probability(native: Any) -> ProbabilityResult:
    return ProbabilityResult(native.data(), native)


def design_probability(
    scene: SceneLike,
    scatter: Union[str, Sequence[str]],
    samples: int = 1000,
    seed: int = 0,
    correlate: Union[str, Sequence[str], None] = None,
    confidence: float = 0.95,
    accuracy: Optional[str] = None,
    shard: Optional[str] = None,
    target_halfwidth: Optional[float] = None,
    exact: bool = True,
    client: Any = None,
    count_outside_validity: bool = False,
    progress: _Progress = None,
) -> ProbabilityResult:
    """The probability that a switch sticks when its design fields scatter from die to
    die, as ``stiction design probability --scatter ... --samples N --seed K``.

    `scatter`: the CLI's ``--scatter`` strings ``"FIELD=DIST"``, FIELD any field of
    :func:`design_map` (:func:`variable_fields`), DIST ``normal(mean,sd)``,
    ``lognormal(median,factor)`` (factor = exp(sigma)), ``uniform(lo,hi)`` or
    ``weibull(scale,shape)`` in the field's SI unit (m, Pa, J/m^2, Pa/m, V ...), e.g.
    ``"surface.sigma_s=lognormal(7.78e-9,1.1)"``. A distribution that puts more than 1e-6
    of its mass outside the field's domain raises :class:`InputError` naming the field
    (values are never clipped). `correlate`: ``"A,B=RHO"`` strings (Gaussian copula).
    `samples` devices are drawn (sample i from (`seed`, i) alone) and run in parallel
    threads, each a design point of the scene (until accommodated); `confidence` of the
    Clopper-Pearson intervals; `accuracy` of the design points (``"fast"`` for Monte
    Carlo); `shard` ``"K/N"`` runs part K of N (join with :func:`design_merge`);
    `target_halfwidth` stops once the stiction interval's half-width is at most it
    (checked every 100 samples); `exact` (with one scattered field) also computes the
    exact answer, the distribution's CDF at the field's critical value.

    The result: ``.stiction_probability`` with ``.ci_low``, ``.ci_high`` (pure numbers),
    ``.by_cycle`` (numpy columns ``cycle``, ``probability``, ``ci_low``, ``ci_high``),
    ``.does_not_close_probability``, ``.outside_validity`` (a count), ``.driver`` and
    ``.rank_correlation``, ``.exact``, and every sample in ``.points``
    (``.values_of(field)``, ``.column("pull_out_ratio")`` as numpy arrays).

    With a ``dask.distributed.Client`` (or any ``concurrent.futures.Executor``) as
    `client`, each sample is a task on the cluster and the answers are assembled into the
    same run (with `target_halfwidth` every sample is run, the engine stops where a local
    run stops). A scene with ``model_form = "check"`` also runs the same samples under
    every other combination of the credible published model forms (on the cluster too)
    and gives ``.model_form`` with ``stiction_probability_range``.

    Samples outside the model's validity are set apart (``.outside_validity``) and the
    answer over every sample that ran is ``.all_samples`` (``stiction.probability`` with
    its interval: a number whenever a sample ran); ``count_outside_validity=True`` makes
    that the headline ``.stiction_probability``, as ``--count-outside-validity``.

    `progress(done, total)` counts the samples done (with `client`, the tasks completed)."""
    scatter_list = [scatter] if isinstance(scatter, str) else list(scatter)
    if correlate is None:
        correlate_list: List[str] = []
    elif isinstance(correlate, str):
        correlate_list = [correlate]
    else:
        correlate_list = list(correlate)
    args = (
        scatter_list,
        _count("samples", samples, 1),
        _count("seed", seed, 0, _U64_MAX),
        correlate_list,
        confidence,
        _word("accuracy", accuracy),
        _word("shard", shard),
        target_halfwidth,
    )
    if not isinstance(count_outside_validity, bool):
        raise InputError(f"invalid count_outside_validity = {count_outside_validity!r}: must be True or False")
    counting = count_outside_validity
    report = _progress(progress)
    if _client(client) is None:
        return _probability(
            _stiction.design_probability(scene, *args, exact, count_outside_validity=counting, progress=report)
        )
    from ._dask import Stages, probability_on_client

    stages = Stages(report)
    native = probability_on_client(client, scene, args, exact, counting, stages)
    forms = _stiction.model_form_scenes(scene, args[5])
    if forms is not None:
        mode, scenes, excluded = forms
        # the other combinations: the same samples in the check's mode, no exact answer
        runs = [
            (form, probability_on_client(client, form_scene, args[:5] + (mode,) + args[6:], False, counting, stages))
            for form, form_scene in scenes
        ]
        native = _stiction.with_probability_model_form(native, mode, runs, excluded)
    stages.end()
    return _probability(native)


def read_probability(path: PathLike) -> ProbabilityResult:
    """Reads a probability.json of ``stiction design probability`` (whole, merged or a
    shard), checked as ``stiction design merge`` checks it."""
    return _probability(_stiction.read_probability(os.fspath(path)))


def tabulate_law(
    scene: SceneLike,
    d_min: Optional[str] = None,
    points: int = 96,
    tolerance: float = 2e-4,
    accuracy: Optional[str] = None,
    progress: _Progress = None,
) -> LawResult:
    """Tabulates the contact law p(d; d_min, path) of a switch or surface scene's rough
    surface for an FE code, as ``stiction law``: `d_min` a uniform grid of histories
    ``"FROM:TO:N"`` (m, m, count) or None for the adaptive default; `points` start points
    per branch; `tolerance` on |p_table - p_surface| / (|p_surface| + |p_pull_out|);
    `accuracy` of the surface evaluations (default fast). ``result.law`` is the
    :class:`ContactLaw` (``.save(path)`` writes law.json). `progress(done, total)`
    counts the work in thousandths (``total`` 1000)."""
    data, native = _stiction.tabulate_law(
        scene, _word("d_min", d_min), _count("points", points, 1), tolerance, _word("accuracy", accuracy),
        progress=_progress(progress),
    )
    data["law"] = ContactLaw(native)
    return LawResult(data)


def calibrate(
    scene: SceneLike,
    fe: Union[PathLike, Mapping[str, Sequence[Any]]],
    fit: str = "c1,c2",
    overlay: bool = False,
) -> CalibrationResult:
    """Fits the constants of eq 13 (c1 = [a1, a2, a3], c2 = [b1, b2, b3]) to
    finite-element force-interference curves of one asperity, as ``stiction calibrate``:
    `scene` an asperity scene (the model and the starting constants); `fe` a CSV file with
    columns delta_max_m, delta_m, force_n, branch (SI; branch loading | unloading), or a
    mapping of those columns; `fit` the constants to fit (c1, c2, all, a1 ... b3,
    comma-separated); `overlay` also samples the fitted model per curve."""
    if isinstance(fe, Mapping):
        cols = ["delta_max_m", "delta_m", "force_n", "branch"]
        missing = [c for c in cols if c not in fe]
        if missing:
            raise InputError(f"fe: the columns {', '.join(missing)} are missing (give {', '.join(cols)})")
        lengths = {c: len(list(fe[c])) for c in cols}
        if len(set(lengths.values())) > 1:
            raise InputError(
                "fe: the columns differ in length ("
                + ", ".join(f"{c}: {n}" for c, n in lengths.items())
                + "): each row is one point of a curve"
            )
        rows = zip(*(list(fe[c]) for c in cols))
        text = ",".join(cols) + "\n" + "".join(
            f"{float(a)!r},{float(b)!r},{float(c)!r},{d}\n" for a, b, c, d in rows
        )
        return CalibrationResult(_stiction.calibrate(scene, None, text, "<columns>", fit, overlay))
    return CalibrationResult(_stiction.calibrate(scene, os.fspath(fe), None, "<columns>", fit, overlay))


def topography(
    path: PathLike,
    file_format: Optional[str] = None,
    spacing: Optional[float] = None,
    height_unit: Optional[str] = None,
    xy_unit: Optional[str] = None,
    detrend: Optional[str] = None,
    route: Optional[str] = None,
    undefined: Optional[str] = None,
    channel: Optional[Union[str, int]] = None,
    cutoff: Optional[float] = None,
    contact_radius: Optional[float] = None,
) -> TopographyResult:
    """A measured height map (AFM, profilometer) reduced to the Greenwood-Williamson
    parameters of a scene, as ``stiction topography FILE``: the report (``to_dict()`` is
    the command's JSON), the height map as read (``.height_map``, m, a numpy array, rows = y,
    with ``.dx``, ``.dy``) and the ``[surface]`` scene fragment (``.fragment``). The options
    are the command's: `file_format` (text, xyz, npy, gsf, gwy, x3p, nanoscope, opd,
    metropro, sur, plu, vk4, sdf; default from the file's first bytes, else its extension),
    `spacing` (m, for a format without one), `height_unit` and `xy_unit` (m, mm, um, nm, pm,
    A), `detrend` (mean, plane, poly:N), `route` (summits, spectral), `undefined` (refuse,
    the default, or fill: the file's undefined points filled by harmonic interpolation;
    ``to_dict()["source"]["undefined_points"]`` counts them) and `channel` (a name or a
    0-based index among ``to_dict()["source"]["channels"]``; default the first height
    channel), `cutoff` (m: the short-wavelength cutoff, the map low-pass filtered at it
    before the analysis, a Gaussian of ISO 16610-61; 0 or a cutoff at the pixel scale: the map
    as sampled) and `contact_radius` (m: the asperity tip radius R whose contact-spot scale
    gives the default cutoff, 4 sqrt(R sigma_s)); ``to_dict()["cutoff"]`` says which band was
    taken and ``to_dict()["band"]`` repeats both routes across a few cutoffs. A bad option
    raises :class:`InputError` naming it (docs/topography.md sections 9 and 10)."""
    for name, value in (("file_format", file_format), ("height_unit", height_unit), ("xy_unit", xy_unit),
                        ("detrend", detrend), ("route", route), ("undefined", undefined)):
        _word(name, value)
    for name, value in (("spacing", spacing), ("cutoff", cutoff), ("contact_radius", contact_radius)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))):
            raise InputError(f"invalid {name} = {value!r}: must be a length in m")
    if channel is not None:
        if isinstance(channel, bool) or not isinstance(channel, (str, int)):
            raise InputError(f"invalid channel = {channel!r}: must be a channel's name (a str) or its 0-based index")
        if isinstance(channel, int):
            if channel < 0:
                raise InputError(f"invalid channel = {channel!r}: an index is 0 or more")
            channel = str(channel)
    spacing, cutoff, contact_radius = (None if v is None else float(v) for v in (spacing, cutoff, contact_radius))
    native = _stiction.topography(os.fspath(path), file_format, spacing, height_unit, xy_unit, detrend, route,
                                  undefined, channel, cutoff, contact_radius)
    return TopographyResult._of_native(native)


for _long in (run, design_threshold, design_map, design_probability, tabulate_law):
    _long.__doc__ = (_long.__doc__ or "") + "\n\n    " + _PROGRESS_DOC
del _long


def __dir__() -> List[str]:
    """The public names (``__all__``): the helpers this module imports are not part of it."""
    return sorted(__all__)
