"""An explicit tag on a bad scalar is an input error that names the key, like every other.

``alpha: !!float ""`` said only "i.yaml:2: cannot read value '' as float": no
key, and nothing about what to write instead.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from alpha_audit.errors import InputError
from alpha_audit.load.yamldoc import load_yaml


@pytest.mark.parametrize(
    ("text", "key", "line"),
    [
        ('icons: svg/*.svg\nalpha: !!float ""\n', "alpha", 2),
        ('canvases:\n  - {name: a, color: !!bool ""}\n', "canvases[0].color", 2),
        ('sizes: [24, !!int "z"]\n', "sizes[1]", 1),
    ],
)
def test_bad_tagged_scalar_names_file_line_and_key(
    tmp_path: Path, text: str, key: str, line: int
) -> None:
    path = tmp_path / "i.yaml"
    path.write_text(text)
    with pytest.raises(InputError) as info:
        load_yaml(path)
    message = str(info.value)
    assert f"i.yaml:{line}: {key}: cannot read value" in message
    assert "plain value" in message and "\n" not in message
