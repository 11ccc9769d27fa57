#!/usr/bin/env python3
"""report.html in a real browser: Debian's chromium, headless, opens the page of a flight from
file:// and runs the page's self-test (report.html#selftest=T), read back with --dump-dom.

- the page loads with no console error and no network request;
- the 3-D canvas is not blank (pixel variance) and shows the map (the boxes' colours where their
  centres project);
- the slider at a time puts the vehicle where telemetry.csv says;
- a 25 s flight's page stays under 3 MB;
- the page of a collision shows the failure and marks where it happened;
- a sweep writes one page of its own;
- several vehicles: every one drawn where its telemetry.csv says, the charts of the one chosen.

Usage: report_test.py AEROBOX_BINARY SOURCE_DIR"""
import csv
import html
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

AEROBOX, TOP = sys.argv[1], sys.argv[2]
CHROMIUM = ["chromium", "--headless", "--no-sandbox", "--enable-unsafe-swiftshader",
            "--window-size=1280,900", "--virtual-time-budget=8000", "--disable-dev-shm-usage",
            "--enable-logging=stderr", "--v=0", "--no-first-run", "--disable-extensions",
            "--disable-sync", "--disable-background-networking", "--disable-component-update"]


def fly(out, *args):
    command = [AEROBOX, "fly", *args, "--no-video", "--quiet", "--out", out]
    return subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          check=False)


def selftest(page, t, profile, extra=""):
    """The page's self-test at time t (`extra`: more of the address's fragment), and chromium's
    console lines."""
    done = subprocess.run(
        CHROMIUM + [f"--user-data-dir={profile}", "--dump-dom", f"file://{page}#selftest={t}{extra}"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=120, check=False)
    found = re.search(r'<pre id="selftest">([^<]*)</pre>', done.stdout)
    if not found:
        raise AssertionError(f"no self-test result in the page; chromium said:\n{done.stderr[-3000:]}")
    console = [line for line in done.stderr.splitlines() if "CONSOLE" in line]
    return json.loads(html.unescape(found.group(1))), console


def telemetry_at(path, t):
    """Position from telemetry.csv at time t, linearly between its rows."""
    with open(path, encoding="utf-8") as f:
        rows = [(float(r["t"]), float(r["x"]), float(r["y"]), float(r["z"])) for r in csv.DictReader(f)]
    for a, b in zip(rows, rows[1:]):
        if a[0] <= t <= b[0]:
            u = 0.0 if b[0] == a[0] else (t - a[0]) / (b[0] - a[0])
            return [a[k] + u * (b[k] - a[k]) for k in (1, 2, 3)]
    return list(rows[-1][1:])


class Report(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.TemporaryDirectory()
        cls.profile = os.path.join(cls.work.name, "profile")
        # the window at 1 m/s: a flight of about 25 s
        cls.slow = os.path.join(cls.work.name, "slow")
        done = fly(cls.slow, os.path.join(TOP, "scenes/window/scenario.toml"), "--max-speed", "1.0")
        assert done.returncode == 0, done.stderr
        # the forest in a 4 m/s wind: seed 1 hits block_14
        cls.crash = os.path.join(cls.work.name, "crash")
        done = fly(cls.crash, os.path.join(TOP, "scenes/forest/scenario.toml"), "--wind", "4,0,0",
                   "--turbulence", "1.0", "--seed", "1")
        assert done.returncode == 5, (done.returncode, done.stdout, done.stderr)

        # walls found in flight (replans), and wind
        cls.unknown = os.path.join(cls.work.name, "unknown")
        done = fly(cls.unknown, os.path.join(TOP, "scenes/maze_unknown/scenario.toml"))
        assert done.returncode == 0, done.stderr
        # pillars found by a depth camera: the occupancy map in time
        cls.depth = os.path.join(cls.work.name, "depth")
        done = fly(cls.depth, os.path.join(TOP, "scenes/depth_forest/scenario.toml"))
        assert done.returncode == 0, done.stderr
        cls.windy = os.path.join(cls.work.name, "windy")
        done = fly(cls.windy, os.path.join(TOP, "scenes/windy_window/scenario.toml"))
        assert done.returncode == 0, done.stderr
        # eight vehicles in one world: one page for all
        cls.swarm = os.path.join(cls.work.name, "swarm")
        done = fly(cls.swarm, os.path.join(TOP, "scenes/swarm_swap/scenario.toml"))
        assert done.returncode == 0, done.stderr
        # a sweep of two runs: its own page
        cls.sweep = os.path.join(cls.work.name, "sweep")
        sweep_file = os.path.join(cls.work.name, "two.toml")
        with open(sweep_file, "w", encoding="utf-8") as f:
            f.write(f'scenarios = ["{TOP}/scenes/window/scenario.toml"]\nseeds = 2\n'
                    '[grid]\n"trajectory.max_speed" = [3.0]\n')
        done = subprocess.run([AEROBOX, "sweep", sweep_file, "--out", cls.sweep, "--quiet"],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=False)
        assert done.returncode == 0, done.stderr

    @classmethod
    def tearDownClass(cls):
        cls.work.cleanup()

    def assert_clean(self, result, console):
        self.assertEqual(result["errors"], [], "errors in the page")
        self.assertEqual(result["resources"], [], "the page fetched something")
        bad = [line for line in console
               if re.search(r"Uncaught|Error|Failed to load|net::ERR", line)
               and "GL Driver Message" not in line]
        self.assertEqual(bad, [], "console errors")

    def test_page_loads_draws_the_map_and_follows_the_slider(self):
        page = os.path.join(self.slow, "report.html")
        with open(os.path.join(self.slow, "summary.json"), encoding="utf-8") as f:
            summary = json.load(f)
        self.assertGreater(summary["flight_time_s"], 20.0)
        size = os.path.getsize(page)
        self.assertLess(size, 3 * 1024 * 1024, f"{size} bytes")
        with open(page, encoding="utf-8") as f:
            text = f.read()
        self.assertNotRegex(text, r'<script[^>]+src=', "a script the page would fetch")
        for t in (0.0, 7.3, 18.25):
            result, console = selftest(page, t, self.profile)
            self.assert_clean(result, console)
            self.assertAlmostEqual(result["time"], t, delta=0.01)
            self.assertGreater(result["variance"], 100.0, "a blank canvas")
            self.assertEqual(result["boxes"], 8)
            self.assertGreaterEqual(result["boxes_in_view"], 6)
            self.assertGreaterEqual(result["boxes_seen"], 0.9 * result["boxes_in_view"])
            expected = telemetry_at(os.path.join(self.slow, "telemetry.csv"), t)
            for got, want in zip(result["vehicle"], expected):
                self.assertAlmostEqual(got, want, delta=0.01, msg=f"at t = {t} s")
            self.assertEqual(result["status"], "reached goal")
            self.assertEqual(result["failure_text"], "")
            self.assertEqual(result["charts"], 7)

    def test_a_collision_shows_the_failure_and_where(self):
        page = os.path.join(self.crash, "report.html")
        with open(os.path.join(self.crash, "summary.json"), encoding="utf-8") as f:
            summary = json.load(f)
        result, console = selftest(page, summary["flight_time_s"], self.profile)
        self.assert_clean(result, console)
        self.assertEqual(result["status"], "collision")
        self.assertIn("collision with block_14", result["failure_text"])
        self.assertIsNotNone(result["failure_marker"])
        # the marker stands where the flight ended, and the vehicle is there at that time
        end = telemetry_at(os.path.join(self.crash, "telemetry.csv"), summary["flight_time_s"])
        for got, want in zip(result["failure_marker"], end):
            self.assertAlmostEqual(got, want, delta=0.05)
        for got, want in zip(result["vehicle"], end):
            self.assertAlmostEqual(got, want, delta=0.05)


    def test_revealed_boxes_replans_and_wind_show_in_time(self):
        with open(os.path.join(self.unknown, "summary.json"), encoding="utf-8") as f:
            summary = json.load(f)
        never = summary["unknown_boxes"] - summary["revealed_boxes"]
        page = os.path.join(self.unknown, "report.html")
        start, console = selftest(page, 0, self.profile)
        self.assert_clean(start, console)
        end, console = selftest(page, summary["flight_time_s"], self.profile)
        self.assert_clean(end, console)
        # faint until revealed: more at the start than at the end, where only the never seen are
        self.assertGreater(start["faint_boxes"], end["faint_boxes"])
        self.assertEqual(end["faint_boxes"], never)
        self.assertEqual(start["abandoned_shown"], 0)
        self.assertEqual(end["abandoned_shown"], len(summary["replans"]))
        # the trajectory drawn is the one in force: the planned one first, the last one at the end
        replaced = [r for r in summary["replans"]
                    if r["outcome"].startswith("replanned") or r["outcome"].startswith("braking")]
        self.assertEqual(start["trajectory_stages"], 1 + len(replaced))
        self.assertEqual(start["trajectory_stage"], 0)
        self.assertEqual(end["trajectory_stage"], len(replaced))
        windy, console = selftest(os.path.join(self.windy, "report.html"), 3.0, self.profile)
        self.assert_clean(windy, console)
        self.assertTrue(windy["wind_arrow"])
        self.assertFalse(end["wind_arrow"])  # still air in the maze

    def test_a_depth_camera_s_occupied_cells_show_as_known_then(self):
        with open(os.path.join(self.depth, "summary.json"), encoding="utf-8") as f:
            summary = json.load(f)
        page = os.path.join(self.depth, "report.html")
        shown = []
        for t in (0.5, 0.5 * summary["flight_time_s"], summary["flight_time_s"]):
            result, console = selftest(page, t, self.profile)
            self.assert_clean(result, console)
            # the last snapshot (one a second) before the slider's time
            self.assertLessEqual(result["occupied_snapshot_t"], t)
            self.assertGreater(result["occupied_snapshot_t"], t - 1.1)
            shown.append(result["occupied_boxes"])
        # the map grows as the pillars are seen
        self.assertLess(shown[0], shown[2])
        self.assertGreater(shown[2], 50)
        # a flight without a depth camera has none
        result, _ = selftest(os.path.join(self.slow, "report.html"), 5.0, self.profile)
        self.assertEqual(result["occupied_boxes"], 0)

    def test_several_vehicles_each_where_its_telemetry_says_and_charts_per_vehicle(self):
        page = os.path.join(self.swarm, "report.html")
        with open(os.path.join(self.swarm, "summary.json"), encoding="utf-8") as f:
            names = [v["name"] for v in json.load(f)["vehicles"]]
        self.assertEqual(len(names), 8)
        for t in (0.0, 1.1):
            result, console = selftest(page, t, self.profile)
            self.assert_clean(result, console)
            self.assertEqual(result["vehicles"], 8)
            self.assertGreater(result["variance"], 100.0, "a blank canvas")
            for name, got in zip(names, result["vehicle_positions"]):
                expected = telemetry_at(os.path.join(self.swarm, name, "telemetry.csv"), t)
                for g, w in zip(got, expected):
                    self.assertAlmostEqual(g, w, delta=0.01, msg=f"{name} at t = {t} s")
            self.assertEqual(result["charts_of"], names[0])
        # the charts of the third vehicle: its x at the end
        result, console = selftest(page, 1.0, self.profile, "&vehicle=2")
        self.assert_clean(result, console)
        self.assertEqual(result["charts_of"], names[2])
        with open(os.path.join(self.swarm, names[2], "telemetry.csv"), encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        self.assertAlmostEqual(result["charts_first_x"]["y"], float(rows[-1]["x"]), delta=1e-3)

    def test_a_sweep_has_one_page(self):
        result, console = selftest(os.path.join(self.sweep, "report.html"), 0, self.profile)
        self.assert_clean(result, console)
        self.assertEqual(result["rows"], 1)  # one cell of two seeds
        self.assertEqual(result["charts"], 2)
        # and the runs have no page of their own unless [keep] report asks
        self.assertEqual([f for _, _, files in os.walk(os.path.join(self.sweep, "runs"))
                          for f in files if f == "report.html"], [])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
