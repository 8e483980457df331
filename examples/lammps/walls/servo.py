"""sffcal's lateral wall servo (docs/dem.md "Walls", dem/src/wall.cc servo_displacement), for
LAMMPS: loaded by shear.in with the `python` command when -var lateral_walls servo.

LAMMPS has no wall servo in this build (no fix controller), so the four lateral walls are plane
regions moved by `move v_dxlo ...`, each displacement a python-style variable read from the state
below; `fix ave/time 1 1 1 v_servo` calls servo_update() at the end of every step with the walls'
forces and contact counts of that step (fix wall/gran/region ... contacts, summed by compute
reduce), and it sets the displacements of the next step. Every MPI rank runs the same function on
the same (reduced) numbers, so all ranks move the walls alike.

Per wall and step, as sffcal (k_w = contacts x the sphere-wall stiffness, cap = max_speed dt):
    c = gain (F_target - F) / k_w                  the correction [m], inward positive
    I = clamp(I_prev + dt / (T_i dt_c) c, +-cap)   the integral
    move = blend (c + I) + (1 - blend) move_prev, clamped to +-cap (while clamped, the integral
           does not grow in the clamped direction); no contact: move = cap inward, I = 0.
F_target = sigma_3 x the face area (the other lateral width x the platens' gap). SI units.
"""
S = {}


def servo_setup(kw, p0, dt, dtc, gain, blend, ti, vmax, wx0, wy0, h0, vp):
    S.update(kw=kw, p0=p0, dt=dt, dtc=dtc, gain=gain, blend=blend, ti=ti, cap=vmax * dt,
             w0=(wx0, wy0), h0=h0, vp=vp, step=None,
             d=[0.0, 0.0, 0.0, 0.0],        # displacement along +axis: xlo, xhi, ylo, yhi [m]
             move=[0.0, 0.0, 0.0, 0.0], integral=[0.0, 0.0, 0.0, 0.0])
    return 0.0


def servo_update(step, f0, f1, f2, f3, n0, n1, n2, n3):
    """End of step `step`: forces f (magnitudes pushing the grains inward [N]) and contact counts n
    of the walls xlo, xhi, ylo, yhi; sets the displacements of the next step. Returns 0."""
    if step == S["step"]:  # evaluated more than once in a step: update once
        return 0.0
    S["step"] = step
    d, cap = S["d"], S["cap"]
    h = S["h0"] - 2.0 * S["vp"] * step * S["dt"]
    width = (S["w0"][0] + d[1] - d[0], S["w0"][1] + d[3] - d[2])
    area = (width[1] * h, width[1] * h, width[0] * h, width[0] * h)
    for k, (force, contacts) in enumerate(zip((f0, f1, f2, f3), (n0, n1, n2, n3))):
        target = S["p0"] * area[k]
        if contacts < 0.5:
            S["integral"][k] = 0.0
            move = cap
        else:
            correction = S["gain"] * (target - force) / (contacts * S["kw"])
            integral = S["integral"][k] + S["dt"] / (S["ti"] * S["dtc"]) * correction
            integral = max(-cap, min(cap, integral))
            move = S["blend"] * (correction + integral) + (1.0 - S["blend"]) * S["move"][k]
            if abs(move) > cap:
                move = max(-cap, min(cap, move))
                if (integral - S["integral"][k]) * move > 0.0:
                    integral = max(-cap, min(cap, S["integral"][k]))
            S["integral"][k] = integral
        S["move"][k] = move
        d[k] += move if k % 2 == 0 else -move  # inward: +axis for a lower wall, -axis for an upper
    return 0.0


def wall_dxlo():
    return S["d"][0]


def wall_dxhi():
    return S["d"][1]


def wall_dylo():
    return S["d"][2]


def wall_dyhi():
    return S["d"][3]
