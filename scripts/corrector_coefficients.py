#!/usr/bin/env python3
"""Coefficients of the symplectic correctors of the Wisdom-Holman map (src/celestial/
near_integrable_table.c), derived as in Wisdom, Holman & Touma, Fields Inst. Commun. 10 (1996)
217, and Wisdom, Astron. J. 131 (2006) 2294:

The WH map A(h/2) B(h) A(h/2) (A = Kepler drift, B = interaction kick, H = A + eps B) is the
time-h flow of K = A + eps f(h ad_A) B + O(eps^2), f(z) = (z/2)/sinh(z/2) = sum_k f_k z^(2k)
(symmetric BCH formula to first order in the small term). A corrector C conjugates it to the
flow of H up to O(eps h^(2K+2)) + O(eps^2): its generator chi must satisfy
ad_A chi = sum_{k>=1} f_k h^(2k) ad_A^(2k) B. C is built from Z(a, b) = X(a, b) X(-a, -b),
X(a, b) = A(a h) B(b h) A(-a h), whose generator is 2 b h sinh(a h ad_A) B + O(eps^2); with
a_i = i alpha (alpha = sqrt(7/40), the choice of Wisdom et al.), C = prod_i Z(a_i, b_i) and
    sum_i 2 b_i a_i^(2k-1)/(2k-1)! = f_k,   k = 1..K,
a K x K linear system solved here exactly in rationals (alpha^2 = 7/40 is rational, so
b_i = rational / alpha). K = 1, 2, 3, 5, 8 give the correctors of order 3, 5, 7, 11, 17.
Run: python3 scripts/corrector_coefficients.py (needs sympy)."""
import sympy as sp

z = sp.symbols('z')
f = sp.series((z / 2) / sp.sinh(z / 2), z, 0, 20).removeO()
alpha2 = sp.Rational(7, 40)
alpha = sp.sqrt(alpha2)
for K, order in ((1, 3), (2, 5), (3, 7), (5, 11), (8, 17)):
    fk = [f.coeff(z, 2 * k) for k in range(1, K + 1)]
    # unknowns c_i = b_i * alpha: sum_i 2 c_i i^(2k-1) alpha^(2k-2)/(2k-1)! = f_k
    M = sp.Matrix(K, K, lambda k, i: 2 * sp.Integer(i + 1) ** (2 * k + 1) * alpha2 ** k
                  / sp.factorial(2 * k + 1))
    c = M.LUsolve(sp.Matrix(fk))
    b = [sp.nsimplify(ci) / alpha for ci in c]
    print(f"order {order} (K = {K}):")
    for i, bi in enumerate(b):
        print(f"  b_{i + 1} = {sp.N(bi, 25)}")
