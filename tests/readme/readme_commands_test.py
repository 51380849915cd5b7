#!/usr/bin/env python3
"""Runs every command of the README's "Using it" block that starts with build-release/, as a user would
after ./scripts/demo.sh: from a scratch folder that holds the repository's samples/ (linked) and an out/
folder, with build-release/ standing for the build under test. Fails, naming the line, when a command
exits non-zero or the block has no such command. `cmake --build` lines build targets the test build
already has, so they are not run.

Usage: readme_commands_test.py README.md SOURCE_DIR BUILD_DIR
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile


def using_it_commands(readme):
    with open(readme, encoding="utf-8") as f:
        text = f.read()
    section = text.split("## Using it", 1)[1]
    block = re.search(r"```sh\n(.*?)```", section, re.S).group(1)
    return [line for line in block.splitlines() if line.startswith("build-release/")]


def main():
    readme, source, build = sys.argv[1:4]
    commands = using_it_commands(readme)
    if not commands:
        print("no build-release/ command in the README's Using it block")
        return 1
    failed = 0
    with tempfile.TemporaryDirectory() as scratch:
        os.symlink(os.path.join(source, "samples"), os.path.join(scratch, "samples"))
        os.mkdir(os.path.join(scratch, "out"))
        for line in commands:
            argv = shlex.split(line, comments=True)
            argv[0] = os.path.join(build, argv[0][len("build-release/"):])
            if not os.path.exists(argv[0]):
                print(f"FAIL (not built: {argv[0]}): {line}")
                failed += 1
                continue
            run = subprocess.run(argv, cwd=scratch, capture_output=True, text=True, timeout=600)
            status = "ok" if run.returncode == 0 else f"FAIL (exit {run.returncode})"
            print(f"{status}: {line}")
            if run.returncode != 0:
                print(run.stderr[-2000:])
                failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
