"""High-precision reference for the exact free-rigid-body flow test on the T-handle.

Integrates Euler's equations of the `dzhanibekov` scene's default body (the T-handle's
body-frame inertia J and initial body angular momentum m0, identity orientation, as the scene
builds them in f64; the decimal values below are those doubles exactly) to t = 10 s with
mpmath's Taylor-series ODE solver at 40 significant digits, and prints the final quaternion
(w >= 0 convention flipped to match the run's sign if needed) and body angular velocity.

    m' = m x w,  R' = R hat(w),  w = J^-1 m

Run: python3 tools/exact_flow_reference.py   (needs `pip install mpmath`)
"""
import mpmath as mp

mp.mp.dps = 40
J = [mp.mpf("2.8639455782312924e-5"), mp.mpf("4.292517006802721e-5"), mp.mpf("1.7619047619047623e-5")]
m0 = [mp.mpf("5.727891156462585e-4"), mp.mpf("8.585034013605443e-7"), mp.mpf("3.523809523809525e-7")]
R0 = [1, 0, 0, 0, 1, 0, 0, 0, 1]


def rhs(t, y):
    m = y[:3]
    w = [m[i] / J[i] for i in range(3)]
    dm = [m[1] * w[2] - m[2] * w[1], m[2] * w[0] - m[0] * w[2], m[0] * w[1] - m[1] * w[0]]
    R = [y[3 + k] for k in range(9)]  # row-major R[r][c] = R[3r + c]
    # R' = R hat(w); hat(w) = [[0,-w3,w2],[w3,0,-w1],[-w2,w1,0]]
    H = [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]
    dR = [sum(R[3 * r + k] * H[k][c] for k in range(3)) for r in range(3) for c in range(3)]
    return dm + dR


def main():
    f = mp.odefun(rhs, 0, [mp.mpf(x) for x in m0] + [mp.mpf(x) for x in R0], tol=mp.mpf(10) ** -32, degree=40)
    y = f(mp.mpf(10))
    m = y[:3]
    R = [[y[3 + 3 * r + c] for c in range(3)] for r in range(3)]
    w = [m[i] / J[i] for i in range(3)]
    # Quaternion of R (Shepperd), w >= 0.
    tr = R[0][0] + R[1][1] + R[2][2]
    qw = mp.sqrt(max(0, 1 + tr)) / 2
    qx = mp.sqrt(max(0, 1 + R[0][0] - R[1][1] - R[2][2])) / 2
    qy = mp.sqrt(max(0, 1 - R[0][0] + R[1][1] - R[2][2])) / 2
    qz = mp.sqrt(max(0, 1 - R[0][0] - R[1][1] + R[2][2])) / 2
    qx = mp.sign(R[2][1] - R[1][2]) * qx if qw > 0 else qx
    qy = mp.sign(R[0][2] - R[2][0]) * qy if qw > 0 else qy
    qz = mp.sign(R[1][0] - R[0][1]) * qz if qw > 0 else qz
    for name, v in [("qw", qw), ("qx", qx), ("qy", qy), ("qz", qz), ("omega_x", w[0]), ("omega_y", w[1]), ("omega_z", w[2])]:
        print(name, mp.nstr(v, 25))
    print("|R^T R - 1|", mp.nstr(max(abs(sum(R[k][i] * R[k][j] for k in range(3)) - (1 if i == j else 0)) for i in range(3) for j in range(3)), 3))


if __name__ == "__main__":
    main()
