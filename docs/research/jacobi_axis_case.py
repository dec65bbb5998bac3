#!/usr/bin/python3
"""Case (a): h = eta e_k along a principal axis.  x = M_k obeys xdot^2 = P4(x) = -G_i(x) G_j(x),
G_l(x) = (1/I_l - 1/I_k) x^2 + 2 eta x / I_k + 2E - m^2/I_l - eta^2/I_k.
With the 4 real roots in cyclic order (alpha, beta, gamma, delta) around the libration interval [beta, alpha]:
  x = [beta(alpha-gamma) - gamma(alpha-beta) sn^2 u] / [(alpha-gamma) - (alpha-beta) sn^2 u],
  k^2 = (alpha-beta)(gamma-delta)/((alpha-gamma)(beta-delta)),  u = lam (t - t*),  lam^2 = -c (alpha-gamma)(beta-delta)/4,
  and M_i, M_j = const * (product of two of sn, cn, dn, 1)/den  (single valued, no branch tracking).
Checked against the general Weierstrass/stereographic closed form (gyrostat_closed_form.py)."""
import os, sys; sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gyrostat_closed_form import *
mp.mp.dps = 40

def jacobi_axis(I, k, eta, w0):
    I = [mp.mpf(x) for x in I]; eta = mp.mpf(eta); w0 = [mp.mpf(x) for x in w0]
    i, j = [l for l in range(3) if l != k]
    h = [0, 0, 0]; h[k] = eta
    M0 = [I[l]*w0[l]+h[l] for l in range(3)]
    m2 = dot(M0, M0); E2 = sum(I[l]*w0[l]**2 for l in range(3))
    G = lambda l: [E2-m2/I[l]-eta**2/I[k], 2*eta/I[k], 1/I[l]-1/I[k]]
    Gi, Gj = G(i), G(j)
    P4 = pscale(pmul(Gi, Gj), -1)
    c = P4[4]
    rts = mp.polyroots(list(reversed(P4)), maxsteps=200, extraprec=200)
    assert all(abs(mp.im(r)) < 1e-25 for r in rts), "2 real roots: use cn-form / Weierstrass"
    r = sorted([mp.re(x) for x in rts], reverse=True)
    x0 = M0[k]
    # interval containing x0, roots in cyclic (descending, wrapping) order
    for a in range(4):
        alpha, beta = r[a], r[(a+1) % 4]
        if a < 3 and beta <= x0 <= alpha and mp.sign(peval(P4, (alpha+beta)/2)) >= 0:
            gamma, delta = r[(a+2) % 4], r[(a+3) % 4]
            break
    else:
        raise RuntimeError("no interval")
    k2 = (alpha-beta)*(gamma-delta)/((alpha-gamma)*(beta-delta))
    lam = mp.sqrt(-c*(alpha-gamma)*(beta-delta)/4)
    s0 = (x0-beta)*(alpha-gamma)/((alpha-beta)*(x0-gamma))
    phi0 = mp.asin(mp.sqrt(min(max(s0, 0), 1)))
    u0 = mp.ellipf(phi0, k2)
    # sign of u0 from xdot0 = (M_i M_j)(1/I_j - 1/I_i)... sign(dx/du) = sign(sn cn dn * (alpha-beta)(beta-gamma)(alpha-gamma))
    Mdot = cross(M0, [(M0[l]-h[l])/I[l] for l in range(3)])
    sgn = mp.sign(Mdot[k])*mp.sign((alpha-beta)*(beta-gamma)*(alpha-gamma))
    u0 = u0 if sgn >= 0 else -u0
    # which root factors belong to G_i, G_j; map root -> jacobi factor
    fac = {'alpha': 'cn', 'beta': 'sn', 'gamma': '1', 'delta': 'dn'}
    named = {'alpha': alpha, 'beta': beta, 'gamma': gamma, 'delta': delta}
    def factors(Gl):
        rr = mp.polyroots(list(reversed(Gl)), extraprec=200)
        return [fac[min(named, key=lambda nm: abs(named[nm]-q))] for q in rr]
    fi, fj = factors(Gj), factors(Gi)     # M_i^2 ~ G_j, M_j^2 ~ G_i
    def J(u):
        sn, cn, dn = mp.ellipfun('sn', u, m=k2), mp.ellipfun('cn', u, m=k2), mp.ellipfun('dn', u, m=k2)
        return {'sn': sn, 'cn': cn, 'dn': dn, '1': mp.mpf(1)}, (alpha-gamma)-(alpha-beta)*sn**2
    f0, den0 = J(u0)
    Ci = M0[i]*den0/(f0[fi[0]]*f0[fi[1]])
    Cj = M0[j]*den0/(f0[fj[0]]*f0[fj[1]])
    def M_of_t(t):
        u = u0+lam*t
        f, den = J(u)
        x = (beta*(alpha-gamma)-gamma*(alpha-beta)*f['sn']**2)/den
        M = [0, 0, 0]; M[k] = x; M[i] = Ci*f[fi[0]]*f[fi[1]]/den; M[j] = Cj*f[fj[0]]*f[fj[1]]/den
        return M
    return M_of_t, dict(k2=k2, lam=lam, roots=r, fi=fi, fj=fj, interval=(alpha, beta))

if __name__ == "__main__":
    R0 = random_rotation(1)
    for I, k, eta, w0 in [(('1.0', '2.0', '3.0'), 1, '1.5', ('0.01', '1.0', '0.02')),
                          (('2.5', '1.2', '1.9'), 0, '2.0', ('0.3', '-0.8', '0.5')),
                          (('1.0', '2.0', '3.0'), 2, '0.4', ('0.6', '0.3', '0.5'))]:
        h = ['0', '0', '0']; h[k] = eta
        Mj, info = jacobi_axis(I, k, eta, w0)
        g = GyrostatClosedForm(I, h, w0, R0)
        err = max(max(abs(a-b) for a, b in zip(Mj(mp.mpf(t)/7), g.M_of_t(mp.mpf(t)/7))) for t in range(1, 701, 7))
        print("I=%s h-axis=%d eta=%s: roots=%s k^2=%s  M-factors i:%s j:%s   max|M_jacobi - M_general| over [0,100] = %s"
              % (I, k, eta, [mp.nstr(x, 6) for x in info['roots']], mp.nstr(info['k2'], 8), info['fi'], info['fj'], mp.nstr(err, 3)))
