"""The warm-up stamp hashes every kernel module; an edited kernel makes `python -m mrm.warmup` compile."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from mrm import warmup

ROOT = Path(warmup.__file__).resolve().parent


def test_every_njit_module_is_in_the_stamp() -> None:
    # A module with @njit kernels that the stamp does not hash would keep a stale stamp "current".
    with_kernels = set()
    for p in ROOT.rglob("*.py"):
        if re.search(r"^\s*@njit\b", p.read_text(encoding="utf-8"), re.MULTILINE):
            with_kernels.add(p.relative_to(ROOT).as_posix())
    assert with_kernels, "no kernel module found: the scan is broken"
    assert with_kernels <= set(warmup.KERNEL_MODULES), sorted(with_kernels - set(warmup.KERNEL_MODULES))


@pytest.fixture
def fake_root(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A copy of the kernel modules with a numba index beside each, as after a warm-up."""
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    for rel in warmup.KERNEL_MODULES:
        src = ROOT / rel
        dst = tmp_path / rel
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src, dst)
        (dst.parent / "__pycache__").mkdir(exist_ok=True)
    _index_files(tmp_path)
    monkeypatch.setattr(warmup, "_package_root", lambda: tmp_path)
    return tmp_path


def _index_files(root: Path) -> None:
    # What numba leaves after compiling: an index beside each kernel module.
    for rel in warmup.KERNEL_MODULES:
        p = root / rel
        (p.parent / "__pycache__" / f"{p.stem}.kernel-1.py311.nbi").write_bytes(b"")


def _fake_warm_up(root: Path, runs: list[int]) -> object:
    # warm_up without compiling: the cache files and the stamp it leaves behind.
    def fake(progress: object = None) -> None:
        runs.append(1)
        _index_files(root)
        warmup._write_stamp()

    return fake


@pytest.fixture
def warm_ups(fake_root: Path, monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The warm-up replaced by :func:`_fake_warm_up`; the list grows by one each time it runs."""
    runs: list[int] = []
    monkeypatch.setattr(warmup, "warm_up", _fake_warm_up(fake_root, runs))
    return runs


def test_warmup_compiles_again_after_a_kernel_module_is_edited(
    fake_root: Path, warm_ups: list[int], capsys: pytest.CaptureFixture[str]
) -> None:
    runs = warm_ups
    warmup._write_stamp()
    assert warmup.main([]) == 0
    assert runs == []
    assert "already compiled" in capsys.readouterr().out
    # edit one kernel module: numba recompiles it, so the warm-up must run again
    p = fake_root / "geometry" / "reconstruct/_merge.py"
    p.write_text(p.read_text(encoding="utf-8") + "\n# edited\n", encoding="utf-8")
    assert warmup.main([]) == 0
    assert runs == [1]
    assert "already compiled" not in capsys.readouterr().out
    # and after that warm-up the stamp is current again
    assert warmup.main([]) == 0
    assert runs == [1]


def test_a_current_stamp_without_the_cache_files_is_cold(
    fake_root: Path, warm_ups: list[int], capsys: pytest.CaptureFixture[str]
) -> None:
    # The cache files deleted by hand and the stamp left: "already compiled" would be a lie, and every
    # kernel would compile on first use instead (a minute, with no notice).
    runs = warm_ups
    warmup._write_stamp()
    assert warmup.is_warm()
    for f in fake_root.rglob("*.nbi"):
        f.unlink()
    assert not warmup.is_warm()
    assert warmup.main(["--check"]) == 1
    assert warmup.main([]) == 0
    assert runs == [1]
    assert "already compiled" not in capsys.readouterr().out
    assert warmup.is_warm()  # the warm-up left its cache files


def test_an_unreadable_stamp_is_cold(fake_root: Path) -> None:
    warmup.stamp_path().parent.mkdir(parents=True, exist_ok=True)
    warmup.stamp_path().write_text("{not json", encoding="utf-8")
    assert not warmup.is_warm()
    assert warmup.main(["--check"]) == 1


def test_a_warm_up_after_an_edit_drops_every_cached_kernel_first(
    fake_root: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # numba would keep a caller's cached code when only its callee's module changed: after an edit the
    # warm-up removes the cached code of every kernel module (not only the edited one) before compiling.
    seen: list[list[Path]] = []
    monkeypatch.setattr(
        warmup,
        "warm_up",
        lambda progress=None: seen.append(sorted(fake_root.rglob("*.nb[ic]"))) or warmup._write_stamp(),
    )
    warmup._write_stamp()
    p = fake_root / "geometry" / "reconstruct/_minlink.py"
    p.write_text(p.read_text(encoding="utf-8") + "\n# edited\n", encoding="utf-8")
    before = sorted(fake_root.rglob("*.nbi"))
    assert len(before) == len(warmup.KERNEL_MODULES)
    assert warmup.main([]) == 0
    assert seen == [[]]  # nothing cached was left when the warm-up compiled
    unrelated = fake_root / "geometry" / "__pycache__" / "other.cpython-311.pyc"
    unrelated.write_bytes(b"")
    p.write_text(p.read_text(encoding="utf-8") + "\n# edited again\n", encoding="utf-8")
    assert warmup.main([]) == 0
    assert unrelated.exists()  # only numba's kernel files go


def test_the_warm_up_sets_reach_every_path_of_r(monkeypatch: pytest.MonkeyPatch) -> None:
    # A kernel the warm-up never calls compiles for the first user who needs it (a minute's wait, in a
    # worker): the warm-up's pixel sets must hold a ring R computes and one it copies from its twin
    # (ADR 0036), so that fill_twins is compiled too.
    import mrm.geometry.reconstruct as rec

    fill = rec._tw.fill_twins
    calls = []

    def counted(*args: object) -> object:
        calls.append(1)
        return fill(*args)

    monkeypatch.setattr(rec._tw, "fill_twins", counted)
    for ps in warmup._pixel_sets():
        rec.reconstruct(ps)  # type: ignore[arg-type]
    assert calls
