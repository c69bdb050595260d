"""Write a coefficient into an icon-set manifest, touching nothing but the alpha values.

``suggest --apply`` uses this.  The manifest is not re-serialised: the YAML is
composed only to find where each ``alpha`` value sits (top level, in an
``icons:`` entry, in ``overrides:``), and those character spans are replaced.
Comments, order, quoting, spacing and line endings everywhere else stay byte
for byte.  The edited text is parsed again and must mean the same document
with only the alpha values changed, or nothing is written; an anchored alpha
(which an alias elsewhere would follow) is refused.  The file keeps its mode,
and a symbolic link keeps pointing at the edited file (its target must lie in
the project).
"""

from __future__ import annotations

import os
import stat
from pathlib import Path
from typing import Any

import yaml

from alpha_audit.errors import InputError
from alpha_audit.load.files import read_text_capped
from alpha_audit.load.yamldoc import MAX_YAML_BYTES
from alpha_audit.output import write_bytes

__all__ = ["alpha_spans", "apply_alpha", "format_alpha", "set_alpha"]


def format_alpha(alpha: float, precision: int) -> str:
    """A coefficient as YAML: at most ``precision`` decimals, no trailing zeros.

    >>> format_alpha(1.25, 3), format_alpha(2.0, 3), format_alpha(1.0, 0)
    ('1.25', '2.0', '1')
    """
    text = f"{alpha:.{precision}f}".rstrip("0")
    return text + "0" if text.endswith(".") else text


def _value(node: yaml.MappingNode, key: str) -> yaml.Node | None:
    k: yaml.Node
    v: yaml.Node
    for k, v in node.value:
        if isinstance(k, yaml.ScalarNode) and k.value == key:
            return v
    return None


def alpha_spans(text: str, path: str | Path | None = None) -> tuple[list[tuple[int, int]], bool]:
    """Character spans of every ``alpha`` value, and whether a top-level one exists.

    >>> alpha_spans("name: x\\nalpha: 1.1  # comment\\n")
    ([(15, 18)], True)
    """
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
        anchored = {
            e.start_mark.index
            for e in yaml.parse(text, Loader=yaml.SafeLoader)
            if isinstance(e, yaml.NodeEvent) and e.anchor is not None and e.start_mark is not None
        }
    except yaml.YAMLError as exc:
        raise InputError(f"cannot edit this manifest: {exc}", path=path) from exc
    if not isinstance(root, yaml.MappingNode):
        raise InputError("cannot edit this manifest: not a mapping", path=path)
    nodes: list[yaml.Node] = []
    top = _value(root, "alpha")
    if top is not None:
        nodes.append(top)
    icons = _value(root, "icons")
    if isinstance(icons, yaml.SequenceNode):
        nodes.extend(
            v
            for item in icons.value
            if isinstance(item, yaml.MappingNode)
            for v in [_value(item, "alpha")]
            if v is not None
        )
    overrides = _value(root, "overrides")
    if isinstance(overrides, yaml.MappingNode):
        nodes.extend(
            v
            for _, item in overrides.value
            if isinstance(item, yaml.MappingNode)
            for v in [_value(item, "alpha")]
            if v is not None
        )
    for node in nodes:
        if not isinstance(node, yaml.ScalarNode):
            raise InputError(
                f"cannot edit this manifest: alpha on line {node.start_mark.line + 1} "
                "is not a plain number",
                path=path,
            )
        if node.start_mark.index in anchored:
            raise InputError(
                f"cannot edit this manifest: alpha on line {node.start_mark.line + 1} carries "
                "an anchor that other values may follow; write the number itself there",
                path=path,
            )
    spans = sorted({(n.start_mark.index, n.end_mark.index) for n in nodes})
    return spans, top is not None


def set_alpha(text: str, value: str, path: str | Path | None = None) -> str:
    """``text`` with every alpha value replaced by ``value`` (and a top-level one added).

    Without a top-level ``alpha:`` the icons that use the default would keep
    1.0, so one is appended at the end of the document.

    >>> print(set_alpha("# demo\\nalpha: 1.1  # was\\noverrides:\\n  a: {alpha: 1.3}\\n", "1.25"))
    # demo
    alpha: 1.25  # was
    overrides:
      a: {alpha: 1.25}
    <BLANKLINE>
    """
    spans, has_top = alpha_spans(text, path)
    out = []
    pos = 0
    for start, end in spans:
        out.append(text[pos:start])
        out.append(value)
        pos = end
    out.append(text[pos:])
    edited = "".join(out)
    if not has_top:
        eol = "\r\n" if text.count("\r\n") * 2 > text.count("\n") else "\n"  # the file's own
        newline = "" if edited.endswith("\n") or not edited else eol
        edited += f"{newline}alpha: {value}{eol}"
    _check_meaning(text, edited, float(value), path)
    return edited


def _with_alpha(data: Any, alpha: float) -> Any:
    """``data`` (a parsed manifest) as it should read after the edit."""
    if not isinstance(data, dict):
        return data
    out = dict(data, alpha=alpha)
    if isinstance(out.get("icons"), list):
        out["icons"] = [
            dict(i, alpha=alpha) if isinstance(i, dict) and "alpha" in i else i
            for i in out["icons"]
        ]
    if isinstance(out.get("overrides"), dict):
        out["overrides"] = {
            k: dict(v, alpha=alpha) if isinstance(v, dict) and "alpha" in v else v
            for k, v in out["overrides"].items()
        }
    return out


def _check_meaning(before: str, after: str, alpha: float, path: str | Path | None) -> None:
    """Refuse an edit whose text does not parse, or means more than new alpha values."""
    try:
        expected = _with_alpha(yaml.safe_load(before), alpha)
        got = yaml.safe_load(after)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}" if mark is not None else ""
        problem = getattr(exc, "problem", None) or "a syntax error"
        raise InputError(
            "cannot edit this manifest safely: with alpha added the text would not be valid "
            f"YAML ({problem}{where}); set alpha by hand",
            path=path,
        ) from exc
    if got != expected:
        raise InputError(
            "cannot edit this manifest safely: the edit would change more than the alpha "
            "values (flow style, an indented top level or a document end marker?); "
            f"set alpha: {alpha:g} by hand",
            path=path,
        )


def apply_alpha(
    path: str | Path, alpha: float, precision: int, *, root: str | Path | None = None
) -> bool:
    """Write ``alpha`` into the manifest at ``path``; returns whether the file changed.

    The file is replaced atomically and only when its text changes, keeping
    its mode.  If ``path`` is a symbolic link, the file it points to is edited
    (the link stays) when that file lies inside ``root`` (default: the working
    directory); otherwise the edit is refused.
    """
    given = Path(path)
    target = given
    if given.is_symlink():
        try:
            target = given.resolve(strict=True)
        except (OSError, RuntimeError) as exc:  # dangling, or a loop of links
            raise InputError("is a link that leads to no file; not editing it", path=given) from exc
        base = Path(root if root is not None else Path.cwd()).resolve()
        if not target.is_relative_to(base):
            raise InputError(
                f"is a link to {target}, outside the project {base}; not editing it", path=given
            )
    text = read_text_capped(target, MAX_YAML_BYTES, InputError, "an icon-set manifest")
    edited = set_alpha(text, format_alpha(alpha, precision), given)
    if edited == text:
        return False
    mode = stat.S_IMODE(os.stat(target).st_mode)
    write_bytes(target, edited.encode("utf-8"), overwrite=True, mode=mode)
    return True
