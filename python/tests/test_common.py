import re

import rigid


def test_version_is_semver():
    assert re.fullmatch(r"\d+\.\d+\.\d+", rigid.__version__)


def test_error_is_a_value_error():
    assert issubclass(rigid.Error, ValueError)
