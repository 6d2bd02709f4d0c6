#!/usr/bin/env python3
"""ROS packaging conventions of every package: catkin_lint reports nothing, and every rosdep key
the package.xml files name resolves to Debian packages (scripts/install-deps --list), so that the
package.xml files are the one list of dependencies. Usage: packaging_test.py REPOSITORY."""
import pathlib
import subprocess
import sys
import unittest


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


if __name__ == "__main__":
    ROOT = pathlib.Path(sys.argv.pop(1)).resolve()
    unittest.main()
