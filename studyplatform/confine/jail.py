"""Run a command confined: memory, CPU and file-size limits, no network, few files.

Run by path, never imported by the platform (it needs the standard library alone and
starts in milliseconds): ``python jail.py POLICY -- COMMAND …``. *POLICY* is JSON:

- ``memory_bytes``, ``cpu_s``, ``file_bytes``: RLIMIT_AS, RLIMIT_CPU, RLIMIT_FSIZE;
- ``read``: paths the command may read (and run) beneath; ``write``: paths it may
  also write, create and remove beneath. Everything else is out of reach (Linux
  Landlock, any ABI; on a kernel without it only the limits and the network hold);
- the command gets a network namespace of its own with nothing in it (as root; else a
  user namespace's, where the kernel allows one), and Landlock (ABI 4+) refuses TCP.

Then it replaces itself with the command, which inherits all of it. The parent keeps
the wall clock (:mod:`studyplatform.confine.runner`).
"""

import ctypes
import json
import os
import resource
import sys

SYS_LANDLOCK_CREATE_RULESET, SYS_LANDLOCK_ADD_RULE, SYS_LANDLOCK_RESTRICT_SELF = 444, 445, 446
LANDLOCK_CREATE_RULESET_VERSION = 1
LANDLOCK_RULE_PATH_BENEATH = 1
PR_SET_NO_NEW_PRIVS = 38
CLONE_NEWUSER, CLONE_NEWNET = 0x10000000, 0x40000000
# Landlock's filesystem rights (include/uapi/linux/landlock.h).
EXECUTE, WRITE_FILE, READ_FILE, READ_DIR = 1, 2, 4, 8
READ = EXECUTE | READ_FILE | READ_DIR
FILE_RIGHTS = EXECUTE | WRITE_FILE | READ_FILE | (1 << 14) | (1 << 15)  # + TRUNCATE, IOCTL_DEV
# The rights each ABI handles: 13 in ABI 1, REFER in 2, TRUNCATE in 3, IOCTL_DEV in 5.
ABI_FS_RIGHTS = {1: (1 << 13) - 1, 2: (1 << 14) - 1, 3: (1 << 15) - 1, 5: (1 << 16) - 1}


class _RulesetAttr(ctypes.Structure):
    _fields_ = [
        ("handled_access_fs", ctypes.c_uint64),
        ("handled_access_net", ctypes.c_uint64),
        ("scoped", ctypes.c_uint64),
    ]


class _PathBeneath(ctypes.Structure):
    _pack_ = 1
    _fields_ = [("allowed_access", ctypes.c_uint64), ("parent_fd", ctypes.c_int32)]


LIBC = ctypes.CDLL(None, use_errno=True)


def landlock_abi() -> int:
    """Return the kernel's Landlock ABI version (0: none)."""
    version = LIBC.syscall(SYS_LANDLOCK_CREATE_RULESET, None, 0, LANDLOCK_CREATE_RULESET_VERSION)
    return max(0, version)


def _fs_rights(abi: int) -> int:
    return ABI_FS_RIGHTS[max(k for k in ABI_FS_RIGHTS if k <= abi)]


def restrict_files(read: list[str], write: list[str]) -> int:
    """Allow only *read* (read, list, run) and *write* (anything) beneath those paths, and
    no TCP; return the ABI used (0: the kernel has no Landlock, nothing restricted)."""
    abi = landlock_abi()
    if abi == 0:
        return 0
    handled = _fs_rights(abi)
    attr = _RulesetAttr(handled, 3 if abi >= 4 else 0, 3 if abi >= 6 else 0)  # TCP; scopes
    size = 8 if abi < 4 else 16 if abi < 6 else 24
    ruleset = LIBC.syscall(SYS_LANDLOCK_CREATE_RULESET, ctypes.byref(attr), size, 0)
    if ruleset < 0:
        raise OSError(ctypes.get_errno(), "landlock_create_ruleset")
    for paths, rights in ((read, READ), (write, handled)):
        for path in paths:
            try:
                fd = os.open(path, os.O_PATH | os.O_CLOEXEC)
            except OSError:
                continue  # a path this machine lacks (/lib64 on some) grants nothing
            allowed = rights if os.path.isdir(path) else rights & FILE_RIGHTS
            rule = _PathBeneath(allowed & handled, fd)
            done = LIBC.syscall(
                SYS_LANDLOCK_ADD_RULE, ruleset, LANDLOCK_RULE_PATH_BENEATH, ctypes.byref(rule), 0
            )
            os.close(fd)
            if done < 0:
                raise OSError(ctypes.get_errno(), f"landlock_add_rule {path}")
    if LIBC.prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) < 0:
        raise OSError(ctypes.get_errno(), "prctl(PR_SET_NO_NEW_PRIVS)")
    if LIBC.syscall(SYS_LANDLOCK_RESTRICT_SELF, ruleset, 0) < 0:
        raise OSError(ctypes.get_errno(), "landlock_restrict_self")
    os.close(ruleset)
    return abi


def isolate_network() -> bool:
    """Move into an empty network namespace; return whether that worked."""
    if LIBC.unshare(CLONE_NEWNET) == 0:
        return True
    return LIBC.unshare(CLONE_NEWUSER | CLONE_NEWNET) == 0


def limit(memory_bytes: int, cpu_s: int, file_bytes: int) -> None:
    """Set the address-space, CPU-time and file-size limits, and no core dumps."""
    resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
    resource.setrlimit(resource.RLIMIT_CPU, (cpu_s, cpu_s + 1))
    resource.setrlimit(resource.RLIMIT_FSIZE, (file_bytes, file_bytes))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def main(argv: list[str]) -> None:
    policy, separator, command = json.loads(argv[1]), argv[2], argv[3:]
    if separator != "--" or not command:
        raise SystemExit("usage: jail.py POLICY -- COMMAND …")
    limit(policy["memory_bytes"], policy["cpu_s"], policy["file_bytes"])
    isolate_network()
    restrict_files(policy.get("read", []), policy.get("write", []))
    os.execv(command[0], command)


if __name__ == "__main__":
    main(sys.argv)
