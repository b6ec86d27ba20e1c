"""flag-sim from Python: a scene's simulation stepped frame by frame, and the hybrid's infill alone.

    import flagsim
    sim = flagsim.Simulation(None, overrides={"wind.velocity": [5, 0, 0]})  # the default scene
    sim.step(30)                    # one second at 30 fps
    tip = sim.positions[16, -1]     # [J, K, 3] numpy view of the dense lattice, m
    sim.run("out/windy.h5")         # the scene's whole run, the HDF5 of `flag-sim run`

Names (README "Python"):
  Simulation(scene=None, overrides=None)  scene: a path, a TOML string, a dict or None (the
      embedded default scene); overrides: {"dotted.key": value}, as `--set dotted.key=value`.
  .step(frames=1), .time (s), .frame, .fps, .mode, .shape (J, K),
  .positions, .velocities ([J, K, 3], read-only views that follow every step, no copy),
  .coarse_positions ([Jc, Kc, 3] in the hybrid, else None), .run(path, quiet=True).
  infill(coarse, fine=(J, K), size=(width, height), pin="left", solver="smooth") -> [J, K, 3].
  SceneError (a ValueError): a bad scene, override or argument, with the command line's message.
  WriteError (an OSError): an output that cannot be written. A diverged frame is RuntimeError.
  .state() -> dict of copies (frame, time, positions, velocities; coarse_positions and
      coarse_velocities in the hybrid; infill_memory with [wrinkles]; format), .set_state(state):
      go on from it, here or in a new Simulation of the same scene, bit for bit.
"""
import math
import os

from ._flagsim import SceneError, WriteError, infill
from ._flagsim import Simulation as _Simulation

__all__ = ["Simulation", "SceneError", "WriteError", "infill"]


def _toml_value(value):
    """A Python value as a TOML value (what `--set KEY=VALUE` takes)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise SceneError(f"{value!r}: scene values are finite numbers")
        return repr(value)
    if isinstance(value, str):
        escaped = value.replace("\\", "\\\\").replace('"', '\\"')
        escaped = "".join(c if c >= " " else f"\\u{ord(c):04x}" for c in escaped)
        return f'"{escaped}"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):  # an inline table: a fold line of flag.folds
        return "{ " + ", ".join(f"{_toml_value(str(k))} = {_toml_value(v)}"
                                for k, v in value.items()) + " }"
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        return _toml_value(value.tolist())
    raise SceneError(f"{value!r}: expected a number, bool, string, list or dict for a scene value")


def _toml_document(scene):
    """A dict of tables ({"flag": {"fine": [33, 49]}, "wind": {...}}) as TOML text."""
    lines = []

    def table(name, body):
        plain = {k: v for k, v in body.items() if not isinstance(v, dict)}
        if name:
            lines.append(f"[{name}]")
        for key, value in plain.items():
            lines.append(f"{key} = {_toml_value(value)}")
        for key, value in body.items():
            if isinstance(value, dict):
                table(f"{name}.{key}" if name else key, value)

    if not isinstance(scene, dict):
        raise SceneError("a scene dict maps table names to dicts of keys")
    table("", scene)
    return "\n".join(lines) + "\n"


class Simulation(_Simulation):
    """A scene compiled and running; see the module's help."""

    def __init__(self, scene=None, overrides=None):
        from_file = False
        if scene is None:
            text, source = None, ""
        elif isinstance(scene, dict):
            text, source = _toml_document(scene), "<scene dict>"
        elif isinstance(scene, (str, os.PathLike)):
            path = os.fspath(scene)
            if "\n" not in path and (path.endswith(".toml") or os.path.isfile(path)):
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                source, from_file = path, True
            else:
                text, source = path, "<scene text>"
        else:
            raise SceneError(f"{type(scene).__name__}: a scene is a path, a TOML string, a dict "
                             "or None")
        sets = [f"{key}={_toml_value(value)}" for key, value in (overrides or {}).items()]
        super().__init__(text, source, sets, from_file)
