"""The build hook (hatchling's ``custom`` hook, configured in pyproject.toml): vendors three.js before a wheel, an
editable install or an sdist is built, and makes the gitignored ``worldgen/view/three/`` part of what is built.

It loads ``vendor.py`` by its file path: it runs in pip's isolated build environment, where worldgen's package and
dependencies cannot be imported. It is left out of the wheel (pyproject.toml excludes it) but kept in the sdist,
whose wheel build runs it again (and finds the files already there).
"""

from __future__ import annotations

import importlib.util
from pathlib import Path
from typing import Any, Dict

from hatchling.builders.hooks.plugin.interface import BuildHookInterface

VENDOR = Path("worldgen") / "view" / "vendor.py"
FOLDER = "worldgen/view/three"


def load_vendor(root: Path) -> Any:
    """``worldgen/view/vendor.py`` under ``root`` as a module of its own (not ``worldgen.view.vendor``)."""
    path = root / VENDOR
    spec = importlib.util.spec_from_file_location("_worldgen_build_vendor", str(path))
    if spec is None or spec.loader is None:
        raise RuntimeError(f"cannot load {path}")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class VendorThreeHook(BuildHookInterface):
    """Fetch three.js into the source tree when it is missing, and include it although git ignores it."""

    PLUGIN_NAME = "custom"

    def initialize(self, version: str, build_data: Dict[str, Any]) -> None:
        root = Path(self.root)
        vendor = load_vendor(root)
        folder = root / FOLDER
        if not vendor.is_vendored(folder):
            self.app.display_info(f"worldgen: fetching three@{vendor.THREE_VERSION} from {vendor.tarball_url()}")
            vendor.fetch(folder)
        # An editable install (version "editable") reads the source tree, where the files now are; a wheel and an
        # sdist take them in as artifacts (files git ignores but a build ships).
        build_data["artifacts"].append(f"/{FOLDER}/")
