#!/usr/bin/env python3
"""A launch-file net split over two machines gives what it gives in one manager.

Two network namespaces stand for two hosts (scripts/two-hosts): "robot" (10.77.0.1) and
"workstation" (10.77.0.2), joined by a veth pair. One ROS master runs on the robot. The Fig. 3.4
net (imagenets_blocks/launch/fig3_4_parallel_subnets.launch: a stereo pair of file sources, each image through
the Fig. 3.3 segmentation sub-net in an imagenets/SubNet nodelet) runs

  1. in one nodelet manager on the robot (the reference), then
  2. split: the stereo acquisition in a manager on the robot, the two sub-nets in a manager on the
     workstation, two roslaunch instances each with the ROS_IP of its host (as on real machines;
     there is no ssh for roslaunch <machine> tags here).

Both runs' binary images must be equal, the robot's camera topics must be published on the robot
and read on the workstation, and the images must have crossed the veth (the workstation's
interface received at least one image's bytes).

Usage: split_net_test.py REPOSITORY DEVEL_SPACE       (run by ctest as `nets_across_machines`)
       split_net_test.py --listen TIMEOUT TOPIC...    (inside a namespace: print what arrives, JSON)
Needs root where network namespaces work. Before anything else it asks `scripts/two-hosts check`
whether two namespaces joined by a veth pair can be made here; where they cannot (not root, an
unprivileged container, a chroot) it prints SKIPPED with the reason and exits 77, which ctest
reports as skipped (SKIP_RETURN_CODE), never as passed. With IMAGENETS_TESTS_NO_SKIP=1 in the
environment it fails instead (for machines that must run everything, like CI).
"""
import hashlib
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

ROBOT_IP, WORKSTATION_IP = "10.77.0.1", "10.77.0.2"  # scripts/two-hosts
MASTER_URI = "http://%s:11311" % ROBOT_IP  # the namespaces are private: the default port cannot clash
SKIP_RETURN_CODE = 77  # netns/CMakeLists.txt
TIMEOUT = 180.0  # seconds for a net to come up and deliver; generous, the machine may be loaded
LAUNCH = "fig3_4_parallel_subnets.launch"
OUTPUTS = ["/stereo/left_segmentation/out/binary", "/stereo/right_segmentation/out/binary"]
CAMERAS = ["/stereo/left_source/out/image", "/stereo/right_source/out/image"]


def cannot_run_here(repo):
    """Why two hosts cannot be made here (what `scripts/two-hosts check` says), or None if they can."""
    check = subprocess.run([os.path.join(repo, "scripts", "two-hosts"), "check"], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, universal_newlines=True)
    if check.returncode == 0:
        return None
    said = check.stdout.strip().replace("two-hosts: ", "", 1)
    return "scripts/two-hosts check says: " + (said or "nothing (exit %d)" % check.returncode)


def skip_message(reason):
    return ("SKIPPED: nets_across_machines needs two network namespaces joined by a veth pair and cannot make "
            "them here: %s. It runs in full as root where network namespaces work: on a Linux machine or VM, or "
            "in a privileged container (docker run --privileged)." % reason)


def listen(timeout, topics):
    """Runs inside a namespace: the first message of each topic and who publishes / reads it."""
    import rospy
    from sensor_msgs.msg import Image
    import xmlrpc.client

    master = xmlrpc.client.ServerProxy(os.environ["ROS_MASTER_URI"])
    deadline = time.time() + timeout
    while True:  # rospy.init_node would wait for the master silently
        try:
            master.getSystemState("/listener")
            break
        except OSError:
            if time.time() > deadline:
                print(json.dumps({"error": "no master at %s" % os.environ["ROS_MASTER_URI"]}))
                return 1
            time.sleep(0.5)
    rospy.init_node("split_net_listener", anonymous=True, disable_signals=True)
    images = {}

    def on_image(msg, topic):
        images.setdefault(topic, {"md5": hashlib.md5(msg.data).hexdigest(), "width": msg.width,
                                  "height": msg.height, "encoding": msg.encoding,
                                  "frame_id": msg.header.frame_id})

    subs = [rospy.Subscriber(t, Image, on_image, callback_args=t, queue_size=1) for t in topics]
    while len(images) < len(topics) and time.time() < deadline:
        time.sleep(0.1)
    for s in subs:
        s.unregister()
    _, _, state = master.getSystemState("/listener")
    publishers, subscribers, _ = state
    nodes = {n for _, ns in publishers + subscribers for n in ns}
    uris = {n: master.lookupNode("/listener", n)[2] for n in nodes}
    print(json.dumps({"images": images, "publishers": dict(publishers), "subscribers": dict(subscribers),
                      "uris": uris}))
    rospy.signal_shutdown("done")
    return 0


class NetsAcrossMachines(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.repo = os.path.abspath(sys.argv[1])
        cls.devel = os.path.abspath(sys.argv[2])
        cls.two_hosts = os.path.join(cls.repo, "scripts", "two-hosts")
        cls.home = tempfile.mkdtemp(prefix="nets_across_machines_")
        cls.processes = []
        cls.remove_leftovers()
        # Unique per run, so that a leftover of a killed run cannot get in the way.
        cls.id = "imagenets-%d-%04x" % (os.getpid(), random.getrandbits(16))
        cls.robot, cls.workstation = cls.id + "-robot", cls.id + "-workstation"
        try:
            subprocess.run([cls.two_hosts, "up", cls.id], check=True)
            cls.master = cls.spawn(cls.robot, ROBOT_IP, "master", ["roscore", "-p", "11311"])
        except BaseException:
            cls.tearDownClass()
            raise

    @classmethod
    def tearDownClass(cls):
        # Also called on SIGTERM / SIGINT and at exit (see main): idempotent.
        for p in reversed(cls.processes):
            cls.stop(p)
        if getattr(cls, "id", None):
            subprocess.run([cls.two_hosts, "down", cls.id])
            cls.id = None
        shutil.rmtree(cls.home, ignore_errors=True)

    @classmethod
    def remove_leftovers(cls):
        # Namespaces of earlier runs whose process is gone (killed by a timeout, say).
        listed = subprocess.run(["ip", "netns", "list"], stdout=subprocess.PIPE, universal_newlines=True).stdout
        for pid, tag in set(re.findall(r"^imagenets-(\d+)-([0-9a-f]{4})-(?:robot|workstation)", listed, re.M)):
            if not os.path.exists("/proc/%s" % pid):
                subprocess.run([cls.two_hosts, "down", "imagenets-%s-%s" % (pid, tag)])

    # --- processes on a host -------------------------------------------------------------------
    @classmethod
    def command(cls, namespace, ip, argv):
        env = ["env", "-i", "HOME=" + cls.home, "ROS_HOME=" + os.path.join(cls.home, namespace),
               "PATH=/usr/sbin:/usr/bin:/bin", "LANG=C.UTF-8", "ROS_IP=" + ip, "ROS_MASTER_URI=" + MASTER_URI]
        # As a user on that host: a shell that sourced the devel space, then the command.
        return (["ip", "netns", "exec", namespace] + env +
                ["bash", "-c", 'source "$0/setup.bash" && exec "$@"', cls.devel] + argv)

    @classmethod
    def spawn(cls, namespace, ip, name, argv):
        log = open(os.path.join(cls.home, "%s.log" % name), "w+")
        p = subprocess.Popen(cls.command(namespace, ip, argv), stdout=log, stderr=subprocess.STDOUT,
                             start_new_session=True)
        p.log, p.name = log, name
        cls.processes.append(p)
        return p

    @classmethod
    def stop(cls, p):
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGINT)  # roslaunch stops its nodes on SIGINT
            try:
                p.wait(timeout=60)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
        p.log.close()
        if p in cls.processes:
            cls.processes.remove(p)

    def log_of(self, p):
        p.log.flush()
        with open(p.log.name) as f:
            return "---- %s ----\n%s" % (p.name, f.read()[-4000:])

    def listen(self, namespace, ip, topics, *launches):
        r = subprocess.run(self.command(namespace, ip, ["/usr/bin/python3", os.path.abspath(__file__), "--listen",
                                                        str(TIMEOUT)] + topics),
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                           timeout=TIMEOUT + 120)
        logs = "\n".join(self.log_of(p) for p in launches + (self.master,))
        self.assertEqual(r.returncode, 0, "listener failed:\n%s%s\n%s" % (r.stdout, r.stderr, logs))
        result = json.loads(r.stdout.strip().splitlines()[-1])
        missing = [t for t in topics if t not in result["images"]]
        self.assertFalse(missing, "nothing arrived on %s within %.0f s\n%s" % (missing, TIMEOUT, logs))
        return result

    def received_bytes(self, namespace):
        r = subprocess.run(["ip", "netns", "exec", namespace, "cat", "/sys/class/net/eth0/statistics/rx_bytes"],
                           stdout=subprocess.PIPE, universal_newlines=True, check=True)
        return int(r.stdout)

    def roslaunch(self, namespace, ip, name, args):
        return self.spawn(namespace, ip, name, ["roslaunch", "--wait", "imagenets_blocks", LAUNCH, "rate:=5.0"] + args)

    # --- the test ------------------------------------------------------------------------------
    def test_split_net_equals_one_manager(self):
        # 1. The whole net in one manager on the robot.
        one = self.roslaunch(self.robot, ROBOT_IP, "one_manager", [])
        reference = self.listen(self.robot, ROBOT_IP, OUTPUTS, one)["images"]
        self.stop(one)

        # 2. Split: cameras on the robot, the sub-nets on the workstation, as docs/launch.md says.
        robot_args = ["manager:=robot_manager", "segmentation:=false"]
        workstation_args = ["manager:=workstation_manager", "use_file_sources:=false"]
        with open(os.path.join(self.repo, "docs", "launch.md")) as f:
            readme = f.read()
        for args in (robot_args, workstation_args):
            command = " ".join(["roslaunch imagenets_blocks", LAUNCH] + args)
            self.assertIn(command, readme, "docs/launch.md no longer gives `%s`: update this test" % command)
        before = self.received_bytes(self.workstation)
        robot = self.roslaunch(self.robot, ROBOT_IP, "robot", robot_args)
        workstation = self.roslaunch(self.workstation, WORKSTATION_IP, "workstation", workstation_args)
        split = self.listen(self.workstation, WORKSTATION_IP, OUTPUTS + CAMERAS, robot, workstation)
        received = self.received_bytes(self.workstation) - before

        for topic in OUTPUTS:
            self.assertEqual(split["images"][topic], reference[topic],
                             "%s differs between the split and the one-manager run" % topic)
            self.assertEqual(split["images"][topic]["encoding"], "mono8")
        image = split["images"][CAMERAS[0]]
        for camera in CAMERAS:
            self.assertEqual(split["publishers"].get(camera), ["/stereo/robot_manager"], camera)
            self.assertIn("/stereo/workstation_manager", split["subscribers"].get(camera, []), camera)
        self.assertIn("//%s:" % ROBOT_IP, split["uris"]["/stereo/robot_manager"])
        self.assertIn("//%s:" % WORKSTATION_IP, split["uris"]["/stereo/workstation_manager"])
        image_bytes = image["width"] * image["height"] * 3
        self.assertGreaterEqual(received, image_bytes,
                                "the workstation's interface received %d bytes, less than one %dx%d image"
                                % (received, image["width"], image["height"]))


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--listen":
        sys.exit(listen(float(sys.argv[2]), sys.argv[3:]))
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    reason = cannot_run_here(os.path.abspath(sys.argv[1]))
    if reason:
        if os.environ.get("IMAGENETS_TESTS_NO_SKIP") == "1":
            print("FAILED (IMAGENETS_TESTS_NO_SKIP=1, so nothing may be skipped): " + skip_message(reason))
            sys.exit(1)
        print(skip_message(reason))
        sys.exit(SKIP_RETURN_CODE)
    def terminate(signum, frame):
        raise SystemExit("stopped by signal %d" % signum)
    signal.signal(signal.SIGTERM, terminate)
    signal.signal(signal.SIGINT, terminate)
    try:
        result = unittest.main(argv=sys.argv[:1], verbosity=2, exit=False).result
    finally:
        if hasattr(NetsAcrossMachines, "home"):
            NetsAcrossMachines.tearDownClass()
    sys.exit(0 if result.wasSuccessful() else 1)
