#!/usr/bin/env python3
"""Accuracy of vofdem.DEMSystem on the analytic contact cases, written to
validation/results/dem_validation.md (the same cases as tests/cpp/stones/test_dem_contact.cpp, with the
measured errors printed instead of checked).

usage: PYTHONPATH=python python3 validation/dem_validation.py
"""
import math
import os

import numpy as np

import vofdem

R, RHO = 0.024, 2650.0
M = RHO * 4.0 / 3.0 * math.pi * R**3
HERE = os.path.dirname(os.path.abspath(__file__))


def wall_impact(vx, vz, e, mu=0.3, kn=1e5, steps_per_contact=400):
    p = vofdem.DEMParams()
    p.flags &= ~vofdem.DEM_GRAVITY
    p.stiffness_normal = kn
    p.restitution = e
    p.tangential_damping_factor = 0.0
    p.walls = [vofdem.DEMWall(point=[0.0, 0.0], normal=[0.0, 1.0], friction=mu)]
    s = vofdem.DEMSystem(p, pos=np.array([[0.5, R + 0.001]]), density=[2650.0], radius=np.array([R]))
    s.stone_vel[0] = [vx, vz]
    zeta = vofdem.damping_ratio_from_restitution(e)
    tc = vofdem.contact_duration(kn, M, zeta)
    dt = tc / steps_per_contact
    duration, touched = 0.0, False
    for _ in range(100000):
        s.step(dt)
        if s.wall_contact_count > 0:
            touched = True
            duration += dt
        elif touched:
            break
    return s.stone_vel[0].copy(), s.stone_omega[0], duration, tc


def incline(theta, mu, rotation=True, f=0.4, mu_r=0.0, hold=False):
    p = vofdem.DEMParams()
    p.rolling_friction_wall = mu_r
    p.medium.gravity = [9.81 * math.sin(theta), -9.81 * math.cos(theta)]
    p.stiffness_normal = 1e5
    p.inertia_factor = f
    if not rotation:
        p.flags &= ~vofdem.DEM_ROTATION
    p.walls = [vofdem.DEMWall(point=[0.0, 0.0], normal=[0.0, 1.0], friction=mu)]
    delta = M * 9.81 * math.cos(theta) / 1e5
    s = vofdem.DEMSystem(p, pos=np.array([[0.0, R - delta]]), density=[2650.0], radius=np.array([R]))
    if hold:
        s.advance(2.0)
        return s.stone_vel[0, 0], s.stone_pos[0, 0]
    s.advance(0.5)
    v0 = s.stone_vel[0, 0]
    s.advance(0.5)
    return (s.stone_vel[0, 0] - v0) / 0.5


def rolling_box(frac, mu_r=0.3):
    """(total - E0) / dissipated after 0.5 s of 60 stones falling into a box, rolling friction mu_r."""
    rng = np.random.default_rng(5)
    p = vofdem.DEMParams()
    p.add_flume(0.0, 0.45, 0.0, 0.3)
    p.stiffness_normal, p.restitution = 2e5, 0.3
    p.rolling_friction_stone = p.rolling_friction_wall = mu_r
    pos = np.array([[0.03 + 0.055 * (k % 8) + 0.002 * rng.random(), 0.03 + 0.055 * (k // 8)] for k in range(60)])
    s = vofdem.DEMSystem(p, pos=pos, density=[2650.0], radius=R * (0.9 + 0.2 * rng.random(60)))
    dt = frac * s.stable_dt()
    e0 = s.energy().total
    for _ in range(int(0.5 / dt)):
        s.step(dt)
    e = s.energy()
    return (e.total - e0) / e.dissipated


def rolling_rows():
    """Rolling resistance (tests/cpp/stones/test_rolling_resistance.cpp): a disc on an incline holds while
    tan(theta) <= mu_r and rolls at g (sin - mu_r cos) / (1 + f) above; the energy balance."""
    g, mu, mu_r = 9.81, 0.577, 0.2
    rows = []
    v, x = incline(math.atan(0.95 * mu_r), mu, mu_r=mu_r, hold=True)
    rows.append(f"| rolling resistance mu_r = {mu_r}, tan(theta) = 0.95 mu_r, 2 s | speed {abs(v):.1e} m/s, "
                f"displacement {abs(x):.1e} m (holds: 0) |")
    for f in (0.4, 0.5):
        for k in (1.2, 1.5, 2.0):
            th = math.atan(k * mu_r)
            a = incline(th, mu, f=f, mu_r=mu_r)
            ex = g * (math.sin(th) - mu_r * math.cos(th)) / (1.0 + f)
            rows.append(f"| rolling resistance mu_r = {mu_r}, f = {f}, tan(theta) = {k} mu_r | acceleration error "
                        f"{100 * (a - ex) / ex:+.3f} % against g (sin - mu_r cos) / (1 + f) |")
    e1, e2 = rolling_box(0.5), rolling_box(0.25)
    rows.append(f"| rolling resistance 0.3, 60 stones into a box (e = 0.3), energy balance | (total - E0) / dissipated "
                f"{100 * e1:+.2f} % at stable_dt / 2, {100 * e2:+.2f} % at stable_dt / 4 |")
    return rows


def main():
    rows = []
    for e in (0.3, 0.5, 0.9):
        for spc in (20, 400):
            v, _, dur, tc = wall_impact(0.0, -1.0, e, steps_per_contact=spc)
            rows.append(f"| normal impact e = {e}, {spc} steps/contact | restitution {v[1]:.4f} "
                        f"(error {100 * (v[1] - e) / e:+.2f} %), duration error {100 * (dur - tc) / tc:+.2f} % |")
    mu, e = 0.092, 0.98
    for ang in (5, 15, 45, 60, 80):
        a = math.radians(ang)
        vn, vt = 3.9 * math.cos(a), 3.9 * math.sin(a)
        v, om, _, _ = wall_impact(vt, -vn, e, mu=mu)
        dvt = mu * (1 + e) * vn
        regime = "sliding" if vt / vn > mu * (1 + e) * 3.5 else "sticking"
        rows.append(f"| oblique impact {ang} deg ({regime}; Chung & Ooi test 4 inputs) | "
                    f"dv_t / (mu (1+e) v_n) = {(vt - v[0]) / dvt:.4f}, -omega r f / (mu (1+e) v_n) = "
                    f"{-om * R * 0.4 / dvt:.4f} (sliding theory: 1, 1) |")
    g = 9.81
    th = math.atan(0.9 * 0.5)
    a = incline(th, 0.5, rotation=False)
    rows.append(f"| block (no rotation), tan(theta) = 0.9 mu | acceleration {a:.2e} m/s^2 (holds: 0) |")
    th = math.atan(1.1 * 0.5)
    a = incline(th, 0.5, rotation=False)
    ex = g * (math.sin(th) - 0.5 * math.cos(th))
    rows.append(f"| block, tan(theta) = 1.1 mu | acceleration error {100 * (a - ex) / ex:+.3f} % |")
    th = math.radians(20)
    for f, name, frac in ((0.4, "sphere inertia", 5 / 7), (0.5, "disc inertia", 2 / 3)):
        a = incline(th, 0.577, f=f)
        ex = frac * g * math.sin(th)
        rows.append(f"| rolling, {name}, 20 deg | acceleration error {100 * (a - ex) / ex:+.3f} % |")
    rows += rolling_rows()
    lines = ["# DEM validation (analytic contact cases)", "",
             "Stone: 4.8 cm, 2650 kg/m^3 (sphere mass 0.15345 kg), k_n = 1e5 N/m unless stated.", "",
             "| case | result |", "|---|---|"] + rows
    os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
    path = os.path.join(HERE, "results", "dem_validation.md")
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
