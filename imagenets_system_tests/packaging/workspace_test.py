#!/usr/bin/env python3
"""The repository as a ROS user gets it: copied into a new workspace's src/, built there with
catkin_make and installed (only the framework and what it needs: no FRIEND package, no Ceres),
then, with the workspace's src/, build/ and devel/ moved away, used from the install space alone:
`imagenets blocks`, `imagenets run` on a shipped net, a nodelet net from a launch file, the
Designer page. The repository may be a git checkout owned by another user (a folder mounted into a
container) or no checkout at all (a source archive): the files copied are those git would list.
Usage: workspace_test.py REPOSITORY."""
import fnmatch
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.request

TIMEOUT = 60.0


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def files_by_git(root):
    """The repository's files as git lists them (tracked, and new ones not ignored), or None where
    git cannot say (no git, no checkout). safe.directory: the checkout may belong to another user."""
    try:
        done = subprocess.run(["git", "-c", "safe.directory=" + root, "-C", root, "ls-files", "-z", "--cached",
                               "--others", "--exclude-standard"], capture_output=True)
    except FileNotFoundError:
        return None
    if done.returncode != 0:
        return None
    files = [f for f in done.stdout.decode().split("\0") if f]
    return [f for f in files if os.path.lexists(os.path.join(root, f))]  # not those deleted in the tree


def files_by_walking(root):
    """The files git would list, without git: every file except .git (a folder, or a file in a
    worktree) and what the .gitignore files exclude (their simple patterns: `/anchored`, `folder/`,
    `*.glob`)."""
    rules = []  # (folder of the .gitignore, pattern, anchored, folders only)
    found = []
    for folder, dirs, files in os.walk(root):
        rel = os.path.relpath(folder, root)
        rel = "" if rel == "." else rel
        if ".gitignore" in files:
            with open(os.path.join(folder, ".gitignore")) as f:
                for line in f:
                    line = line.strip()
                    if line and not line.startswith("#"):
                        rules.append((rel, line.strip("/"), line.startswith("/"), line.endswith("/")))

        def ignored(name, is_dir):
            path = os.path.join(rel, name)
            for base, pattern, anchored, dirs_only in rules:
                if (dirs_only and not is_dir) or not (base == "" or path.startswith(base + "/")):
                    continue
                inside = path[len(base) + 1:] if base else path
                if fnmatch.fnmatch(inside if anchored else name, pattern):
                    return True
            return False

        dirs[:] = sorted(d for d in dirs if d != ".git" and not ignored(d, True))
        found += [os.path.join(rel, f) for f in sorted(files) if f != ".git" and not ignored(f, False)]
    return found


class CopiedFiles(unittest.TestCase):
    def test_without_git_the_same_files_are_copied(self):
        by_git = files_by_git(ROOT)
        if by_git is None:
            self.skipTest("not a git checkout here: nothing to compare the walk with")
        by_walking = files_by_walking(ROOT)
        self.assertEqual(sorted(set(by_walking) - set(by_git)), [], "copied without git, not by git")
        self.assertEqual(sorted(set(by_git) - set(by_walking)), [], "copied by git, not without it")


class InstalledWorkspace(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.ws = tempfile.mkdtemp(prefix="imagenets_ws_")
        src = os.path.join(cls.ws, "src", "imagenets")
        files = files_by_git(ROOT)
        if files is None:
            files = files_by_walking(ROOT)
        for f in files:
            os.makedirs(os.path.dirname(os.path.join(src, f)), exist_ok=True)
            shutil.copy2(os.path.join(ROOT, f), os.path.join(src, f), follow_symlinks=False)
        cls.install = os.path.join(cls.ws, "install")
        env = dict(os.environ, PATH="/usr/bin:/bin")
        build = subprocess.run(
            ["catkin_make", "-C", cls.ws, "install", "--only-pkg-with-deps", "imagenets_tools", "imagenets_designer",
             "-DCMAKE_BUILD_TYPE=Release", "-DCATKIN_ENABLE_TESTING=OFF", "-DPYTHON_EXECUTABLE=/usr/bin/python3",
             "-j%s" % os.environ.get("JOBS", "2")],
            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        cls.build_log = build.stdout
        cls.built = build.returncode == 0
        # Nothing of the sources or the build may be needed any more.
        away = os.path.join(cls.ws, "moved_away")
        os.makedirs(away)
        for d in ["src", "build", "devel"]:
            if os.path.exists(os.path.join(cls.ws, d)):
                os.rename(os.path.join(cls.ws, d), os.path.join(away, d))
        cls.home = os.path.join(cls.ws, "home")
        os.makedirs(cls.home)
        cls.env = {"HOME": cls.home, "PATH": "/usr/bin:/bin", "LANG": "C.UTF-8", "ROS_HOSTNAME": "localhost",
                   "ROS_MASTER_URI": "http://localhost:%d" % free_port(), "ROS_HOME": os.path.join(cls.home, "ros")}
        cls.background = []

    @classmethod
    def tearDownClass(cls):
        for p in reversed(cls.background):
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGINT)
                try:
                    p.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    os.killpg(p.pid, signal.SIGKILL)
        shutil.rmtree(cls.ws, ignore_errors=True)

    def setUp(self):
        self.assertTrue(self.built, "catkin_make install failed:\n" + self.build_log[-6000:])

    def shell(self, command):
        return ["bash", "-c", 'source "$0/setup.bash" && ' + command, self.install]

    def run_in_install(self, command, timeout=TIMEOUT):
        r = subprocess.run(self.shell(command), cwd=self.home, env=self.env, stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, universal_newlines=True, timeout=timeout)
        self.assertEqual(r.returncode, 0, "`%s` failed (exit %d):\n%s" % (command, r.returncode, r.stdout))
        return r.stdout

    def spawn(self, command):
        log = tempfile.TemporaryFile("w+", dir=self.home)
        p = subprocess.Popen(self.shell(command), cwd=self.home, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                             start_new_session=True)
        p.log = log
        self.background.append(p)
        return p

    def log_of(self, p):
        p.log.flush()
        p.log.seek(0)
        return p.log.read()

    def test_install_space_has_no_friend_package(self):
        share = os.listdir(os.path.join(self.install, "share"))
        self.assertIn("imagenets_blocks", share)
        self.assertFalse([p for p in share if p.startswith("friend_")], share)

    def test_blocks_lists_the_block_library(self):
        out = self.run_in_install("imagenets blocks")
        self.assertIn("imagenets/Threshold - Fixed threshold", out)
        self.assertIn("imagenets/SubNet - Runs a net file", out)  # the engine's block, from imagenets_nodelet

    def test_run_a_shipped_net(self):
        out = self.run_in_install("imagenets run $(rospack find imagenets_blocks)/config/nets/threshold_demo.yaml "
                                  "-o out --quiet && ls out")
        self.assertIn("threshold.image.png", out)

    def test_launch_file_net_in_a_nodelet_manager(self):
        launch = self.spawn("roslaunch -p %s imagenets_blocks fig3_3_segmentation_chain.launch rate:=5"
                            % self.env["ROS_MASTER_URI"].rsplit(":", 1)[1])
        deadline = time.monotonic() + TIMEOUT
        while True:
            self.assertIsNone(launch.poll(), "roslaunch exited:\n" + self.log_of(launch))
            r = subprocess.run(self.shell("timeout 10 rostopic echo -n 1 --noarr /segmentation/threshold/out/image"),
                               cwd=self.home, env=self.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               universal_newlines=True)
            if r.returncode == 0 and "height:" in r.stdout:
                break
            self.assertLess(time.monotonic(), deadline, "no image from the launch file's net:\n" + self.log_of(launch))
            time.sleep(1.0)  # polling interval while the master and the manager come up

    def test_designer_serves_its_page(self):
        port = free_port()
        designer = self.spawn("imagenets designer $(rospack find imagenets_blocks)/config/nets/threshold_demo.yaml "
                              "--port %d" % port)
        deadline = time.monotonic() + TIMEOUT
        while True:
            self.assertIsNone(designer.poll(), "the Designer exited:\n" + self.log_of(designer))
            try:
                page = urllib.request.urlopen("http://127.0.0.1:%d/" % port, timeout=5).read().decode()
                break
            except OSError:
                self.assertLess(time.monotonic(), deadline, "no page:\n" + self.log_of(designer))
                time.sleep(0.5)  # polling interval while the server starts
        self.assertIn("main.js", page)
        script = urllib.request.urlopen("http://127.0.0.1:%d/main.js" % port, timeout=5).read()
        self.assertGreater(len(script), 100000)


if __name__ == "__main__":
    ROOT = os.path.abspath(sys.argv.pop(1))
    unittest.main()
