#!/usr/bin/env python3
"""control_msgs, which Debian does not package, comes with the workspace (third_party/control_msgs,
upstream's ROS 1 definitions verbatim): its types and md5 sums are ROS's, and a control_msgs the
user has installed takes precedence over it.

Each case builds a small catkin workspace with catkin_make: the repository's control_msgs and a
client package that finds control_msgs (find_package, as any package of the workspace does),
notes which one it found and prints, from C++, the md5 sum of every control_msgs type.
- Alone: the workspace's copy is built; C++ (gencpp) and Python (genpy) md5 sums equal the
  reference table (control_msgs_md5sums.txt, ROS's published sums).
- Over an underlay where control_msgs is installed (here: upstream's package built and installed
  under another version number, as a user's /opt/ros/noetic or own workspace would hold it): the
  client finds the installed one, the workspace's copy generates nothing, and an earlier build of
  the copy left in the devel space is removed so it cannot shadow the installed one.
Usage: control_msgs_test.py REPOSITORY."""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest

CLIENT_CMAKE = """cmake_minimum_required(VERSION 3.0.2)
project(fjt_client)
find_package(catkin REQUIRED COMPONENTS roscpp control_msgs)
catkin_package()
file(WRITE ${CMAKE_BINARY_DIR}/found_control_msgs.txt "${control_msgs_DIR}\\n${control_msgs_VERSION}\\n")
include_directories(${catkin_INCLUDE_DIRS})
add_executable(md5sums md5sums.cpp)
target_link_libraries(md5sums ${catkin_LIBRARIES})
add_dependencies(md5sums ${catkin_EXPORTED_TARGETS})
install(TARGETS md5sums RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
"""
CLIENT_XML = """<?xml version="1.0"?>
<package format="2"><name>fjt_client</name><version>0.0.1</version><description>client</description>
<maintainer email="dev@imagenets.local">test</maintainer><license>BSD</license>
<buildtool_depend>catkin</buildtool_depend><depend>roscpp</depend><depend>control_msgs</depend></package>
"""

PYTHON_MD5SUMS = """import sys
import control_msgs.msg, control_msgs.srv
for name in sys.argv[1:]:
    short = name.split("/")[1]
    module = control_msgs.srv if short.startswith("Query") else control_msgs.msg
    print(getattr(module, short)._md5sum, name)
"""


def reference():
    table = {}
    for line in (pathlib.Path(__file__).parent / "control_msgs_md5sums.txt").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            md5, name = line.split()
            table[name] = md5
    return table


def client_source(table):
    lines = ["#include <iostream>", "#include <ros/message_traits.h>", "#include <ros/service_traits.h>"]
    body = []
    for name in sorted(table):
        short = name.split("/")[1]
        lines.append("#include <control_msgs/%s.h>" % short)
        traits = "service_traits" if short.startswith("Query") else "message_traits"
        body.append('  std::cout << ros::%s::md5sum<control_msgs::%s>() << " %s\\n";' % (traits, short, name))
    return "\n".join(lines) + "\nint main() {\n" + "\n".join(body) + "\n  return 0;\n}\n"


class ControlMsgs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="control_msgs_")
        cls.table = reference()
        cls.env = dict(os.environ, PATH="/usr/bin:/bin")
        for k in ["ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH", "PYTHONPATH", "LD_LIBRARY_PATH", "PKG_CONFIG_PATH"]:
            cls.env.pop(k, None)  # nothing of the test's own workspace

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def workspace(self, name, version=None, client=True):
        ws = pathlib.Path(self.tmp) / name
        shutil.copytree(ROOT / "third_party" / "control_msgs", ws / "src" / "control_msgs")
        if version:  # the "installed" one: upstream's package as released, under its own version
            xml = ws / "src" / "control_msgs" / "package.xml"
            xml.write_text(xml.read_text().replace("<version>1.5.2</version>", "<version>%s</version>" % version))
        if client:
            (ws / "src" / "fjt_client").mkdir()
            (ws / "src" / "fjt_client" / "CMakeLists.txt").write_text(CLIENT_CMAKE)
            (ws / "src" / "fjt_client" / "package.xml").write_text(CLIENT_XML)
            (ws / "src" / "fjt_client" / "md5sums.cpp").write_text(client_source(self.table))
        return ws

    def catkin_make(self, ws, underlay=None, *args):
        command = "catkin_make -C %s -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release %s -j%s" % (
            ws, " ".join(args), os.environ.get("JOBS", "2"))
        if underlay:
            command = "source %s/setup.bash && %s" % (underlay, command)
        done = subprocess.run(["bash", "-c", command], env=self.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              universal_newlines=True, timeout=1800)
        self.assertEqual(done.returncode, 0, "catkin_make failed:\n" + done.stdout[-6000:])
        return done.stdout

    def in_workspace(self, ws, command):
        done = subprocess.run(["bash", "-c", "source %s/devel/setup.bash && %s" % (ws, command)], env=self.env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=120)
        self.assertEqual(done.returncode, 0, command + ":\n" + done.stdout)
        return done.stdout

    def found(self, ws):
        directory, version = (ws / "build" / "found_control_msgs.txt").read_text().split()
        return pathlib.Path(directory).resolve(), version

    def md5sums(self, ws):
        out = self.in_workspace(ws, str(ws / "devel" / "lib" / "fjt_client" / "md5sums"))
        return dict(reversed(line.split()) for line in out.splitlines())

    def test_1_alone_the_workspaces_copy_is_built_with_ros_md5_sums(self):
        ws = self.workspace("alone")
        self.catkin_make(ws)
        self.assertEqual(self.found(ws), ((ws / "devel" / "share" / "control_msgs" / "cmake").resolve(), "1.5.2"))
        self.assertTrue((ws / "devel" / "include" / "control_msgs" / "FollowJointTrajectoryAction.h").is_file())
        self.assertEqual(len(self.table), 43)
        self.assertEqual(self.md5sums(ws), self.table)  # C++
        script = pathlib.Path(self.tmp) / "md5sums.py"
        script.write_text(PYTHON_MD5SUMS)
        python = self.in_workspace(ws, "/usr/bin/python3 %s %s" % (script, " ".join(sorted(self.table))))
        self.assertEqual(dict(reversed(line.split()) for line in python.splitlines()), self.table)  # genpy

    def test_2_an_installed_control_msgs_takes_precedence(self):
        installed = self.workspace("installed", version="1.5.99", client=False)
        self.catkin_make(installed, None, "install")
        underlay = installed / "install"
        self.assertTrue((underlay / "share" / "control_msgs" / "cmake" / "control_msgsConfig.cmake").is_file())

        # A new workspace over it: the client finds the installed control_msgs.
        ws = self.workspace("overlay")
        log = self.catkin_make(ws, underlay)
        self.assertIn("control_msgs: using the installed one in %s" % underlay.resolve(), log)
        self.assertEqual(self.found(ws), ((underlay / "share" / "control_msgs" / "cmake").resolve(), "1.5.99"))
        self.assertFalse((ws / "devel" / "include" / "control_msgs").exists())
        self.assertFalse((ws / "devel" / "share" / "control_msgs").exists())
        self.assertEqual(self.md5sums(ws), self.table)

        # The workspace built alone first (its copy in devel), then the user installs control_msgs:
        # the next build uses the installed one and clears the copy's output.
        alone = pathlib.Path(self.tmp) / "alone"
        self.assertTrue((alone / "devel" / "include" / "control_msgs").exists(), "test_1 builds it first")
        log = self.catkin_make(alone, underlay, "--force-cmake")
        self.assertIn("control_msgs: using the installed one", log)
        self.assertEqual(self.found(alone)[1], "1.5.99")
        self.assertFalse((alone / "devel" / "include" / "control_msgs").exists())
        self.assertFalse((alone / "devel" / "share" / "control_msgs").exists())
        self.assertEqual(self.md5sums(alone), self.table)


if __name__ == "__main__":
    ROOT = pathlib.Path(sys.argv.pop(1)).resolve()
    unittest.main()
