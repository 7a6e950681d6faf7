"""Renderings of results for people (rich text) and machines (JSON, CSV, JUnit, ...).

Reports read the plain data returned by the core (:mod:`rkcheck.check`) and never
compute mathematics themselves.
"""
