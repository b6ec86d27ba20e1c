#!/usr/bin/python3
"""The Python module `flagsim` (contract: "Library and Python") against the command line.

Usage: flagsim_module_test.py FLAG_SIM_BINARY   (with PYTHONPATH holding build/python)
"""
import os
import subprocess
import sys
import tempfile
import unittest

import h5py
import numpy as np

import flagsim

FLAG_SIM = None
SMALL = {"flag.fine": [33, 49]}  # the default scene (hybrid, 9 x 13 coarse) on a small lattice
SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes")


def cli_frames(*args, frames=4):
    """The command line's /frames/positions and /coarse/positions of `flag-sim run ARGS`."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cli.h5")
        subprocess.run([FLAG_SIM, "run", "--quiet", "--frames", str(frames), "-o", out, *args],
                       check=True, stdout=subprocess.DEVNULL)
        with h5py.File(out, "r") as f:
            return f["/frames/positions"][()], f["/coarse/positions"][()]


class Simulation(unittest.TestCase):
    def test_each_frame_is_the_command_lines_bit_for_bit(self):
        positions, coarse = cli_frames("--set", "flag.fine=[33,49]")
        sim = flagsim.Simulation(None, overrides=SMALL)
        self.assertEqual(sim.shape, (33, 49))
        self.assertEqual(sim.mode, "hybrid")
        for frame in range(4):
            if frame:
                sim.step()
            # The file stores float32 (contract): the same rounding of the same doubles.
            np.testing.assert_array_equal(sim.positions.astype(np.float32), positions[frame])
            np.testing.assert_array_equal(sim.coarse_positions.astype(np.float32), coarse[frame])
        self.assertAlmostEqual(sim.time, 3 / 30.0, places=12)

    def test_the_arrays_view_the_state_and_follow_each_step(self):
        sim = flagsim.Simulation(None, overrides=SMALL)
        view = sim.positions
        before = view.copy()
        sim.step(2)
        self.assertEqual(view.ctypes.data, sim.positions.ctypes.data)  # no copy
        self.assertGreater(np.abs(view - before).max(), 1e-4)  # moved with the state
        self.assertFalse(view.flags.writeable)  # the state is changed by step(), not by hand
        with self.assertRaises(ValueError):
            view[0, 0, 0] = 1.0
        del sim  # the view keeps the simulation alive
        self.assertTrue(np.isfinite(view).all())

    def test_a_file_a_toml_string_and_a_dict_are_the_same_scene(self):
        scene = ('[scene]\nname = "py"\nmode = "hybrid"\nduration = 1.0\n'
                 '[flag]\nfine = [17, 25]\ncoarse = [5, 7]\ninitial_perturbation = 0.01\n'
                 '[wind]\nvelocity = [8.0, 0.0, 0.0]\n')
        as_dict = {"scene": {"name": "py", "mode": "hybrid", "duration": 1.0},
                   "flag": {"fine": [17, 25], "coarse": [5, 7], "initial_perturbation": 0.01},
                   "wind": {"velocity": [8.0, 0.0, 0.0]}}
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "py.toml")
            with open(path, "w") as f:
                f.write(scene)
            runs = [flagsim.Simulation(s) for s in (path, scene, as_dict)]
            for sim in runs:
                sim.step(5)
            for sim in runs[1:]:
                np.testing.assert_array_equal(sim.positions, runs[0].positions)

    def test_run_writes_the_command_lines_file_and_never_over_its_scene(self):
        positions, _ = cli_frames("--set", "flag.fine=[33,49]", "--set", "scene.duration=0.1")
        sim = flagsim.Simulation(None, overrides={**SMALL, "scene.duration": 0.1})
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "py.h5")
            self.assertEqual(sim.run(out), 0)
            with h5py.File(out, "r") as f:
                np.testing.assert_array_equal(f["/frames/positions"][()], positions)
            scene = os.path.join(tmp, "s.toml")
            with open(scene, "w") as f:
                f.write("[scene]\nduration = 0.1\n[flag]\nfine = [17, 25]\ncoarse = [5, 7]\n")
            with self.assertRaisesRegex(ValueError, "s.toml"):
                flagsim.Simulation(scene).run(scene)
            with open(scene) as f:
                self.assertTrue(f.read().startswith("[scene]"))  # untouched
            # A scene from a dict or a string has no file: nothing named like its
            # message label ("<scene dict>") is taken for its input.
            label = "<scene dict>"
            here = os.getcwd()
            os.chdir(tmp)
            try:
                with open(label, "w") as f:
                    f.write("not a scene")
                as_dict = {"scene": {"duration": 0.1, "mode": "hybrid"},
                           "flag": {"fine": [17, 25], "coarse": [5, 7]}}
                self.assertEqual(flagsim.Simulation(as_dict).run(label), 0)
                with h5py.File(label, "r") as f:
                    self.assertEqual(f["/frames/positions"].shape[1:3], (17, 25))
            finally:
                os.chdir(here)

    def test_bad_scenes_raise_the_command_lines_messages(self):
        with self.assertRaisesRegex(ValueError, r"flag.coarse: \[9, 13\] does not divide"):
            flagsim.Simulation(None, overrides={"flag.fine": [33, 50]})
        with self.assertRaisesRegex(ValueError, "wind.velocty.*did you mean"):
            flagsim.Simulation(None, overrides={"wind.velocty": [1, 0, 0]})
        with self.assertRaisesRegex(ValueError, "<scene text>"):
            flagsim.Simulation("[flag]\nfine = \n")
        with self.assertRaises(ValueError):
            flagsim.Simulation(None, overrides={"flag.size": [float("nan"), 1.0]})
        with self.assertRaises(ValueError):
            flagsim.Simulation(42)
        with self.assertRaises(FileNotFoundError):
            flagsim.Simulation("no/such/scene.toml")

    def test_a_diverged_frame_raises_and_stops(self):
        sim = flagsim.Simulation(None, overrides={**SMALL, "flag.stretch_modulus": 1.0,
                                                  "limits.max_strain": 0.05})
        with self.assertRaisesRegex(RuntimeError, "diverged at t = .*max link strain"):
            sim.step(60)
        with self.assertRaisesRegex(RuntimeError, "diverged earlier"):
            sim.step()


class State(unittest.TestCase):
    """state() / set_state(): going on from a restored state is going on from where it was taken."""

    CASES = {
        "hybrid": (None, SMALL),
        "hybrid, wrinkles": (os.path.join(SCENES, "hard", "hybrid_storm_wrinkles.toml"),
                             {"flag.fine": [17, 25], "flag.coarse": [5, 7]}),
        "hybrid, paper infill": (None, {**SMALL, "infill.solver": "paper"}),
        "hybrid, bullet": (None, {**SMALL, "solver.backend": "bullet"}),
        "mass-spring": (None, {"scene.mode": "mass-spring", "flag.fine": [17, 25]}),
        "implicit": (None, {"scene.mode": "implicit", "flag.fine": [17, 25]}),
        "xpbd": (None, {"scene.mode": "xpbd", "flag.fine": [17, 25]}),
        "mass-spring, creased": (None, {"scene.mode": "mass-spring", "flag.fine": [17, 25],
                                        "flag.folds": [{"axis": "col", "at": 0.5, "angle": 2.5}],
                                        "bending.stiffness": 1e-4, "creases.set_time": 1.0}),
        "infill": (os.path.join(SCENES, "infill", "twisted.toml"), {"flag.fine": [17, 25]}),
    }

    def test_a_restored_state_goes_on_bit_for_bit_in_every_mode(self):
        for name, (scene, overrides) in self.CASES.items():
            with self.subTest(name):
                sim = flagsim.Simulation(scene, overrides=overrides)
                sim.step(3)
                saved = sim.state()
                sim.step(3)
                after = (sim.positions.copy(), sim.velocities.copy(), sim.time, sim.frame)
                self.assertGreater(np.abs(after[0] - saved["positions"]).max(), 1e-5)
                # The state is a copy: stepping on did not change it.
                self.assertEqual(saved["frame"], 3)
                for target in (sim, flagsim.Simulation(scene, overrides=overrides)):
                    target.set_state(saved)
                    self.assertEqual(target.frame, 3)
                    np.testing.assert_array_equal(target.positions, saved["positions"])
                    target.step(3)
                    np.testing.assert_array_equal(target.positions, after[0])
                    np.testing.assert_array_equal(target.velocities, after[1])
                    self.assertEqual((target.time, target.frame), after[2:])

    def test_the_infill_memory_is_restored(self):
        # 3.5 keeps each wave on the side it was (property 2): the memory decides the sides.
        scene, overrides = self.CASES["hybrid, wrinkles"]
        sim = flagsim.Simulation(scene, overrides=overrides)
        sim.step(3)
        saved = sim.state()
        sim.step()
        kept = sim.positions.copy()
        sim.set_state({**saved, "infill_memory": -saved["infill_memory"]})
        sim.step()
        self.assertGreater(np.abs(sim.positions - kept).max(), 1e-4)

    def test_the_creases_rest_angles_are_restored(self):
        # The creases' rest and held angles (issue 32): 2 x 766 bending triples of 17 x 25.
        scene, overrides = self.CASES["mass-spring, creased"]
        sim = flagsim.Simulation(scene, overrides=overrides)
        sim.step(3)
        saved = sim.state()
        self.assertEqual(saved["physics_memory"].shape, (2 * (17 * 23 + 15 * 25),))
        sim.step()
        kept = sim.positions.copy()
        sim.set_state({**saved, "physics_memory": 0 * saved["physics_memory"]})  # no creases
        sim.step()
        self.assertGreater(np.abs(sim.positions - kept).max(), 1e-6)
        with self.assertRaises(flagsim.SceneError):
            sim.set_state({**saved, "physics_memory": saved["physics_memory"][:-1]})

    def test_the_state_names_its_parts(self):
        sim = flagsim.Simulation(None, overrides=SMALL)
        sim.step()
        state = sim.state()
        self.assertEqual(state["format"], "flagsim.state/1")
        self.assertEqual(state["positions"].shape, (33, 49, 3))
        self.assertEqual(state["coarse_velocities"].shape, (9, 13, 3))
        np.testing.assert_array_equal(state["coarse_positions"], sim.coarse_positions)
        self.assertAlmostEqual(state["time"], 1 / 30.0, places=12)
        full = flagsim.Simulation(None, overrides={"scene.mode": "mass-spring",
                                                   "flag.fine": [17, 25]})
        self.assertNotIn("coarse_positions", full.state())

    def test_a_state_brings_a_diverged_simulation_back(self):
        sim = flagsim.Simulation(None, overrides={**SMALL, "flag.stretch_modulus": 1.0,
                                                  "limits.max_strain": 0.05})
        start = sim.state()
        with self.assertRaises(RuntimeError):
            sim.step(60)
        sim.set_state(start)
        sim.step()  # no "diverged earlier"
        self.assertEqual(sim.frame, 1)

    def test_a_state_that_does_not_fit_is_refused_and_changes_nothing(self):
        sim = flagsim.Simulation(None, overrides=SMALL)
        sim.step(2)
        good = sim.state()
        before = sim.positions.copy()
        other = flagsim.Simulation(None, overrides={"flag.fine": [17, 25]}).state()
        cases = [
            (other, r"'positions' must be an array of shape \[33, 49, 3\]"),
            ({k: v for k, v in good.items() if k != "coarse_velocities"},
             "no 'coarse_velocities'"),
            ({**good, "positions": good["positions"] * np.nan}, "not finite"),
            ({**good, "format": "something else"}, "expected a dict from state"),
            ({**good, "frame": -1}, "'frame' must be 0 or more"),
        ]
        for bad, message in cases:
            with self.subTest(message):
                with self.assertRaisesRegex(ValueError, message):
                    sim.set_state(bad)
                np.testing.assert_array_equal(sim.positions, before)
                self.assertEqual(sim.frame, 2)


class Wind(unittest.TestCase):
    """The wind settable between steps (issue 30): README's loop, state() keeps it."""

    def test_a_loop_that_changes_the_wind_every_frame(self):
        sim = flagsim.Simulation(None, overrides=SMALL)
        np.testing.assert_array_equal(sim.wind, [10.0, 0.0, 0.0])
        steady = flagsim.Simulation(None, overrides=SMALL)
        for frame in range(6):
            sim.wind = [10.0 - frame, 0.0, 0.0]
            sim.step()
            steady.step()
        np.testing.assert_array_equal(sim.wind, [5.0, 0.0, 0.0])
        self.assertGreater(np.abs(sim.positions - steady.positions).max(), 1e-4)

    def test_the_state_keeps_the_wind(self):
        sim = flagsim.Simulation(None, overrides={**SMALL, "wind.turbulence.intensity": 0.2})
        sim.step(2)
        sim.wind = [4.0, 0.0, 1.0]
        sim.step(2)
        saved = sim.state()
        np.testing.assert_array_equal(saved["wind"]["velocity"], [4.0, 0.0, 1.0])
        sim.step(2)
        after = sim.positions.copy()
        other = flagsim.Simulation(None, overrides={**SMALL, "wind.turbulence.intensity": 0.2})
        other.set_state(saved)
        np.testing.assert_array_equal(other.wind, [4.0, 0.0, 1.0])
        other.step(2)
        np.testing.assert_array_equal(other.positions, after)

    def test_what_cannot_change_is_said(self):
        sim = flagsim.Simulation(None, overrides=SMALL)
        with self.assertRaisesRegex(ValueError, "faster than the scene's wind.velocity"):
            sim.wind = [0.0, 0.0, 11.0]
        calm = flagsim.Simulation("[scene]\nmode = 'mass-spring'\n[flag]\nfine = [5, 7]\n")
        self.assertIsNone(calm.wind)
        with self.assertRaisesRegex(ValueError, r"the scene has no \[wind\]"):
            calm.wind = [1.0, 0.0, 0.0]


class Infill(unittest.TestCase):
    def test_the_infill_alone_gives_the_hybrids_dense_frame(self):
        sim = flagsim.Simulation(None, overrides=SMALL)
        sim.step(5)
        dense = flagsim.infill(sim.coarse_positions, fine=(33, 49), size=(1.5, 1.0))
        np.testing.assert_array_equal(dense, sim.positions)

    def test_bad_arguments(self):
        coarse = np.zeros((9, 13, 3))
        with self.assertRaisesRegex(ValueError, "not a refinement"):
            flagsim.infill(coarse, fine=(33, 50))
        with self.assertRaisesRegex(ValueError, "shape"):
            flagsim.infill(np.zeros((9, 13)), fine=(33, 49))
        with self.assertRaisesRegex(ValueError, "pin"):
            flagsim.infill(coarse, fine=(33, 49), pin="middle")


if __name__ == "__main__":
    FLAG_SIM = sys.argv.pop(1)
    unittest.main(verbosity=2)
