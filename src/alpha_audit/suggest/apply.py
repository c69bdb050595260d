"""Write a coefficient into an icon-set manifest, touching nothing but the alpha values.

``suggest --apply`` uses this.  The manifest is not re-serialised: the YAML is
composed only to find where each ``alpha`` value sits (top level, in an
``icons:`` entry, in ``overrides:``), and those character spans are replaced.
Comments, order, quoting and spacing everywhere else stay byte for byte.
"""

from __future__ import annotations

from pathlib import Path

import yaml

from alpha_audit.errors import InputError
from alpha_audit.load.yamldoc import MAX_YAML_BYTES
from alpha_audit.output import write_text

__all__ = ["alpha_spans", "apply_alpha", "format_alpha", "set_alpha"]


def format_alpha(alpha: float, precision: int) -> str:
    """A coefficient as YAML: at most ``precision`` decimals, no trailing zeros.

    >>> format_alpha(1.25, 3), format_alpha(2.0, 3), format_alpha(1.0, 0)
    ('1.25', '2.0', '1.0')
    """
    text = f"{alpha:.{precision}f}".rstrip("0")
    return text + "0" if text.endswith(".") else text


def _value(node: yaml.MappingNode, key: str) -> yaml.Node | None:
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
        newline = "" if edited.endswith("\n") or not edited else "\n"
        edited += f"{newline}alpha: {value}\n"
    return edited


def apply_alpha(path: str | Path, alpha: float, precision: int) -> bool:
    """Write ``alpha`` into the manifest at ``path``; returns whether the file changed.

    The file is replaced atomically and only when its text changes.
    """
    target = Path(path)
    raw = target.read_bytes()
    if len(raw) > MAX_YAML_BYTES:
        raise InputError(f"larger than {MAX_YAML_BYTES} bytes; not editing it", path=target)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError("not UTF-8 text; not editing it", path=target) from exc
    if "\r" in text:
        # Keep Windows line endings: edit with \n, put \r\n back.
        edited = set_alpha(text.replace("\r\n", "\n"), format_alpha(alpha, precision), target)
        edited = edited.replace("\n", "\r\n")
    else:
        edited = set_alpha(text, format_alpha(alpha, precision), target)
    if edited == text:
        return False
    write_text(target, edited, overwrite=True)
    return True
