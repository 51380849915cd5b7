# Shared fixtures: the source tree's scenes and the C++ programs the ctest entry names.
import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("SUPERMODAL_SOURCE_DIR", pathlib.Path(__file__).parents[2]))


@pytest.fixture
def scenes():
    return SOURCE_DIR


@pytest.fixture
def program():
    def find(variable):
        path = os.environ.get(variable)
        if not path or not os.path.exists(path):
            pytest.fail(f"{variable} is not set to a built program (run through ctest)")
        return path

    return find
