"""TEST DOUBLE ONLY: a tiny pure-Python stand-in for the coupled simulation, used to test the run
loop, the output and the CLI without the C++ solver. Its "physics" is made up: the water level
follows a weir formula of the inflow, and stones of the downstream face are pushed off one by one
once the discharge passes a per-stone threshold. It is never shipped as a solver."""
from types import SimpleNamespace

import numpy as np


class FakeProfile:
    def __init__(self):
        self.names = ["fake_fluid", "fake_dem"]
        self.seconds = [0.0, 0.0]
        self.calls = [0, 0]


class FakeSimulation:
    def __init__(self, scene, fail_at=None, thresholds_lps=None):
        self.scene = scene
        g = scene.grid
        nx = int(round(scene.flume.length / g.dx))
        z_faces = np.arange(0.0, scene.flume.height + 1e-9, g.dz)
        self.fluid = SimpleNamespace(grid=SimpleNamespace(nx=nx, nz=z_faces.size - 1, dx=g.dx, x0=0.0,
                                                          z_faces=list(z_faces)))
        nz = z_faces.size - 1
        self.fluid.cell_F = np.zeros(nx * nz)
        self.fluid.cell_p = np.zeros(nx * nz)
        self.fluid.cell_porosity = np.ones(nx * nz)
        self.fluid.face_u = np.zeros((nx + 1) * nz)
        self.fluid.face_w = np.zeros(nx * (nz + 1))
        w, d = scene.weir, scene.stones.diameter
        xs = np.arange(w.toe_x + d, w.x_toe_down - d / 2, d)
        pos = np.stack([xs, np.maximum(w.surface(xs) - d / 2, d / 2)], axis=1)
        n = len(pos)
        self.params = SimpleNamespace(n_exp=scene.stones.n_exp)  # as the Coupler's CouplerParams
        self.stones = SimpleNamespace(shape="disc", stone_pos=pos, stone_vel=np.zeros((n, 2)),
                                      stone_radius=np.full(n, d / 2), stone_active=np.ones(n, bool),
                                      stone_fixed=pos[:, 1] <= d / 2 + 1e-12, held=False)
        self.stone_force_drag = np.zeros((n, 2))
        self.stone_force_pressure = np.zeros((n, 2))
        self.profile = FakeProfile()
        self.time = 0.0
        self.fail_at = fail_at
        self.table = None
        # stones of the downstream face go at given discharges (default 15, 15.2, 18, 18.1, 18.3 l/s)
        down = [i for i in np.argsort(-pos[:, 0]) if pos[i, 0] > w.x_crest_down and not self.stones.stone_fixed[i]]
        self.thresholds = dict(zip(down, thresholds_lps or [15.0, 15.2, 18.0, 18.1, 18.3]))

    def set_inflow_table(self, times, q):
        assert np.all(np.diff(times) > 0)
        self.table = (np.asarray(times), np.asarray(q))

    def advance(self, t_end):
        if self.fail_at is not None and t_end > self.fail_at:
            self.time = self.fail_at
            raise RuntimeError(f"fake stage 'pressure': no convergence in cell (3, 4) at t = {self.fail_at} s")
        dt = t_end - self.time
        q = float(np.interp(t_end, *self.table))
        nx, nz = self.fluid.grid.nx, self.fluid.grid.nz
        zc = 0.5 * (np.asarray(self.fluid.grid.z_faces[1:]) + np.asarray(self.fluid.grid.z_faces[:-1]))
        level = self.scene.weir.height + (q / (1.7 * self.scene.flume.width)) ** (2 / 3)
        F = np.clip((level - zc[:, None]) / self.scene.grid.dz + 0.5, 0, 1) * np.ones((1, nx))
        self.fluid.cell_F[:] = F.ravel()
        self.fluid.cell_p[:] = (1000 * 9.81 * np.clip(level - zc, 0, None)[:, None] * np.ones((1, nx))).ravel()
        self.fluid.face_u[:] = q / self.scene.flume.width / max(level, 1e-3)
        st = self.stones
        for i, thr in self.thresholds.items():
            if q * 1e3 >= thr and not st.stone_fixed[i] and not st.held:
                st.stone_vel[i] = (0.3, -0.05)
                st.stone_pos[i] += dt * st.stone_vel[i]
                self.stone_force_drag[i] = (1.0, 0.1)
                self.stone_force_pressure[i] = (0.5, 1.0)
        st.stone_active[:] = st.stone_pos[:, 0] < self.scene.flume.length
        self.profile.seconds = [s + 1e-3 for s in self.profile.seconds]
        self.profile.calls = [c + 1 for c in self.profile.calls]
        self.time = float(t_end)

    @property
    def step_count(self):
        return self.profile.calls[0]  # one step per advance, as the profile counts them

    def step_limits(self):
        return {"fake_limit": self.step_count}  # every step bound by one made-up limit

    def export_state(self):
        st, fl = self.stones, self.fluid
        return {"time": np.array([self.time]), "pos": st.stone_pos.copy(), "vel": st.stone_vel.copy(),
                "active": st.stone_active.astype(float), "fixed": st.stone_fixed.astype(float),
                "drag": self.stone_force_drag.copy(), "pressure": self.stone_force_pressure.copy(),
                "F": fl.cell_F.copy(), "p": fl.cell_p.copy(), "u": fl.face_u.copy()}

    def import_state(self, s):
        st, fl = self.stones, self.fluid
        self.time = float(s["time"][0])
        # a checkpoint holds each array flat
        st.stone_pos[...], st.stone_vel[...] = (np.reshape(s[k], (-1, 2)) for k in ("pos", "vel"))
        st.stone_active[...], st.stone_fixed[...] = s["active"] != 0, s["fixed"] != 0
        self.stone_force_drag[...], self.stone_force_pressure[...] = (np.reshape(s[k], (-1, 2)) for k in ("drag", "pressure"))
        fl.cell_F[...], fl.cell_p[...], fl.face_u[...] = s["F"], s["p"], s["u"]


def short_scene():
    """The quick Maeno 2008 scene with a 2 s spin-up, a 30 s ramp 10 -> 25 l/s and 1 s snapshots."""
    from vofdem.scene import Hydrograph, Scene

    s = Scene.maeno2008().quick()
    s.hydrograph = Hydrograph(discharge_start_lps=10, discharge_end_lps=25, ramp_duration=30, spin_up_duration=2)
    s.output.snapshot_interval = 1.0
    return s.validate()
