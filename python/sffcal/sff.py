"""The stress-force-fabric analysis of contacts given as numpy arrays (compiled: sffcal._core;
docs/python.md, "The SFF analysis"; the mathematics: docs/sff.md).

    from sffcal import sff
    records = sff.contacts(normal=n, normal_force=fn, tangential_force=ft, branch=b,
                           body_a=a, body_b=b_ids)          # or an array of sff.CONTACT_DTYPE
    result = sff.analyse(records, volume=V, solid_volume=Vs, num_bodies=N,
                         youngs_modulus=E, friction=mu)
    result["eta"], result["a_c"], result["fabric_tensor"]

Units SI; a contact joins body A to body B, its normal points from A to B and its forces are those
on B (normal_force > 0 in compression); a wall contact has body_a = -1 and its wall's index.
"""
import numpy as np

try:
    from sffcal._core import CONTACT_DTYPE, StatisticsError, analyse, check  # noqa: F401
except ImportError as error:  # the source tree's copy of the package, without the build's module
    raise ImportError("sffcal.sff needs the compiled module sffcal._core, which CMake builds into "
                      f"BUILD/python/sffcal: put BUILD/python on PYTHONPATH (docs/python.md); "
                      f"{error}") from error

__all__ = ["CONTACT_DTYPE", "StatisticsError", "analyse", "check", "contacts"]


def contacts(normal, normal_force, tangential_force, branch, body_a, body_b, wall=None,
             sliding=None, point=None, overlap=None):
    """One array of CONTACT_DTYPE from separate arrays, n contacts each: normal (n, 3) unit vectors
    from A to B, normal_force (n,) [N], tangential_force (n, 3) [N], branch (n, 3) [m], body_a and
    body_b (n,) body ids (body_a = -1 for a wall contact, whose wall index goes in `wall`);
    optional wall (n,) (default -1), sliding (n,) 0/1, point (n, 3) [m], overlap (n,) [m]. This
    copies once; analyse() then reads the result in place."""
    normal = np.asarray(normal, dtype=float)
    if normal.ndim != 2 or normal.shape[1] != 3:
        raise ValueError(f"contacts: normal must be an array (n, 3), not of shape {normal.shape}")
    n = len(normal)
    records = np.zeros(n, dtype=CONTACT_DTYPE)
    records["wall"] = -1
    fields = {"normal": normal, "normal_force": normal_force, "tangential_force": tangential_force,
              "branch": branch, "body_a": body_a, "body_b": body_b, "wall": wall,
              "sliding": sliding, "point": point, "overlap": overlap}
    for name, value in fields.items():
        if value is None:
            continue
        value = np.asarray(value)
        shape = (n,) + CONTACT_DTYPE[name].shape
        if value.shape != shape:  # no broadcasting: one row per contact, as given
            raise ValueError(f"contacts: {name} must be of shape {shape}, not {value.shape}")
        integral = np.issubdtype(CONTACT_DTYPE[name].base, np.integer)
        if integral and not np.issubdtype(value.dtype, np.integer):
            raise ValueError(f"contacts: {name} must hold integers, not {value.dtype}")
        records[name] = value
    return records
