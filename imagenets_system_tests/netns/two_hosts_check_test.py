#!/usr/bin/env python3
"""The check that decides whether `nets_across_machines` runs or is skipped.

- It agrees with the machine: an independent attempt (plain `ip` commands, not scripts/two-hosts)
  makes two network namespaces, joins them by a veth pair and connects from one to the other; the
  check must say yes exactly when that works. So where namespaces can be made the test is never
  skipped, and where they cannot it is never run into a failure.
- Where two hosts cannot be made, split_net_test.py exits 77 (ctest: skipped) and says what is
  missing and where it runs, in the environments ROS users test in: as a user who is not root; as
  root of a user namespace without privileges over the machine (like an unprivileged container);
  in a chroot into a plain directory (where ip cannot enter a namespace). With
  IMAGENETS_TESTS_NO_SKIP=1 it fails instead. An environment this machine cannot build (no user
  namespaces, say) is skipped by unittest, with the reason.

Usage: two_hosts_check_test.py REPOSITORY DEVEL_SPACE   (run by ctest as `nets_across_machines_check`)
"""
import os
import random
import shutil
import subprocess
import sys
import tempfile
import unittest

REPO = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.getcwd()
DEVEL = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else os.path.join(REPO, "devel")
TWO_HOSTS = os.path.join(REPO, "scripts", "two-hosts")
SPLIT_NET_TEST = os.path.join(REPO, "imagenets_system_tests", "netns", "split_net_test.py")
IP = shutil.which("ip", path="/usr/sbin:/sbin:/usr/bin:/bin")
NOBODY = 65534


def run(argv, **kwargs):
    return subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                          timeout=120, **kwargs)


def two_hosts_by_hand():
    """Makes two namespaces joined by a veth pair with plain ip commands, in another order than
    scripts/two-hosts (the pair is made outside and moved in), and connects from one to the other.
    Returns None if all of it worked, else the step that failed and what ip said. Removes it all."""
    if IP is None:
        return "no ip command"
    tag = "imagenets-oracle-%d-%04x" % (os.getpid(), random.getrandbits(16))
    a, b = tag + "-a", tag + "-b"
    va, vb = ("io%04x%04x" % (os.getpid() & 0xffff, random.getrandbits(16)) + end for end in "ab")
    steps = [
        ("create namespace a", [IP, "netns", "add", a]),
        ("create namespace b", [IP, "netns", "add", b]),
        ("make a veth pair", [IP, "link", "add", va, "type", "veth", "peer", "name", vb]),
        ("move one end into a", [IP, "link", "set", va, "netns", a]),
        ("move the other end into b", [IP, "link", "set", vb, "netns", b]),
        ("address a", [IP, "netns", "exec", a, IP, "addr", "add", "10.78.0.1/24", "dev", va]),
        ("address b", [IP, "netns", "exec", b, IP, "addr", "add", "10.78.0.2/24", "dev", vb]),
        ("bring a up", [IP, "netns", "exec", a, IP, "link", "set", va, "up"]),
        ("bring b up", [IP, "netns", "exec", b, IP, "link", "set", vb, "up"]),
        ("connect from b to a", [IP, "netns", "exec", b, "/usr/bin/python3", "-c",
                                 "import socket, sys\n"
                                 "try:\n socket.create_connection(('10.78.0.1', 9), 20)\n"
                                 "except ConnectionRefusedError: sys.exit(0)\n"]),
    ]
    try:
        for what, argv in steps:
            r = run(argv)
            if r.returncode != 0:
                return "%s: %s" % (what, r.stdout.strip())
        return None
    finally:
        run([IP, "link", "del", va])  # if the pair was made but not moved
        for ns in (a, b):
            run([IP, "netns", "del", ns])


def leftovers():
    if IP is None:
        return []
    listed = run([IP, "netns", "list"]).stdout
    return [line for line in listed.splitlines() if line.startswith(("imagenets-probe-", "imagenets-oracle-"))]


def remove_scaffold(root):
    """Removes the chroot's empty folders and links one by one: never a recursive delete, which would
    go through a bind mount (of /usr, say) if one had outlived its mount namespace."""
    for link in ("bin", "sbin", "lib", "lib64"):
        if os.path.islink(os.path.join(root, link)):
            os.unlink(os.path.join(root, link))
    repo = REPO.strip("/").split("/")
    folders = ["/".join(repo[:n]) for n in range(len(repo), 0, -1)]  # first: it may lie in tmp/
    folders += ["usr", "etc", "proc", "dev", "sys", "tmp", "run/netns", "run", ""]
    for folder in folders:
        try:
            os.rmdir(os.path.join(root, folder))
        except FileNotFoundError:
            pass


class TwoHostsCheck(unittest.TestCase):
    def split_net_test(self, prefix=(), env=None):
        env = dict(env if env is not None else os.environ)
        env.pop("IMAGENETS_TESTS_NO_SKIP", None)
        return run(list(prefix) + ["/usr/bin/python3", SPLIT_NET_TEST, REPO, DEVEL], env=env)

    def assert_skipped(self, r, reason):
        self.assertEqual(r.returncode, 77, "split_net_test.py should have skipped (exit 77):\n" + r.stdout)
        self.assertTrue(r.stdout.startswith("SKIPPED: nets_across_machines needs two network namespaces"), r.stdout)
        self.assertIn(reason, r.stdout)
        self.assertIn("as root where network namespaces work", r.stdout)
        self.assertIn("privileged container", r.stdout)
        self.assertEqual(leftovers(), [], "the check left namespaces behind")

    def test_the_check_agrees_with_the_machine(self):
        by_hand = two_hosts_by_hand()
        check = run([TWO_HOSTS, "check"])
        if by_hand is None:
            self.assertEqual(check.returncode, 0, "two namespaces joined by a veth pair can be made here, but the "
                             "check says no, so nets_across_machines would be skipped:\n" + check.stdout)
            self.assertEqual(check.stdout, "")
        else:
            self.assertNotEqual(check.returncode, 0, "the check says yes, but by hand: " + by_hand)
            self.assertTrue(check.stdout.startswith("two-hosts: "), check.stdout)
        self.assertEqual(leftovers(), [])

    def test_not_root(self):
        prefix = []
        if os.geteuid() == 0:
            prefix = ["setpriv", "--reuid=%d" % NOBODY, "--regid=%d" % NOBODY, "--clear-groups"]
            if run(prefix + ["test", "-r", SPLIT_NET_TEST]).returncode != 0:
                self.skipTest("user %d cannot read %s" % (NOBODY, SPLIT_NET_TEST))
        r = self.split_net_test(prefix)
        self.assert_skipped(r, "not root (uid %d)" % (NOBODY if prefix else os.geteuid()))

    def test_root_of_a_user_namespace_without_privileges(self):
        prefix = ["unshare", "--user", "--map-root-user"]
        probe = run(prefix + ["id", "-u"])
        if probe.returncode != 0:
            self.skipTest("no user namespaces here: " + probe.stdout.strip())
        self.assertEqual(probe.stdout.strip(), "0")
        self.assert_skipped(self.split_net_test(prefix), "cannot create a network namespace")

    def test_chroot_into_a_plain_directory(self):
        if os.geteuid() != 0:
            self.skipTest("making a chroot needs root")
        # The scaffold needs a mount namespace of its own, which root without CAP_SYS_ADMIN (an
        # unprivileged container) cannot make: nothing to test there.
        probe = run(["unshare", "--mount", "--propagation", "private", "true"])
        if probe.returncode != 0:
            self.skipTest("cannot make a mount namespace for the chroot: " + probe.stdout.strip())
        root = tempfile.mkdtemp(prefix="two_hosts_chroot_")
        try:
            # In a mount namespace of its own: the binds vanish with it, nothing to undo here.
            script = r'''
set -e
r=$1 repo=$2
for d in usr etc proc dev sys tmp run "$repo"; do mkdir -p "$r/$d"; done
for l in bin sbin lib lib64; do [ -L /$l ] && ln -s "$(readlink /$l)" "$r/$l"; done
mount --rbind /usr "$r/usr"; mount --rbind /etc "$r/etc"; mount --rbind /dev "$r/dev"
mount --rbind /sys "$r/sys"; mount -t proc proc "$r/proc"; mount --bind "$repo" "$r/$repo"
chmod 1777 "$r/tmp"
shift 2
exec chroot "$r" "$@"
'''
            r = self.split_net_test(["unshare", "--mount", "--propagation", "private", "bash", "-c", script,
                                     "chroot", root, REPO])
            self.assert_skipped(r, "cannot enter a network namespace")
            self.assertIn("chroot", r.stdout)
        finally:
            remove_scaffold(root)

    def test_no_skip_turns_the_skip_into_a_failure(self):
        if os.geteuid() != 0:
            prefix = []
        else:
            prefix = ["setpriv", "--reuid=%d" % NOBODY, "--regid=%d" % NOBODY, "--clear-groups"]
            if run(prefix + ["test", "-r", SPLIT_NET_TEST]).returncode != 0:
                self.skipTest("user %d cannot read %s" % (NOBODY, SPLIT_NET_TEST))
        r = run(prefix + ["env", "IMAGENETS_TESTS_NO_SKIP=1", "/usr/bin/python3", SPLIT_NET_TEST, REPO, DEVEL])
        self.assertEqual(r.returncode, 1, r.stdout)
        self.assertTrue(r.stdout.startswith("FAILED (IMAGENETS_TESTS_NO_SKIP=1"), r.stdout)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
