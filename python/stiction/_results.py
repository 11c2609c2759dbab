"""Typed results: the model library's results (their serde form) as Python objects.

A result is a :class:`Record`: its fields are attributes, declared with their types and
units on each class below (the library's own field names; a field named after a Python
keyword gets a trailing underscore: ``lambda_``, ``from_``). Curves and other lists of
flat rows are :class:`Table` objects whose columns are numpy arrays (``result.loading.d``,
``result.loading.pressure``) and whose rows are records (``result.loading[0].d``). Lists of
numbers are numpy arrays. Nothing is handed over as JSON text.

Units are SI throughout: m, N, Pa, Pa/m, J/m^2, V (the nondimensional Maugis-Kim curve
excepted, in the units of ``stiction md``).
"""

from __future__ import annotations

import keyword
import typing
from typing import Any, ClassVar, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

__all__ = [
    "Record",
    "Table",
    "CycleTable",
    "PressureCurve",
    "ForceCurve",
    "MdCurve",
    "ModelWarning",
    "Validity",
    "Laws",
    "Targets",
    "SwitchErrors",
    "DriveReport",
    "ContactState",
    "Cycle",
    "ElasticComparison",
    "ModelFormRun",
    "ModelFormReport",
    "SwitchResult",
    "SurfaceErrors",
    "SurfaceResult",
    "AsperityErrors",
    "AsperityCase",
    "AsperityResult",
    "MdResult",
    "MapPoint",
    "DesignMap",
    "ThresholdResult",
    "Estimate",
    "ProbabilityCounts",
    "Stopping",
    "CycleProbabilities",
    "RankCorrelations",
    "ExactAnswer",
    "ProbabilitySample",
    "ProbabilityResult",
    "Histories",
    "LawResult",
    "LawEvaluation",
    "PlasticState",
    "PullOut",
    "CalibrationResult",
]


def _attr_name(key: str) -> str:
    return key + "_" if keyword.iskeyword(key) else key


def _key_name(attr: str) -> str:
    """The key of the command's JSON an attribute stands for (`from_` -> `from`)."""
    if attr.endswith("_") and keyword.iskeyword(attr[:-1]):
        return attr[:-1]
    return attr


def _cell(v: Any) -> Any:
    """A table cell as plain data; a NaN float marks a row without the value (the
    library leaves the key out there, and never writes NaN)."""
    v = _plain(v)
    return None if isinstance(v, float) and v != v else v


def _plain(v: Any) -> Any:
    """A numpy scalar as its Python value."""
    return v.item() if isinstance(v, np.generic) else v



def _pandas() -> Any:
    """pandas, imported when a conversion asks for it."""
    try:
        import pandas
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_pandas() needs pandas: pip install pandas") from e
    return pandas


def _xarray() -> Any:
    """xarray, imported when a conversion asks for it."""
    try:
        import xarray
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_xarray() needs xarray: pip install xarray") from e
    return xarray


def _saved(paths: Sequence[str]) -> List[str]:
    return list(paths)


class Table:
    """Rows of a result stored as columns: each column a numpy array (float64 with NaN
    where a row has no value, int64, bool), or a list for words.

    ``t.d`` (or ``t["d"]``) is a column; ``len(t)`` the rows; ``t[i]`` row ``i`` as a
    :class:`Record`; iterating gives the rows; ``t.columns`` the names;
    ``t.to_dict()`` the columns.
    """

    __slots__ = ("_columns",)
    #: the columns a table of this kind has, with their units (for empty tables and docs)
    _units: ClassVar[Dict[str, str]] = {}

    def __init__(self, columns: Mapping[str, Any]) -> None:
        cols: Dict[str, Any] = {}
        for k, v in columns.items():
            if isinstance(v, np.ndarray):
                cols[k] = v
            elif all(isinstance(x, str) for x in v):
                cols[k] = np.asarray(v, dtype=str) if len(v) else np.asarray([], dtype=str)
            else:
                cols[k] = np.asarray(v, dtype=object)
        object.__setattr__(self, "_columns", cols)

    @classmethod
    def empty(cls) -> "Table":
        """A table of no rows with this kind's columns."""
        return cls({k: np.zeros(0) for k in cls._units})

    @classmethod
    def from_rows(cls, rows: List[Mapping[str, Any]]) -> "Table":
        """A table from a list of dicts (the serde form of a list of flat records)."""
        if not rows:
            return cls.empty()
        names: List[str] = []
        for r in rows:
            for k in r:
                if k not in names:
                    names.append(k)
        cols: Dict[str, Any] = {}
        for k in names:
            cells = [r.get(k) for r in rows]
            if all(isinstance(c, bool) for c in cells):
                cols[k] = np.asarray(cells, dtype=bool)
            elif all(isinstance(c, int) and not isinstance(c, bool) for c in cells):
                cols[k] = np.asarray(cells, dtype=np.int64)
            elif all(isinstance(c, (int, float)) and not isinstance(c, bool) or c is None for c in cells):
                cols[k] = np.asarray([np.nan if c is None else c for c in cells], dtype=float)
            else:
                cols[k] = cells
        return cls(cols)

    @property
    def columns(self) -> List[str]:
        """The column names."""
        return list(self._columns)

    def __getattr__(self, name: str) -> Any:
        cols = object.__getattribute__(self, "_columns")
        if name in cols:
            return cols[name]
        if name.endswith("_") and name[:-1] in cols:
            return cols[name[:-1]]
        raise AttributeError(f"{type(self).__name__} has no column {name!r}; columns: {', '.join(cols)}")

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("a result table is read-only")

    def __len__(self) -> int:
        for v in self._columns.values():
            return len(v)
        return 0

    def __getitem__(self, i: Union[int, str, slice]) -> Any:
        if isinstance(i, str):
            return self._columns[i]
        if isinstance(i, slice):
            return type(self)({k: v[i] for k, v in self._columns.items()})
        n = len(self)
        if i < 0:
            i += n
        if not 0 <= i < n:
            raise IndexError(f"row {i} of a table of {n} rows")
        return Record({k: _plain(v[i]) for k, v in self._columns.items()})

    def __iter__(self) -> Iterator["Record"]:
        for i in range(len(self)):
            yield self[i]

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self._columns))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Table) or self.columns != other.columns:
            return NotImplemented
        return all(
            np.array_equal(np.asarray(a), np.asarray(b))
            for a, b in zip(self._columns.values(), other._columns.values())
        )

    def to_dict(self) -> Dict[str, Any]:
        """The columns, by name."""
        return dict(self._columns)

    def to_pandas(self) -> Any:
        """The table as a ``pandas.DataFrame``, one column per column of the table, in
        order (pandas is imported here: ImportError naming it when it is missing)."""
        pd = _pandas()
        return pd.DataFrame({k: (v.tolist() if v.dtype == object else v) for k, v in self._columns.items()})

    def __repr__(self) -> str:
        return f"<{type(self).__name__}: {len(self)} rows of {', '.join(self._columns)}>"


class PressureCurve(Table):
    """A pressure curve of the rough surface: columns ``d`` (separation, m) and
    ``pressure`` (nominal pressure, Pa, compressive positive, adhesive negative)."""

    _units = {"d": "m", "pressure": "Pa"}
    d: np.ndarray
    pressure: np.ndarray


class ForceCurve(Table):
    """A force curve of one asperity: columns ``delta`` (interference, m) and ``force``
    (N, compressive positive)."""

    _units = {"delta": "m", "force": "N"}
    delta: np.ndarray
    force: np.ndarray


class MdCurve(Table):
    """The nondimensional Maugis-Kim curve (paper eq 7, Kim extension): columns
    ``delta`` (interference Delta), ``force`` (Fbar), ``a`` (contact radius A), ``c``
    (radius of the cohesive zone C), ``s`` (C/A on the contact branch; NaN off contact),
    ``branch`` ("contact" | "non_contact"), ``stable``."""

    _units = {"delta": "-", "force": "-", "a": "-", "c": "-", "s": "-", "branch": "", "stable": ""}


class CycleTable(Table):
    """A switch run's cycles, one row per cycle (``SwitchResult.per_cycle``): the cycles'
    scalar fields and the contact states' as ``hold_*`` / ``end_*``. ``to_pandas()`` has
    exactly the columns of cycles.csv (``stiction switch --out``), in its order and with
    its unit-suffixed names, one row per cycle (cycles.csv adds a last row for the
    elastic comparison)."""

    #: cycles.csv's header: each column and the table column it holds
    CSV_COLUMNS: ClassVar[Dict[str, str]] = {
        "cycle": "cycle",
        "d_e_m": "d_e",
        "pull_out_pressure_pa": "pull_out_pressure",
        "pull_out_separation_m": "pull_out_separation",
        "sticks": "sticks",
        "pull_out_ratio": "pull_out_ratio",
        "deepened": "deepened",
        "hold_status": "hold_status",
        "hold_separation_m": "hold_separation",
        "hold_real_contact_fraction": "hold_real_contact_fraction",
        "hold_spot_density_per_m2": "hold_spot_density",
        "hold_mean_spot_radius_m": "hold_mean_spot_radius",
        "hold_contact_resistance_ohm": "hold_contact_resistance",
        "end_real_contact_fraction": "end_real_contact_fraction",
        "end_spot_density_per_m2": "end_spot_density",
        "end_mean_spot_radius_m": "end_mean_spot_radius",
        "end_contact_resistance_ohm": "end_contact_resistance",
    }

    def to_pandas(self) -> Any:
        """The cycles as a ``pandas.DataFrame`` with cycles.csv's columns (NaN where
        cycles.csv has an empty cell)."""
        pd = _pandas()
        cols = self.to_dict()
        return pd.DataFrame(
            {
                name: (cols[col].tolist() if cols[col].dtype == object else cols[col])
                for name, col in self.CSV_COLUMNS.items()
            }
        )


class Record:
    """A result: fields as attributes (see the class's annotations for types and units),
    ``r["field"]`` too; ``r.to_dict()`` the whole tree as plain Python data."""

    _hints_cache: ClassVar[Dict[type, Dict[str, Any]]] = {}

    def __init__(self, data: Mapping[str, Any]) -> None:
        hints = type(self)._hints()
        for key, value in data.items():
            name = _attr_name(key)
            object.__setattr__(self, name, _convert(value, hints.get(name)))
        absent = tuple(name for name in hints if name not in self.__dict__)
        for name in absent:
            object.__setattr__(self, name, None)
        # declared fields the source left out (the library omits an absent optional key):
        # None as attributes, left out again by to_dict so that it equals the source
        object.__setattr__(self, "_absent", absent)

    @classmethod
    def _hints(cls) -> Dict[str, Any]:
        cache = Record._hints_cache
        if cls not in cache:
            if cls is Record:
                cache[cls] = {}
            else:
                hints = typing.get_type_hints(cls)
                cache[cls] = {k: v for k, v in hints.items() if not k.startswith("_") and typing.get_origin(v) is not ClassVar}
        return cache[cls]

    @classmethod
    def _of(cls, fields: Mapping[str, Any]) -> "Record":
        """A record of fields already of their declared types (no conversion)."""
        obj = object.__new__(cls)
        obj.__dict__.update(fields)
        return obj

    @classmethod
    def fields(cls) -> List[str]:
        """The declared fields."""
        return list(cls._hints())

    def keys(self) -> List[str]:
        """The fields this result has."""
        return [k for k in self.__dict__ if not k.startswith("_")]

    def __getitem__(self, key: str) -> Any:
        try:
            return self.__dict__[_attr_name(key)]
        except KeyError:
            raise KeyError(key) from None

    def __contains__(self, key: str) -> bool:
        return _attr_name(key) in self.__dict__

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("a result is read-only")

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        a = {k: v for k, v in self.__dict__.items() if k != "_report"}
        b = {k: v for k, v in other.__dict__.items() if k != "_report"}  # type: ignore[union-attr]
        if a.keys() != b.keys():
            return False
        for k in a:
            x, y = a[k], b[k]
            if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
                if not np.array_equal(np.asarray(x), np.asarray(y)):
                    return False
            elif x != y:
                return False
        return True

    __hash__ = None  # type: ignore[assignment]

    def to_dict(self) -> Dict[str, Any]:
        """The result as plain Python data (dicts, lists; arrays as lists)."""

        def plain(v: Any) -> Any:
            if isinstance(v, Record):
                return v.to_dict()
            if isinstance(v, Table):
                cols = v.to_dict()
                rows = []
                for i in range(len(v)):
                    row = {k: _cell(c[i]) for k, c in cols.items()}
                    rows.append({k: x for k, x in row.items() if x is not None})
                return rows
            if isinstance(v, np.ndarray):
                return v.tolist()
            if isinstance(v, list):
                return [plain(x) for x in v]
            if isinstance(v, dict):
                return {k: plain(x) for k, x in v.items()}
            return _plain(v)

        absent = self.__dict__.get("_absent", ())
        return {
            _key_name(k): plain(v)
            for k, v in self.__dict__.items()
            if not k.startswith("_") and not (k in absent and v is None)
        }

    def __repr__(self) -> str:
        parts = []
        for k, v in self.__dict__.items():
            if k.startswith("_"):
                continue
            if isinstance(v, (Record, Table, dict)) or (isinstance(v, list) and len(v) > 3):
                s = f"<{type(v).__name__}>" if not isinstance(v, list) else f"[{len(v)} items]"
            elif isinstance(v, np.ndarray):
                s = f"array({v.shape})" if v.size > 4 else repr(v.tolist())
            else:
                s = repr(v)
            parts.append(f"{k}={s}")
            if len(parts) == 8:
                parts.append("...")
                break
        return f"{type(self).__name__}({', '.join(parts)})"


def _convert(value: Any, hint: Any) -> Any:
    """`value` (Python data from the extension) as the declared type `hint`."""
    if hint is None or hint is Any:
        return value
    origin = typing.get_origin(hint)
    if origin is Union:
        args = [a for a in typing.get_args(hint) if a is not type(None)]
        if value is None:
            return None
        return _convert(value, args[0]) if len(args) == 1 else value
    if origin in (list, List):
        (item,) = typing.get_args(hint) or (Any,)
        if isinstance(value, Table):
            value = [dict(zip(value.columns, (_plain(c[i]) for c in value.to_dict().values()))) for i in range(len(value))]
        if isinstance(value, np.ndarray):
            value = value.tolist()
        return [_convert(v, item) for v in value]
    if isinstance(hint, type):
        if issubclass(hint, Table):
            if isinstance(value, Table):
                return hint(value.to_dict())
            if isinstance(value, list):
                return hint.from_rows(value)
            return value
        if issubclass(hint, Record):
            return hint(value) if isinstance(value, Mapping) else value
        if hint is float:
            if isinstance(value, str):
                return float(value)  # "inf"
            if isinstance(value, int) and not isinstance(value, bool):
                return float(value)
            return value
        if hint is np.ndarray:
            if isinstance(value, np.ndarray):
                return value
            return np.asarray(value, dtype=float)
    return value


class _Tabled:
    """A result the library keeps for its presentation (``stiction-report``, the command
    line's own): ``table()`` is what the command prints."""

    def table(self) -> str:
        """What the command prints (``--format table``)."""
        return self._report.table()  # type: ignore[attr-defined, no-any-return]


class _Drawn(_Tabled):
    """A result with a figure too: ``to_svg()``."""

    def to_svg(self) -> str:
        """The figure as SVG text, byte for byte the command's (``--plot`` or the SVG of
        ``--out``)."""
        return self._report.to_svg()  # type: ignore[attr-defined, no-any-return]


class _Saved(_Drawn):
    """A result whose command writes a folder (``--out DIR``)."""

    def save(self, folder: Any) -> List[str]:
        """Writes the command line's ``--out`` files to `folder`, byte for byte, as the
        command writes them: the folder is replaced as a whole (it may hold only the
        command's files, else InputError), each file whole, a FIFO or device never
        replaced. Returns the paths written."""
        import os

        return _saved(self._report.save(os.fspath(folder)))  # type: ignore[attr-defined]


# ---------------------------------------------------------------- shared parts


class ModelWarning(Record):
    """A physics guard raised by a run: the model is used where it leaves its ground."""

    code: str  #: stable identifier (adhesion_yields_asperity, beyond_fit_range, ...)
    message: str  #: what happened and what it means, with numbers
    breaks_validity: Optional[bool]  #: whether it puts the result outside the model's validity (design results)


class Validity(Record):
    """Whether the model holds for a result, and which checks say it does not."""

    holds: bool
    reasons: List[str]  #: codes of the checks that fail


class Laws(Record):
    """The laws and modelling choices of a run."""

    adhesion: str  #: adhesion law (maugis_kim, jkr, dmt, hertz, ...)
    plasticity: str  #: plasticity law (etsion_kadin, kogut_etsion, adhesion_coupled, elastic, ...)
    yield_modulus: str  #: reading of eq 1 (as_printed | composite)
    reload: str  #: reload rule (as_printed | bounded)



class Targets(Record):
    """An accuracy mode and what it promises."""

    mode: str  #: accurate | balanced | fast | reference
    d_e_tolerance_sigma: float  #: d_e to this fraction of sigma_s
    pull_out_tolerance: float  #: pull-out to this fraction of itself ...
    pull_out_floor_of_restoring: float  #: ... or of K_s d0, whichever is larger


# ---------------------------------------------------------------- switch


class SwitchErrors(Record):
    """Error estimates of a switch run."""

    d_e: float  #: largest d_e error estimate over the cycles (m)
    pull_out: float  #: largest pull-out error estimate (Pa), the stopping rule's included
    accommodation: float  #: how much the largest pull-out could still grow in cycles not run (Pa)
    pull_out_ratio: float  #: error of the pull-out ratio (-)


class DriveReport(Record):
    """Which of K_s, U, E_I the scene gave and which were derived."""

    mode: str  #: impact_energy | spring
    given: List[str]
    derived: List[str]


class ContactState(Record):
    """The closed switch's contact at one state of a cycle (the rest under the hold, or
    the end of impact): real contact area, spots, contact resistance (theory 6.5)."""

    separation: float  #: mean plane of asperity heights to the counter-surface (m)
    contact_pressure: float  #: Pa per contact area (compressive > 0)
    real_contact_fraction: float  #: A_r / (phi A) (-)
    spot_density: float  #: contacting asperities per unit contact area (1/m^2)
    mean_spot_radius: float  #: m
    spots: Optional[float]  #: spots on phi x electrode_area (with electrode_area)
    contact_resistance: Optional[float]  #: the spots in parallel, Holm-Sharvin (Wexler) (ohm)
    interaction_resistance: Optional[float]  #: Greenwood's 16 rho / (3 pi^2 alpha) (ohm)
    contact_resistance_with_interaction: Optional[float]  #: the sum (ohm)
    knudsen_number: Optional[float]  #: lambda / mean spot radius (-)
    relative_error: float  #: largest relative error estimate of the integrals


class Cycle(Record):
    """One switch cycle: the impact (eq 17) and the pull-out."""

    cycle: int  #: 1-based
    d_e: float  #: end-of-impact separation (m)
    d_e_error: float  #: its error estimate (m)
    deepened: bool  #: this impact went deeper than every earlier one
    shallower_by: float  #: how far d_e stopped above the deepest earlier separation (m)
    contact_pressure: float  #: approach pressure at d_e (Pa, per contact area)
    pull_out_pressure: float  #: pull-out pressure (Pa, per contact area, >= 0)
    pull_out_error: float  #: its error estimate (Pa)
    pull_out_separation: float  #: where the pull-out occurs (m)
    pull_out_ratio: float  #: phi pull-out / (K_s d0); above 1 the switch sticks
    sticks: bool  #: ratio above 1: the spring cannot open the switch
    unloading: PressureCurve  #: unloading curve (empty with points = 0)
    well: PressureCurve  #: the adhesive well with the pull-out point (empty with points = 0)
    hold: Optional[ContactState]  #: the rest under the hold (None: opens or not computed)
    hold_status: str  #: rests | deeper_than_impact | opens | not_computed | not_computable
    end_of_impact: Optional[ContactState]  #: the contact at d_e (None: not computed)


class ModelFormRun(Record):
    """One combination of a model-form check (``model_form.runs``)."""

    laws: Laws  #: its plasticity law, eq-1 reading, reload rule and adhesion law
    pull_out_ratio: float  #: the largest pull-out ratio over its cycles
    stiction: bool  #: whether it sticks (ratio > 1)
    validity_holds: bool  #: whether the model holds for it
    decided: bool  #: whether its ratio lies farther from 1 than its error estimate
    closes: bool  #: whether the switch closes under it


class ModelFormReport(Record):
    """The model-form check of a switch (``model_form = "check"``): would another
    published model form change the verdict? (docs/theory.md section 12)"""

    accuracy: str  #: the mode the other combinations ran in
    robust: bool  #: every combination gives the scene's verdict
    flips: List[str]  #: the choices that flip the verdict when changed alone
    ratio_range: List[float]  #: [lowest, highest] pull-out ratio over the combinations
    runs: List[ModelFormRun]  #: one per combination, the scene's own first
    excluded: List[Dict[str, Any]]  #: values and combinations left out, with the reason
    summary: str  #: the verdict in words


class ElasticComparison(Record):
    """The same surface with asperities that never yield, one cycle."""

    d_e: float  #: m
    pull_out_pressure: float  #: Pa
    pull_out_separation: float  #: m
    pull_out_ratio: float  #: -
    sticks: bool
    unloading: PressureCurve


class SwitchResult(_Saved, Record):
    """A switch run (``stiction switch``): the micro-switch cycle by cycle (paper Fig 4)
    and the stiction verdict."""

    title: str
    laws: Laws
    accuracy: Targets
    error_estimate: SwitchErrors
    k_s: float  #: spring stiffness per unit area K_s (Pa/m)
    v_pull_in: float  #: static pull-in voltage V_PI (V)
    dynamic_pull_in_voltage: float  #: lowest step voltage that closes the switch (V)
    voltage: float  #: step voltage U (V)
    impact_energy: float  #: impact energy per electrode area E_I (J/m^2)
    restoring_pressure: float  #: K_s d0 (Pa)
    contact_area_fraction: float  #: fraction phi of the electrode in contact
    hold_voltage: float  #: voltage holding the switch shut after each impact (V; 0 with hold_force)
    hold_force: Optional[float]  #: force holding it shut on its contacts (N), if given instead
    hold_pressure: float  #: the hold's pressure per contact area (Pa)
    contact_state: str  #: every_cycle | last_cycle | none
    closes: bool  #: whether the electrode reaches contact
    drive: DriveReport
    accommodation_tolerance: float  #: relative change that counts as accommodated
    loading: PressureCurve  #: virgin loading curve of cycle 1 (empty with points = 0)
    cycles: List[Cycle]  #: the cycles (none when the switch does not close)
    elastic: Optional[ElasticComparison]  #: the elastic comparison, if run
    accommodated_after: Optional[int]  #: the cycle after which nothing changes
    accommodation_cause: Optional[str]  #: saturated | non_deepening | None
    largest_pull_out: float  #: largest pull-out of all cycles (Pa)
    pull_out_ratio: float  #: phi largest pull-out / (K_s d0); above 1 the switch sticks
    first_sticking_cycle: Optional[int]
    stiction: bool  #: some cycle sticks
    validity: Validity
    extrapolated_fraction: float  #: asperities loaded beyond the fits' range after the last cycle
    warnings: List[ModelWarning]
    scene: Dict[str, Any]  #: the resolved scene (every key, defaults filled in)
    model_form: Optional[ModelFormReport]  #: the model-form check (``model_form = "check"``), else None

    def dynamics_svg(self) -> Optional[str]:
        """dynamics.svg of a switch in time, byte for byte the command's (None for a
        quasi-static run or without curves)."""
        return self._report.dynamics_svg()  # type: ignore[attr-defined, no-any-return]

    @property
    def per_cycle(self) -> "CycleTable":
        """The cycles' scalar fields as a table of numpy columns (``r.per_cycle.d_e``),
        with the contact under the hold and at the end of impact as ``hold_*`` and
        ``end_*`` columns (NaN where not computed): ``hold_contact_resistance``,
        ``end_real_contact_fraction``, ... ``to_pandas()`` gives cycles.csv's columns."""
        contact = [k for k, t in ContactState._hints().items() if t in (float, Optional[float])]

        def row(c: "Cycle") -> Dict[str, Any]:
            r = {
                k: v
                for k, v in c.__dict__.items()
                if not isinstance(v, (Table, Record))
                and not k.startswith("_")
                and k not in ("hold", "end_of_impact")
            }
            for prefix, state in (("hold_", c.hold), ("end_", c.end_of_impact)):
                for k in contact:
                    v = None if state is None else getattr(state, k)
                    r[prefix + k] = np.nan if v is None else float(v)
            return r

        rows = [row(c) for c in self.cycles]
        if rows:
            return CycleTable.from_rows(rows)  # type: ignore[return-value]
        # no cycle (the switch does not close): the scalar columns, empty
        scalar = (int, float, bool, str)
        hints = Cycle._hints()
        cols: Dict[str, Any] = {
            k: np.zeros(0, dtype=bool if t is bool else int if t is int else float)
            if t in (int, float, bool)
            else np.asarray([], dtype=str)
            for k, t in hints.items()
            if t in scalar
        }
        for prefix in ("hold_", "end_"):
            cols.update({prefix + k: np.zeros(0) for k in contact})
        return CycleTable(cols)


# ---------------------------------------------------------------- surface


class SurfaceErrors(Record):
    """Error estimates of a surface run (Pa)."""

    pressure: float  #: largest error estimate of a curve pressure
    pull_out: Optional[float]  #: the pull-out pressure's


class SurfaceResult(_Drawn, Record):
    """A surface run (``stiction surface``): the rough surface's loading, unloading and
    reloading curves (eqs 14-16)."""

    title: str
    laws: Laws
    sigma_s: float  #: RMS asperity height (m)
    accuracy: Targets
    error_estimate: SurfaceErrors
    loading: PressureCurve  #: virgin loading from d_start to the first touch
    unload_from: Optional[float]  #: separation unloaded from (m)
    unloading: PressureCurve  #: from unload_from to the last contact
    reloading: PressureCurve  #: approach with the history of unload_from
    pull_out_pressure: Optional[float]  #: magnitude of the most tensile unloading pressure (Pa)
    pull_out_separation: Optional[float]  #: where (m)
    extrapolated_fraction: float
    validity: Validity
    warnings: List[ModelWarning]
    scene: Dict[str, Any]


# ---------------------------------------------------------------- asperity


class AsperityErrors(Record):
    """Error estimates of an asperity run."""

    pull_off: float  #: largest change of a pull-off force within its location tolerance (N)


class AsperityCase(Record):
    """One asperity loaded to delta_max and unloaded (paper Fig 2)."""

    delta_max: float  #: maximum interference (m)
    delta_res: float  #: residual height loss (m), eq 4
    r_res: float  #: residual radius (m), eq 5
    r_eff_loading: float  #: R_eff on loading at delta_max (m), eq 12 with x = 1
    pull_off_force: float  #: most tensile force on unloading (N)
    pull_off_interference: float  #: where (m)
    elastic_pull_off_force: float  #: the same for the elastic asperity (N)
    extrapolated: bool  #: delta_max beyond the fits' range
    loading: ForceCurve
    unloading: ForceCurve


class AsperityResult(_Drawn, Record):
    """An asperity run (``stiction asperity``)."""

    title: str
    laws: Laws
    delta_cp: float  #: yield onset delta_CP (m), eq 1 (inf if it never yields)
    lambda_: float  #: transition parameter lambda at the initial radius (eq 6)
    radius: float  #: initial radius (m)
    accuracy: Targets
    error_estimate: AsperityErrors
    cases: List[AsperityCase]
    validity: Validity
    warnings: List[ModelWarning]
    scene: Dict[str, Any]


# ---------------------------------------------------------------- Maugis-Kim


class MdResult(_Tabled, Record):
    """The nondimensional Maugis-Kim curve and its landmarks (``stiction md``):
    Delta = delta / (pi^2 w^2 R / K^2)^(1/3), Fbar = F / (pi w R)."""

    lambda_: float  #: transition parameter lambda (eq 6)
    jump_in_delta: float  #: jump-in on approach, Delta_in = -2/(pi lambda)
    turning_delta: float  #: turning point (jump-out) Delta_t
    turning_force: float  #: force there
    pull_off_load_control: float  #: minimum force on the stable branch (DMT -2, JKR -3/2)
    pull_off_displacement_control: float  #: force at jump-out (JKR -5/6)
    curve: MdCurve


# ---------------------------------------------------------------- design


class MapPoint(Record):
    """One point of a design map (a row of map.csv, a point of map.json). The design
    fields are None where the point has no design (out of domain, failed)."""

    index: int  #: index in the grid (the first varied field varies slowest)
    values: Dict[str, Union[float, str]]  #: the varied fields' values (SI), a word on a categorical axis
    status: str  #: ok | does_not_close | out_of_domain | failed
    detail: Optional[str]  #: why, for out_of_domain and failed
    pull_out_ratio: Optional[float]  #: largest pull-out after accommodation / K_s d0 (> 1 sticks; 0: does not close)
    largest_pull_out_pa: Optional[float]  #: Pa
    restoring_pressure_pa: Optional[float]  #: K_s d0 (Pa)
    cycles_to_accommodation: Optional[int]
    first_sticking_cycle: Optional[int]
    sticks: Optional[bool]  #: the switch stays shut
    closes: Optional[bool]  #: the electrode reaches contact
    validity_holds: Optional[bool]  #: the model holds at this point
    accommodation_cause: Optional[str]  #: saturated | non_deepening
    contact_resistance: Optional[float]  #: under the hold after the last cycle (ohm)
    real_contact_fraction: Optional[float]  #: under the hold after the last cycle (-)
    meets_requirement: Optional[bool]  #: with a requirement
    in_window: Optional[bool]  #: free of stiction and meeting the requirement


class DesignMap(Record):
    """A design map (``stiction design map``): the pull-out ratio after accommodation over
    a 1-D or 2-D grid of scene fields. ``to_json()``, ``to_csv()``, ``to_svg()`` give the
    files of the command, byte for byte; ``save(folder)`` writes them."""

    format: str  #: "stiction-design-map"
    version: int
    accuracy: str  #: accuracy mode of the design points
    grid: Dict[str, Any]  #: the axes: field, from, to, spacing, n, values (a categorical axis: field, words, n)
    scene: Dict[str, Any]  #: the scene as run (design settings applied)
    shard: Optional[Dict[str, Any]]  #: this map's part K of N, for a shard
    requirement: Optional[str]  #: the second requirement (``contact_resistance<1e0``), if any
    points: List[MapPoint]
    warnings: List[ModelWarning]  #: guards the points raised (one per kind, with counts)
    validity: Optional[Validity]  #: whether the model holds at every point (None for a merged map)
    model_form: Optional[Dict[str, Any]]  #: the model-form check: ``share_sticking`` per point

    def __init__(self, data: Mapping[str, Any], native: Any = None) -> None:
        super().__init__(data)
        object.__setattr__(self, "_native", native)

    @property
    def laws(self) -> Optional[Laws]:
        """The base scene's laws and modelling choices (from its ``scene`` echo; a map axis
        may vary one of them point by point)."""
        laws = self._native.laws()
        return None if laws is None else Laws(laws)

    def keys(self) -> List[str]:
        return [k for k in self.__dict__ if not k.startswith("_")]

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, DesignMap):
            return NotImplemented
        return self.to_json() == other.to_json()

    def to_dict(self) -> Dict[str, Any]:
        d = super().to_dict()
        d.pop("_native", None)
        return d

    def column(self, name: str) -> np.ndarray:
        """One field of every point as a numpy array in index order (float with NaN where
        a point has none, bool for flags, object otherwise)."""
        cells = [getattr(p, name) for p in self.points]
        if all(isinstance(c, bool) for c in cells):
            return np.asarray(cells, dtype=bool)
        if all(c is None or (isinstance(c, (int, float)) and not isinstance(c, bool)) for c in cells):
            return np.asarray([np.nan if c is None else c for c in cells], dtype=float)
        return np.asarray(cells, dtype=object)

    def values_of(self, field: str) -> np.ndarray:
        """The values of a varied field at every point (SI), in index order: floats, or
        the words (str, dtype object) of a categorical axis."""
        cells = [p.values[field] for p in self.points]
        if any(isinstance(c, str) for c in cells):
            return np.asarray(cells, dtype=object)
        return np.asarray(cells, dtype=float)

    def to_json(self) -> str:
        """map.json exactly as ``stiction design map`` writes it."""
        return self._native.to_json()

    def to_csv(self) -> str:
        """map.csv exactly as ``stiction design map`` writes it."""
        return self._native.to_csv()

    def to_svg(self) -> str:
        """map.svg exactly as ``stiction design map`` writes it."""
        return self._native.to_svg()

    def table(self) -> str:
        """The table ``stiction design map`` prints."""
        return self._native.table()

    def save(self, folder: Any) -> List[str]:
        """Writes the files of ``stiction design map --out`` to `folder`, byte for byte
        (map.csv, map.json, map.svg; with a model-form check model_form.json and
        model_form.svg), as the command writes them: the folder is replaced as a whole and
        may hold only those files (else InputError), each file whole, a FIFO or device
        never replaced. Returns the paths written."""
        import os

        return _saved(self._native.save(os.fspath(folder)))

    def to_xarray(self) -> Any:
        """The map as an ``xarray.Dataset`` on its grid: one dimension per varied field
        (its values, or its words on a categorical axis, as the coordinate, with the unit
        in ``attrs["units"]``), and the points' ``pull_out_ratio``, ``largest_pull_out_pa``,
        ``restoring_pressure_pa``, ``contact_resistance``, ``real_contact_fraction``
        (NaN where a point has none or a shard lacks it), ``sticks``, ``closes``,
        ``validity_holds`` (NaN-able floats 1/0), ``cycles_to_accommodation`` and
        ``first_sticking_cycle`` (counts, NaN where none), ``status`` and
        ``accommodation_cause`` (words; "" where absent): every column of map.csv.
        xarray is imported here (ImportError naming it when missing)."""
        xr = _xarray()
        axes = self.grid["axes"]
        units = self._native.units()
        dims = [a["field"] for a in axes]
        shape = tuple(int(a["n"]) for a in axes)
        coords = {}
        for a in axes:
            if a.get("words") is not None:
                values = np.asarray(a["words"], dtype=object)
                unit = "-"
            else:
                values = np.asarray(a["values"], dtype=float)
                unit = units.get(a["field"], "-")
            coords[a["field"]] = (a["field"], values, {"units": unit})
        numbers = {
            "pull_out_ratio": "-",
            "largest_pull_out_pa": "Pa",
            "restoring_pressure_pa": "Pa",
            "contact_resistance": "ohm",
            "real_contact_fraction": "-",
            "sticks": "-",
            "closes": "-",
            "validity_holds": "-",
            "cycles_to_accommodation": "count",
            "first_sticking_cycle": "count",
        }
        data = {}
        for name, unit in numbers.items():
            grid = np.full(shape, np.nan)
            for p in self.points:
                v = getattr(p, name)
                if v is not None:
                    grid.flat[p.index] = float(v)
            data[name] = (dims, grid, {"units": unit})
        for name in ("status", "accommodation_cause"):
            words = np.full(shape, "", dtype=object)
            for p in self.points:
                words.flat[p.index] = getattr(p, name) or ""
            data[name] = (dims, words)
        return xr.Dataset(data, coords=coords, attrs={"accuracy": self.accuracy, "format": self.format})


class ThresholdResult(_Tabled, Record):
    """The critical value of one scene field (``stiction design threshold``): where the
    pull-out ratio after accommodation crosses 1."""

    parameter: str  #: the varied field
    critical_value: Optional[float]  #: in the field's unit
    free_side: Optional[str]  #: above | below: where the switch is free of stiction
    kind: Optional[str]  #: continuous | closure | ...
    uncertainty: Optional[float]  #: of the critical value
    ratio_at_from: Optional[float]
    ratio_at_to: Optional[float]
    evaluations: int  #: design points run
    from_: float  #: one end of the range
    to: float  #: the other end
    spacing: str  #: lin | log scan
    tolerance: float  #: relative tolerance of the root
    ratio_rel_error: float  #: relative error of the ratio at this accuracy
    crossings: List[Dict[str, Any]]  #: every crossing of 1 found
    closure_boundary: Optional[Dict[str, Any]]
    closure_boundaries: List[Dict[str, Any]]
    scan: Table  #: value, status, pull_out_ratio, closes, validity_holds (, contact_resistance, ...)
    requirement: Optional[Dict[str, Any]]  #: with ``require``: requirement, crossings, window
    accuracy: str
    laws: Laws  #: the base scene's laws and modelling choices
    scene: Dict[str, Any]  #: the base scene as run (design settings applied)
    unit: Optional[str]  #: SI unit of the field
    validity: Validity
    warnings: List[ModelWarning]
    model_form: Optional[Dict[str, Any]]  #: the model-form check: critical value per combination, ``critical_range``


# ---------------------------------------------------------------- probability


class Estimate(Record):
    """A probability with its exact binomial (Clopper-Pearson) interval."""

    count: int  #: counted samples with the outcome
    probability: Optional[float]  #: count / counted samples (None when nothing was counted)
    ci_low: float  #: lower end of the interval (0 when nothing was counted)
    ci_high: float  #: upper end (1 when nothing was counted)


class ProbabilityCounts(Record):
    """The samples of a probability run by outcome. ``sticks + free + does_not_close``
    are the counted samples (the denominator); the others are counted apart."""

    sticks: int  #: counted samples that stick at some cycle
    free: int  #: counted samples that close and never stick
    does_not_close: int  #: counted samples whose electrode never reaches contact
    outside_validity: int  #: ran, outside the model's validity (apart)
    out_of_domain: int  #: a value out of a field's domain (apart; never clipped)
    failed: int  #: failed numerically (apart)
    not_accommodated: int  #: counted closing samples that reached the cycle cap first
    near_threshold: int  #: counted closing samples with a ratio within the mode's error of 1


class Stopping(Record):
    """How a probability run stopped."""

    rule: str  #: samples (all requested ran) | target_halfwidth (stopped early)
    samples_requested: int  #: the samples asked for (the cap with a target half-width)
    target_halfwidth: Optional[float]  #: the target half-width of the stiction interval
    halfwidth: float  #: the half-width reached
    target_met: Optional[bool]  #: None without a target


class CycleProbabilities(Table):
    """P(stuck by cycle n), one row per cycle n = 1 .. the scene's cycles: ``cycle``
    (int), ``probability``, ``ci_low``, ``ci_high`` (Clopper-Pearson, pure numbers) and
    ``sticking`` (samples stuck by that cycle, int)."""

    _units = {"cycle": "-", "probability": "-", "ci_low": "-", "ci_high": "-", "sticking": "-"}
    cycle: np.ndarray
    probability: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    sticking: np.ndarray


class RankCorrelations(Table):
    """Spearman's rank correlation of each scattered field with the pull-out ratio (over
    the counted samples that close): ``field``, ``spearman`` (NaN when undefined),
    ``ci_low``, ``ci_high`` (approximate, Fisher z), ``samples`` (pairs used)."""

    _units = {"field": "", "spearman": "-", "ci_low": "-", "ci_high": "-", "samples": "-"}


class ExactAnswer(Record):
    """The exact single-field answer: the field's threshold (``design threshold`` over its
    quantiles 1e-6 .. 1 - 1e-6) and the distribution's CDF there, when the ratio is
    monotone in the field."""

    field: str  #: the scattered field
    available: bool  #: whether there is an exact answer (else ``reason``)
    reason: Optional[str]  #: why there is none
    monotone: bool  #: the ratio is monotone in the field over the range
    direction: Optional[str]  #: increasing | decreasing: the ratio in the field
    stiction_probability: Optional[float]  #: F(critical value) or 1 - F(critical value)
    uncertainty: Optional[float]  #: from the critical value's uncertainty (density x it)
    does_not_close_probability: Optional[float]  #: the mass beyond the closure boundary
    does_not_close_uncertainty: Optional[float]
    critical_value: Optional[float]  #: where the ratio crosses 1 (the field's SI unit)
    free_side: str  #: above | below | unknown: where the switch is free of stiction
    boundaries: List[Dict[str, Any]]  #: kind, value, uncertainty, cdf, side, crossing
    range: np.ndarray  #: the searched range [lo, hi] (the field's SI unit)
    tail_mass: float  #: the distribution's mass outside the range
    evaluations: int  #: design points run
    scan_outside_validity: Optional[int]  #: scan points outside the model's validity


class ProbabilitySample(MapPoint):
    """One sample of a probability run (a row of samples.csv, a point of
    probability.json): its field values drawn from (seed, index) alone, its status and its
    design point (None where the sample has none: out of domain, failed)."""


class ProbabilityResult(Record):
    """The probability of stiction under process scatter (``stiction design
    probability``): every sample a design point of the scene at its scattered values.
    Probabilities are over the *counted* samples (``denominator``: inside the model's
    validity, ``ok`` or ``does_not_close``); the others are counted apart
    (``outside_validity``, ``counts``). ``to_json()`` and ``to_csv()`` are the command's
    probability.json and samples.csv, byte for byte; ``save(folder)`` writes them."""

    format: str  #: "stiction-design-probability"
    version: int
    samples: int  #: samples run (all statuses)
    stiction_probability: Optional[float]  #: P(stiction after accommodation) (None: nothing counted)
    ci_low: float  #: its Clopper-Pearson lower end
    ci_high: float  #: its upper end
    confidence: float  #: of every interval (0.95 unless asked)
    does_not_close_probability: Optional[float]  #: P(the switch does not close)
    outside_validity: int  #: samples outside the model's validity (counted apart unless count_outside_validity)
    count_outside_validity: bool  #: whether the headline counts the samples outside validity
    all_samples: Dict[str, Any]  #: P over every sample that ran: ``denominator``, ``outside_validity``, ``stiction`` and ``does_not_close`` (probability, ci_low, ci_high)
    by_cycle: CycleProbabilities  #: P(stuck by cycle n) with its interval, n = 1 .. cycles
    denominator: int  #: the counted samples
    stiction: Estimate  #: the stiction estimate with its count
    does_not_close: Estimate  #: the does-not-close estimate with its count
    counts: ProbabilityCounts  #: samples by outcome
    rank_correlation: RankCorrelations  #: Spearman's rho of each field with the pull-out ratio
    driver: Optional[str]  #: the field of largest |rho|: the one that drives failure most
    stopping: Stopping  #: how the run stopped
    exact_inside_interval: Optional[bool]  #: whether the exact answer lies in the interval
    exact: Optional[ExactAnswer]  #: with a single scattered field (unless exact=False)
    accuracy: str  #: accuracy mode of the samples
    ratio_rel_error: float  #: relative error of the ratio in that mode
    scatter: List[str]  #: the scattered fields, ``FIELD=DIST`` (SI)
    correlate: List[str]  #: the correlations, ``A,B=RHO``
    seed: int  #: sample i's values depend on (seed, i) alone
    samples_requested: int
    cycles: int  #: the scene's cycle cap
    target_halfwidth: Optional[float]
    shard: Optional[Dict[str, Any]]  #: this run's part K of N, for a shard
    scene: Dict[str, Any]  #: the scene as run (design settings applied)
    points: List[ProbabilitySample]  #: every sample, in index order
    warnings: List[ModelWarning]  #: guards the samples raised (one per kind, with counts)
    validity: Optional[Validity]  #: whether the model holds at every sample (None when read back or merged)
    model_form: Optional[Dict[str, Any]]  #: the model-form check: P(stiction) per combination, ``stiction_probability_range``

    def __init__(self, data: Mapping[str, Any], native: Any = None) -> None:
        super().__init__(data)
        object.__setattr__(self, "_native", native)

    @property
    def laws(self) -> Optional[Laws]:
        """The base scene's laws and modelling choices (from its ``scene`` echo)."""
        laws = self._native.laws()
        return None if laws is None else Laws(laws)

    def keys(self) -> List[str]:
        return [k for k in self.__dict__ if not k.startswith("_")]

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ProbabilityResult):
            return NotImplemented
        return self.to_json() == other.to_json()

    def to_dict(self) -> Dict[str, Any]:
        d = super().to_dict()
        d.pop("_native", None)
        return d

    def column(self, name: str) -> np.ndarray:
        """One field of every sample as a numpy array in index order (float with NaN where
        a sample has none, bool for flags, object otherwise)."""
        cells = [getattr(p, name) for p in self.points]
        if cells and all(isinstance(c, bool) for c in cells):
            return np.asarray(cells, dtype=bool)
        if all(c is None or (isinstance(c, (int, float)) and not isinstance(c, bool)) for c in cells):
            return np.asarray([np.nan if c is None else c for c in cells], dtype=float)
        return np.asarray(cells, dtype=object)

    def values_of(self, field: str) -> np.ndarray:
        """The values of a scattered field at every sample (SI), in index order."""
        return np.asarray([p.values[field] for p in self.points], dtype=float)

    def counted(self) -> np.ndarray:
        """Whether each sample is in the denominator (bool array, index order)."""
        return np.asarray(
            [p.status in ("ok", "does_not_close") and bool(p.validity_holds) for p in self.points], dtype=bool
        )

    def to_json(self) -> str:
        """probability.json exactly as ``stiction design probability --out`` writes it."""
        return self._native.to_json()

    def summary_json(self) -> str:
        """What ``stiction design probability --format json`` prints (no samples)."""
        return self._native.summary_json()

    def to_csv(self) -> str:
        """samples.csv exactly as ``stiction design probability --out`` writes it."""
        return self._native.to_csv()

    def to_svg(self) -> str:
        """probability.svg exactly as ``stiction design probability --out`` writes it."""
        return self._native.to_svg()

    def table(self) -> str:
        """The table ``stiction design probability`` prints."""
        return self._native.table()

    def save(self, folder: Any) -> List[str]:
        """Writes the files of ``stiction design probability --out`` to `folder`, byte for
        byte: samples.csv, probability.json, probability.svg (and model_form.json with a
        model-form check), as the command writes them (the folder replaced as a whole; it
        may hold only those files, else InputError): a folder ``stiction design merge``
        reads. Returns the paths written."""
        import os

        return _saved(self._native.save(os.fspath(folder)))


# ---------------------------------------------------------------- contact law


class Histories(Record):
    """How the tabulated histories d_min were chosen."""

    rule: str  #: adaptive | uniform FROM:TO:N
    d_min_lo: float  #: deepest tabulated history (m)
    d_min_hi: float  #: shallowest (m)
    deepest_d_e: Optional[float]  #: deepest end of impact of the scene's cycles (m)
    cycles_d_e: Optional[np.ndarray]  #: the cycles' d_e (m)
    below_deepest_d_e: Optional[float]  #: m
    first_touch_reference: Optional[float]  #: Pa
    first_touch_fraction: Optional[float]
    virgin_reach: float  #: where the first asperity jumps in on a virgin approach (m)
    description: str


class LawResult(_Saved, Record):
    """A tabulation of the contact law (``stiction law``); ``law`` is the
    :class:`stiction.ContactLaw` itself (``law.save(path)`` writes law.json)."""

    title: str
    laws: Laws
    validity: Validity
    accuracy: Targets
    sigma_s: float  #: m
    histories: Histories
    branches: int  #: number of tabulated histories
    virgin_nodes: int
    nodes: int
    tolerance: float  #: refinement tolerance
    measured_error: Dict[str, Any]  #: interpolation error measured against the surface
    partial_reload: Dict[str, Any]  #: error of the one-number history after a partial reload
    partial_reload_turn_fractions: np.ndarray
    source_evaluations: int  #: surface pressure evaluations
    converged: bool
    seconds: float  #: wall time (s)
    law_json_bytes: int
    summary: Table  #: per history: d_min, start_pressure, pull_out_d, pull_out_pressure, ...
    warnings: List[ModelWarning]
    law: Any  #: the tabulated law (stiction.ContactLaw)

    def to_dict(self) -> Dict[str, Any]:
        """The summary as plain data, equal to ``stiction law --format json``; the law itself
        (``law``, a :class:`stiction.ContactLaw`) is left out: ``law.to_json()`` is its
        law.json."""
        d = super().to_dict()
        d.pop("law", None)
        return d


class LawEvaluation(Record):
    """Values of a contact law at arrays of separations (``ContactLaw.evaluate``), each of
    the separations' shape."""

    pressure: np.ndarray  #: p (Pa), compressive positive, adhesive negative
    tangent: np.ndarray  #: dp/dd at fixed history (Pa/m)
    d_min: np.ndarray  #: the history after the call (m): d where d < the d_min given
    retract: np.ndarray  #: True where the path after the call is retract

    @property
    def path(self) -> np.ndarray:
        """The path after the call, "approach" | "retract" per point."""
        return np.where(self.retract, "retract", "approach")


class PlasticState(Record):
    """The plastic state of an asperity after loading to delta_max (eqs 4-5)."""

    delta_res: Any  #: residual height loss (m)
    r_res: Any  #: residual radius (m)
    extrapolated: Any  #: delta_max beyond the fits' range


class PullOut(Record):
    """The pull-out of a rough surface pressed to d_min."""

    pressure: float  #: magnitude of the most tensile pressure (Pa, >= 0)
    separation: float  #: where (m)
    error: float  #: error estimate (Pa)


# ---------------------------------------------------------------- calibration


class CalibrationResult(_Drawn, Record):
    """A calibration of eq 13 to finite-element curves (``stiction calibrate``). Besides
    the fields below it carries every key of the library's fit report."""

    title: str
    laws: Laws
    model: Dict[str, Any]  #: work_of_adhesion (J/m^2), z0 (m), radius (m)
    fe_file: str
    data_points: int
    ignored_columns: List[str]
    c1: np.ndarray  #: fitted [a1, a2, a3] of eq 13
    c2: np.ndarray  #: fitted [b1, b2, b3]
    start_c1: np.ndarray
    start_c2: np.ndarray
    residual_rms_n: float  #: RMS residual force (N)
    converged: bool
    scene_fragment: str  #: a [contact.effective_radius] table to paste into a scene
    warnings: List[ModelWarning]
    scene: Dict[str, Any]
    points: Table  #: every data point with the model's force: delta_max, branch, delta, force, model_force
    overlay: List[Dict[str, Any]]  #: data and model per curve (with overlay=True)


class TopographyResult(_Saved, Record):
    """A measured height map reduced to the scene's Greenwood-Williamson parameters
    (``stiction topography FILE``): the report's fields as attributes (``rms_height``,
    ``moments``, ``spectral``, ``summits``, ``grid``, ``source`` ...), ``to_dict()`` the
    command's JSON (``heights`` there: the heights' skewness and kurtosis); beside it
    ``height_map`` (the map as read, m, rows = y, a numpy array),
    ``dx``, ``dy`` (m) and ``fragment``, the ``[surface]`` scene fragment (TOML text, what
    ``--out`` writes as surface.toml), with ``fragment_warnings``."""

    @classmethod
    def _of_native(cls, native: Mapping[str, Any]) -> "TopographyResult":
        r = cls(native["report"])
        object.__setattr__(r, "_report", native["_report"])
        object.__setattr__(r, "_height_map", native["heights"])
        for name in ("dx", "dy", "fragment"):
            object.__setattr__(r, "_" + name, native[name])
        object.__setattr__(r, "_fragment_warnings", list(native["warnings"]))
        return r

    @property
    def height_map(self) -> np.ndarray:
        """The height map as read, before detrending (m), rows = y."""
        return self._height_map  # type: ignore[attr-defined, no-any-return]

    @property
    def dx(self) -> float:
        """Grid spacing in x (m)."""
        return self._dx  # type: ignore[attr-defined, no-any-return]

    @property
    def dy(self) -> float:
        """Grid spacing in y (m)."""
        return self._dy  # type: ignore[attr-defined, no-any-return]

    @property
    def fragment(self) -> str:
        """The ``[surface]`` scene fragment (TOML), values outside a key's domain commented."""
        return self._fragment  # type: ignore[attr-defined, no-any-return]

    @property
    def fragment_warnings(self) -> List[Tuple[str, str]]:
        """(code, message) of each value the fragment left out."""
        return self._fragment_warnings  # type: ignore[attr-defined, no-any-return]
