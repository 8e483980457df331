#!/usr/bin/env python3
"""Run a command and report how much CPU *other* processes used meanwhile.

usage: cpuguard.py [--idle-wait S] [--idle-thresh C] -- command args...

Before starting, waits (at most S seconds, default 600) until the machine has been idle
(< C busy cores, default 0.15) for 3 consecutive 1-s samples. Then runs the command and
prints to stderr one line
    CPUGUARD wall_s=<wall> child_cpu_s=<cpu of the command> foreign_cores=<avg busy cores not ours>
foreign_cores is (busy CPU time of the whole machine from /proc/stat - CPU time of the
command and its children) / wall time. Exit status is the command's.
"""
import os, resource, subprocess, sys, time

HZ = os.sysconf("SC_CLK_TCK")


def busy_seconds():
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:]]
    # user nice system idle iowait irq softirq steal ...
    busy = v[0] + v[1] + v[2] + v[5] + v[6]
    return busy / HZ


def main():
    args = sys.argv[1:]
    idle_wait, idle_thresh = 600.0, 0.15
    while args and args[0] != "--":
        if args[0] == "--idle-wait":
            idle_wait = float(args[1]); args = args[2:]
        elif args[0] == "--idle-thresh":
            idle_thresh = float(args[1]); args = args[2:]
        else:
            sys.exit("cpuguard.py: unknown option " + args[0])
    cmd = args[1:]
    t_end = time.time() + idle_wait
    quiet = 0
    waited = 0.0
    while quiet < 3 and time.time() < t_end:
        b0, t0 = busy_seconds(), time.time()
        time.sleep(1.0)
        load = (busy_seconds() - b0) / (time.time() - t0)
        quiet = quiet + 1 if load < idle_thresh else 0
        waited += 1.0
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    b0, t0 = busy_seconds(), time.time()
    rc = subprocess.call(cmd)
    t1, b1 = time.time(), busy_seconds()
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    child = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    wall = t1 - t0
    foreign = max(0.0, (b1 - b0) - child) / wall if wall > 0 else 0.0
    sys.stderr.write("CPUGUARD wall_s=%.3f child_cpu_s=%.3f foreign_cores=%.3f idle_wait_s=%.0f\n"
                     % (wall, child, foreign, waited))
    return rc


if __name__ == "__main__":
    sys.exit(main())
