#!/usr/bin/python3
"""Waits for one cloud from the stereo launch net and checks the depths of known surfaces."""
import statistics
import sys
import unittest

import rospy
import rostest
from sensor_msgs import point_cloud2
from sensor_msgs.msg import PointCloud2


class StereoCloudTest(unittest.TestCase):
    def test_depths_of_board_and_wall(self):
        topic = rospy.get_param("~topic", "/stereo/points2")
        cloud = rospy.wait_for_message(topic, PointCloud2, timeout=40.0)
        self.assertEqual(cloud.header.frame_id, "left_camera_optical")
        self.assertEqual((cloud.width, cloud.height), (640, 480))  # organised, one point per pixel
        names = [f.name for f in cloud.fields]
        self.assertIn("rgb", names)
        # Sample pixels: board centre region and wall region right of the board.
        board = [(u, v) for u in range(250, 390, 7) for v in range(170, 310, 7)]
        wall = [(u, v) for u in range(520, 630, 7) for v in range(20, 460, 7)]
        for uvs, depth, name in ((board, 1.5, "board"), (wall, 3.0, "wall")):
            zs = [p[2] for p in point_cloud2.read_points(cloud, ("x", "y", "z"), skip_nans=True, uvs=uvs)]
            self.assertGreater(len(zs), 0.8 * len(uvs), "%s: too few valid points" % name)
            self.assertAlmostEqual(statistics.median(zs), depth, delta=0.02 * depth, msg=name)


if __name__ == "__main__":
    rospy.init_node("check_stereo_cloud")
    rostest.rosrun("imagenets_blocks", "stereo_point_cloud_launch_net", StereoCloudTest, sys.argv)
