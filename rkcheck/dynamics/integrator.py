"""One Runge–Kutta step of any tableau on a Hamiltonian, in float64 or mpmath.

The same algorithm runs in two number contexts (:class:`Float64` and :class:`MP`): the
context supplies the numbers and the tolerance tied to its precision; the small LU
factorisation is generic, factored once per Jacobian and reused by every iteration.

* explicit tableaux: stages in order;
* implicit tableaux: stage increments ``Z_i = h Σ_j a_ij f(y + Z_j)`` by **simplified
  Newton** with the exact Jacobian ``f'(y₀)`` (from the Hessian polynomials) in the
  iteration matrix ``I − h A ⊗ f'(y₀)``; when the contraction is poor (rate > 1/2) the
  matrix is rebuilt at the current stage values.  The iteration stops when the update is
  below the context's tolerance (≈ 10^-(dps−3) relative for mpmath, 4·10⁻¹⁶ for float64);
  if it diverges or has not converged after the iteration limit a :class:`NewtonError`
  is raised — never a silently wrong step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

from rkcheck.errors import UserError
from rkcheck.numbers.precision import mpmath_bits
from rkcheck.numbers.reading import DecimalsMode


@dataclass(frozen=True)
class StepAdvice:
    """What a message about the step size tells the user to change: the options through
    which the command chose its steps (``simulate --h``; ``workprec --T`` and ``--steps``)."""

    smaller: str
    larger: str
    place: str


#: the steps of ``simulate``: its ``--h`` (and ``--dps`` for a step that underflows)
H_ADVICE = StepAdvice("a smaller --h", "a larger --h, or --dps", "--h")


class NewtonError(UserError):
    """The stage equations could not be solved (the step is probably too large)."""


class DivergedError(UserError):
    """The numerical solution left the representable numbers (NaN or ±inf): an explicit
    method blew up.  Never a column of ``nan`` and a zero energy error."""


def _finite(ctx, y: Sequence[Any]) -> bool:
    size = ctx.norm(y)
    return size == size and size != float("inf")  # NaN != NaN; mpf('inf') == inf


def _magnitude(x) -> str:
    from fractions import Fraction

    from rkcheck.numbers.formatting import decimal_string

    return decimal_string(Fraction(x), 3)


class Float64:
    name = "float64"

    def __init__(self) -> None:
        import numpy as np

        self.np = np
        self.tol = 4e-16
        self.max_iter = 60

    def num(self, x) -> float:
        from fractions import Fraction

        try:
            if isinstance(x, Fraction):
                return x.numerator / x.denominator
            return float(x)
        except OverflowError:
            raise UserError(f"a value of about {_magnitude(x)} is beyond float64's range (about 1.8e308), in which "
                            "this integration runs (simulate --dps integrates in mpmath)") from None

    def norm(self, v: Sequence[float]) -> float:
        return max((abs(x) for x in v), default=0.0)


class MP:
    """mpmath numbers; callers run inside ``mpmath.workdps(ctx.dps)``."""

    name = "mpmath"

    def __init__(self, dps: int) -> None:
        import mpmath

        self.mpmath = mpmath
        self.dps = dps
        self.tol = mpmath.mpf(10) ** (-(dps - 3))
        self.max_iter = 60 + 2 * dps

    def num(self, x):
        from fractions import Fraction

        mpmath = self.mpmath
        if isinstance(x, Fraction):
            return mpmath.mpf(x.numerator) / x.denominator
        return mpmath.mpf(x)

    def norm(self, v):
        return max((abs(x) for x in v), default=self.mpmath.mpf(0))


@dataclass
class RKMethod:
    """Numeric A and b of a tableau in one context (c = A·1 is implied)."""

    A: list[list[Any]]
    b: list[Any]
    explicit: bool

    @staticmethod
    def from_tableau(tableau, ctx, bits: int = 0) -> "RKMethod":
        bits = bits or mpmath_bits(getattr(ctx, "dps", 16))
        A_i, b_i = tableau.enclosures(bits, DecimalsMode.EXACT)
        A = [[ctx.num(x.mid) for x in row] for row in A_i]
        b = [ctx.num(x.mid) for x in b_i]
        return RKMethod(A, b, tableau.structure == "explicit")


def _add(y, z):
    return [a + b for a, b in zip(y, z)]


def lu_factor(M: list[list[Any]]) -> tuple[list[list[Any]], list[int]]:
    """LU with partial pivoting (Doolittle), in any number type; raises on a singular M."""
    n = len(M)
    LU = [list(row) for row in M]
    piv = list(range(n))
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(LU[i][k]))
        if LU[p][k] == 0:
            raise ZeroDivisionError("singular iteration matrix")
        if p != k:
            LU[k], LU[p] = LU[p], LU[k]
            piv[k], piv[p] = piv[p], piv[k]
        inv = 1 / LU[k][k]
        rowk = LU[k]
        for i in range(k + 1, n):
            f = LU[i][k] * inv
            if f:
                rowi = LU[i]
                rowi[k] = f
                for j in range(k + 1, n):
                    rowi[j] -= f * rowk[j]
            else:
                LU[i][k] = f
    return LU, piv


def lu_solve(LU: list[list[Any]], piv: list[int], b: list[Any]) -> list[Any]:
    n = len(LU)
    x = [b[piv[i]] for i in range(n)]
    for i in range(n):
        row = LU[i]
        acc = x[i]
        for j in range(i):
            acc -= row[j] * x[j]
        x[i] = acc
    for i in range(n - 1, -1, -1):
        row = LU[i]
        acc = x[i]
        for j in range(i + 1, n):
            acc -= row[j] * x[j]
        x[i] = acc / row[i]
    return x


def step(method: RKMethod, ham, y: Sequence[Any], h: Any, ctx, where: str = "", guess=None,
         advice: StepAdvice = H_ADVICE) -> list[Any]:
    """y₁ from y₀ = y with step h (see the module docstring).  ``guess``: a list to read
    and update with the stage increments, used to warm-start the next implicit step;
    ``advice``: what a failure tells the user to change."""
    s = len(method.b)
    A, b = method.A, method.b
    if method.explicit:
        F: list[list[Any]] = []  # f at each stage
        for i in range(s):
            Yi = list(y)
            for j in range(i):
                if A[i][j]:
                    Yi = [Yk + h * A[i][j] * fk for Yk, fk in zip(Yi, F[j])]
            F.append(ham.f(Yi))
    else:
        F = _implicit_stages(method, ham, y, h, ctx, where, guess, advice)
    y1 = list(y)
    for i in range(s):
        if b[i]:
            y1 = [yk + h * b[i] * fk for yk, fk in zip(y1, F[i])]
    return y1


def _iteration_matrix(A, h, jacobians, n, s):
    """I − h (A ⊗ I) blockdiag(J_j), as a dense (s·n)×(s·n) list of lists."""
    size = s * n
    M = [[0] * size for _ in range(size)]
    for i in range(s):
        for j in range(s):
            a = A[i][j]
            J = jacobians[j]
            for r in range(n):
                for c in range(n):
                    M[i * n + r][j * n + c] = (1 if (i == j and r == c) else 0) - (h * a * J[r][c] if a else 0)
    return M


def _implicit_stages(method, ham, y, h, ctx, where, guess=None, advice: StepAdvice = H_ADVICE):
    s, n = len(method.b), len(y)
    A = method.A
    try:
        LU, piv = lu_factor(_iteration_matrix(A, h, [ham.jacobian(y)] * s, n, s))
        if guess:  # the previous step's increments: a better start than the predictor
            Z = [list(z) for z in guess[0]]
        else:
            f0 = ham.f(y)
            Z = [[h * sum(row) * fk for fk in f0] for row in A]  # explicit predictor
        prev = None
        scale = ctx.norm(y) + 1
        for _ in range(ctx.max_iter):
            F = [ham.f(_add(y, Zi)) for Zi in Z]
            G = []
            for i in range(s):
                acc = list(Z[i])
                for j in range(s):
                    if A[i][j]:
                        acc = [a - h * A[i][j] * fj for a, fj in zip(acc, F[j])]
                G.extend(acc)
            delta = lu_solve(LU, piv, [-g for g in G])
            Z = [[Z[i][k] + delta[i * n + k] for k in range(n)] for i in range(s)]
            size = ctx.norm(delta)
            if not size == size or size > 1e30 * scale:  # NaN or blow-up
                break
            if size <= ctx.tol * scale:
                if guess is not None:
                    guess[:] = [Z]
                return [ham.f(_add(y, Zi)) for Zi in Z]
            if prev is not None and prev > 0 and size > prev / 2:  # poor contraction: refresh
                LU, piv = lu_factor(_iteration_matrix(A, h, [ham.jacobian(_add(y, Zi)) for Zi in Z], n, s))
            prev = size
    except (ZeroDivisionError, OverflowError):
        pass
    raise NewtonError(
        f"Newton's method did not converge{where} (h = {float(h):.3g}): the step is probably too large "
        f"for this problem; try {advice.smaller}"
    )


def integrate(method: RKMethod, ham, y0, h, steps: int, ctx, record_every: int = 1,
              advice: StepAdvice = H_ADVICE):
    """(times, states, energies) every ``record_every`` steps, from t = 0.  Raises
    :class:`DivergedError` when the solution overflows (NaN or ±inf), and a UserError for a
    step size that is zero in the number context (``--h 1e-1000`` in float64); each says
    what to change through ``advice``."""
    if not ctx.num(h):
        raise UserError(f"the step size is 0 in {ctx.name} (it underflows); use {advice.larger}", advice.place)
    y = list(y0)
    H0 = ham.energy(y)
    times, states, energies = [0], [list(y)], [H0]
    guess: list = []
    for k in range(1, steps + 1):
        try:
            y = step(method, ham, y, h, ctx, f" at step {k}", guess, advice)
            finite = _finite(ctx, y)
            energy = ham.energy(y) if finite and (k % record_every == 0 or k == steps) else None
        except OverflowError:
            finite = False
        if not finite or (energy is not None and not _finite(ctx, [energy])):
            raise DivergedError(
                f"the solution diverged at step {k} (t = {float(k * h):.6g}): it overflowed {ctx.name}; the step "
                f"is probably too large for this method and problem; try {advice.smaller}", advice.place)
        if energy is not None:
            times.append(k * h)
            states.append(list(y))
            energies.append(energy)
    return times, states, energies
