"""What the Python tests share: the command line, the sources and two scenes."""
import os
import subprocess
import sys

import pytest

BIN = os.environ["SOFTTRACE_BIN"]
SRC = os.environ["SOFTTRACE_SOURCE_DIR"]
TWO_BLOBS = os.path.join(SRC, "examples", "consumer", "two_blobs.json")


def fnv1a64(data: bytes) -> int:
    """64-bit FNV-1a, as the EXR header's softtrace/sceneHash (in hex)."""
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return h


@pytest.fixture(scope="session")
def blob_scene(tmp_path_factory):
    """tools/blob_scene.py's 1000 blobs: a field slow enough to interrupt."""
    path = tmp_path_factory.mktemp("blobs") / "blobs1000.json"
    subprocess.run([sys.executable, os.path.join(SRC, "tools", "blob_scene.py"), "1000",
                    "-o", str(path)], check=True)
    return str(path)
