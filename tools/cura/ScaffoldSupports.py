# Cura post-processing script: runs scaffold on the sliced G-code.
# Copy this file into Cura's "scripts" folder (Help > Show Configuration
# Folder, then scripts/), restart Cura, and add "Scaffold supports" under
# Extensions > Post Processing > Modify G-Code. Slice with supports off.
#
# Cura hands its scripts the G-code without the ;SETTING_3 block (it adds
# that only when saving, and then only the settings the user changed), so
# the settings scaffold needs are read from Cura's own stacks here and passed
# on the command line: support extrusion then matches the printer's filament
# (2.85 mm on Ultimaker and LulzBot machines), nozzle and retraction.
import os
import subprocess
import tempfile

try:
    from ..Script import Script
except (ImportError, ValueError):  # outside Cura (tests): a stand-in base
    class Script:
        def getSettingValueByKey(self, key):
            return self._values[key]

# Cura setting keys scaffold reads (gcode/settings.cpp knows them by these
# names); values come from the first extruder's stack, else the global one.
CURA_KEYS = (
    "material_diameter", "machine_nozzle_size", "layer_height", "layer_height_0",
    "retraction_amount", "retraction_speed", "retraction_prime_speed",
    "retraction_hop_enabled", "retraction_hop", "retraction_min_travel",
    "machine_firmware_retract", "speed_travel", "speed_support", "speed_layer_0",
    "bridge_skin_speed", "machine_width", "machine_depth", "magic_spiralize",
    "print_sequence", "machine_gcode_flavor",
)


def cura_settings():
    """The CURA_KEYS values of the running Cura, as strings; {} outside Cura."""
    try:
        from cura.CuraApplication import CuraApplication
    except ImportError:
        return {}
    stack = CuraApplication.getInstance().getGlobalContainerStack()
    if stack is None:
        return {}
    extruders = stack.extruderList if hasattr(stack, "extruderList") else []
    values = {}
    for key in CURA_KEYS:
        for s in (extruders[0] if extruders else None, stack):
            if s is None:
                continue
            v = s.getProperty(key, "value")
            if v is not None:
                values[key] = str(v)
                break
    return values


def command_line(binary, method, extra, settings, path):
    """scaffold's arguments: the method, Cura's settings as --set, the user's extras, the file."""
    args = [binary, "--method", method]
    for key in sorted(settings):
        args += ["--set", key + "=" + settings[key]]
    return args + list(extra) + [path]


class ScaffoldSupports(Script):
    def getSettingDataString(self):
        return """{
            "name": "Scaffold supports",
            "key": "ScaffoldSupports",
            "metadata": {},
            "version": 2,
            "settings": {
                "binary": {
                    "label": "scaffold program",
                    "description": "Full path of the scaffold executable.",
                    "type": "str",
                    "default_value": "/usr/local/bin/scaffold"
                },
                "method": {
                    "label": "Method",
                    "description": "scaffold: bridges and pillars; pillars: vertical pillars only.",
                    "type": "enum",
                    "options": {"scaffold": "Scaffold (bridges)", "pillars": "Pillars only"},
                    "default_value": "scaffold"
                },
                "extra": {
                    "label": "Extra options",
                    "description": "More scaffold options, e.g. --xy-gap 0.6 --overhang-angle 50",
                    "type": "str",
                    "default_value": ""
                }
            }
        }"""

    def execute(self, data):
        binary = self.getSettingValueByKey("binary")
        method = self.getSettingValueByKey("method")
        extra = self.getSettingValueByKey("extra").split()
        fd, path = tempfile.mkstemp(suffix=".gcode")
        try:
            # UTF-8 whatever the system's code page (Windows): G-code may
            # carry any character in its comments.
            with os.fdopen(fd, "w", newline="", encoding="utf-8", errors="surrogateescape") as f:
                f.write("".join(data))
            # No console window flashing up on Windows.
            flags = getattr(subprocess, "CREATE_NO_WINDOW", 0)
            result = subprocess.run(command_line(binary, method, extra, cura_settings(), path),
                                    capture_output=True, text=True, creationflags=flags)
            if result.returncode != 0:
                raise RuntimeError("scaffold failed: " + result.stderr.strip())
            with open(path, newline="", encoding="utf-8", errors="surrogateescape") as f:
                text = f.read()
        finally:
            os.unlink(path)
        # Cura joins the list when it saves; one element holds the whole file.
        return [text]
