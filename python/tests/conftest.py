# Paths for the pytest suite of the Python module (ctest sets them; the defaults suit a
# run from the source tree with the build in build/).
import os
import pathlib
import sys

SOURCE_DIR = pathlib.Path(os.environ.get("MFP_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BUILD_DIR = pathlib.Path(os.environ.get("MFP_BUILD_DIR", SOURCE_DIR / "build"))
sys.path.insert(0, str(BUILD_DIR / "python"))
