"""The report's JSON text: the same value as Python's encoder gives (read back by
``json.loads``, the independent route), with rows and arrays of numbers one to a line."""

import json

from hypothesis import given
from hypothesis import strategies as st

from rkcheck.reports.jsontext import dumps

scalars = st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text()
values = st.recursive(scalars, lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(), inner,
                                                                                           max_size=4), max_leaves=30)


@given(values)
def test_reads_back_as_the_same_value(doc):
    assert json.loads(dumps(doc)) == json.loads(json.dumps(doc))


def test_keys_that_are_not_strings_are_written_as_json_writes_them():
    doc = {3: "a", 2.5: "b", True: "c", None: "d"}
    assert json.loads(dumps(doc)) == json.loads(json.dumps(doc))


def test_rows_and_arrays_of_numbers_take_one_line_each():
    doc = {"conditions": [{"id": "1,2,2", "level_sequence": [1, 2, 2], "bracket": "[τ²]"},
                          {"id": "1,2,3", "level_sequence": [1, 2, 3], "bracket": "[[τ]]"}],
           "warnings": ["first", "second"]}
    lines = dumps(doc).splitlines()
    assert '    {"id": "1,2,2", "level_sequence": [1, 2, 2], "bracket": "[τ²]"},' in lines
    assert '    "first",' in lines  # strings keep a line each
    assert lines[0] == "{" and lines[-1] == "}"


@given(st.lists(st.dictionaries(st.text(), scalars, max_size=3), max_size=6), st.integers(1, 50))
def test_an_iterator_is_written_as_its_list_in_pieces_of_any_size(rows, size):
    from rkcheck.reports.jsontext import chunks

    text = "".join(chunks({"conditions": iter(rows), "after": [1, 2]}, size=size))
    assert text == dumps({"conditions": rows, "after": [1, 2]})
    assert json.loads(text) == {"conditions": rows, "after": [1, 2]}
