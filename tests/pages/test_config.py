"""The ``render:`` table of ``alpha-audit.yaml`` read without a browser."""

from __future__ import annotations

from pathlib import Path

import pytest

from alpha_audit.errors import InputError
from alpha_audit.pages import FolderSource, StorybookSource
from alpha_audit.pages.config import config_from_yaml


def _config(tmp_path: Path, table: str) -> Path:
    (tmp_path / ".git").mkdir()
    for folder in ("storybook-static", "site"):
        (tmp_path / folder).mkdir()
    path = tmp_path / "alpha-audit.yaml"
    path.write_text("render:\n" + table, encoding="utf-8")
    return path


@pytest.mark.parametrize(
    ("table", "kinds"),
    [
        ("  storybook: storybook-static\n", [StorybookSource]),
        ("  pages: site\n", [FolderSource]),
        ("  storybook: [storybook-static]\n  pages: [site]\n", [StorybookSource, FolderSource]),
    ],
)
def test_a_table_names_only_the_sources_it_has(tmp_path: Path, table: str, kinds) -> None:
    config = config_from_yaml(_config(tmp_path, table))
    assert config is not None
    assert [type(s) for s in config.sources] == kinds


def test_an_empty_list_of_sources_is_refused_at_its_key(tmp_path: Path) -> None:
    with pytest.raises(InputError, match=r"alpha-audit.yaml:3: render.pages: .*empty list"):
        config_from_yaml(_config(tmp_path, "  storybook: storybook-static\n  pages: []\n"))
