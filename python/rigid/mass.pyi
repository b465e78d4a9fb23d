# Type stubs of rigid.mass, generated from the built module's signatures by scripts/make_stubs.py:
# do not edit; rerun the script after changing a binding.
import os
from typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence

import numpy
from numpy.typing import NDArray

import rigid


class _Pybind11Type(type):
    """The metaclass of the classes (pybind11_builtins.pybind11_type)."""


def solid_sphere_with_mass(m: float, r: float) -> rigid.MassProperties:
    """Uniform solid_sphere of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def solid_sphere_with_density(rho: float, r: float) -> rigid.MassProperties:
    """Uniform solid_sphere of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def thick_spherical_shell_with_mass(m: float, r_inner: float, r_outer: float) -> rigid.MassProperties:
    """Uniform thick_spherical_shell of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def thick_spherical_shell_with_density(rho: float, r_inner: float, r_outer: float) -> rigid.MassProperties:
    """Uniform thick_spherical_shell of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def thin_spherical_shell_with_mass(m: float, r: float) -> rigid.MassProperties:
    """Uniform thin_spherical_shell of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def thin_spherical_shell_with_density(rho: float, r: float) -> rigid.MassProperties:
    """Uniform thin_spherical_shell of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def solid_ellipsoid_with_mass(m: float, a: float, b: float, c: float) -> rigid.MassProperties:
    """Uniform solid_ellipsoid of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def solid_ellipsoid_with_density(rho: float, a: float, b: float, c: float) -> rigid.MassProperties:
    """Uniform solid_ellipsoid of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def solid_box_with_mass(m: float, lx: float, ly: float, lz: float) -> rigid.MassProperties:
    """Uniform solid_box of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def solid_box_with_density(rho: float, lx: float, ly: float, lz: float) -> rigid.MassProperties:
    """Uniform solid_box of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def solid_cylinder_with_mass(m: float, r: float, h: float) -> rigid.MassProperties:
    """Uniform solid_cylinder of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def solid_cylinder_with_density(rho: float, r: float, h: float) -> rigid.MassProperties:
    """Uniform solid_cylinder of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def thick_tube_with_mass(m: float, r_inner: float, r_outer: float, h: float) -> rigid.MassProperties:
    """Uniform thick_tube of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def thick_tube_with_density(rho: float, r_inner: float, r_outer: float, h: float) -> rigid.MassProperties:
    """Uniform thick_tube of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def thin_cylindrical_shell_with_mass(m: float, r: float, h: float) -> rigid.MassProperties:
    """Uniform thin_cylindrical_shell of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def thin_cylindrical_shell_with_density(rho: float, r: float, h: float) -> rigid.MassProperties:
    """Uniform thin_cylindrical_shell of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def capped_cylindrical_shell_with_mass(m: float, r: float, h: float) -> rigid.MassProperties:
    """Uniform capped_cylindrical_shell of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def capped_cylindrical_shell_with_density(rho: float, r: float, h: float) -> rigid.MassProperties:
    """Uniform capped_cylindrical_shell of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def solid_cone_with_mass(m: float, r: float, h: float) -> rigid.MassProperties:
    """Uniform solid_cone of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def solid_cone_with_density(rho: float, r: float, h: float) -> rigid.MassProperties:
    """Uniform solid_cone of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def solid_frustum_with_mass(m: float, r_bottom: float, r_top: float, h: float) -> rigid.MassProperties:
    """Uniform solid_frustum of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def solid_frustum_with_density(rho: float, r_bottom: float, r_top: float, h: float) -> rigid.MassProperties:
    """Uniform solid_frustum of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def solid_capsule_with_mass(m: float, r: float, l: float) -> rigid.MassProperties:
    """Uniform solid_capsule of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def solid_capsule_with_density(rho: float, r: float, l: float) -> rigid.MassProperties:
    """Uniform solid_capsule of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def solid_torus_with_mass(m: float, R: float, a: float) -> rigid.MassProperties:
    """Uniform solid_torus of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def solid_torus_with_density(rho: float, R: float, a: float) -> rigid.MassProperties:
    """Uniform solid_torus of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def thin_rod_with_mass(m: float, l: float) -> rigid.MassProperties:
    """Uniform thin_rod of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def thin_rod_with_density(rho: float, l: float) -> rigid.MassProperties:
    """Uniform thin_rod of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def thin_rectangular_plate_with_mass(m: float, lx: float, ly: float) -> rigid.MassProperties:
    """Uniform thin_rectangular_plate of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def thin_rectangular_plate_with_density(rho: float, lx: float, ly: float) -> rigid.MassProperties:
    """Uniform thin_rectangular_plate of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def thin_disk_with_mass(m: float, r: float) -> rigid.MassProperties:
    """Uniform thin_disk of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def thin_disk_with_density(rho: float, r: float) -> rigid.MassProperties:
    """Uniform thin_disk of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def thin_ring_with_mass(m: float, r: float) -> rigid.MassProperties:
    """Uniform thin_ring of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def thin_ring_with_density(rho: float, r: float) -> rigid.MassProperties:
    """Uniform thin_ring of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def disk_lamina_with_mass(m: float, r: float) -> rigid.MassProperties2:
    """Uniform disk_lamina of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def disk_lamina_with_density(rho: float, r: float) -> rigid.MassProperties2:
    """Uniform disk_lamina of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def annulus_lamina_with_mass(m: float, r_inner: float, r_outer: float) -> rigid.MassProperties2:
    """Uniform annulus_lamina of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def annulus_lamina_with_density(rho: float, r_inner: float, r_outer: float) -> rigid.MassProperties2:
    """Uniform annulus_lamina of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def rectangle_lamina_with_mass(m: float, lx: float, ly: float) -> rigid.MassProperties2:
    """Uniform rectangle_lamina of mass m (kg); sizes in m (frame and formula: docs/mass.md)."""


def rectangle_lamina_with_density(rho: float, lx: float, ly: float) -> rigid.MassProperties2:
    """Uniform rectangle_lamina of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m for the rod); sizes in m."""


def solid_tetrahedron_with_mass(m: float, v0: object, v1: object, v2: object, v3: object) -> rigid.MassProperties:
    """Uniform solid tetrahedron of mass m (kg) with vertices v0..v3 (each shape (3,), m), in the vertices' frame (frame and formula: docs/mass.md)."""


def polygon_lamina_with_mass(m: float, vertices: object) -> rigid.MassProperties2:
    """Uniform polygonal lamina of mass m (kg); vertices shape (n, 2) in m, one per row, in order around a simple polygon; in the vertices' plane frame."""


def solid_tetrahedron_with_density(rho: float, v0: object, v1: object, v2: object, v3: object) -> rigid.MassProperties:
    """Uniform solid tetrahedron of density rho (kg/m³) with vertices v0..v3 (each shape (3,), m), in the vertices' frame."""


def polygon_lamina_with_density(sigma: float, vertices: object) -> rigid.MassProperties2:
    """Uniform polygonal lamina of areal density sigma (kg/m²); vertices shape (n, 2) in m, one per row, in order around a simple polygon."""


def primitive_uncertainty(name: str, tolerance: str, about: object = ..., **kwargs: Any) -> dict[str, Any]:
    """Mass, COM and inertia (about `about`, the COM when None) of a catalogue primitive with their 1σ, first-order propagation of independent inputs: primitive_uncertainty('cylinder', 'dims=±0.1mm,density=±2%', density=2700, radius=0.05, height=0.4). Takes the factories' keywords (axis=, origin=, rpy= too); ± is one standard deviation."""


def place(body: rigid.MassProperties, axis: object = ..., origin: object = ..., rpy: object = ...) -> rigid.MassProperties:
    """The body (given in a shape's own frame) placed in the link frame: its z axis turned along axis ('x', 'y', 'z', '-x', '-y', '-z' or a vector), then rotated by rpy (rad, URDF: Rz(yaw) Ry(pitch) Rx(roll)), then its origin moved to origin (m). Every catalogue factory takes the same axis=, origin=, rpy=."""


def placement_rotation(axis: object = ..., rpy: object = ...) -> NDArray[numpy.float64]:
    """R_LS of a placement: Rz(yaw) Ry(pitch) Rx(roll) · (shortest rotation from z to axis)."""


def primitive(name: str, **kwargs: Any) -> rigid.MassProperties:
    """Mass properties of the catalogue's primitive `name` (any name or alias, as in scene files and `rigid inertia`): primitive('cylinder', mass=2.0, radius=0.1, height=0.5). Sizes in m, mass in kg or density in kg/m³ (kg/m² shells and plates, kg/m rods); vertices as (x, y, z)."""


def solid_sphere(**kwargs: Any) -> rigid.MassProperties:
    """solid sphere, centred in its own frame: solid_sphere(mass= or density=, radius= (radius, m)). Density in kg/m³. Also called: sphere."""


def sphere(**kwargs: Any) -> rigid.MassProperties:
    """solid sphere, centred in its own frame: solid_sphere(mass= or density=, radius= (radius, m)). Density in kg/m³. Also called: sphere."""


def thick_spherical_shell(**kwargs: Any) -> rigid.MassProperties:
    """solid shell between two spheres, centred in its own frame: thick_spherical_shell(mass= or density=, inner_radius= (inner radius, m), outer_radius= (outer radius, m)). Density in kg/m³. Also called: spherical_shell."""


def spherical_shell(**kwargs: Any) -> rigid.MassProperties:
    """solid shell between two spheres, centred in its own frame: thick_spherical_shell(mass= or density=, inner_radius= (inner radius, m), outer_radius= (outer radius, m)). Density in kg/m³. Also called: spherical_shell."""


def thin_spherical_shell(**kwargs: Any) -> rigid.MassProperties:
    """spherical surface, centred (density in kg/m²) in its own frame: thin_spherical_shell(mass= or density=, radius= (radius, m)). Density in kg/m². Also called: hollow_sphere."""


def hollow_sphere(**kwargs: Any) -> rigid.MassProperties:
    """spherical surface, centred (density in kg/m²) in its own frame: thin_spherical_shell(mass= or density=, radius= (radius, m)). Density in kg/m². Also called: hollow_sphere."""


def solid_ellipsoid(**kwargs: Any) -> rigid.MassProperties:
    """solid ellipsoid, semi-axes along x, y, z, centred in its own frame: solid_ellipsoid(mass= or density=, semi_x= (semi-axis along x, m), semi_y= (semi-axis along y, m), semi_z= (semi-axis along z, m)). Density in kg/m³. Also called: ellipsoid."""


def ellipsoid(**kwargs: Any) -> rigid.MassProperties:
    """solid ellipsoid, semi-axes along x, y, z, centred in its own frame: solid_ellipsoid(mass= or density=, semi_x= (semi-axis along x, m), semi_y= (semi-axis along y, m), semi_z= (semi-axis along z, m)). Density in kg/m³. Also called: ellipsoid."""


def solid_box(**kwargs: Any) -> rigid.MassProperties:
    """solid box, edges along x, y, z, centred in its own frame: solid_box(mass= or density=, lx= (edge along x, m), ly= (edge along y, m), lz= (edge along z, m)). Density in kg/m³. Also called: box, cuboid."""


def box(**kwargs: Any) -> rigid.MassProperties:
    """solid box, edges along x, y, z, centred in its own frame: solid_box(mass= or density=, lx= (edge along x, m), ly= (edge along y, m), lz= (edge along z, m)). Density in kg/m³. Also called: box, cuboid."""


def cuboid(**kwargs: Any) -> rigid.MassProperties:
    """solid box, edges along x, y, z, centred in its own frame: solid_box(mass= or density=, lx= (edge along x, m), ly= (edge along y, m), lz= (edge along z, m)). Density in kg/m³. Also called: box, cuboid."""


def solid_cylinder(**kwargs: Any) -> rigid.MassProperties:
    """solid cylinder, axis z, centred in its own frame: solid_cylinder(mass= or density=, radius= (radius, m), height= (height, m)). Density in kg/m³. Also called: cylinder."""


def cylinder(**kwargs: Any) -> rigid.MassProperties:
    """solid cylinder, axis z, centred in its own frame: solid_cylinder(mass= or density=, radius= (radius, m), height= (height, m)). Density in kg/m³. Also called: cylinder."""


def thick_tube(**kwargs: Any) -> rigid.MassProperties:
    """thick-walled tube, axis z, centred in its own frame: thick_tube(mass= or density=, inner_radius= (inner radius, m), outer_radius= (outer radius, m), height= (height, m)). Density in kg/m³. Also called: tube, thick_walled_tube."""


def tube(**kwargs: Any) -> rigid.MassProperties:
    """thick-walled tube, axis z, centred in its own frame: thick_tube(mass= or density=, inner_radius= (inner radius, m), outer_radius= (outer radius, m), height= (height, m)). Density in kg/m³. Also called: tube, thick_walled_tube."""


def thick_walled_tube(**kwargs: Any) -> rigid.MassProperties:
    """thick-walled tube, axis z, centred in its own frame: thick_tube(mass= or density=, inner_radius= (inner radius, m), outer_radius= (outer radius, m), height= (height, m)). Density in kg/m³. Also called: tube, thick_walled_tube."""


def thin_cylindrical_shell(**kwargs: Any) -> rigid.MassProperties:
    """thin open cylindrical surface, axis z, centred (density in kg/m²) in its own frame: thin_cylindrical_shell(mass= or density=, radius= (radius, m), height= (height, m)). Density in kg/m². Also called: cylindrical_shell."""


def cylindrical_shell(**kwargs: Any) -> rigid.MassProperties:
    """thin open cylindrical surface, axis z, centred (density in kg/m²) in its own frame: thin_cylindrical_shell(mass= or density=, radius= (radius, m), height= (height, m)). Density in kg/m². Also called: cylindrical_shell."""


def capped_cylindrical_shell(**kwargs: Any) -> rigid.MassProperties:
    """thin cylindrical surface with end disks, axis z, centred (density in kg/m²) in its own frame: capped_cylindrical_shell(mass= or density=, radius= (radius, m), height= (height, m)). Density in kg/m². Also called: closed_cylindrical_shell."""


def closed_cylindrical_shell(**kwargs: Any) -> rigid.MassProperties:
    """thin cylindrical surface with end disks, axis z, centred (density in kg/m²) in its own frame: capped_cylindrical_shell(mass= or density=, radius= (radius, m), height= (height, m)). Density in kg/m². Also called: closed_cylindrical_shell."""


def solid_cone(**kwargs: Any) -> rigid.MassProperties:
    """solid cone, base at z = 0, apex at z = height in its own frame: solid_cone(mass= or density=, radius= (base radius, m), height= (height, m)). Density in kg/m³. Also called: cone."""


def cone(**kwargs: Any) -> rigid.MassProperties:
    """solid cone, base at z = 0, apex at z = height in its own frame: solid_cone(mass= or density=, radius= (base radius, m), height= (height, m)). Density in kg/m³. Also called: cone."""


def solid_frustum(**kwargs: Any) -> rigid.MassProperties:
    """solid conical frustum, bottom at z = 0, top at z = height in its own frame: solid_frustum(mass= or density=, bottom_radius= (radius at z = 0, m), top_radius= (radius at z = height, m), height= (height, m)). Density in kg/m³. Also called: frustum."""


def frustum(**kwargs: Any) -> rigid.MassProperties:
    """solid conical frustum, bottom at z = 0, top at z = height in its own frame: solid_frustum(mass= or density=, bottom_radius= (radius at z = 0, m), top_radius= (radius at z = height, m), height= (height, m)). Density in kg/m³. Also called: frustum."""


def solid_capsule(**kwargs: Any) -> rigid.MassProperties:
    """solid capsule, axis z, centred (total length = length + 2 radius) in its own frame: solid_capsule(mass= or density=, radius= (radius, m), length= (length of the cylindrical part, m)). Density in kg/m³. Also called: capsule."""


def capsule(**kwargs: Any) -> rigid.MassProperties:
    """solid capsule, axis z, centred (total length = length + 2 radius) in its own frame: solid_capsule(mass= or density=, radius= (radius, m), length= (length of the cylindrical part, m)). Density in kg/m³. Also called: capsule."""


def solid_torus(**kwargs: Any) -> rigid.MassProperties:
    """solid torus, axis z, centred in its own frame: solid_torus(mass= or density=, major_radius= (radius of the centre circle, m), minor_radius= (radius of the tube, m)). Density in kg/m³. Also called: torus."""


def torus(**kwargs: Any) -> rigid.MassProperties:
    """solid torus, axis z, centred in its own frame: solid_torus(mass= or density=, major_radius= (radius of the centre circle, m), minor_radius= (radius of the tube, m)). Density in kg/m³. Also called: torus."""


def thin_rod(**kwargs: Any) -> rigid.MassProperties:
    """thin rod along z, centred (density in kg/m) in its own frame: thin_rod(mass= or density=, length= (length, m)). Density in kg/m. Also called: rod."""


def rod(**kwargs: Any) -> rigid.MassProperties:
    """thin rod along z, centred (density in kg/m) in its own frame: thin_rod(mass= or density=, length= (length, m)). Density in kg/m. Also called: rod."""


def thin_rectangular_plate(**kwargs: Any) -> rigid.MassProperties:
    """thin rectangular plate in the xy-plane, edges lx along x and ly along y, centred (kg/m²) in its own frame: thin_rectangular_plate(mass= or density=, lx= (edge along x, m), ly= (edge along y, m)). Density in kg/m². Also called: plate, rectangular_plate."""


def plate(**kwargs: Any) -> rigid.MassProperties:
    """thin rectangular plate in the xy-plane, edges lx along x and ly along y, centred (kg/m²) in its own frame: thin_rectangular_plate(mass= or density=, lx= (edge along x, m), ly= (edge along y, m)). Density in kg/m². Also called: plate, rectangular_plate."""


def rectangular_plate(**kwargs: Any) -> rigid.MassProperties:
    """thin rectangular plate in the xy-plane, edges lx along x and ly along y, centred (kg/m²) in its own frame: thin_rectangular_plate(mass= or density=, lx= (edge along x, m), ly= (edge along y, m)). Density in kg/m². Also called: plate, rectangular_plate."""


def thin_disk(**kwargs: Any) -> rigid.MassProperties:
    """thin disk in the xy-plane, centred (kg/m²) in its own frame: thin_disk(mass= or density=, radius= (radius, m)). Density in kg/m². Also called: disk, disc."""


def disk(**kwargs: Any) -> rigid.MassProperties:
    """thin disk in the xy-plane, centred (kg/m²) in its own frame: thin_disk(mass= or density=, radius= (radius, m)). Density in kg/m². Also called: disk, disc."""


def disc(**kwargs: Any) -> rigid.MassProperties:
    """thin disk in the xy-plane, centred (kg/m²) in its own frame: thin_disk(mass= or density=, radius= (radius, m)). Density in kg/m². Also called: disk, disc."""


def thin_ring(**kwargs: Any) -> rigid.MassProperties:
    """thin ring (hoop) of the given radius in the xy-plane, axis z, centred (density in kg/m) in its own frame: thin_ring(mass= or density=, radius= (radius of the circle, m)). Density in kg/m. Also called: hoop, ring, thin_hoop."""


def hoop(**kwargs: Any) -> rigid.MassProperties:
    """thin ring (hoop) of the given radius in the xy-plane, axis z, centred (density in kg/m) in its own frame: thin_ring(mass= or density=, radius= (radius of the circle, m)). Density in kg/m. Also called: hoop, ring, thin_hoop."""


def ring(**kwargs: Any) -> rigid.MassProperties:
    """thin ring (hoop) of the given radius in the xy-plane, axis z, centred (density in kg/m) in its own frame: thin_ring(mass= or density=, radius= (radius of the circle, m)). Density in kg/m. Also called: hoop, ring, thin_hoop."""


def thin_hoop(**kwargs: Any) -> rigid.MassProperties:
    """thin ring (hoop) of the given radius in the xy-plane, axis z, centred (density in kg/m) in its own frame: thin_ring(mass= or density=, radius= (radius of the circle, m)). Density in kg/m. Also called: hoop, ring, thin_hoop."""


def solid_tetrahedron(**kwargs: Any) -> rigid.MassProperties:
    """solid tetrahedron with the given vertices (coordinates kept) in its own frame: solid_tetrahedron(mass= or density=, v0= (vertex 0 as (x, y, z), m), v1= (vertex 1 as (x, y, z), m), v2= (vertex 2 as (x, y, z), m), v3= (vertex 3 as (x, y, z), m)). Density in kg/m³. Also called: tetrahedron."""


def tetrahedron(**kwargs: Any) -> rigid.MassProperties:
    """solid tetrahedron with the given vertices (coordinates kept) in its own frame: solid_tetrahedron(mass= or density=, v0= (vertex 0 as (x, y, z), m), v1= (vertex 1 as (x, y, z), m), v2= (vertex 2 as (x, y, z), m), v3= (vertex 3 as (x, y, z), m)). Density in kg/m³. Also called: tetrahedron."""


def primitives() -> list[Any]:
    """The primitive catalogue: every shape with its name, aliases, sizes (name, help, unit, aliases), vertices and density unit."""


def n_ball_with_mass(m: float, r: float, n: int) -> rigid.SecondMoments:
    """Uniform n-ball of mass m (kg) and radius r (m) in n ≥ 1 dimensions, centred: J = m r²/(n + 2) · 1 (kg·m²)."""


def n_ball_with_density(rho: float, r: float, n: int) -> rigid.SecondMoments:
    """Uniform n-ball of density rho (kg/mⁿ) and radius r (m) in n ≥ 1 dimensions, centred; volume π^{n/2} rⁿ / Γ(n/2 + 1)."""


def n_box_with_mass(m: float, sizes: object) -> rigid.SecondMoments:
    """Uniform n-box of mass m (kg) with edge lengths `sizes` (shape (n,), m), centred: J = m diag(l_i²/12)."""


def n_box_with_density(rho: float, sizes: object) -> rigid.SecondMoments:
    """Uniform n-box of density rho (kg/mⁿ) with edge lengths `sizes` (shape (n,), m), centred."""


def point_mass(m: float, p: object) -> rigid.MassProperties:
    """A point mass m (kg) at p (shape (3,), m): COM p, zero inertia about it."""


def point_masses(masses: object, points: object) -> rigid.MassProperties:
    """Point masses masses[i] (kg, shape (n,)) at points[i] (shape (n, 3), m, one point per row), combined into one body in the points' frame."""


def point_set_second_moments(masses: object, points: object) -> rigid.SecondMoments:
    """n-D second moments (rigid.SecondMoments) of point masses masses[i] (kg, shape (k,)) at points[i] (shape (k, n), m, one point per row): J_C = Σ m (p − c)(p − c)ᵀ about the COM c."""


def polygon_moments(vertices: object) -> tuple[Any, ...]:
    """(area m², centroid (2,) m, J_C (2, 2) m⁴ per unit areal density) of a simple polygon, vertices shape (n, 2) in order (either direction)."""


def check_rotational_moments(moments: object) -> str | None:
    """Why principal moments (kg·m², shape (3,), any order) cannot be those of a body that turns (not finite, negative, I_i > I_j + I_k, or a zero moment), or None: the check the dynamics (rigid.body, rigid.spring) make."""


class DensityIntegration(metaclass=_Pybind11Type):
    """Mass properties of a variable density by adaptive cubature, with error bounds."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def mass_properties(self) -> rigid.MassProperties:
        """The integrated rigid.MassProperties (in the shape's frame, centred)."""
    @property
    def mass_error(self) -> float:
        """Error bound on the mass (kg)."""
    @property
    def com_error(self) -> float:
        """Error bound on every COM component (m)."""
    @property
    def inertia_error(self) -> float:
        """Error bound on every element of the inertia about the COM (kg·m²)."""
    @property
    def cells(self) -> int:
        """Cells used."""
    @property
    def converged(self) -> bool:
        """False if max_cells was reached before the relative tolerance."""
    def __repr__(self) -> str: ...


def integrate_density_over_box(rho: Callable[..., Any], lx: float, ly: float, lz: float, relative_tolerance: float = ..., max_cells: int = ...) -> DensityIntegration:
    """Mass properties of the density rho(p) (kg/m³; p a point in m, the box's frame) over the box [-lx/2, lx/2] × [-ly/2, ly/2] × [-lz/2, lz/2] (m), by adaptive cubature: a DensityIntegration."""


def integrate_density_over_cylinder(rho: Callable[..., Any], r: float, h: float, relative_tolerance: float = ..., max_cells: int = ...) -> DensityIntegration:
    """Mass properties of the density rho(p) (kg/m³) over the cylinder of radius r and height h (m), axis z, centred at the origin, by adaptive cubature: a DensityIntegration."""


def integrate_density_over_sphere(rho: Callable[..., Any], r: float, relative_tolerance: float = ..., max_cells: int = ...) -> DensityIntegration:
    """Mass properties of the density rho(p) (kg/m³) over the ball of radius r (m) centred at the origin, by adaptive cubature: a DensityIntegration."""


def write_inertial_document(mp: rigid.MassProperties, format: str, name: str = ..., principal: bool = ..., inertial_frame: object = ...) -> str:
    """A minimal URDF/MJCF/SDF document holding one inertial; with principal=True, inertial_frame=R_LI (e.g. placement_rotation(axis, rpy)) writes that frame exactly."""


def pseudo_inertia(mp: rigid.MassProperties) -> NDArray[numpy.float64]:
    """The 4×4 pseudo-inertia J = [[Σ, h], [hᵀ, m]] about the frame origin: Σ = ½ tr(I_O) 1 − I_O, h = m c [Wensing2017]."""


def from_pseudo_inertia(J: object) -> rigid.MassProperties:
    """The body of a pseudo-inertia J; raises rigid.Error naming the failed condition (mass, triangle inequality) when J is not positive semidefinite."""


def log_cholesky(mp: rigid.MassProperties) -> NDArray[numpy.float64]:
    """The 10 log-Cholesky parameters (alpha, d1, d2, d3, s12, s23, s13, t1, t2, t3) of the body about the frame origin [Rucker2022]; J = U Uᵀ, m = exp(2 alpha)."""


def from_log_cholesky(theta: object) -> rigid.MassProperties:
    """The body of 10 log-Cholesky parameters (any finite vector is a physical body)."""


def pseudo_inertia_from_log_cholesky(theta: object) -> NDArray[numpy.float64]:
    """J = U Uᵀ of 10 log-Cholesky parameters."""


def read_inertials(path: object = ..., *, text: object = ..., source: str | None = ...) -> list[Any]:
    """Every inertial of a URDF/MJCF/SDF document, in document order, as dicts: name, line, mass (kg), com (m), inertia_com (kg·m², about the COM), all in the link/body frame (the inertial's own rotation applied), and problem (why it is not physical, or None). read_inertials(path) reads a file (a str or pathlib.Path; messages start with its name); read_inertials(text=xml) parses a document in memory (messages name `source`, default '<string>'). A str is always a path, never XML."""


def fix_inertials(path: object, output: object = ..., density: float | None = ..., keep_mass: bool = ..., geometry: str = ..., only: list[str] = ..., package_path: object = ...) -> dict[str, Any]:
    """Recompute the inertials of a URDF/SDF/MJCF model from its geometry (as `rigid inertia fix`): the report of old vs new per link, with the rewritten document as 'text'; writes it to `output` when given. Raises rigid.Error (and writes nothing) if a link cannot be fixed."""
