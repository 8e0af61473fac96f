"""three.js, vendored: fetched from the npm registry at build time into this package's ``three/`` folder, so that
the 3D pages inline it and open with no network.

The release is pinned (:data:`THREE_VERSION`) and so is its tarball's npm ``dist.integrity`` (sha512), checked
before anything is read from it. Only the files a page uses are kept (:data:`FILES`), with three.js's MIT
``LICENSE`` beside them and a ``VERSION`` file saying which release they are. The folder is written whole or not
at all (a temporary folder, then a rename).

The fetch path uses the standard library only: the build hook (``build_hook.py``) loads this file by its path in
pip's isolated build environment, where neither worldgen nor its dependencies are installed. Inside the package,
:class:`VendorError` is a :class:`~worldgen.core.errors.WorldgenError`; loaded alone, it is a plain exception.

``python -m worldgen.view.vendor`` fetches into the package's folder.
"""

from __future__ import annotations

import base64
import hashlib
import hmac
import io
import os
import shutil
import sys
import tarfile
import tempfile
import time
import urllib.error
import urllib.request
from pathlib import Path
from typing import Dict, Optional

try:
    from ..core.errors import WorldgenError as _ErrorBase
except ImportError:   # loaded by file path (the build hook): no package around this module
    _ErrorBase = Exception   # type: ignore[assignment,misc]

THREE_VERSION = "0.170.0"   # the last release with a single-file build/three.module.min.js
THREE_INTEGRITY = ("sha512-FQK+LEpYc0fBD+J8g6oSEyyNzjp+Q7Ks1C568WWaoMRLW+TkNNWmenWeGgJjV105Gd+p/2ql1ZcjYvNiPZBhuQ==")
DEFAULT_REGISTRY = "https://registry.npmjs.org/"
TIMEOUT = 60.0        # seconds, per attempt
ATTEMPTS = 3
MAX_TARBALL = 64 * 1024 * 1024   # three-0.170.0.tgz is 7 MB

# The names a page uses → the file in the npm tarball.
FILES = {
    "three": "package/build/three.module.min.js",
    "OrbitControls": "package/examples/jsm/controls/OrbitControls.js",
    "GLTFLoader": "package/examples/jsm/loaders/GLTFLoader.js",
    "BufferGeometryUtils": "package/examples/jsm/utils/BufferGeometryUtils.js",
    "LICENSE": "package/LICENSE",
}
FOLDER = Path(__file__).resolve().parent / "three"
VERSION_FILE = "VERSION"


class VendorError(_ErrorBase):   # type: ignore[misc,valid-type]
    """three.js could not be fetched, or what came is not what was pinned."""

    def __init__(self, message: str, hint: Optional[str] = None):
        if _ErrorBase is Exception:
            super().__init__(f"{message} ({hint})" if hint else message)
        else:
            super().__init__(message, hint=hint)


def registry() -> str:
    """The npm registry to fetch from: ``npm_config_registry`` (as npm sets it) or the public one."""
    url = os.environ.get("npm_config_registry") or os.environ.get("NPM_CONFIG_REGISTRY") or DEFAULT_REGISTRY
    return url.rstrip("/") + "/"


def tarball_url() -> str:
    return f"{registry()}three/-/three-{THREE_VERSION}.tgz"


def _disk_name(key: str) -> str:
    return FILES[key].rsplit("/", 1)[1]


def _version_text() -> str:
    return f"{THREE_VERSION}\n{THREE_INTEGRITY}\n"


def is_vendored(folder: Optional[Path] = None) -> bool:
    """Whether ``folder`` (the package's ``three/`` by default) holds every file of the pinned release."""
    folder = Path(folder) if folder is not None else FOLDER
    try:
        if (folder / VERSION_FILE).read_text(encoding="utf-8") != _version_text():
            return False
    except OSError:
        return False
    return all((folder / _disk_name(key)).is_file() for key in FILES)


def modules() -> Dict[str, str]:
    """The texts of the vendored files by the names a page uses (``three``, ``OrbitControls``, ``GLTFLoader``,
    ``BufferGeometryUtils``) and ``LICENSE``."""
    if not is_vendored(FOLDER):
        from ..core.errors import WorldgenError   # here: the build hook loads this file alone, with no package

        raise WorldgenError(
            f"three.js is missing from this installation of worldgen ({FOLDER})",
            hint=f"reinstall worldgen with pip (its build fetches three@{THREE_VERSION} from the npm registry) "
                 "or run `python -m worldgen.view.vendor`")
    return {key: (FOLDER / _disk_name(key)).read_text(encoding="utf-8") for key in FILES}


def _download(url: str, timeout: float) -> bytes:
    request = urllib.request.Request(url, headers={"User-Agent": "worldgen-vendor (python urllib)",
                                                   "Accept": "application/octet-stream"})
    last: Exception = VendorError("no attempt")
    for attempt in range(ATTEMPTS):
        if attempt:
            time.sleep(2.0 * attempt)
        try:
            with urllib.request.urlopen(request, timeout=timeout) as response:   # noqa: S310 (https or the user's)
                data = response.read(MAX_TARBALL + 1)
        except urllib.error.HTTPError as exc:
            if exc.code < 500:   # 404, 403 …: asking again gives the same answer
                raise VendorError(f"cannot fetch three.js from {url}: HTTP {exc.code} {exc.reason}",
                                  hint="check npm_config_registry") from exc
            last = exc
            continue
        except (urllib.error.URLError, OSError) as exc:   # socket.timeout is an OSError
            last = exc
            continue
        if len(data) > MAX_TARBALL:
            raise VendorError(f"cannot fetch three.js from {url}: more than {MAX_TARBALL} bytes")
        return data
    reason = getattr(last, "reason", last)
    raise VendorError(f"cannot fetch three.js from {url} ({ATTEMPTS} attempts): {reason}",
                      hint="building worldgen needs the npm registry, or a mirror of it in npm_config_registry")


def _check_integrity(data: bytes, url: str) -> None:
    algorithm, _, expected = THREE_INTEGRITY.partition("-")
    got = base64.b64encode(hashlib.new(algorithm, data).digest()).decode("ascii")
    if not hmac.compare_digest(got, expected):
        raise VendorError(f"{url} is not the pinned three@{THREE_VERSION}: its {algorithm} is {got}, "
                          f"expected {expected}", hint="a registry or proxy served other bytes; nothing was written")


def _extract(data: bytes, url: str) -> Dict[str, str]:
    texts = {}
    with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as tar:
        for key, member_name in FILES.items():
            try:
                member = tar.getmember(member_name)
            except KeyError:
                raise VendorError(f"{url} has no {member_name}") from None
            handle = tar.extractfile(member) if member.isfile() else None
            if handle is None:
                raise VendorError(f"{url}: {member_name} is not a regular file")
            text = handle.read().decode("utf-8")
            if "</script" in text.lower():
                raise VendorError(f"{member_name} of three@{THREE_VERSION} contains '</script', which would end "
                                  "the <script> element a page inlines it in",
                                  hint="pin a three.js release without it, or escape it when inlining")
            texts[key] = text
    return texts


def _write_atomically(texts: Dict[str, str], dest: Path) -> None:
    """Write the files into a temporary sibling of ``dest``, then rename it to ``dest``; an older ``dest`` is
    moved aside first and removed after."""
    dest.parent.mkdir(parents=True, exist_ok=True)
    fresh = Path(tempfile.mkdtemp(prefix=f".{dest.name}-new-", dir=str(dest.parent)))
    try:
        for key, text in texts.items():
            (fresh / _disk_name(key)).write_bytes(text.encode("utf-8"))
        (fresh / VERSION_FILE).write_bytes(_version_text().encode("utf-8"))
        fresh.chmod(0o755)   # mkdtemp made it 0700
        old = None
        if dest.exists() or dest.is_symlink():
            old = Path(tempfile.mkdtemp(prefix=f".{dest.name}-old-", dir=str(dest.parent))) / dest.name
            os.replace(str(dest), str(old))
        try:
            os.replace(str(fresh), str(dest))
        except OSError:
            if not is_vendored(dest):   # another fetch finished first: its copy is as good as ours
                raise
        if old is not None:
            shutil.rmtree(str(old.parent), ignore_errors=True)
    finally:
        if fresh.exists():
            shutil.rmtree(str(fresh), ignore_errors=True)


def fetch(dest: Optional[Path] = None, *, timeout: float = TIMEOUT) -> Path:
    """Download three@:data:`THREE_VERSION` from the npm registry, check its integrity, and write the files a
    page uses into ``dest`` (the package's ``three/`` by default). Returns ``dest``. Raises :class:`VendorError`."""
    dest = Path(dest) if dest is not None else FOLDER
    url = tarball_url()
    data = _download(url, timeout)
    _check_integrity(data, url)
    texts = _extract(data, url)
    _write_atomically(texts, dest)
    return dest


def main() -> int:
    try:
        dest = fetch()
    except (VendorError, OSError, tarfile.TarError, UnicodeDecodeError) as exc:
        print(f"worldgen: error: {' '.join(str(exc).split())}", file=sys.stderr)
        return 2
    print(f"three.js {THREE_VERSION} (with its LICENSE) fetched from {registry()} into {dest}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
