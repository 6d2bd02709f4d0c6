#!/usr/bin/env python3
"""ROS packaging conventions of every package: catkin_lint reports nothing, and every rosdep key
the package.xml files name resolves to Debian packages (scripts/install-deps --list), so that the
package.xml files are the one list of dependencies; and what scripts/install-deps does for a user
who is not root: with every package installed, nothing (no sudo needed); with a package missing
and no way to install it, the exact apt-get line, and `make test` / `make demo` stop before
building, as they do when HOME cannot be written. Usage: packaging_test.py REPOSITORY."""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest

NOBODY = 65534
ABSENT = "imagenets-absent-test-package"  # a Debian package name that exists nowhere


class Packaging(unittest.TestCase):
    def test_catkin_lint_reports_no_error_and_no_warning(self):
        done = subprocess.run(["catkin_lint", "-W1", str(ROOT)], capture_output=True, text=True, timeout=600)
        # Lines starting "catkin_lint: " are its own notes (e.g. no rosdep database offline).
        problems = [line for line in (done.stdout + done.stderr).splitlines()
                    if line.strip() and not line.startswith("catkin_lint: ")]
        self.assertEqual(problems, [], "catkin_lint -W1:\n" + "\n".join(problems))
        self.assertEqual(done.returncode, 0)

    def test_every_rosdep_key_resolves_to_debian_packages(self):
        done = subprocess.run([str(ROOT / "scripts" / "install-deps"), "--list"], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        packages = done.stdout.split()
        for expected in ["libceres-dev", "libapriltag-dev", "liborocos-kdl-dev", "nlohmann-json3-dev", "chromium",
                         "catkin-lint", "ros-stereo-image-proc"]:
            self.assertIn(expected, packages)

    def test_a_key_without_debian_packages_is_named(self):
        copy = pathlib.Path(self.tmp) / "ws"
        (copy / "scripts").mkdir(parents=True)
        (copy / "demo_pkg").mkdir()
        (copy / "demo_pkg" / "package.xml").write_text(
            "<package format='3'><name>demo_pkg</name><depend>no_such_key</depend></package>")
        for name in ["install-deps", "rosdep-debian.yaml"]:
            (copy / "scripts" / name).write_bytes((ROOT / "scripts" / name).read_bytes())
        (copy / "scripts" / "install-deps").chmod(0o755)
        done = subprocess.run([str(copy / "scripts" / "install-deps"), "--list"], capture_output=True, text=True)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("no_such_key (demo_pkg/package.xml)", done.stderr)

    def setUp(self):
        import tempfile
        self._dir = tempfile.TemporaryDirectory()
        self.tmp = self._dir.name

    def tearDown(self):
        self._dir.cleanup()


class MakeAsAUserWhoIsNotRoot(unittest.TestCase):
    """A workspace of one package whose rosdep key resolves to PACKAGE (scripts/rosdep-debian.yaml
    plus one line), with the real Makefile and install-deps, run by a user who is not root (as root:
    user nobody, who owns the copy)."""

    def setUp(self):
        self._dir = tempfile.TemporaryDirectory()
        self.ws = pathlib.Path(self._dir.name) / "ws"
        self.prefix = []
        if os.geteuid() == 0:
            self.prefix = [shutil.which("setpriv", path="/usr/bin:/bin"), "--reuid=%d" % NOBODY, "--regid=%d" % NOBODY,
                           "--clear-groups"]
        elif shutil.which("sudo") and subprocess.run(["sudo", "-n", "true"], capture_output=True).returncode == 0:
            self.skipTest("this user can install packages with sudo: the test would run apt-get")

    def tearDown(self):
        self._dir.cleanup()

    def workspace(self, package, optional=None):
        (self.ws / "scripts").mkdir(parents=True)
        (self.ws / "demo_pkg").mkdir()
        (self.ws / "demo_pkg" / "package.xml").write_text(
            "<package format='3'><name>demo_pkg</name><depend>test_key</depend></package>")
        table = (ROOT / "scripts" / "rosdep-debian.yaml").read_text() + "test_key: [%s]\n" % package
        (self.ws / "scripts" / "rosdep-debian.yaml").write_text(table)
        script = (ROOT / "scripts" / "install-deps").read_text()
        if optional:
            self.assertIn("\noptional=(ccache)\n", script)
            script = script.replace("\noptional=(ccache)\n", "\noptional=(ccache %s)\n" % optional)
        (self.ws / "scripts" / "install-deps").write_text(script)
        (self.ws / "scripts" / "install-deps").chmod(0o755)
        shutil.copy(ROOT / "Makefile", self.ws / "Makefile")
        for path in [self.ws.parent, *self.ws.parent.rglob("*")]:
            if self.prefix:
                os.chown(path, NOBODY, NOBODY)
        return self.ws

    def run_as_user(self, argv, path=None, home=None):
        env = {"PATH": path or "/usr/bin:/bin", "LANG": "C.UTF-8", "HOME": home or str(self.ws)}
        return subprocess.run(self.prefix + argv, cwd=self.ws, env=env, capture_output=True, text=True, timeout=300)

    def assert_stops_with_the_apt_line(self, done, packages):
        self.assertNotEqual(done.returncode, 0, done.stdout + done.stderr)
        self.assertIn("\n  apt-get update && apt-get install -y --no-install-recommends %s\n" % packages, done.stderr)
        self.assertIn("install-deps: as root, run", done.stderr)

    def test_make_test_and_make_demo_stop_before_building(self):
        self.workspace(ABSENT)
        for target in ["test", "demo"]:
            done = self.run_as_user(["make", target])
            self.assert_stops_with_the_apt_line(done, ABSENT)
            self.assertIn("install-deps: cannot install the 1 missing Debian package(s): ", done.stderr)
            self.assertFalse((self.ws / "build").exists(), "make %s went on to configure" % target)
            self.assertFalse((self.ws / "devel").exists(), "make %s went on to configure" % target)

    def test_without_sudo_the_message_says_so(self):
        self.workspace(ABSENT)
        tools = self.ws.parent / "tools"  # a PATH with what install-deps runs, and no sudo
        tools.mkdir()
        for tool in ["bash", "dirname", "dpkg-query", "id"]:
            (tools / tool).symlink_to(shutil.which(tool, path="/usr/bin:/bin"))
        done = self.run_as_user(["scripts/install-deps"], path=str(tools))
        self.assertEqual(done.returncode, 1, done.stdout + done.stderr)
        self.assert_stops_with_the_apt_line(done, ABSENT)
        self.assertIn("is not root and there is no sudo", done.stderr)

    def test_a_sudo_that_refuses_is_no_way_either(self):
        self.workspace(ABSENT)
        tools = self.ws.parent / "tools"
        tools.mkdir()
        (tools / "sudo").write_text("#!/bin/sh\necho \"$(id -un) is not in the sudoers file.\" >&2\nexit 1\n")
        (tools / "sudo").chmod(0o755)
        done = self.run_as_user(["scripts/install-deps"], path="%s:/usr/bin:/bin" % tools)
        self.assertEqual(done.returncode, 1, done.stdout + done.stderr)
        self.assert_stops_with_the_apt_line(done, ABSENT)
        self.assertIn("sudo needs a password but there is no terminal to ask", done.stderr)

    def test_with_everything_installed_nothing_is_needed(self):
        self.workspace("dpkg")  # installed on every Debian
        if subprocess.run(["dpkg-query", "-W", "ccache"], capture_output=True).returncode != 0:
            self.skipTest("ccache is not installed here (an optional package install-deps adds)")
        done = self.run_as_user(["make", "deps"])
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        self.assertEqual(done.stderr, "")
        self.assertNotIn("install-deps", done.stdout)

    def test_a_home_that_cannot_be_written_stops_before_building(self):
        self.workspace("dpkg")
        if subprocess.run(["dpkg-query", "-W", "ccache"], capture_output=True).returncode != 0:
            self.skipTest("ccache is not installed here (an optional package install-deps adds)")
        for home in ["/nonexistent", "/proc"]:
            done = self.run_as_user(["make", "test"], home=home)
            self.assertNotEqual(done.returncode, 0, done.stdout + done.stderr)
            self.assertIn("make: HOME (%s) is not a writable folder: npm, ccache and ROS keep their caches" % home,
                          done.stderr)
            self.assertIn("HOME=$(mktemp -d) make test", done.stderr)
            self.assertFalse((self.ws / "build").exists(), "make test went on to configure")

    def test_only_an_optional_package_missing_is_a_note(self):
        self.workspace(ABSENT, optional=ABSENT)
        done = self.run_as_user(["make", "deps"])
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        self.assertIn("not installed: %s (optional, so the build goes on" % ABSENT, done.stderr)
        self.assertIn("apt-get install -y --no-install-recommends %s" % ABSENT, done.stderr)


if __name__ == "__main__":
    ROOT = pathlib.Path(sys.argv.pop(1)).resolve()
    unittest.main()
