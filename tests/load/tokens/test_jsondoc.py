"""The line-recording JSON reader parses exactly what the standard library parses."""

from __future__ import annotations

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st

from alpha_audit.errors import InputError
from alpha_audit.load.tokens.jsondoc import parse_json

scalars = (
    st.none()
    | st.booleans()
    | st.integers()
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.text()
)
documents = st.recursive(
    scalars,
    lambda children: (
        st.lists(children, max_size=4) | st.dictionaries(st.text(max_size=5), children, max_size=4)
    ),
    max_leaves=30,
)


@given(documents, st.sampled_from([None, 0, 2]))
def test_same_data_as_json_loads(doc, indent) -> None:
    text = json.dumps(doc, indent=indent)
    assert parse_json(text).data == json.loads(text)


@given(st.dictionaries(st.text(min_size=1, max_size=5), st.integers(), min_size=1, max_size=8))
def test_each_key_is_on_its_own_line(doc) -> None:
    text = json.dumps(doc, indent=2)
    parsed = parse_json(text)
    lines = text.split("\n")
    for key in doc:
        assert json.dumps(key) in lines[parsed.lines[(key,)] - 1]


@pytest.mark.parametrize("text", ["", "{", '{"a" 1}', "[1 2]", '"\\x"', "01", "{'a': 1}", "[1,]"])
def test_invalid_json_is_an_input_error_like_json_loads(text) -> None:
    with pytest.raises(json.JSONDecodeError):
        json.loads(text)
    with pytest.raises(InputError, match="invalid JSON"):
        parse_json(text)
