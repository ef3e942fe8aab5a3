#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs one contour4d step of the cohort workflow and records it; never fails, so one subject's failure never
stops the others.

usage: run_step.py --status STATUS.json [--after PREVIOUS.json] -- COMMAND...

STATUS.json gets {"command", "exit_code", "message", "seconds", "skipped"}: the exit code and the last error
line of the command (128 + N for a signal N), or, when the previous step failed, skipped = true with that
step's exit code. The command's output goes to STATUS.log beside it.
"""
import argparse
import json
import os
import subprocess
import sys
import time


def last_error(text):
    lines = [line for line in text.splitlines() if line.strip()]
    errors = [line for line in lines if "error" in line.lower()]
    return (errors or lines or [""])[-1][:500]


def run(command):
    """(exit code, message, output, seconds) of one command."""
    t0 = time.monotonic()
    try:
        p = subprocess.run(command, capture_output=True, text=True)
    except OSError as e:  # the binary itself is missing or not executable
        p = subprocess.CompletedProcess(command, 127, "", f"error: cannot run {command[0]}: {e}\n")
    seconds = round(time.monotonic() - t0, 3)
    if p.returncode < 0:
        return 128 - p.returncode, f"killed by signal {-p.returncode}", p.stdout + p.stderr, seconds
    message = last_error(p.stderr or p.stdout) if p.returncode else ""
    return p.returncode, message, p.stdout + p.stderr, seconds


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--status", required=True)
    ap.add_argument("--after")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    command = a.command[1:] if a.command[:1] == ["--"] else a.command
    os.makedirs(os.path.dirname(a.status) or ".", exist_ok=True)
    status = {"command": command, "exit_code": 0, "message": "", "seconds": 0.0, "skipped": False}
    previous = json.load(open(a.after)) if a.after else None
    if previous and previous["exit_code"] != 0:
        status.update(exit_code=previous["exit_code"], message=previous["message"], skipped=True,
                      failed_step=previous.get("failed_step", os.path.basename(a.after)[:-5]))
        output = f"skipped: the {status['failed_step']} step failed (exit code {status['exit_code']})\n"
    else:
        code, message, output, seconds = run(command)
        status.update(exit_code=code, message=message, seconds=seconds)
        if code:
            status["failed_step"] = os.path.basename(a.status)[:-5]
    with open(a.status[:-5] + ".log", "w") as f:
        f.write(output)
    tmp = a.status + ".tmp"
    with open(tmp, "w") as f:
        json.dump(status, f, indent=2)
    os.replace(tmp, a.status)
    return 0


if __name__ == "__main__":
    sys.exit(main())
