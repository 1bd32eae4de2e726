#!/usr/bin/python3
"""Every CSV column names its unit, says _norm, or is dimensionless by nature
(docs/commands.md, "Units of the CSV columns"; issue 12 item 7, issue 15 item 3).

usage: check_units.py COMMANDS_MD FILE.csv...
The unit suffixes are read from the table in COMMANDS_MD (rows "| `_m` | ..."), so a
suffix used here and not documented there fails, and so does a column that ends in
none of them and is not in the list of dimensionless columns below.  Prints one
line per offending column (file: column) and exits 1 on any."""
import csv, re, sys

# dimensionless by nature: counts, indices, labels and names, flags, ratios
DIMENSIONLESS = set("""
j k dim nodes nodes_x nodes_y kernel shape quadrature mass dilation fixed periodic physics poisson
source perturb seed convention dofs bound_valid negative_phi_points alpha bound_ratio
arpack_iterations arpack_matvecs arpack_residual arpack_tol particles nonpositive_masses min_mass_particle
gershgorin_ratio certified_fraction certify_margin certify_factorizations zero_tol zero_modes
rigid_modes spurious_modes zero_runs seeds zero_modes_min zero_modes_median zero_modes_max
negative_phi_min negative_phi_median negative_phi_max nonpositive_mass_models quadrature_points
evaluated_points verdict rule dt_rule_fraction dt_rule_unsafe spurious_participation
spurious_location spurious_peak_particle max_participation max_location max_boundary_share
max_peak_particle lattice_label lattice_spurious_zeros
lattice frame material support_rule lambda1 lambda2 J pde_stable stable spurious_zeros label
branch stretch_x stretch_y unstable longwave_deviation
problem method ebc plane_strain level unknowns multipliers solver rcond backward_error
reproduces_1e-10 patch_1e-10 interior_nodes test_lambda test_lambda_dev lambda_points
figure run scene scheme equation printed alpha_continuum stretch artifact paper mfstab status csv
mode kind location particle participation_ratio boundary_share layer_share in_layer
""".split())
PATTERNS = [r'dt_rule_[a-z_]+_unsafe', r'rate_.*', r'local_rate_.*', r'.*_ratio']

def suffixes(md):
    s = re.findall(r'^\| `(_[a-z0-9_]+)` \|', open(md).read(), re.M)
    return sorted(set(s), key=len, reverse=True)

def main():
    suf = suffixes(sys.argv[1])
    if not suf:
        print('check_units: no suffix table in', sys.argv[1]); return 1
    bad = 0
    for p in sys.argv[2:]:
        with open(p, newline='') as f:
            header = next(csv.reader(f), [])
        for c in header:
            if c in DIMENSIONLESS or any(re.fullmatch(x, c) for x in PATTERNS):
                continue
            if not any(c.endswith(x) and len(c) > len(x) for x in suf):
                print(f'{p.rsplit("/", 1)[-1]}: column {c}: no unit suffix ({" ".join(suf)}), not _norm, '
                      'not in the dimensionless list')
                bad += 1
    return 1 if bad else 0

sys.exit(main())
