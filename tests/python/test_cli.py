"""aerobox fly --controller / --trajectory-module / --planner-module file.py:Class: user Python
classes in an ordinary run, with every output; their failures exit 2, name the option, the time
and the key, and leave no outputs behind."""

import json
import os
import subprocess
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.environ.get("AEROBOX_SOURCE_DIR", os.path.join(HERE, "..", ".."))
AEROBOX = os.environ.get("AEROBOX_BIN", os.path.join(SOURCE, "build", "aerobox"))
WINDOW = os.path.join(SOURCE, "scenes", "window", "scenario.toml")
PARTS = os.path.join(HERE, "user_parts.py")
SE3 = os.path.join(HERE, "se3_controller.py") + ":SE3Control"


def fly(*args, out):
    return subprocess.run([AEROBOX, "fly", WINDOW, "--no-video", "--quiet", "--out", out, *args],
                          capture_output=True, text=True, timeout=300)


def summary(out):
    with open(os.path.join(out, "summary.json")) as file:
        return json.load(file)


class PythonInTheCommand(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.out = os.path.join(self.folder.name, "run")

    def tearDown(self):
        self.folder.cleanup()

    def test_a_python_se3_controller_flies_the_window(self):
        run = fly("--controller", SE3, out=self.out)
        self.assertEqual(run.returncode, 0, run.stderr)
        s = summary(self.out)
        self.assertEqual(s["status"], "reached goal")
        self.assertEqual(s["controller"], SE3)
        self.assertEqual(s["collisions"], 0)
        self.assertGreater(s["min_clearance_m"], 0)
        self.assertLess(s["tracking_rms_m"], 0.06)
        self.assertLess(s["tracking_max_m"], 0.15)
        for name in ("path.csv", "trajectory.csv", "telemetry.csv", "overview.png"):
            self.assertTrue(os.path.exists(os.path.join(self.out, name)), name)

    def test_a_python_controller_flies_a_mission_with_obstacles_found_in_flight(self):
        # the run is aerobox's: its planner, the sensor revealing unknown walls, replanning;
        # the user's controller tracks the reference as it is replaced
        scenario = os.path.join(SOURCE, "scenes", "maze_unknown", "scenario.toml")
        run = subprocess.run([AEROBOX, "fly", scenario, "--no-video", "--quiet", "--out", self.out,
                              "--controller", SE3, "--goal", "5,4,1.5", "--goal", "9,7,1.5"],
                             capture_output=True, text=True, timeout=300)
        self.assertEqual(run.returncode, 0, run.stderr)
        s = summary(self.out)
        self.assertEqual(s["status"], "reached goal")
        self.assertEqual(s["controller"], SE3)
        self.assertEqual(s["collisions"], 0)
        self.assertGreater(s["revealed_boxes"], 0)
        self.assertGreater(len(s["replans"]), 0)
        self.assertEqual(len(s["goals"]), 2)

    def test_a_python_planner_and_trajectory_class_fly(self):
        run = fly("--planner-module", PARTS + ":WindowPlanner", "--trajectory-module",
                  PARTS + ":Smoothstep", out=self.out)
        self.assertEqual(run.returncode, 0, run.stderr)
        s = summary(self.out)
        self.assertEqual(s["status"], "reached goal")
        with open(os.path.join(self.out, "path.csv")) as file:
            self.assertEqual(len(file.read().splitlines()), 1 + 6)  # header + the planner's 6

    def test_a_built_in_controller_by_name(self):
        run = fly("--controller", "se3", out=self.out)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual(summary(self.out)["controller"], "se3")
        run = fly("--controller", "nonesuch", out=self.out)
        self.assertEqual(run.returncode, 2)
        self.assertIn("--controller", run.stderr)

    def test_failures_exit_2_name_the_time_and_leave_nothing(self):
        cases = {
            # the user's traceback, then the message naming the option, the time and the line
            "Raising": ["--controller", "the user's controller broke", "t = 0.3 s",
                        "Traceback (most recent call last)",
                        'raise RuntimeError("the user\'s controller broke")'],
            "ReturnsNaN": ["--controller", "'cmd_motor_thrusts' is not finite", "t = 0.3 s"],
        }
        for name, expected in cases.items():
            with self.subTest(name=name):
                run = fly("--controller", PARTS + ":" + name, out=self.out)
                self.assertEqual(run.returncode, 2, run.stderr)
                for words in expected:
                    self.assertIn(words, run.stderr)
                self.assertFalse(os.path.exists(self.out) and os.listdir(self.out),
                                 os.listdir(self.out) if os.path.exists(self.out) else "")

    def test_a_module_that_does_not_import(self):
        broken = os.path.join(self.folder.name, "broken.py")
        with open(broken, "w") as file:
            file.write("def update(:\n")
        # a syntax error names the user's file and line, not the importer's frames
        run = fly("--controller", broken + ":Controller", out=self.out)
        self.assertIn("SyntaxError: invalid syntax (broken.py, line 1)", run.stderr)
        self.assertNotIn("frozen", run.stderr)
        for spec, words in ((broken + ":Controller", "SyntaxError"),
                            (PARTS + ":NoSuchClass", "has no class 'NoSuchClass'"),
                            (os.path.join(self.folder.name, "absent.py") + ":C", "no such"),
                            ("user_parts.py", "file.py:Class")):
            with self.subTest(spec=spec):
                run = fly("--controller", spec, out=self.out)
                self.assertEqual(run.returncode, 2, run.stderr)
                self.assertIn("--controller", run.stderr)
                self.assertIn(words, run.stderr)
                self.assertFalse(os.path.exists(self.out))


if __name__ == "__main__":
    unittest.main()
