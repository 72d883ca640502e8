# scaffold: adds support structures to every G-code file uploaded to
# Moonraker, whatever sent it (a slicer's upload, Mainsail, Fluidd,
# Bambu Studio's or OrcaSlicer's "Send").
#
# A Moonraker component: this file is linked into moonraker/components/
# (integrations/moonraker/install.sh does it) and configured by a
# [scaffold] section in moonraker.conf:
#
#   [scaffold]
#   path: ~/scaffold/scaffold-linux-aarch64  # the executable (default: the
#                                            # release file for this board in
#                                            # ~/scaffold, else scaffold on PATH)
#   method: scaffold                         # scaffold | pillars
#   options: --overhang-angle 50             # more scaffold options
#   enabled: True
#   timeout: 600                             # seconds for one file
#
# It registers scaffold as a G-code processor of the file manager's
# metadata storage: Moonraker runs it on each upload, in place, before it
# reads the file's metadata, and skips files whose first MiB already holds
# scaffold's header line or a "; scaffold: off" line (the per-file switch).
#
# Copyright: the scaffold project. Not part of Moonraker; written against
# its component interface (file_manager.get_metadata_storage()
# .register_gcode_processor, Moonraker since February 2025).

from __future__ import annotations

import logging
import os
import pathlib
import platform
import re
import shlex
import shutil
import subprocess
from typing import TYPE_CHECKING, Any, Dict, List, Optional

if TYPE_CHECKING:
    from ..confighelper import ConfigHelper

NAME = "scaffold"
# scaffold's header line (the second line of a file it wrote), or the
# user's own "; scaffold: off" line: either means "do not run scaffold".
IDENT_REGEX = (
    r"^; scaffold(?: (?P<version>\d+(?:\.\d+)*) \(post-processed supports\)"
    r"|: off\b)"
)
METHODS = ("scaffold", "pillars")


def release_asset_name(machine: Optional[str] = None) -> Optional[str]:
    """The release file that runs on this board: static programs, so the
    kernel's architecture decides (a 64-bit kernel runs the aarch64 file
    even under a 32-bit Raspberry Pi OS)."""
    m = (machine or platform.machine()).lower()
    if m in ("aarch64", "arm64"):
        return "scaffold-linux-aarch64"
    if m.startswith("armv7") or m.startswith("armv8l"):
        return "scaffold-linux-armhf"
    return None


def default_path() -> str:
    asset = release_asset_name()
    if asset is not None:
        candidate = pathlib.Path("~/scaffold").expanduser() / asset
        if candidate.is_file():
            return str(candidate)
    return shutil.which("scaffold") or "/usr/bin/scaffold"


def build_processor_config(
    path: str, method: str, options: str, enabled: bool, timeout: float,
    version: str = "?"
) -> Dict[str, Any]:
    """The configuration Moonraker's metadata script runs: the command as an
    argument list with {gcode_file_path} (scaffold rewrites the file in
    place, through a temporary file, so a failure leaves it untouched)."""
    command: List[str] = [path, "--method", method]
    command += shlex.split(options)
    command.append("{gcode_file_path}")
    return {
        "name": NAME,
        "command": command,
        "timeout": timeout,
        "version": version,
        "enabled": enabled,
        "ident": {"regex": IDENT_REGEX, "location": "header"},
    }


def detect_version(path: str) -> Optional[str]:
    try:
        out = subprocess.run(
            [path, "--version"], capture_output=True, timeout=30, check=True
        ).stdout.decode(errors="ignore")
    except (OSError, subprocess.SubprocessError):
        return None
    m = re.match(r"scaffold (\d+(?:\.\d+)*)", out)
    return m.group(1) if m else None


class Scaffold:
    def __init__(self, config: ConfigHelper) -> None:
        self.server = config.get_server()
        self.path = os.path.expanduser(config.get("path", None) or default_path())
        method = config.get("method", "scaffold")
        if method not in METHODS:
            raise config.error(
                f"[{config.get_name()}]: option 'method' must be one of "
                f"{', '.join(METHODS)}, not '{method}'"
            )
        options = config.get("options", "")
        try:
            shlex.split(options)
        except ValueError as e:
            raise config.error(
                f"[{config.get_name()}]: option 'options' cannot be split: {e}"
            )
        self.enabled = config.getboolean("enabled", True)
        timeout = config.getfloat("timeout", 600.0, above=0.0)
        # Kept by reference in the file manager: component_init fills in the
        # version and turns it off if the executable does not run.
        self.proc_config = build_processor_config(
            self.path, method, options, self.enabled, timeout
        )
        fm = self.server.lookup_component("file_manager")
        fm.get_metadata_storage().register_gcode_processor(NAME, self.proc_config)

    async def component_init(self) -> None:
        eventloop = self.server.get_event_loop()
        version = await eventloop.run_in_thread(detect_version, self.path)
        if version is None:
            self.proc_config["enabled"] = False
            msg = (
                f"[{NAME}]: '{self.path} --version' failed: scaffold is off "
                "until option 'path' names a scaffold executable for this board"
            )
            self.server.add_warning(msg)  # logged too
            return
        self.proc_config["version"] = version
        state = "on" if self.enabled else "off (enabled: False)"
        logging.info(f"scaffold {version} at {self.path}: processing uploads {state}")


def load_component(config: ConfigHelper) -> Scaffold:
    return Scaffold(config)
