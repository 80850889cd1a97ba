#!/usr/bin/env python3
"""Probe (issue 12, not part of the pipeline): per-view rigid co-registration of a block's depth maps.

    coregistration_probe.py SRC DST

SRC is a COLMAP workspace with a text model (SRC/sparse/{cameras,images}.txt; convert a binary one with `colmap
model_converter --output_type TXT`) and SRC/stereo/depth_maps/<image>.geometric.bin. DST/sparse/images.txt gets the
same images with corrected poses; everything else in DST (images, stereo, cameras.txt) is the caller's, e.g.
symbolic links to SRC. Needs python3-numpy.

Each view's depth map, back-projected with its written pose, is compared with every view within 65 degrees of its
viewing direction: its points on a grid of every STEP-th pixel are projected into the other view, and the residual
is the distance from the other view's back-projected depth there along that view's surface normal (from its depth
map, differences over +-3 pixels). Residuals over 2 m are left out, the rest weighed by Huber (0.3 m). The unknowns
are a small rotation w_k about the centroid of view k's samples and a translation t_k per view (X' = X + w_k x (X -
P_k) + t_k); a weak prior keeps each small (rotations scaled by 50 m), and the mean rotation and translation over
all views are held at zero, so the block's datum does not move. Damped Gauss-Newton (Levenberg-Marquardt, the
diagonal doubled: without it the poses drifted on a narrow-angle block whose rotations and translations the data
hardly separate), ITERS times, re-projecting each time.
Measured in README "SAC fusion: the choices" (per-view co-registration); the pipeline does not do this yet.
Environment: ITERS (8), STEP (6 px).
"""
import os
import sys

import numpy as np

ITERS = int(os.environ.get("ITERS", "8"))
STEP = int(os.environ.get("STEP", "6"))
HUBER_M, MAX_RESIDUAL_M, MAX_ANGLE_DEG = 0.3, 2.0, 65.0
PRIOR, ROTATION_SCALE_M, MEAN_WEIGHT, DAMPING = 1.0, 50.0, 1e9, 1.0


def read_depth(path):
    with open(path, "rb") as f:
        header, amps = b"", 0
        while amps < 3:
            ch = f.read(1)
            header += ch
            amps += ch == b"&"
        w, h, c = (int(x) for x in header.decode().strip("&").split("&"))
        data = np.fromfile(f, np.float32)
    return data.reshape((w, h, c), order="F").transpose(1, 0, 2)[:, :, 0]


def quat_to_matrix(w, x, y, z):
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def matrix_to_quat(m):
    t = np.trace(m)
    if t > 0:
        s = np.sqrt(t + 1) * 2
        return 0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s
    i = int(np.argmax(np.diag(m)))
    if i == 0:
        s = np.sqrt(1 + m[0, 0] - m[1, 1] - m[2, 2]) * 2
        return (m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s
    if i == 1:
        s = np.sqrt(1 + m[1, 1] - m[0, 0] - m[2, 2]) * 2
        return (m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s
    s = np.sqrt(1 + m[2, 2] - m[0, 0] - m[1, 1]) * 2
    return (m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s


def rotation(w):
    angle = np.linalg.norm(w)
    if angle < 1e-15:
        return np.eye(3)
    k = w / angle
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * kx @ kx


def camera_normals(depth, f):
    fx, fy, cx, cy = f
    u, v = np.meshgrid(np.arange(depth.shape[1]) + 0.5, np.arange(depth.shape[0]) + 0.5)
    p = np.stack([(u - cx) / fx * depth, (v - cy) / fy * depth, depth], -1)
    dx, dy, s = np.zeros_like(p), np.zeros_like(p), 3
    dx[:, s:-s] = p[:, 2 * s:] - p[:, :-2 * s]
    dy[s:-s] = p[2 * s:] - p[:-2 * s]
    n = np.cross(dx, dy)
    norm = np.linalg.norm(n, axis=-1, keepdims=True)
    return n / np.maximum(norm, 1e-12), (norm[..., 0] > 0) & (depth > 0)


def back_project(view, rows, cols, depth):
    fx, fy, cx, cy = view["f"]
    p_cam = np.stack([(cols + 0.5 - cx) / fx * depth, (rows + 0.5 - cy) / fy * depth, depth], -1)
    return p_cam @ view["R"] + view["C"]  # world_from_cam: R^T p + C


def load(src):
    cameras = {}
    for line in open(os.path.join(src, "sparse", "cameras.txt")):
        if line.strip() and not line.startswith("#"):
            p = line.split()
            cameras[int(p[0])] = [float(x) for x in p[4:8]]
    lines = open(os.path.join(src, "sparse", "images.txt")).read().split("\n")
    views, i = [], 0
    while i < len(lines):
        if not lines[i].strip() or lines[i].startswith("#"):
            i += 1
            continue
        p = lines[i].split()
        r = quat_to_matrix(*(float(x) for x in p[1:5]))
        t = np.array([float(x) for x in p[5:8]])
        depth = read_depth(os.path.join(src, "stereo", "depth_maps", p[9] + ".geometric.bin"))
        views.append({"line": p, "points2d": lines[i + 1], "R": r, "C": -r.T @ t, "f": cameras[int(p[8])],
                      "D": depth})
        i += 2
    return [l for l in lines if l.startswith("#")], views


def residuals(views):
    """Per pair (a, b): a's samples, their surface points in b, b's world normals, point-to-plane residuals."""
    out = []
    for a, va in enumerate(views):
        h, w = va["D"].shape
        rows, cols = (x.ravel() for x in np.mgrid[STEP // 2:h:STEP, STEP // 2:w:STEP])
        d = va["D"][rows, cols]
        ok = d > 0
        xa = back_project(va, rows[ok].astype(float), cols[ok].astype(float), d[ok])
        va["P"] = xa.mean(0)
        for b, vb in enumerate(views):
            if b == a or va["R"][2] @ vb["R"][2] < np.cos(np.radians(MAX_ANGLE_DEG)):
                continue
            p_cam = (xa - vb["C"]) @ vb["R"].T
            fx, fy, cx, cy = vb["f"]
            with np.errstate(divide="ignore", invalid="ignore"):
                u = fx * p_cam[:, 0] / p_cam[:, 2] + cx
                v = fy * p_cam[:, 1] / p_cam[:, 2] + cy
            hb, wb = vb["D"].shape
            idx = np.nonzero((p_cam[:, 2] > 0) & (u >= 0) & (u < wb) & (v >= 0) & (v < hb))[0]
            cu, rv = u[idx].astype(int), v[idx].astype(int)
            good = vb["Nok"][rv, cu]
            idx, cu, rv = idx[good], cu[good], rv[good]
            xb = back_project(vb, rv.astype(float), cu.astype(float), vb["D"][rv, cu])
            nb = vb["N"][rv, cu] @ vb["R"]
            r = np.einsum("ij,ij->i", nb, xa[idx] - xb)
            keep = np.abs(r) < MAX_RESIDUAL_M
            if keep.sum() >= 50:
                out.append((a, b, xa[idx][keep], xb[keep], nb[keep], r[keep]))
    return out


def solve(views, pairs):
    n = len(views)
    normal, gradient, total, weighted_ss = np.zeros((6 * n, 6 * n)), np.zeros(6 * n), 0, 0.0
    for a, b, xa, xb, nb, r in pairs:
        ja = np.hstack([np.cross(xa - views[a]["P"], nb), nb])
        jb = -np.hstack([np.cross(xb - views[b]["P"], nb), nb])
        wgt = np.where(np.abs(r) <= HUBER_M, 1.0, HUBER_M / np.abs(r))[:, None]
        sa, sb = slice(6 * a, 6 * a + 6), slice(6 * b, 6 * b + 6)
        normal[sa, sa] += (ja * wgt).T @ ja
        normal[sb, sb] += (jb * wgt).T @ jb
        normal[sa, sb] += (ja * wgt).T @ jb
        normal[sb, sa] += (jb * wgt).T @ ja
        gradient[sa] += (ja * wgt).T @ r
        gradient[sb] += (jb * wgt).T @ r
        total += len(r)
        weighted_ss += float(np.sum(wgt[:, 0] * r * r))
    scale = np.tile([ROTATION_SCALE_M] * 3 + [1.0] * 3, n)
    normal += PRIOR * np.diag(scale ** 2)
    normal += DAMPING * np.diag(np.diag(normal))  # Levenberg-Marquardt: small steps where the data say little
    mean = np.tile(np.eye(6), (1, n)) * scale[None, :]
    normal += MEAN_WEIGHT * mean.T @ mean
    return -np.linalg.solve(normal, gradient), total, np.sqrt(weighted_ss / max(total, 1))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, dst = sys.argv[1], sys.argv[2]
    comments, views = load(src)
    origin = np.mean([v["C"] for v in views], 0)
    for v in views:
        v["C"] = v["C"] - origin
        v["N"], v["Nok"] = camera_normals(v["D"], v["f"])
    for it in range(ITERS):
        x, total, wrms = solve(views, residuals(views))
        print(f"iteration {it}: {total} residuals, weighted rms {wrms:.3f} m, median correction "
              f"{np.median([np.degrees(np.linalg.norm(x[6 * k:6 * k + 3])) for k in range(len(views))]):.4f} deg, "
              f"{np.median([np.linalg.norm(x[6 * k + 3:6 * k + 6]) for k in range(len(views))]):.3f} m", flush=True)
        for k, v in enumerate(views):
            rw = rotation(x[6 * k:6 * k + 3])
            v["R"] = v["R"] @ rw.T  # cam_from_world of world_from_cam' = Rw world_from_cam about P
            v["C"] = rw @ (v["C"] - v["P"]) + v["P"] + x[6 * k + 3:6 * k + 6]
    out = list(comments)
    for v in views:
        p = v["line"]
        t = -v["R"] @ (v["C"] + origin)
        out.append(" ".join([p[0]] + ["%.15f" % q for q in matrix_to_quat(v["R"])] + ["%.9f" % q for q in t] + p[8:]))
        out.append(v["points2d"])
    os.makedirs(os.path.join(dst, "sparse"), exist_ok=True)
    with open(os.path.join(dst, "sparse", "images.txt"), "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
