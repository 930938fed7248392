#!/usr/bin/env python3
"""Generate the high-precision coefficient literals of tumble-integrators.

Run:  python3 crates/integrators/tools/gen_tables.py > /tmp/tables.txt
(requires mpmath; computations at 60 significant digits, printed with 30).

What it prints (pasted into the crate's `tables` modules and tests):

1. Gauss-Legendre collocation on [0, 1] for s = 1..6: nodes c_i = (1 + x_i)/2
   with x_i the roots of the Legendre polynomial P_s, weights b_i, and
   a_ij = int_0^{c_i} l_j(tau) dtau with l_j the Lagrange basis on the nodes.
2. Composition coefficients that are defined by equations rather than
   published to 25+ digits: Yoshida's triple jump, Suzuki's fractal,
   McLachlan's 5-stage order-4 method (gamma_1 = 0.28 fixed, gamma_2 the root
   of the order-4 condition near 0.6254664), and Yoshida's 8th-order
   solution D refined from its 15 published digits by Gauss-Newton on the
   order conditions.
3. The residuals of the order conditions of every composition (published and
   refined), computed in a faithful matrix representation (see below).
4. Jacobi elliptic reference values sn, cn, dn and K(m) for the tests.

Order conditions of a symmetric composition of a symmetric second-order base
method: write the base method as S(h) = exp(h X + h^3 Y3 + h^5 Y5 + h^7 Y7 + h^9 Y9)
(a symmetric method has only odd powers in its modified generator).  The
composition prod_i S(gamma_i h) has order p iff the generator of the product
equals h X + O(h^{p+1}).  With X, Y3, ... random matrices the graded
components of the free Lie algebra up to degree 9 are represented faithfully
(generically), so the coefficients of h^3..h^p of log(prod) vanish exactly
when the order conditions hold.
"""
import mpmath as mp

mp.mp.dps = 60
DIGITS = 30


def fmt(x):
    s = mp.nstr(mp.mpf(x), DIGITS, min_fixed=-1, max_fixed=1, strip_zeros=False)
    if 'e' not in s and '.' not in s:
        s += '.0'
    return s


# ---------------------------------------------------------------- Gauss--Legendre
def gauss(s):
    # P_s(x) = 2^-s sum_k (-1)^k C(s,k) C(2s-2k, s) x^(s-2k), highest degree first
    coeffs = [mp.mpf(0)] * (s + 1)
    for k in range(s // 2 + 1):
        coeffs[2 * k] = (-1) ** k * mp.binomial(s, k) * mp.binomial(2 * s - 2 * k, s) / mp.mpf(2) ** s
    xs = sorted(mp.re(x) for x in mp.polyroots(coeffs, maxsteps=500, extraprec=300))
    # polish each root with Newton on P_s
    xs = [mp.findroot(lambda x: mp.legendre(s, x), x0) for x0 in xs]
    assert all(xs[i] < xs[i + 1] for i in range(s - 1))
    c = [(1 + x) / 2 for x in xs]

    def lag(j, t):
        v = mp.mpf(1)
        for k in range(s):
            if k != j:
                v *= (t - c[k]) / (c[j] - c[k])
        return v

    b = [mp.quad(lambda t: lag(j, t), [0, 1]) for j in range(s)]
    a = [[mp.quad(lambda t: lag(j, t), [0, c[i]]) for j in range(s)] for i in range(s)]
    return c, b, a


def emit_gauss():
    for s in range(1, 7):
        c, b, a = gauss(s)
        print(f"// ---- Gauss-Legendre s = {s}")
        print(f"c: [{', '.join(fmt(x) for x in c)}],")
        print(f"b: [{', '.join(fmt(x) for x in b)}],")
        print("a: [")
        for row in a:
            print(f"    [{', '.join(fmt(x) for x in row)}],")
        print("],")
        # checks
        res = max(abs(sum(b[i] * c[i] ** (k - 1) for i in range(s)) - mp.mpf(1) / k) for k in range(1, 2 * s + 1))
        sym = max(abs(b[i] * a[i][j] + b[j] * a[j][i] - b[i] * b[j]) for i in range(s) for j in range(s))
        print(f"// B(2s) residual {mp.nstr(res, 3)}, symplectic residual {mp.nstr(sym, 3)}")


# ---------------------------------------------------------------- compositions
N = 4
mp.mp.dps = 60
rng_seed = [12345]


def rnd():
    rng_seed[0] = (rng_seed[0] * 1103515245 + 12345) % (2 ** 31)
    return mp.mpf(rng_seed[0]) / 2 ** 31 - mp.mpf(0.5)


def rmat():
    return mp.matrix([[rnd() for _ in range(N)] for _ in range(N)])


DEG = 11
GEN = {1: rmat(), 3: rmat(), 5: rmat(), 7: rmat(), 9: rmat()}
ZERO = mp.zeros(N, N)
ID = mp.eye(N)


def smul(a, b):
    out = [ZERO.copy() for _ in range(DEG + 1)]
    for i, ai in enumerate(a):
        for j in range(DEG + 1 - i):
            out[i + j] += ai * b[j]
    return out


def sexp(g):  # g[0] = 0
    out = [ZERO.copy() for _ in range(DEG + 1)]
    out[0] = ID.copy()
    term = [ZERO.copy() for _ in range(DEG + 1)]
    term[0] = ID.copy()
    for k in range(1, DEG + 1):
        term = [t / k for t in smul(term, g)]
        out = [o + t for o, t in zip(out, term)]
    return out


def slog(p):  # p[0] = I
    x = [ZERO.copy()] + p[1:]
    out = [ZERO.copy() for _ in range(DEG + 1)]
    term = [ID.copy()] + [ZERO.copy() for _ in range(DEG)]
    for k in range(1, DEG + 1):
        term = smul(term, x)
        sign = 1 if k % 2 == 1 else -1
        out = [o + sign * t / k for o, t in zip(out, term)]
    return out


def base(w):
    g = [ZERO.copy() for _ in range(DEG + 1)]
    for k, m in GEN.items():
        g[k] = m * w ** k
    return sexp(g)


def residuals(gammas, order):
    p = [ID.copy()] + [ZERO.copy() for _ in range(DEG)]
    for w in gammas:
        p = smul(p, base(w))
    lg = slog(p)
    res = [abs(sum(gammas) - 1)]
    for k in range(2, order + 1):
        res.append(mp.mnorm(lg[k], 1))
    return res


def full(half, middle_derived=True):
    if middle_derived:
        mid = 1 - 2 * sum(half)
        return list(half) + [mid] + list(reversed(half))
    return list(half) + list(reversed(half[:-1]))


def refine(half, order):
    """Gauss-Newton on the order conditions of a symmetric composition whose
    middle coefficient is derived from the sum."""
    x = [mp.mpf(v) for v in half]

    def resvec(x):
        g = full(x)
        p = [ID.copy()] + [ZERO.copy() for _ in range(DEG)]
        for w in g:
            p = smul(p, base(w))
        lg = slog(p)
        v = []
        for k in range(3, order + 1, 2):
            v += [lg[k][i, j] for i in range(N) for j in range(N)]
        return mp.matrix(v)

    for _ in range(6):
        r = resvec(x)
        eps = mp.mpf(10) ** -30
        cols = []
        for i in range(len(x)):
            xp = list(x)
            xp[i] += eps
            cols.append((resvec(xp) - r) / eps)
        J = mp.matrix(len(r), len(x))
        for i in range(len(x)):
            for k in range(len(r)):
                J[k, i] = cols[i][k]
        dx = mp.lu_solve(J.T * J, -(J.T * r))
        x = [xi + dxi for xi, dxi in zip(x, dx)]
        if mp.norm(dx) < mp.mpf(10) ** -50:
            break
    return x


def emit_compositions():
    two13 = mp.cbrt(2)
    y4 = 1 / (2 - two13)
    print("// Yoshida 4 (triple jump): gamma_1 = 1/(2 - 2^(1/3)), gamma_2 = -2^(1/3) gamma_1")
    print(fmt(y4), fmt(-two13 * y4))
    p = 1 / (4 - mp.cbrt(4))
    print("// Suzuki 4: p = 1/(4 - 4^(1/3)), middle 1 - 4p")
    print(fmt(p), fmt(1 - 4 * p))
    a = mp.mpf('0.28')
    b = mp.findroot(lambda b: 2 * a ** 3 + 2 * b ** 3 + (1 - 2 * a - 2 * b) ** 3, mp.mpf('0.6254664'))
    print("// McLachlan 4 (5 stages): gamma_1 = 0.28, gamma_2 root of the order-4 condition, middle 1 - 2(g1+g2)")
    print(fmt(a), fmt(b), fmt(1 - 2 * (a + b)))
    y6 = ['0.78451361047755726381949763', '0.23557321335935813368479318', '-1.17767998417887100694641568']
    y6r = refine(y6, 6)
    print("// Yoshida 6 (solution A) refined from Hairer-Lubich-Wanner's 26 digits")
    print(', '.join(fmt(v) for v in y6r), '| middle', fmt(1 - 2 * sum(y6r)))
    # Yoshida's w_1..w_7 of solution D; composition order w7 .. w1 w0 w1 .. w7
    y8 = ['0.914844246229740', '0.253693336566229', '-1.44485223686048', '-0.158240635368243',
          '1.93813913762276', '-1.96061023297549', '0.102799849391985']
    y8r = refine(y8, 8)
    print("// Yoshida 8 (solution D) refined from the 15 published digits (outermost first)")
    print(', '.join(fmt(v) for v in y8r), '| middle', fmt(1 - 2 * sum(y8r)))
    print("// order-condition residuals |sum-1|, then |log coefficient of h^k| for k = 2..p")
    kl6 = ['0.39216144400731413927925056', '0.33259913678935943859974864', '-0.70624617255763935980996482',
           '0.08221359629355080023149045', '0.79854399093482996339895035']
    kl8 = ['0.13020248308889008087881763', '0.56116298177510838456196441', '-0.38947496264484728640807860',
           '0.15884190655515560089621075', '-0.39590389413323757733623154', '0.18453964097831570709183254',
           '0.25837438768632204729397911', '0.29501172360931029887096624', '-0.60550853383003451169892108']
    ss10 = ['0.07879572252168641926390768', '0.31309610341510852776481247', '0.02791838323507806610952027',
            '-0.22959284159390709415121340', '0.13096206107716486317465686', '-0.26973340565451071434460973',
            '0.07497334315589143566613711', '0.11199342399981020488957508', '0.36613344954622675119314812',
            '-0.39910563013603589787862981', '0.10308739852747107731580277', '0.41143087395589023782070412',
            '-0.00486636058313526176219566', '-0.39203335370863990644808194', '0.05194250296244964703718290',
            '0.05066509075992449633587434', '0.04967437063972987905456880', '0.04931773575959453791768001']
    cases = [
        ('yoshida4', [y4, -two13 * y4, y4], 4),
        ('suzuki4', [p, p, 1 - 4 * p, p, p], 4),
        ('mclachlan4', [a, b, 1 - 2 * (a + b), b, a], 4),
        ('yoshida6', full(y6r), 6),
        ('yoshida8', full(y8r), 8),
        ('yoshida8-published', full([mp.mpf(v) for v in y8]), 8),
        ('kahan-li6', full([mp.mpf(v) for v in kl6], False), 6),
        ('kahan-li8', full([mp.mpf(v) for v in kl8], False), 8),
        ('sofroniou-spaletta10', full([mp.mpf(v) for v in ss10], False), 10),
    ]
    for name, g, order in cases:
        r = residuals(g, order)
        print(f"// {name} ({len(g)} stages): " + ' '.join(mp.nstr(x, 2) for x in r))


# ---------------------------------------------------------------- Jacobi elliptic
def emit_jacobi():
    print("// Jacobi sn, cn, dn (u, m) and K(m), mpmath.ellipfun / ellipk")
    for (u, m) in [(0.5, 0.3), (1.2, 0.5), (2.0, 0.9), (3.7, 0.99), (4.0, 0.998001), (10.0, 0.998001),
                   (0.1, 0.0), (1.0, 1.0), (-2.5, 0.7), (7.3, 0.2)]:
        u = mp.mpf(u)
        m = mp.mpf(m)
        print(f"({fmt(u)}, {fmt(m)}, {fmt(mp.ellipfun('sn', u, m=m))}, {fmt(mp.ellipfun('cn', u, m=m))}, "
              f"{fmt(mp.ellipfun('dn', u, m=m))}),")
    for m in ['0.0', '0.5', '0.9', '0.998001', '0.999999']:
        print(f"K({m}) = {fmt(mp.ellipk(mp.mpf(m)))}")


# ---------------------------------------------------------------- explicit RK pairs
# Tsitouras 5(4) and Verner's "most efficient" 6(5) ... 9(8) pairs with interpolants.
# The coefficients are data (rk_pairs_data.py); this part checks every order
# condition at 100 digits and writes src/tables/rk_pairs.rs (f64, round to nearest).
#
# Order conditions (Butcher): for every rooted tree t with |t| nodes, the elementary
# weight sum_i w_i g_i(t) equals 1/gamma(t), where g(single node) = 1 and
# g([t_1 ... t_m]) = prod_k (A g(t_k)) componentwise, gamma([t_1 ... t_m]) =
# |t| prod_k gamma(t_k).  A continuous extension sum_i b_i(theta) k_i of order q
# satisfies sum_i b_i(theta) g_i(t) = theta^|t| / gamma(t) for |t| <= q, i.e. with
# b_i(theta) = sum_m r_im theta^m: sum_i r_im g_i(t) = [m == |t|] / gamma(t).

RK_PAIRS = [
    # (data name, Rust name, registry name, order, embedded order, per-step stages,
    #  FSAL row (1-based), dense order, citation)
    ('TSIT5', 'TSIT5', 'tsit5', 5, 4, 7, 7, 4,
     'Tsitouras 5(4) (Comput. Math. Appl. 62 (2011) 770-775), FSAL, order-4 dense output'),
    ('VERN6', 'VERN6', 'vern6', 6, 5, 9, 9, 6,
     "Verner's most efficient 6(5) pair (RKV65.IIIXb.Efficient), FSAL, "
     'order-6 interpolant with 3 extra stages'),
    ('VERN7', 'VERN7', 'vern7', 7, 6, 10, 11, 7,
     "Verner's most efficient 7(6) pair (RKV76.IIa.Efficient), order-7 interpolant "
     '(corrected 2024) with 6 extra stages'),
    ('VERN8', 'VERN8', 'vern8', 8, 7, 13, 14, 8,
     "Verner's most efficient 8(7) pair (RKV87.IIa.Efficient), order-8 interpolant "
     'with 8 extra stages'),
    ('VERN9', 'VERN9', 'vern9', 9, 8, 16, 17, 9,
     "Verner's most efficient 9(8) pair (RKV98.IIa.Efficient), order-9 interpolant "
     'with 10 extra stages'),
]


def rk_trees(max_order):
    """All rooted trees up to max_order as (order, children ids), ids into the list."""
    out = [(1, ())]
    for n in range(2, max_order + 1):
        existing = len(out)

        def rec(start, remaining, cur):
            if remaining == 0:
                yield tuple(cur)
                return
            for i in range(start, existing):
                if out[i][0] <= remaining:
                    yield from rec(i, remaining - out[i][0], cur + [i])

        out += [(n, ch) for ch in rec(0, n - 1, [])]
    return out


def rk_value(expr):
    def R(s):
        p, _, q = s.partition('/')
        return mp.mpf(int(p)) / (mp.mpf(int(q)) if q else 1)
    return eval(expr, {'__builtins__': {}}, {'R': R, 'D': mp.mpf, 'S6': mp.sqrt(6)})


def rk_load(d, stages):
    rows = set(i for i, _ in d['a']) | {1}
    s = max(rows)
    a = [[mp.mpf(0)] * s for _ in range(s)]
    for (i, j), v in d['a'].items():
        assert j < i, 'explicit'
        a[i - 1][j - 1] = rk_value(v)
    b = [mp.mpf(0)] * s
    e = [mp.mpf(0)] * s
    for i, v in d['b'].items():
        b[i - 1] = rk_value(v)
    for i, v in d['e'].items():
        e[i - 1] = rk_value(v)
    if 'r' in d:
        deg = max(m for _, m in d['r'])
        r = [[mp.mpf(0)] * s for _ in range(deg)]
        for (i, m), v in d['r'].items():
            r[m - 1][i - 1] = rk_value(v)
    else:
        # weights b_i(theta_j) at nodes theta_j: solve the Vandermonde system
        # sum_m r_im theta_j^m = b_i(theta_j) for the polynomial coefficients
        nodes = [rk_value(x) for x in d['r_at_nodes']['nodes']]
        deg = len(nodes)
        vmat = mp.matrix([[t ** (m + 1) for m in range(deg)] for t in nodes])
        r = [[mp.mpf(0)] * s for _ in range(deg)]
        for col, st in enumerate(d['r_at_nodes']['stages']):
            rhs = mp.matrix([rk_value(row[col]) for row in d['r_at_nodes']['weights']])
            sol = mp.lu_solve(vmat, rhs)
            for m in range(deg):
                r[m][st - 1] = sol[m]
    c = [mp.fsum(row) for row in a]
    return a, b, e, r, c


def rk_residuals(a, weights, trees, orders):
    """max |sum_i w_i g_i(t) - target(n, gamma(t))| per order n in `orders`, over the
    trees (the whole list up to max(orders), children before parents)."""
    s = len(a)
    g, gam = [], []
    worst = {}
    for n, ch in trees:
        v = [mp.mpf(1)] * s
        gm = mp.mpf(n)
        for c in ch:
            w = g[c]
            aw = [mp.fsum(a[i][j] * w[j] for j in range(i)) for i in range(s)]
            v = [v[i] * aw[i] for i in range(s)]
            gm *= gam[c]
        g.append(v)
        gam.append(gm)
        if n not in orders:
            continue
        for w, target in weights:
            res = abs(mp.fsum(w[i] * v[i] for i in range(s)) - target(n, gm))
            worst[n] = max(worst.get(n, mp.mpf(0)), res)
    return worst


def rk_check(name, a, b, e, r, c, p, q, dense_q, fsal):
    s = len(a)
    trees = rk_trees(max(p, dense_q))
    bhat = [b[i] - e[i] for i in range(s)]
    exact = lambda n, gm: 1 / gm  # noqa: E731
    main = rk_residuals(a, [(b, exact)], trees, range(1, p + 1))
    emb = rk_residuals(a, [(bhat, exact)], trees, range(1, q + 1))
    emb_next = rk_residuals(a, [(bhat, exact)], trees, [q + 1])
    dense = rk_residuals(
        a,
        [(row, (lambda m: lambda n, gm: (1 / gm if n == m + 1 else 0))(m)) for m, row in enumerate(r)],
        trees, range(1, dense_q + 1))
    b_at_1 = max(abs(mp.fsum(r[m][i] for m in range(len(r))) - b[i]) for i in range(s))
    fsal_row = max(abs(a[fsal - 1][j] - b[j]) for j in range(s))
    out = {
        'order conditions of b up to order %d' % p: max(main.values()),
        'embedded b - e up to order %d' % q: max(emb.values()),
        'interpolant up to order %d' % dense_q: max(dense.values()),
        'b(1) - b': b_at_1,
        'FSAL row - b': fsal_row,
        '|c(FSAL) - 1|': abs(c[fsal - 1] - 1),
    }
    # the embedded formula is not of order q + 1 (it would estimate nothing)
    assert max(emb_next.values()) > mp.mpf(10) ** -8, name
    return out


def rk_f64(x):
    """x rounded to the nearest f64 (exact binary expansion of the mpf, then one rounding)."""
    from fractions import Fraction
    sign, man, exp, _ = mp.mpf(x)._mpf_
    if man == 0:
        return 0.0
    fr = Fraction(int(man)) * (Fraction(2) ** int(exp))
    return float(-fr if sign else fr)


def rk_lit(x):
    v = rk_f64(x)
    t = repr(v)
    if 'e' not in t and '.' not in t:
        t += '.0'
    if t == '-0.0':
        t = '0.0'
    return t


def rk_array(xs, indent):
    lits = [rk_lit(x) for x in xs]
    lines, cur = [], ''
    for lit in lits:
        piece = lit + ','
        if cur and len(cur) + 1 + len(piece) + indent > 96:
            lines.append(cur)
            cur = piece
        else:
            cur = (cur + ' ' + piece) if cur else piece
    lines.append(cur)
    pad = ' ' * indent
    return '[\n' + '\n'.join(pad + l for l in lines) + '\n' + ' ' * (indent - 4) + ']'


def emit_rk_pairs(path):
    import rk_pairs_data as data
    with mp.workdps(100):
        src = [
            '//! Tsitouras 5(4) and Verner\'s "most efficient" 6(5), 7(6), 8(7), 9(8) pairs with',
            '//! their interpolants (see [`crate::tables::explicit`] for the references).',
            '//!',
            '//! Generated by `crates/integrators/tools/gen_tables.py --rk-pairs` from',
            '//! `crates/integrators/tools/rk_pairs_data.py` after checking every order condition',
            '//! at 100 digits (worst residuals below); each literal is the published value',
            '//! rounded to the nearest `f64`. Do not edit by hand.',
            '//!',
            '//! Layout: rows `0 .. stages` are the stages of a step, row `fsal` is `b` with `c = 1`',
            '//! (`f(t + h, y₁)`), the remaining rows are the interpolant\'s extra stages; `dense[m]`',
            '//! holds the coefficients of `θ^(m+1)` in the weights `bᵢ(θ)`.',
            '',
            'use super::{DenseForm, ErrorEstimator, ExplicitTableau};',
        ]
        report = []
        for (dname, rname, reg, p, q, stages, fsal, dense_q, _cite) in RK_PAIRS:
            d = getattr(data, dname)
            a, b, e, r, c = rk_load(d, stages)
            s = len(a)
            res = rk_check(dname, a, b, e, r, c, p, q, dense_q, fsal)
            report.append((reg, res))
            # the checks above bound the differences; emit the FSAL row as b exactly
            a[fsal - 1] = list(b)
            c[fsal - 1] = mp.mpf(1)
            doc = [f'/// `{reg}`: order {p}, embedded order {q}, {stages} stages per step '
                   f'(FSAL row {fsal - 1}), order-{dense_q} interpolant, {s} rows.',
                   '///', '/// Worst order-condition residuals at 100 digits:']
            for k, v in res.items():
                doc.append(f'/// - {k}: {mp.nstr(v, 2)}')
            src.append('')
            src += doc
            src.append('#[rustfmt::skip]')
            src.append(f'pub const {rname}: ExplicitTableau<{s}> = ExplicitTableau {{')
            src.append(f'    name: "{reg}",')
            src.append(f'    order: {p},')
            src.append(f'    stages: {stages},')
            src.append(f'    fsal: {fsal - 1},')
            src.append(f'    c: {rk_array(c, 8)},')
            src.append('    a: [')
            for i in range(s):
                if all(x == 0 for x in a[i]):
                    src.append(f'        [0.0; {s}],')
                else:
                    src.append(f'        {rk_array(a[i], 12)},')
            src.append('    ],')
            src.append(f'    b: {rk_array(b, 8)},')
            src.append('    error: ErrorEstimator::Embedded {')
            src.append(f'        weights: {rk_array(e, 12)},')
            src.append(f'        order: {q + 1},')
            src.append('    },')
            src.append('    dense: &[')
            for row in r:
                src.append(f'        {rk_array(row, 12)},')
            src.append('    ],')
            src.append('    dense_form: DenseForm::Polynomial,')
            src.append(f'    dense_order: {dense_q},')
            src.append('};')
        with open(path, 'w') as f:
            f.write('\n'.join(src) + '\n')
        for reg, res in report:
            print(reg)
            for k, v in res.items():
                print(f'  {k}: {mp.nstr(v, 3)}')


if __name__ == '__main__':
    import os
    import sys
    if '--rk-pairs' in sys.argv:
        here = os.path.dirname(os.path.abspath(__file__))
        sys.path.insert(0, here)
        emit_rk_pairs(os.path.join(here, '..', 'src', 'tables', 'rk_pairs.rs'))
    else:
        emit_gauss()
        emit_compositions()
        emit_jacobi()
