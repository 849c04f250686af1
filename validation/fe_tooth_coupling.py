"""3-D linear-elastic FE check of the face coupling of the slice load-distribution model.

One tooth of each gear of FZG H501 as a straight extrusion of its transverse section (involute flank above the base
circle, constant thickness below it as in efficiency.compliance, a rim sector one module deep clamped at its
bottom and sides), hex8 elements (2×2×2 Gauss), scipy sparse LU. The influence matrix between flank points is
the displacement along the load line of the tooth-centreline point per unit flank force (Weber's convention:
the Hertzian approach to the centre line is added separately, as in the model). It replaces the slice model's
tooth part (bending, shear, compression: √(c_i c_j) G_ij/Δz) in the same complementarity solve with Weber's
contact compliance, and the loss factor over a cycle is compared with the model at several coupling lengths and
with the rigid-uniform H_VL. Writes validation/results/fe_tooth_coupling.json. Run:
``python validation/fe_tooth_coupling.py [--body]`` (about 2 minutes and 2 GB; with ``--body``, teeth on a gear-body
sector down to the bore, about 10 minutes and 7 GB).
"""
import math
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from efficiency.geometry import involute


def hex8_stiffness(coords, E, nu):
    """Element stiffness matrices (n_el, 24, 24) for hex8 with 2x2x2 Gauss; coords (n_el, 8, 3)."""
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[np.arange(3), np.arange(3)] += 2 * mu
    D[3:, 3:] = np.eye(3) * mu
    nat = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                    [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
    g = 1 / math.sqrt(3)
    ke = np.zeros((coords.shape[0], 24, 24))
    for gx in (-g, g):
        for gy in (-g, g):
            for gz in (-g, g):
                xi = np.array([gx, gy, gz])
                dN = np.empty((8, 3))
                for a in range(8):
                    f = 1 + nat[a] * xi
                    dN[a, 0] = nat[a, 0] * f[1] * f[2] / 8
                    dN[a, 1] = nat[a, 1] * f[0] * f[2] / 8
                    dN[a, 2] = nat[a, 2] * f[0] * f[1] / 8
                J = np.einsum("ai,eaj->eij", dN, coords)
                detJ = np.linalg.det(J)
                Jinv = np.linalg.inv(J)
                dNx = np.einsum("eij,aj->eai", Jinv, dN)  # (e, a, xyz)
                B = np.zeros((coords.shape[0], 6, 24))
                for a in range(8):
                    B[:, 0, 3 * a] = dNx[:, a, 0]
                    B[:, 1, 3 * a + 1] = dNx[:, a, 1]
                    B[:, 2, 3 * a + 2] = dNx[:, a, 2]
                    B[:, 3, 3 * a] = dNx[:, a, 1]
                    B[:, 3, 3 * a + 1] = dNx[:, a, 0]
                    B[:, 4, 3 * a + 1] = dNx[:, a, 2]
                    B[:, 4, 3 * a + 2] = dNx[:, a, 1]
                    B[:, 5, 3 * a] = dNx[:, a, 2]
                    B[:, 5, 3 * a + 2] = dNx[:, a, 0]
                ke += np.einsum("eki,kl,elj,e->eij", B, D, B, np.abs(detJ))
    return ke


def hex_connectivity(idx):
    """Node numbers (E, 8) of the hexahedra of a structured block whose node numbers are ``idx`` (n_r, n_t, n_z)."""
    a = idx[:-1, :-1, :-1]; b_ = idx[1:, :-1, :-1]; c = idx[1:, 1:, :-1]; d = idx[:-1, 1:, :-1]
    return np.stack([a, b_, c, d, a + 1, b_ + 1, c + 1, d + 1], axis=-1).reshape(-1, 8)


def global_stiffness(nodes, conn, E, nu):
    """Sparse global stiffness matrix (3 dof per node) of the hexahedra ``conn`` on ``nodes`` [m], E [Pa]."""
    ke = hex8_stiffness(nodes[conn], E, nu)
    dofs = (3 * conn[:, :, None] + np.arange(3)).reshape(-1, 24)
    rows = np.repeat(dofs, 24, axis=1).ravel()
    cols = np.tile(dofs, (1, 24)).ravel()
    n = nodes.shape[0] * 3
    return sp.csr_matrix((ke.ravel(), (rows, cols)), shape=(n, n))


class ToothFE:
    """One tooth of ``gear`` (1 or 2) of ``pair`` as a straight extrusion of its transverse section, SI units: the
    involute flank above the base circle, constant thickness between root and base circle (as the slice model), a
    rim ``body_depth_modules`` transverse modules deep below the root circle whose half-angle widens to 0.9 of the
    half pitch, clamped at its bottom (and at its sides with ``fix_sides``). ``n_tooth``, ``n_body``, ``n_t``,
    ``n_z``: elements along the radius in the tooth and the rim, across the thickness and across the face."""

    def __init__(self, pair, gear, n_tooth=16, n_body=5, n_t=8, n_z=46, E=206e9, nu=0.3, body_depth_modules=1.5,
                 fix_sides=False):
        i = gear - 1
        self.pair = pair
        rb = float(pair.base_radii[i]); rf = float(pair.root_radii[i]); ra = float(pair.tip_radii[i])
        r_ref = float(pair.reference_radii[i]); st = float(pair.transverse_thicknesses[i])
        at = float(pair.transverse_pressure_angle); z_teeth = (pair.z1, pair.z2)[i]
        m = float(pair.transverse_module)
        self.rb, self.rf, self.ra = rb, rf, ra
        b = float(pair.face_width)

        def psi(r):
            r = np.maximum(r, rb)
            return st / (2 * r_ref) + involute(at) - involute(np.arccos(rb / r))

        r_body = rf - body_depth_modules * m
        r_tooth = np.linspace(rf, ra, n_tooth + 1)
        r_bod = np.linspace(r_body, rf, n_body + 1)[:-1]
        rs = np.concatenate([r_bod, r_tooth])
        half_pitch = math.pi / z_teeth
        theta_f = psi(rb) * rb / rf

        def theta(r):
            out = np.where(r >= rb, psi(r), psi(rb) * rb / r)
            fillet_top = rf
            fillet_bot = rf - 0.5 * m
            w = np.clip((fillet_top - r) / (fillet_top - fillet_bot), 0, 1)
            return np.where(r >= rf, out, theta_f + w * (0.9 * half_pitch - theta_f))

        ts = np.linspace(-1, 1, n_t + 1)
        zs = np.linspace(0, b, n_z + 1)
        self.rs, self.ts, self.zs = rs, ts, zs
        R, T, Z = np.meshgrid(rs, ts, zs, indexing="ij")
        th = theta(R) * T
        X = R * np.sin(th); Y = R * np.cos(th)
        nodes = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
        nr, nt, nz = len(rs), len(ts), len(zs)
        idx = np.arange(nr * nt * nz).reshape(nr, nt, nz)
        self.idx = idx
        K = global_stiffness(nodes, hex_connectivity(idx), E, nu)
        n = nodes.shape[0] * 3
        fixed = np.zeros(n, bool)
        bottom = idx[0].ravel()
        if fix_sides:
            sides = np.concatenate([idx[:n_body, 0].ravel(), idx[:n_body, -1].ravel()])
            bottom = np.concatenate([bottom, sides])
        for k in range(3):
            fixed[3 * bottom + k] = True
        self.free = np.flatnonzero(~fixed)
        self.K = K[self.free][:, self.free].tocsc()
        self.lu = spla.splu(self.K)
        self.nodes = nodes
        self.ndof = n

    def flank_load_vectors(self, rho, z, t_index=None):
        """Load vectors (ndof_free, P) of unit forces pressing on the flank along the line of action at roll
        ``rho`` (from this gear's base tangent point) and axial position z; bilinear over the flank nodes."""
        rho = np.atleast_1d(rho); z = np.atleast_1d(z)
        r = np.sqrt(self.rb**2 + rho**2)
        P = r.size
        F = np.zeros((self.ndof, P))
        it = len(self.ts) - 1 if t_index is None else t_index  # flank t = +1
        for p in range(P):
            kr = np.clip(np.searchsorted(self.rs, r[p]) - 1, 0, len(self.rs) - 2)
            kz = np.clip(np.searchsorted(self.zs, z[p]) - 1, 0, len(self.zs) - 2)
            fr = (r[p] - self.rs[kr]) / (self.rs[kr + 1] - self.rs[kr])
            fz = (z[p] - self.zs[kz]) / (self.zs[kz + 1] - self.zs[kz])
            for dr, wr in ((0, 1 - fr), (1, fr)):
                for dz, wz in ((0, 1 - fz), (1, fz)):
                    node = self.idx[kr + dr, it, kz + dz]
                    x, y, _ = self.nodes[self.idx[kr + dr, len(self.ts) - 1, kz + dz]]
                    phi = math.atan2(x, y)
                    rr = math.hypot(x, y)
                    alpha = math.acos(min(self.rb / rr, 1.0))
                    e_r = np.array([math.sin(phi), math.cos(phi)])
                    e_t = np.array([math.cos(phi), -math.sin(phi)])
                    n = math.sin(alpha) * e_r + math.cos(alpha) * e_t
                    F[3 * node, p] += -n[0] * wr * wz
                    F[3 * node + 1, p] += -n[1] * wr * wz
        return F[self.free]

    def compliance(self, rho, z, centreline=True):
        """(P, P) influence matrix [m/N]: displacement along the load line of the tooth-centreline point (or the
        flank point) per unit flank force."""
        F = self.flank_load_vectors(rho, z)
        U = self.lu.solve(F)
        if not centreline:
            return F.T @ U
        M = self.flank_load_vectors(rho, z, t_index=(len(self.ts) - 1) // 2)
        C = M.T @ U
        return 0.5 * (C + C.T)



class ToothBodyFE(ToothFE):
    """One tooth on a gear-body sector: the annular sector r_int ≤ r ≤ r_f over ±``pitches`` circular pitches
    (r_int = r_f / hub_ratio, the bore of efficiency.compliance's foundation term), clamped at the bore and at its
    two radial cut faces, with the tooth (no fillet: it stands on the root circle) on top. Same flank-load and
    centreline-displacement interface as :class:`ToothFE`."""

    def __init__(self, pair, gear, n_tooth=16, n_t=8, n_z=46, n_body=10, n_side=10, pitches=1.5, hub_ratio=2.0,
                 E=206e9, nu=0.3):
        i = gear - 1
        self.pair = pair
        rb = float(pair.base_radii[i]); rf = float(pair.root_radii[i]); ra = float(pair.tip_radii[i])
        r_ref = float(pair.reference_radii[i]); st = float(pair.transverse_thicknesses[i])
        at = float(pair.transverse_pressure_angle); z_teeth = (pair.z1, pair.z2)[i]
        self.rb, self.rf, self.ra = rb, rf, ra
        b = float(pair.face_width)

        def psi(r):
            r = np.maximum(r, rb)
            return st / (2 * r_ref) + involute(at) - involute(np.arccos(rb / r))

        def theta(r):
            return np.where(r >= rb, psi(r), psi(rb) * rb / r)

        theta_f = float(theta(np.array(rf)))
        self.rs = np.linspace(rf, ra, n_tooth + 1)
        self.ts = np.linspace(-1, 1, n_t + 1)
        self.zs = np.linspace(0, b, n_z + 1)
        big = pitches * 2 * math.pi / z_teeth
        # graded side angles: fine next to the tooth, coarse towards the cut faces
        g = np.linspace(0, 1, n_side + 1)[1:] ** 1.6
        side = theta_f + (big - theta_f) * g
        phis = np.concatenate([-side[::-1], theta_f * self.ts, side])
        r_int = rf / hub_ratio
        rb_nodes = rf - (rf - r_int) * (np.linspace(0, 1, n_body + 1)[::-1] ** 1.6)  # fine near r_f
        nzn = len(self.zs)
        # body nodes
        RB, PB, ZB = np.meshgrid(rb_nodes, phis, self.zs, indexing="ij")
        body_nodes = np.stack([(RB * np.sin(PB)).ravel(), (RB * np.cos(PB)).ravel(), ZB.ravel()], axis=1)
        nrb, nph = len(rb_nodes), len(phis)
        body_idx = np.arange(nrb * nph * nzn).reshape(nrb, nph, nzn)
        # tooth nodes above r_f (row 0 of the tooth = body top row, shared)
        RT, TT, ZT = np.meshgrid(self.rs[1:], self.ts, self.zs, indexing="ij")
        th = theta(RT) * TT
        tooth_nodes = np.stack([(RT * np.sin(th)).ravel(), (RT * np.cos(th)).ravel(), ZT.ravel()], axis=1)
        nt_nodes = len(self.ts)
        tooth_idx = np.empty((len(self.rs), nt_nodes, nzn), dtype=int)
        tooth_idx[0] = body_idx[-1, n_side:n_side + nt_nodes]
        tooth_idx[1:] = body_idx.size + np.arange(tooth_nodes.shape[0]).reshape(len(self.rs) - 1, nt_nodes, nzn)
        nodes = np.concatenate([body_nodes, tooth_nodes])
        self.idx = tooth_idx
        conn = np.concatenate([hex_connectivity(body_idx), hex_connectivity(tooth_idx)])
        K = global_stiffness(nodes, conn, E, nu)
        n = nodes.shape[0] * 3
        fixed = np.zeros(n, bool)
        clamped = np.concatenate([body_idx[0].ravel(), body_idx[:, 0].ravel(), body_idx[:, -1].ravel()])
        for k in range(3):
            fixed[3 * clamped + k] = True
        self.free = np.flatnonzero(~fixed)
        self.K = K[self.free][:, self.free].tocsc()
        self.lu = spla.splu(self.K)
        self.nodes = nodes
        self.ndof = n

def _loss_factor_run(pair, kin, tooth_matrix, torque=300.0):
    """Elastic load distribution over the cycle with a given tooth compliance builder; returns (H, profile)."""
    from efficiency.compliance import centreline_depth, weber_log_terms
    from efficiency.load_distribution import solve_contact_weber

    cos_b = math.cos(kin.base_helix_angle)
    dz = kin.slice_width
    scale = cos_b / dz
    normal_load = torque / (float(pair.base_radii[0]) * cos_b)
    loads = np.zeros(kin.shape)
    for m in range(kin.shape[0]):
        inside = kin.in_contact[m]
        lines, slices = np.nonzero(inside)
        r1, r2 = kin.rho1[m][inside], kin.rho2[m][inside]
        same = lines[:, None] == lines[None, :]
        matrix = tooth_matrix(r1, r2, slices) * same
        terms = weber_log_terms(kin.r_eq_normal[m][inside], centreline_depth(pair, 1, r1),
                                centreline_depth(pair, 2, r2))
        sol, _, _ = solve_contact_weber(matrix, np.zeros(lines.size), normal_load, terms, scale,
                                        np.full(lines.size, normal_load * cos_b / (1.5 * float(pair.face_width))))
        loads[m][inside] = sol.loads
    h = float((loads * np.abs(kin.u_s)).sum(axis=(1, 2)).mean() / (torque * kin.omega1))
    inside = kin.in_contact
    xi = (kin.roll[inside] - kin.contact_start) / (kin.contact_end - kin.contact_start)
    w = loads[inside]
    idx = np.minimum((xi * 10).astype(int), 9)
    profile = np.array([w[idx == i].mean() for i in range(10)]) / w.mean()
    return h, profile


def main(argv=None) -> int:
    import argparse
    import json
    import sys
    import time
    from pathlib import Path

    from efficiency.compliance import face_coupling, tooth_compliance, whole_depth
    from efficiency.geometry import GearPair
    from efficiency.kinematics import mesh_kinematics
    from efficiency.loss_factor import wimmer_loss_factor
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))  # _common.py, shared with the speed benchmarks
    from _common import machine_info  # noqa: E402

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="default validation/results/fe_tooth_coupling[_body].json")
    parser.add_argument("--pair", choices=("H501", "H701"), default="H501", help="FZG pair (gear_cases.md)")
    parser.add_argument("--coarse", action="store_true",
                        help="coarser body mesh (12 × 6 tooth, 8 + 2 × 8 body elements per face layer; on H501 it "
                             "changes the FE loss factor by 2e-4 relative)")
    parser.add_argument("--body", action="store_true",
                        help="teeth on a gear-body sector (bore r_f/2 clamped, cut faces at ±1.5 pitches clamped) "
                             "compared with the model's tooth + foundation compliance (about 10 min, 7 GB)")
    args = parser.parse_args(argv)
    if args.out is None:
        suffix = ("_body" if args.body else "") + ("" if args.pair == "H501" else f"_{args.pair}")
        args.out = str(Path(__file__).parent / "results" / f"fe_tooth_coupling{suffix}.json")
    deg = math.pi / 180
    if args.pair == "H501":
        pair = GearPair(20, 30, 3.5e-3, 20 * deg, 15 * deg, 23e-3, 0.1809, 0.0891, center_distance=0.0915)
        slices = 23
    else:
        pair = GearPair(28, 42, 2.5e-3, 20 * deg, 15 * deg, 17e-3, 0.2290, 0.1489, center_distance=0.0915)
        slices = 17
    positions = 24
    started = time.perf_counter()
    if args.body:
        mesh = dict(n_tooth=12, n_t=6, n_body=8, n_side=8) if args.coarse else {}
        fe = [ToothBodyFE(pair, g, n_z=2 * slices, **mesh) for g in (1, 2)]
    else:
        fe = [ToothFE(pair, g, body_depth_modules=1.0, n_body=4, fix_sides=True, n_z=2 * slices) for g in (1, 2)]
    build_s = time.perf_counter() - started
    kin = mesh_kinematics(pair, positions, slices, 100.0)
    cos2 = math.cos(kin.base_helix_angle) ** 2
    dz = kin.slice_width
    depth = whole_depth(pair, 1)
    b = float(pair.face_width)

    def fe_tooth(r1, r2, j):
        z = kin.z[j]
        return cos2 * (fe[0].compliance(r1, z) + fe[1].compliance(r2, z))

    def model_part(part, factor, foundation_factor=None):
        g = face_coupling(kin.z, b, factor * depth) / dz
        g_f = None if foundation_factor is None else face_coupling(kin.z, b, foundation_factor * depth) / dz

        def build(r1, r2, j):
            out = 0.0
            for gear, r in ((1, r1), (2, r2)):
                c = tooth_compliance(pair, gear, r)
                if g_f is not None:  # tooth and foundation parts with their own coupling
                    t, f = c["total"] - c["foundation"], c["foundation"]
                    out = out + (np.outer(np.sqrt(t), np.sqrt(t)) * g[np.ix_(j, j)]
                                 + np.outer(np.sqrt(f), np.sqrt(f)) * g_f[np.ix_(j, j)])
                    continue
                c = c["foundation"] if part == "foundation" else (c["total"] - c["foundation"] if part == "tooth"
                                                                  else c["total"])
                out = out + np.outer(np.sqrt(c), np.sqrt(c)) * g[np.ix_(j, j)]
            return cos2 * out
        return build

    # influence of a concentrated load along the face at mid-path, mid-face (FE tooth)
    rho_mid = 0.5 * (float(pair.contact_start) + float(pair.contact_end))
    z_nodes = np.linspace(0.0, b, 2 * slices + 1)
    influence = fe[0].compliance(np.full(z_nodes.size, rho_mid), z_nodes)
    weights = np.full(z_nodes.size, b / (2 * slices))
    weights[[0, -1]] *= 0.5
    mid = slices
    effective_width = float((influence @ weights)[mid] / influence[mid, mid])

    if args.body:
        cases = {"fe_tooth_on_body": fe_tooth}
        for ft, ff in ((0.6, 0.3), (0.6, 0.6), (0.6, 1.0)):
            cases[f"model_tooth_l{ft}_foundation_l{ff}"] = model_part("split", ft, ff)
        cases["model_total_l1.0_old_default"] = model_part("total", 1.0)
    else:
        cases = {"fe_tooth": fe_tooth}
        for factor in (0.3, 0.6, 1.0):
            cases[f"model_tooth_l{factor}"] = model_part("tooth", factor)
        cases["model_total_l1.0_old_default"] = model_part("total", 1.0)
    results = {}
    for name, builder in cases.items():
        h, profile = _loss_factor_run(pair, kin, builder)
        results[name] = {"loss_factor": h, "load_profile_deciles": [round(float(v), 4) for v in profile]}
    default = evaluate_mesh(pair, 300.0, 100.0, options=MeshOptions(positions=positions, slices=slices,
                                                                      outputs=frozenset()))
    results["model_default_tooth_and_foundation_l0.6"] = {"loss_factor": default.loss_factor}
    payload = {
        "benchmark": f"3-D FE check of the slice model's face coupling (FZG {args.pair}, 300 N·m)",
        "body": bool(args.body), "coarse": bool(args.coarse),
        "machine": machine_info(), "fe_build_s": build_s, "positions": positions, "slices": slices,
        "whole_depth_m": depth, "fe_effective_width_mid_m": effective_width,
        "wimmer_h_vl": wimmer_loss_factor(pair),
        "rigid_uniform_same_grid": evaluate_mesh(pair, 300.0, 100.0, options=MeshOptions(
            positions=positions, slices=slices, outputs=frozenset(), load_sharing="rigid-uniform")).loss_factor,
        "results": results,
    }
    Path(args.out).write_text(json.dumps(payload, indent=2) + "\n")
    print(json.dumps(payload, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
