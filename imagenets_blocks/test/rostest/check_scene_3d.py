#!/usr/bin/python3
"""Checks the scene of launch/nets/scene_3d.launch: frames, the board model and the cloud."""
import statistics
import sys
import unittest

import rospy
import rostest
from visualization_msgs.msg import MarkerArray


class Scene3dTest(unittest.TestCase):
    def test_scene_in_base_link(self):
        deadline = rospy.Time.now() + rospy.Duration(40)
        scene = None
        while rospy.Time.now() < deadline and not rospy.is_shutdown():
            msg = rospy.wait_for_message("/scene/joiner/out/markers", MarkerArray, timeout=40.0)
            if any(m.ns == "clouds" for m in msg.markers):  # the cloud arrives after the first runs
                scene = msg
                break
        self.assertIsNotNone(scene, "no scene with a cloud")
        by_ns = {}
        for m in scene.markers:
            by_ns.setdefault(m.ns, []).append(m)
        self.assertEqual(len(by_ns["frames"]), 3)  # one triad
        self.assertEqual(by_ns["frame_names"][0].text, "left_camera_optical")
        board = by_ns["board"][0]
        self.assertEqual(board.header.frame_id, "base_link")
        # 1.5 m in front of a camera 1.2 m up that looks along base x.
        self.assertAlmostEqual(board.pose.position.x, 1.5, places=6)
        self.assertAlmostEqual(board.pose.position.z, 1.2, places=6)
        cloud = by_ns["clouds"][0]
        self.assertGreater(len(cloud.points), 1000)
        # Cloud points are in the camera frame; the marker's pose puts them in base_link: the
        # farthest surface (the wall) is 3 m along the optical axis.
        self.assertAlmostEqual(cloud.pose.position.z, 1.2, places=6)
        depths = sorted(p.z for p in cloud.points)
        self.assertAlmostEqual(depths[int(0.9 * len(depths))], 3.0, delta=0.1)


if __name__ == "__main__":
    rospy.init_node("check_scene_3d")
    rostest.rosrun("imagenets_blocks", "scene_3d_launch_net", Scene3dTest, sys.argv)
