#!/usr/bin/python3
"""A small joint trajectory controller written with rospy and Python actionlib, for the
FollowJointTrajectory block's interoperation test: its control_msgs classes are genpy's, generated
from the same definitions, so a goal that arrives proves the C++ client and it agree on the types.

Serves control_msgs/FollowJointTrajectory on ~action for the joints ~joints (all must be named:
INVALID_JOINTS otherwise), moves them linearly to the last waypoint in its time_from_start (in
real time) and publishes joint_states at 50 Hz. A new goal preempts the running one; cancel stops
the joints where they are. Fault: the joint ~settle_joint ends ~settle_error rad from its goal
(read per goal), which the goal's tolerance turns into GOAL_TOLERANCE_VIOLATED. What each goal
carried is left in parameters ~last_goal/... for the test, and ~md5sum holds the md5 sum of the
action goal type as this side computes it."""
import threading

import actionlib
import rospy
from control_msgs.msg import (FollowJointTrajectoryAction, FollowJointTrajectoryActionGoal,
                              FollowJointTrajectoryFeedback, FollowJointTrajectoryResult)
from sensor_msgs.msg import JointState


class Controller:
    def __init__(self):
        self.joints = rospy.get_param("~joints", ["j1", "j2"])
        self.q = [0.0] * len(self.joints)
        self.lock = threading.Lock()
        self.active = None  # [goal handle, start time, start positions, target, duration, tolerance]
        rospy.set_param("~md5sum", FollowJointTrajectoryActionGoal._md5sum)
        self.states = rospy.Publisher("joint_states", JointState, queue_size=10)
        self.server = actionlib.ActionServer(rospy.get_param("~action", "arm_controller/follow_joint_trajectory"),
                                             FollowJointTrajectoryAction, self.on_goal, self.on_cancel,
                                             auto_start=False)
        self.server.start()
        rospy.Timer(rospy.Duration(0.02), self.tick)

    def on_goal(self, gh):
        goal = gh.get_goal()
        names = list(goal.trajectory.joint_names)
        result = FollowJointTrajectoryResult()
        unknown = [n for n in names if n not in self.joints]
        missing = [n for n in self.joints if n not in names]
        if unknown or missing:
            result.error_code = FollowJointTrajectoryResult.INVALID_JOINTS
            result.error_string = "joints do not match the controller's (%s): unknown %s, missing %s" % (
                ", ".join(self.joints), unknown, missing)
            gh.set_rejected(result, result.error_string)
            return
        if not goal.trajectory.points:
            result.error_code = FollowJointTrajectoryResult.INVALID_GOAL
            gh.set_rejected(result, "empty trajectory")
            return
        last = goal.trajectory.points[-1]
        target = [last.positions[names.index(j)] for j in self.joints]
        tolerance = {t.name: t.position for t in goal.goal_tolerance}
        rospy.set_param("~last_goal", {
            "joint_names": names,
            "duration": last.time_from_start.to_sec(),
            "points": len(goal.trajectory.points),
            "stamp": goal.trajectory.header.stamp.to_sec(),
            "velocities": list(last.velocities),
            "accelerations": list(last.accelerations),
            "path_tolerance": [t.position for t in goal.path_tolerance],
            "goal_tolerance": [t.position for t in goal.goal_tolerance],
            "goal_time_tolerance": goal.goal_time_tolerance.to_sec(),
        })
        settle_joint = rospy.get_param("~settle_joint", "")
        settle_error = rospy.get_param("~settle_error", 0.0)
        with self.lock:
            if self.active:
                self.active[0].set_canceled(FollowJointTrajectoryResult(), "preempted by a new goal")
            gh.set_accepted()
            self.active = [gh, rospy.get_time(), list(self.q), target, last.time_from_start.to_sec(), tolerance,
                           settle_joint, settle_error]

    def on_cancel(self, gh):
        with self.lock:
            if self.active and self.active[0] == gh:
                gh.set_canceled(FollowJointTrajectoryResult(), "canceled: stopped where the joints were")
                self.active = None

    def tick(self, _):
        with self.lock:
            if self.active:
                gh, t0, start, target, duration, tolerance, settle_joint, settle_error = self.active
                u = min(1.0, (rospy.get_time() - t0) / duration) if duration > 0 else 1.0
                self.q = [a + u * (b - a) for a, b in zip(start, target)]
                if settle_joint in self.joints:
                    self.q[self.joints.index(settle_joint)] += u * settle_error
                feedback = FollowJointTrajectoryFeedback()
                feedback.joint_names = self.joints
                feedback.actual.positions = self.q
                gh.publish_feedback(feedback)
                if u >= 1.0:
                    result = FollowJointTrajectoryResult()
                    off = [(abs(q - g), j) for q, g, j in zip(self.q, target, self.joints)
                           if tolerance.get(j, 0.0) > 0 and abs(q - g) > tolerance[j]]
                    if off:
                        error, joint = max(off)
                        result.error_code = FollowJointTrajectoryResult.GOAL_TOLERANCE_VIOLATED
                        result.error_string = "joint '%s' ended %.4f rad from its goal (goal tolerance %.4f rad)" % (
                            joint, error, tolerance[joint])
                        gh.set_aborted(result, result.error_string)
                    else:
                        gh.set_succeeded(result, "reached")
                    self.active = None
            state = JointState(name=self.joints, position=list(self.q), velocity=[0.0] * len(self.joints))
        state.header.stamp = rospy.Time.now()
        self.states.publish(state)


if __name__ == "__main__":
    rospy.init_node("trajectory_controller")
    Controller()
    rospy.spin()
