"""render(outputs=...) on a full disk and to a FIFO: as `softtrace render -o`, nothing is committed
that is not complete on the disk, no existing file is lost, no temporary file is left, and the
render raises. (A small EXR once went out as a 0-byte file over the old one, without an error.)"""
import ctypes
import errno
import os
import stat

import pytest
from conftest import TWO_BLOBS

import softtrace


@pytest.fixture
def full_disk(tmp_path):
    """A 64 KiB tmpfs holding old.exr and old.png ("old"), the rest filled. Mounting needs root
    (CAP_SYS_ADMIN): the test skips elsewhere, as tests/renderer/cli/test_output_faults.cpp's do."""
    disk = tmp_path / "disk"
    disk.mkdir()
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.mount(b"tmpfs", bytes(disk), b"tmpfs", 0, b"size=64k,mode=0755") != 0:
        pytest.skip("cannot mount a tmpfs: " + os.strerror(ctypes.get_errno()))
    try:
        (disk / "old.exr").write_text("old")
        (disk / "old.png").write_text("old")
        with open(disk / "filler", "wb", buffering=0) as filler:
            try:
                for _ in range(64):
                    filler.write(b"x" * 4096)
            except OSError as e:
                assert e.errno == errno.ENOSPC
        yield disk
    finally:
        libc.umount2(bytes(disk), 2)  # MNT_DETACH


def test_a_full_disk_commits_nothing_and_raises(full_disk):
    scene = softtrace.load_scene(TWO_BLOBS)
    for outputs in (["old.exr"], ["old.exr", "old.png"]):
        with pytest.raises(RuntimeError, match="No space left on device"):
            softtrace.render(scene, width=8, height=6, outputs=[full_disk / o for o in outputs])
    assert (full_disk / "old.exr").read_text() == "old"
    assert (full_disk / "old.png").read_text() == "old"
    assert sorted(os.listdir(full_disk)) == ["filler", "old.exr", "old.png"]


def test_a_fifo_output_is_refused(tmp_path):
    fifo = tmp_path / "out.exr"
    os.mkfifo(fifo)
    scene = softtrace.load_scene(TWO_BLOBS)
    with pytest.raises(ValueError, match="is a FIFO; outputs must be regular files or links"):
        softtrace.render(scene, width=8, height=6, outputs=[fifo])
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert os.listdir(tmp_path) == ["out.exr"]
