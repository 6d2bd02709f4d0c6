#!/usr/bin/env python3
"""The generic packages name nothing of FRIEND: no FRIEND package and no FRIEND type in their
package.xml, CMake files, sources, nets or launch files. Usage: layering_test.py REPOSITORY."""
import pathlib
import re
import sys
import unittest

GENERIC = ["imagenets", "imagenets_vision", "robot_description", "imagenets_blocks", "imagenets_tools",
           "imagenets_designer", "imagenets_calibration_msgs", "imagenets_calibration"]
FRIEND = re.compile(r"\b(friend_msgs|friend_description|friend_hw_sim|friend_blocks|friend_calibration|"
                    r"MoveJoints\w*|WorldModel(Get|Set)\w*|SetTrueRobot\w*)\b")
TEXT = {".xml", ".txt", ".cmake", ".cpp", ".h", ".hpp", ".py", ".yaml", ".launch", ".test", ".msg", ".srv",
        ".action", ".js", ".jsx", ".mjs", ".json"}
SKIP = {"node_modules", "dist"}


def offending_lines(root):
    for package in GENERIC:
        for path in sorted((root / package).rglob("*")):
            if not path.is_file() or path.suffix not in TEXT or SKIP & set(path.parts):
                continue
            if path.name == "package-lock.json":
                continue
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                found = FRIEND.search(line)
                if found:
                    yield f"{path.relative_to(root)}:{number}: names {found.group(0)}"


class Layering(unittest.TestCase):
    def test_generic_packages_name_nothing_of_friend(self):
        found = list(offending_lines(ROOT))
        self.assertEqual(found, [], "generic packages must not depend on FRIEND's:\n" + "\n".join(found))

    def test_the_check_sees_a_friend_name(self):
        self.assertTrue(FRIEND.search('#include "friend_msgs/MoveJointsAction.h"'))
        self.assertFalse(FRIEND.search("a friendly block"))


if __name__ == "__main__":
    ROOT = pathlib.Path(sys.argv.pop(1)).resolve()
    unittest.main()
