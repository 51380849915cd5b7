# SPDX-License-Identifier: MIT
"""What the bench reports write beside their numbers about the machine they ran on."""
import platform


def cpu_name():
    """The CPU's model name from /proc/cpuinfo, else what platform knows, else 'unknown'."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"
