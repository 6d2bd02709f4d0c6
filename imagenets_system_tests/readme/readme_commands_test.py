#!/usr/bin/env python3
"""The commands the README and docs/launch.md give, run exactly as written, as a new user runs them:
in a fresh shell at the repository root whose only preparation is `source devel/setup.bash`, with a
clean environment (no variable of the build or of ctest leaks in). Each command must still appear
verbatim in the document named beside it, so the documents and this test cannot drift apart.

Usage: readme_commands_test.py REPOSITORY DEVEL_SPACE   (run by ctest as `readme_commands`)
"""
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest

REPO = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.getcwd()
DEVEL = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else os.path.join(REPO, "devel")
TIMEOUT = 120.0  # seconds for anything to appear; generous, the machine may be loaded


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


class ReadmeCommands(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.home = tempfile.mkdtemp(prefix="readme_commands_")
        cls.env = {
            "HOME": cls.home,
            "ROS_HOME": os.path.join(cls.home, "ros"),
            "PATH": "/usr/bin:/bin",
            "LANG": "C.UTF-8",
            "ROS_HOSTNAME": "localhost",
            "ROS_MASTER_URI": "http://localhost:%d" % free_port(),
        }
        cls.background = []

    @classmethod
    def tearDownClass(cls):
        for p in reversed(cls.background):
            cls.stop(p)
            p.log.close()
        shutil.rmtree(cls.home, ignore_errors=True)

    # --- helpers -------------------------------------------------------------------------------
    def documented(self, doc, command):
        with open(os.path.join(REPO, doc)) as f:
            text = f.read()
        self.assertTrue(command in text, "%s no longer gives `%s`: update this test with it" % (doc, command))

    def script(self, command):
        # `source` runs catkin's setup in this very shell, as a user types it.
        return ["bash", "-c", 'source "$0/setup.bash" && ' + command, DEVEL]

    def run_command(self, doc, command, timeout=TIMEOUT):
        self.documented(doc, command)
        r = subprocess.run(self.script(command), cwd=REPO, env=self.env, stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, universal_newlines=True, timeout=timeout)
        self.assertEqual(r.returncode, 0, "`%s` failed (exit %d):\n%s" % (command, r.returncode, r.stdout))
        return r.stdout

    def start(self, doc, command):
        self.documented(doc, command)
        return self.spawn(command)

    def spawn(self, command):
        log = open(os.path.join(self.home, "bg%d.log" % len(self.background)), "w+")
        p = subprocess.Popen(self.script(command), cwd=REPO, env=self.env, stdout=log,
                             stderr=subprocess.STDOUT, start_new_session=True)
        p.log = log
        self.background.append(p)
        return p

    @staticmethod
    def stop(p):
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGINT)
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()

    def output_of(self, p):
        p.log.flush()
        p.log.seek(0)
        return p.log.read()

    def wait_for_service(self, name, p):
        deadline = time.monotonic() + TIMEOUT
        while time.monotonic() < deadline:
            self.assertIsNone(p.poll(), "exited before offering %s:\n%s" % (name, self.output_of(p)))
            r = subprocess.run(self.script("rosservice list"), cwd=REPO, env=self.env,
                               stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, universal_newlines=True)
            if name in r.stdout.split():
                return
            time.sleep(0.5)  # polling interval, not a synchronisation
        self.fail("no service %s after %.0f s:\n%s" % (name, TIMEOUT, self.output_of(p)))

    def ensure_master(self):
        if not any(getattr(p, "is_master", False) for p in self.background):
            master = self.spawn("roscore -p %s" % self.env["ROS_MASTER_URI"].rsplit(":", 1)[1])
            master.is_master = True
            deadline = time.monotonic() + TIMEOUT
            while subprocess.run(self.script("rostopic list"), cwd=REPO, env=self.env,
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode != 0:
                self.assertLess(time.monotonic(), deadline, "roscore did not start")
                time.sleep(0.5)

    # --- the commands --------------------------------------------------------------------------
    def test_rosrun_tool(self):
        out = self.run_command("README.md", "rosrun imagenets_tools imagenets blocks")
        self.assertIn("imagenets/Threshold - Fixed threshold", out)

    def test_tool_on_path_lists_its_commands(self):
        out = self.run_command("README.md", "imagenets --help")
        self.assertIn("usage: imagenets COMMAND", out)
        self.assertIn("  run ", out)

    def test_tool_on_path_runs_a_net(self):
        out_dir = os.path.join(REPO, "out/stereo")
        shutil.rmtree(out_dir, ignore_errors=True)
        self.run_command("README.md", "imagenets run imagenets_blocks/config/nets/stereo_point_cloud.yaml -o out/stereo")
        written = os.listdir(out_dir)
        self.assertTrue(any(f.endswith(".ply") for f in written), "no point cloud written: %s" % written)
        self.assertTrue(any(f.endswith(".png") for f in written), "no disparity picture written: %s" % written)

    def test_rosrun_friend_urdf(self):
        out = self.run_command("friend_description/config/robot.yaml", "rosrun friend_hw_sim friend_urdf")
        self.assertIn('<robot name="friend"', out)

    def test_message_types_are_named_by_their_packages(self):
        # The calibration's types and FRIEND's each in their own package: the tools find them by name.
        out = self.run_command("README.md", "rossrv show imagenets_calibration_msgs/Calibrate")
        self.assertIn("int32 redundancy", out)
        out = self.run_command("README.md", "rosmsg show friend_msgs/MoveJointsGoal")
        self.assertIn("float64[] positions", out)

    def test_rosrun_node_serves(self):
        self.ensure_master()
        node = self.start("README.md", "rosrun friend_hw_sim friend_sim_node")
        self.wait_for_service("/friend_sim/set_true_robot", node)
        self.stop(node)
        self.assertEqual(node.returncode, 0, self.output_of(node))

    def test_segmentation_chain_and_live_threshold(self):
        self.ensure_master()
        launch = self.start("README.md", "roslaunch imagenets_blocks fig3_3_segmentation_chain.launch")
        self.wait_for_service("/segmentation/threshold/set_parameters", launch)
        command = "rosrun dynamic_reconfigure dynparam set /segmentation/threshold threshold 72"
        self.documented("docs/launch.md", command)
        self.run_command("README.md", command)
        value = subprocess.run(self.script("rosparam get /segmentation/threshold/threshold"), cwd=REPO,
                               env=self.env, stdout=subprocess.PIPE, universal_newlines=True).stdout.strip()
        self.assertEqual(value, "72")
        self.stop(launch)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
