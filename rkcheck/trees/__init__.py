"""Rooted trees, free trees and the energy conditions as pure combinatorics.

Takes: an order N and a degree bound m.  Gives: rooted-tree tables (level sequences,
σ, γ, Butcher factors), free trees with their rootings and parities, and the energy
conditions of the seed's Theorem 2 as terms ``sign/σ(u) · a(B₋(u))`` — no numbers.

May import: :mod:`rkcheck.errors` only.
"""
