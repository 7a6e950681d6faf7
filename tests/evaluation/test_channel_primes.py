"""The channel primes: the sieved window gives the largest primes below the limit, the
same ones Miller–Rabin finds number by number, and sympy's primality agrees."""

from __future__ import annotations

import pytest
import sympy

from rkcheck.evaluation.channels import PRIME_BITS, _primes_below, _sieve_window, is_prime, primes


def _largest_by_test(limit: int, count: int) -> list[int]:
    """The ``count`` largest primes below ``limit``, each number tested on its own."""
    out, q = [], limit - 1
    while len(out) < count and q >= 2:
        if is_prime(q):
            out.append(q)
        q -= 1
    return out


def test_the_largest_30_bit_primes_are_those_miller_rabin_finds():
    limit = 1 << PRIME_BITS
    got = _primes_below(limit, 2500)
    assert list(got) == _largest_by_test(limit, 2500)
    assert all(sympy.isprime(q) for q in got[:200]) and got[0] == limit - 35  # 2^30 − 35: the largest


def test_a_window_holds_exactly_the_primes_in_it():
    lo, hi = (1 << PRIME_BITS) - 60_000, (1 << PRIME_BITS) - 20_000
    window = _sieve_window(lo, hi).tolist()
    assert window == [q for q in range(lo, hi) if is_prime(q)]
    assert window == list(sympy.primerange(lo, hi))


@pytest.mark.parametrize("limit", [2, 3, 4, 30, 100, 1 << 16])
def test_small_limits_list_every_prime(limit):
    assert _sieve_window(0, limit).tolist() == list(sympy.primerange(0, limit))
    assert list(_primes_below(limit, 10)) == sorted(sympy.primerange(0, limit), reverse=True)[:10]


def test_primes_skip_and_count_slice_one_fixed_order():
    first = primes(300)
    assert primes(100, 150) == first[150:250]
    assert list(first) == sorted(first, reverse=True) and len(set(first)) == 300


@pytest.mark.parametrize("count", [1, 2, 3, 7, 64, 301])
def test_chinese_remaindering_gives_the_integers_with_those_residues(count):
    # against the textbook formula x = Σ r_i·(M/m_i)·((M/m_i)^-1 mod m_i) mod M, one
    # integer at a time, on random residues of the channels' own primes
    import math
    import random

    from rkcheck.evaluation.channels import primes
    from rkcheck.evaluation.remainders import crt_columns

    rng = random.Random(count)
    moduli = list(primes(count))
    columns = [[rng.randrange(m) for _ in range(5)] for m in moduli]
    M = math.prod(moduli)
    expected = [sum(col[k] * (M // m) * pow(M // m, -1, m) for col, m in zip(columns, moduli)) % M for k in range(5)]
    assert crt_columns(columns, moduli) == expected
    assert crt_columns(columns, moduli) == expected  # again, from the cached tree of the moduli


@pytest.mark.parametrize("rows, chunk", [(8192, 128), (7, 3)])  # one block; many blocks and limb chunks
def test_large_integers_reduced_through_their_limbs_are_pythons_residues(monkeypatch, rows, chunk):
    import random

    from rkcheck.evaluation import remainders

    monkeypatch.setattr(remainders, "LIMB_ROWS", rows)
    monkeypatch.setattr(remainders, "LIMB_CHUNK", chunk)
    rng = random.Random(rows)
    values = [rng.getrandbits(rng.randint(0, 4000)) * rng.choice([1, -1]) for _ in range(300)]
    values += [0, 1, -1, 2**30, -(2**4000), (2**16 - 1) * 2**2000]
    moduli = list(primes(40))
    got = remainders.LimbResidues(values).modulo(moduli)
    assert got.tolist() == [[v % p for p in moduli] for v in values]  # Python's own %, the reference


def test_a_tableau_of_large_entries_has_the_same_channel_images_either_way():
    # entries of thousands of bits take the limbs (LIMB_MIN_BITS); the images of A and b
    # at every channel are the residues Python's % gives, prime by prime
    from fractions import Fraction

    from rkcheck.evaluation.scaled import LIMB_MIN_BITS, scaled_rational

    big = Fraction(3**2000 + 7, 2**1500 + 1)
    A = [[big, Fraction(1, 3)], [Fraction(-5, 7), -big]]
    b = [Fraction(1, 2), big / 3]
    scaled = scaled_rational(A, b)
    assert max(abs(x[0]).bit_length() for row in scaled.A for x in row) >= LIMB_MIN_BITS
    chosen = scaled.primes_for(4000)
    for p, roots in chosen[:70]:
        images_A, images_b = scaled._images(p, roots[0])
        assert images_A.tolist() == [[x[0] % p for x in row] for row in scaled.A]
        assert images_b.tolist() == [x[0] % p for x in scaled.b]
