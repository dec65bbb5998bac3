"""40-digit references for the exact gyrostat flow's tests (tests/integrate/gyrostat_flow_test.cpp).

Each case: principal moments I, constant rotor momentum h (body frame), omega(0), and R(0) from the unit
quaternion (0.8, 0.2, -0.4, 0.4) (w, x, y, z), whose matrix is exact in decimal. The reference is the
Taylor-series integrator of gyrostat_closed_form.py (order 40, 40 digits), independent of the closed form.
Prints omega(t) and R(t) at t = 10 and 100 s with 25 significant digits, as C++ initialisers.
Run: /usr/bin/python3 docs/research/gyrostat_references.py   (about a minute)
"""
import mpmath as mp

from gyrostat_closed_form import taylor_reference

mp.mp.dps = 40
w, x, y, z = (mp.mpf(s) for s in ('0.8', '0.2', '-0.4', '0.4'))
R0 = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
      [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
CASES = [
    ("dual_spin", ('1.0', '2.0', '3.0'), ('0', '1.5', '0'), ('0.01', '1.0', '0.02')),
    ("off_axis", ('1.0', '2.0', '3.0'), ('0.3', '-0.4', '0.5'), ('0.7', '0.2', '-0.4')),
    ("near_separatrix", ('1.0', '2.0', '3.0'), ('0.001', '0.002', '-0.0015'), ('0.3', '0.5', '0.1733')),
    ("unsorted_axis_1", ('2.5', '1.2', '1.9'), ('2.0', '0', '0'), ('0.3', '-0.8', '0.5')),
    ("one_oval", ('1.0', '2.0', '3.0'), ('0.01', '0.02', '0.03'), ('0.1', '0.2', '1.0')),
    ("two_ovals", ('1.0', '2.0', '3.0'), ('0.01', '0.02', '0.03'), ('0.5', '0.3', '0.8')),
    ("free_body", ('3.0', '1.0', '2.0'), ('0', '0', '0'), ('0.4', '0.3', '-0.6')),
]
for name, I, h, w0 in CASES:
    times = [mp.mpf(10), mp.mpf(100)]
    ref = taylor_reference(I, h, w0, R0, times)
    print(f"// {name}: I = {I}, h = {h}, omega0 = {w0}")
    for t in times:
        M, R = ref[t]
        om = [(M[i] - mp.mpf(h[i])) / mp.mpf(I[i]) for i in range(3)]
        print(f"//   t = {int(t)}")
        print("   {" + ", ".join(mp.nstr(v, 25) for v in om) + "},")
        print("   {" + ", ".join(mp.nstr(R[i][j], 25) for i in range(3) for j in range(3)) + "},")
