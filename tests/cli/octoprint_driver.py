"""Calls the OctoPrint plugin (integrations/octoprint) the way OctoPrint
does, without OctoPrint (it is not packaged in Debian): the few modules the
plugin imports are imitated here with OctoPrint's documented behaviour, the
plugin is loaded by its __plugin_load__, its settings come from its own
get_settings_defaults() overridden by KEY=VALUE arguments, and one upload
goes through FileManager.add_file's steps: the preprocessor hook gets
(path in storage, file wrapper, printer_profile=..., allow_overwrite=...),
an exception is logged and ignored, and what the hook returns (or the
original wrapper when it returns None) is saved to the storage path.
Usage: octoprint_driver.py PLUGIN_DIR UPLOAD STORED [disk|stream] [KEY=VALUE...]
Prints the plugin's log lines to stderr."""
import importlib
import logging
import os
import shutil
import sys
import types

logging.basicConfig(stream=sys.stderr, level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")


# octoprint.filemanager.util: the file wrappers storage saves from.
class AbstractFileWrapper:
    def __init__(self, filename):
        self.filename = filename

    def save(self, path, permissions=None):
        raise NotImplementedError()

    def stream(self):
        raise NotImplementedError()


class DiskFileWrapper(AbstractFileWrapper):
    def __init__(self, filename, path, move=True):
        super().__init__(filename)
        self.path, self.move = path, move

    def save(self, path, permissions=None):
        (shutil.move if self.move else shutil.copyfile)(self.path, path)

    def stream(self):
        return open(self.path, "rb")


class StreamWrapper(AbstractFileWrapper):
    def __init__(self, filename, *streams):
        super().__init__(filename)
        self.streams = streams

    def save(self, path, permissions=None):
        with open(path, "wb") as out:
            for s in self.streams:
                shutil.copyfileobj(s, out)

    def stream(self):
        return self.streams[0]


def valid_file_type(filename, type=None):
    ext = os.path.splitext(filename)[1].lower()
    return ext in (".gcode", ".gco", ".g") if type == "gcode" else True


class _Plugin:
    pass


def install_octoprint_imitation():
    octoprint = types.ModuleType("octoprint")
    plugin = types.ModuleType("octoprint.plugin")
    plugin.SettingsPlugin = type("SettingsPlugin", (_Plugin,), {})
    plugin.TemplatePlugin = type("TemplatePlugin", (_Plugin,), {})
    filemanager = types.ModuleType("octoprint.filemanager")
    filemanager.valid_file_type = valid_file_type
    util = types.ModuleType("octoprint.filemanager.util")
    for c in (AbstractFileWrapper, DiskFileWrapper, StreamWrapper):
        setattr(util, c.__name__, c)
    filemanager.util = util
    octoprint.plugin, octoprint.filemanager = plugin, filemanager
    sys.modules.update({"octoprint": octoprint, "octoprint.plugin": plugin,
                        "octoprint.filemanager": filemanager, "octoprint.filemanager.util": util})


# The plugin's self._settings (octoprint.plugin.PluginSettings): get,
# get_boolean, get_int over the defaults and what the user saved.
class Settings:
    def __init__(self, values):
        self.values = values

    def get(self, path):
        return self.values[path[0]]

    def get_boolean(self, path):
        v = self.values[path[0]]
        return v if isinstance(v, bool) else str(v).lower() in ("true", "1", "yes")

    def get_int(self, path):
        return int(self.values[path[0]])


def main():
    plugin_dir, upload, stored, kind = sys.argv[1:5]
    install_octoprint_imitation()
    sys.path.insert(0, plugin_dir)
    mod = importlib.import_module("octoprint_scaffold")
    mod.__plugin_load__()
    impl = mod.__plugin_implementation__
    values = impl.get_settings_defaults()
    for kv in sys.argv[5:]:
        k, v = kv.split("=", 1)
        assert k in values, "no setting " + k
        values[k] = v
    impl._settings = Settings(values)
    impl._logger = logging.getLogger("octoprint.plugins.scaffold")
    assert [t["type"] for t in impl.get_template_configs()] == ["settings"]

    name = os.path.basename(stored)
    if kind == "disk":   # an HTTP upload: Tornado's temporary file
        tmp = stored + ".upload"
        shutil.copyfile(upload, tmp)
        file_object = DiskFileWrapper(name, tmp)
    else:                # a copy across storages: a stream
        file_object = StreamWrapper(name, open(upload, "rb"))
    hook = mod.__plugin_hooks__["octoprint.filemanager.preprocessor"]
    try:
        result = hook(name, file_object, printer_profile={"id": "_default"}, allow_overwrite=False)
    except Exception:
        logging.getLogger("octoprint.filemanager").exception("Error when calling preprocessor hook for plugin scaffold, ignoring")
        result = None
    if result is not None:
        file_object = result
    file_object.save(stored)
    print("returned " + ("nothing" if result is None else type(result).__name__))


main()
