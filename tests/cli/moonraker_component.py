"""Loads integrations/moonraker/scaffold.py the way Moonraker does (its
load_component with a config section, then component_init) and prints, as
JSON, the G-code processor configuration it registered with the file
manager's metadata storage. Moonraker's server is imitated by the few calls
the component makes; the config section is read by configparser, as
Moonraker's ConfigHelper does.
Usage: python3 moonraker_component.py COMPONENT.py CONF_FILE"""
import asyncio
import configparser
import importlib.util
import json
import sys


class ConfigError(Exception):
    pass


class Server:
    def __init__(self):
        self.processors = {}
        self.warnings = []

    # Moonraker's FileManager.get_metadata_storage().register_gcode_processor,
    # with the same required fields.
    def register_gcode_processor(self, name, cfg):
        if name in self.processors:
            raise ConfigError(f"File processor {name} already registered")
        for field in ("name", "command", "timeout"):
            if field not in cfg:
                raise ConfigError(f"File processor configuration requires a `{field}` field")
        self.processors[name] = cfg

    def get_metadata_storage(self):
        return self

    def lookup_component(self, name):
        assert name == "file_manager", name
        return self

    def get_event_loop(self):
        return self

    def run_in_thread(self, func, *args):
        return asyncio.get_running_loop().run_in_executor(None, func, *args)

    def add_warning(self, msg, warn_id=None, log=True, exc_info=None):
        self.warnings.append(msg)
        print(f"moonraker warning: {msg}", file=sys.stderr)


_MISSING = object()


class Config:
    def __init__(self, server, parser, section):
        self.server, self.parser, self.section = server, parser, section
        self.error = ConfigError

    def get_server(self):
        return self.server

    def get_name(self):
        return self.section

    def _get(self, fn, option, default):
        if not self.parser.has_option(self.section, option):
            if default is _MISSING:
                raise ConfigError(f"[{self.section}]: option '{option}' missing")
            return default
        return fn(self.section, option)

    def get(self, option, default=_MISSING):
        return self._get(self.parser.get, option, default)

    def getboolean(self, option, default=_MISSING):
        return self._get(self.parser.getboolean, option, default)

    def getfloat(self, option, default=_MISSING, above=None, **_):
        v = self._get(self.parser.getfloat, option, default)
        if above is not None and v <= above:
            raise ConfigError(f"[{self.section}]: option '{option}' must be above {above}")
        return v


def main():
    spec = importlib.util.spec_from_file_location("scaffold_component", sys.argv[1])
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    parser = configparser.ConfigParser(interpolation=None)
    parser.read(sys.argv[2])
    server = Server()
    try:
        comp = mod.load_component(Config(server, parser, "scaffold"))
    except ConfigError as e:
        print(f"config error: {e}", file=sys.stderr)
        sys.exit(3)
    asyncio.run(comp.component_init())
    json.dump(server.processors["scaffold"], sys.stdout)


main()
