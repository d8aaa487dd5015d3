from typing import Any, Callable, Iterable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

Label = Union[int, str]
Progress = Callable[[str, str], None]

class Error(RuntimeError): ...

class Mesh:
    @property
    def points(self) -> npt.NDArray[np.float64]: ...
    @property
    def triangles(self) -> npt.NDArray[np.int32]: ...
    @property
    def phases(self) -> npt.NDArray[np.int32]: ...
    @property
    def phase_names(self) -> list[str]: ...
    @property
    def phase_labels(self) -> list[int]: ...
    @property
    def num_triangles(self) -> int: ...
    def validate(self) -> list[str]: ...
    def junctions(self) -> list[dict[str, Any]]: ...
    def stats_json(self) -> str: ...
    def stats(self) -> dict[str, Any]: ...
    def write(self, path: str, ascii: bool = False) -> None: ...
    def to_meshio(self) -> Any: ...

def mesh_labels(labels: npt.NDArray[np.integer], spacing: Sequence[float] = (1.0, 1.0, 1.0),
                origin: Sequence[float] = (0.0, 0.0, 0.0), *, iterations: int = 20, pipeline: str = "",
                size: float = 0.0, tolerance: float = 0.0, min_size: float = 0.0, threads: int = 0, close: bool = False, grid: Union[int, Sequence[int], None] = None,
                lattice: str = "bcc", snap: float = 0.2, top_k: int = 4, validate: bool = True,
                stop_when_converged: bool = False, crossing_guard: bool = True,
                drop_labels: Iterable[Label] = (), keep_labels: Iterable[Label] = (),
                merge_labels: Iterable[Iterable[Label]] = (), background: int = 0, no_background: bool = False,
                signed_distance: bool = False, smoothing: float = 1.0, band: float = 3.0,
                progress: Optional[Progress] = None) -> Mesh: ...

def mesh_values(values: Union[npt.NDArray[np.floating], Sequence[npt.NDArray[np.floating]]],
                spacing: Sequence[float] = (1.0, 1.0, 1.0), origin: Sequence[float] = (0.0, 0.0, 0.0),
                names: Sequence[str] = (), labels: Sequence[int] = (), *, iterations: int = 20, pipeline: str = "",
                size: float = 0.0, tolerance: float = 0.0, min_size: float = 0.0, threads: int = 0, close: bool = False, grid: Union[int, Sequence[int], None] = None,
                lattice: str = "bcc", snap: float = 0.2, top_k: int = 4, validate: bool = True,
                stop_when_converged: bool = False, crossing_guard: bool = True,
                progress: Optional[Progress] = None) -> Mesh: ...

def mesh_file(path: str, *, iterations: int = 20, pipeline: str = "", size: float = 0.0, tolerance: float = 0.0, min_size: float = 0.0, threads: int = 0,
              close: bool = False, grid: Union[int, Sequence[int], None] = None, lattice: str = "bcc",
              snap: float = 0.2, top_k: int = 4, validate: bool = True, stop_when_converged: bool = False,
              crossing_guard: bool = True, drop_labels: Iterable[Label] = (), keep_labels: Iterable[Label] = (),
              merge_labels: Iterable[Iterable[Label]] = (), background: int = 0, no_background: bool = False,
              signed_distance: bool = False, smoothing: float = 1.0, band: float = 3.0,
              voxels_per_cell: float = 1.0, ignore_direction: bool = False, world: str = "file",
              progress: Optional[Progress] = None) -> Mesh: ...

class Mesher:
    """One set of options (those of mesh_file(), checked here) for input after input."""
    def __init__(self, **options: Any) -> None: ...  # the keywords of mesh_file()
    def mesh_labels(self, labels: npt.NDArray[np.integer], spacing: Sequence[float] = (1.0, 1.0, 1.0),
                    origin: Sequence[float] = (0.0, 0.0, 0.0)) -> Mesh: ...
    def mesh_values(self, values: Union[npt.NDArray[np.floating], Sequence[npt.NDArray[np.floating]]],
                    spacing: Sequence[float] = (1.0, 1.0, 1.0), origin: Sequence[float] = (0.0, 0.0, 0.0),
                    names: Sequence[str] = (), labels: Sequence[int] = ()) -> Mesh: ...
    def mesh_file(self, path: str) -> Mesh: ...
    @property
    def meshes_made(self) -> int: ...

def output_extensions() -> list[str]: ...
