#!/usr/bin/python3
"""Runs `imagenets repeatability` in small against the running simulator and checks what it writes."""
import csv
import os
import subprocess
import unittest

import roslib.packages
import rospy
import rostest


class RepeatabilityTest(unittest.TestCase):
    def test_small_study_writes_csv_table_and_scatter(self):
        out = rospy.get_param("~output_dir")
        tool = roslib.packages.find_node("friend_calibration", "imagenets-repeatability")[0]
        done = subprocess.run([tool, "--runs", "3", "--redundancy", "1,3", "--method", "paper",
                               "--real-speed-runs", "1", "--output-dir", out],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=100)
        self.assertEqual(done.returncode, 0, done.stdout)

        with open(os.path.join(out, "runs.csv")) as f:
            runs = list(csv.DictReader(f))
        self.assertEqual(len(runs), 2 * (3 + 1), runs)
        self.assertTrue(all(r["success"] == "1" for r in runs), [r["message"] for r in runs])
        scales = sorted({float(r["time_scale"]) for r in runs})
        self.assertEqual(scales, [1.0, 50.0])
        for r in runs:  # the paper's method: millimetres from the truth, never centimetres
            self.assertLess(float(r["error_mm"]), 10.0, r)
        # One run per redundancy at real speed (time_scale 1.0, checked above); their durations are
        # not compared with the fast ones: on a loaded machine computing, not motion, dominates both
        # (that comparison failed under load in the rostest sweep; speed belongs in bench/).
        for n in ("1", "3"):
            self.assertEqual(sum(1 for r in runs if r["redundancy"] == n and r["time_scale"] == "1.0"), 1, runs)

        with open(os.path.join(out, "table.md")) as f:
            table = f.read()
        rows = [line.split("|") for line in table.splitlines() if line.startswith("| paper |")]
        self.assertEqual([(r[2].strip(), r[3].strip()) for r in rows], [("1", "3"), ("3", "3")], table)
        with open(os.path.join(out, "scatter_paper.png"), "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertEqual(rospy.get_param("/friend_sim/time_scale"), 50.0)


if __name__ == "__main__":
    rospy.init_node("check_repeatability")
    rostest.rosrun("friend_calibration", "repeatability_study", RepeatabilityTest)
