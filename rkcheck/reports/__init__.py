"""Renderings of results for people (rich text, Markdown, charts) and machines (JSON,
CSV, JUnit, GitHub annotations).

Takes: the plain data that the stages above return.  Gives: text.  Reports never compute
mathematics themselves.

May import: every stage except :mod:`rkcheck.cli`.
"""
