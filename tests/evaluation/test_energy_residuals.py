"""Energy-condition residuals of the fast engine against independently derived values.

Expected values come from
* ``reference.energy_residual`` (slow brute force of SPEC §3, exact ``Fraction``s);
* closed forms derived by hand from SPEC §3 / seed Section 2 and evaluated here with plain
  ``Fraction`` linear algebra (star, double bush, triple bush, "asymbush");
* the AVF B-series of SPEC §4.

Constants derived by hand (each condition's designated rooting is its canonical centre,
``R`` is the engine's residual, all tableaux use ``c = A·1``):

* star with k leaves, centre ``[τ^k]`` (σ = k!) and leaf rooting ``[[τ^{k-1}]]``
  (σ = (k-1)!, distance 1):
  ``R = (Σb)^k/k! − bᵀc^{k−1}/(k−1)!``; with Σb = 1:
  ``R = −(bᵀc^{k−1} − 1/k)/(k−1)!``.
* double bush ``t_{p,q}`` (p < q): the canonical centre is the bush with **p** leaves
  (level sequence (1,2,3^q,2^p) > (1,2,3^p,2^q)), i.e. the seed's ``t_2``, at odd distance
  from the seed's ``t_1``.  Rootings t1..t4 have σ = (p−1)!q!, p!q!, p!q!, p!(q−1)!:
  ``−p!q!·R = p bᵀC^{p−1}Ac^q − q bᵀC^{q−1}Ac^p − (Σb)^p bᵀc^q + (Σb)^q bᵀc^p``,
  so under the quadrature conditions ``R = −DB_{p,q}/(p!q!)`` with
  ``DB_{p,q} = p bᵀC^{p−1}Ac^q − q bᵀC^{q−1}Ac^p − (1/(q+1) − 1/(p+1))`` (seed eq. (DBmono)).
* triple bush ``t_{p,r,q}``: the centre is the middle vertex M (diameter 4), rooting
  ``[τ^r [τ^p] [τ^q]]`` with σ_M = r!p!q! (×2 when p = q).  Summing the six rootings:
  ``R = T_{p,r,q}/σ_M`` where T is the seed's (unnumbered) triple bush expression
  ``p bᵀC^{p−1}AC^rAc^q − bᵀC^rAc^q + 1/((p+1)(q+1)) − r bᵀC^{r−1}(Ac^q∘Ac^p)
  − bᵀC^rAc^p + q bᵀC^{q−1}AC^rAc^p`` — note the LAST term: the seed prints
  ``q bᵀC^{q−1}AC^rAc^q``, a typo (by symmetry, and by its own polynomial form (3bush),
  it must end in ``Ac^p``).  The polynomial form (3bush) is then
  ``Σ α_{p'} β_{q'} ρ_{r'} T_{p',r',q'} = Σ α β ρ σ_M(p',r',q') R(t_{p',r',q'})``.
* asymbush (one leaf and q branches of length two at V; the centre is V for q ≥ 2;
  q = 1 is the superfluous 4-path):
  ``−q!·R = bᵀ(Ac)^q − q bᵀAC(Ac)^{q−1} + q(Σb) bᵀC(Ac)^{q−1} − (Σb)(bᵀc)^q``,
  so under Σb = 1, bᵀc = 1/2: ``R = −S_q/q!`` with S_q the seed's eq. (asymbush).
"""

from __future__ import annotations

import math
import random
from fractions import Fraction as F
from functools import lru_cache

import networkx as nx
import pytest
from support import reference as ref
from support.shapes import asymbush, double_bush, triple_bush

from rkcheck.evaluation.algorithm import condition_sums
from rkcheck.evaluation.balls import BallContext
from rkcheck.evaluation.modular import exact_condition_sums
from rkcheck.evaluation.scaled import scaled_rational
from rkcheck.numbers.intervals import Interval
from rkcheck.properties.orders import TreeWeights
from rkcheck.trees.listing import ConditionListing
from rkcheck.trees.table import TreeTable

# ------------------------------------------------------------ linear algebra


def matvec(A, x):
    return [sum((a * y for a, y in zip(row, x)), F(0)) for row in A]


def had(x, y):
    return [u * v for u, v in zip(x, y)]


def pw(x, k):
    return [u ** k for u in x]


def dot(x, y):
    return sum((u * v for u, v in zip(x, y)), F(0))


def row_sums(A):
    return [sum(row, F(0)) for row in A]


def solve(M, rhs):
    """Exact Gauss–Jordan solution of the square system M x = rhs."""
    n = len(rhs)
    aug = [list(M[i]) + [rhs[i]] for i in range(n)]
    for col in range(n):
        piv = next(r for r in range(col, n) if aug[r][col] != 0)
        aug[col], aug[piv] = aug[piv], aug[col]
        aug[col] = [x / aug[col][col] for x in aug[col]]
        for r in range(n):
            if r != col and aug[r][col] != 0:
                f = aug[r][col]
                aug[r] = [x - f * y for x, y in zip(aug[r], aug[col])]
    return [aug[i][n] for i in range(n)]


# ------------------------------------------------------------------ tableaux


def random_tableau(rng, s, sum_b_one=False, num=4, den=4):
    A = [[F(rng.randint(-num, num), rng.randint(1, den)) for _ in range(s)] for _ in range(s)]
    b = [F(rng.randint(-num, num), rng.randint(1, den)) for _ in range(s)]
    if sum_b_one:
        b[-1] = 1 - sum(b[:-1])
    return A, b


def quadrature_rule(rng, s):
    """s distinct random rational nodes and the weights with Σ b c^(k−1) = 1/k, k = 1..s
    (Vandermonde system)."""
    while True:
        c = [F(rng.randint(-12, 12), rng.randint(1, 6)) for _ in range(s)]
        if len(set(c)) == s:
            break
    b = solve([[cj ** k for cj in c] for k in range(s)], [F(1, k + 1) for k in range(s)])
    return c, b


def tableau_with_quadrature(rng, s):
    """Random A with A·1 = c for a rule exact to degree s−1 (quadrature conditions k ≤ s)."""
    c, b = quadrature_rule(rng, s)
    A = [[F(rng.randint(-5, 5), rng.randint(1, 5)) for _ in range(s)] for _ in range(s)]
    for i in range(s):
        A[i][-1] = c[i] - sum(A[i][:-1])
    assert row_sums(A) == c
    for k in range(1, s + 1):
        assert dot(b, pw(c, k - 1)) == F(1, k)
    return A, b


# ------------------------------------------------------------ engine access


@lru_cache(maxsize=None)
def cond_table(degree):
    return ConditionListing(8, degree)  # conditions with 3..9 vertices


@lru_cache(maxsize=None)
def ref_by_id():
    out = {}
    for n in range(3, 10):
        for d in ref.energy_conditions(n):
            out[d["id"]] = d
    return out


def exact_residuals(listing, A, b):
    """{canonical id: exact residual} of every condition (designated sign)."""
    sums = exact_condition_sums(scaled_rational(A, b), listing)
    out = {}
    for n, o in sums.items():
        for k in range(len(listing.orders[n])):
            rec = listing.record(n, k)
            out[rec.level_sequence] = o.value(k) * listing.flip(n, k)
    return out


def engine_residual(G, A, b, degree=None):
    """Exact engine residual of the condition of free tree G (found by the reference's
    centre canonical id)."""
    got = exact_residuals(cond_table(degree), A, b)
    return got[ref.centre_canonical_id(G)]


# ------------------------------------------------------------- free trees


def star(k):
    return nx.star_graph(k)


# ================================================== engine vs reference, exact


TABLEAU_CASES = [(seed, s) for seed, s in [(1, 2), (2, 3), (3, 4), (4, 3), (5, 2)]]


@pytest.mark.parametrize("seed,s", TABLEAU_CASES)
def test_exact_residuals_equal_reference(seed, s):
    # expected: reference.energy_residual (exact Fractions), every condition up to order 8
    rng = random.Random(seed)
    A, b = random_tableau(rng, s, sum_b_one=(seed % 2 == 0))
    refs = ref_by_id()
    want = {cid: ref.energy_residual(d, A, b) for cid, d in refs.items()}
    nonzero = 0
    for degree in (None, 3, 4):
        got = exact_residuals(cond_table(degree), A, b)
        expected_ids = {cid for cid, d in refs.items() if degree is None or d["max_degree"] <= degree}
        assert set(got) == expected_ids
        for cid, value in got.items():
            assert value == want[cid], (degree, cid)
            nonzero += value != 0
    assert nonzero > 0  # random data: the comparison is not 0 == 0


@pytest.mark.parametrize("seed,s", TABLEAU_CASES[:3])
def test_ball_backend_encloses_exact_residual(seed, s):
    # expected: the exact reference residual lies in the ball enclosure, radius < 1e-50
    rng = random.Random(100 + seed)
    A, b = random_tableau(rng, s, sum_b_one=True)
    refs = ref_by_id()
    for degree in (None, 4):
        listing = cond_table(degree)
        ctx = BallContext([[Interval.point(x) for x in row] for row in A], [Interval.point(x) for x in b], bits=200)
        for n, sums in condition_sums(listing, ctx, s).items():
            for k in range(len(sums)):
                enc = sums.enclosure(k)
                rec = listing.record(n, k)
                exact = ref.energy_residual(refs[rec.level_sequence], A, b)
                assert not enc.exact
                assert abs(enc.mid * listing.flip(n, k) - exact) <= enc.rad, rec.id
                assert enc.rad < F(1, 10 ** 50), (rec.id, float(enc.rad))


@pytest.mark.parametrize("recompute_bytes", [0, 1 << 62])
def test_weights_recomputed_or_stored_give_the_reference(monkeypatch, recompute_bytes):
    # Φ and ψ of the trees with top − 2 vertices computed twice (a budget of 0 bytes) or
    # stored: the exact residuals equal the reference's, and the balls enclose them
    import rkcheck.evaluation.algorithm as algorithm

    monkeypatch.setattr(algorithm, "RECOMPUTE_BYTES", recompute_bytes)
    rng = random.Random(7)
    A, b = random_tableau(rng, 3, sum_b_one=True)
    refs = ref_by_id()
    listing = cond_table(None)
    for cid, value in exact_residuals(listing, A, b).items():
        assert value == ref.energy_residual(refs[cid], A, b), cid
    ctx = BallContext([[Interval.point(x) for x in row] for row in A], [Interval.point(x) for x in b], bits=200)
    for n, sums in condition_sums(listing, ctx, 3).items():
        for k in range(len(sums)):
            enc, rec = sums.enclosure(k), listing.record(n, k)
            exact = ref.energy_residual(refs[rec.level_sequence], A, b)
            assert abs(enc.mid * listing.flip(n, k) - exact) <= enc.rad < F(1, 10 ** 50), rec.id


@pytest.mark.parametrize("degree", [None, 3])
@pytest.mark.parametrize("a_before_top", [False, True])
def test_top_a_stored_before_the_top_order_or_computed_in_it_give_the_reference(monkeypatch, degree, a_before_top):
    # a of the trees with top − 1 vertices computed where the top order's terms need it,
    # or stored before the top order with Φ and ψ released: the exact residuals equal the
    # reference's either way
    import rkcheck.evaluation.algorithm as algorithm

    chosen = []

    def decide(*args):
        chosen.append(a_before_top)
        return a_before_top

    monkeypatch.setattr(algorithm, "_a_before_top", decide)
    listing = cond_table(degree)
    rng = random.Random(11)
    A, b = random_tableau(rng, 3, sum_b_one=True)
    refs = ref_by_id()
    got = exact_residuals(listing, A, b)
    assert chosen  # the choice was made, not skipped
    assert sum(value != 0 for value in got.values()) > 0  # random data: not 0 == 0
    for cid, value in got.items():
        assert value == ref.energy_residual(refs[cid], A, b), cid


@pytest.mark.parametrize("order", [3, 4, 5])
def test_every_order_checked_alone_with_the_fewest_weights_stored_gives_the_reference(monkeypatch, order):
    # the lowest top orders with Φ and ψ of the trees with top − 2 vertices recomputed
    # and a stored before the top order (what vectors of a few hundred stages and many
    # directions choose): at order 3 only Φ(τ) is left stored, which no factors give
    import rkcheck.evaluation.algorithm as algorithm

    monkeypatch.setattr(algorithm, "RECOMPUTE_BYTES", 0)
    monkeypatch.setattr(algorithm, "_a_before_top", lambda *args: True)
    listing = ConditionListing(order, None)
    rng = random.Random(order)
    A, b = random_tableau(rng, 3, sum_b_one=True)
    refs = ref_by_id()
    ctx = BallContext([[Interval.point(x) for x in row] for row in A], [Interval.point(x) for x in b], bits=200)
    sums = condition_sums(listing, ctx, 3, [order + 1])[order + 1]
    for k in range(len(sums)):
        enc, rec = sums.enclosure(k), listing.record(order + 1, k)
        exact = ref.energy_residual(refs[rec.level_sequence], A, b)
        assert abs(enc.mid * listing.flip(order + 1, k) - exact) <= enc.rad < F(1, 10 ** 50), rec.id


def test_symmetry_factors_equal_reference_sigmas():
    # expected: σ(u) of every rooting from the reference (the engine folds (n−1)!/σ(u)
    # into each term's coefficient)
    listing = cond_table(None)
    for n in listing.orders:
        for k in range(len(listing.orders[n])):
            rec = listing.record(n, k)
            d = ref_by_id()[rec.level_sequence]
            got = sorted(sigma for _, sigma, _ in listing.term_forests(n, k))
            assert got == sorted(sig for _, _, sig, _ in d["terms"])
            assert math.factorial(n - 1) % math.lcm(*got) == 0  # σ(u) divides (n−1)!


# ======================================================== closed forms: star


@pytest.mark.parametrize("k", range(2, 9))
def test_star_condition_is_quadrature_condition(k):
    # hand derivation (module docstring): R = (Σb)^k/k! − bᵀc^{k−1}/(k−1)!
    G = star(k)
    assert ref.centre_canonical_id(G) == (1,) + (2,) * k  # rooted at the hub
    rng = random.Random(k)
    for s in (2, 3, 4):
        A, b = random_tableau(rng, s)
        c = row_sums(A)
        want = sum(b) ** k / math.factorial(k) - dot(b, pw(c, k - 1)) / math.factorial(k - 1)
        assert engine_residual(G, A, b) == want
        # Σb = 1: R = −(Σ b c^{k−1} − 1/k)/(k−1)!, the quadrature condition k
        A, b = random_tableau(rng, s, sum_b_one=True)
        c = row_sums(A)
        got = engine_residual(G, A, b, degree=k)
        assert got == -(dot(b, pw(c, k - 1)) - F(1, k)) / math.factorial(k - 1)
        assert got != 0
    # a rule exact to degree k−1 satisfies it exactly
    A, b = tableau_with_quadrature(rng, k)
    assert engine_residual(G, A, b) == 0


# ================================================== closed forms: double bush


DB_PAIRS = [(p, q) for p in range(1, 5) for q in range(p + 1, 6) if p + q + 2 <= 9]


def db_general(A, b, p, q):
    """−p!q!·R of t_{p,q} for any tableau (hand derivation)."""
    c = row_sums(A)
    sb = sum(b)
    return (p * dot(b, had(pw(c, p - 1), matvec(A, pw(c, q))))
            - q * dot(b, had(pw(c, q - 1), matvec(A, pw(c, p))))
            - sb ** p * dot(b, pw(c, q)) + sb ** q * dot(b, pw(c, p)))


def db_seed(A, b, p, q):
    """Seed eq. (DBmono), LHS − RHS."""
    c = row_sums(A)
    return (p * dot(b, had(pw(c, p - 1), matvec(A, pw(c, q))))
            - q * dot(b, had(pw(c, q - 1), matvec(A, pw(c, p))))
            - (F(1, q + 1) - F(1, p + 1)))


@pytest.mark.parametrize("p,q", DB_PAIRS)
def test_double_bush_general_tableau(p, q):
    # hand derivation: R = −(p bᵀC^{p−1}Ac^q − q bᵀC^{q−1}Ac^p − (Σb)^p bᵀc^q + (Σb)^q bᵀc^p)/(p!q!)
    G = double_bush(p, q)
    assert ref.centre_canonical_id(G) == (1, 2) + (3,) * q + (2,) * p  # rooted at the p-bush
    rng = random.Random(10 * p + q)
    for s in (2, 3):
        A, b = random_tableau(rng, s)
        got = engine_residual(G, A, b)
        assert got == -db_general(A, b, p, q) / (math.factorial(p) * math.factorial(q))
        assert got != 0


@pytest.mark.parametrize("p,q", DB_PAIRS)
def test_double_bush_equals_seed_formula_under_quadrature(p, q):
    # seed eq. (DBmono) on tableaux with quadrature conditions k ≤ m = q+1 (and A·1 = c):
    # R = −DB_{p,q}/(p!q!)
    G = double_bush(p, q)
    rng = random.Random(1000 + 10 * p + q)
    m = q + 1
    for s in (m, m + 1):
        A, b = tableau_with_quadrature(rng, s)
        got = engine_residual(G, A, b, degree=m)
        want = -db_seed(A, b, p, q) / (math.factorial(p) * math.factorial(q))
        assert got == want
        assert got != 0
        # the seed's particular solution A = c bᵀ (eq. (avfmat)) satisfies it
        c = row_sums(A)
        A_avf = [[ci * bj for bj in b] for ci in c]
        assert db_seed(A_avf, b, p, q) == 0
        assert engine_residual(G, A_avf, b, degree=m) == 0


# ================================================== closed forms: triple bush


def seed_T(A, b, p, r, q, typo=False):
    """The seed's monomial triple bush expression (last term corrected unless typo)."""
    c = row_sums(A)
    Acq, Acp = matvec(A, pw(c, q)), matvec(A, pw(c, p))
    Cr = pw(c, r)
    t = p * dot(b, had(pw(c, p - 1), matvec(A, had(Cr, Acq))))
    t -= dot(b, had(Cr, Acq))
    t += F(1, (p + 1) * (q + 1))
    if r:
        t -= r * dot(b, had(pw(c, r - 1), had(Acq, Acp)))
    t -= dot(b, had(Cr, Acp))
    t += q * dot(b, had(pw(c, q - 1), matvec(A, had(Cr, Acq if typo else Acp))))
    return t


def sigma_M(p, r, q):
    s = math.factorial(p) * math.factorial(q) * math.factorial(r)
    return 2 * s if p == q else s


TB_CASES = [(p, r, q) for p in range(1, 4) for q in range(p, 4) for r in range(0, 4)
            if p + q + r + 3 <= 9]


@pytest.mark.parametrize("p,r,q", TB_CASES)
def test_triple_bush_equals_seed_formula(p, r, q):
    # hand derivation + seed: R(t_{p,r,q}) = T_{p,r,q}/σ_M under the quadrature conditions
    G = triple_bush(p, r, q)
    cid = ref.centre_canonical_id(G)
    assert cid == ref.canonicalize((1,) + (2,) * r + (2,) + (3,) * p + (2,) + (3,) * q)  # at M
    rng = random.Random(100 * p + 10 * r + q)
    s = max(p, q) + 1
    for _ in range(2):
        A, b = tableau_with_quadrature(rng, s)
        got = engine_residual(G, A, b)
        assert got == seed_T(A, b, p, r, q) / sigma_M(p, r, q)
        assert got != 0


def test_seed_triple_bush_printed_last_term_is_a_typo():
    # the seed prints "+ q bᵀC^{q−1}AC^rAc^q"; with p ≠ q that does not give the condition
    rng = random.Random(7)
    A, b = tableau_with_quadrature(rng, 3)
    G = triple_bush(1, 1, 2)
    got = engine_residual(G, A, b)
    assert got == seed_T(A, b, 1, 1, 2) / sigma_M(1, 1, 2)
    assert got != seed_T(A, b, 1, 1, 2, typo=True) / sigma_M(1, 1, 2)
    assert ref.energy_residual(ref_by_id()[ref.centre_canonical_id(G)], A, b) == got


def poly_eval(coeffs, x):
    return sum((a * x ** k for k, a in coeffs.items()), F(0))


def poly_deriv(coeffs):
    return {k - 1: k * a for k, a in coeffs.items() if k}


def poly_integral01(coeffs):
    return sum((a / (k + 1) for k, a in coeffs.items()), F(0))


def seed_3bush_poly(A, b, P, Q, R):
    """Seed eq. (3bush), evaluated directly."""
    c = row_sums(A)

    def vec(poly):
        return [poly_eval(poly, ci) for ci in c]

    Pc, Qc, Rc = vec(P), vec(Q), vec(R)
    dP, dQ, dR = vec(poly_deriv(P)), vec(poly_deriv(Q)), vec(poly_deriv(R))
    AQ, AP = matvec(A, Qc), matvec(A, Pc)
    return (dot(b, had(dP, matvec(A, had(Rc, AQ)))) + dot(b, had(dQ, matvec(A, had(Rc, AP))))
            - poly_eval(P, 1) * dot(b, had(Rc, AQ)) - poly_eval(Q, 1) * dot(b, had(Rc, AP))
            - dot(b, had(dR, had(AQ, AP)))
            + poly_eval(R, 1) * poly_integral01(P) * poly_integral01(Q))


@pytest.mark.parametrize("P,Q,R", [
    ({1: F(-1), 2: F(1)}, {1: F(-1), 2: F(1)}, {0: F(1)}),  # the seed's §2.4 choice
    ({1: F(1), 2: F(2)}, {2: F(1)}, {0: F(1), 1: F(-1)}),
    ({1: F(3)}, {1: F(1), 2: F(-1, 2)}, {1: F(2)}),
])
def test_triple_bush_polynomial_form(P, Q, R):
    # seed eq. (3bush) = Σ α_{p'} β_{q'} ρ_{r'} T_{p',r',q'} = Σ α β ρ σ_M R(t_{p',r',q'})
    rng = random.Random(31)
    A, b = tableau_with_quadrature(rng, 3)  # quadrature k ≤ 3 covers p', q' ≤ 2
    combo = F(0)
    for pp, al in P.items():
        for qq, be in Q.items():
            for rr, rho in R.items():
                combo += al * be * rho * sigma_M(pp, rr, qq) * engine_residual(triple_bush(pp, rr, qq), A, b)
    assert combo == seed_3bush_poly(A, b, P, Q, R)
    assert combo != 0


# ===================================================== closed forms: asymbush


@pytest.mark.parametrize("q", [2, 3])
def test_asymbush(q):
    G = asymbush(q)
    assert ref.centre_canonical_id(G) == (1,) + (2, 3) * q + (2,)  # rooted at V: [τ[τ]^q]
    rng = random.Random(50 + q)
    fq = math.factorial(q)
    for s in (2, 3):
        # general tableau: −q!R = bᵀ(Ac)^q − q bᵀAC(Ac)^{q−1} + q(Σb)bᵀC(Ac)^{q−1} − (Σb)(bᵀc)^q
        A, b = random_tableau(rng, s)
        c = row_sums(A)
        Ac = matvec(A, c)
        sb = sum(b)
        general = (dot(b, pw(Ac, q)) - q * dot(b, matvec(A, had(c, pw(Ac, q - 1))))
                   + q * sb * dot(b, had(c, pw(Ac, q - 1))) - sb * dot(b, c) ** q)
        got = engine_residual(G, A, b)
        assert got == -general / fq and got != 0
        # seed eq. (asymbush) under Σb = 1, bᵀc = 1/2: R = −S_q/q!
        A, b = tableau_with_quadrature(rng, s)
        c = row_sums(A)
        Ac = matvec(A, c)
        S = (dot(b, pw(Ac, q)) - q * dot(b, matvec(A, had(c, pw(Ac, q - 1))))
             + q * dot(b, had(c, pw(Ac, q - 1))) - F(1, 2) ** q)
        got = engine_residual(G, A, b, degree=q + 1)
        assert got == -S / fq and got != 0


def test_asymbush_q1_is_superfluous():
    # one leaf + one branch of length two = the 4-path, superfluous (no condition)
    G = asymbush(1)
    assert ref.is_superfluous(G)
    listing = cond_table(None)
    assert ref.centre_canonical_id(G) not in {r.level_sequence for n in listing.orders for r in listing.records(n)}


# ========================================================== AVF B-series


def avf_weight(seq):
    """SPEC §4: a(τ) = 1, a([t1..tk]) = a(t1)…a(tk)/(k+1)."""
    kids = ref.subtrees_at_root(seq)
    out = F(1, len(kids) + 1)
    for t in kids:
        out *= avf_weight(t)
    return out


def child_counts(seq):
    adj = ref.level_sequence_to_adj(seq)
    return [len(adj[v]) - (0 if v == 0 else 1) for v in adj]


@pytest.mark.parametrize("p,seed", [(2, 1), (3, 2), (4, 3)])
def test_avf_identity_for_c_bT(p, seed):
    # For A = c bᵀ: Φ([t1..tk]) = Π (c bᵀΦ(tj)) = c^k Π a(tj), so
    # a([t1..tk]) = (Σ b c^k) Π a(tj) and a(t) = Π_v w_{k_v}, w_k = Σ b c^k, k_v = #children.
    # With quadrature order exactly p, w_k = 1/(k+1) iff k ≤ p−1: a(t) equals the AVF weight
    # when every vertex has ≤ p−1 children.
    rng = random.Random(seed)
    c, b = quadrature_rule(rng, p)
    w = {k: dot(b, pw(c, k)) for k in range(0, 7)}
    assert all(w[k] == F(1, k + 1) for k in range(p))
    bad_k = [k for k in range(p, 7) if w[k] != F(1, k + 1)]
    assert p in bad_k  # quadrature order exactly p
    A = [[ci * bj for bj in b] for ci in c]
    table = TreeTable(7)
    ctx = BallContext([[Interval.point(x) for x in row] for row in A], [Interval.point(x) for x in b], bits=300)
    tree_weights = TreeWeights(ctx, p)
    n_equal = n_diff = 0
    for n in range(1, 8):
        order_weights = ctx.enclosures(tree_weights.extend(table, n))
        weights = dict(zip(table.ids_of_order(n), order_weights))
        for t in table.ids_of_order(n):
            seq = table.level_sequence(t)
            a = math.prod(w[k] for k in child_counts(seq))  # the closed form, exact
            assert abs(weights[t].mid - a) <= weights[t].rad < F(1, 10**80), seq
            ks = child_counts(seq)
            if max(ks) <= p - 1:
                assert a == avf_weight(seq), seq
                n_equal += 1
            elif any(k in bad_k for k in ks):
                # a/avf = Π_v (k_v+1) w_{k_v} ≠ 1 for this data (checked, not assumed)
                assert math.prod((k + 1) * w[k] for k in ks) != 1
                assert a != avf_weight(seq), seq
                n_diff += 1
    assert n_equal > 0 and n_diff > 0


@pytest.mark.parametrize("stages", [9, 17])
def test_many_stages_sum_their_products_in_slices_and_match_the_reference(stages):
    """Beyond SLICE stages ``x Aᵀ`` and ``x b`` are summed a slice at a time before each
    reduction (products of residues below 2^60): dense tableaux with that many stages and
    large denominators, exactly, in one channel per pass and several, against the
    reference's Fraction residuals."""
    from rkcheck.evaluation.channels import SLICE
    from rkcheck.evaluation.modular import exact_condition_sums
    from rkcheck.evaluation.scaled import ScaledTableau, scaled_rational
    from rkcheck.trees.listing import ConditionListing

    assert stages > SLICE
    rng = random.Random(stages)
    A = [[F(rng.randint(-10**6, 10**6), rng.randint(1, 10**5)) for _ in range(stages)] for _ in range(stages)]
    b = [F(rng.randint(-10**6, 10**6), rng.randint(1, 10**5)) for _ in range(stages)]
    listing = ConditionListing(4, None)
    scaled = scaled_rational(A, b)
    for width in (1, None):  # one channel per pass, or as many as fit
        if width is not None:
            scaled.channels_per_pass = lambda listing, top: 1  # type: ignore[method-assign]
        else:
            scaled = scaled_rational(A, b)
        sums = exact_condition_sums(scaled, listing)
        for n in listing.orders:
            want = {c["id"]: ref.energy_residual(c, A, b) for c in ref.energy_conditions(n)}
            for k in range(len(listing.orders[n])):
                got = sums[n].value(k) * listing.flip(n, k)
                assert got == want[listing.record(n, k).level_sequence], (n, k)
    assert isinstance(scaled, ScaledTableau)
