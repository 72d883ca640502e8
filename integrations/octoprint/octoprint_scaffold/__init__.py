# scaffold for OctoPrint: adds support structures to each G-code file as it
# is uploaded (from a slicer, the web interface or the API), through
# OctoPrint's "octoprint.filemanager.preprocessor" hook: the upload is saved
# to a temporary file, scaffold rewrites that file in place, and a disk-file
# wrapper of it goes back to OctoPrint's storage. A file scaffold refuses
# (or that already carries its header, or a "; scaffold: off" line) is
# stored as it came, and the reason goes to octoprint.log.
#
# Settings (Settings > scaffold): the executable's path, the method,
# extra options, on/off, and a timeout in seconds.

import logging
import os
import re
import shlex
import shutil
import subprocess
import tempfile

import octoprint.filemanager
import octoprint.filemanager.util
import octoprint.plugin

# scaffold's header line, or the user's "; scaffold: off" line (the same
# regex as the Moonraker component's ident), within the file's first MiB.
SKIP_REGEX = re.compile(
    rb"^; scaffold(?: (\d+(?:\.\d+)*) \(post-processed supports\)|: off\b)", re.MULTILINE
)
HEAD_BYTES = 1024 * 1024
METHODS = ("scaffold", "pillars")


def default_path():
    return shutil.which("scaffold") or "/usr/bin/scaffold"


def scaffold_command(path, method, options, gcode_path):
    if method not in METHODS:
        raise ValueError("method must be one of {}, not '{}'".format(", ".join(METHODS), method))
    return [path, "--method", method] + shlex.split(options or "") + [gcode_path]


def run_scaffold(settings, gcode_path, logger):
    """Runs scaffold on gcode_path in place. Returns True when it rewrote the
    file; on any failure the file is as it was (scaffold writes through a
    temporary file) and the reason is logged."""
    with open(gcode_path, "rb") as f:
        m = SKIP_REGEX.search(f.read(HEAD_BYTES))
    if m is not None:
        logger.info("%s: %s, left as it is", os.path.basename(gcode_path),
                    "already processed by scaffold " + m.group(1).decode() if m.group(1) else "'; scaffold: off'")
        return False
    try:
        cmd = scaffold_command(settings["path"], settings["method"], settings["options"], gcode_path)
        ret = subprocess.run(cmd, capture_output=True, timeout=settings["timeout"])
    except (OSError, ValueError, subprocess.SubprocessError) as e:
        logger.warning("scaffold did not run on %s: %s", os.path.basename(gcode_path), e)
        return False
    err = ret.stderr.decode(errors="replace").strip()
    if ret.returncode != 0:
        logger.warning("scaffold failed with code %d on %s, file stored unchanged: %s",
                       ret.returncode, os.path.basename(gcode_path), err)
        return False
    if err:
        logger.info("%s", err)
    return True


class ScaffoldPlugin(octoprint.plugin.SettingsPlugin, octoprint.plugin.TemplatePlugin):

    def get_settings_defaults(self):
        return dict(path=default_path(), method="scaffold", options="", enabled=True, timeout=600)

    def get_template_configs(self):
        return [dict(type="settings", custom_bindings=False)]

    def _current_settings(self):
        return dict(
            path=os.path.expanduser(self._settings.get(["path"]) or default_path()),
            method=self._settings.get(["method"]),
            options=self._settings.get(["options"]) or "",
            timeout=max(1, self._settings.get_int(["timeout"]) or 600),
        )

    # octoprint.filemanager.preprocessor: called by FileManager.add_file with
    # the path in storage and the upload's file wrapper; what it returns is
    # what the storage saves.
    def preprocess_upload(self, path, file_object, links=None, printer_profile=None,
                          allow_overwrite=False, *args, **kwargs):
        if not self._settings.get_boolean(["enabled"]):
            return file_object
        if not octoprint.filemanager.valid_file_type(path, type="gcode"):
            return file_object
        fd, tmp = tempfile.mkstemp(prefix="scaffold-", suffix=".gcode")
        os.close(fd)
        try:
            file_object.save(tmp)
        except Exception:
            os.remove(tmp)
            raise
        if run_scaffold(self._current_settings(), tmp, self._logger):
            self._logger.info("scaffold added supports to %s", path)
        # The temporary file is moved into storage by the wrapper's save().
        return octoprint.filemanager.util.DiskFileWrapper(file_object.filename, tmp, move=True)


__plugin_name__ = "scaffold"
__plugin_description__ = "Adds support structures (pillars and bridges) to uploaded G-code"
__plugin_pythoncompat__ = ">=3.7,<4"


def __plugin_load__():
    global __plugin_implementation__
    __plugin_implementation__ = ScaffoldPlugin()
    global __plugin_hooks__
    __plugin_hooks__ = {
        "octoprint.filemanager.preprocessor": __plugin_implementation__.preprocess_upload,
    }
