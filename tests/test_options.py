"""One validation layer for options: the file's [check], [tool.rkcheck], the
API and the command line accept the same ranges and refuse with the same one-line shape."""

from __future__ import annotations

import pytest
from support.clirun import run_cli

from rkcheck.errors import UserError
from rkcheck.options import DPS_RANGE, MAX_ORDER, CheckOptions, validate_check_table

MIDPOINT = '[tableau]\nA = [["1/2"]]\nb = [1]\n'


@pytest.mark.parametrize(
    "key, value, message",
    [
        ("order", 0, f"expected an integer from 1 to {MAX_ORDER}, got 0"),
        ("order", MAX_ORDER + 1, f"expected an integer from 1 to {MAX_ORDER}, got {MAX_ORDER + 1}"),
        ("order", 10**40, f"expected an integer from 1 to {MAX_ORDER}, got an integer of about 41 digits"),
        ("order", 10**4000, f"expected an integer from 1 to {MAX_ORDER}, got an integer of about 4001 digits"),
        ("order", "x" * 100, f"expected an integer from 1 to {MAX_ORDER}, got '{'x' * 36}..."),
        ("order", True, f"expected an integer from 1 to {MAX_ORDER}, got True"),
        ("dps", 1, f"expected an integer from {DPS_RANGE[0]} to {DPS_RANGE[1]}, got 1"),
        ("dps", 10_000_000, f"expected an integer from {DPS_RANGE[0]} to {DPS_RANGE[1]}, got 10000000"),
        ("dps", "1e7", f"expected an integer from {DPS_RANGE[0]} to {DPS_RANGE[1]}, got '1e7'"),
        ("degree", 0, "expected a positive integer or 'none', got 0"),
        ("degree", 201, "expected a degree from 1 to 200 or 'none', got 201"),
        ("degree", "\u00b2", "expected a positive integer or 'none', got '\u00b2'"),  # str.isdigit() is true of it
        ("degree", "\u0663", "expected a positive integer or 'none', got '\u0663'"),
        ("decimals", "round", "expected one of 'auto', 'rounded', 'float64', 'exact', got 'round'"),
    ],
)
def test_the_same_ranges_from_every_source(key, value, message):
    with pytest.raises(UserError) as err:
        validate_check_table({key: value})
    assert str(err.value) == f"check.{key}: {message}"
    with pytest.raises(UserError) as err:
        CheckOptions(**{key: value})
    assert str(err.value) == f"{key}: {message}"


def test_unknown_keys_name_the_nearest_valid_one():
    with pytest.raises(UserError) as err:
        validate_check_table({"ordr": 4})
    assert str(err.value) == "check.ordr: unknown key (did you mean 'order'?) (known: degree, order, dps, decimals, require)"
    with pytest.raises(UserError) as err:
        validate_check_table({"zzz": 4})
    assert "did you mean" not in str(err.value)


@pytest.mark.parametrize(
    "check, message",
    [
        ("order = 31", "check.order: expected an integer from 1 to 30, got 31"),
        ("dps = 10000000", "check.dps: expected an integer from 10 to 5000, got 10000000"),
        ("dps = 1e7", "check.dps: expected an integer from 10 to 5000, got '1e7'"),
        ("dps = 1", "check.dps: expected an integer from 10 to 5000, got 1"),
        ("degre = 4", "check.degre: unknown key (did you mean 'degree'?)"),
    ],
)
def test_file_check_table_is_refused_like_the_command_line(tmp_path, capsys, check, message):
    f = tmp_path / "t.toml"
    f.write_text(MIDPOINT + "[check]\n" + check + "\n", encoding="utf-8")
    r = run_cli(capsys, "verify", str(f))
    assert r.code == 2
    assert r.err.count("\n") == 1 and "Traceback" not in r.err
    assert r.err.startswith(f"rkcheck: error: {f}: {message}")


def test_command_line_refuses_the_same_order_and_dps(tmp_path, capsys):
    f = tmp_path / "t.toml"
    f.write_text(MIDPOINT, encoding="utf-8")
    for args in (["--order", str(MAX_ORDER + 1)], ["--dps", "1"], ["--dps", str(DPS_RANGE[1] + 1)],
                 ["--degree", "5001"]):
        r = run_cli(capsys, "verify", str(f), *args)
        assert r.code == 2 and r.err.count("\n") == 1, args


@pytest.mark.parametrize(
    "claim, message",
    [
        ("classical_order = 100000", "expect.classical_order: expected an integer from 0 to 14, got 100000 (the limit "
         "MAX_CLASSICAL_CLAIM: judging it checks every rooted tree of one more vertex)"),
        ("energy_order = {degree = 2, value = 100000}",
         "expect.energy_order.value: expected an integer from 1 to 29, got 100000"),
        ("energy_order = {degree = 2, value = 3, order = 99999}",
         "expect.energy_order.order: expected an integer from 1 to 30, got 99999"),
    ],
)
def test_claims_cannot_ask_for_orders_past_the_limit(tmp_path, capsys, claim, message):
    # judging a claim of order N checks order N + 1: energy claims are bounded by MAX_ORDER - 1,
    # classical ones by MAX_CLASSICAL_CLAIM (the rooted trees of N + 1 vertices)
    f = tmp_path / "t.toml"
    f.write_text(MIDPOINT + "[expect]\n" + claim + "\n", encoding="utf-8")
    r = run_cli(capsys, "verify", str(f))
    assert r.code == 2 and r.err == f"rkcheck: error: {f}: {message}\n"
