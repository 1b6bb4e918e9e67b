"""Dynamics of one whisker (docs/dynamics.md): natural modes and motion with a prescribed base.

Both take their settings under the keys of the ``vibrissa modes`` / ``vibrissa dynamics`` case (the C++ code
that reads the case reads them), so a call and the command give the same numbers.
"""

import json

from ._vibrissa import Shape, _modes, _simulate_dynamics
from .labelled import to_dataset
from .pipeline import _NamedArrays

__all__ = ["DynamicsResult", "modes", "simulate_dynamics"]


def _settings(density, damping_ratio, joint_damping_time, gravity, **rest):
    dyn = {}
    if density is not None:
        dyn["density"] = float(density)
    if damping_ratio is not None:
        dyn["damping_ratio"] = float(damping_ratio)
    if joint_damping_time is not None:
        dyn["joint_damping_time"] = float(joint_damping_time)
    if gravity is not None:
        dyn["gravity"] = [float(g) for g in gravity]
    out = {"dynamics": dyn} if dyn else {}
    out.update({k: v for k, v in rest.items() if v is not None})
    return json.dumps(out)


def modes(whisker, count=10, *, load=None, hold=None, density=None, damping_ratio=None,
          joint_damping_time=None):
    """The ``count`` lowest natural modes of ``whisker`` (second-order scheme) about its rest shape, or with
    ``load`` (a dict as the ``"load"`` of ``vibrissa solve``: force, dead_load, point, edge, frictional_edge,
    object) about its equilibrium under that load; ``hold`` ("stick" or "slip") overrides how a contact holds
    (docs/dynamics.md). Returns ``frequency`` and ``damped_frequency`` [Hz], ``damping_ratio``,
    ``torsion_fraction`` (NumPy arrays, one value per mode), ``joint_shapes`` (3N, modes), ``node_shapes``
    (modes, N+1, 3; node displacements in the whisker frame, largest 1) and ``equilibrium`` (a dict: the held
    load, constraints, Newton's residual; None about rest). Defaults: density 1300 kg/m³, first-mode damping
    ratio 0.14 (Hartmann et al. 2003); ``joint_damping_time`` [s] sets the joint dampers instead
    (ζ_n = β ω_n / 2 about rest)."""
    m, eq = _modes(whisker, _settings(density, damping_ratio, joint_damping_time, None, load=load,
                                      hold=hold), int(count))
    view = _ModesView(m, whisker.links)
    view.equilibrium = json.loads(eq) if eq else None
    return view


class _ModesView:
    def __init__(self, m, links):
        self._m = m
        self.frequency = m.frequency
        self.damped_frequency = m.damped_frequency
        self.damping_ratio = m.damping_ratio
        self.torsion_fraction = m.torsion_fraction
        self.omega = m.omega
        self.joint_shapes = m.joint_shapes
        self.joint_damping_time = m.joint_damping_time
        self.node_shapes = m.node_shapes_flat.T.reshape(len(m), links + 1, 3)
        self.equilibrium = None

    def __len__(self):
        return len(self._m)

    def __repr__(self):
        f = ", ".join(f"{x:.4g}" for x in self.frequency[:4])
        return f"Modes({len(self)} modes, frequencies [Hz]: {f}{', ...' if len(self) > 4 else ''})"


class DynamicsResult(_NamedArrays):
    """The outputs of ``vibrissa dynamics``: the variables of ``dynamics.h5`` by name as NumPy arrays
    (``result.time``, ``result.Fx_B``, ``result.MB``, ``result.nodes_W`` of shape (frames, N+1, 3)), ``summary``
    (the dict of ``summary.json``), ``modes``, :meth:`to_xarray` and :meth:`write`."""

    _what = "dataset"

    def __init__(self, run, links):
        self._run = run
        self.datasets = dict(run.datasets())
        self._arrays = self.datasets
        self.summary = json.loads(run.summary_json())
        self.status = run.status
        self.modes = _ModesView(run.modes, links)
        #: contact events in time order: dicts with ``time`` [s], ``type`` ("touch", "slip", "stick", "release"),
        #: ``object`` (index into ``objects``), ``arc_length`` [m], ``point_W`` and ``force_W`` (on the whisker).
        self.events = self.summary.get("events", [])

    def __repr__(self):
        return (f"DynamicsResult(frames={len(self.datasets['time'])}, status={self.status!r}, "
                f"steps={self.summary['steps']})")

    def to_xarray(self):
        """The time series as an ``xarray.Dataset`` (dimensions ``time``, ``node``, ``component``), identical to
        ``xarray.open_dataset`` of the ``dynamics.h5`` that :meth:`write` writes."""
        return to_dataset(self._run.labelled())

    def write(self, directory):
        """Writes dynamics.csv, dynamics.h5 and summary.json into ``directory`` (as ``vibrissa dynamics``)."""
        self._run.write(str(directory))


def simulate_dynamics(whisker, duration=1.0, output_rate=1000.0, *, whisking=None, tip_force=None,
                      force=None, arc_length=None, density=None, damping_ratio=None, joint_damping_time=None, gravity=None,
                      relative_tolerance=None, absolute_tolerance=None, objects=None, contact=None, model=None):
    """Motion of ``whisker`` over ``duration`` [s], frames at ``output_rate`` [Hz] (docs/dynamics.md).

    ``whisking``: a dict with the keys of the case's ``"whisking"`` (``amplitude_deg``, ``frequency_Hz``,
    ``set_point_deg``, ``phase_deg``, ``series`` {``time_s``, ``dtheta_deg``}, ``k_phi``, ``k_zeta``): the base
    turns about the whisker's pose; None: the base holds still. ``tip_force`` (3,) [N] in the whisker frame:
    start in equilibrium under it, released at t = 0; ``force`` with ``arc_length`` [m]: the same at that arc
    length (a peg letting go). ``gravity`` (3,) [m/s²] in the world frame.

    ``objects``: a list of dicts as the case's ``"objects"`` (``{"type": "peg", "point": [...], "direction": [...],
    "radius": r, "friction_coefficient": mu}``, ``{"type": "edge", ...}``, or a surface as ``vibrissa solve``'s
    object: ``{"type": "sphere", "centre": [...], "radius": R, "friction_coefficient": mu, "thickness": True}``,
    plane, cylinder, box, mesh; world frame, SI), or shapes (``vibrissa.Sphere(...)``, ``vibrissa.Mesh.from_file(...)``,
    frictionless, the whisker's thickness), or ``{"shape": shape, "friction_coefficient": mu, "thickness": True}``,
    that the whisker may touch during the motion (the nonlinear chain; events in ``result.events``, per-object
    columns ``contact0_...``);
    ``contact``: ``{"stiffness", "tangential_stiffness", "damping_ratio"}``; ``model``: "automatic", "linear" or
    "nonlinear"."""
    initial = {}
    if tip_force is not None:
        initial["tip_force"] = [float(f) for f in tip_force]
    if force is not None:
        initial["force"] = [float(f) for f in force]
    if arc_length is not None:
        initial["arc_length"] = float(arc_length)
    described, shapes = _split_objects(objects)
    text = _settings(density, damping_ratio, joint_damping_time, gravity, duration=float(duration),
                     output_rate=float(output_rate), whisking=whisking, initial=initial or None,
                     relative_tolerance=relative_tolerance, absolute_tolerance=absolute_tolerance,
                     objects=described, contact=contact, model=model)
    return DynamicsResult(_simulate_dynamics(whisker, text, shapes), whisker.links)


def _split_objects(objects):
    """The objects described in JSON, and the shapes given as objects with their places in the list."""
    if objects is None:
        return None, []
    described, shapes = [], []
    for k, o in enumerate(objects):
        if isinstance(o, Shape):
            shapes.append((k, o, True, 0.0))
        elif isinstance(o, dict) and isinstance(o.get("shape"), Shape):
            unknown = sorted(set(o) - {"shape", "thickness", "friction_coefficient"})
            if unknown:
                raise ValueError(f"objects[{k}]: unknown field {unknown[0]!r}")
            shapes.append((k, o["shape"], bool(o.get("thickness", True)), float(o.get("friction_coefficient", 0.0))))
        else:
            described.append(o)
    return described, shapes
