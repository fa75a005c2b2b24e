"""GUI start-up: ``mrm`` (an example project), ``mrm PROJECT``, ``mrm --screenshot OUT.png [PROJECT]``.

``--screenshot`` opens the window (offscreen when there is no display), waits until every view has drawn
the document — background derivations included — saves a picture of the whole window and exits. The README's
and the user guide's pictures are made this way, so they always show the real application.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from mrm.resources import default_example, examples_dir

#: The bundled example projects (package data of mrm.resources, also in an installed wheel).
EXAMPLES = examples_dir()
RESOURCES = EXAMPLES.parent


def build_parser() -> argparse.ArgumentParser:
    """The options of the GUI start-up (the headless subcommands have their own parser)."""
    p = argparse.ArgumentParser(
        prog="mrm",
        description="MR Modeler: multi-representation discrete geometry in 2D and 3D. Without a subcommand, "
        "start the desktop application (subcommands: see `mrm --help-commands`).",
    )
    p.add_argument(
        "project", nargs="?", help="project (.mrm) to open, or an image / GeoJSON / WKT file to import"
    )
    p.add_argument(
        "--screenshot", metavar="OUT.png", help="save a picture of the window once drawn, then exit"
    )
    p.add_argument("--size", default="1440x900", help="window size for --screenshot (default 1440x900)")
    p.add_argument("--layout", choices=("grid", "tabs"), help="arrange the views in a 2×2 grid or as tabs")
    p.add_argument("--tool", help="start with this tool (select, polygon, vertex, paint, erase, …)")
    p.add_argument("--select", metavar="NAME", help="select the object with this name")
    p.add_argument("--theme", choices=("system", "light", "dark"), help="colour theme")
    p.add_argument(
        "--segment", metavar="CHAIN,K", help="with --select: pick segment K of boundary chain CHAIN"
    )
    p.add_argument(
        "--view", choices=("discrete", "region", "analytical", "euclidean"), help="view to bring forward"
    )
    p.add_argument(
        "--live-preview", action="store_true", help="switch the Operations panel's live preview on (a ghost)"
    )
    p.add_argument("--timeout", type=float, default=120.0, help="seconds --screenshot waits for the views")
    return p


def run_gui(args: list[str]) -> int:
    """Start the desktop application; returns the exit status."""
    if args and args[0] in ("--help-commands",):
        from mrm.cli import build_parser as cli_parser

        cli_parser().print_help()
        return 0
    if "-h" in args or "--help" in args:
        from mrm.cli import build_parser as cli_parser

        print(build_parser().format_help())
        print("Headless subcommands (mrm COMMAND --help for each):\n")
        print(cli_parser().format_help())
        return 0
    opts = build_parser().parse_args(args)
    if opts.screenshot is None:
        from mrm.app.application import has_display

        if not has_display():
            print(
                "mrm: no display found (DISPLAY and WAYLAND_DISPLAY are unset). "
                "Start mrm from a desktop session, "
                "or render the window offscreen with `mrm --screenshot OUT.png [PROJECT]`; the headless "
                "subcommands are listed by `mrm --help-commands`.",
                file=sys.stderr,
            )
            return 2
    project = Path(opts.project) if opts.project else None
    if project is not None and not project.exists():
        print(f"mrm: error: {project}: no such file", file=sys.stderr)
        return 2
    t0 = time.perf_counter()
    from mrm.app.application import create_application, has_display, theme_controller

    app = create_application([sys.argv[0]], offscreen=opts.screenshot is not None and not has_display())
    from PySide6 import QtCore

    from mrm.app.main_window import MainWindow
    from mrm.app.settings import Preferences, make_settings

    if opts.screenshot is not None:
        # Pictures must not depend on this user's preferences (or change them): fresh settings.
        import tempfile

        prefs = Preferences(make_settings(Path(tempfile.mkdtemp(prefix="mrm-shot-")) / "mrm.ini"))
    else:
        prefs = Preferences(make_settings())
    theme_controller().set_preference(opts.theme or prefs.theme)
    win = MainWindow(prefs)
    if opts.layout:
        win.set_layout(opts.layout)
    if opts.screenshot is not None:
        try:
            w, h = (int(v) for v in opts.size.lower().split("x"))
        except ValueError:
            print(f"mrm: error: --size must look like 1440x900, got {opts.size!r}", file=sys.stderr)
            return 2
        win.resize(w, h)
    else:
        win.restore_window_state()
    if opts.tool and opts.tool not in win.tools.tools:
        print(
            f"mrm: error: unknown tool {opts.tool!r}; choose from {', '.join(win.tools.tools)}",
            file=sys.stderr,
        )
        return 2
    win.show()

    def load() -> bool:
        """Open what was asked for (or recover a crashed session's work, or the example)."""
        opened = True
        if project is not None:
            opened = win.files.open(project, ask=False)
        elif opts.screenshot is not None or not win.files.check_orphans():
            example = default_example()
            if example is not None:
                opened = win.files.open(example, ask=False)
        if opts.select:
            found = win.doc.find(opts.select)
            if found:
                win.doc.set_selection([found[0].id])
                if opts.segment:
                    chain, k = (int(v) for v in opts.segment.split(","))
                    win.scene.select_segment(found[0].id, chain, k)
        if opts.tool:
            win.tools.set_tool(opts.tool)
        if opts.live_preview:
            win.operations.live.setChecked(True)
        if opts.view:
            win.views.show_view(win.views.by_name(opts.view))
        win.fit_all()
        return opened

    from mrm.app.startup import prepare_then, when_exposed

    if opts.screenshot is None:
        # The window paints first, then the document loads (on a fresh install while the kernels compile on
        # a worker, with progress in the status bar): it is on screen and usable as soon as possible.
        win.show_message(f"ready in {time.perf_counter() - t0:.2f} s", 4000)
        when_exposed(win, lambda: prepare_then(win, load))
        try:
            return int(app.exec())
        finally:
            from mrm.app.processes import close_pool

            close_pool()
    loaded: list[bool] = []
    prepare_then(win, lambda: loaded.append(load()), open_at_once=False)  # the finished drawing
    deadline = time.monotonic() + max(opts.timeout, 600.0)  # a cold compile takes minutes on a slow box
    while not loaded and time.monotonic() < deadline:
        QtCore.QCoreApplication.processEvents(QtCore.QEventLoop.ProcessEventsFlag.AllEvents, 50)
        time.sleep(0.01)
    if not (loaded and loaded[0]) and project is not None:
        print(f"mrm: error: cannot open {project}", file=sys.stderr)
        return 2
    return screenshot(app, win, Path(opts.screenshot), opts.timeout)


def wait_until_drawn(app: object, win: object, timeout: float) -> bool:
    """Process events until the window has drawn everything (True) or ``timeout`` seconds passed."""
    from PySide6 import QtCore, QtWidgets

    deadline = time.monotonic() + timeout
    settled = 0
    while time.monotonic() < deadline:
        QtWidgets.QApplication.processEvents(QtCore.QEventLoop.ProcessEventsFlag.AllEvents, 50)
        if win.is_drawn() and not win.runner.is_busy():  # type: ignore[attr-defined]
            settled += 1
            if settled >= 3:  # a few quiet turns: layouts and deferred fits have run too
                return True
        else:
            settled = 0
            time.sleep(0.01)
    return False


def screenshot(app: object, win: object, out: Path, timeout: float) -> int:
    """Save a picture of the whole window once every view is drawn; exit status 0, or 2 on failure."""
    from PySide6 import QtWidgets

    if not wait_until_drawn(app, win, timeout):
        print(
            f"mrm: warning: the views were not all drawn after {timeout:g} s; saving anyway", file=sys.stderr
        )
    win.fit_all()  # type: ignore[attr-defined]
    wait_until_drawn(app, win, timeout)
    pixmap = win.grab()  # type: ignore[attr-defined]
    out.parent.mkdir(parents=True, exist_ok=True)
    ok = pixmap.save(str(out), "PNG")
    win.close_now()  # type: ignore[attr-defined]
    QtWidgets.QApplication.processEvents()
    if not ok:
        print(f"mrm: error: cannot write {out}", file=sys.stderr)
        return 2
    print(str(out))
    return 0
