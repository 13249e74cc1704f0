#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets (fuzz/corpus/<target>/), in the input encoding of
fuzz/fuzz_common.h. Re-run after changing the encoding; the files are committed."""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
SPECIALS = ["0", "-0", "1", "-1", "1e-300", "1e300", "-1e300", "denorm_min", "min/4", "max", "inf", "-inf", "nan",
            "1e-100", "1e100", "1e-4", "1e6", "1+eps"]


def val(x):
    """One double: nice (int16 / 2^k) when exact, else its raw bits; strings name kSpecials."""
    if isinstance(x, str):
        i = SPECIALS.index(x)
        return bytes([208 + (i - 208) % len(SPECIALS)])  # selector % len == i
    for k in range(16 if math.isfinite(x) else 0):
        v = x * 2 ** k
        if v == int(v) and -32768 <= v <= 32767:
            return bytes([k]) + struct.pack(">h", int(v))
    return bytes([128]) + struct.pack(">d", x)


def vals(*xs):
    return b"".join(val(x) for x in xs)


def write(target, name, data):
    d = os.path.join(HERE, "corpus", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def quat(axis, angle):
    n = math.sqrt(sum(a * a for a in axis))
    s = math.sin(angle / 2) / n
    return (math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s)


# --- fuzz_static: ra, [flag, q], pa, rb, [flag, q], pb, T(q, t)
def static(ra, qa, pa, rb, qb, pb, qt=(1, 0, 0, 0), t=(0, 0, 0), raw=False):
    flag = bytes([1 if raw else 0])
    return vals(*ra) + flag + vals(*qa) + vals(*pa) + vals(*rb) + flag + vals(*qb) + vals(*pb) + vals(*qt) + vals(*t)


I = (1, 0, 0, 0)
write("fuzz_static", "spheres_separated", static((1, 1, 1), I, (0, 0, 0), (1, 1, 1), I, (3, 0, 0)))
write("fuzz_static", "spheres_tangent", static((1, 1, 1), I, (0, 0, 0), (1, 1, 1), I, (2, 0, 0)))
write("fuzz_static", "rotated_overlap", static((2, 1, 0.5), quat((1, 2, 3), 0.7), (0, 0, 0), (1, 0.25, 3),
                                               quat((0, 1, 0), 1.1), (1.5, 0.5, 0), quat((1, 1, 0), 0.3), (5, -2, 1)))
write("fuzz_static", "near_tangent", static((2, 1, 1), I, (0, 0, 0), (2, 1, 1), I, (4.0000001, 0, 0)))
write("fuzz_static", "aspect_1e-4", static((1, 1, "1e-4"), quat((1, 0, 0), 0.2), (0, 0, 0), (1, "1e-4", 1),
                                           I, (0, 0, 0.5)))
write("fuzz_static", "far_1e6", static((1, 2, 3), I, ("1e6", "1e6", 0), (3, 2, 1), quat((0, 0, 1), 2.0),
                                       (1000003.5, 1000000, 0)))
write("fuzz_static", "tiny_huge", static(("1e-100", 1, 1), I, (0, 0, 0), ("1e100", 1, 1), I, ("1e100", 0, 0)))
write("fuzz_static", "nan_radius", static(("nan", 1, 1), I, (0, 0, 0), (1, 1, 1), I, (0, 0, 0)))
write("fuzz_static", "subnormal", static(("denorm_min", "min/4", 1), I, (0, 0, 0), (1, 1, 1), I, ("min/4", 0, 0)))
write("fuzz_static", "non_rotation", static((1, 1, 1), (1, 1, 0, 0), (0, 0, 0), (1, 1, 1), I, (1, 0, 0), raw=True))
write("fuzz_static", "inf_centre", static((1, 1, 1), I, ("inf", 0, 0), (1, 1, 1), I, (1e300, 0, 0)))

# --- fuzz_fcl: kind1, 4 values, kind2, 4 values, pose1 (flag, q, t), pose2, num_contacts, enable_contact
def fclcase(k1, p1, k2, p2, q1=I, t1=(0, 0, 0), q2=I, t2=(0, 0, 0), raw=0):
    return (bytes([k1]) + vals(*p1) + bytes([k2]) + vals(*p2) + bytes([raw]) + vals(*q1) + vals(*t1) + bytes([raw])
            + vals(*q2) + vals(*t2) + bytes([0, 0]))


kinds = ["ellipsoid", "sphere", "box", "capsule", "cylinder", "cone", "plane", "halfspace"]
params = {0: (1, 2, 0.5, 0), 1: (1, 0, 0, 0), 2: (1, 2, 3, 0), 3: (0.5, 2, 0, 0), 4: (0.5, 2, 0, 0), 5: (1, 2, 0, 0),
          6: (0, 0, 1, 0.5), 7: (0, 1, 0, -0.5)}
for k in range(8):
    write("fuzz_fcl", f"ellipsoid_{kinds[k]}_touching", fclcase(0, (1, 2, 0.5, 0), k, params[k],
                                                                 quat((1, 1, 1), 0.4), (0, 0, 0), quat((0, 1, 0), 0.9),
                                                                 (1.2, 0.3, -0.2)))
    write("fuzz_fcl", f"ellipsoid_{kinds[k]}_apart", fclcase(0, (1, 2, 0.5, 0), k, params[k], I, (0, 0, 0),
                                                              quat((0, 0, 1), 0.5), (6, 0, 0)))
write("fuzz_fcl", "sphere_ellipsoid", fclcase(1, (1, 0, 0, 0), 0, (1, 2, 3, 0), I, (0, 0, 0), I, (1.9, 0, 0)))
write("fuzz_fcl", "nan_transform", fclcase(0, (1, 1, 1, 0), 0, (1, 1, 1, 0), I, ("nan", 0, 0), I, (0, 0, 0)))
write("fuzz_fcl", "negative_radius", fclcase(0, (1, -1, 1, 0), 2, (1, 1, 1, 0)))
write("fuzz_fcl", "zero_plane_normal", fclcase(0, (1, 1, 1, 0), 6, (0, 0, 0, 1)))


# --- fuzz_motion: degree, bad_last_row, coefficients (13 per degree, or 16), ra, rb bytes, X0, X1, flags
def motion(coeffs, ra=(1, 0.5, 0.25), rb=(1, 2, 1), X0=(I, (0, -3, 0)), X1=(I, (0, 3, 0)), flags=0, bad=False):
    deg = len(coeffs) - 1
    out = bytes([deg, 0xFF if bad else 0])
    for M in coeffs:
        for i in range(4):
            for j in range(4):
                if i == 3 and j < 3 and not bad:
                    continue
                out += val(M[i][j])
    out += vals(*ra) + bytes(rb) + vals(*X0[0]) + vals(*X0[1]) + vals(*X1[0]) + vals(*X1[1]) + bytes([flags])
    return out


def eye():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def zero():
    return [[0.0] * 4 for _ in range(4)]


C0 = eye()
write("fuzz_motion", "constant_identity", motion([C0]))
C1 = zero()
C1[0][3] = 4.0
C0t = eye()
C0t[0][3] = -2.0
write("fuzz_motion", "linear_translation", motion([C0t, C1]))
write("fuzz_motion", "linear_translation_affine_first_contact", motion([C0t, C1], flags=3))
# w(t) = 1 + t^2 and a scaling of the linear part: a rational (non-polynomial) motion.
C2 = zero()
C2[3][3] = 1.0
C2[0][0] = 0.5
write("fuzz_motion", "rational_w", motion([C0t, C1, C2]))
# w(t) = 1 - 2t vanishes at t = 1/2: rejected.
Cw = zero()
Cw[3][3] = -2.0
write("fuzz_motion", "w_root", motion([C0, Cw]))
write("fuzz_motion", "bad_last_row", motion([C0], bad=True))
# Degree 6 with small coefficients everywhere, and one with huge ones.
import random
rng = random.Random(6)
high = [eye()] + [[[round(rng.uniform(-0.2, 0.2), 3) for _ in range(4)] for _ in range(4)] for _ in range(6)]
for M in high[1:]:
    M[3][:3] = [0.0, 0.0, 0.0]
write("fuzz_motion", "degree6_small", motion(high))
huge = [[[x * 1e300 if isinstance(x, float) else x for x in row] for row in M] for M in high]
write("fuzz_motion", "degree6_huge", motion(huge))
write("fuzz_motion", "nan_coefficient", motion([[[float("nan")] * 4] * 4]))

# --- fuzz_scene: mode byte (0 check, 1 ccd, 2 command line, 3 render, 4 plot, 5 bench) + body
examples = os.path.join(HERE, "..", "examples")
# scene_quadrics.json and scene_quadrics_ccd.json are left out: their CSG shapes take about 100 s
# (check) and several seconds (ccd: a rim contact) per execution under ASan (the quadric-region
# engines at -O1); quadrics_small and ccd_quadrics_small below stand in for them.
for name in sorted(os.listdir(examples)):
    if name.endswith(".json") and name not in ("scene_quadrics.json", "scene_quadrics_ccd.json"):
        text = open(os.path.join(examples, name), "rb").read()
        write("fuzz_scene", "check_" + name, b"\x00" + text)
        write("fuzz_scene", "ccd_" + name, b"\x01" + text)
write("fuzz_scene", "check_box_pairs", b"\x00" + b'{"objects":[{"name":"A","shape":{"type":"box","size":[1,2,3]}},'
      b'{"name":"B","shape":{"type":"box","size":[1,1,1]},"pose":{"translation":[1,0,0]}},'
      b'{"name":"C","shape":{"type":"ellipsoid","radii":[1,0.5,0.25]},"pose":{"quaternion":[0,1,0,0]}}],'
      b'"pairs":[["A","B"],["C","A"],["B","C"]]}')
write("fuzz_scene", "ccd_polynomial_high_degree", b"\x01" + b'{"objects":[{"name":"A","shape":{"type":"sphere","radius":1},'
      b'"motion":{"type":"polynomial","matrix":[[1,0,0,[-3,6,0,0,0,0,1e-3]],[0,1,0,[0,0,0,0,0,0,1e-3]],[0,0,1,0],'
      b'[0,0,0,[1,0,0,0,0,0,1e-6]]]}},{"name":"B","shape":{"type":"ellipsoid","radii":[1,2,0.5]}}]}')
write("fuzz_scene", "check_huge_numbers", b"\x00" + b'{"objects":[{"name":"A","shape":{"type":"ellipsoid",'
      b'"radii":[1e-300,1e300,1]}},{"name":"B","shape":{"type":"sphere","radius":1e308},"pose":{"translation":[1e400,0,0]}}]}')
# The region CCD's cheap paths: a ball passing a capped cylinder far away (certified free in a few
# boxes) and a box overlapping an elliptic cylinder at t = 0 (a witness at once).
write("fuzz_scene", "ccd_quadrics_small", b"\x01" + b'{"objects":[{"name":"P","shape":{"type":"cylinder","radius":0.5,'
      b'"length":1}},{"name":"Q","shape":{"type":"sphere","radius":0.25},"motion":{"type":"linear",'
      b'"from":{"translation":[3,2,0]},"to":{"translation":[3,-2,0]}}},{"name":"R","shape":{"type":"box",'
      b'"size":[1,1,1]},"pose":{"translation":[0.2,0,0]}}],"pairs":[["P","Q"],["R","P"]]}')
write("fuzz_scene", "demo_small", b"\x02demo\n--frames\n3\n--objects\n4")
write("fuzz_scene", "demo_seed_max", b"\x02demo\n--seed\n18446744073709551615\n--frames\n2\n--objects\n2")
write("fuzz_scene", "help", b"\x02--help")
write("fuzz_scene", "check_missing_file", b"\x02check\n/nonexistent/scene.json")

# render / plot: an options byte and an argument byte before the scene (fuzz_scene.cpp, fuzzPicture)
def example(name):
    return open(os.path.join(examples, name), "rb").read()
write("fuzz_scene", "render_basic_svg", b"\x03\x00\x00" + example("scene_basic.json"))
write("fuzz_scene", "render_ccd_png_time", b"\x03\x03\x78" + example("scene_ccd.json"))
quadrics_small = (b'{"objects":[{"name":"pillar","shape":{"type":"elliptic_cylinder","radii":[0.6,0.3],"length":2.0}},'
                  b'{"name":"pin","shape":{"type":"sphere","radius":0.4},"pose":{"translation":[0.8,0,0]}},'
                  b'{"name":"floor","shape":{"type":"halfspace","normal":[0,0,1],"offset":-1.5}}]}')
write("fuzz_scene", "check_quadrics_small", b"\x00" + quadrics_small)
write("fuzz_scene", "render_quadrics_small_svg", b"\x03\x00\x00" + quadrics_small)
write("fuzz_scene", "plot_ccd_function_pair", b"\x04\x02\x01" + example("scene_ccd.json"))
write("fuzz_scene", "plot_discriminant_png", b"\x04\x05\x00" + example("scene_ccd_2d.json"))
write("fuzz_scene", "plot_timeline", b"\x04\x08\x00" + example("scene_ccd.json"))
# bench: "SIZE\nONLY" (fuzzBench)
write("fuzz_scene", "bench_tiny_cheap", b"\x05tiny\nboxing,broadphase,octree")
write("fuzz_scene", "bench_unknown_experiment", b"\x05tiny\nboxing,bogus")
write("fuzz_scene", "bench_bad_size", b"\x05huge\n")
