"""Misuse mypy must catch (tests/api/test_typing.py): proves the annotations are seen."""

import rkcheck

result = rkcheck.verify("@rk4", order="eight")
order: str = result.energy_order
