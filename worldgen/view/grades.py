"""A class's grades as a folder of pages (``validate|run FOLDER --html DIR``): ``index.html`` (:mod:`.index`), a row
per submission, linking to ``pages/NAME.html``, each submission's own 3D page — its world with the findings
(``validate``), or its run replayed (``run``). The pages share one three.js, ``pages/three.js``
(:func:`~worldgen.view.page.library_script`): 40 pages of a class room make 2.4 MB, not 36 MB.

The folder is written all or nothing (:func:`worldgen.core.fsio.write_tree`). Like ``--junit``, it replaces the
report a previous run wrote there, and nothing else: a folder that is not empty and holds no worldgen index is
refused.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Callable, Sequence

from ..check.report import Result
from .page import Panel, library_script, render_page, replay_page, world_source
from ..core.errors import InputError, WorldgenError
from ..core.fsio import write_tree
from ..spec.model import ROBOT_MODELS
from .index import index_page, index_rows
from .replay import run_replay
from .scene_data import read_source, world_data

INDEX = "index.html"
PAGES = "pages"
MARKER = '<meta name="worldgen-report" content="index">'   # only the index of a report has it
BACK = f"../{INDEX}"   # a submission's page's link to the index
LIBRARY = "three.js"   # the pages' shared three.js, beside them in pages/ (a submission's page is NAME.html)


def page_names(names: Sequence[str]) -> list[str]:
    """A file name under ``pages/`` for each name, readable and unique (``a/b c.yaml`` → ``a_b_c.yaml.html``)."""
    out, taken = [], set()
    for name in names:
        stem = re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip("._") or "submission"
        stem = stem[-100:]
        candidate, n = stem, 2
        while candidate.lower() in taken:
            candidate, n = f"{stem}_{n}", n + 1
        taken.add(candidate.lower())
        out.append(f"{PAGES}/{candidate}.html")
    return out


def panel(result: Result) -> dict:
    """What a submission's page shows beside the world: its verdict, metrics (the index's) and findings."""
    row = index_rows([result])[0]
    text = {"ok": "pass", "warn": "pass, with warnings", "FAIL": "fail"}[result.verdict]
    graded = row["task"] or ("run" if row["kind"] == "run" else "validate")
    return {"verdict": result.verdict, "verdict_text": f"{graded}: {text}",
            "metrics": [(m["label"], m["text"]) for m in row["metrics"]], "findings": result.sorted_findings()}


def check_report_folder(folder: Path) -> None:
    """Refuse (InputError) a ``--html`` folder that holds anything but a report an earlier ``--html`` wrote (its
    index, with :data:`MARKER`, ``pages/*.html`` and ``pages/three.js``): the folder is replaced as a whole."""
    if not folder.exists() and not folder.is_symlink():
        if folder.suffix.lower() in (".html", ".htm"):
            raise InputError(f"--html here writes a folder (its index.html, and a page for each file), and "
                             f"{folder.name} names a page", path=folder,
                             hint=f"give a folder name such as {folder.with_suffix('').name or 'report'}/")
        return
    if not folder.is_dir() or folder.is_symlink():
        raise InputError(f"cannot write the report folder {folder}: it is a file", hint="give --html a folder name")
    entries = list(folder.iterdir())
    if not entries:
        return
    index = folder / INDEX
    ours = index.is_file() and MARKER in index.read_text(encoding="utf-8", errors="replace")[:4000]
    pages = folder / PAGES
    others = [e for e in entries if e.name not in (INDEX, PAGES)]
    if pages.exists():
        if pages.is_dir():
            others += [e for e in pages.iterdir() if not (e.is_file() and (e.suffix == ".html" or e.name == LIBRARY))]
        else:
            others.append(pages)
    if not ours or others:
        raise InputError(f"{folder} holds files that are not a worldgen report"
                         + (f" ({others[0].name}, …)" if others else ""),
                         hint="give --html a new folder, or one an earlier --html wrote")


def write_report(folder: Path, results: list[Result], page_of: Callable[[Result], bytes | None], title: str) -> Path:
    """The index and every page ``page_of`` gives (None: a row without a page), written as ``folder``."""
    files: dict[str, bytes] = {}
    hrefs: list[str | None] = []
    for result, name in zip(results, page_names([r.name for r in results])):
        page = _page_or_none(page_of, result)
        if page is not None:
            files[name] = page
        hrefs.append(name if page is not None else None)
    if files:
        files[f"{PAGES}/{LIBRARY}"] = library_script()
    files[INDEX] = index_page(index_rows(results, hrefs), title)   # it counts the verdicts itself, once
    return write_tree(folder, files, force=True)


def _page_or_none(page_of, result: Result) -> bytes | None:
    """``page_of(result)``; a page that cannot be made (a world gone since, a bug of ours) is a row without a
    link and one warning line, never the whole report lost."""
    try:
        return page_of(result)
    except Exception as err:   # noqa: BLE001  (any failure of one page)
        import sys

        first = (str(err).splitlines() or [type(err).__name__])[0]
        print(f"worldgen: warning: no page for {result.name}: {first}", file=sys.stderr)
        return None


def validate_page(result: Result, model_paths=()) -> bytes | None:
    """A validated file's page: its world (a world file, a spec, or the world a launch file starts) from the spawn
    pose checked, with the findings; None for a row with no world to draw (a package's own check, a file that
    could not be read)."""
    import dataclasses

    path = Path(result.path)
    if not path.is_file():
        return None
    try:
        source = read_source(path, model_paths)
    except WorldgenError:
        return None
    known = result.robot in ROBOT_MODELS or Path(result.robot).is_file()   # a model, or --robot FILE
    source = dataclasses.replace(source, spawn=result.spawn or source.spawn,
                                 robot=result.robot if known else source.robot)
    return render_page(world_data(source), Panel(result.name, source.subtitle, back=BACK, **panel(result)),
                       library=LIBRARY)


def run_page(result: Result, world, trace: dict, title: str | None = None, back: str | None = None) -> bytes:
    """A graded run's page: the world it ran in (``world``: :class:`worldgen.bridge.world.World`, or anything with
    its ``path``, ``scene``, ``spawn`` and ``robot``), the robot replayed along its trace, the verdict and
    findings; ``back``: a link to the index (:data:`BACK` in a report folder), and then three.js is the folder's
    shared :data:`LIBRARY`, not inlined: without it, the page is one self-contained file."""
    source = world_source(world.path, world.scene, world.spawn, world.robot)
    return replay_page(source, run_replay(trace), Panel(title or result.name, f"in {Path(str(world.path)).name}",
                                                        back=back, **panel(result)),
                       library=LIBRARY if back is not None else None)
