r"""The powertrain on its elastic mounts: a rigid body with six degrees of freedom.

The powertrain (engine and gearbox) is one rigid body of mass m, centre of gravity G and
inertia tensor :math:`I_G` about G, held by N mounts, each a spring in three principal
directions with hysteretic (:math:`k(1 + i\eta)`) or viscous damping. All vectors are in
the engine axes (docs/theory.md, "Conventions": x across, y along the crank axis, z along
the cylinder axis of an in-line engine) with the origin at the crank's reference point P
(``crank_train.moment_point``), the point the free forces and moments are taken about.

* **Coordinates** :math:`q = (u_x, u_y, u_z, \theta_x, \theta_y, \theta_z)`: the small
  translation of G and the small rotation of the body about the engine axes. A point at
  r (from P) moves by :math:`u + \theta \times (r - G)`.
* **Inertia tensor** :math:`I_{ij} = \int (|\rho|^2\delta_{ij} - \rho_i\rho_j)\,dm`
  about G: its off-diagonal entries are :math:`-\int xy\,dm` etc. (products of inertia
  entered as the tensor's entries, not as :math:`\int xy\,dm`).
* **Mount orientation**: before rotation a mount's compression axis is the body's z, its
  first shear axis x and its second shear axis y; the orientation :math:`(a, b, c)` turns
  these axes by a about the body's x, then b about the body's y, then c about the body's z
  (fixed axes): :math:`R = R_z(c) R_y(b) R_x(a)`, the columns of R are the mount's shear
  1, shear 2 and compression axes in body coordinates, and the mount's stiffness in body
  axes is :math:`R\,\mathrm{diag}(k_{s1}, k_{s2}, k_c)\,R^T`.
* **Loads**: a force F at P and a moment :math:`M_P` act on G as F and
  :math:`M_G = M_P - G \times F`.
* **Harmonics**: a real signal of angular frequency Ω is :math:`\mathrm{Re}(X e^{i\Omega
  t})`; the response is :math:`Q = [K(1 + i\eta) + i\Omega C - \Omega^2 M]^{-1} F` (one
  loss factor per mount scales its stiffness). An engine order n at crank speed ω has
  :math:`\Omega = n\omega`, :math:`\theta = \omega t`.
* **Order phasors -> real signals** (:func:`order_loads`): a force of order n is
  :math:`F_n(\theta) = F_n^+ e^{in\theta} + F_n^- e^{-in\theta}` as :math:`z + ix`
  (:mod:`crankbalance.physics.shaking`), so :math:`F_z = \mathrm{Re}(X_z e^{in\theta})`
  with :math:`X_z = F_n^+ + \overline{F_n^-}` and :math:`F_x` with
  :math:`X_x = -i(F_n^+ - \overline{F_n^-})`; the couple C maps the same way and the moment
  is :math:`M = iC`, so :math:`M_x` takes C's z amplitude and :math:`M_z` minus its x
  amplitude; the roll is :math:`M_y = \mathrm{Re}(R_n e^{in\theta})`; no free force has a
  y component.

References
----------
Jeong and Singh (2000), analytical methods of decoupling the automotive engine torque roll
axis (the torque-roll axis, the kinetic-energy distribution); Yu, Naganathan and Dukkipati
(2001), a literature review of automotive vehicle engine mounting systems (the six-degree
of freedom model, hysteretic and viscous mounts).
"""

from __future__ import annotations

import math
from dataclasses import field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ..records import record
from ..results import ResultMixin

#: Standard gravity [m/s²].
GRAVITY = 9.80665
#: Most mounts of one powertrain.
MAX_MOUNTS = 16
#: Most (speed sample x engine order) pairs of one forced response: each is one 6x6 solve
#: and N mount forces; docs/mounts.md, "Limits".
MAX_RESPONSE_POINTS = 50_000
#: A stiffness matrix whose smallest eigenvalue is below this fraction of its largest (in
#: units scaled by the body's size) does not hold the body in all six directions.
SINGULAR_RATIO = 1e-9
#: Names of the six coordinates.
COORDINATES = ("x", "y", "z", "roll_x", "roll_y", "roll_z")
#: Names of the six coordinates in the kinetic-energy table.
ENERGY_NAMES = ("x", "y", "z", "roll", "pitch", "yaw")


@record
class Mount(ResultMixin):
    """One elastic mount.

    Parameters
    ----------
    name : str
        Its name, as the messages and tables show it.
    position : ndarray, shape (3,)
        Its elastic centre (x, y, z) from the reference point [m].
    stiffness : ndarray, shape (3,)
        Principal stiffnesses: compression, first shear, second shear [N/m].
    orientation : ndarray, shape (3,)
        Rotations (a, b, c) of its axes about the body's x, then y, then z [rad] (module
        docstring).
    loss_factor : float
        Hysteretic loss factor η of all three directions [-]: stiffness k(1 + iη).
    damping : ndarray, shape (3,)
        Viscous damping along compression, first and second shear [N·s/m].
    """

    name: str
    position: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    orientation: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    loss_factor: float = 0.0
    damping: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))

    def axes(self) -> NDArray[np.float64]:
        """Columns: the mount's first shear, second shear and compression axes in body axes.

        Returns
        -------
        ndarray, shape (3, 3)
            :math:`R = R_z(c) R_y(b) R_x(a)` [-].
        """
        return rotation(self.orientation)

    def body_stiffness(self) -> NDArray[np.float64]:
        """Its 3x3 stiffness in body axes.

        Returns
        -------
        ndarray, shape (3, 3)
            :math:`R\\,\\mathrm{diag}(k_{s1}, k_{s2}, k_c)\\,R^T` [N/m].
        """
        return _in_body(self.axes(), self.stiffness)

    def body_damping(self) -> NDArray[np.float64]:
        """Its 3x3 viscous damping in body axes.

        Returns
        -------
        ndarray, shape (3, 3)
            [N·s/m].
        """
        return _in_body(self.axes(), self.damping)


def _in_body(axes: NDArray[np.float64], principal: NDArray[np.float64]) -> NDArray[np.float64]:
    compression, shear1, shear2 = np.asarray(principal, dtype=float)
    return np.asarray(axes @ np.diag([shear1, shear2, compression]) @ axes.T, dtype=float)


def rotation(angles: ArrayLike) -> NDArray[np.float64]:
    """The rotation :math:`R_z(c) R_y(b) R_x(a)`: a about x, then b about y, then c about z,
    all about the fixed body axes.

    Parameters
    ----------
    angles : array_like, shape (3,)
        (a, b, c) [rad].

    Returns
    -------
    ndarray, shape (3, 3)
        The rotation matrix [-].
    """
    a, b, c = np.asarray(angles, dtype=float)
    ca, sa, cb, sb, cc, sc = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(c), np.sin(c)
    rx = np.array([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
    ry = np.array([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]])
    rz = np.array([[cc, -sc, 0], [sc, cc, 0], [0, 0, 1]])
    return np.asarray(rz @ ry @ rx, dtype=float)


def inertia_tensor(moments: ArrayLike, products: ArrayLike = (0.0, 0.0, 0.0)) -> NDArray:
    """The inertia tensor from its diagonal and its off-diagonal entries.

    Parameters
    ----------
    moments : array_like, shape (3,)
        :math:`I_{xx}, I_{yy}, I_{zz}` about the centre of gravity [kg·m²].
    products : array_like, shape (3,)
        The tensor's entries :math:`I_{xy}, I_{yz}, I_{xz}` [kg·m²], each
        :math:`-\\int xy\\,dm` etc. (the negative of the product of inertia).

    Returns
    -------
    ndarray, shape (3, 3)
        The symmetric tensor [kg·m²].
    """
    ixx, iyy, izz = np.asarray(moments, dtype=float)
    ixy, iyz, ixz = np.asarray(products, dtype=float)
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


@record
class Powertrain(ResultMixin):
    """The rigid powertrain and its mounts.

    Parameters
    ----------
    mass : float
        Its mass [kg].
    cg : ndarray, shape (3,)
        Its centre of gravity from the reference point [m].
    inertia : ndarray, shape (3, 3)
        Inertia tensor about the centre of gravity, off-diagonals :math:`-\\int xy\\,dm`
        [kg·m²].
    mounts : tuple of Mount
        The mounts.
    up : ndarray, shape (3,)
        The upward vertical in body axes (unit vector) [-]; weight acts along ``-up``.
    """

    mass: float
    cg: NDArray[np.float64]
    inertia: NDArray[np.float64]
    mounts: tuple[Mount, ...]
    up: NDArray[np.float64] = field(default_factory=lambda: np.array([0.0, 0.0, 1.0]))


def skew(r: ArrayLike) -> NDArray[np.float64]:
    """The matrix of the cross product: ``skew(r) @ v == np.cross(r, v)``.

    Parameters
    ----------
    r : array_like, shape (3,)
        The vector [any unit].

    Returns
    -------
    ndarray, shape (3, 3)
        [unit of r].
    """
    x, y, z = np.asarray(r, dtype=float)
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def point_map(cg: ArrayLike, point: ArrayLike) -> NDArray[np.float64]:
    """The 3x6 matrix that gives a body point's displacement from q: :math:`u + \\theta
    \\times (r - G) = u - [r - G]_\\times \\theta`.

    Parameters
    ----------
    cg : array_like, shape (3,)
        The centre of gravity [m].
    point : array_like, shape (3,)
        The point [m].

    Returns
    -------
    ndarray, shape (3, 6)
        [-] for translations, [m] for rotations.
    """
    arm = np.asarray(point, dtype=float) - np.asarray(cg, dtype=float)
    return np.hstack([np.eye(3), -skew(arm)])


def mass_matrix(pt: Powertrain) -> NDArray[np.float64]:
    """The 6x6 mass matrix in the coordinates of G.

    Parameters
    ----------
    pt : Powertrain
        The powertrain.

    Returns
    -------
    ndarray, shape (6, 6)
        diag(m, m, m) and :math:`I_G` [kg], [kg·m²].
    """
    out = np.zeros((6, 6))
    out[:3, :3] = pt.mass * np.eye(3)
    out[3:, 3:] = pt.inertia
    return out


def _assemble(pt: Powertrain, part: str) -> NDArray[np.float64]:
    out = np.zeros((6, 6))
    for mount in pt.mounts:
        t = point_map(pt.cg, mount.position)
        local = mount.body_stiffness() if part == "k" else mount.body_damping()
        if part == "h":
            local = mount.loss_factor * mount.body_stiffness()
        out += t.T @ local @ t
    return out


def stiffness_matrix(pt: Powertrain) -> NDArray[np.float64]:
    """The 6x6 stiffness matrix of the mounts, :math:`\\sum_i T_i^T K_i T_i`.

    Parameters
    ----------
    pt : Powertrain
        The powertrain.

    Returns
    -------
    ndarray, shape (6, 6)
        [N/m], [N/rad], [N·m/rad].
    """
    return _assemble(pt, "k")


def damping_matrices(pt: Powertrain) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The hysteretic part :math:`\\sum \\eta_i T_i^T K_i T_i` and the viscous damping matrix.

    Parameters
    ----------
    pt : Powertrain
        The powertrain.

    Returns
    -------
    hysteretic : ndarray, shape (6, 6)
        The imaginary part of the complex stiffness [N/m], [N·m/rad].
    viscous : ndarray, shape (6, 6)
        [N·s/m], [N·m·s/rad].
    """
    return _assemble(pt, "h"), _assemble(pt, "c")


def check_held(pt: Powertrain) -> None:
    """Refuse mounts that do not hold the body in all six directions (a singular stiffness
    matrix): one :class:`InputError` naming the mounts and the free direction.

    Parameters
    ----------
    pt : Powertrain
        The powertrain.

    Returns
    -------
    None
    """
    k = stiffness_matrix(pt)
    size = max(
        float(np.max(np.abs(pt.cg))),
        *(float(np.max(np.abs(m.position - pt.cg))) for m in pt.mounts),
        1e-3,
    )
    scale = np.diag([1.0, 1.0, 1.0, size, size, size])
    values, vectors = np.linalg.eigh(scale @ k @ scale)
    if values[0] > SINGULAR_RATIO * max(values[-1], 0.0):
        return
    free = vectors[:, 0]
    axis = COORDINATES[int(np.argmax(np.abs(free)))]
    names = ", ".join(m.name for m in pt.mounts)
    raise InputError(
        "powertrain.mount",
        names,
        "must hold the powertrain in all six directions; their stiffness matrix is "
        f"singular (the body is free to move mostly along {axis}): add a mount or give "
        "every mount stiffness in more than one direction",
    )


@record
class Statics(ResultMixin):
    """The powertrain under its weight and a steady torque.

    Parameters
    ----------
    displacement : ndarray, shape (6,)
        q: translation of G [m] and rotation [rad].
    mount_loads : ndarray, shape (N, 3)
        The force each mount carries (the body's push on it), body axes [N].
    mount_loads_local : ndarray, shape (N, 3)
        The same along each mount's compression, first and second shear axes [N].
    load : ndarray, shape (6,)
        The static load at G: force [N] and moment [N·m].
    """

    displacement: NDArray[np.float64]
    mount_loads: NDArray[np.float64]
    mount_loads_local: NDArray[np.float64]
    load: NDArray[np.float64]


def statics(pt: Powertrain, torque: float = 0.0, gravity: float = GRAVITY) -> Statics:
    """Deflection and rotation under the weight and the reaction of a steady engine torque
    (the block takes :math:`-T` about the crank axis y), and each mount's static load.

    Parameters
    ----------
    pt : Powertrain
        The powertrain.
    torque : float
        The mean engine torque on the crank, positive in the sense of rotation [N·m].
    gravity : float
        Acceleration of gravity [m/s²].

    Returns
    -------
    Statics
    """
    check_held(pt)
    up = np.asarray(pt.up, dtype=float)
    load = np.concatenate([-pt.mass * gravity * up / np.linalg.norm(up), [0.0, -torque, 0.0]])
    q = np.linalg.solve(stiffness_matrix(pt), load)
    loads = np.array([m.body_stiffness() @ point_map(pt.cg, m.position) @ q for m in pt.mounts])
    return Statics(q, loads, _local(pt, loads), load)


def _local(pt: Powertrain, body: NDArray) -> NDArray:
    """Body-axis vectors per mount (..., N, 3) -> compression, shear 1, shear 2."""
    out = np.empty_like(body)
    for i, mount in enumerate(pt.mounts):
        along = body[..., i, :] @ mount.axes()  # shear1, shear2, compression
        out[..., i, 0] = along[..., 2]
        out[..., i, 1] = along[..., 0]
        out[..., i, 2] = along[..., 1]
    return out


def torque_roll_axis(inertia: ArrayLike, axis: ArrayLike = (0.0, 1.0, 0.0)) -> NDArray:
    """The torque-roll axis: the direction a free rigid body starts to turn about under a
    torque about ``axis``, :math:`I^{-1} e / |I^{-1} e|` (Jeong and Singh 2000).

    Parameters
    ----------
    inertia : array_like, shape (3, 3)
        The inertia tensor about the centre of gravity [kg·m²].
    axis : array_like, shape (3,)
        The torque's axis (the crank axis) [-].

    Returns
    -------
    ndarray, shape (3,)
        Unit vector, pointing with ``axis`` [-].
    """
    direction = np.linalg.solve(np.asarray(inertia, dtype=float), np.asarray(axis, dtype=float))
    direction = direction / np.linalg.norm(direction)
    return np.asarray(direction if direction @ np.asarray(axis) >= 0 else -direction)


@record
class Modes(ResultMixin):
    """The six rigid-body modes on the mounts (undamped).

    Parameters
    ----------
    frequencies : ndarray, shape (6,)
        Natural frequencies, ascending [Hz].
    shapes : ndarray, shape (6, 6)
        Column r: mode r's q, mass-normalised, its largest entry positive; translations
        then rotations [m/kg^0.5] and [rad/kg^0.5].
    energy : ndarray, shape (6, 6)
        Row r: per cent of mode r's kinetic energy in x, y, z, roll, pitch, yaw (the
        coordinates u_x, u_y, u_z, θ_y (roll about the crank axis), θ_x, θ_z):
        :math:`100\\,\\phi_{jr} (M\\phi_r)_j` [%].
    torque_roll_axis : ndarray, shape (3,)
        Its unit vector [-].
    roll_mode : int
        The mode with the most kinetic energy in roll (index into the six).
    roll_axis_angle : float
        Angle between the roll mode's rotation and the torque-roll axis [rad].
    """

    frequencies: NDArray[np.float64]
    shapes: NDArray[np.float64]
    energy: NDArray[np.float64]
    torque_roll_axis: NDArray[np.float64]
    roll_mode: int
    roll_axis_angle: float


#: the columns of the energy table as coordinates: x, y, z, roll (θ_y), pitch (θ_x), yaw (θ_z)
ENERGY_ORDER = (0, 1, 2, 4, 3, 5)


def modes(pt: Powertrain) -> Modes:
    """Natural frequencies, mode shapes and kinetic-energy distribution, the torque-roll
    axis and how close the roll mode turns about it.

    Roll is the rotation about the crank axis y, pitch about x, yaw about z (for a
    transverse engine the vehicle's pitch is the engine's roll: the table names the
    engine's axes).

    Parameters
    ----------
    pt : Powertrain
        The powertrain.

    Returns
    -------
    Modes
    """
    from scipy import linalg

    check_held(pt)
    mass = mass_matrix(pt)
    values, vectors = linalg.eigh(stiffness_matrix(pt), mass)
    values = np.clip(values, 0.0, None)
    # each shape's sign: its largest entry positive (eigh's sign is arbitrary)
    largest = vectors[np.argmax(np.abs(vectors), axis=0), np.arange(6)]
    vectors = vectors * np.where(largest < 0, -1.0, 1.0)[None, :]
    energy = 100.0 * vectors * (mass @ vectors)  # (6 coordinates, 6 modes)
    energy = energy[list(ENERGY_ORDER), :].T
    roll = int(np.argmax(energy[:, 3]))
    tra = torque_roll_axis(pt.inertia)
    turn = vectors[3:, roll]
    cosine = abs(float(turn @ tra)) / float(np.linalg.norm(turn))
    return Modes(
        np.sqrt(values) / (2 * math.pi),
        vectors,
        energy,
        tra,
        roll,
        float(math.acos(min(1.0, cosine))),
    )


def order_loads(
    force_forward: ArrayLike,
    force_backward: ArrayLike,
    couple_forward: ArrayLike,
    couple_backward: ArrayLike,
    roll: ArrayLike,
) -> NDArray[np.complex128]:
    """The complex amplitudes of the six real load signals of each order at the reference
    point, from crankbalance's order phasors (module docstring).

    Parameters
    ----------
    force_forward, force_backward : array_like of complex, shape (K,)
        :math:`F_n^\\pm` as :math:`z + ix` [N].
    couple_forward, couple_backward : array_like of complex, shape (K,)
        :math:`C_n^\\pm` [N·m]; the moment is :math:`M = iC`.
    roll : array_like of complex, shape (K,)
        :math:`R_n`, the roll :math:`M_y = \\mathrm{Re}(R_n e^{in\\theta})` [N·m].

    Returns
    -------
    ndarray of complex, shape (K, 6)
        :math:`X` of :math:`F_x, F_y, F_z, M_x, M_y, M_z` with each signal
        :math:`\\mathrm{Re}(X e^{in\\theta})` [N], [N·m].
    """
    fp, fm = np.asarray(force_forward, complex), np.conj(np.asarray(force_backward, complex))
    cp, cm = np.asarray(couple_forward, complex), np.conj(np.asarray(couple_backward, complex))
    out = np.zeros((fp.size, 6), dtype=complex)
    out[:, 0] = -1j * (fp - fm)
    out[:, 2] = fp + fm
    out[:, 3] = cp + cm
    out[:, 4] = np.asarray(roll, complex)
    out[:, 5] = 1j * (cp - cm)
    return out


def at_cg(loads: ArrayLike, cg: ArrayLike) -> NDArray[np.complex128]:
    """Loads at the reference point moved to the centre of gravity:
    :math:`M_G = M_P - G \\times F`.

    Parameters
    ----------
    loads : array_like, shape (..., 6)
        Force [N] and moment [N·m] at the reference point.
    cg : array_like, shape (3,)
        The centre of gravity from the reference point [m].

    Returns
    -------
    ndarray, shape (..., 6)
        Force [N] and moment about G [N·m].
    """
    loads = np.asarray(loads)
    out = np.array(loads, dtype=complex)
    out[..., 3:] = loads[..., 3:] - np.cross(np.asarray(cg, dtype=float), loads[..., :3])
    return out


def peak_magnitude(amplitude: ArrayLike) -> NDArray[np.float64]:
    """Largest length over a cycle of a harmonic vector :math:`\\mathrm{Re}(a e^{i\\Omega t})`:
    :math:`\\sqrt{(|a|^2 + |a \\cdot a|)/2}` (the major half-axis of its ellipse).

    Parameters
    ----------
    amplitude : array_like of complex, shape (..., 3)
        The complex vector a [any unit].

    Returns
    -------
    ndarray, shape (...)
        [unit of a].
    """
    a = np.asarray(amplitude, dtype=complex)
    square = np.sum(np.abs(a) ** 2, axis=-1)
    dot = np.abs(np.sum(a * a, axis=-1))
    return np.asarray(np.sqrt(np.clip((square + dot) / 2.0, 0.0, None)), dtype=float)


def response_size(speeds: int, orders: int) -> int:
    """The number of (speed, order) pairs a forced response solves.

    Parameters
    ----------
    speeds : int
        Speed samples [-].
    orders : int
        Engine orders [-].

    Returns
    -------
    int
        ``speeds * orders`` [-], at most :data:`MAX_RESPONSE_POINTS` for a run.
    """
    return int(speeds) * int(orders)


@record
class Response(ResultMixin):
    """The forced response over speed, order by order.

    Parameters
    ----------
    speeds : ndarray, shape (S,)
        Crank speeds [rad/s].
    orders : ndarray, shape (K,)
        Engine orders [-] (halves of a four-stroke's gas torque among them).
    displacement : ndarray of complex, shape (S, K, 6)
        q of each order: :math:`\\mathrm{Re}(Q e^{in\\theta})` [m], [rad].
    mount_forces : ndarray of complex, shape (S, K, N, 3)
        Force each mount transmits to the frame, body axes [N].
    mount_peak : ndarray, shape (S, K, N)
        Its largest length over a cycle [N].
    """

    speeds: NDArray[np.float64]
    orders: NDArray[np.float64]
    displacement: NDArray[np.complex128]
    mount_forces: NDArray[np.complex128]
    mount_peak: NDArray[np.float64]

    def point(self, cg: ArrayLike, point: ArrayLike) -> NDArray[np.complex128]:
        """Displacement of a body point, every speed and order.

        Parameters
        ----------
        cg : array_like, shape (3,)
            The centre of gravity [m].
        point : array_like, shape (3,)
            The point, from the reference point [m].

        Returns
        -------
        ndarray of complex, shape (S, K, 3)
            :math:`\\mathrm{Re}(U e^{in\\theta})` [m].
        """
        return np.asarray(self.displacement @ point_map(cg, point).T)


def forced_response(
    pt: Powertrain,
    loads: ArrayLike,
    orders: ArrayLike,
    reference_speed: float,
    speeds: ArrayLike,
    constant_loads: ArrayLike | None = None,
) -> Response:
    """Steady-state response of every order at every speed to the engine's loads.

    The loads are inertia forces, proportional to the speed squared: given at
    ``reference_speed``, they are scaled by :math:`(\\omega/\\omega_0)^2`. The
    ``constant_loads`` (the gas torque's reaction) are added as they are at every speed.

    Parameters
    ----------
    pt : Powertrain
        The powertrain.
    loads : array_like of complex, shape (K, 6)
        Each order's amplitudes at the reference point (:func:`order_loads`) [N], [N·m].
    orders : array_like, shape (K,)
        The engine orders n [-].
    reference_speed : float
        The crank speed the loads are given at [rad/s].
    speeds : array_like, shape (S,)
        Crank speeds [rad/s].
    constant_loads : array_like of complex, shape (K, 6), optional
        Loads of each order that do not change with the speed [N], [N·m].

    Returns
    -------
    Response
    """
    check_held(pt)
    speeds = np.asarray(speeds, dtype=float)
    orders = np.asarray(orders, dtype=float)
    if response_size(speeds.size, orders.size) > MAX_RESPONSE_POINTS:
        raise InputError(
            "speed_samples",
            speeds.size,
            f"speed samples x orders must be at most {MAX_RESPONSE_POINTS} ({orders.size} orders)",
        )
    k = stiffness_matrix(pt)
    h, c = damping_matrices(pt)
    m = mass_matrix(pt)
    omega = speeds[:, None] * orders[None, :]  # (S, K) excitation [rad/s]
    dynamic = (
        (k + 1j * h)[None, None]
        + 1j * omega[..., None, None] * c[None, None]
        - (omega**2)[..., None, None] * m[None, None]
    )
    scale = (speeds / reference_speed) ** 2
    force = at_cg(loads, pt.cg)[None, :, :] * scale[:, None, None]
    if constant_loads is not None:
        force = force + at_cg(constant_loads, pt.cg)[None, :, :]
    q = np.asarray(np.linalg.solve(dynamic, force[..., None])[..., 0], dtype=complex)
    forces = np.empty((*q.shape[:2], len(pt.mounts), 3), dtype=complex)
    for i, mount in enumerate(pt.mounts):
        d = q @ point_map(pt.cg, mount.position).T
        spring = mount.body_stiffness() * (1 + 1j * mount.loss_factor)
        complex_k = spring[None, None] + 1j * omega[..., None, None] * mount.body_damping()
        forces[:, :, i, :] = np.einsum("skab,skb->ska", complex_k, d)
    return Response(speeds, orders, q, forces, peak_magnitude(forces))


@record
class Crossing(ResultMixin):
    """An engine order meeting a natural frequency.

    Parameters
    ----------
    mode : int
        The mode's index (0 the lowest) [-].
    order : float
        The engine order [-].
    speed : float
        The crank speed where the order's frequency equals the mode's [rad/s].
    """

    mode: int
    order: float
    speed: float


def crossings(
    frequencies: ArrayLike, orders: ArrayLike, low: float, high: float
) -> tuple[Crossing, ...]:
    """Every (mode, order) whose crossing speed :math:`2\\pi f / n` lies in [low, high].

    Parameters
    ----------
    frequencies : array_like, shape (6,)
        Natural frequencies [Hz].
    orders : array_like
        Engine orders [-].
    low, high : float
        The speed range [rad/s].

    Returns
    -------
    tuple of Crossing
        By mode, then order.
    """
    out = []
    for r, f in enumerate(np.asarray(frequencies, dtype=float)):
        for n in np.asarray(orders, dtype=float):
            speed = 2 * math.pi * f / n
            if low <= speed <= high:
                out.append(Crossing(r, float(n), float(speed)))
    return tuple(out)
