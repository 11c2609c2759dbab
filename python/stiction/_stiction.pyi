"""Type stubs of the extension module ``stiction._stiction`` (Rust, PyO3), the layer under
the public API of ``stiction`` (whose modules are typed Python: ``__init__.py``,
``_laws.py``, ``_results.py``). Units are SI (m, N, Pa, Pa/m, J/m^2, V) unless said.

Array arguments take any array-like of numbers (scalar, list, ndarray of any shape and
numeric dtype); results have the shape of the first array argument (a float for a
scalar). Errors raise ``stiction.InputError`` or ``stiction.NumericalError``.
"""

from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union
import os

import numpy as np
from numpy.typing import ArrayLike, NDArray

__version__: str

_SceneLike = Union["Scene", str, "os.PathLike[str]", Mapping[str, Any]]
_Array = Union[float, NDArray[np.float64]]
_BoolArray = Union[bool, NDArray[np.bool_]]

class Scene:
    """A scene as written (TOML/JSON keys, SI units) with the name of its source."""

    @staticmethod
    def paper(kind: str = "switch") -> Scene:
        """The embedded paper scene of `kind` ("asperity", "surface", "switch")."""
    @staticmethod
    def from_toml(text: str, file: str = "<toml>") -> Scene:
        """A scene from TOML text (not validated)."""
    @staticmethod
    def from_json(text: str, file: str = "<json>") -> Scene:
        """A scene from JSON text (not validated)."""
    @property
    def kind(self) -> str:
        """"asperity" | "surface" | "switch"."""
    @property
    def file(self) -> str:
        """The name of the source in messages."""
    @property
    def title(self) -> str:
        """The scene's title, else the file name."""
    def get(self, key: str, default: Any = None) -> Any:
        """The value of `key` ("section.key") as written."""
    def set(self, key: str, value: Any) -> None:
        """Sets `key` in place (checked when validated or run)."""
    def remove(self, key: str) -> None:
        """Removes `key` in place."""
    def with_values(self, values: Mapping[str, Any]) -> Scene:
        """A validated copy with these keys set (None removes a key)."""
    def validate(self) -> None:
        """Validates every key (raises InputError naming the key)."""
    def resolved(self) -> Dict[str, Any]:
        """Every key with the value it resolves to (defaults filled in)."""
    def to_toml(self) -> str:
        """The scene as TOML text."""
    def to_dict(self) -> Dict[str, Any]:
        """The keys and values as a dict."""
    def copy(self) -> Scene: ...
    def __copy__(self) -> Scene: ...
    def __deepcopy__(self, _memo: Any) -> Scene: ...
    def __eq__(self, other: object) -> bool: ...
    def __reduce__(self) -> Tuple[Any, Tuple[str, str]]: ...

def load_scene(source: _SceneLike) -> Scene:
    """A scene from a TOML/JSON path, a dict or a Scene, validated by the library."""

def scene_keys(kind: Optional[str] = None) -> List[Dict[str, Any]]:
    """The key registry: key, unit, accepts, default, meaning, scenes."""

def variable_fields() -> List[str]:
    """The fields a design map or threshold may vary."""

def run(
    scene: _SceneLike,
    accuracy: Optional[str] = None,
    progress: Optional[Callable[[int, int], None]] = None,
) -> Tuple[str, Dict[str, Any]]:
    """(kind, result as Python data) of a scene of any kind (its NativeReport under
    ``_report``); `progress(done, total)` as cycles complete; Ctrl-C raises
    KeyboardInterrupt within a fraction of a second."""

class NativeReport:
    """A result kept for its presentation (stiction-report, the command line's)."""

    def table(self) -> str: ...
    def csv(self) -> str: ...
    def to_svg(self) -> str: ...
    def dynamics_svg(self) -> Optional[str]: ...
    def file_names(self) -> Optional[List[str]]: ...
    def save(self, dir: str) -> List[str]:
        """The command line's --out files, byte for byte; the paths written."""

def md_curve(lam: float, points: int = 200, delta_end: float = 5.0) -> Dict[str, Any]:
    """The nondimensional Maugis-Kim curve of lambda and its landmarks."""

def maugis_kim_force(lam: float, delta: ArrayLike, path: str = "approach", from_: Optional[float] = None) -> _Array:
    """Fbar = F/(pi w R) at Delta = delta/(pi^2 w^2 R/K^2)^(1/3) (eqs 7-11, Kim extension)."""

def calibrate(
    scene: _SceneLike,
    fe: Optional[str] = None,
    fe_text: Optional[str] = None,
    fe_name: str = "<columns>",
    fit: str = "c1,c2",
    overlay: bool = False,
) -> Dict[str, Any]:
    """The fit of eq 13 to FE curves (a CSV path, or CSV text)."""

class AdhesionLaw:
    """An adhesion law of one elastic sphere: F (N) at delta (m) for radius R (m)."""

    @staticmethod
    def maugis_kim(k: float, work_of_adhesion: float, z0: float) -> AdhesionLaw: ...
    @staticmethod
    def jkr(k: float, work_of_adhesion: float) -> AdhesionLaw: ...
    @staticmethod
    def dmt(k: float, work_of_adhesion: float, z0: float) -> AdhesionLaw: ...
    @staticmethod
    def hertz(k: float) -> AdhesionLaw: ...
    @staticmethod
    def of_scene(scene: _SceneLike) -> AdhesionLaw: ...
    @property
    def name(self) -> str: ...
    def force(self, delta: ArrayLike, radius: ArrayLike, path: str = "approach", from_: Optional[float] = None) -> _Array: ...
    def jumps(self, radius: float) -> Tuple[float, float]: ...

class Asperity:
    """The elasto-plastic adhesive asperity of a scene's contact section."""

    def __init__(self, scene: _SceneLike, elastic: bool = False) -> None: ...
    @property
    def delta_cp(self) -> float: ...
    @property
    def radius(self) -> float: ...
    def force(
        self, delta: ArrayLike, delta_max: Optional[ArrayLike] = None, path: str = "approach", from_: Optional[float] = None
    ) -> _Array: ...
    def pull_off(self, delta_max: ArrayLike) -> Tuple[_Array, _Array]: ...
    def state(self, delta_max: ArrayLike) -> Dict[str, Any]: ...
    def jumps(self, delta_max: Optional[float] = None) -> Tuple[float, float]: ...

class Surface:
    """The Greenwood-Williamson rough surface of a surface or switch scene."""

    def __init__(self, scene: _SceneLike, accuracy: Optional[str] = None, elastic: bool = False) -> None: ...
    @property
    def sigma_s(self) -> float: ...
    @property
    def accuracy(self) -> str: ...
    def pressure(
        self, d: ArrayLike, d_min: Optional[ArrayLike] = None, path: str = "approach", from_: Optional[float] = None
    ) -> _Array: ...
    def pressure_estimate(
        self, d: ArrayLike, d_min: Optional[ArrayLike] = None, path: str = "approach", from_: Optional[float] = None
    ) -> Tuple[_Array, _Array]: ...
    def reach(self, d_min: Optional[float] = None, path: str = "approach", from_: Optional[float] = None) -> float: ...
    def pull_out(self, d_min: float) -> Dict[str, float]: ...

def design_threshold(
    scene: _SceneLike,
    vary: str,
    from_: float,
    to: float,
    accuracy: Optional[str] = None,
    require: Optional[str] = None,
    progress: Optional[Callable[[int, int], None]] = None,
) -> Dict[str, Any]:
    """The critical value of one field (a dict of the threshold's fields); `progress` as
    design points are evaluated."""

class NativeMap:
    """A computed design map (whole, a shard, merged)."""

    def to_json(self) -> str: ...
    def to_csv(self) -> str: ...
    def to_svg(self) -> str: ...
    def table(self) -> str: ...
    def save(self, dir: str) -> List[str]: ...
    def units(self) -> Dict[str, str]: ...
    def laws(self) -> Optional[Dict[str, Any]]: ...
    def data(self) -> Dict[str, Any]: ...

def design_map(
    scene: _SceneLike,
    vary: Sequence[str],
    accuracy: Optional[str] = None,
    shard: Optional[str] = None,
    require: Optional[str] = None,
    progress: Optional[Callable[[int, int], None]] = None,
) -> NativeMap:
    """A map with its points run here (rayon); `progress` as points complete."""

def design_map_plan(
    scene: _SceneLike,
    vary: Sequence[str],
    accuracy: Optional[str] = None,
    shard: Optional[str] = None,
    require: Optional[str] = None,
) -> Tuple[str, List[Tuple[int, List[Tuple[str, Union[float, str]]]]]]:
    """(base scene TOML, [(index, [(field, value)])]) of a map, checked; a value is a
    float, or the word of a categorical axis."""

def design_point(
    base: str, values: Sequence[Tuple[str, Union[float, str]]]
) -> Tuple[str, Optional[Dict[str, Any]], Optional[str], List[Tuple[str, str, bool]]]:
    """One design point as a worker evaluates it: (status, design, message, warnings)."""

def design_map_assemble(
    scene: _SceneLike,
    vary: Sequence[str],
    answers: List[Tuple[int, Any]],
    accuracy: Optional[str] = None,
    shard: Optional[str] = None,
    require: Optional[str] = None,
) -> NativeMap:
    """The map of the workers' answers."""

def design_merge(parts: List[Union[NativeMap, str]]) -> NativeMap:
    """The merge of a map's shards."""

def model_form_scenes(
    scene: _SceneLike, accuracy: Optional[str] = None
) -> Optional[Tuple[str, List[Tuple[Dict[str, str], Scene]], str]]:
    """(mode, [(form, scene)], excluded as JSON) of a checked design question, None unchecked."""

def with_map_model_form(
    own: NativeMap, accuracy: str, forms: List[Tuple[Dict[str, str], NativeMap]], excluded: str
) -> NativeMap:
    """The map with its model-form check from the other combinations' maps."""

def read_map(path: str) -> NativeMap:
    """A map.json."""

class NativeProbability:
    """A computed probability run (whole, a shard, merged)."""

    def to_json(self) -> str:
        """probability.json, byte for byte the command's."""
    def summary_json(self) -> str:
        """What ``--format json`` prints: probability.json without the samples."""
    def to_csv(self) -> str:
        """samples.csv, byte for byte the command's."""
    def to_svg(self) -> str:
        """probability.svg, byte for byte the command's."""
    def table(self) -> str: ...
    def save(self, dir: str) -> List[str]:
        """The --out files (samples.csv, probability.json, probability.svg[, model_form.json])."""
    def laws(self) -> Optional[Dict[str, Any]]: ...
    def data(self) -> Dict[str, Any]:
        """probability.json's keys as Python data, plus warnings and validity."""

def design_probability(
    scene: _SceneLike,
    scatter: Sequence[str],
    samples: int = 1000,
    seed: int = 0,
    correlate: Optional[Sequence[str]] = None,
    confidence: float = 0.95,
    accuracy: Optional[str] = None,
    shard: Optional[str] = None,
    target_halfwidth: Optional[float] = None,
    exact: bool = True,
    count_outside_validity: bool = False,
    progress: Optional[Callable[[int, int], None]] = None,
) -> NativeProbability:
    """A probability run with its samples run here (rayon): ``scatter`` FIELD=DIST in the
    field's SI unit, ``correlate`` A,B=RHO."""

def design_probability_plan(
    scene: _SceneLike,
    scatter: Sequence[str],
    samples: int = 1000,
    seed: int = 0,
    correlate: Optional[Sequence[str]] = None,
    confidence: float = 0.95,
    accuracy: Optional[str] = None,
    shard: Optional[str] = None,
    target_halfwidth: Optional[float] = None,
    count_outside_validity: bool = False,
) -> Tuple[str, List[Tuple[int, List[Tuple[str, float]]]]]:
    """(design scene TOML, [(index, [(field, value)])]) of a probability run, checked."""

def design_probability_assemble(
    scene: _SceneLike,
    scatter: Sequence[str],
    answers: List[Tuple[int, Any]],
    samples: int = 1000,
    seed: int = 0,
    correlate: Optional[Sequence[str]] = None,
    confidence: float = 0.95,
    accuracy: Optional[str] = None,
    shard: Optional[str] = None,
    target_halfwidth: Optional[float] = None,
    exact: bool = True,
    count_outside_validity: bool = False,
) -> NativeProbability:
    """The probability run of the workers' answers."""

def with_probability_model_form(
    own: NativeProbability, accuracy: str, forms: List[Tuple[Dict[str, str], NativeProbability]], excluded: str
) -> NativeProbability:
    """The run with its model-form check from the other combinations' runs."""

def design_merge_probability(parts: List[Union[NativeProbability, str]]) -> NativeProbability:
    """The merge of a probability run's shards."""

def read_probability(path: str) -> NativeProbability:
    """A probability.json."""

class ContactLaw:
    """A tabulated contact law p(d; d_min, path)."""

    @staticmethod
    def load(path: str) -> ContactLaw: ...
    @staticmethod
    def from_json(text: str) -> ContactLaw: ...
    def evaluate(
        self, d: ArrayLike, d_min: Optional[ArrayLike] = None, path: Any = None
    ) -> Tuple[_Array, _Array, _Array, _BoolArray]: ...
    def follow(
        self, d: ArrayLike, state: Optional[Mapping[str, Any]] = None
    ) -> Tuple[_Array, _Array, _Array, _BoolArray, Dict[str, Any]]: ...
    def virgin_pressure(self, d: ArrayLike) -> Tuple[_Array, _Array]: ...
    def reach(self, d_min: float, path: str = "approach") -> float: ...
    @property
    def d_min_range(self) -> Tuple[float, float]: ...
    @property
    def d_min_grid(self) -> NDArray[np.float64]: ...
    @property
    def length_scale(self) -> Optional[float]: ...
    @property
    def scene(self) -> Dict[str, Any]: ...
    @property
    def measured_error(self) -> Optional[Dict[str, Any]]: ...
    def to_json(self) -> str: ...
    def to_csv(self) -> str: ...
    def save(self, path: str) -> None: ...

def tabulate_law(
    scene: _SceneLike,
    d_min: Optional[str] = None,
    points: int = 96,
    tolerance: float = 2e-4,
    accuracy: Optional[str] = None,
    progress: Optional[Callable[[int, int], None]] = None,
) -> Tuple[Dict[str, Any], ContactLaw]:
    """(summary, law) of a tabulation; `progress` in thousandths of the work."""

def topography(
    path: str,
    file_format: Optional[str] = None,
    spacing: Optional[float] = None,
    height_unit: Optional[str] = None,
    xy_unit: Optional[str] = None,
    detrend: Optional[str] = None,
    route: Optional[str] = None,
    undefined: Optional[str] = None,
    channel: Optional[str] = None,
    cutoff: Optional[float] = None,
    contact_radius: Optional[float] = None,
) -> Dict[str, Any]:
    """The analysis of a height map: report, heights, dx, dy, fragment, warnings."""
