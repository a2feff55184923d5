"""
vofdem C++ core: VOF flow, DEM stones and their coupling
"""
from __future__ import annotations
import collections.abc
import enum
import numpy
import numpy.typing
import typing
__all__: list[str] = ['COUPLE_CHECKS', 'COUPLE_DEFAULT', 'COUPLE_DEM', 'COUPLE_DISPLACE_FLOW', 'COUPLE_DRAG', 'COUPLE_FLUID', 'COUPLE_FORCES', 'COUPLE_LOOKUP_POROSITY', 'COUPLE_ONE_WAY', 'COUPLE_OVERFLOW_LOAD', 'COUPLE_POROSITY', 'COUPLE_PRESSURE_GRADIENT', 'COUPLE_TWO_WAY', 'COUPLE_WET_FRACTION', 'CornerViscosity', 'Coupler', 'CouplerEffect', 'CouplerParams', 'CouplerState', 'CouplingMapping', 'DEMEnergy', 'DEMFlag', 'DEMParams', 'DEMState', 'DEMSystem', 'DEMWall', 'DEM_ADDED_MASS', 'DEM_ALL_EFFECTS', 'DEM_BUOYANCY', 'DEM_DAMPING', 'DEM_EXTERNAL_FORCE', 'DEM_FRICTION', 'DEM_GRAVITY', 'DEM_REMOVAL', 'DEM_ROLLING_RESISTANCE', 'DEM_ROTATION', 'DEM_SLEEPING', 'DischargeTable', 'DragLaw', 'ERGUN_K1', 'ERGUN_K2', 'FlowEffect', 'FlowParams', 'FlowStableDt', 'FlowState', 'GRADED_MERGE_FRACTION', 'Grid2D', 'InletBoundary', 'InletProfile', 'KEpsilonPoreStrain', 'KEpsilonProduction', 'KEpsilonTimeScheme', 'Medium', 'MomentumTimeScheme', 'OutletBoundary', 'PAPER_K1', 'PAPER_K2', 'PorosityMapper', 'PorosityMethod', 'PorosityParams', 'PressureProblem', 'PressureSolveStats', 'PressureSolver', 'PressureSolverKind', 'SettleReport', 'StageProfile', 'StepControl', 'StoneDragModel', 'TopBoundary', 'VOFGrid', 'VOF_CLIP_TOLERANCE', 'ViscousBound', 'ViscousScheme', 'VofBoundaryInflow', 'VofNormal', 'VofScratch', 'WallCondition', 'WeirPackingReport', 'WeirSpec', 'advect_vof', 'built_with_openmp', 'contact_duration', 'damping_ratio_from_restitution', 'drag_coefficient', 'forchheimer_coefficient', 'max_threads', 'pack_weir', 'permeability', 'plic_area_below', 'plic_line_constant', 'porosity_eq11', 'pressure_residual', 'quarried_stone', 'quarried_stone_names', 'random_polygons', 'restitution_from_damping_ratio', 'set_thread_min_cells', 'set_threads', 'stone_cell_area', 'stone_model_names', 'thread_min_cells', 'threads', 'vof_stable_dt', 'weir_outline_error', 'weir_porosity']
class Grid2D:
    """
    Staggered 2D vertical grid: uniform in x, free spacing in z (SI units).
    """
    @staticmethod
    def graded(nx: typing.SupportsInt | typing.SupportsIndex, length_x: typing.SupportsFloat | typing.SupportsIndex, height_z: typing.SupportsFloat | typing.SupportsIndex, dz: typing.SupportsFloat | typing.SupportsIndex, dz_bed: typing.SupportsFloat | typing.SupportsIndex, z_bed_top: typing.SupportsFloat | typing.SupportsIndex, merge_fraction: typing.SupportsFloat | typing.SupportsIndex = 0.5) -> Grid2D:
        ...
    @staticmethod
    def uniform(nx: typing.SupportsInt | typing.SupportsIndex, nz: typing.SupportsInt | typing.SupportsIndex, length_x: typing.SupportsFloat | typing.SupportsIndex, height_z: typing.SupportsFloat | typing.SupportsIndex, x0: typing.SupportsFloat | typing.SupportsIndex = 0.0, z0: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> Grid2D:
        ...
    def __init__(self, nx: typing.SupportsInt | typing.SupportsIndex, dx: typing.SupportsFloat | typing.SupportsIndex, z_faces: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], x0: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def dx(self) -> float:
        """
        column width [m] (uniform in x)
        """
    @property
    def height_z(self) -> float:
        """
        height of the domain [m]
        """
    @property
    def length_x(self) -> float:
        """
        length of the domain along the flume [m]
        """
    @property
    def ncell(self) -> int:
        """
        cells nx nz [-]
        """
    @property
    def nx(self) -> int:
        """
        columns [-]
        """
    @property
    def nz(self) -> int:
        """
        rows [-]
        """
    @property
    def x0(self) -> float:
        """
        x of the first column's left face [m]
        """
    @property
    def z_faces(self) -> list[float]:
        """
        heights of the nz + 1 row faces [m], increasing from the bed
        """
class Medium:
    """
    Water, air and gravity (SI units), one value for the flow and the stones: FlowParams.medium owns it, a Coupler hands it to the stones (DEMParams.medium).
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: Medium) -> bool:
        ...
    def __init__(self) -> None:
        ...
    def __ne__(self, arg0: Medium) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def validate(self) -> None:
        """
        ValueError naming the field unless the densities are positive, the viscosities non-negative and the gravity finite
        """
    @property
    def gravity(self) -> typing.Annotated[list[float], "FixedSize(2)"]:
        """
        gravitational acceleration (x along the flume, z up) [m/s^2]
        """
    @gravity.setter
    def gravity(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(2)"]) -> None:
        ...
    @property
    def nu_air(self) -> float:
        """
        air kinematic viscosity [m^2/s], default 1.516e-05
        """
    @nu_air.setter
    def nu_air(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nu_water(self) -> float:
        """
        water kinematic viscosity [m^2/s], default 1.004e-06
        """
    @nu_water.setter
    def nu_water(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rho_air(self) -> float:
        """
        air density [kg/m^3], default 1.204
        """
    @rho_air.setter
    def rho_air(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rho_water(self) -> float:
        """
        water density [kg/m^3], default 998.2
        """
    @rho_water.setter
    def rho_water(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class StageProfile:
    """
    Accumulated wall time [s] and calls of each named solver stage.
    """
    def reset(self) -> None:
        """
        zeroes every stage's time and calls
        """
    @property
    def calls(self) -> list[int]:
        """
        how often each stage ran [-]
        """
    @property
    def names(self) -> list[str]:
        """
        the stages' names, in the order they first ran
        """
    @property
    def seconds(self) -> list[float]:
        """
        accumulated wall time of each stage [s]
        """
    @property
    def total_seconds(self) -> float:
        """
        the stages' summed wall time [s]
        """
class DragLaw:
    """
    Drag coefficient C_D [-] of a stone against its Reynolds number (drag.h).
    
    Members:
    
      PAPER : C_D = 0.4 + 24/Re (seed eq. 18)
    
      SCHILLER_NAUMANN : C_D = 24/Re (1 + 0.15 Re^0.687), 0.44 above Re=1000
    """
    PAPER: typing.ClassVar[DragLaw]
    SCHILLER_NAUMANN: typing.ClassVar[DragLaw]
    __members__: typing.ClassVar[dict[str, DragLaw]]
    @typing.overload
    def __eq__(self, other: DragLaw) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: DragLaw) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class PorosityMethod:
    """
    How the stones' solid area [m^2] in each cell is found (porosity_map.h, eq. 11).
    
    Members:
    
      EXACT : closed-form disc-rectangle areas
    
      LOOKUP : the paper's precomputed sub-area tables
    """
    EXACT: typing.ClassVar[PorosityMethod]
    LOOKUP: typing.ClassVar[PorosityMethod]
    __members__: typing.ClassVar[dict[str, PorosityMethod]]
    @typing.overload
    def __eq__(self, other: PorosityMethod) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: PorosityMethod) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class PorosityParams:
    """
    Parameters of the porosity mapping (SI units).
    """
    def __init__(self) -> None:
        ...
    @property
    def dr(self) -> float:
        """
        radius node spacing of the lookup tables [m], default 0.001
        """
    @dr.setter
    def dr(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def m(self) -> int:
        """
        sub-areas per side of the centre cell (lookup) [-], default 8
        """
    @m.setter
    def m(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_discs(self) -> int:
        """
        largest number of discs of one call [-]
        """
    @max_discs.setter
    def max_discs(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def method(self) -> PorosityMethod:
        """
        PorosityMethod of the solid areas, default EXACT
        """
    @method.setter
    def method(self, arg0: PorosityMethod) -> None:
        ...
    @property
    def n_exp(self) -> float:
        """
        packing porosity of the stones [-], default 0.41
        """
    @n_exp.setter
    def n_exp(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def r_max(self) -> float:
        """
        largest disc radius [m]
        """
    @r_max.setter
    def r_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def r_min(self) -> float:
        """
        smallest disc radius [m]
        """
    @r_min.setter
    def r_min(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class PorosityMapper:
    """
    Cell porosity (seed eq. 11) from stone discs, exact or by the paper's lookup table.
    """
    def __init__(self, grid: Grid2D, params: PorosityParams) -> None:
        ...
    def map(self, disc_x: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], disc_z: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], disc_r: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], active: typing.Any = None) -> None:
        """
        Maps disc centres [m] and radii [m] onto cell_solid_area and cell_porosity (no allocation).
        """
    @property
    def cell_porosity(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        porosity n of each cell [-]; (nz, nx) view
        """
    @property
    def cell_solid_area(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        stone area A_s of each cell [m^2], capped at the cell area; (nz, nx) view
        """
    @property
    def grid(self) -> Grid2D:
        """
        the flow grid the mapper maps onto (Grid2D)
        """
    @property
    def ndisc(self) -> int:
        """
        number of discs of the last map() call [-]
        """
    @property
    def params(self) -> PorosityParams:
        """
        a copy: fixed at construction
        """
    @property
    def profile(self) -> StageProfile:
        """
        wall-clock seconds per mapping stage (StageProfile)
        """
    @property
    def row_class(self) -> list[int]:
        """
        row class of each grid row for the lookup tables (rows with equal z-faces within reach share one)
        """
    @property
    def stone_cell_area(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        area [m^2] of each (disc, cell) pair, uncapped
        """
    @property
    def stone_cell_index(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        flat cell index i + nx k of each (disc, cell) pair
        """
    @property
    def stone_cell_offsets(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        CSR offsets (ndisc + 1) of the cells each disc covers
        """
    @property
    def table_bytes(self) -> int:
        """
        memory of the lookup tables [bytes]
        """
    @property
    def table_count(self) -> int:
        """
        distinct lookup tables (row classes x radius nodes) [-]; 0 with the exact method
        """
class DEMWall:
    """
    Half-plane wall: the solid lies opposite to `normal` (SI units).
    """
    def __init__(self, point: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(2)"], normal: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(2)"], friction: typing.SupportsFloat | typing.SupportsIndex = 0.176) -> None:
        ...
    @property
    def friction(self) -> float:
        """
        stone-wall Coulomb coefficient [-] (paper 0.176)
        """
    @friction.setter
    def friction(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def normal(self) -> typing.Annotated[list[float], "FixedSize(2)"]:
        """
        the wall's normal (x, z) into the stones' side [-]; scaled to unit length
        """
    @normal.setter
    def normal(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(2)"]) -> None:
        ...
    @property
    def point(self) -> typing.Annotated[list[float], "FixedSize(2)"]:
        """
        a point of the wall's line (x, z) [m]
        """
    @point.setter
    def point(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(2)"]) -> None:
        ...
class DEMParams:
    """
    Constant parameters of the DEM of the stones (SI units; see dem_system.h).
    """
    def __init__(self) -> None:
        ...
    def add_flume(self, x_min: typing.SupportsFloat | typing.SupportsIndex, x_max: typing.SupportsFloat | typing.SupportsIndex, z_bed: typing.SupportsFloat | typing.SupportsIndex = 0.0, mu: typing.SupportsFloat | typing.SupportsIndex = 0.176) -> None:
        """
        Adds the flume's walls: the bed z = z_bed and the end walls x = x_min, x_max [m], each with the stone-wall Coulomb coefficient mu [-].
        """
    @property
    def added_mass_coefficient(self) -> float:
        """
        added-mass coefficient C_M [-] (the paper's run 1.0, its text 0.5), default 1
        """
    @added_mass_coefficient.setter
    def added_mass_coefficient(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def contact_steps(self) -> float:
        """
        automatic k_n: DEM steps per undamped contact of two mean stones [-], default 20
        """
    @contact_steps.setter
    def contact_steps(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def domain_max(self) -> typing.Annotated[list[float], "FixedSize(2)"]:
        """
        removal box, upper corner (x, z) [m]
        """
    @domain_max.setter
    def domain_max(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(2)"]) -> None:
        ...
    @property
    def domain_min(self) -> typing.Annotated[list[float], "FixedSize(2)"]:
        """
        removal box, lower corner (x, z) [m]
        """
    @domain_min.setter
    def domain_min(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(2)"]) -> None:
        ...
    @property
    def dt(self) -> float:
        """
        DEM step [s]; advance() substeps never exceed it (the paper's 1e-4), default 1e-04
        """
    @dt.setter
    def dt(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def flags(self) -> int:
        """
        DEMFlag bits of the effects that are on
        """
    @flags.setter
    def flags(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def friction_stone(self) -> float:
        """
        stone-stone Coulomb coefficient mu [-] (the paper's 0.577), default 0.577
        """
    @friction_stone.setter
    def friction_stone(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def inertia_factor(self) -> float:
        """
        moment of inertia I = factor M r^2 [-] (a sphere 0.4, a disc 0.5), default 0.4
        """
    @inertia_factor.setter
    def inertia_factor(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def medium(self) -> Medium:
        """
        water and gravity (Medium); a Coupler sets the flow's
        """
    @medium.setter
    def medium(self, arg0: Medium) -> None:
        ...
    @property
    def neighbour_skin(self) -> float:
        """
        Verlet-list skin [m]; 0 = a tenth of the largest diameter, default 0
        """
    @neighbour_skin.setter
    def neighbour_skin(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def plane_neighbour_list(self) -> bool:
        """
        3D stones: neighbours by their x-z projections whatever their y (True: more pairs, the same forces) or by cells in x, y and z (False), default False
        """
    @plane_neighbour_list.setter
    def plane_neighbour_list(self, arg0: bool) -> None:
        ...
    @property
    def restitution(self) -> float:
        """
        normal restitution coefficient e [-], [0, 1]; 0 = critical damping, default 0
        """
    @restitution.setter
    def restitution(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rolling_damping(self) -> float:
        """
        rolling damper ratio eta_r = C_r / (2 sqrt(I_r k_r)) [-], [0, 1], default 0.3
        """
    @rolling_damping.setter
    def rolling_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rolling_friction_stone(self) -> float:
        """
        rolling friction mu_r stone-stone [-], >= 0 (with ROLLING_RESISTANCE; discs and 3D stones), default 0
        """
    @rolling_friction_stone.setter
    def rolling_friction_stone(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rolling_friction_wall(self) -> float:
        """
        rolling friction mu_r stone-wall [-], >= 0 (with ROLLING_RESISTANCE), default 0
        """
    @rolling_friction_wall.setter
    def rolling_friction_wall(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def side_wall_friction(self) -> float:
        """
        3D stones: stone-side wall Coulomb coefficient [-], >= 0 (the paper's glass 0.176), default 0.176
        """
    @side_wall_friction.setter
    def side_wall_friction(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sleep_time(self) -> float:
        """
        ... held for this long [s], default 0.2
        """
    @sleep_time.setter
    def sleep_time(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sleep_velocity(self) -> float:
        """
        a stone may sleep below this speed (and omega r) [m/s] (with SLEEPING), default 0.001
        """
    @sleep_velocity.setter
    def sleep_velocity(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def stiffness_normal(self) -> float:
        """
        normal spring stiffness k_n [N/m]; 0 = automatic from contact_steps (Gotoh & Sakai 1997), default 0
        """
    @stiffness_normal.setter
    def stiffness_normal(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def stiffness_ratio(self) -> float:
        """
        tangential to normal stiffness k_t / k_n [-], default 0.2857142857142857
        """
    @stiffness_ratio.setter
    def stiffness_ratio(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def submerged(self) -> bool:
        """
        the stones lie in the medium's water (buoyancy, added mass); False: dry
        """
    @submerged.setter
    def submerged(self, arg0: bool) -> None:
        ...
    @property
    def tangential_damping_factor(self) -> float:
        """
        tangential to normal dashpot c_t / c_n [-] (LAMMPS's default), default 0.5
        """
    @tangential_damping_factor.setter
    def tangential_damping_factor(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def wake_acceleration(self) -> float:
        """
        a sleeping stone wakes when its net force gives more [m/s^2], default 0.2
        """
    @wake_acceleration.setter
    def wake_acceleration(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def walls(self) -> list[DEMWall]:
        """
        half-plane walls (DEMWall: the bed, the end walls)
        """
    @walls.setter
    def walls(self, arg0: collections.abc.Sequence[DEMWall]) -> None:
        ...
    @property
    def water_density(self) -> float:
        """
        rho_w of buoyancy and added mass [kg/m^3]: medium.rho_water if submerged, else 0
        """
    @property
    def width(self) -> float:
        """
        3D stones: the flume's width between the side walls y = 0 and y = width [m], > 0 for them, default 0
        """
    @width.setter
    def width(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class DEMFlag(enum.IntFlag):
    """
    Bit flags of the DEM's physical effects (DEMParams.flags).
    """
    ADDED_MASS: typing.ClassVar[DEMFlag]
    ALL_EFFECTS: typing.ClassVar[DEMFlag]
    BUOYANCY: typing.ClassVar[DEMFlag]
    DAMPING: typing.ClassVar[DEMFlag]
    EXTERNAL_FORCE: typing.ClassVar[DEMFlag]
    FRICTION: typing.ClassVar[DEMFlag]
    GRAVITY: typing.ClassVar[DEMFlag]
    REMOVAL: typing.ClassVar[DEMFlag]
    ROLLING_RESISTANCE: typing.ClassVar[DEMFlag]
    ROTATION: typing.ClassVar[DEMFlag]
    SLEEPING: typing.ClassVar[DEMFlag]
    @classmethod
    def __new__(cls, value):
        ...
    def __and__(self, other):
        ...
    def __format__(self, format_spec):
        ...
    def __invert__(self):
        ...
    def __or__(self, other):
        ...
    def __rand__(self, other):
        ...
    def __ror__(self, other):
        ...
    def __rxor__(self, other):
        ...
    def __xor__(self, other):
        ...
class DEMEnergy:
    """
    Energy bookkeeping of the DEM [J].
    """
    @property
    def dissipated(self) -> float:
        """
        dashpots, Coulomb and rolling slip and sleeping, accumulated [J]
        """
    @property
    def elastic(self) -> float:
        """
        energy in the contact springs (the rolling ones too) at the last evaluation [J]
        """
    @property
    def kinetic(self) -> float:
        """
        sum of 1/2 (M + M') v^2 + 1/2 I omega^2 [J]
        """
    @property
    def potential(self) -> float:
        """
        sum of -(M - rho_w V w) g . x [J], zero at the origin
        """
    @property
    def total(self) -> float:
        """
        kinetic + potential + elastic + dissipated - work_external [J]: constant but for round-off and the step's error
        """
    @property
    def work_external(self) -> float:
        """
        work of the external (fluid) forces stone_force_ext, accumulated [J]
        """
class DEMState:
    """
    A copy of a DEMSystem's whole state (DEMSystem.copy_state); set_state() returns to it.
    """
    @property
    def steps(self) -> int:
        """
        steps taken since the start [-]
        """
    @property
    def time(self) -> float:
        """
        simulated time [s]
        """
class DEMSystem:
    """
    Stones as discs (sphere masses), eqs. (8)-(10) of Maeno & Tomita (2008).
    """
    @typing.overload
    def __init__(self, params: DEMParams, n: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @typing.overload
    def __init__(self, params: DEMParams, pos: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], radius: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], density: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], fixed: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex] = []) -> None:
        ...
    def advance(self, duration: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        advances by duration [s] in steps of at most params.dt and the stable step; the GIL is released
        """
    def copy_state(self) -> DEMState:
        """
        a copy of the whole state (DEMState): set_state(copy) continues from it bit for bit
        """
    def energy(self) -> DEMEnergy:
        """
        the energy account (DEMEnergy) [J] at the last evaluation
        """
    def export_state(self) -> dict:
        """
        the whole state as a dict of named numpy arrays, copied (a checkpoint; import_state(dict) restores it bit for bit)
        """
    def import_state(self, state: dict) -> None:
        """
        restores export_state() exactly, written into the arrays in place; a state of another stone count (or, for polygons, vertex count) resizes and so invalidates earlier views
        """
    def inertia(self, i: typing.SupportsInt | typing.SupportsIndex) -> float:
        """
        moment of inertia I_i [kg m^2] of stone i about the plane's normal
        """
    def mass(self, i: typing.SupportsInt | typing.SupportsIndex) -> float:
        """
        M_i = rho_s V_i [kg] of stone i
        """
    def max_speed(self) -> float:
        """
        the largest speed of a free, active stone [m/s]: its centre's or its spin times its radius (3D stones: across the flume and about every axis too)
        """
    def neighbour_pairs(self) -> list[typing.Annotated[list[int], "FixedSize(2)"]]:
        """
        the neighbour list's pairs (i, j), i < j
        """
    def nominal_diameter(self, i: typing.SupportsInt | typing.SupportsIndex) -> float:
        """
        nominal diameter [m] of stone i (a disc's 2 r, a polygon's equal-area disc's)
        """
    def overlapping_pairs(self) -> list[typing.Annotated[list[int], "FixedSize(2)"]]:
        """
        the pairs (i, j) that touch now, from the neighbour list
        """
    def overlapping_pairs_reference(self) -> list[typing.Annotated[list[int], "FixedSize(2)"]]:
        """
        the pairs that touch now by testing every pair (the slow reference of overlapping_pairs)
        """
    @typing.overload
    def projected_area(self, i: typing.SupportsInt | typing.SupportsIndex) -> float:
        ...
    @typing.overload
    def projected_area(self, i: typing.SupportsInt | typing.SupportsIndex, ux: typing.SupportsFloat | typing.SupportsIndex, uz: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    def resize(self, n: typing.SupportsInt | typing.SupportsIndex) -> None:
        """
        n stones, all arrays zeroed (discs again); invalidates every earlier view and the contact histories
        """
    def set_clumps(self, sphere: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], offset: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex]) -> None:
        """
        Makes every stone a clump of overlapping spheres (the model 'clump'): sphere (m, 4) rows (x, y, z, r) [m] in any frame, each stone's stored in its principal frame (stone_pos, stone_y: its centre of mass); stone i owns rows offset[i]:offset[i+1] (1 to 8); stone_radius becomes each bounding radius. The out-of-plane state is made anew.
        """
    def set_model(self, name: str) -> None:
        """
        Makes every stone of the registered stone model `name` (stone_model_names()); shape arrays and contact histories are made anew. Invalidates the poly_* views.
        """
    def set_polygons(self, vertex: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], offset: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex]) -> None:
        """
        Makes every stone a convex polygon: body-frame vertices (x, z) [m], CCW, centroid at the origin; stone i owns vertices offset[i]:offset[i+1]. Invalidates the poly_* views.
        """
    def set_state(self, state: DEMState) -> None:
        """
        returns to a copy_state() copy (checked first; written in place unless the stone or vertex count differs, which invalidates earlier views)
        """
    def set_wet_fraction(self, i: typing.SupportsInt | typing.SupportsIndex, w: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        wet fraction of stone i; when it grows, (M + M') v is kept
        """
    def stable_dt(self) -> float:
        """
        the stable DEM step [s] of the stones' contacts (the stone model's bound); advance() substeps never exceed min(params.dt, it)
        """
    def step(self, dt: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        one DEM step of dt [s] (checked against the stable step); the GIL is released
        """
    def volume(self, i: typing.SupportsInt | typing.SupportsIndex) -> float:
        """
        V_i [m^3] of stone i: that of the 3D stone its model stands for
        """
    @property
    def clump_offset(self) -> list[int]:
        """
        clump stones' first rows of clump_sphere (n + 1), a copy; empty for other stones
        """
    @property
    def clump_sphere(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        clump stones' spheres (m, 4) rows (x, y, z, r) [m] in each stone's principal frame (a copy; empty for other stones); stone i owns rows clump_offset[i]:clump_offset[i + 1]
        """
    @property
    def contact_count(self) -> int:
        """
        touching stone-stone contacts at the last force evaluation
        """
    @property
    def damping_ratio(self) -> float:
        """
        normal damping ratio zeta [-] from params.restitution
        """
    @property
    def held(self) -> bool:
        """
        True: every stone held in place, steps advance the time alone and the contacts keep their springs (a run's spin-up); False lets them go. Holding stops the stones. Not in export_state()
        """
    @held.setter
    def held(self, arg1: bool) -> None:
        ...
    @property
    def n(self) -> int:
        """
        number of stones (removed ones included; see stone_active)
        """
    @property
    def neighbour_builds(self) -> int:
        """
        how often the neighbour (Verlet) list was built
        """
    @property
    def params(self) -> DEMParams:
        """
        a copy (editing it changes nothing); assign a modified copy to change them, checked
        """
    @params.setter
    def params(self, arg1: DEMParams) -> None:
        ...
    @property
    def poly_offset(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        stone i owns poly_vertex[poly_offset[i]:poly_offset[i + 1]] (n + 1), zero-copy view
        """
    @property
    def poly_vertex(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        polygon stones' body-frame vertices (m, 2) [m], zero-copy view (set_polygons reallocates it)
        """
    @property
    def profile(self) -> StageProfile:
        """
        wall-clock seconds per DEM stage (StageProfile)
        """
    @property
    def removed_count(self) -> int:
        """
        stones that left the domain (stone_active = 0)
        """
    @property
    def shape(self) -> str:
        """
        the stone model's registered name (stone_model_names())
        """
    @property
    def steps(self) -> int:
        """
        DEM steps taken
        """
    @property
    def stiffness_normal(self) -> float:
        """
        normal contact stiffness k_n in use [N/m] (params.stiffness_normal, or the automatic value)
        """
    @property
    def stiffness_tangential(self) -> float:
        """
        tangential contact stiffness k_t = stiffness_ratio k_n [N/m]
        """
    @property
    def stone_acc(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        acceleration of the last evaluation (n, 2) [m/s^2], zero-copy view
        """
    @property
    def stone_acc_y(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        3D stones: acceleration across the flume of the last evaluation (n) [m/s^2], zero-copy view
        """
    @property
    def stone_active(self) -> numpy.typing.NDArray[numpy.uint8]:
        """
        0: the stone left the domain (kept, not integrated) (n), zero-copy view
        """
    @property
    def stone_alpha(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        angular acceleration of the last evaluation (n) [rad/s^2], zero-copy view
        """
    @property
    def stone_angle(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        rotation angle, counter-clockwise in (x, z) (n) [rad], zero-copy view
        """
    @property
    def stone_asleep(self) -> numpy.typing.NDArray[numpy.uint8]:
        """
        1: the stone sleeps (not integrated) (n), zero-copy view
        """
    @property
    def stone_density(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        stone density rho_s (n) [kg/m^3], zero-copy view
        """
    @property
    def stone_drag_coef(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        linear drag coefficient c >= 0 per stone (n) [N s/m], zero-copy view
        """
    @property
    def stone_drag_vel(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        velocity U the linear drag c (U - v) pulls towards (n, 2) [m/s], zero-copy view
        """
    @property
    def stone_fixed(self) -> numpy.typing.NDArray[numpy.uint8]:
        """
        1: the stone never moves (bed layer) (n), zero-copy view
        """
    @property
    def stone_force(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        total force of the last evaluation (n, 2) [N], zero-copy view
        """
    @property
    def stone_force_ext(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        external (fluid) forces (n, 2) [N], held until changed; zero-copy view
        """
    @property
    def stone_force_y(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        3D stones: total force across the flume of the last evaluation (n) [N], zero-copy view
        """
    @property
    def stone_omega(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        angular velocity (n) [rad/s], zero-copy view
        """
    @property
    def stone_omega_3d(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        3D stones: angular velocity in the world frame (x, y, z) (n, 3) [rad/s], zero-copy view
        """
    @property
    def stone_pos(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        centres (x along the flume, z up) (n, 2) [m], zero-copy view
        """
    @property
    def stone_quat(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        3D stones: orientation, unit quaternions (w, x, y, z) body -> world (n, 4) [-], zero-copy view
        """
    @property
    def stone_radius(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        radius (n) [m] (a disc's d / 2, a polygon's nominal one), zero-copy view
        """
    @property
    def stone_torque(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        total torque of the last evaluation (n) [N m], zero-copy view
        """
    @property
    def stone_torque_3d(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        3D stones: total torque about the centre of the last evaluation, world frame (n, 3) [N m], zero-copy view
        """
    @property
    def stone_vel(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        velocities (n, 2) [m/s], zero-copy view
        """
    @property
    def stone_vel_y(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        3D stones: velocity across the flume (n) [m/s] (empty for the plane's models), zero-copy view
        """
    @property
    def stone_water_level(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        free-surface level at each stone [m]; NaN: stone_wet held as set
        """
    @property
    def stone_wet(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        wet fraction in [0, 1] (n) [-], zero-copy view
        """
    @property
    def stone_y(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        3D stones: centre across the flume, 0 <= y <= width (n) [m] (empty for the plane's models), zero-copy view
        """
    @property
    def time(self) -> float:
        """
        simulated time of the stones [s]
        """
    @property
    def wall_contact_count(self) -> int:
        """
        touching stone-wall contacts at the last force evaluation
        """
class WeirSpec:
    """
    Trapezoidal rubble mound weir to pack (SI units; see weir_packing.h).
    """
    def __init__(self) -> None:
        ...
    def area(self) -> float:
        """
        The trapezoid's area [m^2].
        """
    def top(self, x: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        The trapezoid's height above the bed [m] at x [m] (0 outside).
        """
    def x_end(self) -> float:
        """
        The downstream toe [m] along the flume.
        """
    @property
    def aspect_ratio(self) -> float:
        """
        length / thickness of a polygon stone's section [-], [1, 3], default 1.5
        """
    @aspect_ratio.setter
    def aspect_ratio(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def clump_names(self) -> list[str]:
        """
        library shapes clump stones draw with equal chances (shape 'clump'; quarried_stone_names())
        """
    @clump_names.setter
    def clump_names(self, arg1: collections.abc.Sequence[str]) -> None:
        ...
    @property
    def clump_ratio_intermediate(self) -> float:
        """
        clumps' intermediate / long axis p [-], in [clump_ratio_short, 1], default 0.8
        """
    @clump_ratio_intermediate.setter
    def clump_ratio_intermediate(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def clump_ratio_short(self) -> float:
        """
        clumps' short / long axis q [-], in [0.55, 1], default 0.6
        """
    @clump_ratio_short.setter
    def clump_ratio_short(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def compaction_friction(self) -> float:
        """
        3D models: the stone-stone friction of the pour's rounds, a compaction before the weir's own friction returns [-], in [0, 2]; -1: the stone model's own (clumps 0.1, spheres none), default -1
        """
    @compaction_friction.setter
    def compaction_friction(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def crest(self) -> float:
        """
        crest length L_c [m], default 0.2
        """
    @crest.setter
    def crest(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def d_mean(self) -> float:
        """
        mean stone diameter [m], > 0, required (0: unset), default 0
        """
    @d_mean.setter
    def d_mean(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def d_spread(self) -> float:
        """
        half-width of the uniform diameter distribution, relative [-], default 0.1
        """
    @d_spread.setter
    def d_spread(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def density(self) -> float:
        """
        stone density [kg/m^3], > 0, required (0: unset), default 0
        """
    @density.setter
    def density(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def height(self) -> float:
        """
        crest height H above the bed [m], default 0.25
        """
    @height.setter
    def height(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def polygon_vertices_max(self) -> int:
        """
        most vertices of a polygon stone [-], [polygon_vertices_min, 16], default 8
        """
    @polygon_vertices_max.setter
    def polygon_vertices_max(self, arg1: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def polygon_vertices_min(self) -> int:
        """
        fewest vertices of a polygon stone [-], [3, 16], default 5
        """
    @polygon_vertices_min.setter
    def polygon_vertices_min(self, arg1: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def radial_jitter(self) -> float:
        """
        polygon vertex radii 1 +- jitter before the hull [-], [0, 0.5], default 0.2
        """
    @radial_jitter.setter
    def radial_jitter(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rest_speed(self) -> float:
        """
        the packing is at rest when every stone is slower [m/s], default 0.001
        """
    @rest_speed.setter
    def rest_speed(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def seed(self) -> int:
        """
        random seed of the diameters, shapes and lattice jitter [-], default 0
        """
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def settle_time_max(self) -> float:
        """
        simulated time allowed each settling phase [s], default 6
        """
    @settle_time_max.setter
    def settle_time_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def shape(self) -> str:
        """
        the stone model drawn, by its registered name (stone_model_names()), default 'disc'
        """
    @shape.setter
    def shape(self, arg1: str) -> None:
        ...
    @property
    def slope_down_deg(self) -> float:
        """
        downstream slope [deg], default 27
        """
    @slope_down_deg.setter
    def slope_down_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def slope_up_deg(self) -> float:
        """
        upstream slope [deg], default 27
        """
    @slope_up_deg.setter
    def slope_up_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def x_toe(self) -> float:
        """
        upstream toe along the flume [m], default 1
        """
    @x_toe.setter
    def x_toe(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def z_bed(self) -> float:
        """
        bed height [m], default 0
        """
    @z_bed.setter
    def z_bed(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class WeirPackingReport:
    """
    What pack_weir produced.
    """
    def __repr__(self) -> str:
        ...
    @property
    def max_speed(self) -> float:
        """
        largest stone speed at the end [m/s]
        """
    @property
    def n_fixed(self) -> int:
        """
        fixed bottom stones
        """
    @property
    def n_stones(self) -> int:
        """
        stones in the weir, the fixed ones included
        """
    @property
    def outline_error(self) -> float:
        """
        weir_outline_error() of the result [m]
        """
    @property
    def porosity(self) -> float:
        """
        porosity of the trapezoid [-]: 1 - (stone area inside) / area in the plane; for 3D stones that of the prism across the width, 1 - (stone volume inside) / (area B)
        """
    @property
    def settle_time(self) -> float:
        """
        simulated time of the settling phases [s]
        """
    @property
    def stones_across(self) -> float:
        """
        3D stones: the mean number of stones a line across the flume through the trapezoid crosses [-] (0 in the plane)
        """
    @property
    def wall_seconds(self) -> float:
        """
        wall-clock time of the packing [s]
        """
class VofBoundaryInflow:
    """
    Water fraction [-] entering through each boundary face where the flow enters (left/right: nz, bottom/top: nx); empty = 0. The arrays are numpy views, writable in place; assigning a whole side replaces its array (earlier views of it are invalidated).
    """
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, grid: Grid2D, value: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def resize(self, grid: Grid2D, value: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        """
        Sizes the four sides for `grid` filled with `value`; invalidates earlier views.
        """
    @property
    def bottom(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        fraction entering through the bottom, per column (nx)
        """
    @bottom.setter
    def bottom(self, arg1: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def left(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        fraction entering at x = x0, per row (nz)
        """
    @left.setter
    def left(self, arg1: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def right(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        fraction entering at the right end, per row (nz)
        """
    @right.setter
    def right(self, arg1: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def top(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        fraction entering through the top, per column (nx)
        """
    @top.setter
    def top(self, arg1: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
class VofNormal:
    """
    Interface normal of the PLIC reconstruction.
    
    Members:
    
      YOUNGS : Youngs (1982): weighted 3x3 gradient of F (default)
    
      MIXED_YOUNGS_CENTERED : Aulisa et al. (2007): height-function normal of the 3x3 block, else Youngs
    """
    MIXED_YOUNGS_CENTERED: typing.ClassVar[VofNormal]
    YOUNGS: typing.ClassVar[VofNormal]
    __members__: typing.ClassVar[dict[str, VofNormal]]
    @typing.overload
    def __eq__(self, other: VofNormal) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: VofNormal) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class VofScratch:
    """
    Work arrays of advect_vof, its water fluxes and clipping report.
    """
    def __init__(self) -> None:
        ...
    @property
    def clip_count(self) -> int:
        """
        cell updates clipped by more than VOF_CLIP_TOLERANCE (0 when the CFL limit holds)
        """
    @clip_count.setter
    def clip_count(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def clip_max(self) -> float:
        """
        largest such excursion of F outside [0, 1]
        """
    @clip_max.setter
    def clip_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def face_flux_x(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        water volume [m^2 per m of width] through each x-face in the last step, along +x (read-only view; empty before the first step)
        """
    @property
    def face_flux_z(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        water volume [m^2 per m of width] through each z-face in the last step, along +z (read-only view)
        """
class PressureSolverKind:
    """
    Solver of the pressure Poisson problem of the projection (FlowParams.pressure_solver).
    
    Members:
    
      EIGEN_DIRECT : Eigen sparse LDL^T: exact to round-off, the reference
    
      MULTIGRID_CG : conjugate gradient preconditioned by a geometric multigrid V-cycle: the default
    """
    EIGEN_DIRECT: typing.ClassVar[PressureSolverKind]
    MULTIGRID_CG: typing.ClassVar[PressureSolverKind]
    __members__: typing.ClassVar[dict[str, PressureSolverKind]]
    @typing.overload
    def __eq__(self, other: PressureSolverKind) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: PressureSolverKind) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class PressureProblem:
    """
    Face coefficients a_f, Dirichlet boundary values [Pa] and active cells of the pressure equation sum_f a_f (p_nb - p_c) = b_c. Arrays are zero-copy numpy views.
    """
    def __init__(self, grid: Grid2D) -> None:
        ...
    @property
    def cell_active(self) -> numpy.typing.NDArray[numpy.uint8]:
        """
        1: an unknown of the equation, 0: a solid cell (ncell), zero-copy view
        """
    @property
    def face_x_bc(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        Dirichlet pressure on the boundary x-faces (i = 0, nx) [Pa], zero-copy view
        """
    @property
    def face_x_coef(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        face coefficient a_f >= 0 on the x-faces, (nx + 1) nz [m^3 s/kg] (0 closes a face), zero-copy view
        """
    @property
    def face_z_bc(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        Dirichlet pressure on the boundary z-faces (k = 0, nz) [Pa], zero-copy view
        """
    @property
    def face_z_coef(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        face coefficient a_f >= 0 on the z-faces, nx (nz + 1) [m^3 s/kg], zero-copy view
        """
class PressureSolveStats:
    """
    Outcome of one pressure solve.
    """
    def __repr__(self) -> str:
        ...
    @property
    def iterations(self) -> int:
        """
        CG iterations (0 for the direct solver)
        """
    @property
    def residual(self) -> float:
        """
        final relative residual ||f - M p|| / ||f||
        """
    @property
    def setup_seconds(self) -> float:
        """
        last setup wall time [s]
        """
    @property
    def solve_seconds(self) -> float:
        """
        solve wall time [s]
        """
class PressureSolver:
    """
    Solver of the pressure projection equation.
    """
    def __init__(self, kind: PressureSolverKind = ..., max_iterations: typing.SupportsInt | typing.SupportsIndex = 200, smoothing_sweeps: typing.SupportsInt | typing.SupportsIndex = 1, coarsest_cells: typing.SupportsInt | typing.SupportsIndex = 64) -> None:
        ...
    def setup(self, grid: Grid2D, problem: PressureProblem) -> None:
        """
        takes new coefficients (call after any change)
        """
    def solve(self, rhs: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], p: numpy.typing.NDArray[numpy.float64], tol: typing.SupportsFloat | typing.SupportsIndex = 1e-08) -> PressureSolveStats:
        """
        solves for p [Pa] in place (a C-contiguous float64 array of ncell values, also the initial guess); returns PressureSolveStats
        """
    @property
    def kind(self) -> PressureSolverKind:
        """
        the solver (PressureSolverKind) chosen at construction
        """
class FlowEffect(enum.IntFlag):
    """
    Bit flags of the flow solver's physical effects.
    """
    CONVECTION: typing.ClassVar[FlowEffect]
    DEFAULT: typing.ClassVar[FlowEffect]
    FREE_SURFACE: typing.ClassVar[FlowEffect]
    GRAVITY: typing.ClassVar[FlowEffect]
    POROUS_DARCY: typing.ClassVar[FlowEffect]
    POROUS_FORCHHEIMER: typing.ClassVar[FlowEffect]
    POROUS_RESISTANCE: typing.ClassVar[FlowEffect]
    RELATIVE_VELOCITY: typing.ClassVar[FlowEffect]
    TURBULENCE: typing.ClassVar[FlowEffect]
    VISCOSITY: typing.ClassVar[FlowEffect]
    @classmethod
    def __new__(cls, value):
        ...
    def __and__(self, other):
        ...
    def __format__(self, format_spec):
        ...
    def __invert__(self):
        ...
    def __or__(self, other):
        ...
    def __rand__(self, other):
        ...
    def __ror__(self, other):
        ...
    def __rxor__(self, other):
        ...
    def __xor__(self, other):
        ...
class InletBoundary:
    """
    The upstream end x = 0 of the flume (FlowParams.inlet).
    
    Members:
    
      WALL : a closed wall
    
      DISCHARGE : prescribed discharge Q(t) over the wetted inlet
    """
    DISCHARGE: typing.ClassVar[InletBoundary]
    WALL: typing.ClassVar[InletBoundary]
    __members__: typing.ClassVar[dict[str, InletBoundary]]
    @typing.overload
    def __eq__(self, other: InletBoundary) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: InletBoundary) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class InletProfile:
    """
    How the inlet spreads the discharge [m^3/s] over its rows (FlowParams.inlet_profile).
    
    Members:
    
      EQUIVALENT_DEPTH : the rows below the inlet's level h = sum(F dz)
    
      WATER_FRACTION : every row by its water fraction (the former profile)
    """
    EQUIVALENT_DEPTH: typing.ClassVar[InletProfile]
    WATER_FRACTION: typing.ClassVar[InletProfile]
    __members__: typing.ClassVar[dict[str, InletProfile]]
    @typing.overload
    def __eq__(self, other: InletProfile) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: InletProfile) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class OutletBoundary:
    """
    The downstream end of the flume (FlowParams.outlet).
    
    Members:
    
      WALL : a closed wall
    
      FREE_OVERFALL : the end face is a brink open to still air (hydrostatic air pressure)
    
      TAILWATER : hydrostatic pressure below FlowParams.tailwater_level
    """
    FREE_OVERFALL: typing.ClassVar[OutletBoundary]
    TAILWATER: typing.ClassVar[OutletBoundary]
    WALL: typing.ClassVar[OutletBoundary]
    __members__: typing.ClassVar[dict[str, OutletBoundary]]
    @typing.overload
    def __eq__(self, other: OutletBoundary) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: OutletBoundary) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class TopBoundary:
    """
    The top of the domain (FlowParams.top).
    
    Members:
    
      OPEN : open to the atmosphere, p = 0
    
      WALL : a slip lid
    """
    OPEN: typing.ClassVar[TopBoundary]
    WALL: typing.ClassVar[TopBoundary]
    __members__: typing.ClassVar[dict[str, TopBoundary]]
    @typing.overload
    def __eq__(self, other: TopBoundary) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: TopBoundary) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class WallCondition:
    """
    Tangential velocity at the bed and the closed walls (FlowParams.walls).
    
    Members:
    
      SLIP : no shear stress: the tangential velocity slips
    
      NO_SLIP : zero tangential velocity at the wall
    """
    NO_SLIP: typing.ClassVar[WallCondition]
    SLIP: typing.ClassVar[WallCondition]
    __members__: typing.ClassVar[dict[str, WallCondition]]
    @typing.overload
    def __eq__(self, other: WallCondition) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: WallCondition) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class ViscousScheme:
    """
    Time stepping of the viscous (molecular + eddy) stresses (FlowParams.viscous_scheme).
    
    Members:
    
      EXPLICIT : forward Euler of every stress: the step limit dz^2 / (4 nu)
    
      IMPLICIT_VERTICAL : the vertical diffusion by backward Euler per column, from the velocities after the explicit part
    
      IMPLICIT_VERTICAL_FROM_START : the former scheme: the columns from u^n beside the explicit part (unstable above 0.7 of its limit)
    
      IMPLICIT : rows and columns implicit, the cross terms explicit: no step bound
    """
    EXPLICIT: typing.ClassVar[ViscousScheme]
    IMPLICIT: typing.ClassVar[ViscousScheme]
    IMPLICIT_VERTICAL: typing.ClassVar[ViscousScheme]
    IMPLICIT_VERTICAL_FROM_START: typing.ClassVar[ViscousScheme]
    __members__: typing.ClassVar[dict[str, ViscousScheme]]
    @typing.overload
    def __eq__(self, other: ViscousScheme) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: ViscousScheme) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class ViscousBound:
    """
    Bound of the viscous step limit [s] (FlowParams.viscous_bound).
    
    Members:
    
      ENERGY : the split scheme's energy bound: no cross terms (a proof)
    
      ROW_SUM : Gershgorin row sums of the explicit stresses, cross terms in
    """
    ENERGY: typing.ClassVar[ViscousBound]
    ROW_SUM: typing.ClassVar[ViscousBound]
    __members__: typing.ClassVar[dict[str, ViscousBound]]
    @typing.overload
    def __eq__(self, other: ViscousBound) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: ViscousBound) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class KEpsilonPoreStrain:
    """
    Which velocity's cross derivatives dU/dz, dW/dx [1/s] enter the k-epsilon production in porous cells (FlowParams.turbulence_pore_strain).
    
    Members:
    
      NEIGHBOURS : each neighbour's own pore velocity u / n
    
      LOCAL : the neighbours' superficial velocities over this cell's porosity
    
      FILTERED : the pore velocity over the porosity averaged over a box of turbulence_pore_filter_length [m]
    """
    FILTERED: typing.ClassVar[KEpsilonPoreStrain]
    LOCAL: typing.ClassVar[KEpsilonPoreStrain]
    NEIGHBOURS: typing.ClassVar[KEpsilonPoreStrain]
    __members__: typing.ClassVar[dict[str, KEpsilonPoreStrain]]
    @typing.overload
    def __eq__(self, other: KEpsilonPoreStrain) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: KEpsilonPoreStrain) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class KEpsilonProduction:
    """
    Production term P [m^2/s^3] of k (FlowParams.turbulence_production).
    
    Members:
    
      STRAIN : P = nu_t S^2 (the standard term)
    
      KATO_LAUNDER : P = nu_t S Omega: none in irrotational strain
    """
    KATO_LAUNDER: typing.ClassVar[KEpsilonProduction]
    STRAIN: typing.ClassVar[KEpsilonProduction]
    __members__: typing.ClassVar[dict[str, KEpsilonProduction]]
    @typing.overload
    def __eq__(self, other: KEpsilonProduction) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: KEpsilonProduction) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class KEpsilonTimeScheme:
    """
    Time stepping of the k-epsilon transport (FlowParams.turbulence_time_scheme).
    
    Members:
    
      POINT_IMPLICIT : predictor and Jacobi sweeps; the step bounded by the explicit limit of all faces
    
      VERTICAL_LINES : columns backward Euler by tridiagonal solves; the step bounded by the horizontal faces only
    
      ALTERNATING_LINES : rows then columns backward Euler by tridiagonal solves; the step bounded by the horizontal advection only
    """
    ALTERNATING_LINES: typing.ClassVar[KEpsilonTimeScheme]
    POINT_IMPLICIT: typing.ClassVar[KEpsilonTimeScheme]
    VERTICAL_LINES: typing.ClassVar[KEpsilonTimeScheme]
    __members__: typing.ClassVar[dict[str, KEpsilonTimeScheme]]
    @typing.overload
    def __eq__(self, other: KEpsilonTimeScheme) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: KEpsilonTimeScheme) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class MomentumTimeScheme:
    """
    Time integration of the convective term (FlowParams.time_scheme).
    
    Members:
    
      EULER : forward Euler of the explicit momentum terms (first order)
    
      ADAMS_BASHFORTH2 : variable-step Adams-Bashforth 2 of the explicit momentum terms (second order)
    """
    ADAMS_BASHFORTH2: typing.ClassVar[MomentumTimeScheme]
    EULER: typing.ClassVar[MomentumTimeScheme]
    __members__: typing.ClassVar[dict[str, MomentumTimeScheme]]
    @typing.overload
    def __eq__(self, other: MomentumTimeScheme) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: MomentumTimeScheme) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class StepControl:
    """
    The advective limit a flow step is taken under (FlowParams.step_control).
    
    Members:
    
      THIS_STEP : the limit of the step's start
    
      TWO_STEPS : the smaller of the limits of this step's start and the last step's: a two-step flicker is not chased
    """
    THIS_STEP: typing.ClassVar[StepControl]
    TWO_STEPS: typing.ClassVar[StepControl]
    __members__: typing.ClassVar[dict[str, StepControl]]
    @typing.overload
    def __eq__(self, other: StepControl) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: StepControl) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class CornerViscosity:
    """
    Viscosity [Pa s] of a cell corner, where the shear stress lives, from its four cells (FlowParams.corner_viscosity).
    
    Members:
    
      ARITHMETIC : the arithmetic mean of the four cells
    
      HARMONIC : the molecular part by arithmetic, the eddy part by harmonic mean (none next to air or solid)
    """
    ARITHMETIC: typing.ClassVar[CornerViscosity]
    HARMONIC: typing.ClassVar[CornerViscosity]
    __members__: typing.ClassVar[dict[str, CornerViscosity]]
    @typing.overload
    def __eq__(self, other: CornerViscosity) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: CornerViscosity) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class FlowParams:
    """
    Flow parameters, constant while stepping (SI units).
    """
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        """
        ValueError naming the first parameter outside its range.
        """
    @property
    def cfl(self) -> float:
        """
        target Courant number of the pore velocity [-], default 0.5
        """
    @cfl.setter
    def cfl(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def corner_viscosity(self) -> CornerViscosity:
        """
        CornerViscosity of the shear stress at a cell corner, default HARMONIC
        """
    @corner_viscosity.setter
    def corner_viscosity(self, arg0: CornerViscosity) -> None:
        ...
    @property
    def flags(self) -> int:
        """
        FlowEffect bits of the effects that are on
        """
    @flags.setter
    def flags(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def flume_width(self) -> float:
        """
        flume width B [m], default 0.5
        """
    @flume_width.setter
    def flume_width(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gravity_x(self) -> float:
        """
        alias of medium.gravity[0] [m/s^2]
        """
    @gravity_x.setter
    def gravity_x(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gravity_z(self) -> float:
        """
        alias of medium.gravity[1] [m/s^2]
        """
    @gravity_z.setter
    def gravity_z(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def initial_dt(self) -> float:
        """
        first time step [s], default 0.001
        """
    @initial_dt.setter
    def initial_dt(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def inlet(self) -> InletBoundary:
        """
        InletBoundary of the left end (x = x0), default WALL
        """
    @inlet.setter
    def inlet(self, arg0: InletBoundary) -> None:
        ...
    @property
    def inlet_profile(self) -> InletProfile:
        """
        InletProfile of the discharge over the inlet rows
        """
    @inlet_profile.setter
    def inlet_profile(self, arg0: InletProfile) -> None:
        ...
    @property
    def k1(self) -> float:
        """
        linear resistance coefficient of eq. (7) [-], default 200
        """
    @k1.setter
    def k1(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def k2(self) -> float:
        """
        quadratic resistance coefficient of eq. (7) [-], default 2.8
        """
    @k2.setter
    def k2(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_dt(self) -> float:
        """
        largest time step [s], default 0.01
        """
    @max_dt.setter
    def max_dt(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_dt_growth(self) -> float:
        """
        dt <= max_dt_growth * the last step [-], default 1.2
        """
    @max_dt_growth.setter
    def max_dt_growth(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def medium(self) -> Medium:
        """
        water, air and gravity (Medium), shared with the stones
        """
    @medium.setter
    def medium(self, arg0: Medium) -> None:
        ...
    @property
    def min_dt(self) -> float:
        """
        a stable step below this is a failure [s], default 1e-08
        """
    @min_dt.setter
    def min_dt(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nu_air(self) -> float:
        """
        alias of medium.nu_air [m^2/s]
        """
    @nu_air.setter
    def nu_air(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nu_water(self) -> float:
        """
        alias of medium.nu_water [m^2/s]
        """
    @nu_water.setter
    def nu_water(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def outlet(self) -> OutletBoundary:
        """
        OutletBoundary of the right end, default FREE_OVERFALL
        """
    @outlet.setter
    def outlet(self, arg0: OutletBoundary) -> None:
        ...
    @property
    def pressure_solver(self) -> PressureSolverKind:
        """
        PressureSolverKind of the projection, default MULTIGRID_CG
        """
    @pressure_solver.setter
    def pressure_solver(self, arg0: PressureSolverKind) -> None:
        ...
    @property
    def pressure_tol(self) -> float:
        """
        relative residual of the pressure solve [-]
        """
    @pressure_tol.setter
    def pressure_tol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rho_air(self) -> float:
        """
        alias of medium.rho_air [kg/m^3]
        """
    @rho_air.setter
    def rho_air(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rho_water(self) -> float:
        """
        alias of medium.rho_water [kg/m^3]
        """
    @rho_water.setter
    def rho_water(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def step_control(self) -> StepControl:
        """
        StepControl: the advective limit of one step or the last two
        """
    @step_control.setter
    def step_control(self, arg0: StepControl) -> None:
        ...
    @property
    def tailwater_level(self) -> float:
        """
        tailwater level [m] for OutletBoundary.TAILWATER
        """
    @tailwater_level.setter
    def tailwater_level(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def time_scheme(self) -> MomentumTimeScheme:
        """
        MomentumTimeScheme of the explicit momentum terms
        """
    @time_scheme.setter
    def time_scheme(self, arg0: MomentumTimeScheme) -> None:
        ...
    @property
    def top(self) -> TopBoundary:
        """
        TopBoundary of the domain, default OPEN
        """
    @top.setter
    def top(self, arg0: TopBoundary) -> None:
        ...
    @property
    def turbulence_bed_roughness(self) -> float:
        """
        equivalent sand roughness k_s of the bed [m]
        """
    @turbulence_bed_roughness.setter
    def turbulence_bed_roughness(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def turbulence_cfl(self) -> float:
        """
        safety factor of the k-epsilon step limit [-], (0, 1], default 0.5
        """
    @turbulence_cfl.setter
    def turbulence_cfl(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def turbulence_inflow_intensity(self) -> float:
        """
        inflow turbulence intensity [-], default 0.05
        """
    @turbulence_inflow_intensity.setter
    def turbulence_inflow_intensity(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def turbulence_inflow_length_scale(self) -> float:
        """
        inflow length scale [m], default 0.01
        """
    @turbulence_inflow_length_scale.setter
    def turbulence_inflow_length_scale(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def turbulence_limit_step(self) -> bool:
        """
        VERTICAL_LINES, ALTERNATING_LINES: the explicit part's limit (the horizontal faces', or the horizontal advection's alone) bounds the step (True) or not (False: not accurate in the weir, docs/k_epsilon.md); POINT_IMPLICIT always limits the step and refuses False
        """
    @turbulence_limit_step.setter
    def turbulence_limit_step(self, arg1: bool) -> None:
        ...
    @property
    def turbulence_pore_filter_length(self) -> float:
        """
        side of the FILTERED pore strain's averaging box [m]
        """
    @turbulence_pore_filter_length.setter
    def turbulence_pore_filter_length(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def turbulence_pore_strain(self) -> KEpsilonPoreStrain:
        """
        k-epsilon strain's cross derivatives: NEIGHBOURS' pore velocities, superficial over this cell's n (LOCAL), or FILTERED (pore velocities over a box-filtered n)
        """
    @turbulence_pore_strain.setter
    def turbulence_pore_strain(self, arg1: KEpsilonPoreStrain) -> None:
        ...
    @property
    def turbulence_production(self) -> KEpsilonProduction:
        """
        production of k: STRAIN (nu_t S^2) or KATO_LAUNDER (nu_t S Omega)
        """
    @turbulence_production.setter
    def turbulence_production(self, arg1: KEpsilonProduction) -> None:
        ...
    @property
    def turbulence_production_limit(self) -> float:
        """
        P_k <= limit * eps (Menter 1994: 10), 0 = off [-]
        """
    @turbulence_production_limit.setter
    def turbulence_production_limit(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def turbulence_time_scheme(self) -> KEpsilonTimeScheme:
        """
        k-epsilon time stepping: POINT_IMPLICIT, VERTICAL_LINES or ALTERNATING_LINES
        """
    @turbulence_time_scheme.setter
    def turbulence_time_scheme(self, arg1: KEpsilonTimeScheme) -> None:
        ...
    @property
    def turbulence_wall_roughness(self) -> float:
        """
        k_s of end walls and solid cells [m]
        """
    @turbulence_wall_roughness.setter
    def turbulence_wall_roughness(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def viscous_bound(self) -> ViscousBound:
        """
        ViscousBound of the viscous step (IMPLICIT_VERTICAL only; the other schemes: ROW_SUM)
        """
    @viscous_bound.setter
    def viscous_bound(self, arg0: ViscousBound) -> None:
        ...
    @property
    def viscous_scheme(self) -> ViscousScheme:
        """
        ViscousScheme of the viscous stresses (EXPLICIT: the forward-Euler reference), default IMPLICIT_VERTICAL
        """
    @viscous_scheme.setter
    def viscous_scheme(self, arg0: ViscousScheme) -> None:
        ...
    @property
    def viscous_substeps(self) -> int:
        """
        the viscous stresses in up to this many substeps of a flow step [-], [1, 64]; 1: one explicit step, default 8
        """
    @viscous_substeps.setter
    def viscous_substeps(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def walls(self) -> WallCondition:
        """
        WallCondition of the bed and the end walls, default SLIP
        """
    @walls.setter
    def walls(self, arg0: WallCondition) -> None:
        ...
class DischargeTable:
    """
    Piecewise-linear discharge Q(t): times [s], discharge [m^3/s].
    """
    @staticmethod
    def constant(q: typing.SupportsFloat | typing.SupportsIndex) -> DischargeTable:
        ...
    @staticmethod
    def ramp(q0: typing.SupportsFloat | typing.SupportsIndex, q1: typing.SupportsFloat | typing.SupportsIndex, t0: typing.SupportsFloat | typing.SupportsIndex, t1: typing.SupportsFloat | typing.SupportsIndex) -> DischargeTable:
        """
        linear ramp from q0 to q1 [m^3/s] over [t0, t1] [s]
        """
    def __init__(self, times: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], discharge: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    def at(self, t: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        Q [m^3/s] at time t [s]
        """
    @property
    def discharge(self) -> list[float]:
        """
        discharge Q at each time [m^3/s], >= 0
        """
    @property
    def times(self) -> list[float]:
        """
        times [s], strictly increasing
        """
class FlowStableDt:
    """
    Largest stable time step [s] of each term (inf: no limit).
    """
    def min(self) -> float:
        """
        the smallest of the terms: the stable step [s]
        """
    @property
    def advective(self) -> float:
        """
        cfl times the smallest h / abs(u / n) over the faces (pore velocity) [s]
        """
    @property
    def advective_cell(self) -> int:
        """
        the cell beside the face that binds the advective limit (-1: none)
        """
    @property
    def gravity(self) -> float:
        """
        cfl times sqrt(2 h_min / abs(g)): a cell crossed by a fall from rest [s]
        """
    @property
    def growth(self) -> float:
        """
        initial_dt before the first step, then max_dt_growth times the last step [s]
        """
    @property
    def max_dt(self) -> float:
        """
        FlowParams.max_dt [s]
        """
    @property
    def turbulence(self) -> float:
        """
        the k-epsilon model's limit [s] (inf when off)
        """
    @property
    def turbulence_cell(self) -> int:
        """
        the cell that binds the k-epsilon limit (-1: none)
        """
    @property
    def viscous(self) -> float:
        """
        the explicit viscous stresses' bound times viscous_substeps [s] (inf with the implicit scheme)
        """
    @property
    def viscous_cell(self) -> int:
        """
        the cell beside the face that binds the viscous limit (-1: none)
        """
class FlowState:
    """
    A copy of a VOFGrid's whole state (VOFGrid.copy_state); set_state() returns to it.
    """
    @property
    def step_count(self) -> int:
        """
        steps taken since the start [-]
        """
    @property
    def time(self) -> float:
        """
        simulated time [s]
        """
class VOFGrid:
    """
    2D vertical free-surface flow through porous media (seed eqs. 1-4). State arrays are zero-copy numpy views: cells (nz, nx), x-faces (nz, nx+1), z-faces (nz+1, nx).
    """
    def __init__(self, grid: Grid2D, params: FlowParams = ...) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def advance(self, t_end: typing.SupportsFloat | typing.SupportsIndex) -> int:
        """
        steps of stable_dt() until time reaches t_end [s] (a step that breaches the CFL taken again shorter); returns the steps; the GIL is released
        """
    def clear_step_history(self) -> None:
        """
        forget the last step (the next one is forward Euler): after velocities were set by hand
        """
    def copy_state(self) -> FlowState:
        """
        a copy of the whole state (FlowState): set_state(copy) continues from it bit for bit
        """
    def discharge_through(self, i: typing.SupportsInt | typing.SupportsIndex) -> float:
        """
        water discharge per width [m^2/s]
        """
    def fill_water_below(self, level: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        water fraction F = 1 below level [m] (a partial fraction in the cut row), 0 above
        """
    def fill_water_box(self, x0: typing.SupportsFloat | typing.SupportsIndex, x1: typing.SupportsFloat | typing.SupportsIndex, z0: typing.SupportsFloat | typing.SupportsIndex, z1: typing.SupportsFloat | typing.SupportsIndex, value: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> None:
        """
        F = value in the cells whose centre lies in [x0, x1] x [z0, z1] [m], untouched elsewhere
        """
    def inlet_discharge_per_width(self) -> float:
        """
        q = Q(t) / B now [m^2/s]
        """
    def pore_velocity_at_cells(self) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
        """
        (U, W) = (u / n, w / n) at the cell centres (nz, nx) [m/s], 0 in solid cells, copied
        """
    def pressure_gradient_at_cells(self) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
        """
        (dp/dx, dp/dz) at the cell centres (nz, nx) [Pa/m] (central, one-sided at walls and solids), copied
        """
    def set_hydrostatic_pressure(self) -> None:
        """
        hydrostatic pressure [Pa] from the water fraction, p = 0 at the top
        """
    def set_porosity(self, porosity: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], displace: bool = False) -> None:
        """
        sets the cell porosity (ncell values in [0, 1]) and the face porosities; displace=True: the change is a source of the next step's continuity (dn/dt + div u = 0), so displaced water flows away
        """
    def set_porosity_box(self, x0: typing.SupportsFloat | typing.SupportsIndex, x1: typing.SupportsFloat | typing.SupportsIndex, z0: typing.SupportsFloat | typing.SupportsIndex, z1: typing.SupportsFloat | typing.SupportsIndex, n: typing.SupportsFloat | typing.SupportsIndex, d: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        porosity n [-] and stone diameter d [m] in the cells whose centre lies in [x0, x1] x [z0, z1] [m]; n = 0 makes solid cells
        """
    def set_state(self, state: FlowState) -> None:
        """
        returns to a copy_state() copy (checked first; written into the arrays in place: views stay valid)
        """
    def stable_dt(self) -> float:
        """
        the stable step [s]: the smallest of stable_dt_terms()
        """
    def stable_dt_terms(self) -> FlowStableDt:
        """
        the stable step's terms (FlowStableDt) [s], with the cells that bind them
        """
    def step(self, dt: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        one flow step of dt [s]; RuntimeError naming the stage, cell and time after restoring the step's start; the GIL is released
        """
    def update_face_porosity(self, displace: bool = False) -> None:
        """
        recomputes the face porosities after writing cell_porosity / cell_stone_diameter
        """
    def water_volume(self) -> float:
        """
        sum(n F V) per metre of width [m^2]
        """
    @property
    def cell_F(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        water fraction [-]
        """
    @property
    def cell_eps(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        dissipation rate [m^2/s^3] (k-epsilon)
        """
    @property
    def cell_k(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        turbulent kinetic energy [m^2/s^2] (k-epsilon)
        """
    @property
    def cell_nut(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        eddy viscosity [m^2/s]
        """
    @property
    def cell_p(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        pressure [Pa]
        """
    @property
    def cell_porosity(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        porosity [-] (0 = solid); call update_face_porosity() after writing
        """
    @property
    def cell_stone_diameter(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        stone diameter D_sp [m]
        """
    @property
    def dilatation_volume(self) -> float:
        """
        water volume per width [m^2] made by the advection's divergence correction where the velocity is not divergence-free (the pressure solve's residual), since construction
        """
    @property
    def discharge(self) -> DischargeTable:
        """
        DischargeTable Q(t) [m^3/s]
        """
    @discharge.setter
    def discharge(self, arg1: DischargeTable) -> None:
        ...
    @property
    def face_u(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        superficial x-velocity [m/s]
        """
    @property
    def face_w(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        superficial z-velocity [m/s]
        """
    @property
    def face_x_porosity(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        porosity n_f on the x-faces (nz, nx + 1) [-] (derived: the smaller of the two cells'), zero-copy view
        """
    @property
    def face_x_solid_u(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        stones' x-velocity at x-faces [m/s]
        """
    @property
    def face_z_porosity(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        porosity n_f on the z-faces (nz + 1, nx) [-] (derived), zero-copy view
        """
    @property
    def face_z_solid_w(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        stones' z-velocity at z-faces [m/s]
        """
    @property
    def grid(self) -> Grid2D:
        """
        the grid (Grid2D), owned by this flow
        """
    @property
    def inlet_volume(self) -> float:
        """
        water volume per width [m^2] that entered through the inlet
        """
    @property
    def last_advective(self) -> float:
        """
        the advective limit [s] measured at the last step's start (0: none)
        """
    @property
    def last_dt(self) -> float:
        """
        the last step [s] the growth limit starts from (0: none yet, initial_dt applies)
        """
    @last_dt.setter
    def last_dt(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def last_pressure_stats(self) -> PressureSolveStats:
        """
        the last pressure solve's outcome (PressureSolveStats: iterations, residual)
        """
    @property
    def net_inflow_volume(self) -> float:
        """
        water volume per width [m^2] in through the boundary faces minus out, since construction (the VOF advection's fluxes)
        """
    @property
    def params(self) -> FlowParams:
        """
        a copy (editing it changes nothing); assign a modified copy to change them, checked, with the pressure solver and the k-epsilon model rebuilt
        """
    @params.setter
    def params(self, arg1: FlowParams) -> None:
        ...
    @property
    def pressure_fallbacks(self) -> int:
        """
        multigrid-CG solves redone by the direct solver (no convergence)
        """
    @property
    def pressure_iterations(self) -> int:
        """
        CG iterations of every pressure solve since construction (a fallback counts max_iterations); per solve: over the 'pressure' stage's calls in profile
        """
    @property
    def prev_dt(self) -> float:
        """
        the last step [s] of the Adams-Bashforth history (0: none, the next step is Euler)
        """
    @property
    def profile(self) -> StageProfile:
        """
        wall-clock seconds per flow stage (StageProfile)
        """
    @property
    def retried_steps(self) -> int:
        """
        steps advance() took again, shorter, after a CFL breach
        """
    @property
    def step_count(self) -> int:
        """
        flow steps taken
        """
    @property
    def time(self) -> float:
        """
        simulated time [s]
        """
    @time.setter
    def time(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def turbulence_profile(self) -> StageProfile:
        """
        the k-epsilon model's own stages (setup, wall functions, production, transport, eddy viscosity, checks): the parts of the 'turbulence' stage
        """
class CouplerEffect(enum.IntFlag):
    """
    Bit flags of the coupling's effects (CouplerParams.flags).
    """
    CHECKS: typing.ClassVar[CouplerEffect]
    DEFAULT: typing.ClassVar[CouplerEffect]
    DEM: typing.ClassVar[CouplerEffect]
    DISPLACE_FLOW: typing.ClassVar[CouplerEffect]
    DRAG: typing.ClassVar[CouplerEffect]
    FLUID: typing.ClassVar[CouplerEffect]
    FORCES: typing.ClassVar[CouplerEffect]
    LOOKUP_POROSITY: typing.ClassVar[CouplerEffect]
    ONE_WAY: typing.ClassVar[CouplerEffect]
    OVERFLOW_LOAD: typing.ClassVar[CouplerEffect]
    POROSITY: typing.ClassVar[CouplerEffect]
    PRESSURE_GRADIENT: typing.ClassVar[CouplerEffect]
    TWO_WAY: typing.ClassVar[CouplerEffect]
    WET_FRACTION: typing.ClassVar[CouplerEffect]
    @classmethod
    def __new__(cls, value):
        ...
    def __and__(self, other):
        ...
    def __format__(self, format_spec):
        ...
    def __invert__(self):
        ...
    def __or__(self, other):
        ...
    def __rand__(self, other):
        ...
    def __ror__(self, other):
        ...
    def __rxor__(self, other):
        ...
    def __xor__(self, other):
        ...
class StoneDragModel:
    """
    Drag on the stones (one of the two, never both).
    
    Members:
    
      SPHERE : single sphere in the pore velocity, eqs. (16)-(18) (the paper's)
    
      BED : reaction of the flow's porous resistance, rho n R per bulk volume
    """
    BED: typing.ClassVar[StoneDragModel]
    SPHERE: typing.ClassVar[StoneDragModel]
    __members__: typing.ClassVar[dict[str, StoneDragModel]]
    @typing.overload
    def __eq__(self, other: StoneDragModel) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: StoneDragModel) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class CouplingMapping:
    """
    How the stones and the flow exchange cell fields.
    
    Members:
    
      CELL : each stone's exact footprint over the raw cells (the paper's)
    
      KERNEL : footprints and flow smoothed by a Gaussian exp(-r^2/b^2) of physical width b (kernel_smoothing.h)
    """
    CELL: typing.ClassVar[CouplingMapping]
    KERNEL: typing.ClassVar[CouplingMapping]
    __members__: typing.ClassVar[dict[str, CouplingMapping]]
    @typing.overload
    def __eq__(self, other: CouplingMapping) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: CouplingMapping) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class SettleReport:
    """
    What Coupler.settle() did.
    """
    def __repr__(self) -> str:
        ...
    @property
    def max_speed(self) -> float:
        """
        the largest free stone's speed at its end [m/s]
        """
    @property
    def rested(self) -> bool:
        """
        ended by the rest criterion (False: at max_time)
        """
    @property
    def time(self) -> float:
        """
        simulated time the stones stepped [s]
        """
class CouplerParams:
    """
    Parameters of the VOF-DEM coupling (SI units; see coupler.h).
    """
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        """
        ValueError naming the first parameter outside its range.
        """
    @property
    def bandwidth(self) -> float:
        """
        KERNEL: the Gaussian's width b in exp(-r^2/b^2) [m], (0, 1], sigma = b / sqrt(2); 0 = unset: 1.0 x the stones' mean nominal diameter
        """
    @bandwidth.setter
    def bandwidth(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def drag_law(self) -> DragLaw:
        """
        DragLaw of the sphere drag
        """
    @drag_law.setter
    def drag_law(self, arg0: DragLaw) -> None:
        ...
    @property
    def drag_relaxation(self) -> float:
        """
        held drag: step at most this fraction of its relaxation time [-], default 0.5
        """
    @drag_relaxation.setter
    def drag_relaxation(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def flags(self) -> int:
        """
        CouplerEffect bits
        """
    @flags.setter
    def flags(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def implicit_drag(self) -> bool:
        """
        drag linearised in the stone's velocity and integrated implicitly by the DEM (True) or held over the step, bounded by drag_relaxation (False), default True
        """
    @implicit_drag.setter
    def implicit_drag(self, arg0: bool) -> None:
        ...
    @property
    def lookup_dr(self) -> float:
        """
        radius spacing of the lookup tables [m], default 5e-04
        """
    @lookup_dr.setter
    def lookup_dr(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def lookup_m(self) -> int:
        """
        sub-areas per side of the lookup table [-], default 8
        """
    @lookup_m.setter
    def lookup_m(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def mapping(self) -> CouplingMapping:
        """
        CouplingMapping of the exchanged fields, default CELL
        """
    @mapping.setter
    def mapping(self, arg0: CouplingMapping) -> None:
        ...
    @property
    def max_dt(self) -> float:
        """
        largest exchange step [s], default 0.01
        """
    @max_dt.setter
    def max_dt(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_snapshot_interval(self) -> int:
        """
        within advance(), the guard's snapshot at most this many steps apart [steps], [1, 4096]; a failing step replays the steps since it (the same bits); 1: every step, default 32
        """
    @max_snapshot_interval.setter
    def max_snapshot_interval(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def min_dt(self) -> float:
        """
        a stable step below this is a failure [s], default 1e-07
        """
    @min_dt.setter
    def min_dt(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def n_exp(self) -> float:
        """
        packing porosity of eq. (11) [-], default 0.41
        """
    @n_exp.setter
    def n_exp(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def overflow_band_height(self) -> float:
        """
        OVERFLOW_LOAD: height of the approach band above a stone's top, in stone diameters [-], (0, 5], default 1
        """
    @overflow_band_height.setter
    def overflow_band_height(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def overflow_drag_coefficient(self) -> float:
        """
        OVERFLOW_LOAD: drag coefficient C_D of a stone's exposed part [-], (0, 5] (Schmeeckle et al. 2007), default 0.91
        """
    @overflow_drag_coefficient.setter
    def overflow_drag_coefficient(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def overflow_lift_coefficient(self) -> float:
        """
        OVERFLOW_LOAD: lift coefficient C_L [-], [0, 5] (Einstein and El-Samni 1949), default 0.178
        """
    @overflow_lift_coefficient.setter
    def overflow_lift_coefficient(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def stone_cfl(self) -> float:
        """
        cells a stone crosses per step at most [-], default 0.5
        """
    @stone_cfl.setter
    def stone_cfl(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def stone_drag(self) -> StoneDragModel:
        """
        StoneDragModel of the drag on the stones, default SPHERE
        """
    @stone_drag.setter
    def stone_drag(self, arg0: StoneDragModel) -> None:
        ...
    @property
    def wet_fraction_tolerance(self) -> float:
        """
        a stone measured this close to wet (dry) is taken as under water (in the air) [-], [0, 0.5]; 0: every measured wet fraction is followed, default 1e-06
        """
    @wet_fraction_tolerance.setter
    def wet_fraction_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class CouplerState:
    """
    A copy of a coupled simulation's whole state (Coupler.copy_state): the flow's, the stones' and the coupler's own; set_state() returns to it.
    """
    @property
    def steps(self) -> int:
        """
        steps taken since the start [-]
        """
    @property
    def time(self) -> float:
        """
        simulated time [s]
        """
class Coupler:
    """
    Two-way VOF-DEM coupling of a VOFGrid and a DEMSystem (either may be None); keeps both alive.
    """
    def __init__(self, fluid: typing.Any, stones: typing.Any, params: CouplerParams = ...) -> None:
        ...
    def advance(self, t_end: typing.SupportsFloat | typing.SupportsIndex) -> int:
        """
        coupled steps of stable_dt() until time reaches t_end [s]; returns the steps; the GIL is released
        """
    def clear_step_limits(self) -> None:
        """
        forgets the counts of which limit bound each step (step_limits)
        """
    def copy_state(self) -> CouplerState:
        """
        a copy of the whole coupled state (CouplerState), to branch from: set_state(copy) continues from it bit for bit
        """
    def export_state(self) -> dict:
        """
        the whole state as a dict of named numpy arrays, copied (a checkpoint; import_state(dict) restores it bit for bit)
        """
    def import_state(self, state: dict) -> None:
        """
        restores export_state() exactly (every part checked first; written into the arrays in place)
        """
    def set_inflow_table(self, times: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], discharge: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        """
        inflow hydrograph Q(t): times [s] (increasing), discharge Q [m^3/s] (forwarded to the flow)
        """
    def set_state(self, state: CouplerState) -> None:
        """
        returns to a copy_state() copy (every part checked first; written into the arrays in place)
        """
    def settle(self, max_time: typing.SupportsFloat | typing.SupportsIndex = 5.0, rest_speed: typing.SupportsFloat | typing.SupportsIndex = 0.001, hold: typing.SupportsFloat | typing.SupportsIndex = 0.2, chunk: typing.SupportsFloat | typing.SupportsIndex = 0.01) -> SettleReport:
        """
        the stones settle in the still water before the first step: the DEM alone steps, each stone buoyant by the water it sits in, the flow frozen, until every free stone has been slower than rest_speed [m/s], (0, 1], for hold [s], [0, 10] (checked every chunk [s], (0, 1]) or for max_time [s], (0, 600]. Returns a SettleReport; call update_porosity() after it to map the settled stones
        """
    def stable_dt(self) -> float:
        """
        the coupled step [s]: the flow's stable step and the stones' exchange bounds; the GIL is released
        """
    @typing.overload
    def step(self) -> None:
        ...
    @typing.overload
    def step(self, dt: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def step_limit_cells(self) -> dict:
        """
        {term: steps bound in each cell (ncell counts, a copy)}
        """
    def step_limits(self) -> dict[str, int]:
        """
        steps of advance() bound by each limit, {term: steps} (a diagnostic, not checkpointed)
        """
    def update_fluid_forces(self) -> None:
        """
        recomputes the fluid forces on the stones now (stone_force_drag, stone_force_pressure, the stones' wet fractions and external forces)
        """
    def update_porosity(self, keep_water_volume: bool = True) -> None:
        """
        maps the stones onto the porosity now; keep_water_volume: True keeps n F V per cell (displaced water moves to neighbours), False keeps F (scene set-up)
        """
    def water_volume(self) -> float:
        """
        the flow's water volume sum(n F V) per unit width [m^2]
        """
    @property
    def cell_base_diameter(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        stone diameter of the base porosity per cell (ncell) [m], zero-copy view
        """
    @property
    def cell_base_porosity(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        porosity without the stones per cell (ncell) [-] (from the flow at construction), zero-copy view
        """
    @property
    def cell_overflow_reaction(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        OVERFLOW_LOAD: the reaction taken from each cell (ncell, 2) [N per metre of flume width], zero-copy view
        """
    @property
    def cpu_profile(self) -> StageProfile:
        """
        the process's CPU seconds (all threads) per coupled stage, the stages and calls of `profile` (StageProfile): unchanged by other work on a shared machine; reset apart
        """
    @property
    def floored_solid_area(self) -> float:
        """
        KERNEL: solid area per unit width [m^2] the porosity floor n >= n_exp removed at the last mapping (0: the flow sees all of the stones' solid volume)
        """
    @property
    def fluid(self) -> VOFGrid:
        """
        the flow (VOFGrid) this coupler steps
        """
    @property
    def kernel_bandwidth(self) -> float:
        """
        the kernel's width b [m] in use (0 with the CELL mapping)
        """
    @property
    def n(self) -> int:
        """
        number of stones
        """
    @property
    def params(self) -> CouplerParams:
        """
        a copy (editing it changes nothing); assign a modified copy to change them, checked, with the porosity mapper following them
        """
    @params.setter
    def params(self, arg1: CouplerParams) -> None:
        ...
    @property
    def profile(self) -> StageProfile:
        """
        wall-clock seconds per coupled stage (StageProfile)
        """
    @property
    def redistributed_volume(self) -> float:
        """
        water moved between cells by the redistribution, accumulated [m^2 per unit width]
        """
    @property
    def replayed_steps(self) -> int:
        """
        steps taken again from the guard's snapshot after a failure (a diagnostic)
        """
    @property
    def step_count(self) -> int:
        """
        coupled steps taken
        """
    @property
    def stone_exposed_share(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        OVERFLOW_LOAD: each stone's projected area share loaded by the overflow (n) [-], zero-copy view
        """
    @property
    def stone_force_drag(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        drag on each stone (sphere or bed drag) (n, 2) [N], zero-copy view
        """
    @property
    def stone_force_overflow(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        OVERFLOW_LOAD: the overflow's drag and lift on each stone (n, 2) [N] (zeros while off), zero-copy view
        """
    @property
    def stone_force_pressure(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        pressure-gradient force on each stone (n, 2) [N], zero-copy view
        """
    @property
    def stones(self) -> DEMSystem:
        """
        the stones (DEMSystem) this coupler steps
        """
    @property
    def time(self) -> float:
        """
        simulated time [s]
        """
def _drag_force_x(arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg2: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg3: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg4: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg5: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg6: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg7: DragLaw) -> typing.Any:
    ...
def _drag_force_z(arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg2: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg3: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg4: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg5: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg6: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg7: DragLaw) -> typing.Any:
    ...
def _porous_resistance_x(arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg2: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg3: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg4: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg5: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg6: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    ...
def _porous_resistance_z(arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg2: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg3: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg4: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg5: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], arg6: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    ...
def advect_vof(grid: Grid2D, cell_porosity: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], face_u: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], face_w: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], inflow: VofBoundaryInflow, dt: typing.SupportsFloat | typing.SupportsIndex, x_first: bool, cell_F: numpy.typing.NDArray[numpy.float64], scratch: VofScratch, normal: VofNormal = ...) -> None:
    """
    Advances the water fraction cell_F (float64, C-contiguous, size ncell; updated in place) by dt [s] with the superficial face velocities face_u, face_w [m/s] (seed eq. 4, PLIC, split with the Weymouth-Yue correction). Raises RuntimeError above CFL 1 (F untouched).
    """
def built_with_openmp() -> bool:
    """
    True if the solvers can run on several threads.
    """
def contact_duration(k: typing.SupportsFloat | typing.SupportsIndex, m_reduced: typing.SupportsFloat | typing.SupportsIndex, zeta: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    Contact duration t_c [s] of a linear spring-dashpot: stiffness k [N/m], reduced mass m_reduced [kg], damping ratio zeta [-] (inf for zeta >= 1).
    """
def damping_ratio_from_restitution(e: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    Damping ratio zeta [-] of a linear spring-dashpot that gives the restitution coefficient e [-] (e = 0: zeta = 1).
    """
def drag_coefficient(re: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], law: DragLaw = ...) -> typing.Any:
    """
    Drag coefficient C_D [-] at Reynolds number re > 0.
    """
def forchheimer_coefficient(n: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], k1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64] = 200.0, k2: typing.Annotated[numpy.typing.ArrayLike, numpy.float64] = 2.8) -> typing.Any:
    """
    Forchheimer coefficient C = k2 / sqrt(k1 n^3) [-] (seed eq. 7).
    """
def max_threads() -> int:
    """
    The most threads set_threads accepts (1 when built without OpenMP).
    """
def pack_weir(spec: WeirSpec, params: DEMParams = ...) -> tuple[DEMSystem, WeirPackingReport]:
    """
    Packs the trapezoidal rubble mound weir `spec` with the contact law of `params`; returns (DEMSystem, WeirPackingReport).
    """
def permeability(n: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], d: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], k1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64] = 200.0) -> typing.Any:
    """
    Intrinsic permeability K = n^3 d^2 / (k1 (1-n)^2) [m^2] (seed eq. 7); n porosity, d stone diameter [m].
    """
def plic_area_below(mx: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], mz: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], dx: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], dz: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], alpha: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    """
    Area [m^2] of {m.x <= alpha} inside the rectangle [0,dx]x[0,dz].
    """
def plic_line_constant(mx: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], mz: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], dx: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], dz: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], f: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    """
    Line constant alpha with area{m.x <= alpha} in [0,dx]x[0,dz] = f dx dz (normal m out of the water).
    """
def porosity_eq11(a_s: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], a_c: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], n_exp: typing.Annotated[numpy.typing.ArrayLike, numpy.float64] = 0.41) -> typing.Any:
    """
    Porosity of seed eq. (11) from stone area a_s [m^2] (capped at a_c) and cell area a_c [m^2].
    """
def pressure_residual(grid: Grid2D, problem: PressureProblem, rhs: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], p: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> numpy.typing.NDArray[numpy.float64]:
    """
    b - A p on active cells (0 elsewhere)
    """
def quarried_stone(name: str, d_eq: typing.SupportsFloat | typing.SupportsIndex, ratio_intermediate: typing.SupportsFloat | typing.SupportsIndex = 0.8, ratio_short: typing.SupportsFloat | typing.SupportsIndex = 0.6) -> numpy.typing.NDArray[numpy.float64]:
    """
    The spheres (k, 4) of a library clump (x, y, z, r) [m] in its principal frame: name one of quarried_stone_names(), d_eq [m] in (0, inf) its volume-equivalent diameter, the aspect ratios intermediate/long in [ratio_short, 1] and short/long in [0.55, 1] [-].
    """
def quarried_stone_names() -> list[str]:
    """
    the library clumps' names (quarried_stone)
    """
def random_polygons(diameters: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], seed: typing.SupportsInt | typing.SupportsIndex = 0, vertices_min: typing.SupportsInt | typing.SupportsIndex = 5, vertices_max: typing.SupportsInt | typing.SupportsIndex = 8, aspect_ratio: typing.SupportsFloat | typing.SupportsIndex = 1.5, radial_jitter: typing.SupportsFloat | typing.SupportsIndex = 0.2) -> tuple[numpy.typing.NDArray[numpy.float64], list[int]]:
    """
    Random convex polygon stones of the given nominal diameters [m] (equal-area discs) from one seed: (vertices (m, 2) body frame [m], offsets (n + 1)). See polygon.h.
    """
def restitution_from_damping_ratio(zeta: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    Restitution coefficient e [-] of a linear spring-dashpot of damping ratio zeta [-] (0 for zeta >= 1).
    """
def set_thread_min_cells(n: typing.SupportsInt | typing.SupportsIndex) -> None:
    """
    The fewest cells a thread is given [-], in [1, 1e9], default 2048: smaller loops run on fewer threads; 1 splits every loop (the determinism tests). ValueError outside the range.
    """
def set_threads(n: typing.SupportsInt | typing.SupportsIndex) -> None:
    """
    Threads of the next steps of every solver in this process [-], in [1, max_threads()]; the results are the same bits for any count (docs/threads.md). ValueError outside the range.
    """
def stone_cell_area(cx: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], cz: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], r: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], x0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], x1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], z0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], z1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    """
    Exact area [m^2] of the disc of centre (cx, cz) [m] and radius r [m] inside [x0, x1] x [z0, z1] [m].
    """
def stone_model_names() -> list[str]:
    """
    the registered stone models' names (DEMSystem.shape, the scene's stones.shape), the built-in ones first
    """
def thread_min_cells() -> int:
    """
    The fewest cells a thread is given [-].
    """
def threads() -> int:
    """
    Threads of the solvers' parallel stages [-] (default: OMP_NUM_THREADS, else every core).
    """
def vof_stable_dt(grid: Grid2D, cell_porosity: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], face_u: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], face_w: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], cfl: typing.SupportsFloat | typing.SupportsIndex = 0.45) -> float:
    """
    Largest advection step [s] at CFL number cfl: per cell and direction the inflow CFL numbers abs(v) dt / (n h) add up to <= cfl, the outflow ones to <= 2 cfl (cfl <= 0.5 keeps F in [0, 1]); inf if at rest.
    """
def weir_outline_error(system: DEMSystem, spec: WeirSpec) -> float:
    """
    Largest deviation [m] of the packing from the trapezoid: how far a stone reaches outside it, or how far a point of its slopes and crest lies from the nearest stone, whichever is larger.
    """
def weir_porosity(system: DEMSystem, spec: WeirSpec, h: typing.SupportsFloat | typing.SupportsIndex = 0.002) -> float:
    """
    2D porosity [-] of the weir's trapezoid filled by the stones (discs or polygons), sampled on a grid of spacing h [m].
    """
COUPLE_CHECKS: CouplerEffect
COUPLE_DEFAULT: CouplerEffect
COUPLE_DEM: CouplerEffect
COUPLE_DISPLACE_FLOW: CouplerEffect
COUPLE_DRAG: CouplerEffect
COUPLE_FLUID: CouplerEffect
COUPLE_FORCES: CouplerEffect
COUPLE_LOOKUP_POROSITY: CouplerEffect
COUPLE_ONE_WAY: CouplerEffect
COUPLE_OVERFLOW_LOAD: CouplerEffect
COUPLE_POROSITY: CouplerEffect
COUPLE_PRESSURE_GRADIENT: CouplerEffect
COUPLE_TWO_WAY: CouplerEffect
COUPLE_WET_FRACTION: CouplerEffect
DEM_ADDED_MASS: DEMFlag
DEM_ALL_EFFECTS: DEMFlag
DEM_BUOYANCY: DEMFlag
DEM_DAMPING: DEMFlag
DEM_EXTERNAL_FORCE: DEMFlag
DEM_FRICTION: DEMFlag
DEM_GRAVITY: DEMFlag
DEM_REMOVAL: DEMFlag
DEM_ROLLING_RESISTANCE: DEMFlag
DEM_ROTATION: DEMFlag
DEM_SLEEPING: DEMFlag
ERGUN_K1: float = 150.0
ERGUN_K2: float = 1.75
GRADED_MERGE_FRACTION: float = 0.5
PAPER_K1: float = 200.0
PAPER_K2: float = 2.8
VOF_CLIP_TOLERANCE: float = 1e-12
__version__: str = '0.1.0'
