"""States a page is audited in: Storybook globals, ``prefers-color-scheme``, ``<html>`` marks.

A :class:`State` combines any of the three; :func:`state_matrix` builds the
product of sweeps (``globals theme: [light, dark]`` x ``color-scheme: [light,
dark]`` gives four states), each audited for every source.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from urllib.parse import quote

from alpha_audit.browser import ColorScheme

__all__ = ["DEFAULT_STATE", "State", "globals_param", "state_matrix"]


@dataclass(frozen=True)
class State:
    """One way of showing a page.

    ``globals`` are Storybook globals (``globals=theme:dark`` in the story's
    URL); ``color_scheme`` is emulated ``prefers-color-scheme``;
    ``attributes`` and ``classes`` are set on ``<html>`` once the page has
    loaded (``data-theme="dark"``, ``class="dark"``).
    """

    name: str
    globals: tuple[tuple[str, str], ...] = ()
    color_scheme: ColorScheme | None = None
    attributes: tuple[tuple[str, str], ...] = ()
    classes: tuple[str, ...] = ()

    @property
    def marks_html(self) -> bool:
        """Whether the state changes ``<html>`` after loading."""
        return bool(self.attributes or self.classes)


DEFAULT_STATE = State("default")


def globals_param(values: Sequence[tuple[str, str]]) -> str:
    """Storybook's ``globals`` URL parameter: ``key:value`` pairs joined by ``;``.

    >>> globals_param([("theme", "dark"), ("density", "compact")])
    'theme:dark;density:compact'
    """
    return ";".join(f"{quote(k, safe='')}:{quote(v, safe='')}" for k, v in values)


def _label(parts: Sequence[str]) -> str:
    return ", ".join(parts) if parts else DEFAULT_STATE.name


def state_matrix(
    globals_values: Sequence[Sequence[tuple[str, str]]] = (),
    color_schemes: Sequence[ColorScheme] = (),
    attributes: Sequence[tuple[str, str]] = (),
    classes: Sequence[str] = (),
) -> tuple[State, ...]:
    """Every combination of the sweeps given; one default state when none is.

    ``globals_values`` lists alternatives (each a set of globals);
    ``attributes`` lists ``(name, value)`` alternatives for ``<html>``, and
    ``classes`` alternative classes (``""`` for none).

    >>> [s.name for s in state_matrix([[("theme", "light")], [("theme", "dark")]], ["dark"])]
    ['theme:light, color-scheme:dark', 'theme:dark, color-scheme:dark']
    """
    dimensions: list[list[tuple[str, dict[str, object]]]] = []
    if globals_values:
        dimensions.append(
            [(globals_param(g).replace(";", " "), {"globals": tuple(g)}) for g in globals_values]
        )
    if color_schemes:
        dimensions.append([(f"color-scheme:{c}", {"color_scheme": c}) for c in color_schemes])
    if attributes:
        dimensions.append([(f"{n}={v}", {"attributes": ((n, v),)}) for n, v in attributes])
    if classes:
        dimensions.append([(f"class:{c}" if c else "class:none", {"classes": (c,) if c else ()})
                           for c in classes])  # fmt: skip
    states = []
    for combination in itertools.product(*dimensions):
        fields: dict[str, object] = {}
        for _, part in combination:
            fields.update(part)
        states.append(State(_label([name for name, _ in combination]), **fields))  # type: ignore[arg-type]  # the fields each dimension sets are State's own
    return tuple(states) or (DEFAULT_STATE,)
