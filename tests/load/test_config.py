"""Project configuration: discovery, keys, paths that must stay inside the project."""

from __future__ import annotations

from pathlib import Path

import pytest

from alpha_audit.errors import InputError, UsageError
from alpha_audit.load.config import find_config, load_config
from alpha_audit.rules import DEFAULT_RULES, Rule


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def test_yaml_config_found_from_a_subfolder(tmp_path: Path) -> None:
    (tmp_path / ".git").mkdir()
    cfg = write(tmp_path / "alpha-audit.yaml", "themes: [t.yaml]\niconset: icons/set.yaml\n")
    assert find_config(tmp_path / "icons" / "deep") == cfg
    write(tmp_path / "icons" / "deep" / "x", "")
    assert find_config(tmp_path / "icons" / "deep") == cfg
    config = load_config(cfg)
    assert config.themes == (tmp_path.resolve() / "t.yaml",)
    assert config.iconsets == (tmp_path.resolve() / "icons" / "set.yaml",)
    assert config.policy.rules == DEFAULT_RULES


def test_search_stops_at_the_repository_root(tmp_path: Path) -> None:
    write(tmp_path / "alpha-audit.yaml", "themes: t.yaml\n")
    (tmp_path / "repo" / ".git").mkdir(parents=True)
    assert find_config(tmp_path / "repo") is None


def test_pyproject_table(tmp_path: Path) -> None:
    (tmp_path / ".git").mkdir()
    write(tmp_path / "pyproject.toml", '[project]\nname = "x"\n')
    assert find_config(tmp_path) is None  # a pyproject without the table is not a config
    cfg = write(
        tmp_path / "pyproject.toml",
        '[tool.alpha-audit]\nthemes = ["t.yaml"]\niconsets = ["s.yaml"]\n'
        'fail-on = ["loss", "separation"]\nmin_delta_e = 5\n'
        '[[tool.alpha-audit.exempt]]\ncanvas = "sun"\nreason = "brand yellow, reviewed"\n',
    )
    assert find_config(tmp_path) == cfg
    config = load_config(cfg)
    assert config.policy.rules == {Rule.LOSS, Rule.SEPARATION}
    assert config.policy.min_delta_e == 5
    assert config.policy.exemptions[0].canvas == "sun"


def test_two_configs_in_one_folder_are_ambiguous(tmp_path: Path) -> None:
    write(tmp_path / "alpha-audit.yaml", "themes: t.yaml\n")
    write(tmp_path / ".alpha-audit.yaml", "themes: t.yaml\n")
    with pytest.raises(UsageError, match="two configurations"):
        find_config(tmp_path)


# (config text, expected message fragment): one row per failure mode.
BAD = [
    ("themse: [t.yaml]\n", "did you mean 'theme"),
    ("fail-on: [los]\n", "unknown rule 'los'"),
    ("max-loss: .nan\n", "out of range"),
    ("max-loss: '0.1'\n", "expected a contrast loss between 0 and 21"),
    ("themes: [/etc/passwd]\n", "absolute"),
    ("themes: [../outside.yaml]\n", "outside"),
    ("baseline: ../../b.json\n", "outside"),
    ("exempt: [{canvas: sun}]\n", "needs a reason"),
    ("exempt: [{reason: why}]\n", "names a canvas, an icon or both"),
    ("exempt: [{icon: x, reason: y, rule: nope}]\n", "unknown rule"),
    ("exempt: [{icon: x, reason: y, rule: seperation}]\n", "did you mean 'separation'"),
    ("theme: a.yaml\nthemes: [b.yaml]\n", "not both"),
    ("max_loss: 1\nmax-loss: 1\n", "give it once"),
    ("strict-svg: yes please\n", "true or false"),
    ("- a\n- b\n", "expected an alpha-audit configuration"),
    ("rules: {loss: fial}\n", "expected one of off, warn, fail"),
    ("rules: {los: fail}\n", "unknown rule 'los'; did you mean 'loss'"),
    ("rules: [loss]\n", "expected rules"),
    ("rules: {loss: warn, newly-failing: off, new-collision: off, confusion: off}\n", "keep one"),
    ("fail-on: [loss]\nrules: {drift: warn}\n", "not both"),
    ("visibility-floor: 0.5\n", "contrast ratio between 1 and 21"),
    ("loss-tolerance: 2\n", "relative tolerance between 0 and 1"),
    ("near-duplicate-delta-e: -1\n", "CIEDE2000 difference between 0 and 200"),
]


@pytest.mark.parametrize(("text", "message"), BAD)
def test_bad_config(tmp_path: Path, text: str, message: str) -> None:
    cfg = write(tmp_path / "alpha-audit.yaml", text)
    with pytest.raises((InputError, UsageError), match=message) as info:
        load_config(cfg)
    assert "alpha-audit.yaml" in str(info.value)


def test_bad_toml_names_the_file(tmp_path: Path) -> None:
    cfg = write(tmp_path / "pyproject.toml", "[tool.alpha-audit]\nthemes = [\n")
    with pytest.raises(InputError, match=r"pyproject\.toml.*invalid TOML"):
        load_config(cfg)
    cfg.write_text('[tool.alpha-audit]\nthemez = ["t.yaml"]\n')
    with pytest.raises(InputError, match=r"tool\.alpha-audit\.themez.*did you mean 'theme"):
        load_config(cfg)


EXEMPT_NAMES = [
    (
        "{canvas: whit, reason: ok}",
        r"exempt\[0\]\.canvas.*canvas 'whit', which no theme has; did you mean 'white'",
    ),
    (
        "{icon: alrt, reason: ok}",
        r"exempt\[0\]\.icon.*icon 'alrt', which no icon set has; did you mean 'alert'",
    ),
    ("{icon: zzz, canvas: white, reason: ok}", r"icon 'zzz', which no icon set has; check"),
]


@pytest.mark.parametrize(("entry", "message"), EXEMPT_NAMES)
@pytest.mark.parametrize("command", ["check", "suggest"])
def test_exemptions_naming_nothing_are_errors(
    tmp_path: Path, repo: Path, entry: str, message: str, command: str
) -> None:
    import re
    import shutil

    from typer.testing import CliRunner

    from alpha_audit.cli import app

    (tmp_path / ".git").mkdir()
    shutil.copytree(repo / "examples" / "vibrant", tmp_path / "vibrant")
    shutil.copy(repo / "themes" / "paper16.yaml", tmp_path / "paper16.yaml")
    write(
        tmp_path / "alpha-audit.yaml",
        f"theme: paper16.yaml\niconset: vibrant/iconset.yaml\nexempt:\n  - {entry}\n",
    )
    import os

    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        res = CliRunner().invoke(app, [command])
    finally:
        os.chdir(cwd)
    assert res.exit_code == 2, res.output
    (line,) = res.stderr.strip().splitlines()
    assert "alpha-audit.yaml" in line and re.search(message, line), line


def test_rules_set_each_rules_level_over_the_defaults(tmp_path: Path) -> None:
    cfg = write(
        tmp_path / "alpha-audit.yaml",
        "rules: {drift: warn, collision: fail, unrenderable: off, loss: warn}\n"
        "visibility-floor: 2\nloss-tolerance: 0.001\nnear-duplicate-delta-e: 2.5\n",
    )
    policy = load_config(cfg).policy
    assert policy.near_duplicate_delta_e == 2.5
    assert policy.rules == (DEFAULT_RULES - {Rule.LOSS}) | {Rule.COLLISION}
    assert Rule.DRIFT in policy.warnings and Rule.LOSS in policy.warnings
    assert Rule.UNRENDERABLE not in policy.reported
    assert (policy.visibility_floor, policy.loss_tolerance) == (2.0, 0.001)
    # YAML 1.1 reads a bare off as false: it still means off.
    write(tmp_path / "alpha-audit.yaml", "rules: {fixed-colour: off}\n")
    assert Rule.FIXED_COLOUR not in load_config(cfg).policy.reported
