import subprocess
import sys


def test_model_imports_neither_pyside6_nor_pyqtgraph():
    """Importing every model module must not load Qt: the model runs headless and in worker processes."""
    code = (
        "import importlib, pkgutil, sys, mrm\n"
        "for m in pkgutil.walk_packages(mrm.__path__, 'mrm.'):\n"
        "    if m.name.split('.')[1] not in ('app', 'views', '__main__'):\n"
        "        importlib.import_module(m.name)\n"
        "bad = sorted(k for k in sys.modules if k.split('.')[0] in ('PySide6', 'pyqtgraph', 'shiboken6'))\n"
        "print(','.join(bad))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"model imported Qt modules: {out.stdout.strip()}"
