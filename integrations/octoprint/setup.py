# The scaffold OctoPrint plugin. Install into OctoPrint's own Python
# environment (docs/host-setup.md):
#   ~/oprint/bin/pip install /usr/share/scaffold/integrations/octoprint
from setuptools import setup

setup(
    name="OctoPrint-Scaffold",
    version="0.1.0",
    description="Adds support structures (pillars and bridges) to uploaded G-code with scaffold",
    license="see the scaffold project",
    packages=["octoprint_scaffold"],
    package_data={"octoprint_scaffold": ["templates/*.jinja2"]},
    include_package_data=True,
    python_requires=">=3.7,<4",
    entry_points={"octoprint.plugin": ["scaffold = octoprint_scaffold"]},
)
