"""The wheel's layout as maturin reads it from pyproject.toml and Cargo.toml.

scripts/test.sh imports the extension module the workspace build made, not one maturin built
(scripts/py-tests.sh says why), so the names maturin packages by are checked here against the
module the tests import: a renamed module or source directory fails here, not only in a user's
`pip install ./crates/topoplex-py`.
"""

import re
import sys
from pathlib import Path

import pytest

import topoplex
import topoplex._core

CRATE = Path(__file__).resolve().parent.parent

if sys.version_info < (3, 11):
    pytest.skip("tomllib is Python 3.11's", allow_module_level=True)
import tomllib


def test_pyproject_names_the_module_the_tests_import() -> None:
    maturin = tomllib.loads((CRATE / "pyproject.toml").read_text())["tool"]["maturin"]
    assert maturin["module-name"] == topoplex._core.__name__
    source = CRATE / maturin["python-source"]
    assert Path(topoplex.__file__).resolve() == (source / "topoplex" / "__init__.py").resolve()


def test_the_rust_library_is_the_module_maturin_names() -> None:
    cargo = tomllib.loads((CRATE / "Cargo.toml").read_text())
    assert cargo["lib"]["name"] == "_core"
    assert cargo["lib"]["crate-type"] == ["cdylib"]
    # The #[pymodule] function gives the module's init symbol its name (PyInit__core).
    src = (CRATE / "src" / "lib.rs").read_text()
    assert re.search(r"#\[pymodule\]\s*fn _core\(", src)
