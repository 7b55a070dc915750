"""CAD files of counterweights: SVG, DXF R12, STL and STEP writers, mesh mass properties.

This module owns every file a counterweight is written to or read back from:
:func:`profile_svg` and :func:`profile_dxf` (exact lines and arcs of
:func:`crankbalance.physics.counterweight.profile_boundary`), :func:`profile_mesh`,
:func:`stl_bytes` and :func:`write_stl` (a closed triangle mesh of the prism),
:func:`write_step` (build123d, ``cad`` extra), the dispatcher :func:`export_counterweight`, and
:func:`mesh_mass_properties` (:class:`MeshMassProperties` of an STL or STEP part, read with
trimesh). Files are written atomically (:func:`crankbalance.io.files.write_atomic`; an error
while writing is a :class:`crankbalance.io.files.WriteError` and leaves the previous file
intact). trimesh and build123d are imported lazily.
"""

from __future__ import annotations

import math
import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import Literal

import numpy as np

from ..errors import InputError
from ..physics.counterweight import (
    DEFAULT_DENSITY,
    BoundaryLine,
    CounterweightDesign,
    check_positive_number,
    profile_boundary,
    profile_section,
)
from ..records import record
from ..results import ResultMixin
from .files import write_atomic

ExportFormat = Literal["svg", "dxf", "stl", "step"]


# --------------------------------------------------------------------------------------
# Exports: SVG, DXF (R12), STL, STEP (optional) and mass properties read back
# --------------------------------------------------------------------------------------

_MM = 1e3  # exports are written in millimetres (CAD convention)


def profile_svg(design: CounterweightDesign, *, show_web: bool = True) -> str:
    """The profile as an SVG document (millimetres, exact arcs, crank axis at the origin).

    SVG's y axis points down, so the drawing is flipped (``transform="scale(1,-1)"``) to
    keep the counterweight above the crank axis as in the paper's Fig. 5.
    """
    loops = profile_boundary(design)
    sec = design.properties()
    size = float(max(sec.outer_radius, design.web_radius)) * _MM * 1.05
    d = []
    for loop in loops:
        first = loop[0]
        start = first.start if isinstance(first, BoundaryLine) else first.point(first.start_angle)
        d.append(f"M {start[0] * _MM:.6f} {start[1] * _MM:.6f}")
        for it in loop:
            if isinstance(it, BoundaryLine):
                d.append(f"L {it.end[0] * _MM:.6f} {it.end[1] * _MM:.6f}")
            else:
                end = it.point(it.end_angle)
                large = 1 if abs(it.sweep) > math.pi else 0
                sweep = 1 if it.ccw else 0  # in the flipped (y up) frame
                d.append(
                    f"A {it.radius * _MM:.6f} {it.radius * _MM:.6f} 0 {large} {sweep} "
                    f"{end[0] * _MM:.6f} {end[1] * _MM:.6f}"
                )
        d.append("Z")
    web = ""
    if show_web:
        web = (
            f'<circle cx="0" cy="0" r="{design.web_radius * _MM:.6f}" fill="none" '
            'stroke="#c0392b" stroke-dasharray="2 1" stroke-width="0.3"/>'
        )
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{2 * size:.3f}mm" '
        f'height="{2 * size:.3f}mm" '
        f'viewBox="{-size:.3f} {-size:.3f} {2 * size:.3f} {2 * size:.3f}">\n'
        f"<title>crankbalance counterweight, mass {sec.mass * 1e3:.2f} g</title>\n"
        '<g transform="scale(1,-1)">\n'
        f'<path d="{" ".join(d)}" fill="#7f8c8d" fill-rule="evenodd" stroke="black" '
        'stroke-width="0.3"/>\n'
        f"{web}\n"
        '<path d="M -2 0 L 2 0 M 0 -2 L 0 2" stroke="black" stroke-width="0.2"/>\n'
        "</g>\n</svg>\n"
    )


def profile_dxf(design: CounterweightDesign) -> str:
    """The profile as a DXF R12 (AC1009) text file: LINE and ARC entities, millimetres.

    Layer ``COUNTERWEIGHT`` holds the closed profile, layer ``WEB`` the web circle.
    """
    out = [
        "0",
        "SECTION",
        "2",
        "HEADER",
        "9",
        "$ACADVER",
        "1",
        "AC1009",
        "9",
        "$INSUNITS",
        "70",
        "4",
        "0",
        "ENDSEC",
        "0",
        "SECTION",
        "2",
        "ENTITIES",
    ]

    def num(v: float) -> str:
        return f"{v:.9f}"

    for loop in profile_boundary(design):
        for it in loop:
            if isinstance(it, BoundaryLine):
                out += [
                    "0",
                    "LINE",
                    "8",
                    "COUNTERWEIGHT",
                    "10",
                    num(it.start[0] * _MM),
                    "20",
                    num(it.start[1] * _MM),
                    "30",
                    "0.0",
                    "11",
                    num(it.end[0] * _MM),
                    "21",
                    num(it.end[1] * _MM),
                    "31",
                    "0.0",
                ]
            else:
                a0, a1 = (
                    (it.start_angle, it.end_angle) if it.ccw else (it.end_angle, it.start_angle)
                )
                out += [
                    "0",
                    "ARC",
                    "8",
                    "COUNTERWEIGHT",
                    "10",
                    num(it.centre[0] * _MM),
                    "20",
                    num(it.centre[1] * _MM),
                    "30",
                    "0.0",
                    "40",
                    num(it.radius * _MM),
                    "50",
                    num(math.degrees(a0) % 360.0),
                    "51",
                    num(math.degrees(a1) % 360.0),
                ]
    out += [
        "0",
        "CIRCLE",
        "8",
        "WEB",
        "10",
        "0.0",
        "20",
        "0.0",
        "30",
        "0.0",
        "40",
        num(design.web_radius * _MM),
        "0",
        "ENDSEC",
        "0",
        "EOF",
    ]
    return "\n".join(out) + "\n"


def profile_mesh(
    design: CounterweightDesign, tolerance: float = 2e-6
) -> tuple[np.ndarray, np.ndarray]:
    """Closed triangle mesh of the counterweight prism [m]: (vertices (V, 3), faces (F, 3)).

    The crank axis is the z axis, the profile lies in ``0 <= z <= thickness``, the centre of
    gravity on ``+y``. The profile is cut into horizontal slabs at every vertex height of
    both arcs (chord error below ``tolerance`` [m]); each slab is a trapezoid between the
    web circle and the outer boundary, mirrored about ``x = 0``. A flat ledge
    (``trapezoid_angle = 0``) gets a slope of 1e-6 of the size so that slabs stay trapezoids.
    """
    r, h_r, delta, big_r, alpha = design.profile_parameters()
    sec = profile_section(r, h_r, delta, big_r, alpha)
    l_c, top, yc = float(sec.overhang), float(sec.top_height), float(sec.segment_centre)
    hub = bool(sec.hub_protrusion)
    eps = 1e-6 * max(r, big_r)
    if l_c > 0 and top - h_r < eps:
        # a flat ledge (delta = 0): give it a tiny slope so that every slab is a trapezoid
        # (changes the volume by about 1e-6 relative)
        top = h_r + eps
        yc = top - big_r * math.cos(alpha / 2)
    y_end = yc + big_r
    if hub:
        y_end = float(np.clip((r**2 - big_r**2 + yc**2) / (2 * yc), top, r))

    def angles(radius: float, a_max: float) -> np.ndarray:
        dphi = 2.0 * math.acos(max(-1.0, 1.0 - tolerance / radius))
        return np.linspace(0.0, a_max, max(2, math.ceil(a_max / dphi)) + 1)

    levels = np.r_[
        0.0,
        h_r,
        top,
        y_end,
        min(r, y_end),
        yc + big_r * np.cos(angles(big_r, math.pi)),
        r * np.cos(angles(r, math.pi / 2)),
    ]
    levels = np.unique(np.clip(levels, 0.0, y_end))
    levels = levels[np.r_[True, np.diff(levels) > 1e-12 * max(r, big_r)]]
    y = levels
    span = top - h_r
    frac = np.clip((y - h_r) / span, 0.0, 1.0) if span > 0 else (y > h_r).astype(float)
    w_out = np.where(y <= h_r, r, r + l_c * frac)
    w_out = np.where(y > top, np.sqrt(np.maximum(big_r**2 - (y - yc) ** 2, 0.0)), w_out)
    w_in = np.sqrt(np.maximum(r**2 - y**2, 0.0))
    w_in = np.minimum(w_in, w_out)
    n = len(y)
    # vertices of the right half: inner chain then outer chain; left half mirrored
    v2 = np.vstack([np.c_[w_in, y], np.c_[w_out, y], np.c_[-w_in, y], np.c_[-w_out, y]])
    k = np.arange(n - 1)
    i0, i1, o0, o1 = k, k + 1, n + k, n + k + 1
    right = np.r_[np.c_[i0, o0, o1], np.c_[i0, o1, i1]]
    left = right[:, ::-1] + 2 * n
    tri = np.r_[right, left]
    # merge coincident vertices (centre line, web-circle ends, hub crossing)
    key = np.round(v2 / (1e-9 * max(r, big_r)))
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    v2 = v2[first]
    tri = inverse.reshape(-1)[tri]
    tri = tri[(tri[:, 0] != tri[:, 1]) & (tri[:, 1] != tri[:, 2]) & (tri[:, 0] != tri[:, 2])]
    # zero-area triangles (collinear) are kept out as well
    p = v2[tri]
    area2 = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 2, 0] - p[:, 0, 0]) * (
        p[:, 1, 1] - p[:, 0, 1]
    )
    proper = np.abs(area2) > 1e-18 * max(r, big_r) ** 2
    tri, area2 = tri[proper], area2[proper]
    tri = np.where((area2 < 0)[:, None], tri[:, ::-1], tri)  # all counter-clockwise
    nv = len(v2)
    t = design.thickness
    vertices = np.vstack([np.c_[v2, np.zeros(nv)], np.c_[v2, np.full(nv, t)]])
    faces = [tri[:, ::-1], tri + nv]
    # walls on boundary edges (edges used by exactly one cap triangle)
    edges = np.r_[tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]
    undirected = np.sort(edges, axis=1)
    _, inv, counts = np.unique(undirected, axis=0, return_inverse=True, return_counts=True)
    boundary = edges[counts[inv.reshape(-1)] == 1]
    a, b = boundary[:, 0], boundary[:, 1]
    faces += [np.c_[a, b, b + nv], np.c_[a, b + nv, a + nv]]
    return vertices, np.vstack(faces)


def stl_bytes(design: CounterweightDesign, tolerance: float = 2e-6) -> bytes:
    """The counterweight prism as a binary STL in millimetres (see :func:`profile_mesh`)."""
    vertices, faces = profile_mesh(design, tolerance)
    tri = vertices[faces] * _MM
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    norm = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = normals / np.where(norm > 0, norm, 1.0)
    record = np.zeros(len(faces), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    record["n"] = normals
    record["v"] = tri
    header = b"crankbalance counterweight, mm".ljust(80, b" ")
    return header + np.uint32(len(faces)).tobytes() + record.tobytes()


def write_stl(design: CounterweightDesign, path: str | Path, tolerance: float = 2e-6) -> Path:
    """Write the counterweight prism as a binary STL in millimetres (see :func:`stl_bytes`)."""
    path = Path(path)
    write_atomic(path, stl_bytes(design, tolerance))
    return path


def _cad_missing(what: str) -> InputError:
    return InputError(
        "format", what, "STEP needs the optional CAD extra: pip install 'crankbalance[cad]'"
    )


def write_step(design: CounterweightDesign, path: str | Path) -> Path:
    """Write the counterweight as a STEP solid (millimetres) with build123d (``cad`` extra)."""
    try:
        import build123d as bd
    except ImportError:
        raise _cad_missing("step") from None
    faces = []
    for loop in profile_boundary(design):
        edges = []
        for it in loop:
            if isinstance(it, BoundaryLine):
                edges.append(
                    bd.Line(tuple(v * _MM for v in it.start), tuple(v * _MM for v in it.end))
                )
            else:
                mid = it.point(0.5 * (it.start_angle + it.end_angle))
                p0, p1 = it.point(it.start_angle), it.point(it.end_angle)
                edges.append(bd.ThreePointArc(*(tuple(v * _MM for v in p) for p in (p0, mid, p1))))
        faces.append(bd.Face(bd.Wire(edges)))
    solid = bd.extrude(
        bd.Sketch() + faces if len(faces) > 1 else faces[0], amount=design.thickness * _MM
    )
    path = Path(path)
    with tempfile.TemporaryDirectory() as folder:
        scratch = Path(folder) / "counterweight.step"
        bd.export_step(solid, str(scratch))
        write_atomic(path, scratch.read_bytes())
    return path


def export_counterweight(
    design: CounterweightDesign, path: str | Path, fmt: ExportFormat | None = None
) -> Path:
    """Write ``design`` to ``path`` as SVG, DXF, STL or STEP (from the suffix unless ``fmt``)."""
    path = Path(path)
    kind = (fmt or path.suffix.lstrip(".")).lower()
    if kind in ("stp",):
        kind = "step"
    if kind not in ("svg", "dxf", "stl", "step"):
        raise InputError("format", kind, "one of svg, dxf, stl, step")
    if kind == "svg":
        write_atomic(path, profile_svg(design))
    elif kind == "dxf":
        write_atomic(path, profile_dxf(design))
    elif kind == "stl":
        write_stl(design, path)
    else:
        write_step(design, path)
    return path


@record
class MeshMassProperties(ResultMixin):
    """Mass properties of a CAD part read back from STL/STEP (SI).

    Attributes
    ----------
    volume : [m^3]. mass : [kg]. centre_of_gravity : (3,) [m].
    cg_radius : Distance of the centre of gravity from the crank axis [m].
    first_moment : mass * cg_radius [kg m].
    inertia : Mass moment of inertia about the crank axis [kg m^2].
    watertight : Whether the mesh is closed (otherwise the numbers are not trustworthy).
    balance : first_moment / required [%] if a requirement was given.
    """

    volume: float
    mass: float
    centre_of_gravity: np.ndarray
    cg_radius: float
    first_moment: float
    inertia: float
    watertight: bool
    balance: float | None = None


def mesh_mass_properties(
    path: str | Path,
    density: float = DEFAULT_DENSITY,
    *,
    length_unit: float = 1e-3,
    axis_point: Sequence[float] = (0.0, 0.0, 0.0),
    axis_direction: Sequence[float] = (0.0, 0.0, 1.0),
    required_first_moment: float | None = None,
) -> MeshMassProperties:
    """Read an STL (or STEP, with the ``cad`` extra) part and compute its mass properties.

    Parameters
    ----------
    path : str or Path
        The file (``.stl``, ``.step``/``.stp``; other mesh formats trimesh reads also work).
    density : float
        [kg/m^3].
    length_unit : float
        Metres per file unit (1e-3 for millimetres, as :func:`write_stl` writes).
    axis_point, axis_direction : sequence of 3 floats
        The crank axis in file units (a point on it and its direction).
    required_first_moment : float, optional
        [kg m]; gives the balance [%].
    """
    rho = check_positive_number("density", density)
    scale = check_positive_number("length_unit", length_unit)
    path = Path(path)
    if not path.is_file():
        raise InputError("path", str(path), "must be an existing STL or STEP file")
    try:
        import trimesh
    except ImportError:
        raise InputError(
            "path", str(path), "reading meshes needs trimesh: pip install 'crankbalance[geometry]'"
        ) from None
    if path.suffix.lower() in (".step", ".stp"):
        try:
            import build123d as bd
        except ImportError:
            raise _cad_missing(path.suffix) from None
        shape = bd.import_step(str(path))
        verts, tris = shape.tessellate(1e-4, 0.005)  # [file units], [rad]
        mesh = trimesh.Trimesh(np.array([tuple(v) for v in verts]), np.asarray(tris))
    else:
        try:
            mesh = trimesh.load_mesh(str(path), force="mesh")
        except Exception as error:  # noqa: BLE001 - any reader failure is bad input
            raise InputError("path", str(path), f"not a readable mesh ({error})") from None
    vertices = np.asarray(mesh.vertices, dtype=float) * scale
    mesh = trimesh.Trimesh(vertices, np.asarray(mesh.faces), process=False)
    volume = float(abs(mesh.volume))
    if not volume > 0:
        raise InputError("path", str(path), "the mesh encloses no volume")
    sign = 1.0 if mesh.volume > 0 else -1.0
    cg = np.asarray(mesh.center_mass, dtype=float)
    inertia_cg = (
        np.asarray(mesh.moment_inertia, dtype=float) * rho * sign
    )  # unit density in trimesh
    n = np.asarray(axis_direction, dtype=float)
    p0 = np.asarray(axis_point, dtype=float) * scale
    if n.shape != (3,) or not (np.all(np.isfinite(n)) and np.linalg.norm(n) > 0):
        raise InputError("axis_direction", axis_direction, "three finite numbers, not all zero")
    if p0.shape != (3,) or not np.all(np.isfinite(p0)):
        raise InputError("axis_point", axis_point, "three finite numbers")
    n = n / np.linalg.norm(n)
    rel = cg - p0
    perp = rel - np.dot(rel, n) * n
    dist = float(np.linalg.norm(perp))
    mass = rho * volume
    inertia = float(n @ inertia_cg @ n) + mass * dist**2
    first = mass * dist
    balance = None
    if required_first_moment is not None:
        balance = (
            100.0 * first / check_positive_number("required_first_moment", required_first_moment)
        )
    return MeshMassProperties(
        volume, mass, cg, dist, first, inertia, bool(mesh.is_watertight), balance
    )
