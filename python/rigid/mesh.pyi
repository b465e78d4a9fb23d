# Type stubs of rigid.mesh, generated from the built module's signatures by scripts/make_stubs.py:
# do not edit; rerun the script after changing a binding.
import os
from typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence

import numpy
from numpy.typing import NDArray

import rigid.mass


class _Pybind11Type(type):
    """The metaclass of the classes (pybind11_builtins.pybind11_type)."""


class TriangleMesh(metaclass=_Pybind11Type):
    """Indexed triangle mesh (vertices in m)."""
    def __init__(self, vertices: object, triangles: object) -> None:
        """A mesh from vertices (shape (n, 3), m, one vertex per row, any real dtype) and triangles (shape (m, 3), integer indices into the vertices; counter-clockwise seen from outside once oriented). Nothing is checked or repaired here: mass_properties refuses a mesh that is open or inconsistently wound."""
    @property
    def vertices(self) -> NDArray[numpy.float64]:
        """Vertex positions, an (n, 3) array (m)."""
    @property
    def triangles(self) -> NDArray[Any]:
        """Vertex indices of each triangle, an (m, 3) integer array."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __len__(self) -> int: ...
    def __repr__(self) -> str: ...
    @property
    def bounding_box(self) -> tuple[Any, ...]:
        """(min corner, max corner) of the vertices (m); zeros when empty."""
    def scale(self, factor: float) -> None:
        """Multiplies every vertex by factor (in place; e.g. 1e-3 for millimetres)."""
    def translate(self, d_M: object) -> None:
        """Moves every vertex by d_M (shape (3,), m; in place)."""
    def reverse_winding(self) -> None:
        """Reverses the winding of every triangle (flips all normals; in place)."""


class EdgeCounts(metaclass=_Pybind11Type):
    """Edges by how many triangles use them."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def boundary(self) -> int:
        """edges used by one triangle"""
    @property
    def non_manifold(self) -> int:
        """edges used by three or more"""
    @property
    def misoriented(self) -> int:
        """edges two triangles traverse in the same direction (inconsistent winding)"""
    def __repr__(self) -> str: ...


class ComponentReport(metaclass=_Pybind11Type):
    """One connected component of a repaired mesh."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def triangles(self) -> int:
        """Triangles in the component."""
    @property
    def boundary_edges(self) -> int:
        """Edges used by one triangle only (0 for a closed component)."""
    @property
    def volume(self) -> float:
        """Signed volume after orientation (m³; meaningful when closed)."""
    @property
    def area(self) -> float:
        """Surface area (m²)."""
    def __repr__(self) -> str: ...


class RepairReport(metaclass=_Pybind11Type):
    """What rigid.mesh.repair found and changed; str() is the text `rigid mesh check` prints."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def welded_vertices(self) -> int:
        """Vertices merged into another."""
    @property
    def degenerate_triangles(self) -> int:
        """Triangles removed: a repeated index or zero area."""
    @property
    def boundary_edges(self) -> int:
        """Edges used by exactly one triangle."""
    @property
    def non_manifold_edges(self) -> int:
        """Edges used by three or more triangles."""
    @property
    def reoriented_triangles(self) -> int:
        """Triangles flipped to agree with their neighbours."""
    @property
    def inverted_components(self) -> int:
        """Closed components with negative volume, flipped outward."""
    @property
    def tolerance_weld(self) -> bool:
        """True if the tolerance weld ran (after the exact weld left open edges)."""
    @property
    def components(self) -> list[ComponentReport]:
        """One ComponentReport per connected component."""
    @property
    def warnings(self) -> list[str]:
        """One sentence per problem left (open edges, non-manifold edges, ...)."""
    @property
    def closed(self) -> bool:
        """True when the mesh bounds a solid: every edge shared by exactly two triangles."""
    def __str__(self) -> str: ...
    def __repr__(self) -> str: ...


class FilledHole(metaclass=_Pybind11Type):
    """One hole closed by rigid.mesh.fill_holes."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def boundary_edges(self) -> int:
        """Edges of the hole's border loop."""
    @property
    def area(self) -> float:
        """Area of the patch that closes it (m²)."""
    def __repr__(self) -> str: ...


class HoleFillReport(metaclass=_Pybind11Type):
    """What rigid.mesh.fill_holes added."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def holes(self) -> list[FilledHole]:
        """One FilledHole per hole, in the order found."""
    @property
    def triangles_added(self) -> int:
        """Triangles added."""
    @property
    def vertices_added(self) -> int:
        """Vertices added (fan centres)."""
    @property
    def area(self) -> float:
        """Total area of the patches (m²)."""
    def __repr__(self) -> str: ...


def read(path: object, scale: float = ...) -> TriangleMesh:
    """Read an STL/OBJ/PLY/OFF file (a str or pathlib.Path; the format from the extension); coordinates multiplied by scale (m per file unit). Errors start with the file name."""


def write_stl(mesh: TriangleMesh, path: object) -> None:
    """Writes a binary STL (float32 coordinates, m) to path (a str or pathlib.Path), atomically: a new file renamed over the old one; a directory, FIFO, socket or device at path is refused, and a symlink is written through."""


def unit_scale(unit: str) -> float:
    """Metres per unit: m, cm, mm or in."""


def count_edges(mesh: TriangleMesh) -> EdgeCounts:
    """Boundary, non-manifold and misoriented edges of the mesh as it is (vertices compared by index; nothing is welded): a solid's mass properties need all three zero."""


def repair(mesh: TriangleMesh, weld_tolerance: float = ...) -> RepairReport:
    """Weld, drop degenerate triangles, orient each component outward (in place); returns the report."""


def fill_holes(mesh: TriangleMesh) -> HoleFillReport:
    """Close every hole whose border is a simple loop (in place; run repair first and again after); a planar hole is closed exactly. Returns the report."""


def volume_moments(mesh: TriangleMesh, about: object = ...) -> dict[str, Any]:
    """Exact moments of the enclosed volume about the point `about` (m, mesh frame; the bounding-box centre when None): measure ∫1 (m³), first ∫r (m⁴), second ∫r rᵀ (m⁵), r = p − about; by the divergence theorem, signed by the winding (no check here)."""


def surface_moments(mesh: TriangleMesh, about: object = ...) -> dict[str, Any]:
    """Exact moments of the surface about `about` (the bounding-box centre when None): measure area (m²), first ∫r (m³), second ∫r rᵀ (m⁴)."""


def mass_properties(mesh: TriangleMesh, *, mass: float | None = ..., density: float | None = ..., shell: bool = ..., thickness: float | None = ..., repair: bool = ...) -> tuple[Any, ...]:
    """(rigid.MassProperties, warnings) of a solid or thin shell in the mesh frame (COM in m, inertia about the COM in kg·m²); exactly one of mass (kg) and density (kg/m³; kg/m² for a shell, or kg/m³ with thickness= in m). A solid must be closed and consistently oriented: otherwise rigid.Error (never a wrong volume), with the remedy rigid.mesh.repair(mesh). repair=True measures a repaired copy instead (weld, drop degenerate triangles, orient outward; the mesh passed is unchanged), and the warnings say what repair changed."""


def mass_from_file(path: object, *, mass: float | None = ..., density: float | None = ..., units: str = ..., shell: bool = ..., thickness: float | None = ..., fill_holes: bool = ...) -> tuple[Any, ...]:
    """(rigid.MassProperties, warnings) of a mesh file (a str or pathlib.Path) read, repaired (holes filled with fill_holes=True) and integrated: what `rigid inertia FILE` prints. Exactly one of mass, density; units m, cm, mm or in."""


def vertex_noise_uncertainty(mesh: TriangleMesh, sigma: float, *, mass: float | None = ..., density: float | None = ..., about: object = ...) -> dict[str, Any]:
    """Mass, COM and inertia (about `about`, the COM when None) of a solid mesh with their 1σ when each vertex coordinate has an independent error of standard deviation sigma (m): first-order propagation, as `rigid inertia FILE --tolerance vertices=±…`."""


def integrate_density(mesh: TriangleMesh, rho: Callable[..., Any], relative_tolerance: float = ..., max_cells: int = ...) -> rigid.mass.DensityIntegration:
    """Mass properties of the density rho(p) (kg/m³; p a point in m, the mesh's frame) over the solid the closed, outward-oriented mesh bounds (run repair first), by adaptive cubature on the tetrahedra from its vertices' centroid (Grundmann–Möller, degrees 9 and 7): a rigid.mass.DensityIntegration (cells: tetrahedra). For a non-convex mesh rho is also sampled outside the solid, where it must be finite and non-negative. An open or misoriented mesh is refused."""
