# Cura post-processing script: runs scaffold on the sliced G-code.
# Copy this file into Cura's "scripts" folder (Help > Show Configuration
# Folder, then scripts/), restart Cura, and add "Scaffold supports" under
# Extensions > Post Processing > Modify G-Code. Slice with supports off.
import os
import subprocess
import tempfile

from ..Script import Script


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
            with os.fdopen(fd, "w", newline="") as f:
                f.write("".join(data))
            result = subprocess.run([binary, "--method", method, *extra, path],
                                    capture_output=True, text=True)
            if result.returncode != 0:
                raise RuntimeError("scaffold failed: " + result.stderr.strip())
            with open(path, newline="") as f:
                text = f.read()
        finally:
            os.unlink(path)
        # Cura joins the list when it saves; one element holds the whole file.
        return [text]
